"""A fast spectral kernel: roots of the characteristic polynomials, compiled with numba.

One pass per grid point, in parallel over the points (``numba.njit(parallel=True)``,
``fastmath=False``: IEEE arithmetic, no reassociation, so the error-free transformations and
the exact structural tests below mean what they say). Per point:

0. *Domain* (:func:`checked_sliding_spectrum`, the default path of :func:`stability.spectrum`):
   the bounds of :func:`stability.parameters.check_domain` tested in the same pass, with the
   same ``A_G`` (bit for bit) and the same comparisons (``sigma <= 2 A_G (1 + 8 u)``); points
   outside get NaN and flag -1 and are counted, and the caller calls ``check_domain`` to raise
   its error when the request is not masked (the messages live there only). Scalars are read
   in place (stride 0), not broadcast in memory.
1. *Coefficients.* For the sliding model (eq. 11) they are formed inside the kernel from the
   parameters, with the same floating-point operations as
   :meth:`stability.models.sliding.Sliding.coefficients` (``A_G`` by Dekker's product and
   Knuth's sum as in :mod:`stability.models.inertia`); ``tests/test_kernel.py`` checks that the two
   agree bit for bit. Any other model of degree <= 3 goes through
   :func:`coefficient_spectrum`, on the coefficients the model returns.
2. *Structural zeros.* Exactly zero trailing coefficients (the sliding model's
   ``c0 = -mu alpha_v q fr_inv`` at ``fr_inv = 0``, ``q = 0`` or ``alpha_v = 0``) give exactly
   zero roots with error bound 0; the polynomial is deflated exactly.
3. *Quadratics* (the deflated cubic, and the fixed-pivot and rolling models, eq. 8) as in
   :mod:`stability.linear.roots`: conservative ones (``p(i nu)`` real) in real arithmetic, so that a
   neutral mode has ``Re s = 0`` exactly; others by the cancellation-free formula; one Newton
   step.
4. *Cubics.* Cardano's formula in complex arithmetic gives three estimates (a real leading
   coefficient divided out in real arithmetic; the cube root without trigonometric functions,
   :func:`_cbrt`: a polynomial start and one Halley step, a few ulp). Where the scales
   are widely separated (smallest estimate below 1e-4 x the largest), Cardano's small roots
   carry an absolute error ``~u |largest|``: the largest root (which Cardano gets to full
   relative accuracy) is Newton-polished and divided out by backward deflation (stable for the
   largest root), and the remaining quadratic is solved by the cancellation-free formula. All
   three roots are then polished on the *undeflated* polynomial by Weierstrass (Durand-Kerner)
   sweeps, ``step = p(r) / (c3 prod_j (r - r_j))`` (Newton's step with the other roots divided
   out, which keeps nearly colliding roots apart), until every relative step is below 1e-8
   (the error left, ``step^2 / separation``, is then under the error bound), at most
   ``polish`` sweeps. This test is the per-point a-posteriori check: over the physical domain
   Cardano's roots are good to ~1e-11, so one sweep passes it everywhere (every point of the
   benchmark's sample, 2x10^5 counted); the sweep cannot be skipped: it is what certifies them.
5. *Error bound*, the one of :mod:`stability.linear.roots`: ``dp = (deg + 4) u sum_k |c_k| |r|^k``,
   ``e = min(dp / |p'(r)|, sqrt(2 dp / |p''(r)|))`` (finite at colliding roots), with ``p'``
   and ``p''`` evaluated at the final roots.
6. *Sorting and the decision* of :mod:`stability.linear.spectra`: modes by decreasing ``Re s`` (ties
   by decreasing ``Im s``; compare-exchanges by selects); a mode is neutral if ``Re s = 0`` by
   structure or ``|Re s| <= 4 e + 16 u max|s|``; the point is unstable, marginal or stable.

Convention: ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, fixed frame; growth rate
``Re s``, frequency ``Im s`` in units of the spin rate.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit, prange

__all__ = ["sliding_spectrum", "checked_sliding_spectrum", "sliding_domain", "coefficient_spectrum",
           "KernelSpectrum", "CheckedSpectrum", "MAX_DEGREE"]

#: highest polynomial degree the kernel solves
MAX_DEGREE = 3

_U = 2.0**-53
_SPLITTER = 134217729.0  # 2**27 + 1 (Veltkamp), as in stability.models.inertia
_STABLE, _MARGINAL, _UNSTABLE, _OUTSIDE = 0, 1, 2, -1
_INSIDE, _OUTSIDE_DOMAIN, _NOT_FINITE = 0, 1, 2  # codes of _domain_code
#: slack of the bound sigma <= 2 A_G, as in stability.parameters (round-off in the caller's bound)
_SIGMA_SLACK = 1.0 + 8 * 2.0**-53
_OMEGA = complex(-0.5, math.sqrt(3.0) / 2.0)  # primitive cube root of unity
_OMEGA2 = complex(-0.5, -math.sqrt(3.0) / 2.0)
_CBRT_I = complex(math.sqrt(3.0) / 2.0, 0.5)  # exp(i pi / 6), a cube root of i
_THIRD = 1.0 / 3.0
#: sin(asin(s) / 3) ~ s (_CB0 + _CB1 s^2 + _CB2 s^4 + _CB3 s^6) for |s| <= 1/sqrt(2) (least
#: squares in Chebyshev form; largest error 1.1e-5, removed by the Halley step of _cbrt)
_CB0, _CB1 = 0.3333211994662179, 0.05011247842998644
_CB2, _CB3 = 0.015346168881758358, 0.030366777474809238

_JIT = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")


class KernelSpectrum(tuple):
    """``(eigenvalues, error_bound, neutral, stability)`` as returned by the kernel drivers.

    eigenvalues : complex (N, n), sorted; error_bound : float (N, n); neutral : bool (N, n);
    stability : int8 (N,) (-1 where the point was marked outside the domain).
    """


# --- scalar helpers (inlined by LLVM) ---------------------------------------------------------

@njit(**_JIT)
def _mod(z):
    """``|z|``: ``sqrt(re^2 + im^2)`` (within an ulp of ``hypot``, and much faster) unless the
    squares would underflow or overflow, then ``hypot``."""
    s = z.real * z.real + z.imag * z.imag
    if 1e-290 < s < 1e290:
        return math.sqrt(s)
    return math.hypot(z.real, z.imag)


@njit(**_JIT)
def _horner(c3, c2, c1, c0, s):
    """``p, p', p''`` at ``s`` (Horner, as stability.linear.roots.horner with leading zeros)."""
    p = c3
    d1 = 0j
    d2 = 0j
    for ck in (c2, c1, c0):
        d2 = d2 * s + 2.0 * d1
        d1 = d1 * s + p
        p = p * s + ck
    return p, d1, d2


