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
``c = -1, lam = n / (1 - q)``.

``U_J(c) = J^2 / (2 D(c)) + mu fr_inv (1 + q c)`` is a lower bound of the energy of every
state with Jellett integral ``J`` and axis height ``c``, reached exactly at the steady states,
which are the critical points of ``U_J`` on ``(-1, 1)`` plus the two ends (S6-S7). Hence

* the tilted states of a level ``J``: roots of the quartic
  ``Q(c) = mu fr_inv q D(c)^2 - J^2 P(c)`` where ``q P(c) > 0`` (:func:`tilted_cosines`);
* the family against ``J``: ``J(c)^2 = mu fr_inv q D(c)^2 / P(c)``; it runs to ``J = inf``
  at ``c0 = sigma q / (A_G - sigma)`` (the root of ``P``) and meets the vertical states at
  the branch points ``J_up``, ``J_inv`` (:func:`branch_point_jellett`), which are eq. (11)'s
  neutral curves at the equivalent spin;
* folds of ``J(c)`` at ``c0 +- sqrt(D(c0) / (3 a))`` (``a > 0`` only; :func:`fold_cosines`);
* the energy criterion of stability (S8): a strict minimum of ``U_J`` is stable, a maximum
  unstable (:func:`energy_test`).

Every function takes Python floats or numpy arrays (plain arithmetic, broadcast), so that the
final-state prediction runs on floats without array overhead; :func:`state_core` is compiled
(numba) for the branch's residual.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from numba import njit

from ..models.inertia import transverse_inertia_g

__all__ = ["a_g", "detuning", "d_of_c", "p_of_c", "c0", "precession_rate", "jellett_of_c",
           "effective_potential", "potential_slope", "potential_curvature", "axial_spin",
           "branch_point_jellett", "fold_cosines", "family_interval", "tilted_cosines",
           "energy_test", "vertical_spin", "state_vector", "vertical_state", "state_core", "ORIENTATIONS"]

#: the two vertical states: name -> cos(theta)
ORIENTATIONS: dict[str, float] = {"upright": 1.0, "inverted": -1.0}


@functools.lru_cache(maxsize=64)
def _a_g_scalar(q: float, mu: float) -> float:
    return float(transverse_inertia_g(q, mu))


def a_g(q: Any, mu: Any) -> Any:
    """Transverse moment about G, ``A_G = 1 - mu q^2`` (units A0), by
    :func:`stability.models.inertia.transverse_inertia_g` (accurate near the domain edge
    ``A_G -> 0``); numbers give a float (cached: the closed forms ask for it often)."""
    if (isinstance(q, float) and isinstance(mu, float)) or (np.ndim(q) == 0 and np.ndim(mu) == 0):
        return _a_g_scalar(float(q), float(mu))
    return transverse_inertia_g(q, mu)


def detuning(q: Any, sigma: Any, mu: Any) -> Any:
    """``a = sigma - A_G``: the family has a fold only where ``a > 0``."""
    return sigma - a_g(q, mu)


def d_of_c(c: Any, q: Any, sigma: Any, mu: Any) -> Any:
    """``D(c) = (K + q k) . I_G (K + q k) = sigma (c + q)^2 + A_G (1 - c^2)`` (S4).

    ``D(1) = sigma (1 + q)^2``, ``D(-1) = sigma (1 - q)^2``; ``D > 0`` on ``[-1, 1]`` in the
    physical domain (a squared length times a moment of inertia)."""
    return sigma * (c + q) ** 2 + a_g(q, mu) * (1.0 - c * c)


def p_of_c(c: Any, q: Any, sigma: Any, mu: Any) -> Any:
    """``P(c) = D'(c) / 2 = (sigma - A_G) c + sigma q`` (S3).

    ``P(1) = sigma (1 + q) - A_G``, ``P(-1) = A_G - sigma (1 - q)``: their signs decide the
    high-spin classes (:mod:`stability.steady.classes`)."""
    return detuning(q, sigma, mu) * c + sigma * q


def c0(q: Any, sigma: Any, mu: Any) -> Any:
    """``c0 = sigma q / (A_G - sigma)``: the root of ``P``, where the family runs to ``J = inf``.

    Also the tilted state of the ``fr_inv = 0`` (high-spin) limit. ``+-inf`` at ``sigma = A_G``
    (no root), NaN at ``q = 0 = sigma - A_G``."""
    ag = a_g(q, mu)
    if isinstance(ag, float):
        den = ag - sigma
        if den == 0.0:
            return math.nan if q == 0.0 else math.copysign(math.inf, sigma * q)
        return sigma * q / den
    with np.errstate(divide="ignore", invalid="ignore"):
        return sigma * np.asarray(q, float) / (ag - sigma)


