"""Closed forms of the steady states of the sliding top: the one home of D, P, lambda, J, E.

Derivation: docs/steady_states.md (equations S1-S8 there). Units and conventions are the
package's (docs/conventions.md): length R, time ``1/Omega``, inertia A0, energy
``A0 Omega^2``, Jellett's integral ``A0 Omega`` (simulate's units); ``G = O + q k``,
``A_G = 1 - mu q^2``; fixed frame with ``K`` up. Write ``c = cos(theta) = k . K`` (``theta``
the tilt, the polar angle of the axis ``k``), ``s = sin(theta)`` and ``a = sigma - A_G``.

A *steady state* is a relative equilibrium: every vector of the state turns rigidly about
``K`` at the precession rate ``lam``. With friction (``alpha_v > 0``) the contact point does
not slip on it, the centre of mass G is at rest, and (S1-S4)::

    omega = lam (K + q k),      V0 = omega x K,      omega . k = lam (c + q),
    lam^2 P(c) = mu fr_inv q                                                  (S3)
    J = lam D(c),     E = J^2 / (2 D(c)) + mu fr_inv (1 + q c) = U_J(c)        (S4, S5)
    D(c) = sigma (c + q)^2 + A_G (1 - c^2) = (K + q k) . I_G (K + q k),   P = D'/2 = a c + sigma q.

The vertical states ``k = +-K`` (spin ``n``, ``omega = n K``) are steady for every ``n``; in
these variables the upright spin is ``c = 1, lam = n / (1 + q)`` and the inverted one
``c = -1, lam = n / (1 - q)``; their Jellett integral is ``J = sigma n (1 + q c)``
(:func:`vertical_jellett`), and their spectrum is eq. (11)'s at the *equivalent point*
``(q c, fr_inv / n^2, alpha_v / |n|)`` times ``|n|`` (:func:`equivalent_point`).

``U_J(c) = J^2 / (2 D(c)) + mu fr_inv (1 + q c)`` is a lower bound of the energy of every
state with Jellett integral ``J`` and axis height ``c``, reached exactly at the steady states,
which are the critical points of ``U_J`` on ``(-1, 1)`` plus the two ends (S6-S7). Hence

* the tilted states of a level ``J``: roots of the quartic
  ``Q(c) = mu fr_inv q D(c)^2 - J^2 P(c)`` where ``q P(c) > 0`` (:func:`tilted_roots`,
  :func:`level_states`);
* the family against ``J``: ``J(c)^2 = mu fr_inv q D(c)^2 / P(c)``; it runs to ``J = inf``
  at ``c0 = sigma q / (A_G - sigma)`` (the root of ``P``) and meets the vertical states at
  the branch points ``J_up``, ``J_inv`` (:func:`branch_point_jellett`), which are eq. (11)'s
  neutral curves at the equivalent spin;
* folds of ``J(c)`` at ``c0 +- sqrt(D(c0) / (3 a))`` (``a > 0`` only; :func:`fold_cosines`);
* the energy criterion of stability (S8): a strict minimum of ``U_J`` is stable, a maximum
  unstable (:func:`energy_test`);
* every steady state of a level at once, in one compiled call (:func:`level_states`: what
  :func:`stability.final_state` and :func:`stability.steady_states` use).

One source, three engines (as :mod:`stability.models.inertia`): the formulas are plain
arithmetic registered with :func:`numba.extending.register_jitable`. Called from Python they
run as written, on floats or numpy arrays (broadcast); called from ``@njit`` code
(:func:`level_states`, :func:`state_core`) they are compiled into the caller. ``A_G`` is
:func:`stability.models.inertia.inertia_g` (compensated) everywhere. Their arguments are
positional or keyword (numba does not take keyword-only arguments); call them with keywords.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.jit import njit, register_jitable

from ..execution import pick
from ..models.inertia import inertia_g, transverse_inertia_g

#: the two vertical states: name -> cos(theta)
ORIENTATIONS: dict[str, float] = {"upright": 1.0, "inverted": -1.0}


def a_g(q: Any, mu: Any) -> Any:
    """Transverse moment about G, ``A_G = 1 - mu q^2`` (units A0), by
    :func:`stability.models.inertia.inertia_g` (accurate near the domain edge ``A_G -> 0``);
    numbers give a float, arrays an array."""
    if np.ndim(q) == 0 and np.ndim(mu) == 0:
        return float(inertia_g(float(q), float(mu)))
    return transverse_inertia_g(q, mu)


@register_jitable
def detuning(q, sigma, mu):
    """``a = sigma - A_G``: the family has a fold only where ``a > 0``."""
    return sigma - inertia_g(q, mu)


@register_jitable
def d_of_c(c, q, sigma, mu):
    """``D(c) = (K + q k) . I_G (K + q k) = sigma (c + q)^2 + A_G (1 - c^2)`` (S4).

    ``D(1) = sigma (1 + q)^2``, ``D(-1) = sigma (1 - q)^2``; ``D > 0`` on ``[-1, 1]`` in the
    physical domain (a squared length times a moment of inertia)."""
    return sigma * ((c + q) * (c + q)) + inertia_g(q, mu) * (1.0 - c * c)


@register_jitable
def p_of_c(c, q, sigma, mu):
    """``P(c) = D'(c) / 2 = (sigma - A_G) c + sigma q`` (S3).

    ``P(1) = sigma (1 + q) - A_G``, ``P(-1) = A_G - sigma (1 - q)``: their signs decide the
    high-spin classes (:mod:`stability.steady.classes`)."""
    return detuning(q, sigma, mu) * c + sigma * q


@register_jitable
def c0_point(q, sigma, mu):
    """``c0 = sigma q / (A_G - sigma)`` of one top (floats; compiled callers): ``+-inf`` (the sign
    of ``sigma q``) at ``sigma = A_G``, NaN at ``q = 0 = sigma - A_G``."""
    den = inertia_g(q, mu) - sigma
    if den == 0.0:
        return math.nan if q == 0.0 else math.copysign(math.inf, sigma * q)
    return sigma * q / den


def c0(q: Any, sigma: Any, mu: Any) -> Any:
    """``c0 = sigma q / (A_G - sigma)``: the root of ``P``, where the family runs to ``J = inf``.

    Also the tilted state of the ``fr_inv = 0`` (high-spin) limit. ``+-inf`` at ``sigma = A_G``
    (no root), NaN at ``q = 0 = sigma - A_G``. Numbers: :func:`c0_point`; arrays: the same
    quotient elementwise (IEEE division gives the same infinities and NaN)."""
    if np.ndim(q) == 0 and np.ndim(sigma) == 0 and np.ndim(mu) == 0:
        return c0_point(float(q), float(sigma), float(mu))
    q = np.asarray(q, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return sigma * q / (a_g(q, mu) - sigma)


def sigma_of_c0(c: Any, q: Any, mu: Any) -> Any:
    """The ``sigma`` at which ``c`` is the root ``c0`` of ``P``: ``P(c) = 0 <=> sigma = A_G c / (c + q)``.

    At ``c = 1``, ``A_G / (1 + q)``; at ``c = -1``, ``A_G / (1 - q)``: the boundaries of the
    high-spin classes (:func:`stability.steady.classes.class_boundaries`)."""
    return a_g(q, mu) * c / (c + q)


def precession_rate(c: Any, *, q: Any, sigma: Any, fr_inv: Any, mu: Any, sign: float = 1.0) -> Any:
    """``lam = sign sqrt(mu fr_inv q / P(c))`` on the tilted family (S3); NaN where ``q P <= 0``."""
    return sign * _root_of_ratio(mu * fr_inv * q, p_of_c(c, q, sigma, mu))


def _root_of_ratio(num: Any, den: Any) -> Any:
    """``sqrt(num / den)`` where the ratio is positive, NaN elsewhere (floats or arrays)."""
    if isinstance(den, float):
        r = num / den if den != 0.0 else math.nan
        return math.sqrt(r) if r > 0 else math.nan
    with np.errstate(divide="ignore", invalid="ignore"):
        r = num / den
    return np.sqrt(np.where(r > 0, r, np.nan))


def jellett_of_c(c: Any, *, q: Any, sigma: Any, fr_inv: Any, mu: Any, sign: float = 1.0) -> Any:
    """``J(c) = lam(c) D(c)``, i.e. ``J^2 = mu fr_inv q D^2 / P`` (S6); NaN off the family."""
    return precession_rate(c, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu, sign=sign) * d_of_c(c, q, sigma, mu)


@register_jitable
def effective_potential(c, jellett, q, sigma, fr_inv, mu):
    """``U_J(c) = J^2 / (2 D(c)) + mu fr_inv (1 + q c)`` (S5): the energy of the steady state at
    ``c`` on the level ``J``, and a lower bound of the energy of every state there."""
    return jellett * jellett / (2.0 * d_of_c(c, q, sigma, mu)) + mu * fr_inv * (1.0 + q * c)


@register_jitable
def axial_spin(c, lam, q):
    """``omega . k = lam (c + q)`` on a steady state (S1)."""
    return lam * (c + q)


@register_jitable
def omega_vertical(c, lam, q):
    """``omega . K = lam (1 + q c)`` on a steady state (S1); the spin ``n`` of a vertical state."""
    return lam * (1.0 + q * c)


@register_jitable
def vertical_jellett(c, spin, q, sigma):
    """``J = sigma n (1 + q c)``: Jellett's integral of the vertical state ``c = +-1`` (upright,
    inverted) with spin ``n`` (``omega = n K``); its spin at a given ``J`` is
    ``J / vertical_jellett(c, 1, q, sigma)``."""
    return sigma * spin * (1.0 + q * c)


def upright_jellett(*, q: Any, sigma: Any) -> Any:
    """Jellett's integral of the upright spin ``omega = K`` (spin 1, the linear atlases' state):
    ``J = sigma (1 + q)``; ``J / upright_jellett`` is the *equivalent upright spin*."""
    return vertical_jellett(1.0, 1.0, q, sigma)


def vertical_spin(orientation: str, jellett: Any, *, q: Any, sigma: Any) -> Any:
    """Spin ``n`` (``omega = n K``) of the upright (``J = sigma n (1 + q)``) or inverted
    (``J = sigma n (1 - q)``) state with Jellett integral ``J`` (:func:`vertical_jellett`)."""
    return jellett / vertical_jellett(ORIENTATIONS[orientation], 1.0, q, sigma)


def equivalent_point(c: Any, spin: Any, *, q: Any, fr_inv: Any, alpha_v: Any) -> tuple[Any, Any, Any]:
    """The point ``(q, fr_inv, alpha_v)`` of eq. (11) whose spectrum, times ``|n|``, is that of the
    vertical state ``c = +-1`` with spin ``n``: ``(q c, fr_inv / n^2, alpha_v / |n|)``.

    Time rescaled by ``|n|`` (eq. (11) is written at spin 1); the inverted top is the upright
    one with ``q -> -q``. docs/steady_states.md, sec. 4.2; the branch points
    (:func:`branch_point_jellett`) are eq. (11)'s neutral curve at this point."""
    return q * c, fr_inv / (spin * spin), alpha_v / abs(spin)


