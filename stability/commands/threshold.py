"""``tippe threshold``: where the leading growth rate changes sign, and a real top's critical spin."""

from __future__ import annotations

import argparse

from ..errors import InputError
from ..models import get_model
from ..parameters import PARAMETERS
from ..top import SPIN_UNITS, Top
from . import _args

HELP = "threshold of one parameter, or the critical spin of a real top"
DESCRIPTION = (
    "PARAM is one of q, fr_inv, sigma, alpha_v, mu (give all the others), or 'spin' for a real top in SI units "
    "(--mass ... or --preset table1): the spin rate above which the upright state is unstable and the inverted "
    "one stable. Default model: sliding."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe threshold``."""
    p.add_argument(
        "param", choices=[*PARAMETERS, "spin"], metavar="PARAM", help="q, fr_inv, sigma, alpha_v, mu or spin"
    )
    _args.add_model_flag(p)
    spin = " (sliding model; with PARAM = spin, held fixed when there is no --mu-v; default 0.5 there)"
    _args.add_parameter_flags(p, PARAMETERS, "value", extra={"alpha_v": spin})
    p.add_argument("--bracket", metavar="LO:HI", help="range searched (default: physical range)")
    every = "list every threshold in the range (default: the one threshold, an error if there are several)"
    _args.add_switches(p, ("--all", every))
    _args.add_top_arguments(p, spin=False)
    g = p.add_argument_group("PARAM = spin")
    g.add_argument(
        "--unit",
        choices=list(SPIN_UNITS),
        help="spin unit of the two launch readings (default rpm; rev/s is printed too)",
    )
    g.add_argument(
        "--orientation",
        choices=["upright", "inverted", "both"],
        help="which state: upright (as given), inverted (q -> -q) or both (default: both)",
    )


def _refuse_unused(args: argparse.Namespace) -> None:
    """Options that the chosen PARAM does not use are errors, not silently ignored."""
    spin = args.param == "spin"
    top = (*_args.TOP_FLAGS, "g", "mu_k", "preset", "top", "mu_v", "orientation")
    values = {n: getattr(args, n) for n in (("q", "fr_inv", "sigma", "mu", "bracket", "all") if spin else top)}
    unused = ", ".join(_args.flag_of(n) for n, v in values.items() if v is not None and v is not False)
    if unused and spin:
        raise InputError(
            f"{unused}: not used by 'tippe threshold spin' (the top's q, sigma and "
            "mu come from --preset or its SI data; the spin rate is what is searched)"
        )
    if unused:
        raise InputError(
            f"{unused}: only used with PARAM = spin (a real top); "
            f"'tippe threshold {args.param}' takes the nondimensional parameters"
        )


def run(args: argparse.Namespace) -> int:
    """Run ``tippe threshold``."""
    from ..linear.critical import _one_threshold, critical_spin, threshold_crossings

    _refuse_unused(args)
    if args.param == "spin":
        return _spin(args, critical_spin)
    model = get_model(args.model)
    fixed = {n: getattr(args, n) for n in PARAMETERS if getattr(args, n) is not None}
    bracket = _args.lo_hi(args.bracket, "--bracket")
    if args.all:
        found = threshold_crossings(args.param, model=model, bracket=bracket, **fixed)
    else:
        found = [_one_threshold(args.param, model, bracket, 257, fixed)]
    if not found:
        print(f"no threshold in {args.param}")
    for t in found:
        more = f"  (unstable {t.unstable_side}; neutral frequency {t.frequency:.12g})" if args.all else ""
        print(f"{args.param} = {t.value:.16g}{more}" + _interval(args.param, t))
    return 0


def _spin(args: argparse.Namespace, critical_spin) -> int:
    """``tippe threshold spin``: the critical spins of a real top, and its two launch readings."""
    top = _args.required_top(args, "tippe threshold spin")
    orientation = args.orientation or "both"
    alpha_v = args.alpha_v if args.alpha_v is not None else 0.5
    found = critical_spin(top, args.model, orientation, alpha_v=alpha_v)
    per = {"upright": found.upright, "inverted": found.inverted} if orientation == "both" else {orientation: found}
    print(f"top: q = {top.q:.6g}, mu = {top.mu:.6g}, sigma = {top.sigma:.6g} ({args.model} model)")
    for o, c in per.items():
        if c is None:
            print(f"{o:>8}: no critical spin: {found.reasons[o]}")
            continue
        print(
            f"{o:>8}: {'unstable' if c.unstable_above else 'stable'} above {c.spin:.10g} rad/s = {c.rpm:.10g} rpm "
            f"(fr_inv = {c.fr_inv:.12g}, neutral frequency {c.frequency:.12g})"
        )
        if not c.exact:
            print(
                f"{'':>8}  an interval, not a value: the change of stability lies between "
                f"{c.spin_interval[0]!r} and {c.spin_interval[1]!r} rad/s (the sign of the growth rate "
                "cannot be decided inside it)"
            )
    print(f"friction: {next(c for c in per.values() if c is not None).friction}")
    if args.model == "sliding" and orientation == "both":
        _launch_readings(top, found, alpha_v, args.unit or "rpm")
    return 0


def _launch_readings(top: Top, found, alpha_v: float, unit: str) -> None:
    """The two readings that must not be mixed up, each on its own line (issue 23)."""
    from ..launches.result import NEVER_INVERTS, inverts_above
    from ..steady.classes import top_class
    from ..top import spin_text

    up = found.upright
    unstable = spin_text(up.spin, unit, digits=10) if up is not None else f"no spin ({found.reasons['upright']})"
    print("the upright top becomes unstable above " + unstable)
    inv = inverts_above(top, up.spin if up is not None else top.spin_rate(0.3), alpha_v)
    if inv is None:
        cls = top_class(q=top.q, sigma=top.sigma, mu=top.mu)
        never = NEVER_INVERTS.get(cls, "the tilted family does not reach the inverted state")
        print("launched upright, it inverts completely above no spin: " + never)
    else:
        print("launched upright, it inverts completely above " + spin_text(inv, unit, digits=10))


def _interval(param: str, t) -> str:
    """What the CLI adds to a threshold known only to an interval (``Threshold.exact`` False)."""
    if t.exact:
        return ""
    return (
        f"\n  an interval, not a value: the change of stability lies in {param} in [{t.lower!r}, {t.upper!r}] "
        "(the sign of the growth rate cannot be decided inside it)"
    )
