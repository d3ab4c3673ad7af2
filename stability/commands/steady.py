"""``tippe steady``: the steady states of a sliding top on one Jellett level, or the branch of
tilted states (``--branch``); see :func:`stability.steady_states` and
:func:`stability.steady_branch`."""

from __future__ import annotations

import argparse

from ..errors import InputError
from ..products import FLAG_NAMES
from ._args import (
    add_float_flags,
    add_output_flags,
    add_parameter_flags,
    add_top_arguments,
    apply_top,
    output_path,
    write_output,
)

__all__ = ["FLAG_NAMES", "add_top_flags", "apply_top_flags"]


#: the parameters of the sliding top's steady states, and those needed without a top
_NAMES, _REQUIRED = ("q", "sigma", "fr_inv", "alpha_v", "mu"), ("q", "sigma", "fr_inv", "alpha_v")


def add_top_flags(p: argparse.ArgumentParser) -> None:
    """``--q``, ``--sigma``, ``--fr-inv``, ``--alpha-v`` (required unless a top is given) and
    ``--mu`` (single numbers), or a real top in SI units with ``--spin`` (:func:`add_top_arguments`)."""
    add_parameter_flags(
        p,
        _NAMES,
        kind="value",
        unless_top=_REQUIRED,
    )
    add_top_arguments(p, spin=True)


def apply_top_flags(args: argparse.Namespace) -> None:
    """The nondimensional parameters from the flags or from the top and its spin (:func:`apply_top`)."""
    apply_top(args, _NAMES, required=_REQUIRED)


HELP = "steady (tilted) states on a Jellett level, or the branch of tilted states"
DESCRIPTION = (
    "Every steady state of the sliding top (upright, inverted, each tilted one) on one Jellett level J, with "
    "tilt, precession rate, spin, energy, growth rate and stability; with --branch, the family of tilted states "
    "traced against J by continuation, with its branch points and folds. Sliding model only. Units: simulate's "
    "(J in A0 Omega). docs/steady_states.md."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe steady``."""
    add_top_flags(p)
    add_float_flags(
        p, ("--jellett", None, "J", "Jellett's integral of the level (default: the upright spin 1, J = sigma (1 + q))")
    )
    p.add_argument(
        "--branch",
        action="store_true",
        help="trace the branch of tilted states against J instead (--jellett is then not used)",
    )
    add_float_flags(
        p,
        (
            "--jellett-max",
            None,
            "J",
            "with --branch: where a branch running to J = infinity is cut (default 10 x J at its branch point)",
        ),
        (
            "--max-step",
            0.02,
            "H",
            "with --branch: largest continuation step in (tilt, log precession rate) (default 0.02)",
        ),
    )
    add_output_flags(p, "write the states (or the branch) as netCDF (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe steady``."""
    from ..steady.branch import steady_branch
    from ..steady.states import steady_states

    if args.branch and args.jellett is not None:
        raise InputError("--jellett is not used with --branch (the branch runs over J); give one of them")
    if not args.branch and (args.jellett_max is not None or args.max_step != 0.02):
        raise InputError("--jellett-max and --max-step are only used with --branch")
    apply_top_flags(args)
    out = output_path(args)
    top = dict(q=args.q, sigma=args.sigma, fr_inv=args.fr_inv, alpha_v=args.alpha_v, mu=args.mu)
    if args.branch:
        ds = steady_branch(**top, jellett_max=args.jellett_max, max_step=args.max_step)
        n = ds.sizes["point"]
        if n == 0:
            print(f"no tilted steady states: {ds.attrs.get('note', '')}")
        else:
            print(
                f"branch of tilted states: {n} points, from the {ds.attrs['start']} branch point "
                f"(ends: {ds.attrs['ends']})"
            )
            print(f"{'kind':<14} {'tilt (deg)':>12} {'J':>14} {'precession':>12} {'stability':>10}  detail")
            for i in range(n):
                kind = str(ds.kind.values[i])
                if kind != "regular":
                    print(
                        f"{kind:<14} {float(ds.tilt[i]):12.6f} {float(ds.jellett[i]):14.10g} "
                        f"{float(ds.precession_rate[i]):12.6g} {FLAG_NAMES[int(ds.stability[i])]:>10}  "
                        f"{ds.detail.values[i]}"
                    )
    else:
        ds = steady_states(**top, jellett=args.jellett)
        print(
            f"steady states at J = {ds.attrs['jellett']:.12g} (q = {args.q:g}, sigma = {args.sigma:g}, "
            f"fr_inv = {args.fr_inv:g}, alpha_v = {args.alpha_v:g}, mu = {args.mu:g})"
        )
        print(
            f"{'kind':<9} {'tilt (deg)':>12} {'precession':>12} {'axial spin':>12} {'energy':>12} "
            f"{'growth rate':>12} {'stability':>10}"
        )
        for i in range(ds.sizes["state"]):
            s = ds.isel(state=i)
            print(
                f"{s.kind.values!s:<9} {float(s.tilt):12.6f} {float(s.precession_rate):12.6g} "
                f"{float(s.axial_spin):12.6g} {float(s.energy):12.8g} {float(s.growth_rate):12.4g} "
                f"{FLAG_NAMES[int(s.stability)]:>10}"
            )
    write_output(ds, out, args)
    return 0
