"""A fast spectral kernel: roots of the characteristic polynomials, one pass per point.

Written once in plain Python and run two ways (:mod:`stability.execution`): compiled by numba,
in parallel over the points (``parallel=True``, ``fastmath=False``: IEEE arithmetic, no
reassociation, so the error-free transformations and the exact structural tests below mean what
they say), or interpreted, for small requests in a process that has not compiled the loop
(no compilation, no numba import; ~200x slower per point, which does not matter below a few
thousand points). The two give the same bits (tests/test_kernel.py). Per point:

0. *Domain* (:func:`checked_model_spectrum`, the default path of :func:`stability.spectrum`
   for a model that offers its coefficients as a formula): the bounds of the domain table
   :data:`stability.parameters.DOMAIN` tested in the same pass, compiled from the same source
   as :func:`stability.parameters.check_domain`'s numpy test (:func:`~stability.parameters.domain_sides`,
   :func:`~stability.parameters.bound_holds`: the same decisions, exact; the two bounds through
   ``A_G`` by a plain comparison with a proven margin where it decides, by the exact expansions
   of ``domain_sides`` only within a few ulp of a bound, :func:`~stability.parameters.domain_sides_quick`,
   which halved the domain test's time); points outside get NaN and flag -1 and are
   counted, and the caller calls ``check_domain`` to raise its error when the request is not
   masked (the messages live there only). Scalars are read in place (stride 0), not broadcast
   in memory.
1. *Coefficients.* A model that offers ``point_coefficients`` (the optional capability of
   :mod:`stability.models.base`; the sliding model, eq. 11) has them formed inside the kernel
   from the parameters: its formula, a ``register_jitable`` function, is compiled into the
   kernel's loop (:func:`_model_kernels`, one set of loops per model, cached on disk), so the
   kernel does the same floating-point operations as the model's own numpy
   :meth:`~stability.models.base.LinearModel.coefficients` (``tests/test_kernel.py`` checks
   that the two engines agree bit for bit). Any other model of degree <= 3 goes through
   :func:`coefficient_spectrum`, on the coefficients the model returns.
2. *Structural zeros.* Exactly zero trailing coefficients (the sliding model's
   ``c0 = -mu alpha_v q fr_inv`` at ``fr_inv = 0``, ``q = 0`` or ``alpha_v = 0``) give exactly
   zero roots with error bound 0; the polynomial is deflated exactly.
3. *Quadratics* (the deflated cubic, and the fixed-pivot and rolling models, eq. 8) by
   :func:`stability.linear.roots.quadratic_roots`: conservative ones (``p(i nu)`` real) in real
   arithmetic, so that a neutral mode has ``Re s = 0`` exactly; others by the
   cancellation-free formula; one Newton step.
4. *Cubics.* Cardano's formula in complex arithmetic gives three estimates (a real leading
   coefficient divided out in real arithmetic; the cube root without trigonometric functions,
   :func:`_cardano`: a polynomial start and one Halley step, a few ulp). Where the scales
   are widely separated (smallest estimate below 1e-4 x the largest), Cardano's small roots
   carry an absolute error ``~u |largest|``: the largest root (which Cardano gets to full
   relative accuracy) is Newton-polished and divided out by backward deflation
   (:func:`stability.linear.roots.deflate_cubic_backward`, stable for the largest root), and the
   remaining quadratic is solved by the cancellation-free formula. All
   three roots are then polished on the *undeflated* polynomial by Weierstrass (Durand-Kerner)
   sweeps, ``step = p(r) / (c3 prod_j (r - r_j))`` (Newton's step with the other roots divided
   out, which keeps nearly colliding roots apart), until every relative step is below 1e-8
   (the error left, ``step^2 / separation``, is then under the error bound), at most
   ``polish`` sweeps. This test is the per-point a-posteriori check: over the physical domain
   Cardano's roots are good to ~1e-11, so one sweep passes it everywhere (every point of the
   benchmark's sample, 2x10^5 counted); the sweep cannot be skipped: it is what certifies them.
   The model loops (compiled) solve their points in blocks of :data:`BLOCK`, in
   structure-of-arrays scratch rows, by loops without a branch on data that the compiler
   turns into packed (SIMD) arithmetic: the same operations in the same order, so the same
   bits; a point that leaves the generic cubic anywhere is solved again point by point
   (:func:`_block_solve`; ~0.2 % of the benchmark's sample). Steps 4-6 then take about half
   the time they took point by point (docs/performance.md).
5. *Error bound*, the one of :mod:`stability.linear.roots`: ``dp = (deg + 4) u sum_k |c_k| |r|^k``,
   ``e = min(dp / |p'(r)|, sqrt(2 dp / |p''(r)|))`` (finite at colliding roots), with ``p'``
   and ``p''`` evaluated at the final roots.
6. *Sorting and the decision* of :mod:`stability.linear.spectra`: modes by decreasing ``Re s`` (ties
   by decreasing ``Im s``; compare-exchanges by selects); a mode is neutral if ``Re s = 0`` by
   structure or ``|Re s| <= 4 e + 16 u max|s|``; the point is unstable, marginal or stable.

Polynomial building blocks (Horner's scheme, the quadratic formula, deflation, the complex
square root and modulus, the real cube root) come from :mod:`stability.linear.roots`, where
they are written once for every engine.

Executions. Every loop is a plain function: its source, which loops over ``prange`` (the
builtin ``range`` here) and indexes ``x[i][j]`` and ``len(x)`` only, runs on Python lists
(interpreted) or on numpy arrays (compiled by :func:`stability.jit.cached`, serial or parallel;
numba's ``prange`` in the parallel copy). The drivers choose the execution by
:func:`stability.execution.use_compiled` (interpreted below
:data:`stability.execution.PYTHON_BELOW` points unless the compiled loop is in memory;
``engine=`` or ``TIPPE_KERNEL`` force one) and the compiled loop by size (serial below
:data:`SERIAL_BELOW` points, or as asked by ``parallel``): a caller that wants one thread asks
for it, the process-wide thread count is never changed. Only the loops are compiled as entry
points (cached on disk); the helpers are ``register_jitable`` functions compiled into them.

Convention: ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, fixed frame; growth rate
``Re s``, frequency ``Im s`` in units of the spin rate.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping
from typing import Any, NamedTuple

import numpy as np

from stability.jit import OPTIONS, overload, register_jitable

from ..errors import InputError
from ..models import LinearModel, get_model
from ..parameters import PARAMETERS, domain_applies, domain_clearly_inside, domain_sides_quick, inside_domain
from . import roots
from .roots import cbrt, csqrt, csqrt_nonzero, deflate_cubic_backward, horner_scheme, modulus, quadratic_roots

__all__ = [
    "MAX_DEGREE",
    "SERIAL_BELOW",
    "CheckedSpectrum",
    "KernelSpectrum",
    "accepts",
    "checked_model_spectrum",
    "coefficient_spectrum",
    "model_domain",
    "model_spectrum",
]

#: highest polynomial degree the kernel solves
MAX_DEGREE = 3


#: compiled batches below this many points run serially unless a caller asks otherwise
SERIAL_BELOW = roots.SERIAL_BELOW

#: the loops' source iterates over ``prange``: the builtin ``range`` when interpreted or compiled
#: serially, numba's ``prange`` in a parallel compilation (:func:`stability.jit.cached`)
prange = range

_STABLE, _MARGINAL, _UNSTABLE, _OUTSIDE = 0, 1, 2, -1
_INSIDE, _OUTSIDE_DOMAIN, _NOT_FINITE = 0, 1, 2  # codes of _domain_code
_UNDECIDED = 3  # a point _domain_clear leaves to _domain_code
_OMEGA = complex(-0.5, math.sqrt(3.0) / 2.0)  # primitive cube root of unity
_OMEGA2 = complex(-0.5, -math.sqrt(3.0) / 2.0)
_CBRT_I = complex(math.sqrt(3.0) / 2.0, 0.5)  # exp(i pi / 6), a cube root of i
_THIRD = 1.0 / 3.0
#: sin(asin(s) / 3) ~ s (_CB0 + _CB1 s^2 + _CB2 s^4 + _CB3 s^6) for |s| <= 1/sqrt(2) (least
#: squares in Chebyshev form; largest error 1.1e-5, removed by the Halley step of _turn)
_CB0, _CB1 = 0.3333211994662179, 0.05011247842998644
_CB2, _CB3 = 0.015346168881758358, 0.030366777474809238


class KernelSpectrum(NamedTuple):
    """What the kernel drivers return (a named tuple: ``ev, bd, nt, st = ...`` still works).

    Attributes
    ----------
    eigenvalues : numpy.ndarray of complex, shape (..., n)
        Sorted by decreasing real part (ties by decreasing imaginary part).
    error_bound : numpy.ndarray of float, shape (..., n)
    neutral : numpy.ndarray of bool, shape (..., n)
    stability : numpy.ndarray of int8, shape (...)
        -1 where the point was marked outside the domain.
    """

    eigenvalues: np.ndarray
    error_bound: np.ndarray
    neutral: np.ndarray
    stability: np.ndarray


# --- scalar helpers (compiled into the loops) ---------------------------------------------------------


@register_jitable
def _finite(z):
    """Both parts of the complex ``z`` finite (``numpy.isfinite`` of a complex number)."""
    return math.isfinite(z.real) and math.isfinite(z.imag)


@register_jitable
def _mod2(z):
    """``|z|^2`` (for comparisons)."""
    return z.real * z.real + z.imag * z.imag


@register_jitable
def _newton(c3, c2, c1, c0, r, iterations):
    """Newton steps on ``p``, each kept only if ``|p|`` drops."""
    p, d1, _ = horner_scheme((c3, c2, c1, c0), r, 1)
    for _ in range(iterations):
        if d1 == 0:
            break
        trial = r - p / d1
        pt, dt, _ = horner_scheme((c3, c2, c1, c0), trial, 1)
        if not _mod2(pt) < _mod2(p):
            break
        r, p, d1 = trial, pt, dt
    return r


@register_jitable
def _scale(z, t):
    """``z t`` for a real ``t``, componentwise (numba would multiply by ``complex(t, 0)``)."""
    return complex(z.real * t, z.imag * t)


@register_jitable
def _cbrt(w):
    """A cube root of ``w`` (:func:`_cardano`)."""
    r = modulus(w)
    if not 0.0 < r < math.inf:
        return w if r != 0 else 0j  # 0; or not finite (Cardano overflowed: caught by the caller)
    return _untwist(cbrt(r), *_turn(w, r))


@register_jitable
def _turn(w, r):
    """The cube root of ``w`` (modulus ``r``, ``0 < r < inf``; :func:`_cardano`) but for the cube root of ``r``:
    ``(zr, zi, tr, ti)`` with ``cbrt(w) = cbrt(r) (zr + i zi) (tr + i ti)`` (no branch on data)."""
    x, y = w.real, w.imag
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
    # undo the turn: times a cube root of sx (sx itself) or of i sy (exp(i sy pi/6))
    tr = sx if flat else _CBRT_I.real
    ti = 0.0 if flat else sy * _CBRT_I.imag
    return cp + (cp * qr - sp * qi), sp + (cp * qi + sp * qr), tr, ti


@register_jitable
def _untwist(m, zr, zi, tr, ti):
    """The cube root from :func:`_turn`'s parts and ``m = cbrt(r)``."""
    zr, zi = m * zr, m * zi
    return complex(zr * tr - zi * ti, zr * ti + zi * tr)