@njit(**_JIT)
def _value(c3, c2, c1, c0, s):
    """``p(s)`` only."""
    return ((c3 * s + c2) * s + c1) * s + c0


@njit(**_JIT)
def _bound(c3, c2, c1, c0, deg, r):
    """Absolute error bound of a root ``r`` (stability.linear.roots, module docstring)."""
    a = _mod(r)
    scale = ((_mod(c3) * a + _mod(c2)) * a + _mod(c1)) * a + _mod(c0)
    dp = (deg + 4) * _U * scale
    _, d1, d2 = _horner(c3, c2, c1, c0, r)
    m1 = _mod(d1)
    m2 = _mod(d2)
    first = dp / m1 if m1 > 0 else np.inf
    second = math.sqrt(2.0 * dp / m2) if m2 > 0 else np.inf
    return min(first, second)


@njit(**_JIT)
def _mod2(z):
    """``|z|^2`` (for comparisons)."""
    return z.real * z.real + z.imag * z.imag


@njit(**_JIT)
def _pd(c3, c2, c1, c0, s):
    """``p, p'`` at ``s``."""
    p = c3 * s + c2
    d1 = c3 * s + p
    p = p * s + c1
    d1 = d1 * s + p
    p = p * s + c0
    return p, d1


@njit(**_JIT)
def _newton(c3, c2, c1, c0, r, iterations):
    """Newton steps on ``p``, each kept only if ``|p|`` drops."""
    p, d1 = _pd(c3, c2, c1, c0, r)
    for _ in range(iterations):
        if d1 == 0:
            break
        trial = r - p / d1
        pt, dt = _pd(c3, c2, c1, c0, trial)
        if not _mod2(pt) < _mod2(p):
            break
        r, p, d1 = trial, pt, dt
    return r


@njit(**_JIT)
def _quadratic(a, b, k):
    """Roots of ``a s^2 + b s + k`` and whether their real part is exactly zero (stability.linear.roots)."""
    if a.imag == 0 and b.real == 0 and k.imag == 0:
        # conservative: p(i nu) = -a nu^2 - b.imag nu + k is real
        A, B, C = -a.real, -b.imag, k.real
        disc = B * B - 4.0 * A * C
        sq = math.sqrt(abs(disc))
        sgn = 1.0 if B >= 0 else -1.0
        if disc >= 0:
            big = -(B + sgn * sq) / 2.0
            nu1 = big / A if big != 0 else 0.0
            nu2 = C / big if big != 0 else 0.0
            return complex(0.0, nu1), complex(0.0, nu2), True
        nu1 = complex(-B / (2 * A), sq / (2 * abs(A)))
        nu2 = complex(-B / (2 * A), -sq / (2 * abs(A)))
        return 1j * nu1, 1j * nu2, False
    sq = _csqrt(b * b - 4.0 * a * k)
    sgn = 1.0 if (b.conjugate() * sq).real >= 0 else -1.0
    big = -(b + sgn * sq) / 2.0
    if big != 0:
        return big / a, k / big, False
    return 0j, 0j, False


@njit(**_JIT)
def _csqrt(z):
    """Principal complex square root, without cancellation (a few ulp; faster than
    ``numpy.sqrt``, which calls ``hypot``)."""
    x, y = z.real, z.imag
    if x == 0 and y == 0:
        return complex(0.0, y)
    t = math.sqrt(0.5 * (abs(x) + _mod(z)))
    if x >= 0:
        return complex(t, y / (2.0 * t))
    return complex(abs(y) / (2.0 * t), math.copysign(t, y))


