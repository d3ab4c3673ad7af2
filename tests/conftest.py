"""Shared fixtures and references: random points of the physical domain (seeded), mpmath roots
and the mpmath eigenvalues of eq. (11)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr


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


def mp_sliding_eigenvalues(q, fr_inv, sigma, alpha_v, mu, dps: int = 50) -> list:
    """Eigenvalues of eq. (11), ``M x' = A x``, at ``dps`` digits (``mpmath.eig`` of ``M^-1 A``,
    the matrices typed from the paper, independently of :mod:`stability.models.sliding`)."""
    import mpmath as mp

    with mp.workdps(dps):
        q, F, sg, a, m = (mp.mpf(float(v)) for v in (q, fr_inv, sigma, alpha_v, mu))
        i = mp.mpc(0, 1)
        M = mp.matrix([[1, 0, i * m * q], [0, 1, 0], [-i * q, 0, 1]])
        A = mp.matrix([
            [-a + i * (sg - 1), i * (-(sg - 1) + m * q * F), i * a],
            [-i, i, 0],
            [-(q + i * a / m), q, -a / m],
        ])
        return list(mp.eig(M**-1 * A, left=False, right=False))


def assert_same_atlas(a: xr.Dataset, b: xr.Dataset) -> None:
    """Two atlases identical in every value, coordinate and attribute but ``history``."""
    a, b = a.copy(), b.copy()
    a.attrs.pop("history", None)
    b.attrs.pop("history", None)
    xr.testing.assert_identical(a, b)


def assert_resume_completes(ds: xr.Dataset, out, reference: xr.Dataset, monkeypatch, missing: int) -> None:
    """After a faulted run: ``write_atlas(ds, out, resume=True)`` computes only the ``missing``
    chunks not kept in the parts store, removes the store and writes an atlas identical to
    ``reference``. Undoes the caller's ``monkeypatch`` first (the injected fault), then counts
    the calls of the real chunk function."""
    import stability
    import stability.grids.chunked as dist

    monkeypatch.undo()
    calls = []
    original = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or original(spec, sl))
    dist.write_atlas(ds, out, resume=True)
    assert len(calls) == missing  # only the chunks not kept
    assert not dist.parts_directory(out).exists()
    assert_same_atlas(stability.open_atlas(out), reference)
