"""``tippe validate``: linear predictions against short nonlinear runs, as a table."""

from __future__ import annotations

import argparse

from ..nonlinear import NONLINEAR_MODELS
from ._args import (
    add_float_flags,
    add_model_flag,
    add_output_flags,
    add_parameter_flags,
    add_top_arguments,
    apply_top,
    parameter_values,
)

HELP = "check linear growth rates against nonlinear runs"
DESCRIPTION = (
    "For each point (values broadcast together), perturb the upright spin along the leading eigenvector, "
    "integrate the nonlinear model, fit growth rate and frequency, and print them beside the predictions. "
    "Default model: sliding (--alpha-v then required)."
)
_COORDS = ("q", "fr_inv", "sigma", "mu", "alpha_v")


def format_points(ds) -> str:
    """The validation dataset as one short block per point (every line under 80 characters).

    Each block names the point's parameters, then the growth rate and frequency of the
    nonlinear model's Jacobian, the values measured on the run and their relative errors, and
    whether the measured growth rate has the Jacobian's sign.
    """
    lines = []
    for j in range(ds.sizes["point"]):
        pt = ds.isel(point=j)
        params = ", ".join(f"{k} = {float(pt[k]):.6g}" for k in _COORDS if k in pt.coords)
        lines += [f"point {j}: {params}", f"  {'':<12} {'Jacobian':>13} {'measured':>13} {'rel. error':>10}"]
        for label, key in (("growth rate", "growth_rate"), ("frequency", "frequency")):
            lines.append(
                f"  {label:<12} {float(pt['jacobian_' + key]):>13.6g} "
                f"{float(pt['measured_' + key]):>13.6g} {float(pt[key + '_error']):>10.2g}"
            )
        lines.append(f"  {'sign agrees':<12} {'yes' if bool(pt['sign_agrees']) else 'NO'}")
        if "status" in pt and str(pt["status"].values) != "ok":
            lines.append(f"  {'status':<12} {pt['status'].values}")
    return "\n".join(lines)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe validate``."""
    add_model_flag(p, NONLINEAR_MODELS, "sliding", what="model (nonlinear, and its linearisation)")
    add_parameter_flags(
        p,
        _COORDS,
        unless_top=("q", "fr_inv", "sigma"),
        extra={"alpha_v": " (sliding only; > 0 there)"},
    )
    add_top_arguments(p, spin=True, grid=True)
    add_float_flags(p, ("--amplitude", 1e-4, "A", "initial tilt |Phi| along the leading eigenvector (0 < A <= 0.1)"))
    add_output_flags(p, "also write the Dataset as netCDF (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe validate``."""
    from ..grids.netcdf import check_output_path, write_dataset
    from ..nonlinear.validation import validate

    apply_top(
        args, _COORDS if args.model == "sliding" else ("q", "fr_inv", "sigma", "mu"), required=("q", "fr_inv", "sigma")
    )
    out = check_output_path(args.output, overwrite=args.overwrite) if args.output else None
    values = parameter_values(args, ("q", "fr_inv", "sigma", "alpha_v", "mu"))
    ds = validate(args.model, amplitude=args.amplitude, **values)
    print(format_points(ds))
    if out is not None:
        write_dataset(ds, out, overwrite=args.overwrite)
    return 0
