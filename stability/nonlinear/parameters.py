"""Packing of the physical parameters into the float vector the compiled kernels take.

Layout (indices are module constants): ``q, fr_inv, sigma, mu, alpha_v, alpha_k, epsilon,
law, normal`` with ``epsilon`` the Coulomb regularisation scale, ``law`` the friction-law code
and ``normal`` the normal-force code of :mod:`stability.nonlinear.friction`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ALPHA_K", "ALPHA_V", "EPSILON", "FR_INV", "LAW", "MU", "NORMAL", "SIGMA", "Q", "pack"]

Q, FR_INV, SIGMA, MU, ALPHA_V, ALPHA_K, EPSILON, LAW, NORMAL = range(9)


def pack(
    *,
    q: float,
    fr_inv: float,
    sigma: float,
    mu: float,
    alpha_v: float = 0.0,
    alpha_k: float = 0.0,
    epsilon: float = 1e-4,
    law: int = 0,
    normal: int = 0,
) -> np.ndarray:
    """Return the parameter vector of the kernels (see module docstring)."""
    return np.array([q, fr_inv, sigma, mu, alpha_v, alpha_k, epsilon, law, normal], dtype=np.float64)
