"""``tippe launch``: what a real top does when spun at a given rate (:func:`stability.launch`)."""

from __future__ import annotations

import argparse

from . import _args

HELP = "what a real top does when you spin it: thresholds, end, flip and settle times"
DESCRIPTION = (
    "A top in SI units (--mass ... or --preset table1) launched at --spin (in --unit), its axis tilted by --tilt "
    "degrees, the sphere's centre at rest: the spin above which the upright top is unstable, the launch spin "
    "above which it inverts completely, its class, where it ends, the time to 90 degrees and to settle, the "
    "smallest normal force (docs/launch.md). Sliding model only."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe launch``."""
    from ..top import SPIN_UNITS

    _args.add_top_arguments(p, spin=False)
    g = p.add_argument_group("the launch")
    g.add_argument("--spin", type=float, required=True, metavar="VALUE", help="launch spin, in --unit")
    g.add_argument("--unit", choices=list(SPIN_UNITS), default="rev/s", help="unit of --spin (default rev/s)")
    alpha_v = "viscous parameter alpha_v (eq. 7) when the top has no --mu-v (default 0.5)"
    _args.add_float_flags(
        g, ("--tilt", 1.0, "DEG", "initial tilt of the axis (default 1)"), ("--alpha-v", None, "VALUE", alpha_v)
    )
    g.add_argument("--model", choices=["sliding"], default="sliding", help="nonlinear model (sliding)")
    _args.add_output_flags(g, "also write the answer as a netCDF dataset")
    g.add_argument(
        "--plot",
        metavar="FILE.png",
        help="also draw the top's bifurcation diagram in --unit, the launch and its end marked",
    )


def run(args: argparse.Namespace) -> int:
    """Run ``tippe launch``."""
    from ..launches.result import launch

    top = _args.required_top(args, "tippe launch")
    out = _args.output_path(args)
    res = launch(**_args.keywords(launch, args, top=top))
    print(res)
    if args.plot:
        _plot(top, res, args)
    _args.write_output(res.to_dataset, out, args)
    return 0


def _plot(top, res, args: argparse.Namespace) -> None:
    """The bifurcation diagram of ``top`` around the launch (:func:`stability.bifurcation_diagram`,
    :func:`stability.plotting.plot_bifurcation`), written to ``args.plot``."""
    from ..files import check_output_path
    from ..plotting.atlas_plots import save_figure
    from ..plotting.steady_plots import plot_bifurcation
    from ..steady.diagram import bifurcation_diagram
    from ..top import from_rad_per_s

    check_output_path(args.plot, overwrite=True)
    marks = [v for v in (res.spin, res.unstable_above, res.inverts_above) if v is not None]
    lo, hi = (from_rad_per_s(v, args.unit) for v in (0.75 * min(marks), 1.25 * max(marks)))
    alpha_v = None if top.mu_v is not None else res.parameters["alpha_v"]
    diagram = bifurcation_diagram(top, unit=args.unit, alpha_v=alpha_v, spin_range=(lo, hi))
    fig, _ = plot_bifurcation(diagram, launch=res)
    save_figure(fig, args.plot)
    print(f"drawn: {args.plot}")
