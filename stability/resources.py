"""Memory: an estimate before allocating, what is available, and a clear refusal.

Layer 0 (docs/architecture.md): the standard library only.

Every entry point that allocates with the size of a request (the output times of
:func:`stability.simulate`, the points of an in-memory atlas, the samples of a threshold search,
the start grid of a neutral curve, a file opened whole) estimates its peak memory from the
constants below and calls :func:`check_memory` before allocating anything. A request above the
limit raises :class:`~stability.errors.ResourceError` (a ``ValueError``; ``tippe`` exits with
status 2) with the estimate, the parameter that sets it, and a way out (chunks, fewer output
times, a larger ``dt``), instead of growing until the kernel's out-of-memory killer ends the
process (measured before this check: ``simulate(t_end=1e7)`` grew to 24 GB).

The limit (:func:`memory_limit`) is ``TIPPE_MEMORY_LIMIT`` (bytes; ``2e9``, ``500M``, ``8G``) when
set, else :data:`HEADROOM` times the smallest of: ``MemAvailable`` (``/proc/meminfo``), the cgroup's
``memory.max - memory.current`` (v2, every level up to the root; v1 ``memory.limit_in_bytes``),
and the room left under the soft ``RLIMIT_AS`` and ``RLIMIT_DATA``; where none is known, the
free physical pages.

The constants are measured peaks (``VmHWM`` after the call minus ``VmRSS`` before it, the peak
reset after a warm-up call; ``tests/test_resources.py`` pins each within [0.7, 1.3] of a fresh
measurement): the stored values plus the temporaries of building them.
"""

from __future__ import annotations

import math
import os
import re

__all__ = [
    "ATLAS_BLOCK_BYTES_PER_POINT",
    "ATLAS_BYTES_PER_POINT",
    "ATLAS_BYTES_PER_POINT_MODE",
    "ATLAS_CHECK_BYTES_PER_POINT",
    "ATLAS_FILE_BYTES_PER_POINT",
    "ATLAS_FILE_BYTES_PER_POINT_MODE",
    "CLASS_ATLAS_BYTES_PER_POINT",
    "ENV_LIMIT",
    "HEADROOM",
    "SIMULATE_BYTES_PER_TIME",
    "SIMULATE_FILE_BYTES_PER_TIME",
    "START_GRID_BYTES_PER_POINT",
    "THRESHOLD_BYTES_PER_SAMPLE",
    "atlas_bytes",
    "atlas_file_bytes",
    "check_class_atlas",
    "check_memory",
    "check_start_grid",
    "check_threshold_samples",
    "format_bytes",
    "memory_limit",
    "simulate_bytes",
    "simulate_file_bytes",
]

#: environment variable overriding the memory limit (bytes)
ENV_LIMIT = "TIPPE_MEMORY_LIMIT"

#: fraction of the measured available memory a request may take (the rest: the interpreter, the
#: libraries, the other processes' growth)
HEADROOM = 0.8

#: simulate: peak bytes per output time, by nonlinear model (measured 386 / 378 / 226 B at 2e5 and
#: 1e6 output times; with the peak reset after a warm-up, 368 B for sliding at 2e5). Stored: 31 float64 per time for the sliding and rolling runs (248 B: omega,
#: k, velocity, position, momentum, friction; 12 scalars and the time), 19 for fixed_pivot
#: (152 B); the peak adds the integrator's output array (10, 8 and 6 float64 per time) and the
#: temporaries of the derived quantities
SIMULATE_BYTES_PER_TIME: dict[str, float] = {"sliding": 400.0, "rolling": 390.0, "fixed_pivot": 235.0}

#: simulate: bytes per output time in the netCDF file (the stored values)
SIMULATE_FILE_BYTES_PER_TIME: dict[str, float] = {"sliding": 248.0, "rolling": 248.0, "fixed_pivot": 152.0}

#: in-memory atlas: bytes per grid point = per point and mode x modes + per point (the stored
#: growth rate, frequency and bound per mode, 24 B; the largest and the leading growth rate and
#: two int8 flags, 18 B), plus :data:`ATLAS_BLOCK_BYTES_PER_POINT` for each point of one block of
#: the spectrum (its complex eigenvalues, bounds, flags and broadcast copies); the atlas's own
#: checks (schema.validate_atlas, the leading growth rate) run in slabs and blocks and stay below
#: that. Measured 86-90 B per point at 1e6 points (sliding, with the peak reset after a warm-up;
#: 115-124 B when the checks took the whole grid at once)
ATLAS_BYTES_PER_POINT_MODE = 24.0
ATLAS_BYTES_PER_POINT = 18.0
ATLAS_BLOCK_BYTES_PER_POINT = 90.0

#: in-memory atlas without ``mask_unphysical``: the domain check of the whole grid before the
#: first block (the broadcast parameters and the temporaries of the bounds) peaks at this many
#: bytes per grid point, whatever the number of modes (the broadcast parameters and one mask per
#: bound; the exact margins are evaluated in blocks, parameters._violations: measured 41.5 B per
#: point at 1e6 points with the peak reset after a warm-up, 120 B before the blocks); the peak is
#: the larger of this and the stored arrays plus one block
ATLAS_CHECK_BYTES_PER_POINT = 45.0