@njit(**_JIT)
def _scale(z, t):
    """``z t`` for a real ``t``, componentwise (numba would multiply by ``complex(t, 0)``)."""
    return complex(z.real * t, z.imag * t)


@njit(**_JIT)
def _cbrt(w):
    """A cube root of ``w`` (not always the principal one: Cardano's formula takes any), to a
    few ulp, without trigonometric functions.

    ``w`` is turned by an exact quarter or half turn into ``W`` with ``|arg W| <= pi/4``; the
    direction of ``W^(1/3)``, ``exp(i asin(s) / 3)`` with ``s = Im W / |W|``, is taken from an
    odd polynomial in ``s`` (relative error 1.1e-5) and corrected by one Halley step on
    ``z^3 = W / |W|`` (cubic convergence: ~1e-15); the modulus is ``cbrt(|W|)``, and the turn
    is undone by a cube root of it (``+-1``, ``exp(+-i pi/6)``). ``cbrt(|w|) exp(i atan2(Im w,
    Re w) / 3)`` (atan2, cos, sin) took ~50 of Cardano's ~100 ns per point (one thread); this
    takes ~35."""
    x, y = w.real, w.imag
    r = _mod(w)
    if not 0.0 < r < np.inf:
        return w if r != 0 else 0j  # 0; or not finite (Cardano overflowed: caught by the caller)
    # the turn by selects, not branches (arg w is random over a grid): w = sx W (|x| >= |y|),
    # w = i sy W (|x| < |y|), with sx, sy the signs of x and y
    sx = math.copysign(1.0, x)
    sy = math.copysign(1.0, y)
    flat = abs(y) <= abs(x)
    X = abs(x) if flat else abs(y)
    Y = sx * y if flat else -sy * x
    ir = 1.0 / r
    c = X * ir
    s = Y * ir
    s2 = s * s
    sp = s * (_CB0 + s2 * (_CB1 + s2 * (_CB2 + s2 * _CB3)))  # ~ sin(asin(s) / 3)
    cp = math.sqrt(1.0 - sp * sp)
    # Halley on z^3 = c + i s: z <- z + z (W - z^3) / (2 z^3 + W), all of modulus ~1
    a2r = cp * cp - sp * sp
    a2i = 2.0 * cp * sp
    z3r = a2r * cp - a2i * sp
    z3i = a2r * sp + a2i * cp
    dr, di = c - z3r, s - z3i
    er, ei = 2.0 * z3r + c, 2.0 * z3i + s
    inv = 1.0 / (er * er + ei * ei)
    qr = (dr * er + di * ei) * inv
    qi = (di * er - dr * ei) * inv
    m = np.cbrt(r)
    zr = m * (cp + (cp * qr - sp * qi))
    zi = m * (sp + (cp * qi + sp * qr))
    # undo the turn: times a cube root of sx (sx itself) or of i sy (exp(i sy pi/6))
    tr = sx if flat else _CBRT_I.real
    ti = 0.0 if flat else sy * _CBRT_I.imag
    return complex(zr * tr - zi * ti, zr * ti + zi * tr)


@njit(**_JIT)
def _cardano(c3, c2, c1, c0):
    """Cardano's three roots of a cubic, in complex arithmetic (a real leading coefficient, as
    the sliding model's, is divided out in real arithmetic)."""
    if c3.imag == 0:
        inv = 1.0 / c3.real
        a, b, c = _scale(c2, inv), _scale(c1, inv), _scale(c0, inv)
    else:
        inv = 1.0 / c3
        a, b, c = c2 * inv, c1 * inv, c0 * inv
    a3 = _scale(a, _THIRD)
    P3 = _scale(b - a * a3, _THIRD)
    Q2 = _scale(c - a3 * b, 0.5) + a3 * a3 * a3
    sd = _csqrt(Q2 * Q2 + P3 * P3 * P3)
    w1 = -Q2 + sd
    w2 = -Q2 - sd
    w = w1 if _mod2(w1) >= _mod2(w2) else w2
    u = _cbrt(w)
    n2 = _mod2(u)
    if 1e-290 < n2 < 1e290:
        v = -P3 * u.conjugate() * (1.0 / n2)
    else:
        v = -P3 / u if u != 0 else 0j
    return u + v - a3, _OMEGA * u + _OMEGA2 * v - a3, _OMEGA2 * u + _OMEGA * v - a3


@njit(**_JIT)
def _weierstrass(c3, c2, c1, c0, r, o1, o2):
    """One Weierstrass (Durand-Kerner) step for root ``r``: ``p(r) / (c3 (r - o1)(r - o2))``,
    Newton's step on ``p`` with the other roots divided out (so nearly colliding roots stay
    apart). Returns the new root and ``|step|^2 - 1e-16 |r|^2`` (> 0: a relative step above
    1e-8)."""
    p = _value(c3, c2, c1, c0, r)
    den = c3 * (r - o1) * (r - o2)
    n2 = _mod2(den)
    if n2 == 0 or not np.isfinite(n2):
        return r, 0.0
    step = p * den.conjugate() * (1.0 / n2)
    return r - step, _mod2(step) - 1e-16 * _mod2(r)