def branch_point_jellett(orientation: str, *, q: Any, sigma: Any, fr_inv: Any, mu: Any) -> Any:
    """``|J|`` at the branch point of the tilted family on a vertical state; NaN if none.

    ``J_up^2 = mu fr_inv q sigma^2 (1 + q)^4 / P(1)``, ``J_inv^2 = mu fr_inv q sigma^2 (1 - q)^4
    / P(-1)``: with ``J = sigma n (1 +- q)`` these are eq. (11)'s neutral curves at the
    equivalent spin ``n`` (``fr_inv -> fr_inv / n^2``; ``q -> -q`` for the inverted top).
    """
    c = ORIENTATIONS[orientation]
    d = d_of_c(c, q, sigma, mu)
    return _root_of_ratio(mu * fr_inv * q * d * d, p_of_c(c, q, sigma, mu))


@register_jitable
def fold_cosines(q, sigma, mu):
    """Cosines ``c0 -+ sqrt(D(c0) / (3 a))`` of the folds of ``J(c)`` (NaN where there is none).

    ``d(J^2)/dc = mu fr_inv q D (4 P^2 - a D) / P^2`` and ``4 P^2 - a D = 3 a^2 (c - c0)^2 -
    a D(c0)``, so ``dJ/dc = 0`` only for ``a > 0`` and ``D(c0) > 0``; the two folds lie on
    either side of ``c0`` and the family on one side only, so a branch has at most one fold.
    The same for every ``fr_inv > 0``. One top (floats; compiled callers).
    """
    a = detuning(q, sigma, mu)
    if a <= 0.0:
        return math.nan, math.nan
    cc = c0_point(q, sigma, mu)
    dc0 = d_of_c(cc, q, sigma, mu)
    if not dc0 > 0.0:
        return math.nan, math.nan
    r = math.sqrt(dc0 / (3.0 * a))
    return cc - r, cc + r


