"""Threshold queries: where the leading growth rate changes sign as one parameter varies.

Method (for :func:`threshold_crossings`, whose values :func:`thresholds` returns):

1. sample the parameter over the bracket (a uniform and a geometric grid, ``samples`` points
   each) and decide, at each sample, the sign of every mode's growth rate against that mode's
   own scale (:mod:`stability.linear.growth`: the root's ``Re s`` where it exceeds four times
   its own error bound, else the structured estimate of
   :func:`stability.linear.roots.axis_growth`, one Newton step from the imaginary axis with the
   real and imaginary parts of ``p(i w)`` evaluated separately). A sample is *unstable* if a
   mode grows, *undecided* if no mode grows and some mode's sign is within rounding of zero;
   not the stability flag of the atlases, whose floor ``16 u max|s|`` (relative to the
   largest mode) hides the tiny growth rates near a crossing at small and large ``alpha_v``
   (docs/hard_cases.md, section 3);
2. each pair of neighbouring decided samples on which "unstable" changes brackets a threshold
   (undecided samples between them lie inside the bracket); bisection on the same sign narrows
   it, as long as the midpoint's sign is decided;
3. Newton's method on the neutral condition of the crossing mode (:mod:`stability.linear.neutrality`:
   the row-scaled ``[Re p(i w) / S_a, Im p(i w) / S_b] = 0`` in the unknowns (parameter, ``w``);
   for a conservative model the collision ``P(w) = P'(w) = 0``) polishes it: the root of the
   smooth mode-wise ``Re s``, not an interpolation. It is accepted only inside the final
   bracket (within 2 ulp of its ends). Otherwise bisection continues to the last bit; if the
   sign cannot be decided down to a few ulp and Newton does not land in the bracket, the answer
   is the bracket itself, an honest interval (``Threshold.exact = False``,
   ``lower``/``upper``), and :func:`threshold` and ``tippe threshold`` say so.

Two crossings closer than the sampling step (a neutral curve folding back between two
samples) do not change the sign from sample to sample. They are looked for where the growth
estimate of the stable samples has a local maximum close to zero (compared with its
variation between samples): the maximum is refined by bounded Brent, and if the mode grows
there the two crossings on either side are polished as above. A crossing that only touches
zero (the growth rate's maximum at zero to rounding, exactly at a fold) is not a change of
stability and is not reported.

:func:`critical_spin` answers the physical question for a real top (:class:`stability.Top`):
the spin rate above which the upright state is unstable, or the inverted one stable.
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from ..errors import DomainError, InputError, ParameterTypeError
from ..models import LinearModel, get_model
from ..parameters import (
    UPPER_BOUND,
    as_scalar,
    check_choice,
    check_domain,
    check_flag,
    check_integer,
    check_range,
    fmt_against,
    sigma_max,
)
from ..resources import check_threshold_samples
from .growth import GROWS, UNDECIDED, growth
from .neutrality import NeutralCondition
from .spectra import MARGINAL, STABLE, UNSTABLE, fixed_parameters, parameter_name

__all__ = [
    "CriticalSpin",
    "CriticalSpins",
    "Threshold",
    "critical_spin",
    "default_bracket",
    "threshold",
    "threshold_crossings",
    "thresholds",
]

#: the largest number of samples a threshold search takes (three grids of this many points)
MAX_SAMPLES = 10**6


class Threshold(NamedTuple):
    """One threshold: the value, the neutral mode's frequency and the unstable side.

    The last three fields say how well the value is known: ``exact`` (the root of the neutral
    condition, or a bracket a few ulp wide) or not, in which case the change of sign lies
    somewhere in ``[lower, upper]`` (the sign of the growth rate could not be decided inside
    it) and ``value`` is its midpoint, or its end on the domain's edge if it reaches one (a
    change of stability at ``alpha_v = 0``, where the model is conservative: the growth rate
    ``~alpha_v`` is decided down to ``alpha_v ~ 1e-45``, not to 0); for an exact threshold
    ``lower = upper = value``.
    """

    value: float
    frequency: float
    unstable_side: str  # "below" or "above" the value
    lower: float = math.nan
    upper: float = math.nan
    exact: bool = True


def default_bracket(param: str, fixed: Mapping[str, float]) -> tuple[float, float]:
    """The physical range of ``param`` given the other parameters (closed, slightly inside).

    ``q``: ``mu q^2 <= 1 - sigma/2`` (from ``sigma <= 2 (1 - mu q^2)``); ``sigma``:
    ``(0, sigma_max(q, mu)]`` (:func:`stability.parameters.sigma_max`, the exact bound
    ``2 (1 - mu q^2)`` rounded down); ``mu``: ``(0, (1 - sigma/2) / q^2]`` capped at
    :data:`stability.parameters.UPPER_BOUND` (1e3); ``fr_inv``, ``alpha_v``: ``[0, 1e3]`` likewise.
    """
    shrink = 1e-12
    if param == "q":
        b = math.sqrt(max(0.0, 1.0 - fixed.get("sigma", 0.0) / 2.0) / fixed["mu"]) * (1 - shrink)
        return (-b, b)
    if param == "sigma":
        return (shrink, float(sigma_max(fixed["q"], fixed["mu"])) * (1 - shrink))
    if param == "mu":
        q = fixed["q"]
        hi = UPPER_BOUND["mu"] if q == 0 else min(UPPER_BOUND["mu"], (1.0 - fixed["sigma"] / 2.0) / q**2 * (1 - shrink))
        return (shrink * hi, hi)
    return (0.0, UPPER_BOUND[param])


def _samples_checked(samples: Any) -> int:
    samples = check_integer("samples", samples, minimum=3, maximum=MAX_SAMPLES)
    check_threshold_samples(samples)
    return samples


def _crossings(
    param: str, model: str | LinearModel, bracket: Sequence[float] | None, samples: Any, fixed: Mapping[str, Any]
) -> tuple[list[Threshold], np.ndarray, LinearModel, dict[str, float], tuple[float, float]]:
    """The arguments of the threshold queries checked, then every threshold in the bracket and
    the states of the samples (:func:`_search`), the model, the fixed parameters and the bracket."""
    samples = _samples_checked(samples)
    m = get_model(model)
    fx = fixed_parameters(m, (parameter_name(m, param, "param"),), fixed)
    if bracket is None:
        lo, hi = default_bracket(param, fx)
    else:
        lo, hi = check_range("bracket", bracket)
        for end in (lo, hi):  # each end on its own: a grid's hint (mask_unphysical) does not apply
            try:
                check_domain(scalar=True, **{**fx, param: end})
            except DomainError as exc:
                a, b = fmt_against(lo, hi)
                raise DomainError(f"bracket = ({a}, {b}) leaves the physical domain: {exc}") from None
    return (*_search(m, fx, param, lo, hi, samples), m, fx, (lo, hi))


def _states(m: LinearModel, fx: Mapping[str, float], param: str, x: np.ndarray):
    """The signs at the samples ``x`` (:func:`stability.linear.growth.growth`)."""
    return growth(m, parallel=False, **{**fx, param: np.asarray(x, dtype=float)})


def _crossing_frequency(sign: np.ndarray, estimate: np.ndarray, eigenvalues: np.ndarray) -> float:
    """The frequency of the crossing mode at an unstable point (its modes' signs, growth
    estimates and eigenvalues): the growing mode with the smallest growth estimate."""
    est = np.where(sign == GROWS, estimate, np.inf)
    return float(eigenvalues[int(np.argmin(est))].imag)


def _newton(cond: NeutralCondition, x0: float, w0: float) -> tuple[float, float] | None:
    """Newton's method on the neutral condition from ``(x0, w0)``: the point with the smallest
    residual if it is at most ``1e-13`` (each row, relative backward error), else None."""
    x = np.array([x0])
    w = w0
    best = None
    for _ in range(40):
        F, J = cond.residual_and_jacobian(x, w)
        fn = float(np.max(np.abs(F)))
        if not math.isfinite(fn):
            break
        if best is None or fn < best[0]:
            best = (fn, float(x[0]), w)
        try:
            d = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(d)):
            break
        x, w = x + d[:1], w + float(d[1])
        if abs(d[0]) <= 2e-16 * max(1.0, abs(x[0])) and abs(d[1]) <= 2e-16 * max(1.0, abs(w)):
            F, _ = cond.residual_and_jacobian(x, w, jacobian=False)
            fn = float(np.max(np.abs(F)))
            if fn < best[0]:
                best = (fn, float(x[0]), w)
            break
    if best is not None and best[0] <= 1e-13:
        return best[1], best[2]
    return None


def _polish(
    m: LinearModel, fx: Mapping[str, float], param: str, a: float, b: float, unstable_a: bool, w_start: float
) -> Threshold:
    """Locate the threshold between decided samples ``a`` (unstable: ``unstable_a``) and ``b``
    (the other state); ``w_start``: the crossing mode's frequency at the unstable one."""
    cond = NeutralCondition(m, (param,), fx, samples=np.array([[a], [b]]))
    w_unstable = w_start
    decided = True

    def bisect(a: float, b: float, steps: int) -> tuple[float, float, bool]:
        nonlocal w_unstable
        for _ in range(steps):
            c = 0.5 * (a + b)
            if c in (a, b):
                break
            gr = _states(m, fx, param, np.array([c]))
            st = int(gr.state[0])
            if st < 0 or st == UNDECIDED:  # outside (rounding at an edge) or sign undecided
                return a, b, False
            if (st == UNSTABLE) == unstable_a:
                a = c
            else:
                b = c
            if st == UNSTABLE:
                w_unstable = _crossing_frequency(gr.sign[0], gr.estimate[0], gr.spectrum.eigenvalues[0])
        return a, b, True

    def accept(a: float, b: float) -> tuple[float, float] | None:
        lo, hi = min(a, b), max(a, b)
        root = _newton(cond, 0.5 * (a + b), w_unstable)
        if root is None:
            return None
        slack = 2.0 * float(np.spacing(max(abs(lo), abs(hi), 1e-300)))
        if lo - slack <= root[0] <= hi + slack:
            return min(max(root[0], lo), hi), root[1]
        return None

    # to 6e-8 of the sample step, then Newton; else bisection to the last bit, Newton again
    a, b, decided = bisect(a, b, 24)
    root = accept(a, b)
    if root is None and decided:
        a, b, decided = bisect(a, b, 2000)
        root = accept(a, b)
    lo, hi = min(a, b), max(a, b)
    if root is not None:
        value, w, exact = root[0], root[1], True
    else:  # exact: a bracket at most 4 ulp wide
        value, w, exact = 0.5 * (a + b), w_unstable, hi - lo <= 4.0 * float(np.spacing(max(abs(lo), abs(hi), 1e-300)))
        if not exact:  # an interval that reaches the domain's edge (inside, the next double out not): the edge
            for end, out in ((lo, -math.inf), (hi, math.inf)):
                _, inside = check_domain(mask=True, **{**fx, param: np.array([end, math.nextafter(end, out)])})
                if inside[0] and not inside[1]:
                    value = end
    # a change of stability at the domain's edge (e.g. alpha_v = 0: every friction destabilises)
    # is polished by Newton to a rounding error on either side of it (alpha_v = -2e-27): the
    # threshold is the edge itself, never a value outside the physical domain
    _, inside = check_domain(mask=True, **{**fx, param: np.array([value])})
    if not inside[0]:
        edge_lo, edge_hi = default_bracket(param, fx)
        value = edge_lo if abs(value - edge_lo) <= abs(value - edge_hi) else edge_hi
    side = "below" if (unstable_a and a < b) or (not unstable_a and b < a) else "above"
    if exact:
        lo = hi = value
    return Threshold(float(value), float(w), side, float(lo), float(hi), bool(exact))


