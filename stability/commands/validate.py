"""``tippe validate``: linear predictions against short nonlinear runs, as a table."""

from __future__ import annotations

import argparse

from . import _args

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
        lines.append(f"point {j}: " + ", ".join(f"{k} = {float(pt[k]):.6g}" for k in _COORDS if k in pt.coords))
        rows = [
            (label, *(float(pt[v]) for v in (f"jacobian_{key}", f"measured_{key}", f"{key}_error")))
            for label, key in (("growth rate", "growth_rate"), ("frequency", "frequency"))
        ]
        lines += _args.table("  {:<12} {:>13.6g} {:>13.6g} {:>10.2g}", ("", "Jacobian", "measured", "rel. error"), rows)
        lines.append(f"  {'sign agrees':<12} {'yes' if bool(pt['sign_agrees']) else 'NO'}")
        if "status" in pt and str(pt["status"].values) != "ok":
            lines.append(f"  {'status':<12} {pt['status'].values}")
    return "\n".join(lines)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe validate``."""
    _args.add_model_flag(p, "model (nonlinear, and its linearisation)")
    only = {"alpha_v": " (sliding only; > 0 there)"}
    _args.add_parameter_flags(p, _COORDS, unless_top=("q", "fr_inv", "sigma"), extra=only)
    _args.add_top_arguments(p, spin=True, grid=True)
    amplitude = "initial tilt |Phi| along the leading eigenvector (0 < A <= 0.1)"
    _args.add_float_flags(p, ("--amplitude", 1e-4, "A", amplitude))
    _args.add_output_flags(p, "also write the Dataset as netCDF (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe validate``."""
    from ..nonlinear.validation import validate

    names = _COORDS if args.model == "sliding" else ("q", "fr_inv", "sigma", "mu")
    _args.apply_top(args, names, required=("q", "fr_inv", "sigma"))
    out = _args.output_path(args)
    ds = validate(args.model, amplitude=args.amplitude, **_args.parameter_values(args, _COORDS))
    print(format_points(ds))
    _args.write_output(ds, out, args)
    return 0
