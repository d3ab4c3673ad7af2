"""``tippe neutral``: trace the neutral curves of a linear model in a parameter plane."""

from __future__ import annotations

import argparse

from ..errors import InputError
from ..models import DEPRECATED_NAMES, MODELS, get_model
from ..parameters import DEFAULT_MU
from ._args import (
    FLAGS,
    add_model_flag,
    add_output_flags,
    add_parameter_flags,
    add_top_arguments,
    apply_top,
    lo_hi,
    output_path,
    write_output,
)

HELP = "neutral curves of a linear model in a parameter plane -> netCDF"
DESCRIPTION = (
    "Trace by pseudo-arclength continuation the curves where a mode is neutral (Re s = 0) in the plane of two "
    "parameters, print the special points (folds, zero-frequency and double crossings, domain edges) and write "
    "the curves. Give the parameters other than --x and --y. Default model: sliding (--alpha-v then required)."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe neutral``."""
    add_model_flag(p, MODELS, "sliding", deprecated=DEPRECATED_NAMES)
    p.add_argument("--x", required=True, choices=list(FLAGS), help="abscissa parameter; required")
    p.add_argument("--y", required=True, choices=list(FLAGS), help="ordinate parameter; required")
    add_parameter_flags(
        p,
        FLAGS,
        kind="value",
        extra={"mu": f" (default {DEFAULT_MU} unless traced)", "alpha_v": " (sliding model only)"},
    )
    add_top_arguments(p, spin=True)
    p.add_argument("--x-range", metavar="LO:HI", help="range of x (default: physical domain)")
    p.add_argument("--y-range", metavar="LO:HI", help="range of y (default: physical domain)")
    add_output_flags(p, "netCDF file to write (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe neutral``."""
    from ..linear.neutral_curves import neutral_curve

    out = output_path(args)
    model = get_model(args.model)
    traced = (args.x, args.y)
    apply_top(args, [n for n in FLAGS if n in model.parameters], spin_needed="fr_inv" not in traced, skip=traced)
    given = {name: getattr(args, name) for name in model.parameters if getattr(args, name) is not None}
    clash = [name for name in given if name in traced]
    if clash:
        raise InputError(f"{FLAGS[clash[0]]} is traced (--x/--y) and cannot also be fixed")
    fixed = {name: v for name, v in given.items() if name not in traced}
    for name in FLAGS:
        if name not in model.parameters and getattr(args, name) is not None:
            raise InputError(f"model {model.name!r} takes no parameter {name} ({FLAGS[name]})")
    xr_ = lo_hi(args.x_range, "--x-range") if args.x_range else None
    yr_ = lo_hi(args.y_range, "--y-range") if args.y_range else None
    ds = neutral_curve(model, args.x, args.y, fixed=fixed, x_range=xr_, y_range=yr_)
    special = ds.where(ds.kind != "regular", drop=True) if ds.sizes["point"] else ds
    print(
        f"{model.name}: {ds.sizes['point']} points on {len(set(ds.branch.values.tolist()))} "
        f"branch(es) in the ({args.x}, {args.y}) plane; form {ds.attrs['form']}; "
        f"largest residual {float(ds.residual.max()) if ds.sizes['point'] else 0:.1e}"
    )
    if special.sizes["point"]:
        print(f"{'branch':>6}  {'kind':<16} {args.x:>18} {args.y:>18} {'frequency':>18}  detail")
        for k in range(special.sizes["point"]):
            print(
                f"{int(special.branch[k]):>6}  {special.kind.values[k]!s:<16} "
                f"{float(special[args.x][k]):>18.12g} {float(special[args.y][k]):>18.12g} "
                f"{float(special.frequency[k]):>18.12g}  {special.detail.values[k]}"
            )
    write_output(ds, out, args)
    return 0