def precession_rate(c: Any, *, q: Any, sigma: Any, fr_inv: Any, mu: Any, sign: float = 1.0) -> Any:
    """``lam = sign sqrt(mu fr_inv q / P(c))`` on the tilted family (S3); NaN where ``q P <= 0``."""
    p = p_of_c(c, q, sigma, mu)
    if isinstance(p, float):
        r = mu * fr_inv * q / p if p != 0.0 else math.nan
        return sign * math.sqrt(r) if r > 0 else math.nan
    with np.errstate(divide="ignore", invalid="ignore"):
        r = mu * fr_inv * q / p
    return sign * np.sqrt(np.where(r > 0, r, np.nan))


def jellett_of_c(c: Any, *, q: Any, sigma: Any, fr_inv: Any, mu: Any, sign: float = 1.0) -> Any:
    """``J(c) = lam(c) D(c)``, i.e. ``J^2 = mu fr_inv q D^2 / P`` (S6); NaN off the family."""
    return precession_rate(c, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu, sign=sign) * d_of_c(c, q, sigma, mu)


def effective_potential(c: Any, jellett: Any, *, q: Any, sigma: Any, fr_inv: Any, mu: Any) -> Any:
    """``U_J(c) = J^2 / (2 D(c)) + mu fr_inv (1 + q c)`` (S5): the energy of the steady state at
    ``c`` on the level ``J``, and a lower bound of the energy of every state there."""
    return jellett * jellett / (2.0 * d_of_c(c, q, sigma, mu)) + mu * fr_inv * (1.0 + q * c)


def potential_slope(c: Any, jellett: Any, *, q: Any, sigma: Any, fr_inv: Any, mu: Any) -> Any:
    """``U_J'(c) = -J^2 P / D^2 + mu fr_inv q``; zero at the tilted states (S3 with S4)."""
    d = d_of_c(c, q, sigma, mu)
    return -jellett * jellett * p_of_c(c, q, sigma, mu) / (d * d) + mu * fr_inv * q


def potential_curvature(c: Any, jellett: Any, *, q: Any, sigma: Any, mu: Any) -> Any:
    """``U_J''(c) = J^2 (4 P^2 - a D) / D^3`` at a tilted state (S8; ``U_J' = 0`` used)."""
    d = d_of_c(c, q, sigma, mu)
    p = p_of_c(c, q, sigma, mu)
    return jellett * jellett * (4.0 * p * p - detuning(q, sigma, mu) * d) / d ** 3


def axial_spin(c: Any, lam: Any, q: Any) -> Any:
    """``omega . k = lam (c + q)`` on a steady state (S1)."""
    return lam * (c + q)


def vertical_spin(orientation: str, jellett: Any, *, q: Any, sigma: Any) -> Any:
    """Spin ``n`` (``omega = n K``) of the upright (``J = sigma n (1 + q)``) or inverted
    (``J = sigma n (1 - q)``) state with Jellett integral ``J``."""
    c = ORIENTATIONS[orientation]
    return jellett / (sigma * (1.0 + q * c))


def branch_point_jellett(orientation: str, *, q: Any, sigma: Any, fr_inv: Any, mu: Any) -> Any:
    """``|J|`` at the branch point of the tilted family on a vertical state; NaN if none.

    ``J_up^2 = mu fr_inv q sigma^2 (1 + q)^4 / P(1)``, ``J_inv^2 = mu fr_inv q sigma^2 (1 - q)^4
    / P(-1)``: with ``J = sigma n (1 +- q)`` these are eq. (11)'s neutral curves at the
    equivalent spin ``n`` (``fr_inv -> fr_inv / n^2``; ``q -> -q`` for the inverted top).
    """
    c = ORIENTATIONS[orientation]
    d = d_of_c(c, q, sigma, mu)
    p = p_of_c(c, q, sigma, mu)
    if isinstance(p, float):
        j2 = mu * fr_inv * q * d * d / p if p != 0.0 else math.nan
        return math.sqrt(j2) if j2 > 0 else math.nan
    with np.errstate(divide="ignore", invalid="ignore"):
        j2 = mu * fr_inv * q * d * d / p
    return np.sqrt(np.where(j2 > 0, j2, np.nan))


