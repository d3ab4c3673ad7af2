"""Threshold queries: where the leading growth rate changes sign as one parameter varies.

Method (for :func:`threshold_crossings`, whose values :func:`thresholds` returns):

1. sample the parameter over the bracket (a uniform and a geometric grid, ``samples`` points
   each) and decide the stability of each sample (:func:`stability.spectrum`);
2. each pair of neighbouring samples on which "unstable" changes brackets a threshold;
   bisection on the stability decision narrows it to ``1e-7`` of the bracket;
3. Newton's method on the neutral condition of the crossing mode (:mod:`stability.linear.neutrality`:
   ``Re p(i w) = Im p(i w) = 0`` in the unknowns (parameter, ``w``); for a conservative model
   the collision ``P(w) = P'(w) = 0``) polishes it to a relative backward error of about
   ``1e-16``: the root of the smooth mode-wise ``Re s``, not an interpolation. If Newton leaves
   the bracket, bisection continues to the last bit instead.

Two crossings closer than the sampling step (a neutral curve folding back between two
samples) do not change the stability decision from sample to sample. They are looked for where
the growth rate of the stable samples has a local maximum close to zero (compared with its
variation between samples): the maximum is refined by bounded Brent, and if it is positive the
two crossings on either side are polished as above. A crossing that only touches zero (the
growth rate's maximum at zero to rounding, exactly at a fold) is not a change of stability and
is not reported.

:func:`critical_spin` answers the physical question for a real top (:class:`stability.Top`):
the spin rate above which the upright state is unstable, or the inverted one stable.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from ..models import LinearModel, get_model
from .neutrality import NeutralCondition
from ..errors import DomainError
from ..parameters import (DEFAULT_MU, as_parameter, as_scalar, check_choice, check_domain, check_flag,
                         check_integer)
from .spectra import UNSTABLE, spectrum

__all__ = ["Threshold", "threshold", "thresholds", "threshold_crossings", "critical_spin", "CriticalSpin",
           "default_bracket", "UPPER_BOUND"]

#: upper end of the default bracket of the parameters without a finite physical bound
UPPER_BOUND: dict[str, float] = {"fr_inv": 1e3, "alpha_v": 1e3, "mu": 1e3}


class Threshold(NamedTuple):
    """One threshold: the value, the neutral mode's frequency and the unstable side."""

    value: float
    frequency: float
    unstable_side: str  # "below" or "above" the value


def default_bracket(param: str, fixed: Mapping[str, float]) -> tuple[float, float]:
    """The physical range of ``param`` given the other parameters (closed, slightly inside).

    ``q``: ``mu q^2 <= 1 - sigma/2`` (from ``sigma <= 2 (1 - mu q^2)``); ``sigma``:
    ``(0, 2 (1 - mu q^2)]``; ``mu``: ``(0, (1 - sigma/2) / q^2]`` capped at 1e3;
    ``fr_inv``, ``alpha_v``: ``[0, 1e3]``.
    """
    shrink = 1e-12
    if param == "q":
        b = math.sqrt(max(0.0, 1.0 - fixed.get("sigma", 0.0) / 2.0) / fixed["mu"]) * (1 - shrink)
        return (-b, b)
    if param == "sigma":
        return (shrink, 2.0 * (1.0 - fixed["mu"] * fixed["q"] ** 2) * (1 - shrink))
    if param == "mu":
        q = fixed["q"]
        hi = UPPER_BOUND["mu"] if q == 0 else min(UPPER_BOUND["mu"], (1.0 - fixed["sigma"] / 2.0) / q**2 * (1 - shrink))
        return (shrink * hi, hi)
    return (0.0, UPPER_BOUND[param])


