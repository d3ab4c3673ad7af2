"""``tippe threshold``: where the leading growth rate changes sign, and a real top's critical spin."""

from __future__ import annotations

import argparse

from ..models import MODELS
from ..top import Top
from ._args import FLAGS

__all__ = ["register", "run"]

_TOP_FLAGS = ("mass", "radius", "com_offset", "inertia_transverse", "inertia_axial")


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``threshold`` subcommand."""
    p = sub.add_parser(
        "threshold", help="threshold of one parameter, or the critical spin of a real top",
        description="PARAM is one of q, fr_inv, sigma, alpha_v, mu (give all the others), or "
                    "'spin' for a real top in SI units (--mass ... or --preset table1): the spin "
                    "rate above which the upright state is unstable and the inverted one stable.")
    p.add_argument("param", choices=[*FLAGS, "spin"], metavar="PARAM",
                   help="q, fr_inv, sigma, alpha_v, mu or spin")
    p.add_argument("--model", choices=list(MODELS), default="sliding")
    for name, flag in FLAGS.items():
        p.add_argument(flag, dest=name, type=float, default=None, metavar="VALUE",
                       help=f"value of {name}" + (" (default 2.28)" if name == "mu" else ""))
    p.add_argument("--bracket", metavar="LO:HI", help="range searched (default: physical range)")
    p.add_argument("--all", action="store_true", help="list every threshold in the range")
    g = p.add_argument_group("a real top (PARAM = spin), SI units")
    g.add_argument("--preset", choices=["table1", "table1_measured"], help="the paper's toy top")
    for name in _TOP_FLAGS:
        g.add_argument("--" + name.replace("_", "-"), dest=name, type=float, metavar="VALUE")
    g.add_argument("--g", dest="gravity", type=float, default=None, metavar="M/S2",
                   help="gravity (default 9.80665)")
    g.add_argument("--mu-v", dest="mu_v", type=float, metavar="S/M",
                   help="viscous friction coefficient (alpha_v then scales as 1/spin)")
    g.add_argument("--orientation", choices=["upright", "inverted", "both"], default=None,
                   help="default: both")
    p.set_defaults(func=run)


def _refuse_unused(args: argparse.Namespace) -> None:
    """Options that the chosen PARAM does not use are errors, not silently ignored."""
    def flag(name: str) -> str:
        return "--g" if name == "gravity" else FLAGS.get(name, "--" + name.replace("_", "-"))

    top_given = [n for n in (*_TOP_FLAGS, "gravity") if getattr(args, n) is not None]
    if args.param == "spin":
        unused = [flag(n) for n in ("q", "fr_inv", "sigma", "mu") if getattr(args, n) is not None]
        unused += ["--bracket"] * bool(args.bracket) + ["--all"] * bool(args.all)
        if unused:
            raise ValueError(f"{', '.join(unused)}: not used by 'tippe threshold spin' (the top's q, sigma and "
                             "mu come from --preset or its SI data; the spin rate is what is searched)")
        if args.preset and top_given:
            raise ValueError(f"--preset {args.preset} and {', '.join(flag(n) for n in top_given)} "
                             "conflict: give a preset or the top's SI data, not both")
        return
    unused = [flag(n) for n in top_given]
    unused += [f"--{n.replace('_', '-')}" for n in ("preset", "mu_v", "orientation") if getattr(args, n) is not None]
    if unused:
        raise ValueError(f"{', '.join(unused)}: only used with PARAM = spin (a real top); "
                         f"'tippe threshold {args.param}' takes the nondimensional parameters")


def _top(args: argparse.Namespace) -> Top:
    if args.preset:
        return getattr(Top, args.preset)(mu_v=args.mu_v)
    missing = [n for n in _TOP_FLAGS if getattr(args, n) is None]
    if missing:
        raise ValueError("tippe threshold spin needs --preset or " + ", ".join(
            "--" + n.replace("_", "-") for n in missing))
    return Top(*(getattr(args, n) for n in _TOP_FLAGS), g=9.80665 if args.gravity is None else args.gravity,
               mu_v=args.mu_v)


def run(args: argparse.Namespace) -> int:
    """Run ``tippe threshold``."""
    from ..linear.critical import _one_threshold, critical_spin, threshold_crossings

    _refuse_unused(args)
    if args.param == "spin":
        top = _top(args)
        orient = ["upright", "inverted"] if args.orientation in (None, "both") else [args.orientation]
        print(f"top: q = {top.q:.6g}, mu = {top.mu:.6g}, sigma = {top.sigma:.6g} ({args.model} model)")
        for o in orient:
            alpha_v = args.alpha_v if args.alpha_v is not None else 0.5
            c = critical_spin(top, args.model, o, alpha_v=alpha_v)
            state = "unstable" if c.unstable_above else "stable"
            print(f"{o:>8}: {state} above {c.spin:.10g} rad/s = {c.rpm:.10g} rpm "
                  f"(fr_inv = {c.fr_inv:.12g}, neutral frequency {c.frequency:.12g})")
            if not c.exact:
                print(f"{'':>8}  an interval, not a value: the change of stability lies between "
                      f"{c.spin_interval[0]!r} and {c.spin_interval[1]!r} rad/s (the sign of the growth rate "
                      "cannot be decided inside it)")
        print(f"friction: {c.friction}")
        return 0
    model = MODELS[args.model]
    fixed = {n: getattr(args, n) for n in FLAGS if getattr(args, n) is not None and n != args.param}
    if getattr(args, args.param) is not None:
        raise ValueError(f"{FLAGS[args.param]} is the parameter searched; do not give its value")
    bracket = None
    if args.bracket:
        try:
            bracket = tuple(float(v) for v in args.bracket.split(":"))
        except ValueError:
            raise ValueError(f"--bracket = {args.bracket!r} must be lo:hi") from None
        if len(bracket) != 2:
            raise ValueError(f"--bracket = {args.bracket!r} must be lo:hi")
    if args.all:
        found = threshold_crossings(args.param, model=model, bracket=bracket, **fixed)
        if not found:
            print(f"no threshold in {args.param}")
        for t in found:
            print(f"{args.param} = {t.value:.16g}  (unstable {t.unstable_side}; neutral frequency {t.frequency:.12g})"
                  + _interval(args.param, t))
        return 0
    t = _one_threshold(args.param, model, bracket, 257, fixed)
    print(f"{args.param} = {t.value:.16g}" + _interval(args.param, t))
    return 0


def _interval(param: str, t) -> str:
    """What the CLI adds to a threshold known only to an interval (``Threshold.exact`` False)."""
    if t.exact:
        return ""
    return (f"\n  an interval, not a value: the change of stability lies in {param} in [{t.lower!r}, {t.upper!r}] "
            "(the sign of the growth rate cannot be decided inside it)")