@njit(**_JIT)
def _cubic(c3, c2, c1, c0, polish):
    """Three roots of a cubic with ``c0 != 0`` (module docstring, step 4)."""
    r0, r1, r2 = _cardano(c3, c2, c1, c0)
    sweeps = polish
    n0, n1, n2 = _mod2(r0), _mod2(r1), _mod2(r2)
    if min(n0, n1, n2) < 1e-8 * max(n0, n1, n2):
        # widely separated scales: Cardano's small roots carry an absolute error ~u |largest|;
        # take the largest root (accurate), divide it out by backward deflation, stable for
        # the largest root, p(s) = (s - r0)(b2 s^2 + b1 s + b0), and solve the quadratic
        if n1 > n0 and n1 >= n2:
            r0 = r1
        elif n2 > n0:
            r0 = r2
        if polish > 0:
            r0 = _newton(c3, c2, c1, c0, r0, 2)
        ib = 1.0 / r0
        b0 = -c0 * ib
        b1 = (b0 - c1) * ib
        b2 = (b1 - c2) * ib
        r1, r2, _ = _quadratic(b2, b1, b0)
    if not (np.isfinite(r0) and np.isfinite(r1) and np.isfinite(r2)):
        # Cardano overflowed (|c2/c3| beyond ~1e100): start on a circle enclosing the roots
        rho = 2.0 * max(_mod(c2 / c3), math.sqrt(_mod(c1 / c3)), np.cbrt(_mod(c0 / c3)))
        r0, r1, r2 = rho * complex(0.6, 0.8), rho * _OMEGA * complex(0.6, 0.8), rho * _OMEGA2 * complex(0.6, 0.8)
        sweeps = 100 * polish
    for _ in range(sweeps):
        # a relative step above 1e-8 may leave an error (step^2 / separation) above round-off:
        # sweep again; below it the remaining error is under the error bound
        r0, e0 = _weierstrass(c3, c2, c1, c0, r0, r1, r2)
        r1, e1 = _weierstrass(c3, c2, c1, c0, r1, r0, r2)
        r2, e2 = _weierstrass(c3, c2, c1, c0, r2, r0, r1)
        if e0 <= 0 and e1 <= 0 and e2 <= 0:
            break
    return r0, r1, r2


@njit(**_JIT)
def _bound_fast(c3, c2, c1, c0, m3, m2, m1, m0, deg, r):
    """:func:`_bound` with the coefficient moduli ``m_k = |c_k|`` given (one square root
    fewer per comparison; the same value up to rounding)."""
    a = _mod(r)
    dp = (deg + 4) * _U * (((m3 * a + m2) * a + m1) * a + m0)
    # p' and p'' directly (Horner's scheme would form p as well)
    t = _scale(c3, 3.0) * r + _scale(c2, 2.0)
    d1 = t * r + c1
    d2 = _scale(c3, 6.0) * r + _scale(c2, 2.0)
    n1 = _mod2(d1)
    n2 = _mod2(d2)
    # min(dp / |p'|, sqrt(2 dp / |p''|)): the second is smaller iff 4 |p'|^4 < dp^2 |p''|^2
    if 4.0 * n1 * n1 < dp * dp * n2 or n1 == 0:
        return math.sqrt(2.0 * dp / math.sqrt(n2)) if n2 > 0 else np.inf
    return dp / math.sqrt(n1)


@njit(**_JIT)
def _before(a, b):
    """Mode ``a`` sorts before ``b``: larger real part, then larger imaginary part."""
    return a.real > b.real or (a.real == b.real and a.imag > b.imag)


@njit(**_JIT)
def _solve(c3, c2, c1, c0, deg, polish):
    """Roots, error bounds and exact-zero-real flags of ``c3 s^3 + c2 s^2 + c1 s + c0``
    (``deg = 3``) or of ``c3 s^2 + c2 s + c1`` (``deg = 2``, ``c0`` ignored), unsorted."""
    if deg == 2:
        c3, c2, c1, c0 = 0j, c3, c2, c1
    nz = 0
    if c0 == 0:
        nz = 1
        if c1 == 0:
            nz = 2
            if deg == 3 and c2 == 0:
                nz = 3
    m = deg - nz  # degree after exact deflation
    # deflated coefficients, right-aligned with leading zeros
    if nz == 0:
        d3, d2, d1, d0 = c3, c2, c1, c0
    elif nz == 1:
        d3, d2, d1, d0 = 0j, c3, c2, c1
    elif nz == 2:
        d3, d2, d1, d0 = 0j, 0j, c3, c2
    else:
        d3, d2, d1, d0 = 0j, 0j, 0j, c3
    r0 = r1 = r2 = 0j
    x0 = x1 = x2 = True  # structural zeros: exactly zero, bound 0
    e0 = e1 = e2 = 0.0
    if m == 3:
        r0, r1, r2 = _cubic(d3, d2, d1, d0, polish)
        x0 = x1 = x2 = False
    elif m == 2:
        r0, r1, ex = _quadratic(d2, d1, d0)
        if not ex and polish > 0:
            r0 = _newton(d3, d2, d1, d0, r0, 1)
            r1 = _newton(d3, d2, d1, d0, r1, 1)
        x0 = x1 = ex
    elif m == 1:
        r0 = -d0 / d1
        x0 = False
    if m > 0:
        m3, m2, m1, m0 = _mod(d3), _mod(d2), _mod(d1), _mod(d0)
        e0 = _bound_fast(d3, d2, d1, d0, m3, m2, m1, m0, m, r0)
        if m > 1:
            e1 = _bound_fast(d3, d2, d1, d0, m3, m2, m1, m0, m, r1)
        if m > 2:
            e2 = _bound_fast(d3, d2, d1, d0, m3, m2, m1, m0, m, r2)
    return r0, r1, r2, e0, e1, e2, x0, x1, x2


