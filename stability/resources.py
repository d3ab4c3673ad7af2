"""Memory: an estimate before allocating, what is available, and a clear refusal.

Layer 0 (docs/architecture.md): the standard library only.

Every entry point that allocates with the size of a request (the output times of
:func:`stability.simulate`, the points of an in-memory atlas, the samples of a threshold search,
the start grid of a neutral curve, a file opened whole) estimates its peak memory as bytes per
point times points and calls :func:`check_memory` before allocating anything. A request above the
limit raises :class:`~stability.errors.ResourceError` (a ``ValueError``; ``tippe`` exits with
status 2) with the estimate, the parameter that sets it, and a way out (chunks, fewer output
times, a larger ``dt``), instead of growing until the kernel's out-of-memory killer ends the
process (measured before this check: ``simulate(t_end=1e7)`` grew to 24 GB).

The limit (:func:`memory_limit`) is ``TIPPE_MEMORY_LIMIT`` (bytes; ``2e9``, ``500M``, ``8G``) when
set, else :data:`HEADROOM` times ``MemAvailable`` of ``/proc/meminfo`` (the kernel's own
estimate); without either, no limit. In a container with a memory limit below the host's, set
``TIPPE_MEMORY_LIMIT`` (``MemAvailable`` is the host's).

The bytes per point are the stored values of the result (its dataset's variables: 8 bytes a
float64, 1 an int8) plus the temporaries of computing them; they are estimates, good to a factor
of about 1.5 (docs/hard_cases.md, "Memory"): enough to refuse a request far above the memory,
which is their one job.
"""

from __future__ import annotations

import os
import re

from .errors import InputError, ResourceError
from .files import format_bytes

__all__ = ["ENV_LIMIT", "HEADROOM", "SIMULATE_BYTES_PER_TIME", "atlas_bytes", "atlas_file_bytes", "check_class_atlas"]
__all__ += ["check_memory", "check_start_grid", "check_threshold_samples", "format_bytes", "memory_limit"]
__all__ += ["simulate_bytes", "simulate_file_bytes"]

#: environment variable overriding the memory limit (bytes)
ENV_LIMIT = "TIPPE_MEMORY_LIMIT"

#: fraction of the available memory a request may take (the rest: the interpreter, the
#: libraries, the other processes' growth)
HEADROOM = 0.8

#: simulate, bytes per output time: the run's dataset stores 31 float64 per time for the sliding
#: and rolling tops (six 3-vectors: omega, k, velocity, position, momentum, friction; 12 scalars
#: and the time), 19 for fixed_pivot; the peak adds the integrator's own output array
#: and the derived quantities' temporaries (about 1.6 x the stored values)
SIMULATE_FILE_BYTES_PER_TIME: dict[str, float] = {"sliding": 248.0, "rolling": 248.0, "fixed_pivot": 152.0}
SIMULATE_BYTES_PER_TIME: dict[str, float] = {k: 1.6 * v for k, v in SIMULATE_FILE_BYTES_PER_TIME.items()}

#: atlas, bytes per grid point as stored (:mod:`stability.grids.schema`): growth rate, frequency
#: and error bound (float64) per mode; max and leading growth rate (float64) and two int8 flags
#: per point; computing adds, for the points of one block, its complex spectrum, bounds, flags
#: and broadcast copies (:data:`_BLOCK`), or, without ``mask_unphysical``, the domain check of the
#: whole grid first (its broadcast parameters and one mask per bound, :data:`_DOMAIN_CHECK`)
_PER_MODE, _PER_POINT, _BLOCK, _DOMAIN_CHECK = 24.0, 18.0, 90.0, 45.0


