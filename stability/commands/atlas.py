"""``tippe atlas``: spectra of a linear model over a parameter grid, written to netCDF."""

from __future__ import annotations

import argparse

from ..atlas import atlas
from ..io import check_output_path, write_dataset
from ..models import MODELS
from ..spectra import METHODS
from ._args import add_parameter_flags, parameter_values

__all__ = ["register", "run"]


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``atlas`` subcommand."""
    p = sub.add_parser(
        "atlas", help="eigenvalues of a linear model over a parameter grid -> netCDF",
        description="Compute the spectrum of a linear model over a grid and write it as a netCDF atlas. "
                    "Ranges: start:stop:num (linspace) or comma lists.")
    p.add_argument("--model", choices=list(MODELS), default="sliding")
    add_parameter_flags(p, ("q", "fr_inv", "sigma", "alpha_v", "mu"), required=("q", "fr_inv", "sigma"))
    p.add_argument("-o", "--output", required=True, help="netCDF file to write (atomically)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output file")
    p.add_argument("--mask-unphysical", action="store_true",
                   help="mask grid points outside the physical domain (NaN) instead of refusing the grid")
    p.add_argument("--method", choices=list(METHODS), default="polynomial")
    p.add_argument("--plot", metavar="PNG", help="also draw the leading growth rate and frequency against --x")
    p.add_argument("--x", default="q", help="abscissa of the plot (a grid dimension)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run ``tippe atlas``."""
    out = check_output_path(args.output, overwrite=args.overwrite)
    if args.plot:
        check_output_path(args.plot, overwrite=True)
    values = parameter_values(args, ("q", "fr_inv", "sigma", "alpha_v", "mu"))
    ds = atlas(args.model, mask_unphysical=args.mask_unphysical, method=args.method, **values)
    if args.plot:
        from ..plotting.figures import atlas_figure
        from ..plotting import save_figure, style

        with style():
            fig = atlas_figure(ds, x=args.x)
        # the figure is complete before anything is written
    write_dataset(ds, out, overwrite=args.overwrite)
    counts = {name: int((ds.stability == flag).sum()) for name, flag in
              (("stable", 0), ("marginal", 1), ("unstable", 2), ("outside domain", -1))}
    grid = " x ".join(f"{d}({ds.sizes[d]})" for d in ds.max_growth_rate.dims) or "one point"
    print(f"wrote {out}: {args.model} model, grid {grid}; "
          + ", ".join(f"{v} {k}" for k, v in counts.items() if v))
    if args.plot:
        save_figure(fig, args.plot)
        print(f"wrote {args.plot}")
    return 0