@register_jitable
def level_quartic(c, jellett, q, sigma, fr_inv, mu):
    """``Q(c) = mu fr_inv q D(c)^2 - J^2 P(c)`` (S6) and ``Q'(c) = 4 mu fr_inv q D P - J^2 a``
    (``D' = 2 P``, ``P' = a``): the tilted states of the level ``J`` are its roots where
    ``q P > 0``."""
    d = d_of_c(c, q, sigma, mu)
    p = p_of_c(c, q, sigma, mu)
    k = mu * fr_inv * q
    j2 = jellett * jellett
    return k * d * d - j2 * p, 4.0 * k * d * p - j2 * detuning(q, sigma, mu)


@register_jitable
def _bracketed_root(lo, hi, flo, fhi, jellett, q, sigma, fr_inv, mu):
    """Safeguarded Newton on :func:`level_quartic` in a bracket with ``flo * fhi < 0``, to the
    last bit of ``c``."""
    x = lo - flo * (hi - lo) / (fhi - flo)
    for _ in range(200):
        fx, d = level_quartic(x, jellett, q, sigma, fr_inv, mu)
        if fx == 0.0:
            return x
        if (fx < 0) == (flo < 0):
            lo, flo = x, fx
        else:
            hi, fhi = x, fx
        xn = x - fx / d if d != 0.0 else 0.5 * (lo + hi)
        if not lo < xn < hi:
            xn = 0.5 * (lo + hi)
        if xn == x or hi - lo <= 4.5e-16 * max(1.0, abs(x)):
            return xn
        x = xn
    return x