def _setup(param: str, model: str | LinearModel, bracket: Sequence[float] | None,
           fixed: Mapping[str, Any]) -> tuple[LinearModel, dict[str, float], tuple[float, float]]:
    m = get_model(model)
    if not isinstance(param, str) or param not in m.parameters:
        raise ValueError(f"param = {param!r} is not a parameter of model {m.name!r}; "
                         f"choose one of {', '.join(m.parameters)}")
    fx = {k: v for k, v in fixed.items() if v is not None}
    if param in fx:
        raise TypeError(f"{param} is the parameter searched and cannot also be given a value")
    if "mu" in m.parameters and param != "mu":
        fx.setdefault("mu", DEFAULT_MU)
    for k in fx:
        if k not in m.parameters:
            raise TypeError(f"model {m.name!r} takes no parameter {k} (it takes {', '.join(m.parameters)})")
    missing = [k for k in m.parameters if k != param and k not in fx]
    if missing:
        raise TypeError(f"{', '.join(missing)} required for a threshold in {param} of model {m.name!r}")
    p, _ = check_domain(scalar=True, **fx)
    fx = {k: float(v) for k, v in p.items()}
    if bracket is None:
        lo, hi = default_bracket(param, fx)
    else:
        try:
            lo, hi = (float(as_parameter("bracket", v)) for v in bracket)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"bracket must be a pair (lo, hi) of real numbers, got {bracket!r}") from exc
        if not lo < hi:
            raise ValueError(f"bracket = ({lo:g}, {hi:g}) must have lo < hi")
        for end in (lo, hi):  # each end on its own: a grid's hint (mask_unphysical) does not apply
            try:
                check_domain(scalar=True, **{**fx, param: end})
            except DomainError as exc:
                raise DomainError(f"bracket = ({lo:g}, {hi:g}) leaves the physical domain: {exc}") from None
    return m, fx, (lo, hi)


def _samples(lo: float, hi: float, n: int) -> np.ndarray:
    w = hi - lo
    g = np.geomspace(1e-8, 1.0, n)
    return np.unique(np.concatenate([np.linspace(lo, hi, n), lo + w * g, hi - w * g]))


def _unstable(m: LinearModel, fx: Mapping[str, float], param: str, x: np.ndarray):
    sp = spectrum(m, mask_unphysical=True, **{**fx, param: x})
    return sp.stability == UNSTABLE, sp.inside, sp.eigenvalues


def _polish(m: LinearModel, fx: Mapping[str, float], param: str, a: float, b: float,
            unstable_a: bool) -> Threshold:
    """Locate the threshold between samples ``a`` (state ``unstable_a``) and ``b``."""
    for _ in range(24):  # bisection on the stability decision, to 6e-8 of the bracket
        c = 0.5 * (a + b)
        u, inside, _ = _unstable(m, fx, param, np.array([c]))
        if not inside[0]:
            break
        if bool(u[0]) == unstable_a:
            a = c
        else:
            b = c
    side_unstable = a if unstable_a else b
    _, _, ev = _unstable(m, fx, param, np.array([side_unstable]))
    ev = ev[0]
    grow = ev[ev.real > 0]
    w0 = float(grow[np.argmin(grow.real)].imag) if grow.size else float(ev[0].imag)
    cond = NeutralCondition(m, (param,), fx, samples=np.array([[a], [b]]))
    lo, hi = min(a, b), max(a, b)
    width = hi - lo
    x = np.array([0.5 * (a + b)])
    w = w0
    best = None
    for _ in range(40):
        F, J = cond.residual_and_jacobian(x, w)
        fn = float(np.linalg.norm(F))
        if best is None or fn < best[0]:
            best = (fn, float(x[0]), w)
        try:
            d = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            break
        x, w = x + d[:1], w + float(d[1])
        if not (lo - 10 * width <= x[0] <= hi + 10 * width) or not np.isfinite(w):
            break
        if abs(d[0]) <= 2e-16 * max(1.0, abs(x[0])) and abs(d[1]) <= 2e-16 * max(1.0, abs(w)):
            F, _ = cond.residual_and_jacobian(x, w, jacobian=False)
            fn = float(np.linalg.norm(F))
            if fn < best[0]:
                best = (fn, float(x[0]), w)
            break
    if best is not None and best[0] <= 1e-13 and lo - 10 * width <= best[1] <= hi + 10 * width:
        value, w = best[1], best[2]
    else:  # bisection to the last bit on the stability decision
        for _ in range(200):
            c = 0.5 * (a + b)
            if c in (a, b):
                break
            u, _, _ = _unstable(m, fx, param, np.array([c]))
            if bool(u[0]) == unstable_a:
                a = c
            else:
                b = c
        value, w = 0.5 * (a + b), w0
    # a change of stability at the domain's edge (e.g. alpha_v = 0: every friction destabilises)
    # is polished by Newton to a rounding error on either side of it (alpha_v = -2e-27): the
    # threshold is the edge itself, never a value outside the physical domain
    _, inside = check_domain(mask=True, **{**fx, param: np.array([value])})
    if not inside[0]:
        edge_lo, edge_hi = default_bracket(param, fx)
        value = edge_lo if abs(value - edge_lo) <= abs(value - edge_hi) else edge_hi
    side = "below" if (unstable_a and a < b) or (not unstable_a and b < a) else "above"
    return Threshold(float(value), float(w), side)


