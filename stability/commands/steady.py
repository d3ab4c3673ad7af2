"""``tippe steady``: the steady states of a sliding top on one Jellett level, or the branch of
tilted states (``--branch``); see :func:`stability.steady_states` and
:func:`stability.steady_branch`."""

from __future__ import annotations

import argparse

from ..errors import InputError
from ..products import FLAG_NAMES
from . import _args

#: the parameters of the sliding top's steady states (a single number each: ``tippe final`` too),
#: and those needed without a top
NAMES, REQUIRED = ("q", "sigma", "fr_inv", "alpha_v", "mu"), ("q", "sigma", "fr_inv", "alpha_v")

HELP = "steady (tilted) states on a Jellett level, or the branch of tilted states"
DESCRIPTION = (
    "Every steady state of the sliding top (upright, inverted, each tilted one) on one Jellett level J, with "
    "tilt, precession rate, spin, energy, growth rate and stability; with --branch, the family of tilted states "
    "traced against J by continuation, with its branch points and folds. Sliding model only. Units: simulate's "
    "(J in A0 Omega). docs/steady_states.md."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe steady``."""
    _args.add_parameter_flags(p, NAMES, "value", unless_top=REQUIRED)
    _args.add_top_arguments(p, spin=True)
    level = "Jellett's integral of the level (default: the upright spin 1, J = sigma (1 + q))"
    _args.add_float_flags(p, ("--jellett", None, "J", level))
    _args.add_switches(
        p, ("--branch", "trace the branch of tilted states against J instead (--jellett is then not used)")
    )
    cut = "with --branch: where a branch running to J = infinity is cut (default 10 x J at its branch point)"
    step = "with --branch: largest continuation step in (tilt, log precession rate) (default 0.02)"
    _args.add_float_flags(p, ("--jellett-max", None, "J", cut), ("--max-step", 0.02, "H", step))
    _args.add_output_flags(p, "write the states (or the branch) as netCDF (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe steady``."""
    from ..steady.branch import steady_branch
    from ..steady.states import steady_states

    if args.branch and args.jellett is not None:
        raise InputError("--jellett is not used with --branch (the branch runs over J); give one of them")
    if not args.branch and (args.jellett_max is not None or args.max_step != 0.02):
        raise InputError("--jellett-max and --max-step are only used with --branch")
    _args.apply_top(args, NAMES, required=REQUIRED)
    out = _args.output_path(args)
    if args.branch:
        ds = steady_branch(**_args.keywords(steady_branch, args))
        n = ds.sizes["point"]
        if n == 0:
            print(f"no tilted steady states: {ds.attrs.get('note', '')}")
        else:
            start, ends = ds.attrs["start"], ds.attrs["ends"]
            print(f"branch of tilted states: {n} points, from the {start} branch point (ends: {ends})")
            columns = (ds[v].values for v in ("kind", "tilt", "jellett", "precession_rate", "stability", "detail"))
            rows = [(str(k), t, j, w, FLAG_NAMES[int(s)], d) for k, t, j, w, s, d in zip(*columns) if k != "regular"]
            header = ("kind", "tilt (deg)", "J", "precession", "stability", "detail")
            print(*_args.table("{:<14} {:12.6f} {:14.10g} {:12.6g} {:>10}  {}", header, rows), sep="\n")
    else:
        ds = steady_states(**_args.keywords(steady_states, args))
        print(
            f"steady states at J = {ds.attrs['jellett']:.12g} (q = {args.q:g}, sigma = {args.sigma:g}, "
            f"fr_inv = {args.fr_inv:g}, alpha_v = {args.alpha_v:g}, mu = {args.mu:g})"
        )
        names = ("kind", "tilt", "precession_rate", "axial_spin", "energy", "growth_rate", "stability")
        rows = [(str(k), *v, FLAG_NAMES[int(s)]) for k, *v, s in zip(*(ds[n].values for n in names))]
        header = ("kind", "tilt (deg)", "precession", "axial spin", "energy", "growth rate", "stability")
        print(*_args.table("{:<9} {:12.6f} {:12.6g} {:12.6g} {:12.8g} {:12.4g} {:>10}", header, rows), sep="\n")
    _args.write_output(ds, out, args)
    return 0