def fold_cosines(q: float, sigma: float, mu: float) -> tuple[float, float]:
    """Cosines ``c0 -+ sqrt(D(c0) / (3 a))`` of the folds of ``J(c)`` (NaN where there is none).

    ``d(J^2)/dc = mu fr_inv q D (4 P^2 - a D) / P^2`` and ``4 P^2 - a D = 3 a^2 (c - c0)^2 -
    a D(c0)``, so ``dJ/dc = 0`` only for ``a > 0`` and ``D(c0) > 0``; the two folds lie on
    either side of ``c0`` and the family on one side only, so a branch has at most one fold.
    The same for every ``fr_inv > 0``.
    """
    a = detuning(q, sigma, mu)
    if a <= 0.0:
        return math.nan, math.nan
    cc = c0(q, sigma, mu)
    dc0 = d_of_c(cc, q, sigma, mu)
    if not dc0 > 0.0:
        return math.nan, math.nan
    r = math.sqrt(dc0 / (3.0 * a))
    return cc - r, cc + r


def family_interval(q: float, sigma: float, fr_inv: float, mu: float) -> tuple[float, float, str, str] | None:
    """Where the tilted family exists: ``(c_lo, c_hi, end_lo, end_hi)`` or None.

    ``fr_inv > 0`` and ``q != 0``: the interval of ``[-1, 1]`` where ``q P(c) > 0`` (one
    interval: ``P`` is linear); its ends are ``"inverted"`` (``c = -1``), ``"upright"``
    (``c = 1``) or ``"infinity"`` (``c0``, where ``J -> inf``). ``fr_inv = 0`` or ``q = 0``:
    the single cosine ``c0`` (``0`` for ``q = 0``) at every ``J``, ends ``"vertical_line"``;
    None if it is outside ``(-1, 1)`` or undefined (``q = 0``, ``sigma = A_G``).
    """
    a = detuning(q, sigma, mu)
    if fr_inv == 0.0 or q == 0.0:
        if a == 0.0:
            return None
        cc = c0(q, sigma, mu)
        return (cc, cc, "vertical_line", "vertical_line") if -1.0 < cc < 1.0 else None
    lo, hi, elo, ehi = -1.0, 1.0, "inverted", "upright"
    cc = c0(q, sigma, mu)
    if -1.0 < cc < 1.0:
        if q * a > 0:  # P = a (c - c0) has the sign of q above c0
            lo, elo = cc, "infinity"
        else:
            hi, ehi = cc, "infinity"
    elif q * p_of_c(0.0, q, sigma, mu) <= 0:
        return None
    return lo, hi, elo, ehi


def _root(f, df, lo: float, hi: float, flo: float, fhi: float) -> float:
    """Safeguarded Newton on a bracket with ``flo * fhi < 0``, to the last bit of ``c``."""
    x = lo - flo * (hi - lo) / (fhi - flo)
    for _ in range(200):
        fx = f(x)
        if fx == 0.0:
            return x
        if (fx < 0) == (flo < 0):
            lo, flo = x, fx
        else:
            hi, fhi = x, fx
        d = df(x)
        xn = x - fx / d if d != 0.0 else 0.5 * (lo + hi)
        if not lo < xn < hi:
            xn = 0.5 * (lo + hi)
        if xn == x or hi - lo <= 4.5e-16 * max(1.0, abs(x)):
            return xn
        x = xn
    return x


def tilted_cosines(jellett: float, *, q: float, sigma: float, fr_inv: float, mu: float) -> list[float]:
    """Cosines of every tilted steady state (``-1 < c < 1``) on the Jellett level ``J``.

    Method: the roots of ``Q(c) = mu fr_inv q D(c)^2 - J^2 P(c)`` (S6). ``[-1, 1]`` is cut at
    ``c0`` and at the folds (:func:`fold_cosines`); on each piece where ``q P > 0`` the function
    ``J^2(c)`` is monotone, so ``Q`` changes sign at most once there, and a safeguarded Newton
    step on the bracket finds the root to the last bit (``Q`` has no pole). ``fr_inv = 0`` or
    ``q = 0``: the single cosine of :func:`family_interval` at every ``J != 0``.

    Returns
    -------
    list of float
        Decreasing (increasing tilt). A level exactly at a fold (a double root) is found only
        if rounding gives a sign change: the state is then marginal (:func:`energy_test`).
    """
    q, sigma, fr_inv, mu, jellett = float(q), float(sigma), float(fr_inv), float(mu), float(jellett)
    if jellett == 0.0:
        return []
    if fr_inv == 0.0 or q == 0.0:
        iv = family_interval(q, sigma, fr_inv, mu)
        return [iv[0]] if iv is not None else []
    ag = a_g(q, mu)
    a = sigma - ag
    k = mu * fr_inv * q
    j2 = jellett * jellett
    sq = sigma * q

    def quartic(c: float) -> float:
        d = sigma * (c + q) ** 2 + ag * (1.0 - c * c)
        return k * d * d - j2 * (a * c + sq)

    def dquartic(c: float) -> float:
        d = sigma * (c + q) ** 2 + ag * (1.0 - c * c)
        return 4.0 * k * d * (a * c + sq) - j2 * a

    cuts = [-1.0, 1.0]
    if a != 0.0:
        cc = -sq / a
        if -1.0 < cc < 1.0:
            cuts.append(cc)
        for cf in fold_cosines(q, sigma, mu):
            if -1.0 < cf < 1.0:
                cuts.append(cf)
    cuts.sort()
    roots = []
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        if q * (a * 0.5 * (lo + hi) + sq) <= 0:
            continue
        flo, fhi = quartic(lo), quartic(hi)
        if flo == 0.0 and lo > -1.0:
            roots.append(lo)
        if flo * fhi < 0:
            r = _root(quartic, dquartic, lo, hi, flo, fhi)
            if -1.0 < r < 1.0:
                roots.append(r)
    return sorted(set(roots), reverse=True)