@register_jitable
def _cardano(c3, c2, c1, c0):
    """Cardano's three roots of a cubic, in complex arithmetic (a real leading coefficient, as
    the sliding model's, is divided out in real arithmetic).

    The cube root ``u`` of ``w`` (not always the principal one: Cardano's formula takes any) is
    taken to a few ulp without trigonometric functions: ``w`` is turned by an exact quarter or
    half turn into ``W`` with ``|arg W| <= pi/4``; the direction of ``W^(1/3)``,
    ``exp(i asin(s) / 3)`` with ``s = Im W / |W|``, is taken from an odd polynomial in ``s``
    (relative error 1.1e-5) and corrected by one Halley step on ``z^3 = W / |W|`` (cubic
    convergence: ~1e-15); the modulus is ``cbrt(|W|)``, and the turn is undone by a cube root
    of it (``+-1``, ``exp(+-i pi/6)``) (:func:`_turn`, :func:`_untwist`). ``cbrt(|w|) exp(i
    atan2(Im w, Re w) / 3)`` (atan2, cos, sin) took ~50 of Cardano's ~100 ns per point (one
    thread); this takes ~35."""
    if c3.imag == 0:
        inv = 1.0 / c3.real
        a, b, c = _scale(c2, inv), _scale(c1, inv), _scale(c0, inv)
    else:
        inv = 1.0 / c3
        a, b, c = c2 * inv, c1 * inv, c0 * inv
    a3, P3, Q2, disc = _depressed(a, b, c)
    w = _larger(Q2, csqrt(disc))
    u = _cbrt(w)
    n2 = _mod2(u)
    if 1e-290 < n2 < 1e290:
        v = -P3 * u.conjugate() * (1.0 / n2)
    else:
        v = -P3 / u if u != 0 else 0j
    return _three_roots(u, v, a3)


@register_jitable
def _depressed(a, b, c):
    """``s^3 + a s^2 + b s + c`` with ``s = x - a/3``: ``x^3 + 3 P3 x + 2 Q2`` (``a/3``, ``P3``,
    ``Q2``) and Cardano's discriminant ``Q2^2 + P3^3``."""
    a3 = _scale(a, _THIRD)
    P3 = _scale(b - a * a3, _THIRD)
    Q2 = _scale(c - a3 * b, 0.5) + a3 * a3 * a3
    return a3, P3, Q2, Q2 * Q2 + P3 * P3 * P3


@register_jitable
def _larger(Q2, sd):
    """The larger in modulus of ``-Q2 + sd`` and ``-Q2 - sd`` (no cancellation; a select)."""
    w1 = -Q2 + sd
    w2 = -Q2 - sd
    return w1 if _mod2(w1) >= _mod2(w2) else w2