@register_jitable
def _insert_decreasing(out, n, x):
    """Insert ``x`` into ``out[:n]`` (decreasing, distinct); return the new count."""
    for i in range(n):
        if out[i] == x:
            return n
    i = n
    while i > 0 and out[i - 1] < x:
        out[i] = out[i - 1]
        i -= 1
    out[i] = x
    return n + 1


@register_jitable
def tilted_roots(jellett, q, sigma, fr_inv, mu, out):
    """Cosines of every tilted steady state (``-1 < c < 1``) on the Jellett level ``J``, written
    to ``out`` (length >= 8) in decreasing order (increasing tilt); returns their number.

    Method: the roots of ``Q(c) = mu fr_inv q D(c)^2 - J^2 P(c)`` (S6, :func:`level_quartic`).
    ``[-1, 1]`` is cut at ``c0`` and at the folds (:func:`fold_cosines`); on each piece where
    ``q P > 0`` the function ``J^2(c)`` is monotone, so ``Q`` changes sign at most once there,
    and a safeguarded Newton step on the bracket finds the root to the last bit (``Q`` has no
    pole). ``fr_inv = 0`` or ``q = 0``: the single cosine ``c0`` (sec. 3; ``0`` for ``q = 0``) at
    every ``J != 0``. A level exactly at a fold (a double root) is found only if rounding gives a
    sign change: the state is then marginal (:func:`energy_test`).
    """
    if jellett == 0.0:
        return 0
    if fr_inv == 0.0 or q == 0.0:
        cc = c0_point(q, sigma, mu)  # c0 (0 for q = 0); NaN or inf at sigma = A_G (no tilt or every tilt)
        if -1.0 < cc < 1.0:
            out[0] = cc
            return 1
        return 0
    cuts = np.empty(5)  # decreasing: 1, the cuts inside, -1
    m = _insert_decreasing(cuts, _insert_decreasing(cuts, 0, 1.0), -1.0)
    if detuning(q, sigma, mu) != 0.0:
        f_lo, f_hi = fold_cosines(q, sigma, mu)
        for cut in (c0_point(q, sigma, mu), f_lo, f_hi):
            if -1.0 < cut < 1.0:
                m = _insert_decreasing(cuts, m, cut)
    n = 0
    for i in range(m - 1):
        hi, lo = cuts[i], cuts[i + 1]
        if q * p_of_c(0.5 * (lo + hi), q, sigma, mu) <= 0:
            continue
        flo = level_quartic(lo, jellett, q, sigma, fr_inv, mu)[0]
        fhi = level_quartic(hi, jellett, q, sigma, fr_inv, mu)[0]
        if flo == 0.0 and lo > -1.0:
            n = _insert_decreasing(out, n, lo)
        if flo * fhi < 0:
            r = _bracketed_root(lo, hi, flo, fhi, jellett, q, sigma, fr_inv, mu)
            if -1.0 < r < 1.0:
                n = _insert_decreasing(out, n, r)
    return n