#: atlas file: bytes per grid point (per mode and per point) as written (the variables of an
#: in-memory atlas; 90.1 B per point measured for 2.5e5 points, three modes)
ATLAS_FILE_BYTES_PER_POINT_MODE = 24.0
ATLAS_FILE_BYTES_PER_POINT = 18.0

#: threshold, thresholds, critical_spin: peak bytes per sample (the uniform and geometric sampling
#: grids' spectra, the structured growth signs of every mode, and the hidden-pair pass; measured
#: 1210 B at 2e5 samples with the peak reset after a warm-up and the freed heap trimmed; 1096 B
#: without the trim, which a cold numba cache's compile made room for; 564 B before the signs
#: came from linear.growth)
THRESHOLD_BYTES_PER_SAMPLE = 1250.0

#: neutral_curve: peak bytes per point of the start grid (its meshgrid, spectrum, structured
#: growth signs and counts; measured 335 B at 700 x 700 with the peak reset after a warm-up,
#: since the signs come from linear.growth; 147 B before)
START_GRID_BYTES_PER_POINT = 340.0

#: class_atlas: peak bytes per grid point (meshgrids, the checked parameters, codes and tilts;
#: measured 138 B at 1e6 points, the peak reset after a warm-up; 179 B before the exact domain
#: margins took their products from models.inertia.two_product, whose temporaries die sooner)
CLASS_ATLAS_BYTES_PER_POINT = 140.0

_SUFFIX = {
    "": 1.0,
    "k": 1e3,
    "m": 1e6,
    "g": 1e9,
    "t": 1e12,
    "kib": 2.0**10,
    "mib": 2.0**20,
    "gib": 2.0**30,
    "tib": 2.0**40,
    "kb": 1e3,
    "mb": 1e6,
    "gb": 1e9,
    "tb": 1e12,
    "b": 1.0,
}


def format_bytes(n: float) -> str:
    """``1234567`` -> ``"1.23 MB"`` (decimal units)."""
    n = float(n)
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.0f} bytes"


def _env_limit() -> float | None:
    text = os.environ.get(ENV_LIMIT, "").strip()
    if not text:
        return None
    m = re.fullmatch(r"([0-9.eE+]+)\s*([a-zA-Z]*)", text)
    value = None
    if m and m.group(2).lower() in _SUFFIX:
        try:
            value = float(m.group(1)) * _SUFFIX[m.group(2).lower()]
        except ValueError:
            value = None
    if value is None or not math.isfinite(value) or value <= 0:
        from .errors import InputError

        raise InputError(f"{ENV_LIMIT} = {text!r} is not a memory size: give bytes > 0 (2e9, 500M, 8G)")
    return value


def _kib_field(path: str, key: str) -> float | None:
    """Bytes of the field ``key`` of a ``/proc`` file of ``key: value kB`` lines; None if unreadable."""
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return float(line.split()[1]) * 1024.0
    except (OSError, ValueError, IndexError):
        return None
    return None


def _meminfo(key: str) -> float | None:
    return _kib_field("/proc/meminfo", key)


def _read_number(path: str) -> float | None:
    try:
        with open(path) as f:
            text = f.read().strip()
    except OSError:
        return None
    if not text or text == "max":
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return None if v >= 2.0**62 else v  # "unlimited" in cgroup v1 is a huge number


def _cgroup_room() -> float | None:
    """The smallest ``limit - usage`` of this process's cgroups (v2 at every level; v1)."""
    rooms = []
    try:
        with open("/proc/self/cgroup") as f:
            lines = f.read().splitlines()
    except OSError:
        return None
    for line in lines:
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        _, controllers, path = parts
        if controllers == "":  # v2
            rel = path.strip("/")
            while True:
                base = os.path.join("/sys/fs/cgroup", rel)
                limit = _read_number(os.path.join(base, "memory.max"))
                used = _read_number(os.path.join(base, "memory.current"))
                if limit is not None:
                    rooms.append(limit - (used or 0.0))
                if not rel:
                    break
                rel = os.path.dirname(rel)
        elif "memory" in controllers.split(","):  # v1
            base = os.path.join("/sys/fs/cgroup/memory", path.strip("/"))
            limit = _read_number(os.path.join(base, "memory.limit_in_bytes"))
            used = _read_number(os.path.join(base, "memory.usage_in_bytes"))
            if limit is not None:
                rooms.append(limit - (used or 0.0))
    return min(rooms) if rooms else None


def _status(key: str) -> float | None:
    return _kib_field("/proc/self/status", key)


def _rlimit_room() -> float | None:
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return None
    rooms = []
    for name, key in (("RLIMIT_AS", "VmSize"), ("RLIMIT_DATA", "VmData")):
        lim = getattr(resource, name, None)
        if lim is None:
            continue
        try:
            soft, _ = resource.getrlimit(lim)
        except (OSError, ValueError):
            continue
        if soft == resource.RLIM_INFINITY or soft < 0:
            continue
        rooms.append(float(soft) - (_status(key) or 0.0))
    return min(rooms) if rooms else None


