"""``tippe final``: where a sliding top ends, predicted from Jellett's integral (or decided by a
run); see :func:`stability.final_state`."""

from __future__ import annotations

import argparse

from ..products import FLAG_NAMES
from . import _args
from .steady import NAMES, REQUIRED

HELP = "predicted final state of a sliding top (Jellett's integral, or a run)"
DESCRIPTION = (
    "Where the motion of a sliding top from a given state ends: the steady states of its Jellett level below its "
    "initial energy decide it when exactly one is stable (method jellett); otherwise a nonlinear run does, and "
    "says so (method simulation). State arguments as in tippe simulate (fixed frame, K up). Sliding model only."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe final``."""
    _args.add_state_flags(
        p,
        omega="initial angular velocity (units of the spin rate)",
        k="initial symmetry axis, within 1 %% of unit length (normalised)",
        velocity="initial horizontal velocity of the sphere's centre, units of Omega R (default 0,0)",
    )
    _args.add_parameter_flags(p, NAMES, "value", unless_top=REQUIRED)
    _args.add_top_arguments(p, spin=True)
    p.add_argument(
        "--no-simulation",
        dest="simulation",
        action="store_false",
        help="do not run a simulation when Jellett's integral does not decide (default: run one)",
    )
    _args.add_float_flags(p, ("--t-max", 2e5, "T", "time limit of a deciding run, units of 1/Omega (default 2e5)"))
    _args.add_output_flags(p, "write the prediction and its candidate table as netCDF (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe final``."""
    from ..steady.final import final_state

    _args.apply_top(args, NAMES, required=REQUIRED)
    out = _args.output_path(args)
    end = final_state(**_args.keywords(final_state, args))
    print(f"final state: {end.kind}, tilt {end.tilt:.6f} deg (method: {end.method})")
    print(
        f"Jellett's integral J = {end.jellett:.12g}, initial energy {end.initial_energy:.10g}, "
        f"final energy {end.energy:.10g}"
    )
    if end.kind == "tilted":
        print(f"precession rate {end.precession_rate:.10g}, axial spin omega . k = {end.axial_spin:.10g}")
    print(f"why: {end.reason}")
    rows = [(c.kind, c.tilt, c.energy, FLAG_NAMES[c.stability], "yes" if c.reachable else "no") for c in end.candidates]
    lines = _args.table(
        "{:<9} {:12.6f} {:14.10g} {:>10} {}", ("kind", "tilt (deg)", "energy", "stability", "reachable"), rows
    )
    print("steady states of the level: " + lines[0], *(f"{'':28}{line}" for line in lines[1:]), sep="\n")
    _args.write_output(end.to_dataset, out, args)
    return 0