def threshold_crossings(
    param: str,
    *,
    model: str | LinearModel = "sliding",
    bracket: Sequence[float] | None = None,
    samples: int = 257,
    **fixed: Any,
) -> list[Threshold]:
    """Every change of stability as ``param`` varies: value, neutral frequency and unstable side.

    The records behind :func:`thresholds` (which returns their values only); the method is the
    module's.

    Parameters
    ----------
    param : {"q", "fr_inv", "sigma", "alpha_v", "mu"}
        The parameter varied.
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"} or LinearModel
        Eqs. (8)-(9) or eq. (11).
    bracket : pair of float, optional
        Range searched (inside the physical domain); default :func:`default_bracket`.
    samples : int
        Points of each of the uniform and geometric sampling grids (3 to ``1e6``).
    **fixed
        All other parameters of the model (``mu`` defaults to 2.28).

    Returns
    -------
    list of Threshold
        Sorted by value: the value, the frequency of the neutral mode there, on which side
        (``"below"`` or ``"above"`` the value) the state is unstable, and the bracket
        ``lower``, ``upper`` that holds the change of sign with ``exact`` (False: the value is
        only known to lie in the bracket, its midpoint given). Empty if the stability never
        changes.

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
    return _crossings(param, model, bracket, samples, fixed)[0]


def thresholds(
    param: str,
    *,
    model: str | LinearModel = "sliding",
    bracket: Sequence[float] | None = None,
    samples: int = 257,
    return_details: bool | None = None,
    **fixed: Any,
) -> np.ndarray:
    """All values of ``param`` at which the leading growth rate changes sign, sorted.

    Parameters
    ----------
    param, model, bracket, samples
        As :func:`threshold_crossings`.
    return_details : bool, optional
        Deprecated (a ``DeprecationWarning``; removed in the next release): ``True`` returned
        the :class:`Threshold` records instead of the values, which is now
        :func:`threshold_crossings`.
    **fixed
        As :func:`threshold_crossings`.

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
        warnings.warn(
            "thresholds(return_details=...) is deprecated and will be removed in the next release: "
            "thresholds() returns the values; threshold_crossings() returns the Threshold records "
            "(value, frequency, unstable side)",
            DeprecationWarning,
            stacklevel=2,
        )
    found = threshold_crossings(param, model=model, bracket=bracket, samples=samples, **fixed)
    _inexact_warning(found, param)
    if return_details:  # the deprecated return type, until the keyword is removed
        return found  # type: ignore[return-value]
    return np.array([t.value for t in found])