@register_jitable
def energy_test_at(c, vertical, jellett, q, sigma, fr_inv, mu):
    """The energy criterion of stability (S8) at ``c``: a signed test and its scale.

    Vertical state (``c = +-1``): ``c (J^2 P / D^2 - mu fr_inv q)``, i.e. ``-U_J'(1)`` upright
    (``n^2 (sigma (1 + q) - A_G) - mu fr_inv q (1 + q)^2`` up to a positive factor: eq. (11)'s
    neutral curve, stable side positive) and ``U_J'(-1)`` inverted (the same with ``q -> -q``).
    Tilted: ``U_J'' = J^2 (4 P^2 - a D) / D^3``. Positive means a strict minimum of ``U_J``
    (stable with friction), negative a maximum (unstable). The scale is the size of the terms
    the test is made of (for a relative tolerance).
    """
    d = d_of_c(c, q, sigma, mu)
    p = p_of_c(c, q, sigma, mu)
    j2 = jellett * jellett
    if vertical:
        return c * (j2 * p / (d * d) - mu * fr_inv * q), j2 * abs(p) / (d * d) + mu * fr_inv * abs(q)
    a = detuning(q, sigma, mu)
    return j2 * (4.0 * p * p - a * d) / (d * d * d), j2 * (4.0 * p * p + abs(a) * d) / (d * d * d)


def energy_test(
    kind: str, c: float, jellett: float, *, q: float, sigma: float, fr_inv: float, mu: float
) -> tuple[float, float]:
    """The energy criterion of stability (S8) of a state of ``kind`` ("upright", "inverted",
    "tilted"; the vertical ones at ``c = +-1``): :func:`energy_test_at`.

    Returns
    -------
    test : float
        Positive at a strict minimum of ``U_J`` (stable with friction), negative at a maximum.
    scale : float
        The size of the terms the test is made of (for a relative tolerance).
    """
    vertical = kind != "tilted"
    return energy_test_at(ORIENTATIONS[kind] if vertical else c, vertical, jellett, q, sigma, fr_inv, mu)


