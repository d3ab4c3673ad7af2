"""``tippe atlas``: spectra of a linear model over a parameter grid, written to netCDF.

With ``--chunks`` the grid is computed and written chunk by chunk (memory stays at a few
chunks), in this process or on a dask.distributed cluster (``--workers N``: a local one;
``--scheduler``: an existing one), with a progress bar; ``--resume`` keeps finished chunks so
that an interrupted run can be continued (stability.grids.chunked).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .. import interrupts
from ..errors import InputError, Interrupted
from ..files import check_output_path
from ..linear.spectra import DEFAULT_METHOD, METHODS
from ..models import get_model
from ..parameters import PARAMETERS
from ..products import FLAG_NAMES
from . import _args
from ._args import add_model_flag, add_output_flags, add_parameter_flags, add_switches, add_top_arguments, apply_top

HELP = "eigenvalues of a linear model over a parameter grid -> netCDF"
DESCRIPTION = (
    "Compute the spectrum of a linear model over a grid and write it as a netCDF atlas. Ranges: start:stop:num "
    "(linspace) or comma lists. Default model: sliding (--alpha-v then required)."
)
#: the most lines --plot draws for a second grid dimension; beyond it, the map over the two
MAX_LINES = 10
#: the flags an atlas's summary counts, in its order (-1: outside the domain)
_COUNTED = {**FLAG_NAMES, -1: "outside domain"}


def plot_figure(ds, x: str):
    """The figure of ``--plot``: growth rate and frequency against ``x``, one line per value of a
    second grid dimension, or, with more than :data:`MAX_LINES` values there, the stability map
    over the two (as the recipes draw a 2-D grid)."""
    from ..plotting.figures import atlas_figure, plot_atlas

    family = [d for d in ds.max_growth_rate.dims if ds.sizes[d] > 1 and d != x]
    if len(family) == 1 and ds.sizes[family[0]] > MAX_LINES:
        return plot_atlas(ds, x=x, y=family[0])[0]
    return atlas_figure(ds, x=x)[0]


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe atlas``."""
    add_model_flag(p)
    unless_top, only = ("q", "fr_inv", "sigma"), {"alpha_v": " (sliding model only)"}
    add_parameter_flags(p, PARAMETERS, unless_top=unless_top, extra=only)
    add_top_arguments(p, spin=True, grid=True)
    overwrite = "replace an existing output file (and --plot file)"
    add_output_flags(p, "netCDF file to write (atomically); required", required=True, overwrite=overwrite)
    mask = "mask grid points outside the physical domain (NaN) instead of refusing the grid"
    add_switches(p, ("--mask-unphysical", mask))
    p.add_argument(
        "--method",
        choices=list(METHODS),
        default=DEFAULT_METHOD,
        help="eigenvalue method: kernel (compiled closed-form roots of the characteristic "
        "polynomial, polished, with error bounds; the fastest at full accuracy), polynomial "
        "(companion-matrix eigenvalues + Newton), lapack (numpy.linalg.eigvals of the "
        "operator); the last two are slower cross-checks",
    )
    p.add_argument(
        "--plot",
        metavar="PNG",
        help="also draw the leading growth rate and frequency against --x "
        f"(one line per value of a second grid dimension; with more than {MAX_LINES} values there, "
        "the stability map over the two)",
    )
    p.add_argument("--x", default="q", help="abscissa of the --plot (a grid dimension: q, fr_inv, sigma, alpha_v, mu)")
    f = p.add_argument_group("what the file stores")
    f.add_argument(
        "--variables",
        choices=("all", "map"),
        default="all",
        help="all: every variable (all modes, for a study; default); map: the leading growth rate "
        "and the stability flag only, the smallest file that draws a stability map",
    )
    f.add_argument(
        "--compression",
        choices=("none", "zlib", "zstd"),
        default="none",
        help="lossless compression of the data variables (netCDF4 filters; default none)",
    )
    f.add_argument(
        "--float32",
        action="store_true",
        help="store growth rates, frequencies and bounds as float32 (relative error <= 2^-24, "
        "stated in the variables' attributes; the flags are decided in float64)",
    )
    g = p.add_argument_group("large grids (dask)")
    g.add_argument(
        "--chunks",
        metavar="SIZES",
        help="compute and write chunk by chunk: one size for every grid dimension (e.g. 100) "
        "or sizes by dimension (e.g. q=100,sigma=50; the others whole) (default: the whole "
        "grid at once)",
    )
    g.add_argument(
        "--workers",
        type=int,
        metavar="N",
        help="run the chunks on a local dask cluster of N processes (default: in this process)",
    )
    g.add_argument(
        "--scheduler",
        metavar="ADDRESS|FILE",
        help="run the chunks on an existing dask cluster: tcp://host:port or a scheduler file",
    )
    add_switches(
        g,
        ("--resume", "keep finished chunks in OUTPUT.parts/ and reuse those of an interrupted run"),
        ("--no-progress", "no progress bar (default: a bar on a terminal)"),
    )