@njit(**_JIT)
def _swap(s, a, b):
    """``(b, a)`` if ``s`` else ``(a, b)`` (a select, not a branch)."""
    return (b, a) if s else (a, b)


@njit(**_JIT)
def _mode(r, e, x, floor):
    """Whether the mode ``r`` (bound ``e``, exactly-zero-real flag ``x``) is neutral, and
    whether it grows (module docstring, step 6)."""
    tol = 4.0 * e + floor
    nt = (x & (r.real == 0)) | (abs(r.real) <= tol)
    return nt, (r.real > tol) & (not nt)


@njit(**_JIT)
def _decide(n, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev, bd, neutral):
    """Sort the ``n`` modes (stable, by decreasing Re s then Im s: a network of
    compare-exchanges by selects, no data-dependent branches), write them to ``ev``, ``bd``,
    ``neutral``; return the stability flag (module docstring, step 6)."""
    if n >= 2:
        s = _before(r1, r0)
        r0, r1 = _swap(s, r0, r1)
        e0, e1 = _swap(s, e0, e1)
        x0, x1 = _swap(s, x0, x1)
    if n == 3:
        s = _before(r2, r1)
        r1, r2 = _swap(s, r1, r2)
        e1, e2 = _swap(s, e1, e2)
        x1, x2 = _swap(s, x1, x2)
        s = _before(r1, r0)
        r0, r1 = _swap(s, r0, r1)
        e0, e1 = _swap(s, e0, e1)
        x0, x1 = _swap(s, x0, x1)
    scale2 = _mod2(r0)
    if n >= 2:
        scale2 = max(scale2, _mod2(r1))
    if n == 3:
        scale2 = max(scale2, _mod2(r2))
    floor = 16.0 * _U * math.sqrt(scale2)
    nt, grows = _mode(r0, e0, x0, floor)
    ev[0], bd[0], neutral[0] = r0, e0, nt
    anyneutral = nt
    if n >= 2:
        nt, g = _mode(r1, e1, x1, floor)
        ev[1], bd[1], neutral[1] = r1, e1, nt
        anyneutral |= nt
        grows |= g
    if n == 3:
        nt, g = _mode(r2, e2, x2, floor)
        ev[2], bd[2], neutral[2] = r2, e2, nt
        anyneutral |= nt
        grows |= g
    if grows:
        return _UNSTABLE
    return _MARGINAL if anyneutral else _STABLE


@njit(**_JIT)
def _mark_outside(n, ev, bd, neutral):
    for j in range(n):
        ev[j] = complex(np.nan, np.nan)
        bd[j] = np.nan
        neutral[j] = False


# --- the sliding model, coefficients formed in the kernel -------------------------------------

@njit(**_JIT)
def _two_product(a, b):
    p = a * b
    c = _SPLITTER * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLITTER * b
    bh = c - (c - b)
    bl = b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@njit(**_JIT)
def _transverse_inertia_g(q, mu):
    """``A_G = 1 - mu q^2`` with the operations of :func:`stability.models.inertia.transverse_inertia_g`
    (Dekker's product, Knuth's sum), so the two agree bit for bit."""
    t, te = _two_product(q, q)
    u, ue = _two_product(mu, t)
    ue = ue + mu * te
    s = 1.0 + (-u)
    bb = s - 1.0
    se = (1.0 - (s - bb)) + (-u - bb)
    return s + (se - ue)


@njit(**_JIT)
def _refused(x, lo, hi):
    """``x`` is not finite or outside the computable range ``lo <= |x| <= hi`` (``|x| < lo``
    counts only for ``x > 0``), as :func:`stability.parameters.check_domain` refuses it.
    ``hi`` is finite (:func:`_computable_limits` puts the largest float for no bound), so
    ``not |x| <= hi`` also refuses NaN and inf; no branches (``&``, ``|``, not ``and``, ``or``)."""
    m = abs(x)
    return (not m <= hi) | ((m < lo) & (x > 0))


@njit(**_JIT)
def _domain_code(q, fr_inv, sigma, alpha_v, mu, a_g, lim):
    """Where a sliding point lies: ``_INSIDE``, ``_OUTSIDE_DOMAIN`` (a bound violated) or
    ``_NOT_FINITE`` (a parameter not finite or outside the computable range ``lim``, the pairs
    ``lo, hi`` for q, fr_inv, sigma, alpha_v, mu, an array of 10 floats, ``hi`` finite: refused
    whatever the mask). The bounds of
    :func:`stability.parameters.check_domain`, with its comparisons as written there
    (``A_G > 0``; ``sigma <= 2 A_G (1 + 8 u)``; NaN fails). Every test is evaluated (``|``, no
    short circuit): the point is inside nearly always, and the branches cost more."""
    bad = (_refused(q, lim[0], lim[1]) | _refused(fr_inv, lim[2], lim[3]) | _refused(sigma, lim[4], lim[5])
           | _refused(alpha_v, lim[6], lim[7]) | _refused(mu, lim[8], lim[9]))
    out = ((mu <= 0.0) | (fr_inv < 0.0) | (alpha_v < 0.0) | (not a_g > 0.0) | (sigma <= 0.0)
           | (sigma > 2.0 * a_g * _SIGMA_SLACK))
    return _NOT_FINITE if bad else (_OUTSIDE_DOMAIN if out else _INSIDE)


