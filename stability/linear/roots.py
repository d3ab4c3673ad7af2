"""Batched roots of low-degree complex polynomials, with structure and an error bound.

The spectra of the linear models are the roots of their characteristic polynomials
``p(s) = det(s M - A)`` (degree 2 or 3). This module finds them for a whole grid at once:

1. *Structural zeros.* A trailing coefficient that is exactly zero (the sliding model's
   ``c0 = -mu alpha_v q fr_inv`` at ``fr_inv = 0``, ``q = 0`` or ``alpha_v = 0``) gives an
   exactly zero root; it is returned as ``0`` with error bound ``0`` and the polynomial is
   deflated exactly.
2. *Conservative structure.* If ``p(i nu)`` has real coefficients (true for the fixed-pivot
   and rolling models and for the frictionless sliding model), its roots in ``nu`` are real
   (a neutral mode, ``Re s = 0`` exactly) or come in conjugate pairs (``s, -conj(s)``).
   Quadratics of this kind are solved in real arithmetic so that a neutral mode has a real
   part of exactly zero, never a round-off sign.
3. *General case.* Quadratics by the cancellation-free formula (``r1 = -(b + sqrt(D))/2a``
   with the sign chosen to avoid cancellation, ``r2 = c / (a r1)``); higher degrees by the
   eigenvalues of the companion matrix (batched LAPACK), then Newton polishing on ``p``.

Error bound (documented in ``docs/conventions.md``): coefficient errors of relative size
``gamma = (deg + 4) u`` (``u = 2**-53``; the coefficients are formed from the parameters in a
few rounded operations) perturb ``p(r)`` by at most ``dp = gamma * sum_k |c_k| |r|**k``. A simple
root moves by ``dp / |p'(r)|``; near a double root the quadratic term dominates and the
movement is ``sqrt(2 dp / |p''(r)|)``. The bound returned is the smaller of the two (the
first-order one is valid while it is the smaller), which stays finite at colliding roots.

A posteriori inclusion (:func:`inclusion_radius`), for eigenvalues found by any other method
(the LAPACK path): for a polynomial of degree ``n`` with roots ``z_k``,
``p'(r)/p(r) = sum_k 1/(r - z_k)``, so some root lies within ``n |p(r)| / |p'(r)|`` of ``r``;
and ``|p(r)| = |c_n| prod_k |r - z_k|``, so some root lies within ``(|p(r)| / |c_n|)^(1/n)``.
Both are rigorous once ``|p(r)|`` is bounded above (computed residual plus the rounding of
its evaluation and of the coefficients) and ``|p'(r)|`` below; the smaller radius is returned.
It does not assume that ``r`` is accurate: an eigenvalue wrong by O(1) (``M^-1 A`` formed
from a near-singular ``M``) gets an O(1) radius, and one beside a double root a radius that
follows the ``sqrt(u)`` error there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PolynomialRoots", "polynomial_roots", "horner", "inclusion_radius"]

UNIT_ROUNDOFF = 2.0**-53


@dataclass(frozen=True)
class PolynomialRoots:
    """Roots of a batch of polynomials.

    Attributes
    ----------
    roots : numpy.ndarray of complex, shape (..., n)
        The roots, unsorted.
    error_bound : numpy.ndarray of float, shape (..., n)
        Absolute error bound of each root (see module docstring).
    exact_real : numpy.ndarray of bool, shape (..., n)
        True where the real part is known exactly by structure (a structural zero root, or a
        real root in ``nu`` of a conservative polynomial): ``Re s = 0`` exactly.
    """

    roots: np.ndarray
    error_bound: np.ndarray
    exact_real: np.ndarray


def horner(c: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Evaluate ``p``, ``p'`` and ``p''`` at ``s`` by Horner's scheme.

    Parameters
    ----------
    c : numpy.ndarray, shape (..., n+1)
        Coefficients, highest degree first.
    s : numpy.ndarray, shape (...)
        Evaluation points.

    Returns
    -------
    p, dp, ddp : numpy.ndarray
        Value, first and second derivative.
    """
    p = np.zeros_like(s, dtype=complex) + c[..., 0]
    dp = np.zeros_like(p)
    ddp = np.zeros_like(p)
    for k in range(1, c.shape[-1]):
        ddp = ddp * s + 2.0 * dp
        dp = dp * s + p
        p = p * s + c[..., k]
    return p, dp, ddp