@register_jitable
def _three_roots(u, v, a3):
    """Cardano's roots ``u + v``, ``omega u + omega^2 v``, ``omega^2 u + omega v``, less ``a/3``."""
    return u + v - a3, _OMEGA * u + _OMEGA2 * v - a3, _OMEGA2 * u + _OMEGA * v - a3


@register_jitable
def _weierstrass(c3, c2, c1, c0, r, o1, o2):
    """One Weierstrass (Durand-Kerner) step for root ``r``: ``p(r) / (c3 (r - o1)(r - o2))``,
    Newton's step on ``p`` with the other roots divided out (so nearly colliding roots stay
    apart). Returns the new root and ``|step|^2 - 1e-16 |r|^2`` (> 0: a relative step above
    1e-8)."""
    p = horner_scheme((c3, c2, c1, c0), r, 0)[0]
    den = c3 * (r - o1) * (r - o2)
    n2 = _mod2(den)
    keep = (n2 == 0) | (not math.isfinite(n2))  # no step (selects: the compiled blocks pack it)
    step = p * den.conjugate() * (1.0 / (1.0 if keep else n2))
    return (r if keep else r - step), (0.0 if keep else _mod2(step) - 1e-16 * _mod2(r))


@register_jitable
def _separated(r0, r1, r2):
    """Whether the scales of three roots are widely separated (:func:`_cubic`: smallest modulus
    below 1e-4 x the largest), and their squared moduli."""
    n0, n1, n2 = _mod2(r0), _mod2(r1), _mod2(r2)
    # selects written out (not min/max): the compiled blocks pack them (benchmarks/kernel_simd.py)
    lo = n0 if n0 < n1 else n1  # noqa: FURB136
    hi = n0 if n0 > n1 else n1  # noqa: FURB136
    return (lo if lo < n2 else n2) < 1e-8 * (hi if hi > n2 else n2), n0, n1, n2  # noqa: FURB136


@register_jitable
def _cubic(c3, c2, c1, c0, polish):
    """Three roots of a cubic with ``c0 != 0``: Cardano's estimates (:func:`_cardano`),
    polished (module docstring, step 4)."""
    r0, r1, r2 = _cardano(c3, c2, c1, c0)
    sweeps = polish
    separated, n0, n1, n2 = _separated(r0, r1, r2)
    if separated:
        # widely separated scales: Cardano's small roots carry an absolute error ~u |largest|;
        # take the largest root (accurate), divide it out by backward deflation, stable for
        # the largest root, p(s) = (s - r0)(b2 s^2 + b1 s + b0), and solve the quadratic
        if n1 > n0 and n1 >= n2:
            r0 = r1
        elif n2 > n0:
            r0 = r2
        if polish > 0:
            r0 = _newton(c3, c2, c1, c0, r0, 2)
        b2, b1, b0 = deflate_cubic_backward(c3, c2, c1, c0, r0)
        r1, r2, _ = quadratic_roots(b2, b1, b0)
    if not (_finite(r0) and _finite(r1) and _finite(r2)):
        # Cardano overflowed (|c2/c3| beyond ~1e100): start on a circle enclosing the roots
        rho = 2.0 * max(modulus(c2 / c3), math.sqrt(modulus(c1 / c3)), cbrt(modulus(c0 / c3)))
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


@register_jitable
def _bound(c3, c2, c1, c0, deg, r):
    """Absolute error bound of a root ``r`` (stability.linear.roots, module docstring)."""
    a = modulus(r)
    scale = ((modulus(c3) * a + modulus(c2)) * a + modulus(c1)) * a + modulus(c0)
    dp = (deg + 4) * roots.UNIT_ROUNDOFF * scale
    _, d1, d2 = horner_scheme((c3, c2, c1, c0), r)
    m1 = modulus(d1)
    m2 = modulus(d2)
    first = dp / m1 if m1 > 0 else math.inf
    second = math.sqrt(2.0 * dp / m2) if m2 > 0 else math.inf
    return min(first, second)


@register_jitable
def _bound_fast(c3, c2, c1, c0, m3, m2, m1, m0, deg, r):
    """:func:`_bound` with the coefficient moduli ``m_k = |c_k|`` given (one square root
    fewer per comparison; the same value up to rounding)."""
    dp, n1, n2, second = _bound_terms(c3, c2, c1, m3, m2, m1, m0, deg, r, modulus(r))
    if second:
        return math.sqrt(2.0 * dp / math.sqrt(n2)) if n2 > 0 else math.inf
    return dp / math.sqrt(n1)


@register_jitable
def _bound_terms(c3, c2, c1, m3, m2, m1, m0, deg, r, a):
    """``dp``, ``|p'(r)|^2``, ``|p''(r)|^2`` of :func:`_bound_fast` (``a = |r|``) and whether
    the bound is ``sqrt(2 dp / |p''|)`` (the smaller: ``4 |p'|^4 < dp^2 |p''|^2``) rather than
    ``dp / |p'|``."""
    dp = (deg + 4) * roots.UNIT_ROUNDOFF * (((m3 * a + m2) * a + m1) * a + m0)
    # p' and p'' directly (Horner's scheme would form p as well)
    t = _scale(c3, 3.0) * r + _scale(c2, 2.0)
    d1 = t * r + c1
    d2 = _scale(c3, 6.0) * r + _scale(c2, 2.0)
    n1 = _mod2(d1)
    n2 = _mod2(d2)
    return dp, n1, n2, (4.0 * n1 * n1 < dp * dp * n2) | (n1 == 0)


@register_jitable
def _solve(c3, c2, c1, c0, deg, polish):
    """Roots, error bounds and exact-zero-real flags of ``c3 s^3 + c2 s^2 + c1 s + c0``
    (``deg = 3``) or of ``c3 s^2 + c2 s + c1`` (``deg = 2``, ``c0`` ignored), unsorted."""
    if deg == 2:
        c3, c2, c1, c0 = 0j, c3, c2, c1
    # exact deflation of the ``nz`` zero trailing coefficients (right-aligned, leading zeros)
    d3, d2, d1, d0 = c3, c2, c1, c0
    nz = 0
    while nz < deg and d0 == 0:
        d3, d2, d1, d0 = 0j, d3, d2, d1
        nz += 1
    m = deg - nz  # degree after exact deflation
    r0 = r1 = r2 = 0j
    x0 = x1 = x2 = True  # structural zeros: exactly zero, bound 0
    e0 = e1 = e2 = 0.0
    if m == 3:
        r0, r1, r2 = _cubic(d3, d2, d1, d0, polish)
        x0 = x1 = x2 = False
    elif m == 2:
        r0, r1, ex = quadratic_roots(d2, d1, d0)
        if not ex and polish > 0:
            r0 = _newton(d3, d2, d1, d0, r0, 1)
            r1 = _newton(d3, d2, d1, d0, r1, 1)
        x0 = x1 = ex
    elif m == 1:
        r0 = -d0 / d1
        x0 = False
    if m > 0:
        m3, m2, m1, m0 = modulus(d3), modulus(d2), modulus(d1), modulus(d0)
        e0 = _bound_fast(d3, d2, d1, d0, m3, m2, m1, m0, m, r0)
        if m > 1:
            e1 = _bound_fast(d3, d2, d1, d0, m3, m2, m1, m0, m, r1)
        if m > 2:
            e2 = _bound_fast(d3, d2, d1, d0, m3, m2, m1, m0, m, r2)
    return r0, r1, r2, e0, e1, e2, x0, x1, x2