def _hidden_pairs(
    m: LinearModel, fx: Mapping[str, float], param: str, x: np.ndarray, state: np.ndarray, g: np.ndarray
) -> list[tuple[float, float, float]]:
    """Pairs of crossings between two samples (a neutral curve folding back there).

    Where the growth estimate ``g`` of the decided, not unstable samples has a local maximum
    whose parabola through the three samples comes within its own variation of zero, the
    maximum is refined (bounded Brent, :func:`scipy.optimize.minimize_scalar`, to ``1e-13``
    relative). Returns ``(a, x_max, b)`` for each refined maximum where a mode grows: the window
    ``(a, b)`` holds two thresholds, one on each side of ``x_max``.
    """
    out = []
    quiet = (state == STABLE) | (state == MARGINAL)
    for k in range(1, len(x) - 1):
        if not (quiet[k - 1] and quiet[k] and quiet[k + 1]) or not (g[k] >= g[k - 1] and g[k] >= g[k + 1]):
            continue
        if not np.all(np.isfinite(g[k - 1 : k + 2])) or g[k] >= 0:
            continue
        rise = max(g[k] - g[k - 1], g[k] - g[k + 1])
        if -g[k] > 4.0 * rise:  # far below zero for its curvature: no crossing nearby
            continue
        a, b = float(x[k - 1]), float(x[k + 1])
        from scipy.optimize import minimize_scalar  # here: most thresholds never refine (0.5 s import)

        res = minimize_scalar(
            # the largest growth estimate over the modes not neutral by structure (-inf if none)
            lambda s: -float(np.max(_states(m, fx, param, np.array([s])).estimate[0])),
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-13 * max(1.0, abs(b - a), abs(a), abs(b))},
        )
        if -res.fun > 0:
            out.append((a, float(res.x), b))
    return out


