"""``tippe simulate``: a nonlinear run written to netCDF (see :func:`stability.simulate`)."""

from __future__ import annotations

import argparse

from ..grids.netcdf import check_output_path, write_dataset
from ..nonlinear import NONLINEAR_MODELS
from ..parameters import DEFAULT_MU

__all__ = ["register", "run"]


def _vec(text: str) -> list[float]:
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma list of numbers") from None


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``simulate`` subcommand."""
    p = sub.add_parser("simulate", help="integrate a nonlinear model -> netCDF",
                       description="Integrate the sliding, rolling or fixed-pivot top from a given "
                                   "state and write the run (omega, k, energy, forces, ...) as netCDF.")
    p.add_argument("--model", choices=list(NONLINEAR_MODELS), default="sliding")
    p.add_argument("--t-end", type=float, required=True, help="final time, units of 1/Omega")
    p.add_argument("--omega", type=_vec, required=True, help="initial angular velocity w1,w2,w3")
    p.add_argument("--k", type=_vec, required=True, help="initial axis k1,k2,k3")
    p.add_argument("--velocity", type=_vec, default=None, help="initial centre velocity V1,V2 (sliding)")
    for flag in ("--q", "--fr-inv", "--sigma"):
        p.add_argument(flag, type=float, required=True)
    p.add_argument("--alpha-v", type=float, default=None)
    p.add_argument("--alpha-k", type=float, default=0.0)
    p.add_argument("--mu", type=float, default=DEFAULT_MU)
    p.add_argument("--friction", choices=("isotropic", "componentwise"), default="isotropic")
    p.add_argument("--normal", choices=("equilibrium", "actual"), default="equilibrium")
    p.add_argument("--slip-scale", type=float, default=1e-4)
    p.add_argument("--method", default="auto")
    p.add_argument("--rtol", type=float, default=1e-9)
    p.add_argument("--atol", type=float, default=1e-12)
    p.add_argument("--dt", type=float, default=0.1, help="output interval")
    p.add_argument("--step", type=float, default=None, help="step of --method rk4")
    p.add_argument("-o", "--output", required=True, help="netCDF file to write")
    p.add_argument("--overwrite", action="store_true")
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