@register_jitable
def _solve_linear(c1, c0):
    """The root of ``c1 s + c0``, its bound and exact-zero flag (in :func:`_solve`'s layout)."""
    r0 = -c0 / c1
    x0 = c0 == 0
    e0 = 0.0 if x0 else _bound(0j, 0j, c1, c0, 1, r0)
    return r0, 0j, 0j, e0, 0.0, 0.0, x0, False, False


@register_jitable
def _swap(s, a, b):
    """``(b, a)`` if ``s`` else ``(a, b)`` (a select, not a branch)."""
    return (b, a) if s else (a, b)


@register_jitable
def _exchange(ra, rb, ea, eb, xa, xb):
    """A compare-exchange of :func:`_decide`: modes ``a`` and ``b`` (root, bound, flag) swapped
    where ``b`` sorts before ``a``: a larger real part, then a larger imaginary part (selects)."""
    s = rb.real > ra.real or (rb.real == ra.real and rb.imag > ra.imag)
    ra, rb = _swap(s, ra, rb)
    ea, eb = _swap(s, ea, eb)
    xa, xb = _swap(s, xa, xb)
    return ra, rb, ea, eb, xa, xb


@register_jitable
def _mode(r, e, x, floor):
    """Whether the mode ``r`` (bound ``e``, exactly-zero-real flag ``x``) is neutral, and
    whether it grows (module docstring, step 6)."""
    tol = 4.0 * e + floor  # roots.neutral_tolerance, with its floor 16 u max|s| formed once per point
    nt = (x & (r.real == 0)) | (abs(r.real) <= tol)
    return nt, (r.real > tol) & (not nt)


@register_jitable(inline="always")
def _decide(n, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev, bd, neutral, i):
    """Sort the ``n`` modes (stable, by decreasing Re s then Im s: a network of
    compare-exchanges by selects, no data-dependent branches), write them to row ``i`` of
    ``ev``, ``bd``, ``neutral``; return the stability flag (module docstring, step 6).

    Compiled into the loop's body (``inline="always"``) and writing the rows through the whole
    arrays (``ev[i][j]``): called as a function with row views (``ev[i]``) made per point, the
    arrays' passing and reference counting cost ~25-30 ns per point, a sixth of the loop on one
    thread (benchmarks/kernel_pieces.py, docs/performance.md)."""
    if n >= 2:
        r0, r1, e0, e1, x0, x1 = _exchange(r0, r1, e0, e1, x0, x1)
    if n == 3:
        r1, r2, e1, e2, x1, x2 = _exchange(r1, r2, e1, e2, x1, x2)
        r0, r1, e0, e1, x0, x1 = _exchange(r0, r1, e0, e1, x0, x1)
    scale2 = _mod2(r0)
    if n >= 2:
        scale2 = max(scale2, _mod2(r1))
    if n == 3:
        scale2 = max(scale2, _mod2(r2))
    floor = 16.0 * roots.UNIT_ROUNDOFF * math.sqrt(scale2)
    # every decision first, then the writes, then the flag by arithmetic (no branch on data)
    nt0, grows = _mode(r0, e0, x0, floor)
    anyneutral = nt0
    nt1 = nt2 = False
    if n >= 2:
        nt1, g1 = _mode(r1, e1, x1, floor)
        anyneutral = anyneutral | nt1
        grows = grows | g1
    if n == 3:
        nt2, g2 = _mode(r2, e2, x2, floor)
        anyneutral = anyneutral | nt2
        grows = grows | g2
    ev[i][0] = r0
    bd[i][0] = e0
    neutral[i][0] = nt0
    if n >= 2:
        ev[i][1] = r1
        bd[i][1] = e1
        neutral[i][1] = nt1
    if n == 3:
        ev[i][2] = r2
        bd[i][2] = e2
        neutral[i][2] = nt2
    # _UNSTABLE if any mode grows, else _MARGINAL if any is neutral, else _STABLE
    return max(_UNSTABLE * int(grows), _MARGINAL * int(anyneutral))


@register_jitable
def _mark_outside(n, ev, bd, neutral):
    for j in range(n):
        ev[j] = complex(math.nan, math.nan)
        bd[j] = math.nan
        neutral[j] = False


# --- the domain test, compiled from the domain table of stability.parameters ------------------


@register_jitable
def _refused(x, lo, hi):
    """``x`` is not finite or outside the computable range ``lo <= |x| <= hi`` (``|x| < lo``
    counts only for ``x > 0``), as :func:`stability.parameters.check_domain` refuses it.
    ``hi`` is finite (:func:`_computable_limits` puts the largest float for no bound), so
    ``not |x| <= hi`` also refuses NaN and inf; no branches (``&``, ``|``, not ``and``, ``or``)."""
    m = abs(x)
    return (not m <= hi) | ((m < lo) & (x > 0))


@register_jitable
def _any_refused(q, fr_inv, sigma, alpha_v, mu, lim):
    """Whether a parameter is not finite or outside the computable range ``lim`` (:func:`_refused`
    of each; ``|``, no short circuit, so a loop over a block is packed)."""
    return (
        _refused(q, lim[0], lim[1])
        | _refused(fr_inv, lim[2], lim[3])
        | _refused(sigma, lim[4], lim[5])
        | _refused(alpha_v, lim[6], lim[7])
        | _refused(mu, lim[8], lim[9])
    )


@register_jitable
def _domain_code(q, fr_inv, sigma, alpha_v, mu, lim, applies):
    """Where a point lies: ``_INSIDE``, ``_OUTSIDE_DOMAIN`` (a bound of
    :data:`stability.parameters.DOMAIN` whose ``applies[k]`` is true is violated) or
    ``_NOT_FINITE`` (a parameter not finite or outside the computable range ``lim``, the pairs
    ``lo, hi`` for q, fr_inv, sigma, alpha_v, mu, a tuple of 10 floats, ``hi`` finite: refused
    whatever the mask). The bounds are :func:`stability.parameters.inside_domain` on
    :func:`stability.parameters.domain_sides_quick` (the signs of ``domain_sides``, the source
    of ``check_domain``'s numpy test, decided cheaply where a plain comparison suffices)
    (NaN fails). Every test is evaluated (``|``, no short circuit): the point is inside nearly
    always, and the branches cost more."""
    bad = _any_refused(q, fr_inv, sigma, alpha_v, mu, lim)
    out = not inside_domain(domain_sides_quick(q, fr_inv, sigma, alpha_v, mu, 0.0), applies)
    return _NOT_FINITE if bad else (_OUTSIDE_DOMAIN if out else _INSIDE)