@njit(cache=True)
def level_states(jellett, q, sigma, fr_inv, mu):
    """Every steady state of the Jellett level ``J``, in one compiled call.

    Rows: the upright state, each tilted state (:func:`tilted_roots`, increasing tilt), the
    inverted state. Columns: ``c``, its energy ``U_J(c)``
    (:func:`effective_potential`), the energy criterion and its scale (:func:`energy_test_at`),
    the precession rate ``J / D(c)`` (NaN for the vertical states) and the axial spin
    ``omega . k`` (vertical: ``c n``, ``n = J / (sigma (1 + q c))``).

    Parameters
    ----------
    jellett, q, sigma, fr_inv, mu : float
        Checked by the caller (no input checks here).

    Returns
    -------
    numpy.ndarray, shape (n_tilted + 2, 6)
    """
    roots = np.empty(8)
    n = tilted_roots(jellett, q, sigma, fr_inv, mu, roots)
    out = np.empty((n + 2, 6))
    for i in range(n + 2):
        vertical = i == 0 or i == n + 1
        c = 1.0 if i == 0 else (-1.0 if i == n + 1 else roots[i - 1])
        test, scale = energy_test_at(c, vertical, jellett, q, sigma, fr_inv, mu)
        if vertical:
            lam = math.nan
            axial = c * (jellett / vertical_jellett(c, 1.0, q, sigma))
        else:
            lam = jellett / d_of_c(c, q, sigma, mu)
            axial = axial_spin(c, lam, q)
        u = effective_potential(c, jellett, q, sigma, fr_inv, mu)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4], out[i, 5] = c, u, test, scale, lam, axial
    return out


@njit(cache=True)
def state_core(theta, lam, q, phi, y):
    """Fill ``y[:8] = (omega, k, V0_h)`` with the steady state at tilt ``theta`` (S1, S2).

    ``k = (sin theta cos phi, sin theta sin phi, cos theta)``, ``omega = lam (K + q k)``,
    ``V0 = omega x K`` (so that the contact point does not slip, ``V0 + K x omega = 0``).
    ``theta`` may be complex (complex-step derivatives); ``y`` real or complex of length >= 8.
    """
    s = np.sin(theta)
    k0, k1, k2 = s * np.cos(phi), s * np.sin(phi), np.cos(theta)
    w0, w1, w2 = lam * q * k0, lam * q * k1, lam * (1.0 + q * k2)
    # V0 = omega x K: (omega x K)_1 = omega_2, (omega x K)_2 = -omega_1
    y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7] = w0, w1, w2, k0, k1, k2, w1, -w0


def state_vector(theta: Any, lam: Any, q: float, phi: Any = 0.0) -> np.ndarray:
    """Steady states ``(omega, k, V0_h)`` (shape ``(..., 8)``) at tilts ``theta`` (radians).

    Vertical states: ``theta = 0`` or ``pi`` with ``lam = n / (1 +- q)`` gives ``omega = n K``.
    """
    theta, lam, phi = np.broadcast_arrays(np.asarray(theta, float), np.asarray(lam, float), np.asarray(phi, float))
    out = np.empty(theta.shape + (8,))
    flat = out.reshape(-1, 8)
    core = pick(state_core, flat.shape[0])  # stability.execution's rule
    for i, (t, la, ph) in enumerate(zip(theta.ravel(), lam.ravel(), phi.ravel())):
        core(float(t), float(la), float(q), float(ph), flat[i])
    return out


def vertical_state(orientation: str, spin: float) -> np.ndarray:
    """The vertical state ``omega = n K``, ``k = +-K``, ``V0 = 0`` as ``(omega, k, V0_h)`` (8,)."""
    y = np.zeros(8)
    y[2] = spin
    y[5] = ORIENTATIONS[orientation]
    return y