def _search(m: LinearModel, fx: Mapping[str, float], param: str, lo: float, hi: float, n: int):
    """Every threshold in ``[lo, hi]`` (module docstring) and the states of the samples."""
    g = (hi - lo) * np.geomspace(1e-8, 1.0, n)
    x = np.unique(np.concatenate([np.linspace(lo, hi, n), lo + g, hi - g]))
    gr = _states(m, fx, param, x)
    keep = gr.state >= 0
    x, state = x[keep], gr.state[keep]
    sign, estimate, ev = gr.sign[keep], gr.estimate[keep], gr.spectrum.eigenvalues[keep]
    found = []
    decided = np.nonzero(state != UNDECIDED)[0]
    unstable = state == UNSTABLE
    for i, j in itertools.pairwise(decided):
        if unstable[i] != unstable[j]:
            k = i if unstable[i] else j
            w0 = _crossing_frequency(sign[k], estimate[k], ev[k])
            found.append(_polish(m, fx, param, float(x[i]), float(x[j]), bool(unstable[i]), w0))
    # two crossings between neighbouring samples (near a fold of the neutral curve): the
    # sign does not change from sample to sample, the growth rate's maximum does
    for a, xm, b in _hidden_pairs(m, fx, param, x, state, np.max(estimate, axis=-1)):
        gm = _states(m, fx, param, np.array([xm]))
        if gm.state[0] == UNSTABLE:
            w0 = _crossing_frequency(gm.sign[0], gm.estimate[0], gm.spectrum.eigenvalues[0])
            found.append(_polish(m, fx, param, a, xm, False, w0))
            found.append(_polish(m, fx, param, b, xm, False, w0))
    found.sort(key=lambda t: t.value)
    return found, state


