"""``tippe validate``: linear predictions against short nonlinear runs, as a table."""

from __future__ import annotations

import argparse

from ..nonlinear import NONLINEAR_MODELS
from ._args import add_parameter_flags, parameter_values

__all__ = ["register", "run"]

_COLUMNS = ("jacobian_growth_rate", "measured_growth_rate", "growth_rate_error",
            "jacobian_frequency", "measured_frequency", "frequency_error", "sign_agrees")


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``validate`` subcommand."""
    p = sub.add_parser("validate", help="check linear growth rates against nonlinear runs",
                       description="For each point (values broadcast together), perturb the upright "
                                   "spin along the leading eigenvector, integrate the nonlinear model, "
                                   "fit growth rate and frequency, and print them beside the predictions.")
    p.add_argument("--model", choices=list(NONLINEAR_MODELS), default="sliding")
    add_parameter_flags(p, ("q", "fr_inv", "sigma", "alpha_v", "mu"), required=("q", "fr_inv", "sigma"))
    p.add_argument("--amplitude", type=float, default=1e-4, help="initial tilt |Phi|")
    p.add_argument("-o", "--output", default=None, help="also write the Dataset as netCDF")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output file")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run ``tippe validate``."""
    from ..grids.netcdf import check_output_path, write_dataset
    from ..nonlinear.validation import validate

    out = check_output_path(args.output, overwrite=args.overwrite) if args.output else None
    values = parameter_values(args, ("q", "fr_inv", "sigma", "alpha_v", "mu"))
    ds = validate(args.model, amplitude=args.amplitude, **values)
    print(ds[list(_COLUMNS)].to_dataframe().to_string(float_format=lambda v: f"{v:.6g}"))
    if out is not None:
        write_dataset(ds, out, overwrite=args.overwrite)
    return 0