def energy_test(kind: str, c: float, jellett: float, *, q: float, sigma: float, fr_inv: float,
                mu: float) -> tuple[float, float]:
    """The energy criterion of stability (S8): a signed test and its scale.

    Upright: ``-U_J'(1)``, i.e. ``n^2 (sigma (1 + q) - A_G) - mu fr_inv q (1 + q)^2`` up to a
    positive factor: eq. (11)'s neutral curve, stable side positive. Inverted: ``U_J'(-1)``
    (the same with ``q -> -q``). Tilted: ``U_J'' = J^2 (4 P^2 - a D) / D^3``. Positive means a
    strict minimum of ``U_J`` (stable with friction), negative a maximum (unstable).

    Returns
    -------
    test : float
    scale : float
        The size of the terms the test is made of (for a relative tolerance).
    """
    d = d_of_c(c, q, sigma, mu)
    p = p_of_c(c, q, sigma, mu)
    j2 = jellett * jellett
    if kind == "tilted":
        a = detuning(q, sigma, mu)
        return j2 * (4.0 * p * p - a * d) / d ** 3, j2 * (4.0 * p * p + abs(a) * d) / d ** 3
    sign = ORIENTATIONS[kind]  # upright: -U'(1); inverted: +U'(-1)
    return sign * (j2 * p / (d * d) - mu * fr_inv * q), j2 * abs(p) / (d * d) + mu * fr_inv * abs(q)


@njit(cache=True)
def state_core(theta, lam, q, phi, y):
    """Fill ``y[:8] = (omega, k, V0_h)`` with the steady state at tilt ``theta`` (S1, S2).

    ``k = (sin theta cos phi, sin theta sin phi, cos theta)``, ``omega = lam (K + q k)``,
    ``V0 = omega x K`` (so that the contact point does not slip, ``V0 + K x omega = 0``).
    ``theta`` may be complex (complex-step derivatives); ``y`` real or complex of length >= 8.
    """
    s = np.sin(theta)
    k0 = s * np.cos(phi)
    k1 = s * np.sin(phi)
    k2 = np.cos(theta)
    w0 = lam * q * k0
    w1 = lam * q * k1
    w2 = lam * (1.0 + q * k2)
    y[0] = w0
    y[1] = w1
    y[2] = w2
    y[3] = k0
    y[4] = k1
    y[5] = k2
    y[6] = w1   # (omega x K)_1 = omega_2
    y[7] = -w0  # (omega x K)_2 = -omega_1


def state_vector(theta: Any, lam: Any, q: float, phi: Any = 0.0) -> np.ndarray:
    """Steady states ``(omega, k, V0_h)`` (shape ``(..., 8)``) at tilts ``theta`` (radians).

    Vertical states: ``theta = 0`` or ``pi`` with ``lam = n / (1 +- q)`` gives ``omega = n K``.
    """
    theta, lam, phi = np.broadcast_arrays(np.asarray(theta, float), np.asarray(lam, float),
                                          np.asarray(phi, float))
    out = np.empty(theta.shape + (8,))
    flat = out.reshape(-1, 8)
    for i, (t, la, ph) in enumerate(zip(theta.ravel(), lam.ravel(), phi.ravel())):
        state_core(float(t), float(la), float(q), float(ph), flat[i])
    return out


def vertical_state(orientation: str, spin: float) -> np.ndarray:
    """The vertical state ``omega = n K``, ``k = +-K``, ``V0 = 0`` as ``(omega, k, V0_h)`` (8,)."""
    y = np.zeros(8)
    y[2] = spin
    y[5] = ORIENTATIONS[orientation]
    return y