def _inexact_warning(found: Sequence[Threshold], param: str) -> None:
    """Warn about thresholds known only to an interval (``exact = False``)."""
    loose = [t for t in found if not t.exact]
    if loose:
        listed = ", ".join(f"[{t.lower!r}, {t.upper!r}]" for t in loose)
        warnings.warn(
            f"{len(loose)} threshold(s) in {param} known only to an interval (the sign of the growth "
            f"rate could not be decided inside it; the value given is its midpoint): {listed}",
            UserWarning,
            stacklevel=3,
        )


def _no_threshold_state(state: np.ndarray, quiet: str | None = None) -> str:
    """What holds throughout a range without a change of sign (for the messages); ``quiet``,
    if given, names every state that is not unstable."""
    n = state.size
    undecided = int((state == UNDECIDED).sum())
    if undecided == n:
        return (
            "within rounding of neutral (the sign of the leading growth rate cannot be decided at "
            "any sample; marginal to working precision)"
        )
    rest = state[state != UNDECIDED]
    names = ((UNSTABLE, "unstable"), (STABLE, "stable"), (MARGINAL, "marginal (neutrally stable)"))
    what = next((name for flag, name in names if (rest == flag).all()), "stable or marginal")
    if quiet is not None and what != "unstable":
        what = quiet
    if undecided:
        return (
            f"{what} wherever the sign can be decided (the sign of the leading growth rate cannot be "
            f"decided at {undecided} of {n} samples)"
        )
    return what


def threshold(
    param: str,
    *,
    model: str | LinearModel = "sliding",
    bracket: Sequence[float] | None = None,
    samples: int = 257,
    **fixed: Any,
) -> float:
    """The value of ``param`` at which the leading growth rate changes sign.

    Parameters
    ----------
    param : {"q", "fr_inv", "sigma", "alpha_v", "mu"}
        The parameter varied; all others are fixed.
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"} or LinearModel
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
        The threshold, to a relative backward error of the neutral condition ``~1e-16`` (each
        of its two rows). Should the sign of the growth rate be undecidable over more than a
        few ulp and Newton's method fail there, the midpoint of the interval that holds the
        change of sign, with a ``UserWarning`` giving the interval
        (:func:`threshold_crossings` returns it as ``lower``, ``upper``, ``exact = False``).

    Raises
    ------
    ValueError
        If there is no sign change in the bracket (the message says whether the state is
        stable, marginal or unstable throughout, or at how many samples the sign cannot be
        decided, and the range searched), or several (the message lists them; use a narrower
        ``bracket`` or :func:`thresholds`).

    Examples
    --------
    >>> import stability
    >>> round(stability.threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5), 12)  # (1 - mu q^2)/(1 + q)
    1.085777777778
    """
    t = _one_threshold(param, model, bracket, samples, fixed)
    _inexact_warning([t], param)
    return t.value