def parse_chunks(text: str) -> int | dict[str, int]:
    """``"100"`` -> 100; ``"q=100,sigma=50"`` -> ``{"q": 100, "sigma": 50}``.

    Raises
    ------
    InputError
        With the offending text.
    """
    try:
        if "=" not in text:
            return int(text.strip())
        return {k.strip().replace("-", "_"): int(v) for k, v in (part.split("=") for part in text.strip().split(","))}
    except ValueError:
        raise InputError(
            f"--chunks = {text!r} is not a size or a list dim=size,... (sizes are integers "
            ">= 1, e.g. 100 or q=100,sigma=50)"
        ) from None


def _counts(var) -> dict[str, int]:
    """The points of each flag of the stability variable ``var`` (in memory, or read lazily
    from the written file), counted in slabs of <= 2e7 points: memory does not grow with the grid."""
    counts = dict.fromkeys(_COUNTED.values(), 0)
    n0 = var.shape[0] if var.ndim else 1
    step = max(1, int(2e7 // max(1, var.size // n0)))
    for i in range(0, n0, step):
        flags = var[i : i + step].values if var.ndim else var.values
        for flag, name in _COUNTED.items():
            counts[name] += int((flags == flag).sum())
    return counts


def _run_chunked(args: argparse.Namespace, out, ds, layout: dict) -> dict[str, int]:
    """``tippe atlas --chunks``: the lazy atlas ``ds`` written chunk by chunk; the counts of its flags."""
    import xarray as xr

    from ..grids.chunked import write_atlas
    from ..grids.cluster import dask_client
    from ..grids.store import is_store_path, open_store, parts_directory

    store = parts_directory(out)
    if args.resume and store.is_dir():
        print(f"found {store}: its chunks are reused if it was written for this atlas", file=sys.stderr)
    kept = f"the finished chunks are kept in {store}; rerun the same command to continue"
    if args.resume:
        interrupts.run.kept = kept
    try:
        with dask_client(workers=args.workers, scheduler=args.scheduler) as client:
            progress = not args.no_progress and sys.stderr.isatty()
            write_atlas(
                ds, out, overwrite=args.overwrite, client=client, resume=args.resume, progress=progress, **layout
            )
    except KeyboardInterrupt:
        raise Interrupted(
            f"no output file was written; {kept}"
            if args.resume
            else "no output file was written and no chunks were kept (run with --resume to keep them across an "
            "interruption)"
        ) from None
    with open_store(out) if is_store_path(out) else xr.open_dataset(out) as f:
        return _counts(f["stability"])


def _check_space(out, model: str, values: dict) -> None:
    """Refuse, before computing, an atlas whose file cannot fit on its file system."""
    import numpy as np

    from ..files import check_free_space
    from ..resources import atlas_file_bytes

    points = np.prod([np.size(v) for v in values.values()])
    check_free_space(out, atlas_file_bytes(get_model(model, warn=False).n_modes, points))


def run(args: argparse.Namespace) -> int:
    """Run ``tippe atlas``."""
    from ..grids.atlases import atlas  # here: ``tippe --help`` imports no xarray
    from ..grids.store import is_store_path

    _apply_top(args)
    zarr_store = is_store_path(args.output)  # a Zarr store: stability.grids.store checks its name
    out = Path(args.output) if zarr_store else check_output_path(args.output, overwrite=args.overwrite)
    if args.plot:
        check_output_path(args.plot, overwrite=args.overwrite)
        _check_plot_format(args.plot)
    values = _args.parameter_values(args, PARAMETERS)
    if args.chunks is not None and args.plot:
        raise InputError(
            "--plot is not available with --chunks (the grid may not fit in memory); "
            "plot a slice of the written file instead"
        )
    if args.chunks is None and (args.workers is not None or args.scheduler is not None or args.resume):
        raise InputError("--workers, --scheduler and --resume apply to chunked runs: give --chunks too")
    chunks = None if args.chunks is None else parse_chunks(args.chunks)
    if chunks is None:  # before computing; a chunked atlas is lazy, its grid checked first
        _check_space(out, args.model, values)
    ds = atlas(args.model, mask_unphysical=args.mask_unphysical, method=args.method, chunks=chunks, **values)
    if args.spin is not None:  # a top and its spin: the spin in --unit on the atlas
        from ..recipes import spin_coordinate

        ds = spin_coordinate(ds, _args.parameter_values(args, ("spin",))["spin"], args.unit or "rad/s")
    compression = None if args.compression == "none" else args.compression
    layout = dict(variables=args.variables, compression=compression, float32=args.float32)
    if chunks is not None:
        _check_space(out, args.model, values)
        counts, how = _run_chunked(args, out, ds, layout), " in chunks"
    else:
        if args.plot:
            from ..plotting import save_figure, style

            with style():
                fig = plot_figure(ds, args.x)
            # the figure is written before the netCDF file is committed: a failure to draw or
            # save it leaves no atlas file behind
            save_figure(fig, args.plot, overwrite=args.overwrite)
        if zarr_store or layout != dict(variables="all", compression=None, float32=False):
            from ..grids.chunked import write_atlas

            write_atlas(ds, out, overwrite=args.overwrite, **layout)
        else:
            from ..grids.netcdf import write_dataset

            write_dataset(ds, out, overwrite=args.overwrite)
        counts, how = _counts(ds.stability), ""
    grid = " x ".join(f"{d}({ds.sizes[d]})" for d in ds.max_growth_rate.dims) or "one point"
    summary = ", ".join(f"{v} {k}" for k, v in counts.items() if v)
    print(
        f"wrote {out}: {args.model} model, grid {grid}{how}; {summary}" + (f"\nwrote {args.plot}" if args.plot else "")
    )
    return 0


def _apply_top(args: argparse.Namespace) -> None:
    """A top in SI units (``--mass ... --spin``): its q, sigma, mu and the fr_inv (and alpha_v)
    of its spin. A grid of spins is a grid of fr_inv with the spin as a coordinate along it; the
    alpha_v of a top with ``--mu-v`` changes along that grid too (eq. 7), which an atlas (one
    dimension per parameter) cannot hold: refused, give ``--alpha-v`` instead (held fixed)."""
    import numpy as np

    names = [n for n in PARAMETERS if n in get_model(args.model, warn=False).parameters]
    top = apply_top(args, names, required=("q", "fr_inv", "sigma"))
    if top is not None and np.ndim(args.fr_inv) == 1 and np.ndim(getattr(args, "alpha_v", None)) == 1:
        raise InputError(
            f"--spin {args.spin} (a grid) and --mu-v {top.mu_v:g}: alpha_v = mu mu_v g / Omega would "
            "change along the spin grid, and an atlas holds one dimension per parameter; give "
            "--alpha-v (held fixed) instead of --mu-v, or one spin"
        )


def _check_plot_format(path: str) -> None:
    """Refuse a ``--plot`` file whose suffix names no format matplotlib can write, before any
    computation (the format comes from the suffix, :func:`stability.plotting.save_figure`)."""
    from matplotlib.backend_bases import FigureCanvasBase

    known = FigureCanvasBase.get_supported_filetypes()
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in known:
        raise InputError(
            f"--plot = {path!r}: the format {('.' + suffix) if suffix else '(no suffix)'} is not "
            f"known to matplotlib; the allowed suffixes are {', '.join('.' + k for k in sorted(known))}"
        )