@register_jitable
def _domain_clear(q, fr_inv, sigma, alpha_v, mu, lim, applies):
    """``_INSIDE`` where plain comparisons alone show that :func:`_domain_code` gives
    ``_INSIDE`` (:func:`_refused` of no parameter and
    :func:`stability.parameters.domain_clearly_inside`, which proves the exact rule's answer),
    ``_UNDECIDED`` elsewhere. No branch on data, so a loop over a block is packed; the points
    left undecided (near a bound, outside, not finite) go to :func:`_domain_code`."""
    bad = _any_refused(q, fr_inv, sigma, alpha_v, mu, lim)
    clear = domain_clearly_inside(q, fr_inv, sigma, alpha_v, mu, 0.0, applies) & (not bad)
    return _INSIDE if clear else _UNDECIDED


def _coefficient_loop(c, n, inside, polish, ev, bd, neutral, stab):
    """The spectrum of the polynomials ``c[i]`` (``n + 1`` complex coefficients, highest power
    first) at the points ``inside`` (the others: NaN, flag -1)."""
    for i in prange(len(stab)):
        ci = c[i]
        sol = _UNSOLVED
        if inside[i] and n == 3:
            sol = _solve(ci[0], ci[1], ci[2], ci[3], 3, polish)
        elif inside[i] and n == 2:
            sol = _solve(ci[0], ci[1], ci[2], 0j, 2, polish)
        elif inside[i]:
            sol = _solve_linear(ci[0], ci[1])
        _finish(n, inside[i], sol, ev, bd, neutral, stab, i)


# --- the loops of a model that offers its coefficients as a formula ---------------------------


@register_jitable
def _solve_parts(parts, polish):
    """:func:`_solve` (:func:`_solve_linear` for degree 1) on the coefficients of a model's
    ``point_coefficients``: ``(re, im)`` pairs, highest power first, degree
    ``len(parts) / 2 - 1`` from 1 to 3 (numba prunes the other branches at compile time)."""
    c3, c2 = complex(parts[0], parts[1]), complex(parts[2], parts[3])
    if len(parts) == 8:
        return _solve(c3, c2, complex(parts[4], parts[5]), complex(parts[6], parts[7]), 3, polish)
    if len(parts) == 6:
        return _solve(c3, c2, complex(parts[4], parts[5]), 0j, 2, polish)
    return _solve_linear(c3, c2)


#: what a model's loop holds for a point it does not solve (:func:`_solve`'s layout)
_UNSOLVED = (0j, 0j, 0j, 0.0, 0.0, 0.0, False, False, False)


@register_jitable(inline="always")
def _finish(n, ok, sol, ev, bd, neutral, stab, i):
    """Point ``i`` of a model's loop: its roots ``sol`` (:func:`_solve`'s layout) sorted and
    decided (:func:`_decide`) where ``ok``, else NaN and flag -1. Compiled into the loop's
    body, once (two inlined copies of :func:`_decide` in one loop make numba warn)."""
    r0, r1, r2, e0, e1, e2, x0, x1, x2 = sol
    if ok:
        stab[i] = _decide(n, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev, bd, neutral, i)
    else:
        _mark_outside(n, ev[i], bd[i], neutral[i])
        stab[i] = _OUTSIDE


# --- the model loops' blocks: the generic cubic, point by point in structure-of-arrays ---------
#
# The model loops solve their points in blocks of :data:`BLOCK`: the coefficients of a block are
# written to a scratch array, one row per quantity (structure of arrays), and the generic cubic
# (step 4 with one sweep passing its test, step 5) is formed by loops over the block with no
# branch on data (selects), which the compiler turns into packed (SIMD) arithmetic. The loops
# call the cores of the point-by-point path (:func:`_depressed`, :func:`_larger`, :func:`_turn`,
# :func:`_untwist`, :func:`_three_roots`, :func:`_separated`, :func:`_weierstrass`,
# :func:`_bound_terms`): the same operations in the same order, so the same bits (IEEE
# arithmetic gives the same result packed or scalar, nothing contracted). A point that leaves
# the generic case anywhere (a complex leading coefficient, a structural zero, a modulus outside
# the range of its plain formula, widely separated scales, a root not finite, a second sweep
# wanted, the bound of a nearly double root) is marked and solved again by :func:`_solve`; the
# cube root of the modulus (the C library's ``cbrt``, a call) is a scalar loop of its own. The
# interpreted execution solves every point by :func:`_solve` (:func:`_compiled`).

#: points per block of the model loops
BLOCK = 256
# rows of a block's scratch array: the coefficients (re, im; highest power first), Cardano's
# intermediates, the roots (re, im) and their error bounds
_C3R, _C3I, _C2R, _C2I, _C1R, _C1I, _C0R, _C0I = 0, 1, 2, 3, 4, 5, 6, 7
_A3R, _A3I, _P3R, _P3I, _ZR, _ZI, _TR, _TI, _RW = 8, 9, 10, 11, 12, 13, 14, 15, 16
_R0R, _R0I, _R1R, _R1I, _R2R, _R2I, _E0, _E1, _E2 = 17, 18, 19, 20, 21, 22, 23, 24, 25
_ROWS = 26


def _compiled():
    """Whether the caller runs compiled: False here, True in numba (the overload below), so that
    the model loops' source takes the blocks only where they are packed."""
    return False


@overload(_compiled, jit_options=OPTIONS)
def _compiled_overload():
    return lambda: True


@register_jitable
def _plain(s):
    """The square of a modulus lies where :func:`stability.linear.roots.modulus` takes its
    plain formula ``sqrt(s)``."""
    return (s > 1e-290) & (s < 1e290)


@register_jitable
def _store_parts(parts, w, j):
    """Column ``j`` of a block's scratch ``w``: a cubic's coefficient ``parts`` (nothing for a
    lower degree, which the blocks do not solve)."""
    if len(parts) == 8:
        for k in range(8):
            w[k, j] = parts[k]


@register_jitable
def _block_start(w, rare, count):
    """:func:`_cardano` up to the cube root of the modulus (:func:`_turn`), for the ``count``
    points of a block; ``rare[j]`` where point ``j`` leaves the generic case."""
    for j in range(count):
        inv = 1.0 / w[_C3R, j]
        c0 = complex(w[_C0R, j], w[_C0I, j])
        a3, P3, Q2, disc = _depressed(
            _scale(complex(w[_C2R, j], w[_C2I, j]), inv), _scale(complex(w[_C1R, j], w[_C1I, j]), inv), _scale(c0, inv)
        )
        s = _mod2(disc)
        x = _larger(Q2, csqrt_nonzero(disc, math.sqrt(s)))
        r2 = _mod2(x)
        w[_ZR, j], w[_ZI, j], w[_TR, j], w[_TI, j] = _turn(x, math.sqrt(r2))
        w[_RW, j] = math.sqrt(r2)
        w[_A3R, j], w[_A3I, j], w[_P3R, j], w[_P3I, j] = a3.real, a3.imag, P3.real, P3.imag
        rare[j] = (w[_C3I, j] != 0) | (c0 == 0) | (not (_plain(s) & _plain(r2)))


@register_jitable
def _block_cbrt(w, count):
    """The cube roots of the moduli (:func:`stability.linear.roots.cbrt`), a scalar loop."""
    for j in range(count):
        w[_RW, j] = cbrt(w[_RW, j])


