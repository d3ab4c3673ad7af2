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

Building blocks, one home each (used by :func:`polynomial_roots`, the compiled kernel
:mod:`stability.linear.kernel` and the neutral condition :mod:`stability.linear.neutrality`):
:func:`horner_scheme` (``p, p', p''``), :func:`quadratic_roots` (the stable quadratic formula,
general and conservative), :func:`divide_root` (synthetic division by ``s - r``, composite) and
:func:`deflate_cubic_backward` (backward division by the largest root), with :func:`csqrt`,
:func:`modulus` and :func:`cbrt`; on the imaginary axis, :func:`axis_norms` (the scales of the
real and imaginary parts of ``p(i w)``, the neutral condition's rows) and :func:`axis_growth` (the
structured growth estimate of a root near the axis, below). They are plain arithmetic registered
with ``register_jitable`` (:mod:`stability.jit`, which defers numba's registration until
compiled code is wanted): one source that runs on Python numbers, inside numba kernels, and
(:func:`horner_scheme`, whose array front end is :func:`horner`) on numpy arrays; batched numpy
callers of the others run a small loop over them (:func:`quadratic_roots_many`), interpreted or
compiled (:mod:`stability.execution`), with the same bits. On arrays, numpy's complex multiplication may use fused
multiply-adds (AVX2/FMA3 machines), so complex arithmetic on arrays agrees with the scalar and
compiled engines only to rounding; the compiled loops agree with the scalar engine bit for bit.

A posteriori inclusion (:func:`inclusion_radius`), for eigenvalues found by any other method
(the LAPACK path): for a polynomial of degree ``n`` with roots ``z_k``,
``p'(r)/p(r) = sum_k 1/(r - z_k)``, so some root lies within ``n |p(r)| / |p'(r)|`` of ``r``;
and ``|p(r)| = |c_n| prod_k |r - z_k|``, so some root lies within ``(|p(r)| / |c_n|)^(1/n)``.
Both are rigorous once ``|p(r)|`` is bounded above (computed residual plus the rounding of
its evaluation and of the coefficients) and ``|p'(r)|`` below; the smaller radius is returned.
It does not assume that ``r`` is accurate: an eigenvalue wrong by O(1) (``M^-1 A`` formed
from a near-singular ``M``) gets an O(1) radius, and one beside a double root a radius that
follows the ``sqrt(u)`` error there.

