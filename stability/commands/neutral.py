"""``tippe neutral``: trace the neutral curves of a linear model in a parameter plane."""

from __future__ import annotations

import argparse

from ..models import get_model
from ..parameters import DEFAULT_MU, PARAMETERS
from . import _args

HELP = "neutral curves of a linear model in a parameter plane -> netCDF"
DESCRIPTION = (
    "Trace by pseudo-arclength continuation the curves where a mode is neutral (Re s = 0) in the plane of two "
    "parameters, print the special points (folds, zero-frequency and double crossings, domain edges) and write "
    "the curves. Give the parameters other than --x and --y. Default model: sliding (--alpha-v then required)."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe neutral``."""
    _args.add_model_flag(p)
    p.add_argument("--x", required=True, choices=PARAMETERS, help="abscissa parameter; required")
    p.add_argument("--y", required=True, choices=PARAMETERS, help="ordinate parameter; required")
    extra = {"mu": f" (default {DEFAULT_MU} unless traced)", "alpha_v": " (sliding model only)"}
    _args.add_parameter_flags(p, PARAMETERS, "value", extra=extra)
    _args.add_top_arguments(p, spin=True)
    p.add_argument("--x-range", metavar="LO:HI", help="range of x (default: physical domain)")
    p.add_argument("--y-range", metavar="LO:HI", help="range of y (default: physical domain)")
    _args.add_output_flags(p, "netCDF file to write (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe neutral``."""
    from ..linear.neutral_curves import neutral_curve

    out = _args.output_path(args)
    model = get_model(args.model)
    traced = (args.x, args.y)
    names = [n for n in PARAMETERS if n in model.parameters]
    _args.apply_top(args, names, spin_needed="fr_inv" not in traced, skip=traced)
    fixed = {name: getattr(args, name) for name in PARAMETERS if getattr(args, name) is not None}
    ranges = {f"{a}_range": _args.lo_hi(getattr(args, f"{a}_range"), f"--{a}-range") for a in "xy"}
    ds = neutral_curve(model, args.x, args.y, fixed=fixed, **ranges)
    n = ds.sizes["point"]
    special = ds.where(ds.kind != "regular", drop=True) if n else ds
    print(
        f"{model.name}: {n} points on {len(set(ds.branch.values.tolist()))} branch(es) in the ({args.x}, {args.y}) "
        f"plane; form {ds.attrs['form']}; largest residual {float(ds.residual.max()) if n else 0:.1e}"
    )
    if special.sizes["point"]:
        columns = (special[v].values for v in ("branch", "kind", args.x, args.y, "frequency", "detail"))
        rows = ((int(b), str(k), x, y, f, d) for b, k, x, y, f, d in zip(*columns))
        header = ("branch", "kind", args.x, args.y, "frequency", "detail")
        print(*_args.table("{:>6}  {:<16} {:>18.12g} {:>18.12g} {:>18.12g}  {}", header, rows), sep="\n")
    _args.write_output(ds, out, args)
    return 0
