"""``tippe simulate``: a nonlinear run written to netCDF (see :func:`stability.simulate`)."""

from __future__ import annotations

import argparse
import math
import os
import sys

from . import _args

HELP = "integrate a nonlinear model -> netCDF"
DESCRIPTION = (
    "Integrate the sliding, rolling or fixed-pivot top from a given state and write the run (omega, k, energy, "
    "forces, ...) as netCDF. Default model: sliding (--alpha-v then required). Times are in units of 1/Omega "
    "(one spin period is 2 pi), rates in units of Omega."
)
#: the integrators --method offers, and the default regularisation scale of the Coulomb term:
#: written here so that ``tippe --help`` does not import scipy and the integrators;
#: tests/test_cli.py checks them against stability.nonlinear.integrators and simulate()'s defaults
_METHODS = ("auto", "dopri5", "rk4", "RK45", "DOP853", "Radau", "BDF", "LSODA")
_SLIP_SCALE = 1e-4
#: the nondimensional parameters simulate takes, and those needed without a top
_NAMES, _REQUIRED = ("q", "fr_inv", "sigma", "alpha_v", "alpha_k", "mu"), ("q", "fr_inv", "sigma")
#: outputs above this size get a warning on stderr before the run
WARN_BYTES = 100e6


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe simulate``."""
    _args.add_model_flag(p, "nonlinear model")
    p.add_argument(
        "--t-end", type=float, required=True, metavar="T", help="final time, units of 1/Omega (> 0); required"
    )
    _args.add_state_flags(
        p,
        omega="initial angular velocity, fixed frame, units of Omega",
        k="initial symmetry axis, fixed frame (normalised)",
        velocity="initial velocity of the sphere's centre O, units of Omega R (sliding only; default 0,0)",
    )
    only = {"alpha_v": " (sliding only; required there)", "alpha_k": " (sliding only; default 0.0)"}
    _args.add_parameter_flags(p, _NAMES, "value", unless_top=_REQUIRED, extra=only)
    _args.add_top_arguments(p, spin=True)
    p.add_argument(
        "--friction",
        choices=("isotropic", "componentwise"),
        default="isotropic",
        help="Coulomb law: isotropic (along the slip, eq. 7) or componentwise (per component, eq. 16)",
    )
    p.add_argument(
        "--normal",
        choices=("equilibrium", "actual"),
        default="equilibrium",
        help="friction proportional to the equilibrium normal force (the paper's law) or to the actual N(t)",
    )
    p.add_argument(
        "--method",
        choices=_METHODS,
        default="auto",
        help="integrator: auto (dopri5, or LSODA when the slip mode is stiff: large alpha_v, "
        "or alpha_k > 0), dopri5 (compiled Dormand-Prince 5(4)), rk4 (fixed step "
        "--step), or scipy's RK45, DOP853, Radau, BDF, LSODA",
    )
    _args.add_float_flags(
        p,
        ("--slip-scale", _SLIP_SCALE, "S", "regularisation scale of the Coulomb term, units of Omega R (> 0)"),
        ("--rtol", 1e-9, "R", "relative tolerance of the adaptive integrators (0 < R < 1)"),
        ("--atol", 1e-12, "A", "absolute tolerance of the adaptive integrators (0 < A < 1)"),
        ("--dt", 0.1, "DT", "output interval, units of 1/Omega (> 0)"),
        (
            "--step",
            None,
            "H",
            "step of --method rk4 (required there), first step of the adaptive methods, "
            "units of 1/Omega (default: chosen by the integrator)",
        ),
    )
    _args.add_output_flags(p, "netCDF file to write; required", required=True)
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--progress",
        action="store_true",
        default=None,
        help="show a progress bar (default: when stderr is a terminal and the run takes over a second)",
    )
    g.add_argument("--no-progress", action="store_false", dest="progress", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    """Run ``tippe simulate``: check the output, the memory and the disk first; warn before a
    large output; show progress on a terminal; say what was written."""
    from ..files import check_free_space
    from ..grids.netcdf import write_dataset
    from ..nonlinear.runs import check_run_memory, simulate
    from ..resources import format_bytes, simulate_file_bytes

    _args.apply_top(args, _NAMES if args.model == "sliding" else ("q", "fr_inv", "sigma", "mu"), required=_REQUIRED)
    out = _args.output_path(args)
    t_end, dt = args.t_end, args.dt
    valid = math.isfinite(t_end) and math.isfinite(dt) and t_end > 0 and dt > 0 and t_end / dt <= 1e8
    if valid:  # else simulate says why
        n = int(math.ceil(t_end / dt - 1e-9)) + 1  # the output times
        check_run_memory(args.model, n, t_end=t_end, dt=dt)
        size = simulate_file_bytes(args.model, n)
        check_free_space(out, size)
        if size > WARN_BYTES:
            print(
                f"tippe simulate: warning: the output will be about {format_bytes(size)} ({n} output times at "
                f"--dt {dt:g}); use a larger --dt or a shorter --t-end for a smaller file",
                file=sys.stderr,
            )
    show = args.progress if args.progress is not None else sys.stderr.isatty()
    ds = simulate(
        **_args.keywords(simulate, args, alpha_k=0.0 if args.alpha_k is None else args.alpha_k, progress=show)
    )
    write_dataset(ds, out, overwrite=args.overwrite)
    a, t = ds.attrs, ds["time"].values
    rk4 = a["method"] == "rk4"
    tol, rejected = (f"step {args.step:g}", "") if rk4 else (f"rtol {a['rtol']:g}", f" ({a['nreject']} rejected)")
    print(
        f"wrote {out} ({format_bytes(os.path.getsize(out))}): {a['model']} model, t = {t[0]:g} ... {t[-1]:g} "
        f"({t.size} output times, dt {dt:g}), {a['method']} {tol}: {a['naccept']} steps{rejected}, "
        f"{a['nfev']} evaluations, status: {a['message']}"
    )
    return 0