@njit(**_JIT)
def sliding_coefficients(q, fr_inv, sigma, alpha_v, mu):
    """``mu det(s M - A)`` of eq. (11) for one point, as Sliding.coefficients computes it."""
    return _sliding_coefficients(q, fr_inv, sigma, alpha_v, mu, _transverse_inertia_g(q, mu))


@njit(**_JIT)
def _sliding_coefficients(q, fr_inv, sigma, alpha_v, mu, a_g):
    """:func:`sliding_coefficients` with ``A_G`` given."""
    a_c = a_g + mu * (1.0 + q) ** 2
    c3 = complex(mu * a_g, 0.0)
    c2 = complex(alpha_v * a_c, -(mu * sigma))
    c1 = complex(-mu * mu * q * fr_inv, -(alpha_v * (sigma + mu * (1.0 + q))))
    c0 = complex(-mu * alpha_v * q * fr_inv, 0.0)
    return c3, c2, c1, c0


@njit(parallel=True, **_JIT)
def _sliding_kernel(q, fr_inv, sigma, alpha_v, mu, inside, polish, ev, bd, neutral, stab):
    for i in prange(q.shape[0]):
        if not inside[i]:
            _mark_outside(3, ev[i], bd[i], neutral[i])
            stab[i] = _OUTSIDE
            continue
        c3, c2, c1, c0 = sliding_coefficients(q[i], fr_inv[i], sigma[i], alpha_v[i], mu[i])
        r0, r1, r2, e0, e1, e2, x0, x1, x2 = _solve(c3, c2, c1, c0, 3, polish)
        stab[i] = _decide(3, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev[i], bd[i], neutral[i])


@njit(inline="always", **_JIT)
def _checked_point(i, q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, lim, polish, ev, bd, neutral, stab, where):
    """Point ``i`` of :func:`_checked_sliding_kernel`."""
    qi, mi = q[i * sq], mu[i * sm]
    fi, si, ai = fr_inv[i * sf], sigma[i * ss], alpha_v[i * sa]
    a_g = _transverse_inertia_g(qi, mi)
    code = _domain_code(qi, fi, si, ai, mi, a_g, lim)
    where[i] = code
    if code != _INSIDE:
        _mark_outside(3, ev[i], bd[i], neutral[i])
        stab[i] = _OUTSIDE
        return
    c3, c2, c1, c0 = _sliding_coefficients(qi, fi, si, ai, mi, a_g)
    r0, r1, r2, e0, e1, e2, x0, x1, x2 = _solve(c3, c2, c1, c0, 3, polish)
    stab[i] = _decide(3, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev[i], bd[i], neutral[i])


@njit(parallel=True, **_JIT)
def _checked_sliding_kernel(q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, lim, polish, ev, bd, neutral,
                            stab, where):
    """:func:`_sliding_kernel` with the domain test fused in; ``where`` (int8) gets the code of
    :func:`_domain_code` per point. Each parameter is a 1-D array read at ``i * stride``
    (stride 1: one value per point; 0: a scalar), so scalars are not broadcast in memory.
    (No reduction variables, which slowed the loop by ~15%; the driver counts.)"""
    for i in prange(stab.shape[0]):
        _checked_point(i, q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, lim, polish, ev, bd, neutral, stab,
                       where)


@njit(**_JIT)
def _checked_sliding_serial(q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, lim, polish, ev, bd, neutral,
                            stab, where):
    """The same loop without threads, for small batches (a parallel launch costs more than a
    few points, and much more on a loaded machine). A separate function, not a second
    ``njit`` of the same one: numba's disk cache would not tell the two apart."""
    for i in range(stab.shape[0]):
        _checked_point(i, q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, lim, polish, ev, bd, neutral, stab,
                       where)


#: batches below this many points run serially
SERIAL_BELOW = 512


@njit(parallel=True, **_JIT)
def _domain_kernel(q, fr_inv, sigma, alpha_v, mu, lim, code):
    for i in prange(q.shape[0]):
        code[i] = _domain_code(q[i], fr_inv[i], sigma[i], alpha_v[i], mu[i],
                               _transverse_inertia_g(q[i], mu[i]), lim)