def threshold_crossings(param: str, *, model: str | LinearModel = "sliding",
                        bracket: Sequence[float] | None = None, samples: int = 257,
                        **fixed: Any) -> list[Threshold]:
    """Every change of stability as ``param`` varies: value, neutral frequency and unstable side.

    The records behind :func:`thresholds` (which returns their values only); the method is the
    module's.

    Parameters
    ----------
    param : {"q", "fr_inv", "sigma", "alpha_v", "mu"}
        The parameter varied.
    model : {"fixed_pivot", "rolling", "sliding"} or LinearModel
        Eqs. (8)-(9) or eq. (11).
    bracket : pair of float, optional
        Range searched (inside the physical domain); default :func:`default_bracket`.
    samples : int
        Points of each of the uniform and geometric sampling grids.
    **fixed
        All other parameters of the model (``mu`` defaults to 2.28).

    Returns
    -------
    list of Threshold
        Sorted by value: the value, the frequency of the neutral mode there, and on which side
        (``"below"`` or ``"above"`` the value) the state is unstable. Empty if the stability
        never changes.

    Raises
    ------
    ValueError, TypeError
        As :func:`thresholds`.

    Examples
    --------
    >>> import stability
    >>> (t,) = stability.threshold_crossings("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5)
    >>> round(t.value, 12), t.unstable_side  # (1 - mu q^2)/(1 + q), unstable for smaller sigma
    (1.085777777778, 'below')
    """
    samples = check_integer("samples", samples, minimum=3)
    m, fx, (lo, hi) = _setup(param, model, bracket, fixed)
    return _search(m, fx, param, lo, hi, samples)[0]


def thresholds(param: str, *, model: str | LinearModel = "sliding", bracket: Sequence[float] | None = None,
               samples: int = 257, return_details: bool | None = None, **fixed: Any) -> np.ndarray:
    """All values of ``param`` at which the leading growth rate changes sign, sorted.

    Parameters
    ----------
    param : {"q", "fr_inv", "sigma", "alpha_v", "mu"}
        The parameter varied.
    model : {"fixed_pivot", "rolling", "sliding"} or LinearModel
        Eqs. (8)-(9) or eq. (11).
    bracket : pair of float, optional
        Range searched (inside the physical domain); default :func:`default_bracket`.
    samples : int
        Points of each of the uniform and geometric sampling grids.
    return_details : bool, optional
        Deprecated (a ``DeprecationWarning``; removed in the next release): ``True`` returned
        the :class:`Threshold` records instead of the values, which is now
        :func:`threshold_crossings`.
    **fixed
        All other parameters of the model (``mu`` defaults to 2.28).

    Returns
    -------
    numpy.ndarray
        The values, sorted; empty if the stability never changes. (With the deprecated
        ``return_details=True``: the list of :class:`Threshold` of :func:`threshold_crossings`.)

    Raises
    ------
    ValueError, TypeError
        Unknown model or parameter, missing or extra parameters, bad bracket, values outside the
        physical domain (naming the parameter, its value and the bound).
    """
    if return_details is not None:
        return_details = check_flag("return_details", return_details)
        warnings.warn("thresholds(return_details=...) is deprecated and will be removed in the next release: "
                      "thresholds() returns the values; threshold_crossings() returns the Threshold records "
                      "(value, frequency, unstable side)", DeprecationWarning, stacklevel=2)
    found = threshold_crossings(param, model=model, bracket=bracket, samples=samples, **fixed)
    if return_details:  # the deprecated return type, until the keyword is removed
        return found  # type: ignore[return-value]
    return np.array([t.value for t in found])


def _growth(m: LinearModel, fx: Mapping[str, float], param: str, x: np.ndarray) -> np.ndarray:
    """Largest growth rate over the modes that are not flagged neutral (structural zeros)."""
    sp = spectrum(m, mask_unphysical=True, **{**fx, param: x})
    ev = np.where(sp.neutral, complex(-np.inf, 0.0), sp.eigenvalues)
    return np.max(ev.real, axis=-1)