def _one_threshold(
    param: str, model: str | LinearModel, bracket: Sequence[float] | None, samples: Any, fixed: Mapping[str, Any]
) -> Threshold:
    """The record behind :func:`threshold` (and ``tippe threshold``): exactly one threshold in
    the bracket, or the errors of :func:`threshold`."""
    found, state, m, fx, (lo, hi) = _crossings(param, model, bracket, samples, fixed)
    given = ", ".join(f"{k} = {v:g}" for k, v in fx.items())
    if not found:
        raise InputError(
            f"no threshold in {param}: the {m.name} model is {_no_threshold_state(state)} "
            f"throughout {param} in [{lo:.6g}, {hi:.6g}] ({given})"
        )
    if len(found) > 1:
        listed = ", ".join(f"{t.value:.12g} (unstable {t.unstable_side})" for t in found)
        raise InputError(
            f"{len(found)} thresholds in {param} in [{lo:.6g}, {hi:.6g}] ({given}): "
            f"{listed}; pass bracket=(lo, hi) around one, or use stability.thresholds"
        )
    return found[0]


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
    exact : bool
        True if the spin is the root of the neutral condition (or known to a few ulp); False if
        the change of sign is only known to lie in ``spin_interval`` (``spin`` its midpoint in
        ``fr_inv``).
    spin_interval : tuple of float
        ``(low, high)`` spin rates (rad/s) between which the change of sign lies (both equal
        to ``spin`` to rounding when ``exact``).
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
    exact: bool = True
    spin_interval: tuple[float, float] = (math.nan, math.nan)


class _SpinScaled(LinearModel):
    """A model whose ``alpha_v`` follows the spin: ``alpha_v = k sqrt(fr_inv)`` (fixed mu_v).

    With ``alpha_v = mu mu_v g / Omega`` and ``Omega = sqrt(g / (R fr_inv))``:
    ``alpha_v = mu mu_v sqrt(g R) sqrt(fr_inv)``.
    """

    def __init__(self, base: LinearModel, k: float):
        self.base = base
        self.k = k
        self.name = f"{base.name} (alpha_v = {k:.6g} sqrt(fr_inv))"
        self.parameters = tuple(p for p in base.parameters if p != "alpha_v")
        for attr in ("equations", "state", "n_modes", "description"):
            setattr(self, attr, getattr(base, attr))

    def _p(self, params: dict) -> dict:
        return {**params, "alpha_v": self.k * np.sqrt(np.abs(np.asarray(params["fr_inv"], float)))}

    def matrices(self, **params):
        return self.base.matrices(**self._p(params))

    def coefficients(self, **params):
        return self.base.coefficients(**self._p(params))


class _NoTransition(InputError):
    """No change of stability in the spin range searched (the message says which state holds)."""


class CriticalSpins(NamedTuple):
    """The critical spins of both orientations of a top (``critical_spin(..., orientation="both")``).

    Attributes
    ----------
    upright, inverted : CriticalSpin or None
        None for an orientation whose stability does not change in the range searched; the
        reason is then in ``reasons``.
    reasons : dict
        Orientation -> why it has no critical spin (empty when both have one).
    """

    upright: CriticalSpin | None
    inverted: CriticalSpin | None
    reasons: dict[str, str]