@register_jitable
def _block_roots(w, rare, count):
    """The rest of :func:`_cardano` for the points of a block, and the tests of :func:`_cubic`
    before its sweeps (scales not widely separated, roots finite: else ``rare``)."""
    for j in range(count):
        u = _untwist(w[_RW, j], w[_ZR, j], w[_ZI, j], w[_TR, j], w[_TI, j])
        n2 = _mod2(u)
        v = -complex(w[_P3R, j], w[_P3I, j]) * u.conjugate() * (1.0 / n2)
        r0, r1, r2 = _three_roots(u, v, complex(w[_A3R, j], w[_A3I, j]))
        finite = _finite(r0) & _finite(r1) & _finite(r2)
        rare[j] = rare[j] | (not _plain(n2)) | _separated(r0, r1, r2)[0] | (not finite)
        _store_roots(w, j, r0, r1, r2)


@register_jitable
def _block_sweep(w, rare, count, more):
    """One Weierstrass sweep of :func:`_cubic` for the points of a block; ``rare`` where it
    does not pass the test and ``more`` sweeps are allowed."""
    for j in range(count):
        c3, c2, c1, c0 = _block_coefficients(w, j)
        r0, r1, r2 = _block_roots_of(w, j)
        r0, e0 = _weierstrass(c3, c2, c1, c0, r0, r1, r2)
        r1, e1 = _weierstrass(c3, c2, c1, c0, r1, r0, r2)
        r2, e2 = _weierstrass(c3, c2, c1, c0, r2, r0, r1)
        _store_roots(w, j, r0, r1, r2)
        rare[j] = rare[j] | (more & (not ((e0 <= 0) & (e1 <= 0) & (e2 <= 0))))


@register_jitable
def _block_bounds(w, rare, count):
    """The error bounds of :func:`_solve` for the roots of a block where they are
    ``dp / |p'|`` (:func:`_bound_terms`; else ``rare``, as where a modulus leaves its plain
    formula)."""
    for j in range(count):
        c3, c2, c1, c0 = _block_coefficients(w, j)
        s3, s2, s1, s0 = _mod2(c3), _mod2(c2), _mod2(c1), _mod2(c0)
        m3, m2, m1, m0 = math.sqrt(s3), math.sqrt(s2), math.sqrt(s1), math.sqrt(s0)
        plain = _plain(s3) & _plain(s2) & _plain(s1) & _plain(s0)
        rs = _block_roots_of(w, j)
        for k in range(3):
            s = _mod2(rs[k])
            dp, n1, _, second = _bound_terms(c3, c2, c1, m3, m2, m1, m0, 3, rs[k], math.sqrt(s))
            w[_E0 + k, j] = dp / math.sqrt(n1)
            plain = plain & _plain(s) & (not second)
        rare[j] = rare[j] | (not plain)


@register_jitable
def _block_coefficients(w, j):
    """The coefficients of point ``j`` of a block (complex, highest power first)."""
    return (
        complex(w[_C3R, j], w[_C3I, j]),
        complex(w[_C2R, j], w[_C2I, j]),
        complex(w[_C1R, j], w[_C1I, j]),
        complex(w[_C0R, j], w[_C0I, j]),
    )


@register_jitable
def _block_roots_of(w, j):
    """The roots of point ``j`` of a block."""
    return complex(w[_R0R, j], w[_R0I, j]), complex(w[_R1R, j], w[_R1I, j]), complex(w[_R2R, j], w[_R2I, j])


@register_jitable
def _store_roots(w, j, r0, r1, r2):
    w[_R0R, j], w[_R0I, j] = r0.real, r0.imag
    w[_R1R, j], w[_R1I, j] = r1.real, r1.imag
    w[_R2R, j], w[_R2I, j] = r2.real, r2.imag


@register_jitable
def _block_solve(w, rare, count, polish):
    """The generic cubics of a block: :func:`_block_start`, :func:`_block_cbrt`,
    :func:`_block_roots`, :func:`_block_sweep` (when ``polish > 0``), :func:`_block_bounds`."""
    _block_start(w, rare, count)
    _block_cbrt(w, count)
    _block_roots(w, rare, count)
    if polish > 0:
        _block_sweep(w, rare, count, polish > 1)
    _block_bounds(w, rare, count)


@register_jitable
def _block_decide(w, count, lo, ev, bd, neutral, stab):
    """:func:`_decide` of the block's points (the block's first point is ``lo``), written to
    the outputs; a point that is rare or outside is then written again by its loop."""
    for j in range(count):
        r0, r1, r2 = _block_roots_of(w, j)
        stab[lo + j] = _decide(
            3, r0, r1, r2, w[_E0, j], w[_E1, j], w[_E2, j], False, False, False, ev, bd, neutral, lo + j
        )


class _Kernels(NamedTuple):
    """The loops of one model (:func:`_compile`), plain functions (:func:`stability.jit.cached`
    compiles them, serial or parallel)."""

    checked: Callable[..., None]
    masked: Callable[..., None]
    n: int