def memory_limit() -> tuple[float, str]:
    """The memory a request may take, in bytes, and where the number comes from.

    Returns
    -------
    (float, str)
        ``TIPPE_MEMORY_LIMIT`` if set (bytes: ``2e9``, ``500M``, ``8G``, ``1GiB``); else
        :data:`HEADROOM` x ``MemAvailable`` (Linux), with a text naming its source; else no limit.
    """
    text = os.environ.get(ENV_LIMIT, "").strip()
    if text:
        m = re.fullmatch(r"((?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?)\s*([kmgt]?)(i?)b?", text.lower())
        value = float(m[1]) * (1024.0 if m[3] else 1000.0) ** " kmgt".index(m[2] or " ") if m else 0.0
        if not 0 < value < float("inf"):
            raise InputError(f"{ENV_LIMIT} = {text!r} is not a memory size: give bytes > 0 (2e9, 500M, 8G)")
        return value, f"the limit {ENV_LIMIT}"
    try:
        with open("/proc/meminfo") as f:
            avail = next(float(ln.split()[1]) * 1024.0 for ln in f if ln.startswith("MemAvailable:"))
    except (OSError, StopIteration, ValueError, IndexError):  # not Linux: no known limit
        return float("inf"), "no known limit"
    return HEADROOM * avail, f"{HEADROOM:.0%} of MemAvailable"


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
        raise ResourceError(
            f"{what} would need about {format_bytes(nbytes)} of memory (set by {parameter}); about "
            f"{format_bytes(limit)} is available ({source}); {way_out}"
        )


def simulate_file_bytes(model: str, n_times: int, per_time: dict[str, float] = SIMULATE_FILE_BYTES_PER_TIME) -> float:
    """Size of the netCDF file of a run of ``n_times`` output times (``per_time``: its bytes per
    output time, by model; the largest for a model not listed)."""
    return per_time.get(model, max(per_time.values())) * float(n_times)


def simulate_bytes(model: str, n_times: int) -> float:
    """Peak memory of :func:`stability.simulate` for ``n_times`` output times."""
    return simulate_file_bytes(model, n_times, SIMULATE_BYTES_PER_TIME)


def atlas_file_bytes(n_modes: int, n_points: float) -> float:
    """Size of the netCDF file of an atlas of ``n_points`` grid points (its stored values)."""
    return (_PER_MODE * n_modes + _PER_POINT) * float(n_points)


def atlas_bytes(n_modes: int, n_points: float, block_points: float, *, domain_check: bool = False) -> float:
    """Peak memory of an in-memory atlas of ``n_points`` grid points computed in blocks of at
    most ``block_points``; ``domain_check``: the whole grid's domain is checked first (without
    ``mask_unphysical``)."""
    stored = atlas_file_bytes(n_modes, n_points) + _BLOCK * min(float(n_points), float(block_points))
    return max(stored, _DOMAIN_CHECK * float(n_points)) if domain_check else stored


#: peak bytes per point of the requests that store little: the samples of a threshold search
#: (the spectra and growth signs of the uniform and geometric samples), the start grid of a
#: neutral curve (its meshgrid, spectrum and signs), a class atlas (meshgrids, parameters, codes,
#: tilts)
_THRESHOLD_SAMPLE, _START_GRID_POINT, _CLASS_ATLAS_POINT = 1250.0, 340.0, 140.0


def check_threshold_samples(samples: int) -> None:
    """Refuse a threshold search (``threshold``, ``thresholds``, ``critical_spin``) whose
    ``samples`` cannot fit in memory."""
    way_out = "use fewer samples (the default is 257; each crossing is refined between two samples)"
    what = f"a threshold search over {samples} samples"
    check_memory(_THRESHOLD_SAMPLE * float(samples), what=what, parameter="samples", way_out=way_out)


def check_start_grid(nx: int, ny: int) -> None:
    """Refuse a neutral curve whose start grid ``nx x ny`` cannot fit in memory."""
    way_out = "use a coarser grid (the default is 25 x 25), or give start points"
    what = f"a start grid of {nx} x {ny} points"
    check_memory(_START_GRID_POINT * float(nx) * float(ny), what=what, parameter="grid", way_out=way_out)


def check_class_atlas(n_points: int) -> None:
    """Refuse a class atlas of ``n_points`` grid points that cannot fit in memory."""
    what, way_out = f"a class atlas of {n_points} grid points", "use fewer points, or compute it in slices of q"
    check_memory(_CLASS_ATLAS_POINT * float(n_points), what=what, parameter="the grid's ranges", way_out=way_out)