Structured growth estimate near the imaginary axis (:func:`axis_growth`). Write
``p(i w) = A(w) + i B(w)`` with the real polynomials ``a_k = Re(c_k i^k)`` and
``b_k = Im(c_k i^k)`` (exact: a product with ``1, i, -1, -i`` only swaps and negates parts).
A Newton step from ``i w`` towards the root, ``delta = -p(i w) / p'(i w)``, has the real part
``(B A' - A B') / (A'^2 + B'^2)`` and the imaginary part ``-(A A' + B B') / (A'^2 + B'^2)`` (by
which ``w`` is first moved, twice, so that the step is nearly real), with ``A, A', B, B'``
(derivatives in ``w``) evaluated by Horner's scheme in real arithmetic, each to its *own*
relative accuracy: ``A`` and ``B`` are never added, so neither is lost in the rounding of the
other. For the sliding model ``p(i w) = alpha_v P_r(w) + i mu w P_f(w)`` (eq. 11): at
``alpha_v = 1e-12`` the real part is ``1e-12`` of the imaginary one and at ``1e12`` ``1e12``
times it, and the eigenvalue's own ``Re s`` (absolute error ``~u |s|`` at best, and the floor
``16 u max|s|`` of the stability flag) cannot resolve a growth rate of ``1e-12 x distance`` from
the crossing, while the estimate resolves its sign down to a relative distance of a few ``u`` at
any ``alpha_v``. A Newton step's own error is second order, ``Re((p''/2p') e0^2)`` with ``e0``
the distance from ``i w`` to the root; ``w`` is a double, so ``e0`` keeps an imaginary part of
up to half an ulp of the frequency, and that term alone (``~1e-32``) would hide growth rates
below it (the sliding top at ``alpha_v < 1e-29``). The estimate is therefore Chebyshev's step,
``g = Re(delta - (p''/2p') delta^2)``, whose error is third order,
``(2 |c2|^2 + |c3|) |e0|^3`` (``c_k = p^(k) / (k! p')``). Its bound ``e_g`` is the rounding of
``A, B`` (``(3 n + 5) u sum_k |a_k| |w|^k``: coefficients formed with relative error
``(n + 4) u``, Horner's ``2 n u``) and of ``A', B'`` carried through the quotient and the
correction, plus that third-order term with ``|e0| <= 2 |delta|``; the estimate is refused
(``e_g = inf``) once ``|c2| |delta| > 1/4``, where a step from the axis says nothing (near a
collision of two roots, where ``p' -> 0``). So ``|g| > 4 e_g`` decides the sign of the growth
rate of the root near ``i w``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.jit import OPTIONS, cached, overload, register_jitable

from .. import execution
from ..errors import InputError

__all__ = [
    "PolynomialRoots",
    "axis_growth",
    "axis_growth_many",
    "axis_norms",
    "cbrt",
    "csqrt",
    "deflate_cubic_backward",
    "divide_root",
    "horner",
    "horner_scheme",
    "inclusion_radius",
    "modulus",
    "neutral_tolerance",
    "polynomial_roots",
    "quadratic_roots",
    "quadratic_roots_many",
    "root_bound",
]

UNIT_ROUNDOFF = 2.0**-53


@register_jitable
def neutral_tolerance(bound, scale):
    """The neutral-mode rule's tolerance (docs/conventions.md), its one home: a root ``s`` with
    error bound ``bound`` (``e``) is neutral when ``|Re s| <= 4 e + 16 u max|s|``, ``scale`` being
    ``max|s|`` over the point's spectrum and ``u = 2**-53``. Floats, numpy arrays (broadcast)
    or compiled code alike."""
    return 4.0 * bound + 16.0 * UNIT_ROUNDOFF * scale


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


@register_jitable
def modulus(z):
    """``|z|``: ``sqrt(re^2 + im^2)`` (within an ulp of ``hypot``, and much faster); where the
    squares would underflow or overflow, the same after scaling both parts by a power of two
    (exact), and ``hypot`` for 0, inf and NaN only. Plain IEEE arithmetic throughout, so the
    interpreter and numba give the same bits: CPython's ``math.hypot`` is an algorithm of its
    own, not the C library's ``hypot`` that numba calls, and the two differ in the last bit on
    about 0.5% of arguments."""
    x, y = z.real, z.imag
    s = x * x + y * y
    if 1e-290 < s < 1e290:
        return math.sqrt(s)
    m = max(abs(x), abs(y))
    if m == 0.0 or not m < math.inf:
        return math.hypot(x, y)  # exact: 0, inf or NaN
    e = math.frexp(m)[1]
    x = math.ldexp(x, -e)
    y = math.ldexp(y, -e)
    return math.ldexp(math.sqrt(x * x + y * y), e)


def cbrt(x):
    """The real cube root of ``x``: the C library's ``cbrt``, from Python (:func:`math.cbrt`)
    and, compiled, through ``numpy.cbrt`` (numba has no ``math.cbrt``; numba's ``numpy.cbrt``
    gives the same bits as ``math.cbrt``, tests/test_one_home.py)."""
    return math.cbrt(x)


@overload(cbrt, jit_options=OPTIONS)
def _cbrt_compiled(x):
    def impl(x):
        return np.cbrt(x)

    return impl


@register_jitable
def csqrt(z):
    """Principal complex square root, without cancellation (a few ulp; in numba faster than
    ``numpy.sqrt``, which calls ``hypot``)."""
    if z.real == 0 and z.imag == 0:
        return complex(0.0, z.imag)
    return csqrt_nonzero(z, modulus(z))


@register_jitable
def csqrt_nonzero(z, m):
    """:func:`csqrt` of ``z != 0`` of modulus ``m`` (no branch on data: compiled loops pack it)."""
    x, y = z.real, z.imag
    t = math.sqrt(0.5 * (abs(x) + m))
    right = x >= 0
    h = (y if right else abs(y)) / (2.0 * t)
    return complex(t, h) if right else complex(h, math.copysign(t, y))


@register_jitable
def horner_scheme(c, s, order=2):
    """``p(s)``, ``p'(s)`` and ``p''(s)`` by Horner's scheme (the one source of every engine).

    Parameters
    ----------
    c : sequence
        Coefficients, highest degree first, indexable as ``c[k]`` with ``len(c)`` of them: a list
        or tuple of numbers, a 1-D array in numba, or for a batch of numpy arrays the
        coefficient axis first (``numpy.moveaxis(c, -1, 0)``; ``c[k]`` broadcasts against ``s``).
    s : number or numpy.ndarray
        Evaluation point(s).
    order : {0, 1, 2}
        The derivatives wanted: those above ``order`` are not evaluated (returned as 0).

    Returns
    -------
    p, dp, ddp
        Value, first and second derivative.
    """
    p = c[0]
    d1 = 0.0
    d2 = 0.0
    for k in range(1, len(c)):
        if order >= 2:
            d2 = d2 * s + 2.0 * d1
        if order >= 1:
            d1 = d1 * s + p
        p = p * s + c[k]
    return p, d1, d2


@register_jitable
def quadratic_roots(a, b, k):
    """Roots of ``a s^2 + b s + k`` and whether their real parts are exactly zero.

    *Conservative* (``p(i nu) = -a nu^2 - Im(b) nu + k`` real: ``a``, ``i b``, ``k`` real): solved
    in ``nu`` in real arithmetic, so a neutral pair has ``Re s = 0`` exactly (flag True); else
    the cancellation-free formula ``r1 = -(b + sgn sqrt(b^2 - 4 a k)) / 2a`` with the sign that
    avoids cancellation, ``r2 = k / (a r1)`` (both 0 if ``b = 0 = k``). Complex arguments
    (Python or numba).
    """
    if a.imag == 0 and b.real == 0 and k.imag == 0:
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
    sq = csqrt(b * b - 4.0 * a * k)
    sgn = 1.0 if (b.conjugate() * sq).real >= 0 else -1.0
    big = -(b + sgn * sq) / 2.0
    if big != 0:
        return big / a, k / big, False
    return 0j, 0j, False


#: compiled batches below this many points run serially unless a caller asks otherwise
SERIAL_BELOW = 512


def run_loop(
    loop: Callable[..., None],
    npts: int,
    parallel: bool | None,
    engine: str | None,
    inputs: list[Any],
    outputs: tuple[np.ndarray, ...],
) -> None:
    """``loop(*inputs, *outputs)`` (a batch loop of this module or of :mod:`stability.linear.kernel`)
    in one execution.

    Compiled (serially as asked by ``parallel``, by default below :data:`SERIAL_BELOW` points: a
    parallel launch costs more than a few points, and much more on a loaded machine) if
    :func:`stability.execution.use_compiled` says so (after the once-per-process notice if it
    must be compiled first); else interpreted, on Python lists (the arrays' ``tolist()``: Python
    floats and complex numbers, the same values; numpy scalars would be slower and complex
    division on them is numpy's, not the one numba copies from CPython), whose results are then
    written into ``outputs`` (every element of which the loops set)."""
    parallel = (npts >= SERIAL_BELOW) if parallel is None else parallel
    if execution.use_compiled(loop, npts, engine, parallel=parallel):
        cached(loop, parallel)(*inputs, *outputs)
        return
    lists = [o.tolist() for o in outputs]
    loop(*(x.tolist() if isinstance(x, np.ndarray) else x for x in inputs), *lists)
    for out, values in zip(outputs, lists):
        out[...] = values


def quadratic_roots_many(a, b, k, roots, exact):
    """:func:`quadratic_roots` over a batch (1-D complex ``a, b, k``) into ``roots`` (m, 2) and
    ``exact`` (m, 2); lists (interpreted) or arrays (compiled by :func:`stability.jit.cached`;
    :func:`_roots_no_trailing_zero` chooses by :func:`stability.execution.use_compiled`)."""
    for i in range(len(a)):
        r1, r2, ex = quadratic_roots(a[i], b[i], k[i])
        roots[i][0] = r1
        roots[i][1] = r2
        exact[i][0] = ex
        exact[i][1] = ex


@register_jitable
def divide_root(c, n, r, out):
    """Synthetic division of ``c[0..n]`` (highest first) by ``(s - r)`` into ``out[0..n-1]``
    (the remainder dropped; ``out`` may be ``c`` itself).

    Composite deflation: the coefficients from the top (forward), except the last, which is
    taken from the bottom, ``-c_n / r`` (backward; ``c_n = -r q_last`` exactly when ``r`` is a
    root). Forward division gives that coefficient an absolute error ``~u max|c_k r^k|``; when
    the quotient has a root much smaller than ``r`` (the sliding top's ``~ i c fr_inv`` as
    ``fr_inv -> 0``, whose real part is ``O(fr_inv^2)``) that error decides the root's sign
    (measured: ``+3.8e-15`` for a true ``-3e-34``, a false double crossing). From the bottom it
    is relative, ``u``. (Lists of Python numbers or numba arrays.)
    """
    prev = c[0]
    out[0] = prev
    for j in range(1, n):
        prev = c[j] + r * prev
        out[j] = prev
    if r != 0 and n >= 2:
        out[n - 1] = -c[n] / r


@register_jitable
def deflate_cubic_backward(c3, c2, c1, c0, r):
    """``(b2, b1, b0)`` with ``c3 s^3 + c2 s^2 + c1 s + c0 = (s - r)(b2 s^2 + b1 s + b0)`` when
    ``r`` is a root, by division from the bottom (``b0 = -c0 / r``, ``b1 = (b0 - c1) / r``,
    ``b2 = (b1 - c2) / r``): stable when ``r`` is the largest root."""
    ib = 1.0 / r
    b0 = -c0 * ib
    b1 = (b0 - c1) * ib
    b2 = (b1 - c2) * ib
    return b2, b1, b0


@register_jitable
def axis_norms(c, ncoef):
    """``(||a||_1, ||b||_1)`` of ``p(i w) = A(w) + i B(w)`` for ``c[0..ncoef-1]`` (highest first):
    ``|Re(c_k i^k)|`` and ``|Im(c_k i^k)|`` summed in a plain loop (each is ``|Re c_k|`` or
    ``|Im c_k|``, exactly). Lists of Python numbers, numba arrays, or numpy arrays with the
    coefficient axis first (``c[k]`` an array)."""
    na = 0.0
    nb = 0.0
    n = ncoef - 1
    for k in range(ncoef):
        ck = c[k]
        a, b = (ck.real, ck.imag) if (n - k) % 2 == 0 else (ck.imag, ck.real)
        na = na + abs(a)
        nb = nb + abs(b)
    return na, nb


@register_jitable
def _horner_step(p, d1, d2, d3, ck, x):
    """One step of Horner's scheme with three derivatives at ``x``: the value and the first
    three derivatives after the next coefficient ``ck`` (each from the previous ones)."""
    return p * x + ck, d1 * x + p, d2 * x + 2.0 * d1, d3 * x + 3.0 * d2


@register_jitable
def _axis_horner(c, ncoef, w):
    """The values and first three derivatives of ``A`` and of ``B`` in ``p(i w) = A(w) + i B(w)``,
    and the scales of their rounding: ``sum_k |a_k| |w|^k`` and its first two derivatives in
    ``|w|`` (and the same for ``b``)."""
    n = ncoef - 1
    A = dA = ddA = dddA = B = dB = ddB = dddB = sa = sda = sdda = sb = sdb = sddb = 0.0
    aw = abs(w)
    for k in range(ncoef):
        ck = c[k]
        # a_k + i b_k = c_k i^(n-k): parts swapped (times i) for odd n - k, negated (times -1)
        # for n - k = 2, 3 mod 4
        ak, bk = (ck.real, ck.imag) if (n - k) % 2 == 0 else (-ck.imag, ck.real)
        if (n - k) % 4 >= 2:
            ak, bk = -ak, -bk
        A, dA, ddA, dddA = _horner_step(A, dA, ddA, dddA, ak, w)
        B, dB, ddB, dddB = _horner_step(B, dB, ddB, dddB, bk, w)
        sa, sda, sdda, _ = _horner_step(sa, sda, sdda, 0.0, abs(ak), aw)
        sb, sdb, sddb, _ = _horner_step(sb, sdb, sddb, 0.0, abs(bk), aw)
    return A, dA, ddA, dddA, B, dB, ddB, dddB, sa, sda, sdda, sb, sdb, sddb


@register_jitable
def _quotient_error(x1, e1, y1, f1, x2, e2, y2, f2, den, value, rel):
    """The error bound of ``value = (x1 y1 +- x2 y2) / den`` (:func:`axis_growth`): the errors
    ``e``, ``f`` of the factors ``x``, ``y`` carried through the products, ``3 u`` of their
    rounding and sum, and ``rel`` relative to the quotient (that of ``den`` and its own)."""
    products = 3.0 * UNIT_ROUNDOFF * (abs(x1 * y1) + abs(x2 * y2))
    return (e1 * abs(y1) + abs(x1) * f1 + e2 * abs(y2) + abs(x2) * f2 + products) / den + abs(value) * rel


@register_jitable
def axis_growth(c, ncoef, w):
    """The structured growth estimate ``g`` of the root of ``c[0..ncoef-1]`` (highest first)
    near ``i w``, and its bound ``e_g`` (module docstring): the real part of Chebyshev's step
    ``delta - (p''/2p') delta^2``, ``delta = -p(i w) / p'(i w)``, with the real and imaginary
    parts of ``p(i w)`` and of its derivatives evaluated separately, after ``w`` is moved twice
    by the imaginary part of ``delta``. ``e_g = inf`` where the step is not informative
    (``p'(i w) = 0``, or a second-order term that is not small). Python numbers or numba (a 1-D
    array ``c``); :func:`axis_growth_many` runs it over a batch."""
    n = ncoef - 1
    for _ in range(2):
        A, dA, ddA, dddA, B, dB, ddB, dddB, sa, sda, sdda, sb, sdb, sddb = _axis_horner(c, ncoef, w)
        den = dA * dA + dB * dB
        if not den > 0.0:
            return 0.0, math.inf
        dw = -(A * dA + B * dB) / den
        if not math.isfinite(dw):
            return 0.0, math.inf
        w = w + dw
    A, dA, ddA, dddA, B, dB, ddB, dddB, sa, sda, sdda, sb, sdb, sddb = _axis_horner(c, ncoef, w)
    den = dA * dA + dB * dB
    if not den > 0.0:
        return 0.0, math.inf
    u = UNIT_ROUNDOFF
    # absolute errors of A, B and their derivatives: coefficients (n + 4) u, Horner 2 n u
    gamma = (3.0 * n + 5.0) * u
    eA = gamma * sa
    eB = gamma * sb
    edA = gamma * sda
    edB = gamma * sdb
    eddA = gamma * sdda
    eddB = gamma * sddb
    eden = 2.0 * (edA * abs(dA) + edB * abs(dB)) / den + 3.0 * u  # relative
    # Newton's step delta = g + i h from i w (p'(i w) = B' - i A')
    g = (B * dA - A * dB) / den
    h = -(A * dA + B * dB) / den
    eg = _quotient_error(B, eB, dA, edA, A, eA, dB, edB, den, g, eden + u)
    eh = _quotient_error(A, eA, dA, edA, B, eB, dB, edB, den, h, eden + u)
    # c2 = p''/(2 p') = cr + i ci, with p''(i w) = -(A'' + i B'')
    cr = -(ddA * dB - ddB * dA) / (2.0 * den)
    ci = -(ddA * dA + ddB * dB) / (2.0 * den)
    ecr = _quotient_error(ddA, eddA, dB, edB, ddB, eddB, dA, edA, 2.0 * den, cr, eden + u)
    eci = _quotient_error(ddA, eddA, dA, edA, ddB, eddB, dB, edB, 2.0 * den, ci, eden + u)
    step = math.sqrt(g * g + h * h) + eg + eh
    c2 = math.sqrt(cr * cr + ci * ci)
    if c2 * step > 0.25:
        return g, math.inf
    # Chebyshev's correction -Re(c2 delta^2), and its error with the real and imaginary parts
    # kept apart: cr and g are small together where the rows' scales differ (module docstring)
    corr = -cr * (g * g - h * h) + 2.0 * ci * g * h
    ecorr = (
        abs(cr) * (2.0 * abs(g) * eg + eg * eg + 2.0 * abs(h) * eh + eh * eh)
        + ecr * abs(g * g - h * h)
        + 2.0 * abs(ci) * (abs(g) * eh + abs(h) * eg + eg * eh)
        + 2.0 * eci * abs(g * h)
        + 4.0 * u * (abs(cr) * (g * g + h * h) + 2.0 * abs(ci * g * h))
    )
    # Chebyshev's third-order error (2 |c2|^2 + |c3|) |e0|^3 with |e0| <= 2 |delta|, c3 = p'''/(6 p')
    c3 = math.sqrt(dddA * dddA + dddB * dddB) / (6.0 * math.sqrt(den))
    third = (2.0 * c2 * c2 + c3) * 8.0 * step * step * step
    est = g + corr
    return est, eg + ecorr + third + u * abs(est)


def axis_growth_many(c, w, g, eg):
    """:func:`axis_growth` over a batch: ``c`` (m, n+1) complex, ``w`` (m, k) into ``g``, ``eg``
    (m, k) (the roots' frequencies ``w[i, j]`` of polynomial ``c[i]``; NaN gives ``e_g = inf``)."""
    ncoef = c.shape[1]
    for i in range(c.shape[0]):
        for j in range(w.shape[1]):
            x = w[i, j]
            if math.isfinite(x):
                g[i, j], eg[i, j] = axis_growth(c[i], ncoef, x)
            else:
                g[i, j] = np.nan
                eg[i, j] = np.inf


def horner(c: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Evaluate ``p``, ``p'`` and ``p''`` at ``s`` by Horner's scheme (:func:`horner_scheme`).

    Parameters
    ----------
    c : numpy.ndarray, shape (..., n+1)
        Coefficients, highest degree first.
    s : numpy.ndarray, shape (...)
        Evaluation points (broadcast against ``c[..., 0]``).

    Returns
    -------
    p, dp, ddp : numpy.ndarray
        Value, first and second derivative.
    """
    return horner_scheme(np.moveaxis(np.asarray(c), -1, 0), s)


def root_bound(c: np.ndarray, r: np.ndarray) -> np.ndarray:
    """The error bound of the module docstring for roots ``r`` (..., m) of the polynomials ``c``
    (..., n+1): ``min(dp / |p'(r)|, sqrt(2 dp / |p''(r)|))``, ``dp = (n + 4) u sum_k |c_k| |r|^k``."""
    c = np.asarray(c, dtype=complex)[..., None, :]
    r = np.asarray(r, dtype=complex)
    deg = c.shape[-1] - 1
    # sum_k |c_k| |r|^k: the scale of rounding errors in p(r)
    dp_scale = (deg + 4) * UNIT_ROUNDOFF * horner_scheme(np.moveaxis(np.abs(c), -1, 0), np.abs(r), 0)[0]
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
    scale, dscale, _ = horner_scheme(np.moveaxis(np.abs(c), -1, 0), np.abs(r), 1)  # sum_k |c_k| |r|^k, d/d|r|
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


def _roots_no_trailing_zero(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roots of polynomials (k, m+1) whose constant term may be anything, m >= 1, and the
    exact-real mask: the quadratic formula (:func:`quadratic_roots` over the batch, compiled or
    interpreted), polished by a Newton step; higher degrees by the companion matrix, polished."""
    m = c.shape[-1] - 1
    exact = np.zeros((len(c), m), dtype=bool)
    if m == 1:
        return (-c[:, 1] / c[:, 0])[:, None], exact
    if m == 2:
        r = np.empty((len(c), 2), dtype=complex)
        run_loop(
            quadratic_roots_many, len(c), False, None, [np.ascontiguousarray(c[:, k]) for k in range(3)], (r, exact)
        )
        return np.where(exact, r, _newton_polish(c, r, iterations=1)), exact
    comp = np.zeros((len(c), m, m), dtype=complex)
    comp[:, 0, :] = -c[:, 1:] / c[:, :1]
    idx = np.arange(m - 1)
    comp[:, idx + 1, idx] = 1.0
    return _newton_polish(c, np.linalg.eigvals(comp)), exact


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
        raise InputError(f"polynomial degree must be >= 1, got {n}")
    if np.any(c[..., 0] == 0):
        raise InputError("leading coefficient is zero (singular mass matrix)")
    flat = c.reshape(-1, n + 1)
    roots = np.zeros((flat.shape[0], n), dtype=complex)
    bound = np.zeros((flat.shape[0], n))
    exact = np.ones((flat.shape[0], n), dtype=bool)  # structural zero roots stay 0, bound 0, exact
    # number of exactly zero trailing coefficients (structural zero roots), at most n
    nz = np.cumprod(flat[:, :0:-1] == 0, axis=1).sum(axis=1)
    for z in np.unique(nz):
        sel = nz == z
        m = n - z
        if m == 0:
            continue
        cm = flat[sel, : m + 1]
        r, ex = _roots_no_trailing_zero(cm)
        roots[sel, :m] = r
        exact[sel, :m] = ex
        bound[sel, :m] = root_bound(cm, r)
    shape = c.shape[:-1] + (n,)
    return PolynomialRoots(roots.reshape(shape), bound.reshape(shape), exact.reshape(shape))
