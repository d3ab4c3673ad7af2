"""Shared fixtures: random points of the physical domain (seeded)."""

from __future__ import annotations

import numpy as np
import pytest


def random_domain_points(n: int, seed: int, *, alpha_v: bool = True) -> dict[str, np.ndarray]:
    """``n`` points spread over the physical domain.

    mu in [0.5, 6]; q uniform in |q| < 0.98 / sqrt(mu) (the mass matrix stays invertible);
    sigma uniform in (0.02, 2 (1 - mu q^2)]; fr_inv uniform in [0, 3]; alpha_v log-uniform in
    [1e-2, 1e1].
    """
    rng = np.random.default_rng(seed)
    mu = rng.uniform(0.5, 6.0, n)
    q = rng.uniform(-0.98, 0.98, n) / np.sqrt(mu)
    sigma = rng.uniform(0.01, 1.0, n) * 2.0 * (1.0 - mu * q * q)
    fr_inv = rng.uniform(0.0, 3.0, n)
    out = {"q": q, "fr_inv": fr_inv, "sigma": sigma, "mu": mu}
    if alpha_v:
        out["alpha_v"] = 10.0 ** rng.uniform(-2.0, 1.0, n)
    return out


@pytest.fixture
def domain_points():
    """Factory fixture for :func:`random_domain_points`."""
    return random_domain_points


def mp_polyroots(coeffs, **kwargs):
    """``mpmath.polyroots`` of coefficients in descending powers, on any mpmath version.

    mpmath 1.4 deprecates the descending order and takes ``asc=True`` for ascending
    coefficients; mpmath 1.3 has no ``asc`` keyword (it raises TypeError).
    """
    import mpmath

    try:
        return mpmath.polyroots(list(coeffs)[::-1], asc=True, **kwargs)
    except TypeError:
        return mpmath.polyroots(list(coeffs), **kwargs)