def _hidden_pairs(m: LinearModel, fx: Mapping[str, float], param: str, x: np.ndarray,
                  u: np.ndarray) -> list[tuple[float, float, float]]:
    """Pairs of crossings between two samples (a neutral curve folding back there).

    Where the growth rate ``g`` of the stable samples has a local maximum whose parabola
    through the three samples comes within its own variation of zero, the maximum is refined
    (bounded Brent, :func:`scipy.optimize.minimize_scalar`, to ``1e-13`` relative). Returns
    ``(a, x_max, b)`` for each refined maximum with ``g > 0``: the window ``(a, b)`` holds two
    thresholds, one on each side of ``x_max``.
    """
    if len(x) < 3:
        return []
    g = _growth(m, fx, param, x)
    out = []
    for k in range(1, len(x) - 1):
        if u[k - 1] or u[k] or u[k + 1] or not (g[k] >= g[k - 1] and g[k] >= g[k + 1]):
            continue
        if not np.all(np.isfinite(g[k - 1:k + 2])) or g[k] >= 0:
            continue
        rise = max(g[k] - g[k - 1], g[k] - g[k + 1])
        if -g[k] > 4.0 * rise:  # far below zero for its curvature: no crossing nearby
            continue
        a, b = float(x[k - 1]), float(x[k + 1])
        from scipy.optimize import minimize_scalar  # here: most thresholds never refine (0.5 s import)

        res = minimize_scalar(lambda s: -float(_growth(m, fx, param, np.array([s]))[0]),
                              bounds=(a, b), method="bounded",
                              options={"xatol": 1e-13 * max(1.0, abs(b - a), abs(a), abs(b))})
        if -res.fun > 0:
            out.append((a, float(res.x), b))
    return out


def _search(m: LinearModel, fx: Mapping[str, float], param: str, lo: float, hi: float, n: int):
    x = _samples(lo, hi, n)
    u, inside, _ = _unstable(m, fx, param, x)
    x, u = x[inside], u[inside]
    found = []
    for k in np.nonzero(u[1:] != u[:-1])[0]:
        found.append(_polish(m, fx, param, float(x[k]), float(x[k + 1]), bool(u[k])))
    # two crossings between neighbouring samples (near a fold of the neutral curve): the
    # stability decision does not change from sample to sample, the growth rate's maximum does
    for a, xm, b in _hidden_pairs(m, fx, param, x, u):
        if _unstable(m, fx, param, np.array([xm]))[0][0]:
            found.append(_polish(m, fx, param, a, xm, False))
            found.append(_polish(m, fx, param, b, xm, False))
    found.sort(key=lambda t: t.value)
    return found, u


def threshold(param: str, *, model: str | LinearModel = "sliding", bracket: Sequence[float] | None = None,
              samples: int = 257, **fixed: Any) -> float:
    """The value of ``param`` at which the leading growth rate changes sign.

    Parameters
    ----------
    param : {"q", "fr_inv", "sigma", "alpha_v", "mu"}
        The parameter varied; all others are fixed.
    model : {"fixed_pivot", "rolling", "sliding"} or LinearModel
        Eqs. (8)-(9) or eq. (11).
    bracket : pair of float, optional
        Range searched; default the physical range (:func:`default_bracket`).
    samples : int
        See :func:`thresholds`.
    **fixed
        All other parameters (``mu`` defaults to 2.28).

    Returns
    -------
    float
        The threshold, to a relative backward error of the neutral condition ``~1e-16``.

    Raises
    ------
    ValueError
        If there is no sign change in the bracket (the message says whether the state is
        stable, marginal or unstable throughout, and the range searched), or several (the
        message lists them; use a narrower ``bracket`` or :func:`thresholds`).

    Examples
    --------
    >>> import stability
    >>> round(stability.threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5), 12)  # (1 - mu q^2)/(1 + q)
    1.085777777778
    """
    samples = check_integer("samples", samples, minimum=3)
    m, fx, (lo, hi) = _setup(param, model, bracket, fixed)
    found, u = _search(m, fx, param, lo, hi, samples)
    given = ", ".join(f"{k} = {v:g}" for k, v in fx.items())
    if not found:
        sp = spectrum(m, mask_unphysical=True, **{**fx, param: _samples(lo, hi, int(samples))})
        st = sp.stability[sp.inside]
        state = ("unstable" if u.all() else "stable" if (st == 0).all()
                 else "marginal (neutrally stable)" if (st == 1).all() else "stable or marginal")
        raise ValueError(f"no threshold in {param}: the {m.name} model is {state} throughout "
                         f"{param} in [{lo:.6g}, {hi:.6g}] ({given})")
    if len(found) > 1:
        listed = ", ".join(f"{t.value:.12g} (unstable {t.unstable_side})" for t in found)
        raise ValueError(f"{len(found)} thresholds in {param} in [{lo:.6g}, {hi:.6g}] ({given}): "
                         f"{listed}; pass bracket=(lo, hi) around one, or use stability.thresholds")
    return found[0].value