def _abs_horner(c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """``sum_k |c_k| |s|**k``: the scale of rounding errors in ``p(s)``."""
    a = np.abs(s)
    out = np.zeros(s.shape) + np.abs(c[..., 0])
    for k in range(1, c.shape[-1]):
        out = out * a + np.abs(c[..., k])
    return out


def _bound(c: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Absolute error bound of roots ``r`` of ``c`` (see module docstring)."""
    deg = c.shape[-1] - 1
    dp_scale = (deg + 4) * UNIT_ROUNDOFF * _abs_horner(c, r)
    _, d1, d2 = horner(c, r)
    with np.errstate(divide="ignore", invalid="ignore"):
        first = np.where(np.abs(d1) > 0, dp_scale / np.abs(d1), np.inf)
        second = np.where(np.abs(d2) > 0, np.sqrt(2.0 * dp_scale / np.abs(d2)), np.inf)
    return np.minimum(first, second)


def inclusion_radius(c: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Radius of a disc about each ``r`` that holds a root of ``c`` (module docstring).

    Parameters
    ----------
    c : array_like of complex, shape (..., n+1)
        Coefficients, highest degree first (leading coefficient nonzero), as formed from the
        parameters in a few rounded operations (relative error ``(n + 4) u`` each).
    r : array_like of complex, shape (..., m)
        Approximate roots (any method), ``m`` per polynomial.

    Returns
    -------
    numpy.ndarray of float, shape (..., m)
        ``min(n P / D, (P / |c_n|)^(1/n))`` with ``P`` an upper bound of ``|p(r)|`` for the
        exact coefficients and ``D`` a lower bound of ``|p'(r)|``; ``inf`` where ``r`` is not
        finite. It bounds the distance to the *nearest* root; with distinct roots it is the
        error of ``r``.
    """
    c = np.asarray(c, dtype=complex)[..., None, :]
    r = np.asarray(r, dtype=complex)
    n = c.shape[-1] - 1
    p, d1, _ = horner(c, r)
    a = np.abs(r)
    scale = np.zeros(r.shape) + np.abs(c[..., 0])
    dscale = np.zeros(r.shape)
    for k in range(1, n + 1):
        dscale = dscale * a + scale
        scale = scale * a + np.abs(c[..., k])
    # rounding of Horner in complex arithmetic (<= 2 sqrt 2 n u per level, taken as 4 n u) and of
    # the coefficients ((n + 4) u each)
    g = (5 * n + 4) * UNIT_ROUNDOFF
    res = np.abs(p) + g * scale
    dlow = np.abs(d1) - g * dscale
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        first = np.where(dlow > 0, n * res / dlow, np.inf)
        second = (res / np.abs(c[..., 0])) ** (1.0 / n)
    out = np.minimum(first, second)
    return np.where(np.isfinite(r), out, np.inf)


def _newton_polish(c: np.ndarray, r: np.ndarray, iterations: int = 3) -> np.ndarray:
    """Polish roots ``r`` (..., n) of polynomials ``c`` (..., n+1); keep a step only if |p| drops."""
    cc = c[..., None, :]
    for _ in range(iterations):
        p, dp, _ = horner(cc, r)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(dp != 0, p / dp, 0.0)
        trial = r - step
        p_new, _, _ = horner(cc, trial)
        better = np.isfinite(trial) & (np.abs(p_new) < np.abs(p))
        r = np.where(better, trial, r)
    return r


def _quadratic(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roots of ``a s^2 + b s + c`` for a batch (..., 3); returns roots and exact_real mask."""
    a, b, k = c[..., 0], c[..., 1], c[..., 2]
    roots = np.empty(c.shape[:-1] + (2,), dtype=complex)
    exact = np.zeros(c.shape[:-1] + (2,), dtype=bool)
    # Conservative structure: p(i nu) = -a nu^2 + i b nu + k real-coefficient <=> a, i b, k real.
    cons = (a.imag == 0) & (b.real == 0) & (k.imag == 0)
    if cons.any():
        # -a nu^2 - b.imag nu + k = 0  <=>  A nu^2 + B nu + C = 0 with:
        A, B, C = -a.real[cons], -b.imag[cons], k.real[cons]
        disc = B * B - 4.0 * A * C
        sq = np.sqrt(np.abs(disc))
        sgn = np.where(B >= 0, 1.0, -1.0)
        nu = np.empty(A.shape + (2,), dtype=complex)
        real = disc >= 0
        # real roots in nu, without cancellation
        big = -(B + sgn * sq) / 2.0
        with np.errstate(divide="ignore", invalid="ignore"):
            nu1 = np.where(big != 0, big / A, 0.0)
            nu2 = np.where(big != 0, C / big, 0.0)
        nu[..., 0] = np.where(real, nu1, (-B / (2 * A)) + 1j * sq / (2 * np.abs(A)))
        nu[..., 1] = np.where(real, nu2, (-B / (2 * A)) - 1j * sq / (2 * np.abs(A)))
        s = 1j * nu
        s = np.where(real[..., None], 0.0 + 1j * nu.real, s)  # real part exactly zero
        roots[cons] = s
        exact[cons] = real[..., None]
    gen = ~cons
    if gen.any():
        A, B, C = a[gen], b[gen], k[gen]
        sq = np.sqrt(B * B - 4.0 * A * C)
        sgn = np.where((np.conj(B) * sq).real >= 0, 1.0, -1.0)
        big = -(B + sgn * sq) / 2.0
        with np.errstate(divide="ignore", invalid="ignore"):
            r1 = np.where(big != 0, big / A, 0.0)
            r2 = np.where(big != 0, C / big, 0.0)
        roots[gen] = np.stack([r1, r2], axis=-1)
    return roots, exact


def _roots_no_trailing_zero(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roots of polynomials (..., m+1) whose constant term may be anything; m >= 1."""
    m = c.shape[-1] - 1
    if m == 1:
        return (-c[..., 1] / c[..., 0])[..., None], np.zeros(c.shape[:-1] + (1,), dtype=bool)
    if m == 2:
        r, exact = _quadratic(c)
        r = np.where(exact, r, _newton_polish(c, r, iterations=1))
        return r, exact
    comp = np.zeros(c.shape[:-1] + (m, m), dtype=complex)
    comp[..., 0, :] = -c[..., 1:] / c[..., :1]
    idx = np.arange(m - 1)
    comp[..., idx + 1, idx] = 1.0
    r = np.linalg.eigvals(comp)
    r = _newton_polish(c, r)
    return r, np.zeros(r.shape, dtype=bool)


def polynomial_roots(c: np.ndarray) -> PolynomialRoots:
    """Roots of a batch of complex polynomials of one degree, with error bounds.

    Parameters
    ----------
    c : array_like of complex, shape (..., n+1)
        Coefficients, highest degree first. The leading coefficient must be nonzero.

    Returns
    -------
    PolynomialRoots
        Roots (..., n), their absolute error bounds, and the exact-real-part mask.
    """
    c = np.asarray(c, dtype=complex)
    n = c.shape[-1] - 1
    if n < 1:
        raise ValueError(f"polynomial degree must be >= 1, got {n}")
    if np.any(c[..., 0] == 0):
        raise ValueError("leading coefficient is zero (singular mass matrix)")
    flat = c.reshape(-1, n + 1)
    roots = np.zeros((flat.shape[0], n), dtype=complex)
    bound = np.zeros((flat.shape[0], n))
    exact = np.zeros((flat.shape[0], n), dtype=bool)
    # number of exactly zero trailing coefficients (structural zero roots), at most n
    nz = np.zeros(flat.shape[0], dtype=int)
    still = np.ones(flat.shape[0], dtype=bool)
    for k in range(n, 0, -1):
        still &= flat[:, k] == 0
        nz += still
    for z in np.unique(nz):
        sel = nz == z
        m = n - z
        if z:
            exact[sel, m:] = True  # roots[sel, m:] stay 0 with bound 0
        if m == 0:
            continue
        cm = flat[sel, : m + 1]
        r, ex = _roots_no_trailing_zero(cm)
        roots[sel, :m] = r
        exact[sel, :m] = ex
        bound[sel, :m] = _bound(cm[:, None, :], r)
    shape = c.shape[:-1] + (n,)
    return PolynomialRoots(roots.reshape(shape), bound.reshape(shape), exact.reshape(shape))
