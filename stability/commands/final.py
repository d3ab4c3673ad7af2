"""``tippe final``: where a sliding top ends, predicted from Jellett's integral (or decided by a
run); see :func:`stability.final_state`."""

from __future__ import annotations

import argparse

from ._args import add_float_flags, add_output_flags, add_state_flags, output_path, write_output
from .steady import FLAG_NAMES, add_top_flags, apply_top_flags

HELP = "predicted final state of a sliding top (Jellett's integral, or a run)"
DESCRIPTION = (
    "Where the motion of a sliding top from a given state ends: the steady states of its Jellett level below its "
    "initial energy decide it when exactly one is stable (method jellett); otherwise a nonlinear run does, and "
    "says so (method simulation). State arguments as in tippe simulate (fixed frame, K up). Sliding model only."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe final``."""
    add_state_flags(
        p,
        omega="initial angular velocity (units of the spin rate)",
        k="initial symmetry axis, within 1 %% of unit length (normalised)",
        velocity="initial horizontal velocity of the sphere's centre, units of Omega R (default 0,0)",
    )
    add_top_flags(p)
    p.add_argument(
        "--no-simulation",
        dest="simulation",
        action="store_false",
        help="do not run a simulation when Jellett's integral does not decide (default: run one)",
    )
    add_float_flags(p, ("--t-max", 2e5, "T", "time limit of a deciding run, units of 1/Omega (default 2e5)"))
    add_output_flags(p, "write the prediction and its candidate table as netCDF (default: print only)")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe final``."""
    from ..steady.final import final_state

    apply_top_flags(args)
    out = output_path(args)
    keywords = ("omega", "k", "velocity", "q", "sigma", "fr_inv", "alpha_v", "mu", "simulation", "t_max")
    end = final_state(**{name: getattr(args, name) for name in keywords})
    print(f"final state: {end.kind}, tilt {end.tilt:.6f} deg (method: {end.method})")
    print(
        f"Jellett's integral J = {end.jellett:.12g}, initial energy {end.initial_energy:.10g}, "
        f"final energy {end.energy:.10g}"
    )
    if end.kind == "tilted":
        print(f"precession rate {end.precession_rate:.10g}, axial spin omega . k = {end.axial_spin:.10g}")
    print(f"why: {end.reason}")
    print(f"steady states of the level: {'kind':<9} {'tilt (deg)':>12} {'energy':>14} {'stability':>10} reachable")
    for c in end.candidates:
        print(
            f"{'':28}{c.kind:<9} {c.tilt:12.6f} {c.energy:14.10g} {FLAG_NAMES[c.stability]:>10} "
            f"{'yes' if c.reachable else 'no'}"
        )
    write_output(end.to_dataset, out, args)
    return 0
