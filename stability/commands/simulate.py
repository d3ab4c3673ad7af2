"""``tippe simulate``: a nonlinear run written to netCDF (see :func:`stability.simulate`)."""

from __future__ import annotations

import argparse

from ..grids.netcdf import check_output_path, write_dataset
from ..nonlinear import NONLINEAR_MODELS
from ._args import add_model_flag, add_parameter_flags

__all__ = ["register", "run"]

#: the integrators --method offers, and the default regularisation scale of the Coulomb term:
#: written here so that ``tippe --help`` does not import scipy and the integrators;
#: tests/test_cli.py checks them against stability.nonlinear.integrators and simulate()'s defaults
_METHODS = ("auto", "dopri5", "rk4", "RK45", "DOP853", "Radau", "BDF", "LSODA")
_SLIP_SCALE = 1e-4


def _vec(text: str) -> list[float]:
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma list of numbers") from None


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``simulate`` subcommand."""
    p = sub.add_parser("simulate", help="integrate a nonlinear model -> netCDF",
                       description="Integrate the sliding, rolling or fixed-pivot top from a given "
                                   "state and write the run (omega, k, energy, forces, ...) as netCDF. "
                                   "Default model: sliding (--alpha-v then required). Times are in "
                                   "units of 1/Omega (one spin period is 2 pi), rates in units of Omega.")
    add_model_flag(p, NONLINEAR_MODELS, "sliding", what="nonlinear model")
    p.add_argument("--t-end", type=float, required=True, metavar="T",
                   help="final time, units of 1/Omega (> 0); required")
    p.add_argument("--omega", type=_vec, required=True, metavar="W1,W2,W3",
                   help="initial angular velocity, fixed frame, units of Omega; required")
    p.add_argument("--k", type=_vec, required=True, metavar="K1,K2,K3",
                   help="initial symmetry axis, fixed frame (normalised); required")
    p.add_argument("--velocity", type=_vec, default=None, metavar="V1,V2",
                   help="initial velocity of the sphere's centre O, units of Omega R (sliding only; "
                        "default 0,0)")
    add_parameter_flags(p, ("q", "fr_inv", "sigma", "alpha_v", "alpha_k", "mu"),
                        required=("q", "fr_inv", "sigma"), kind="value", defaults={"alpha_k": 0.0},
                        extra={"alpha_v": " (sliding only; required there)", "alpha_k": " (sliding only)"})
    p.add_argument("--friction", choices=("isotropic", "componentwise"), default="isotropic",
                   help="Coulomb law: isotropic (along the slip, eq. 7) or componentwise (per component, "
                        "eq. 16)")
    p.add_argument("--normal", choices=("equilibrium", "actual"), default="equilibrium",
                   help="friction proportional to the equilibrium normal force (the paper's law) or to "
                        "the actual N(t)")
    p.add_argument("--slip-scale", type=float, default=_SLIP_SCALE, metavar="S",
                   help="regularisation scale of the Coulomb term, units of Omega R (> 0)")
    p.add_argument("--method", choices=_METHODS, default="auto",
                   help="integrator: auto (dopri5, or LSODA when the slip mode is stiff: large alpha_v, "
                        "or alpha_k > 0), dopri5 (compiled Dormand-Prince 5(4)), rk4 (fixed step "
                        "--step), or scipy's RK45, DOP853, Radau, BDF, LSODA")
    p.add_argument("--rtol", type=float, default=1e-9, metavar="R",
                   help="relative tolerance of the adaptive integrators (0 < R < 1)")
    p.add_argument("--atol", type=float, default=1e-12, metavar="A",
                   help="absolute tolerance of the adaptive integrators (0 < A < 1)")
    p.add_argument("--dt", type=float, default=0.1, metavar="DT",
                   help="output interval, units of 1/Omega (> 0)")
    p.add_argument("--step", type=float, default=None, metavar="H",
                   help="step of --method rk4 (required there), first step of the adaptive methods, "
                        "units of 1/Omega (default: chosen by the integrator)")
    p.add_argument("-o", "--output", required=True, metavar="FILE.nc", help="netCDF file to write; required")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output file (default: refuse)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """Run ``tippe simulate``."""
    from ..nonlinear.runs import simulate

    out = check_output_path(args.output, overwrite=args.overwrite)
    ds = simulate(args.model, t_end=args.t_end, omega=args.omega, k=args.k, velocity=args.velocity,
                  q=args.q, fr_inv=args.fr_inv, sigma=args.sigma, alpha_v=args.alpha_v,
                  alpha_k=args.alpha_k, mu=args.mu, friction=args.friction, normal=args.normal,
                  slip_scale=args.slip_scale, method=args.method, rtol=args.rtol, atol=args.atol,
                  dt=args.dt, step=args.step)
    write_dataset(ds, out, overwrite=args.overwrite)
    return 0