# ------------------------------------------------------------------------------------------
# critical spin of a real top
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CriticalSpin:
    """The spin rate at which a real top's state changes stability.

    Attributes
    ----------
    orientation : str
        ``"upright"`` (as given) or ``"inverted"`` (``q -> -q``).
    spin : float
        Critical spin rate in rad/s.
    rpm : float
        The same in revolutions per minute.
    fr_inv : float
        Inverse Froude number at the critical spin.
    frequency : float
        Frequency of the neutral mode there (units of the spin rate).
    unstable_above : bool
        True if the state is unstable at every spin above ``spin`` (in the range searched).
    alpha_v : float or None
        The viscous friction parameter at the critical spin (sliding model).
    friction : str
        The friction assumption used.
    transitions : tuple of float
        Every spin rate (rad/s) at which the stability changes in the range searched.
    """

    orientation: str
    spin: float
    rpm: float
    fr_inv: float
    frequency: float
    unstable_above: bool
    alpha_v: float | None
    friction: str
    transitions: tuple[float, ...]


class _SpinScaled(LinearModel):
    """A model whose ``alpha_v`` follows the spin: ``alpha_v = k sqrt(fr_inv)`` (fixed mu_v).

    With ``alpha_v = mu mu_v g / Omega`` and ``Omega = sqrt(g / (R fr_inv))``:
    ``alpha_v = mu mu_v sqrt(g R) sqrt(fr_inv)``.
    """

    def __init__(self, base: LinearModel, k: float):
        self.base = base
        self.k = k
        self.name = f"{base.name} (alpha_v = {k:.6g} sqrt(fr_inv))"
        self.equations = base.equations
        self.parameters = tuple(p for p in base.parameters if p != "alpha_v")
        self.state = base.state
        self.n_modes = base.n_modes
        self.description = base.description

    def _p(self, params: dict) -> dict:
        return {**params, "alpha_v": self.k * np.sqrt(np.abs(np.asarray(params["fr_inv"], float)))}

    def matrices(self, **params):
        return self.base.matrices(**self._p(params))

    def coefficients(self, **params):
        return self.base.coefficients(**self._p(params))