def memory_limit() -> tuple[float, str]:
    """The memory a request may take, in bytes, and where the number comes from.

    Returns
    -------
    (float, str)
        ``TIPPE_MEMORY_LIMIT`` if set; else :data:`HEADROOM` x the smallest available amount
        (module docstring), with a text naming its source.
    """
    env = _env_limit()
    if env is not None:
        return env, f"the limit {ENV_LIMIT}"
    found = [
        (v, s)
        for v, s in (
            (_meminfo("MemAvailable"), "MemAvailable"),
            (_cgroup_room(), "the cgroup limit"),
            (_rlimit_room(), "the process limit ulimit -v / -d"),
        )
        if v is not None
    ]
    if not found:
        try:
            found = [(float(os.sysconf("SC_AVPHYS_PAGES")) * os.sysconf("SC_PAGE_SIZE"), "free physical memory")]
        except (ValueError, OSError, AttributeError):  # pragma: no cover - not POSIX
            return math.inf, "no known limit"
    value, source = min(found)
    return max(0.0, HEADROOM * value), f"{HEADROOM:.0%} of {source}"


def check_memory(nbytes: float, *, what: str, parameter: str, way_out: str) -> None:
    """Refuse a request whose estimated peak memory exceeds :func:`memory_limit`.

    Parameters
    ----------
    nbytes : float
        The estimate (from the constants of this module).
    what : str
        The request, as the message shows it: ``"simulate: 100000001 output times (t_end / dt)"``.
    parameter : str
        The parameter that sets the size.
    way_out : str
        What to do instead: ``"give a larger dt or fewer t_eval points"``.

    Raises
    ------
    stability.errors.ResourceError
        "simulate: 100000001 output times (t_end / dt = 1e+07 / 0.1) would need about 40 GB of
        memory (set by t_end / dt); about 17 GB is available (80% of MemAvailable); give a
        larger dt ...".
    """
    limit, source = memory_limit()
    if nbytes > limit:
        from .errors import ResourceError

        raise ResourceError(
            f"{what} would need about {format_bytes(nbytes)} of memory (set by {parameter}); about "
            f"{format_bytes(limit)} is available ({source}); {way_out}"
        )


def simulate_bytes(model: str, n_times: int) -> float:
    """Peak memory of :func:`stability.simulate` for ``n_times`` output times."""
    return SIMULATE_BYTES_PER_TIME.get(model, max(SIMULATE_BYTES_PER_TIME.values())) * float(n_times)


def simulate_file_bytes(model: str, n_times: int) -> float:
    """Size of the netCDF file of a run of ``n_times`` output times."""
    return SIMULATE_FILE_BYTES_PER_TIME.get(model, max(SIMULATE_FILE_BYTES_PER_TIME.values())) * float(n_times)


def atlas_bytes(n_modes: int, n_points: float, block_points: float, *, domain_check: bool = False) -> float:
    """Peak memory of an in-memory atlas of ``n_points`` grid points computed in blocks of at
    most ``block_points``; ``domain_check``: the whole grid's domain is checked first (without
    ``mask_unphysical``)."""
    n = float(n_points)
    stored = (ATLAS_BYTES_PER_POINT_MODE * n_modes + ATLAS_BYTES_PER_POINT) * n + ATLAS_BLOCK_BYTES_PER_POINT * min(
        n, float(block_points)
    )
    return max(stored, ATLAS_CHECK_BYTES_PER_POINT * n) if domain_check else stored


def check_threshold_samples(samples: int) -> None:
    """Refuse a threshold search (``threshold``, ``thresholds``, ``critical_spin``) whose
    ``samples`` cannot fit in memory."""
    check_memory(
        THRESHOLD_BYTES_PER_SAMPLE * float(samples),
        what=f"a threshold search over {samples} samples",
        parameter="samples",
        way_out="use fewer samples (the default is 257; each crossing is refined between two samples)",
    )


def check_start_grid(nx: int, ny: int) -> None:
    """Refuse a neutral curve whose start grid ``nx x ny`` cannot fit in memory."""
    check_memory(
        START_GRID_BYTES_PER_POINT * float(nx) * float(ny),
        what=f"a start grid of {nx} x {ny} points",
        parameter="grid",
        way_out="use a coarser grid (the default is 25 x 25), or give start points",
    )


def check_class_atlas(n_points: int) -> None:
    """Refuse a class atlas of ``n_points`` grid points that cannot fit in memory."""
    check_memory(
        CLASS_ATLAS_BYTES_PER_POINT * float(n_points),
        what=f"a class atlas of {n_points} grid points",
        parameter="the grid's ranges",
        way_out="use fewer points, or compute it in slices of q",
    )


def atlas_file_bytes(n_modes: int, n_points: float) -> float:
    """Size of the netCDF file of an atlas of ``n_points`` grid points."""
    return (ATLAS_FILE_BYTES_PER_POINT_MODE * n_modes + ATLAS_FILE_BYTES_PER_POINT) * float(n_points)