@njit(parallel=True, **_JIT)
def _coefficient_kernel(c, inside, polish, ev, bd, neutral, stab):
    n = c.shape[1] - 1
    for i in prange(c.shape[0]):
        if not inside[i]:
            _mark_outside(n, ev[i], bd[i], neutral[i])
            stab[i] = _OUTSIDE
            continue
        if n == 3:
            r0, r1, r2, e0, e1, e2, x0, x1, x2 = _solve(c[i, 0], c[i, 1], c[i, 2], c[i, 3], 3, polish)
        elif n == 2:
            r0, r1, r2, e0, e1, e2, x0, x1, x2 = _solve(c[i, 0], c[i, 1], c[i, 2], 0j, 2, polish)
        else:
            r0 = -c[i, 1] / c[i, 0]
            x0 = c[i, 1] == 0
            e0 = 0.0 if x0 else _bound(0j, 0j, c[i, 0], c[i, 1], 1, r0)
            r1 = r2 = 0j
            e1 = e2 = 0.0
            x1 = x2 = False
        stab[i] = _decide(n, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev[i], bd[i], neutral[i])


# --- drivers ----------------------------------------------------------------------------------

def _outputs(npts: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    return (np.empty((npts, n), dtype=np.complex128), np.empty((npts, n)),
            np.empty((npts, n), dtype=np.bool_), np.empty(npts, dtype=np.int8))


def _flat(x: np.ndarray, shape: tuple[int, ...], dtype: type = np.float64) -> np.ndarray:
    """A C-contiguous 1-D array that owns its data (views from ``numpy.broadcast_arrays`` are
    copied: numba would otherwise warn about their write flag)."""
    y = np.asarray(x, dtype=dtype)
    if y.shape == shape and y.flags.c_contiguous and y.base is None:
        return y.reshape(-1)
    return np.array(np.broadcast_to(y, shape), dtype=dtype, order="C").reshape(-1)


def sliding_spectrum(q: np.ndarray, fr_inv: np.ndarray, sigma: np.ndarray, alpha_v: np.ndarray,
                     mu: np.ndarray, inside: np.ndarray | None = None, *,
                     polish: int = 3) -> KernelSpectrum:
    """Sorted eigenvalues, error bounds and the stability decision of the sliding model.

    Parameters
    ----------
    q, fr_inv, sigma, alpha_v, mu : numpy.ndarray
        Parameters of eq. (11), broadcast together; not checked against the physical domain
        (:func:`stability.spectrum` does that).
    inside : numpy.ndarray of bool, optional
        Points to compute (the others get NaN and flag -1); default all.
    polish : int, default 3
        Largest number of polishing sweeps; 0 gives Cardano's roots with deflation only.

    Returns
    -------
    KernelSpectrum
        ``(eigenvalues, error_bound, neutral, stability)``, shape ``broadcast + (3,)`` (and
        ``broadcast`` for the flag).
    """
    shape = np.broadcast_shapes(*(np.shape(v) for v in (q, fr_inv, sigma, alpha_v, mu)))
    args = [_flat(v, shape) for v in (q, fr_inv, sigma, alpha_v, mu)]
    npts = args[0].size
    ins = np.ones(npts, dtype=np.bool_) if inside is None else _flat(inside, shape, np.bool_)
    ev, bd, nt, st = _outputs(npts, 3)
    _sliding_kernel(*args, ins, int(polish), ev, bd, nt, st)
    return KernelSpectrum((ev.reshape(shape + (3,)), bd.reshape(shape + (3,)),
                           nt.reshape(shape + (3,)), st.reshape(shape)))


class CheckedSpectrum(NamedTuple):
    """What :func:`checked_sliding_spectrum` returns.

    Attributes
    ----------
    spectrum : KernelSpectrum
        ``(eigenvalues, error_bound, neutral, stability)``; NaN and flag -1 outside the domain.
    inside : numpy.ndarray of bool
        True where the point lies in the physical domain (and every parameter is finite).
    n_outside : int
        Points not inside (the non-finite ones included).
    n_not_finite : int
        Points where a parameter is NaN, infinite or outside the computable range
        (:data:`stability.parameters.COMPUTABLE_RANGE`): refused even when masked.
    """

    spectrum: KernelSpectrum
    inside: np.ndarray
    n_outside: int
    n_not_finite: int


def _computable_limits() -> np.ndarray:
    """``lo, hi`` magnitudes accepted for q, fr_inv, sigma, alpha_v, mu (10 floats), read from
    :data:`stability.parameters.COMPUTABLE_RANGE` at each call (passed to the kernel as data, so
    a change there is never hidden by numba's cache); ``0`` and the largest float where it names
    none (an upper bound is always finite: :func:`_refused` refuses NaN and inf by it)."""
    from .. import parameters

    rng = getattr(parameters, "COMPUTABLE_RANGE", {})
    lim = np.array([float(x) for k in ("q", "fr_inv", "sigma", "alpha_v", "mu") for x in rng.get(k, (0.0, math.inf))])
    lim[1::2] = np.minimum(lim[1::2], np.finfo(np.float64).max)  # |x| <= hi then also means finite
    return lim


def _strided(x: np.ndarray, shape: tuple[int, ...]) -> tuple[np.ndarray, int]:
    """A 1-D float64 array and the stride to read it with: the data itself (stride 1) when it
    already has the full shape and is C-contiguous, its one value (stride 0) for a single
    value, else a broadcast copy."""
    y = np.asarray(x, dtype=np.float64)
    if y.size == 1:
        return y.reshape(1), 0
    if y.shape == shape and y.flags.c_contiguous:
        return y.reshape(-1), 1
    return np.ascontiguousarray(np.broadcast_to(y, shape)).reshape(-1), 1


def checked_sliding_spectrum(q: np.ndarray, fr_inv: np.ndarray, sigma: np.ndarray, alpha_v: np.ndarray,
                             mu: np.ndarray, *, polish: int = 3) -> CheckedSpectrum:
    """The sliding model's spectrum (eq. 11) with the physical domain tested in the same pass.

    The domain test is :func:`stability.parameters.check_domain`'s, point by point (the same
    ``A_G`` bit for bit, the same comparisons; ``tests/test_kernel.py`` checks that they agree
    on and a few ulps around every bound): ``mu > 0``, ``fr_inv >= 0``, ``alpha_v >= 0``,
    ``1 - mu q^2 > 0``, ``0 < sigma <= 2 (1 - mu q^2) (1 + 8 u)``, and every parameter finite and
    in the computable range (:data:`stability.parameters.COMPUTABLE_RANGE`).
    The kernel only reports; raising (with the canonical message) is left to the caller, which
    calls ``check_domain`` when ``n_outside > 0``.

    Parameters
    ----------
    q, fr_inv, sigma, alpha_v, mu : numpy.ndarray of float64
        Parameters, broadcast together (scalars are read in place, not broadcast in memory).
    polish : int, default 3
        Largest number of polishing sweeps (:func:`sliding_spectrum`).

    Returns
    -------
    CheckedSpectrum
        Shapes ``broadcast + (3,)`` and ``broadcast``.

    Raises
    ------
    ValueError
        If the shapes do not broadcast together.
    """
    values = (q, fr_inv, sigma, alpha_v, mu)
    shape = np.broadcast_shapes(*(np.shape(v) for v in values))
    npts = math.prod(shape)
    flat = [_strided(v, shape) for v in values]
    ev, bd, nt, st = _outputs(npts, 3)
    where = np.empty(npts, dtype=np.int8)
    loop = _checked_sliding_serial if npts < SERIAL_BELOW else _checked_sliding_kernel
    loop(*(a for pair in flat for a in pair), _computable_limits(), int(polish), ev, bd, nt, st, where)
    inside = where == _INSIDE
    n_out = npts - int(np.count_nonzero(inside))
    n_bad = int(np.count_nonzero(where == _NOT_FINITE)) if n_out else 0
    spec = KernelSpectrum((ev.reshape(shape + (3,)), bd.reshape(shape + (3,)), nt.reshape(shape + (3,)),
                           st.reshape(shape)))
    return CheckedSpectrum(spec, inside.reshape(shape), int(n_out), int(n_bad))


def sliding_domain(q: np.ndarray, fr_inv: np.ndarray, sigma: np.ndarray, alpha_v: np.ndarray,
                   mu: np.ndarray) -> np.ndarray:
    """The kernel's domain test alone (for tests): 0 inside, 1 outside the physical domain, 2 a
    parameter not finite or outside the computable range (refused even when masked).

    Parameters
    ----------
    q, fr_inv, sigma, alpha_v, mu : numpy.ndarray
        Parameters, broadcast together.

    Returns
    -------
    numpy.ndarray of int8, broadcast shape
    """
    shape = np.broadcast_shapes(*(np.shape(v) for v in (q, fr_inv, sigma, alpha_v, mu)))
    args = [_flat(v, shape) for v in (q, fr_inv, sigma, alpha_v, mu)]
    code = np.empty(args[0].size, dtype=np.int8)
    _domain_kernel(*args, _computable_limits(), code)
    return code.reshape(shape)


def coefficient_spectrum(c: np.ndarray, inside: np.ndarray | None = None, *,
                         polish: int = 3) -> KernelSpectrum:
    """The kernel on given coefficients ``c`` (..., n+1), highest power first, ``1 <= n <= 3``.

    Parameters
    ----------
    c : numpy.ndarray of complex
        Characteristic polynomials (leading coefficient nonzero).
    inside : numpy.ndarray of bool, optional
        Points to compute (the others get NaN and flag -1); default all.
    polish : int, default 3
        Largest number of polishing sweeps.

    Returns
    -------
    KernelSpectrum
        As :func:`sliding_spectrum`, with ``n`` modes.
    """
    c = np.asarray(c, dtype=np.complex128)
    n = c.shape[-1] - 1
    if not 1 <= n <= MAX_DEGREE:
        raise ValueError(f"the kernel solves degrees 1 to {MAX_DEGREE}, got {n}")
    if np.any(c[..., 0] == 0):
        raise ValueError("leading coefficient is zero (singular mass matrix)")
    shape = c.shape[:-1]
    flat = np.ascontiguousarray(c.reshape(-1, n + 1))
    ins = np.ones(flat.shape[0], dtype=np.bool_) if inside is None else _flat(inside, shape, np.bool_)
    ev, bd, nt, st = _outputs(flat.shape[0], n)
    _coefficient_kernel(flat, ins, int(polish), ev, bd, nt, st)
    return KernelSpectrum((ev.reshape(shape + (n,)), bd.reshape(shape + (n,)),
                           nt.reshape(shape + (n,)), st.reshape(shape)))