def critical_spin(top: Any, model: str | LinearModel = "sliding", orientation: str = "upright", *,
                  alpha_v: float = 0.5, fr_inv_range: Sequence[float] = (1e-6, 1e4),
                  samples: int = 257) -> CriticalSpin:
    """The spin rate above which a real top is unstable (upright) or stable (inverted).

    Friction assumption (sliding model, eq. 11): if the top has a viscous coefficient
    ``mu_v`` (s/m), ``alpha_v = mu mu_v g / Omega`` (eq. 7) varies with the spin as
    ``1 / Omega``, i.e. as ``sqrt(fr_inv)``, and is followed exactly. Without ``mu_v``,
    ``alpha_v`` is held at the given value (default 0.5, the paper's Fig. 3). For any
    ``alpha_v > 0`` the sliding model's neutral set does not depend on ``alpha_v``: with
    ``p(i w) = alpha_v P_r(w) + i mu w P_f(w)`` (``P_f`` the free top, ``P_r`` the rolling top,
    both real), a mode is neutral only at a common real root, which is ``w = 1/(1 + q)``, where
    the contact point does not slip; hence ``sigma = (1 - mu q^2)/(1 + q) + mu q (1 + q) fr_inv``
    on the neutral curve, and the critical spin is the same for every positive viscous friction.
    At ``alpha_v = 0`` (no friction) the top is only neutrally stable.

    Parameters
    ----------
    top : stability.Top
        The top (SI units).
    model : str or LinearModel
        A linear model; ``"sliding"`` by default.
    orientation : {"upright", "inverted"}
        ``"inverted"`` uses ``top.inverted()`` (``q -> -q``).
    alpha_v : float
        Viscous parameter used when ``top.mu_v`` is None (sliding model only).
    fr_inv_range : pair of float
        Range of ``fr_inv`` searched (``0 < lo < hi``): spins between ``top.spin_rate(hi)``
        and ``top.spin_rate(lo)``.
    samples : int
        See :func:`thresholds`.

    Returns
    -------
    CriticalSpin
        For the transition at the highest spin (the one above which the state no longer
        changes); all transitions are in ``transitions``.

    Raises
    ------
    ValueError
        Unknown orientation, or no change of stability in the range (the message says which
        state holds throughout, and the spin range in rad/s and rpm).
    TypeError
        If ``top`` is not a :class:`stability.Top`.
    """
    from ..top import Top

    if not isinstance(top, Top):
        raise TypeError(f"top must be a stability.Top, got {type(top).__name__}")
    check_choice("orientation", orientation, ("upright", "inverted"))
    samples = check_integer("samples", samples, minimum=3)
    if isinstance(fr_inv_range, (str, bytes)) or not hasattr(fr_inv_range, "__len__") or len(fr_inv_range) != 2:
        raise TypeError(f"fr_inv_range = {fr_inv_range!r} must be a pair (lo, hi) of real numbers")
    lo, hi = (as_scalar("fr_inv_range", v) for v in fr_inv_range)
    if not 0 < lo < hi:
        raise DomainError(f"fr_inv_range = ({lo:g}, {hi:g}) is outside the allowed range: 0 < lo < hi")
    t = top.inverted() if orientation == "inverted" else top
    base = get_model(model)
    fixed: dict[str, float] = {"q": t.q, "sigma": t.sigma, "mu": t.mu}
    fixed = {k: v for k, v in fixed.items() if k in base.parameters}
    m: LinearModel = base
    if "alpha_v" in base.parameters:
        if t.mu_v is not None:
            k = t.mu * t.mu_v * math.sqrt(t.g * t.radius)
            m = _SpinScaled(base, k)
            friction = (f"viscous, mu_v = {t.mu_v:g} s/m: alpha_v = mu mu_v g / Omega "
                        f"= {k:.6g} sqrt(fr_inv)")
        else:
            a = float(as_parameter("alpha_v", alpha_v))
            if a < 0:
                raise DomainError(f"alpha_v = {a:g} is outside the physical domain: alpha_v >= 0")
            fixed["alpha_v"] = a
            friction = (f"viscous, alpha_v = {a:g} held fixed (no mu_v given); the threshold of the "
                        "sliding model is the same for every alpha_v > 0")
    else:
        friction = f"none: the {base.name} model has no friction parameter"
    try:
        found, u = _search(m, fixed, "fr_inv", lo, hi, int(samples))
    except DomainError:
        raise
    spins = sorted(float(t.spin_rate(th.value)) for th in found)
    if not found:
        state = "unstable" if u.all() else "not unstable (stable or neutrally stable)"
        s_lo, s_hi = t.spin_rate(hi), t.spin_rate(lo)
        raise ValueError(f"the {orientation} {base.name} top is {state} at every spin from "
                         f"{s_lo:.6g} to {s_hi:.6g} rad/s ({s_lo * 60 / (2 * math.pi):.6g} to "
                         f"{s_hi * 60 / (2 * math.pi):.6g} rpm); no critical spin there")
    th = found[0]  # smallest fr_inv = highest spin
    spin = float(t.spin_rate(th.value))
    a_v = None
    if "alpha_v" in base.parameters:
        a_v = float(fixed["alpha_v"]) if "alpha_v" in fixed else float(t.alpha_v(spin))
    return CriticalSpin(orientation=orientation, spin=spin, rpm=spin * 60.0 / (2.0 * math.pi),
                        fr_inv=th.value, frequency=th.frequency,
                        unstable_above=(th.unstable_side == "below"), alpha_v=a_v,
                        friction=friction, transitions=tuple(spins))