@functools.cache
def _compile(formula: Callable[..., tuple], n: int, applies: tuple[bool, ...]) -> _Kernels:
    """The loops for the coefficient formula ``formula`` (a model's ``point_coefficients``, of
    degree ``n``) and the domain bounds ``applies`` (:func:`stability.parameters.domain_applies`).

    Closures over ``formula``, ``n`` and ``applies``, run interpreted or compiled
    (:func:`stability.jit.cached`, nothing is compiled here) with ``cache=True``: numba keys a
    closure's disk cache by its captured values, pickled (the formula by reference), so each
    model's loops are compiled once per machine. The loops call the kernel's helpers as globals
    (never captured: a captured ``njit`` dispatcher pickles differently in every process, and
    the cache would never be found again; tests/test_one_home.py checks the keys), and write
    the point's work out in the loop body rather than in a local helper function (an inlined
    local ``register_jitable`` helper compiled half as fast again).
    """

    def checked(q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, lim, polish, ev, bd, neutral, stab, where):
        """The domain test and the spectrum in one pass; ``where`` (int8) gets the code of
        :func:`_domain_code` per point (compiled: :func:`_domain_clear` over the block, packed,
        and ``_domain_code`` only for the points it leaves undecided; the same codes).
        Each parameter is a 1-D array read at ``i * stride`` (stride 1: one value per point; 0: a
        scalar), so scalars are not broadcast in memory. (No reduction variables, which slowed
        the loop by ~15%: the driver counts. The limits come as a tuple: an array handed to the
        domain test per point is passed and reference-counted at every call.)"""
        npts = len(stab)
        blocks = _compiled() and n == 3
        for b in prange((npts + BLOCK - 1) // BLOCK):  # blocks of points (_block_solve)
            lo = b * BLOCK
            count = min(BLOCK, npts - lo)
            w = np.empty((_ROWS, count if blocks else 0))
            rare = np.empty(count if blocks else 0, dtype=np.bool_)
            p = np.empty((5, count if blocks else 0))  # the block's parameters, contiguous
            if blocks:  # the domain test of the easy majority, in a loop the compiler packs
                for j in range(count):
                    i = lo + j
                    p[0, j], p[1, j], p[2, j] = q[i * sq], fr_inv[i * sf], sigma[i * ss]
                    p[3, j], p[4, j] = alpha_v[i * sa], mu[i * sm]
                for j in range(count):
                    where[lo + j] = _domain_clear(p[0, j], p[1, j], p[2, j], p[3, j], p[4, j], lim, applies)
            for i in range(lo, lo + count):  # the exact test for the others (all points when interpreted)
                if not (blocks and where[i] == _INSIDE):
                    where[i] = _domain_code(
                        q[i * sq], fr_inv[i * sf], sigma[i * ss], alpha_v[i * sa], mu[i * sm], lim, applies
                    )
            if blocks:  # the coefficients in a loop of their own, which the compiler packs
                for j in range(count):
                    _store_parts(formula(p[0, j], p[1, j], p[2, j], p[3, j], p[4, j]), w, j)
                _block_solve(w, rare, count, polish)
                _block_decide(w, count, lo, ev, bd, neutral, stab)
            for i in range(lo, lo + count):  # the points the blocks did not solve
                ok = where[i] == _INSIDE
                if not (blocks and ok and not rare[i - lo]):
                    sol = _UNSOLVED
                    if ok:
                        parts = formula(q[i * sq], fr_inv[i * sf], sigma[i * ss], alpha_v[i * sa], mu[i * sm])
                        sol = _solve_parts(parts, polish)
                    _finish(n, ok, sol, ev, bd, neutral, stab, i)

    def masked(q, sq, fr_inv, sf, sigma, ss, alpha_v, sa, mu, sm, inside, polish, ev, bd, neutral, stab):
        """The spectrum at the points ``inside`` (the others: NaN, flag -1), no domain test. (Not
        ``checked`` with the mask as its codes: the gathering of the block's parameters, which
        the domain test wants, made this loop 2 % slower; its last loop is ``checked``'s.)"""
        npts = len(stab)
        blocks = _compiled() and n == 3
        for b in prange((npts + BLOCK - 1) // BLOCK):  # blocks of points, as in ``checked``
            lo = b * BLOCK
            count = min(BLOCK, npts - lo)
            w = np.empty((_ROWS, count if blocks else 0))
            rare = np.empty(count if blocks else 0, dtype=np.bool_)
            if blocks:
                for i in range(lo, lo + count):
                    _store_parts(
                        formula(q[i * sq], fr_inv[i * sf], sigma[i * ss], alpha_v[i * sa], mu[i * sm]), w, i - lo
                    )
                _block_solve(w, rare, count, polish)
                _block_decide(w, count, lo, ev, bd, neutral, stab)
            for i in range(lo, lo + count):  # the points the blocks did not solve
                ok = inside[i]
                if not (blocks and ok and not rare[i - lo]):
                    sol = _UNSOLVED
                    if ok:
                        parts = formula(q[i * sq], fr_inv[i * sf], sigma[i * ss], alpha_v[i * sa], mu[i * sm])
                        sol = _solve_parts(parts, polish)
                    _finish(n, ok, sol, ev, bd, neutral, stab, i)

    return _Kernels(checked, masked, n)


def _model_kernels(model: LinearModel) -> _Kernels | None:
    """The compiled loops of ``model`` if it offers ``point_coefficients`` (the optional
    capability of :mod:`stability.models.base`) and has degree <= :data:`MAX_DEGREE`, else None."""
    formula = getattr(model, "point_coefficients", None)
    if formula is None or not 1 <= model.n_modes <= MAX_DEGREE:
        return None
    return _compile(formula, int(model.n_modes), domain_applies(model.parameters))


def accepts(model: LinearModel) -> bool:
    """Whether the kernel forms ``model``'s coefficients itself (it offers ``point_coefficients``
    of degree <= :data:`MAX_DEGREE`): :func:`model_spectrum` and :func:`checked_model_spectrum`
    apply; any other model goes through :func:`coefficient_spectrum`."""
    return _model_kernels(model) is not None


# --- drivers ----------------------------------------------------------------------------------


def _flat(x: Any, shape: tuple[int, ...]) -> np.ndarray:
    """A mask as a C-contiguous 1-D bool array that owns its data (views from
    ``numpy.broadcast_arrays`` are copied: numba would otherwise warn about their write flag)."""
    y = np.asarray(x, dtype=np.bool_)
    if y.shape == shape and y.flags.c_contiguous and y.base is None:
        return y.reshape(-1)
    return np.array(np.broadcast_to(y, shape), dtype=np.bool_, order="C").reshape(-1)


def _run(
    loop: Callable[..., None],
    shape: tuple[int, ...],
    n: int,
    inputs: list[Any],
    parallel: bool | None,
    engine: str | None,
    *extra: np.ndarray,
) -> KernelSpectrum:
    """``loop`` (:func:`stability.linear.roots.run_loop`) over the points of ``shape`` into new
    outputs for ``n`` modes (and the ``extra`` ones), in the request's shape."""
    npts = math.prod(shape)
    out = (
        np.empty((npts, n), dtype=np.complex128),
        np.empty((npts, n)),
        np.empty((npts, n), dtype=np.bool_),
        np.empty(npts, dtype=np.int8),
    )
    roots.run_loop(loop, npts, parallel, engine, inputs, out + extra)
    return KernelSpectrum(*(a.reshape(shape + a.shape[1:]) for a in out))


def _spectrum(
    model: str | LinearModel,
    params: Mapping[str, Any],
    inside: np.ndarray | bool | None,
    polish: int,
    parallel: bool | None,
    engine: str | None,
) -> tuple[KernelSpectrum, tuple[np.ndarray, ...]]:
    """A model loop of :func:`_compile`: ``checked`` (the domain tested in the same pass) if
    ``inside`` is None, else ``masked`` (the points ``inside`` only); the spectrum and the
    domain codes (flat; none for ``masked``). The loops take the model's five linear parameters
    in :data:`stability.parameters.PARAMETERS` order (the arguments of ``point_coefficients``;
    ``0.0`` for those the model does not take), each a 1-D array and its stride (:func:`_strided`)."""
    m = get_model(model)
    kernels = _model_kernels(m)
    if kernels is None:
        raise InputError(
            f"model {m.name!r} offers no point_coefficients of degree <= {MAX_DEGREE} "
            "(stability.models.base); use coefficient_spectrum on its coefficients"
        )
    values = [params[n] if n in m.parameters else 0.0 for n in PARAMETERS]
    shape = np.broadcast_shapes(*(np.shape(v) for v in values))
    flat = [a for v in values for a in _strided(v, shape)]
    # checked: the domain limits in, the codes out; masked: the mask in
    codes = (np.empty(math.prod(shape), dtype=np.int8),) if inside is None else ()
    loop, given = (kernels.checked, _computable_limits()) if inside is None else (kernels.masked, _flat(inside, shape))
    return _run(loop, shape, kernels.n, [*flat, given, int(polish)], parallel, engine, *codes), codes


def model_spectrum(
    model: str | LinearModel,
    params: Mapping[str, Any],
    inside: np.ndarray | None = None,
    *,
    polish: int = 3,
    parallel: bool | None = None,
    engine: str | None = None,
) -> KernelSpectrum:
    """Sorted eigenvalues, error bounds and the stability decision of a model whose coefficients
    the kernel forms itself (``point_coefficients``), without a domain check.

    Parameters
    ----------
    model : str or LinearModel
        A model that offers ``point_coefficients`` (:mod:`stability.models.base`).
    params : mapping of str to numpy.ndarray
        The model's parameters, broadcast together; not checked against the physical domain
        (:func:`stability.spectrum` does that).
    inside : numpy.ndarray of bool, optional
        Points to compute (the others get NaN and flag -1); default all.
    polish : int, default 3
        Largest number of polishing sweeps; 0 gives Cardano's roots with deflation only.
    parallel : bool, optional
        Run on numba's threads (True) or in this thread (False); default: serially below
        :data:`SERIAL_BELOW` points.
    engine : {"auto", "python", "compiled"}, optional
        The execution (:mod:`stability.execution`); default: the environment variable
        ``TIPPE_KERNEL``, else ``"auto"`` (interpreted below
        :data:`stability.execution.PYTHON_BELOW` points unless the compiled loop is in memory).

    Returns
    -------
    KernelSpectrum
        Shapes ``broadcast + (n_modes,)`` (and ``broadcast`` for the flag).
    """
    return _spectrum(model, params, True if inside is None else inside, polish, parallel, engine)[0]


class CheckedSpectrum(NamedTuple):
    """What :func:`checked_model_spectrum` returns.

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


def _computable_limits() -> tuple[float, ...]:
    """``lo, hi`` magnitudes accepted for q, fr_inv, sigma, alpha_v, mu (10 floats), read from
    :data:`stability.parameters.COMPUTABLE_RANGE` at each call (passed to the kernel as data, so
    a change there is never hidden by numba's cache); ``0`` and the largest float where it names
    none (an upper bound is always finite: :func:`_refused` refuses NaN and inf by it)."""
    from .. import parameters

    ranges = [parameters.COMPUTABLE_RANGE.get(k, (0.0, math.inf)) for k in PARAMETERS]
    return tuple(x for lo, hi in ranges for x in (float(lo), float(min(hi, np.finfo(np.float64).max))))


def _strided(x: Any, shape: tuple[int, ...]) -> tuple[np.ndarray, int]:
    """A 1-D float64 array and the stride to read it with: the data itself (stride 1) when it
    already has the full shape and is C-contiguous, its one value (stride 0) for a single
    value, else a broadcast copy."""
    y = np.asarray(x, dtype=np.float64)
    if y.size == 1:
        return y.reshape(1), 0
    if y.shape == shape and y.flags.c_contiguous:
        return y.reshape(-1), 1
    return np.ascontiguousarray(np.broadcast_to(y, shape)).reshape(-1), 1


def checked_model_spectrum(
    model: str | LinearModel,
    params: Mapping[str, Any],
    *,
    polish: int = 3,
    parallel: bool | None = None,
    engine: str | None = None,
) -> CheckedSpectrum:
    """A model's spectrum with the physical domain tested in the same pass.

    The domain test is :func:`stability.parameters.check_domain`'s, point by point (the table
    :data:`stability.parameters.DOMAIN` compiled: the same decisions, the two bounds through
    ``A_G`` decided exactly for the doubles given by
    :func:`~stability.parameters.domain_sides_quick`; ``tests/test_kernel.py`` checks that they
    agree on and a few ulps around every bound): ``mu > 0``, ``fr_inv >= 0``, ``alpha_v >= 0``,
    ``1 - mu q^2 > 0``, ``0 < sigma <= 2 (1 - mu q^2)`` exactly, with no slack (those of the
    model's parameters), and every
    parameter finite and in the computable range (:data:`stability.parameters.COMPUTABLE_RANGE`).
    The kernel only reports; raising (with the canonical message) is left to the caller, which
    calls ``check_domain`` when ``n_outside > 0``.

    Parameters
    ----------
    model : str or LinearModel
        A model that offers ``point_coefficients`` (:mod:`stability.models.base`).
    params : mapping of str to numpy.ndarray of float64
        The model's parameters, broadcast together (scalars are read in place, not broadcast
        in memory).
    polish : int, default 3
        Largest number of polishing sweeps (:func:`model_spectrum`).
    parallel, engine : optional
        As in :func:`model_spectrum`.

    Returns
    -------
    CheckedSpectrum
        Shapes ``broadcast + (n_modes,)`` and ``broadcast``.

    Raises
    ------
    ValueError
        If the shapes do not broadcast together.
    """
    spec, (where,) = _spectrum(model, params, None, polish, parallel, engine)
    inside = where == _INSIDE
    n_out = where.size - int(np.count_nonzero(inside))
    n_bad = int(np.count_nonzero(where == _NOT_FINITE)) if n_out else 0
    return CheckedSpectrum(spec, inside.reshape(spec.stability.shape), n_out, n_bad)


def model_domain(model: str | LinearModel, params: Mapping[str, Any], *, engine: str | None = None) -> np.ndarray:
    """The codes of the fused loop's domain test (for tests): 0 inside, 1 outside the physical
    domain, 2 a parameter not finite or outside the computable range (refused even when masked).
    The loop of :func:`checked_model_spectrum`, without polishing.

    Parameters
    ----------
    model : str or LinearModel
        A model that offers ``point_coefficients``.
    params : mapping of str to numpy.ndarray
        The model's parameters, broadcast together.
    engine : {"auto", "python", "compiled"}, optional
        As in :func:`model_spectrum`.

    Returns
    -------
    numpy.ndarray of int8, broadcast shape
    """
    spec, (where,) = _spectrum(model, params, None, 0, None, engine)
    return where.reshape(spec.stability.shape)


def coefficient_spectrum(
    c: np.ndarray,
    inside: np.ndarray | None = None,
    *,
    polish: int = 3,
    parallel: bool | None = None,
    engine: str | None = None,
) -> KernelSpectrum:
    """The kernel on given coefficients ``c`` (..., n+1), highest power first, ``1 <= n <= 3``.

    Parameters
    ----------
    c : numpy.ndarray of complex
        Characteristic polynomials (leading coefficient nonzero).
    inside : numpy.ndarray of bool, optional
        Points to compute (the others get NaN and flag -1); default all.
    polish : int, default 3
        Largest number of polishing sweeps.
    parallel, engine : optional
        As in :func:`model_spectrum`.

    Returns
    -------
    KernelSpectrum
        As :func:`model_spectrum`, with ``n`` modes.
    """
    c = np.asarray(c, dtype=np.complex128)
    n = c.shape[-1] - 1
    if not 1 <= n <= MAX_DEGREE:
        raise InputError(f"the kernel solves degrees 1 to {MAX_DEGREE}, got {n}")
    if np.any(c[..., 0] == 0):
        raise InputError("leading coefficient is zero (singular mass matrix)")
    shape = c.shape[:-1]
    flat = np.ascontiguousarray(c.reshape(-1, n + 1))
    ins = _flat(True if inside is None else inside, shape)
    return _run(_coefficient_loop, shape, n, [flat, n, ins, int(polish)], parallel, engine)