def critical_spin(
    top: Any,
    model: str | LinearModel = "sliding",
    orientation: str = "upright",
    *,
    alpha_v: float = 0.5,
    fr_inv_range: Sequence[float] = (1e-6, 1e4),
    samples: int = 257,
) -> CriticalSpin | CriticalSpins:
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
    orientation : {"upright", "inverted", "both"}
        ``"inverted"`` uses ``top.inverted()`` (``q -> -q``); ``"both"`` answers for the two
        (what ``tippe threshold spin`` prints by default).
    alpha_v : float
        Viscous parameter used when ``top.mu_v`` is None (sliding model only).
    fr_inv_range : pair of float
        Range of ``fr_inv`` searched (``0 < lo < hi``): spins between ``top.spin_rate(hi)``
        and ``top.spin_rate(lo)``.
    samples : int
        See :func:`thresholds`.

    Returns
    -------
    CriticalSpin or CriticalSpins
        For the transition at the highest spin (the one above which the state no longer
        changes); all transitions are in ``transitions``. With ``orientation="both"``, a
        :class:`CriticalSpins` holding one per orientation (None for an orientation without a
        transition in the range, with the reason in ``reasons``).

    Raises
    ------
    ValueError
        Unknown orientation, or no change of stability in the range (the message says which
        state holds throughout, or at how many samples the sign cannot be decided, and the spin
        range in rad/s and rpm); with ``"both"``, only if neither orientation has one.
    TypeError
        If ``top`` is not a :class:`stability.Top`.
    """
    from ..top import Top

    if not isinstance(top, Top):
        raise ParameterTypeError(f"top must be a stability.Top, got {type(top).__name__}")
    check_choice("orientation", orientation, ("upright", "inverted", "both"))
    if orientation == "both":
        found_: dict[str, CriticalSpin | None] = {}
        reasons: dict[str, str] = {}
        for o in ("upright", "inverted"):
            try:
                found_[o] = critical_spin(top, model, o, alpha_v=alpha_v, fr_inv_range=fr_inv_range, samples=samples)
            except _NoTransition as e:
                found_[o], reasons[o] = None, str(e)
        if len(reasons) == 2:
            raise InputError("; ".join(reasons.values()))
        return CriticalSpins(upright=found_["upright"], inverted=found_["inverted"], reasons=reasons)
    samples = _samples_checked(samples)
    lo, hi = check_range("fr_inv_range", fr_inv_range)
    if not lo > 0:
        raise DomainError(f"fr_inv_range = ({lo:g}, {hi:g}) is outside the allowed range: 0 < lo < hi")
    t = top.inverted() if orientation == "inverted" else top
    base = get_model(model)
    fixed: dict[str, float] = {k: getattr(t, k) for k in ("q", "sigma", "mu") if k in base.parameters}
    m: LinearModel = base
    if "alpha_v" in base.parameters:
        if t.mu_v is not None:
            k = t.mu * t.mu_v * math.sqrt(t.g * t.radius)
            m = _SpinScaled(base, k)
            friction = f"viscous, mu_v = {t.mu_v:g} s/m: alpha_v = mu mu_v g / Omega = {k:.6g} sqrt(fr_inv)"
        else:
            a = as_scalar("alpha_v", alpha_v)
            check_domain(scalar=True, alpha_v=a)
            fixed["alpha_v"] = a
            friction = (
                f"viscous, alpha_v = {a:g} held fixed (no mu_v given); the threshold of the "
                "sliding model is the same for every alpha_v > 0"
            )
    else:
        friction = f"none: the {base.name} model has no friction parameter"
    found, state = _search(m, fixed, "fr_inv", lo, hi, samples)
    spins = sorted(float(t.spin_rate(th.value)) for th in found)
    if not found:
        what = _no_threshold_state(state, quiet="not unstable (stable or neutrally stable)")
        s_lo, s_hi = t.spin_rate(hi), t.spin_rate(lo)
        raise _NoTransition(
            f"the {orientation} {base.name} top is {what} at every spin from "
            f"{s_lo:.6g} to {s_hi:.6g} rad/s ({s_lo * 60 / (2 * math.pi):.6g} to "
            f"{s_hi * 60 / (2 * math.pi):.6g} rpm); no critical spin there"
        )
    th = found[0]  # smallest fr_inv = highest spin
    _inexact_warning([th], "fr_inv (the critical spin)")
    spin = float(t.spin_rate(th.value))
    a_v = fixed.get("alpha_v", float(t.alpha_v(spin)) if m is not base else None)
    interval = (float(t.spin_rate(th.upper)), float(t.spin_rate(th.lower)))
    return CriticalSpin(
        orientation=orientation,
        spin=spin,
        rpm=spin * 60.0 / (2.0 * math.pi),
        fr_inv=th.value,
        frequency=th.frequency,
        unstable_above=(th.unstable_side == "below"),
        alpha_v=a_v,
        friction=friction,
        transitions=tuple(spins),
        exact=th.exact,
        spin_interval=interval,
    )
