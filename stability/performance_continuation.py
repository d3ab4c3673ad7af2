"""Work-precision of the continuation: step-size settings against the exact fold.

Problem (the sliding model, eq. 11): the neutral curve in the ``(q, sigma)`` plane at
``fr_inv = 0``, ``alpha_v = 0.5``, ``mu = 2.28``, over the whole physical domain. There the
neutral condition has a closed form (tests/test_neutral.py): the curve is
``sigma = (1 - mu q^2) / (1 + q)`` and its fold (the largest sigma on it, the paper's
``sigma ~ 1.14`` of Figs. 3c-d) is at ``q* = -1 + sqrt(1 - 1/mu)``,
``sigma* = 2 (mu - sqrt(mu (mu - 1)))``.

Measured, per traced curve (best of ``repeat`` runs after a warm-up):

* ``continuation.neutral_curve`` at several ``(max_step, max_angle)`` settings (the engine's
  step controls; the default is ``(0.05, 0.1)``): the whole call (start points from a 25 x 25
  atlas, both directions, fold and domain edges located, the dataset and its LAPACK check).
  Errors: the located fold, ``max(|q - q*|, |sigma - sigma*|)``, and the curve between the
  points, the largest ``|sigma - sigma_ref(q)|`` over the dense output
  (:func:`continuation.dense`, cubic Hermite, 32 samples per step);
* the baseline, ``scipy.optimize.brentq`` per column: ``N`` columns ``q_j`` across the domain,
  brentq in sigma on ``[1e-9, 2 (1 - mu q_j^2)]`` on the leading growth rate (the largest
  ``Re s`` over the modes that are not structurally zero, from :func:`stability.spectrum`, the
  default method), ``xtol = 1e-14``; the curve a cubic spline through the column roots
  (not-a-knot), its error over 20 samples per column interval (over the columns' span only,
  which favours the columns), the fold the spline's maximum.

This is the measuring code of ``benchmarks/bench_neutral.py`` (the same problem, settings and
error definitions), as a suite of :data:`stability.performance.SUITES`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .performance import CONTINUATION_TITLE, FOLD_TARGET, WorkPrecision, best_time

__all__ = ["MU", "ALPHA_V", "Q_STAR", "SIGMA_STAR", "FOLD_TARGET", "SETTINGS", "COLUMNS", "sigma_ref",
           "trace", "continuation_errors", "leading_growth_rate", "columns_in_sigma", "column_errors",
           "continuation_work_precision", "CONTINUATION_TITLE"]

#: the problem: scaled mass and viscous friction (Fig. 3), fr_inv = 0
MU, ALPHA_V = 2.28, 0.5
#: the fold of the neutral curve, closed form
Q_STAR = -1.0 + math.sqrt(1.0 - 1.0 / MU)
SIGMA_STAR = 2.0 * (MU - math.sqrt(MU * (MU - 1.0)))
#: (max_step, max_angle) settings; the first is the engine's default
SETTINGS: tuple[tuple[float, float], ...] = ((0.05, 0.1), (0.1, 0.2), (0.2, 0.3), (0.4, 0.6))
#: column counts of the brentq baseline
COLUMNS: tuple[int, ...] = (10, 15, 25, 50, 100, 200, 400)
DEFAULT_SETTING = (0.05, 0.1)


def sigma_ref(q: np.ndarray) -> np.ndarray:
    """The neutral curve at ``fr_inv = 0``, ``sigma = (1 - mu q^2) / (1 + q)`` (closed form)."""
    q = np.asarray(q, dtype=float)
    return (1.0 - MU * q * q) / (1.0 + q)


def _check_setting(max_step: float, max_angle: float) -> None:
    if not (isinstance(max_step, (int, float)) and 0 < max_step <= 1):
        raise ValueError(f"max_step = {max_step!r} must lie in (0, 1] (arclength in the scaled ranges)")
    if not (isinstance(max_angle, (int, float)) and 0 < max_angle < math.pi / 2):
        raise ValueError(f"max_angle = {max_angle!r} must lie in (0, pi/2) radians")


def trace(max_step: float, max_angle: float) -> Any:
    """The whole ``continuation.neutral_curve`` call for the problem at one step setting.

    Parameters
    ----------
    max_step : float
        Largest continuation step, in (0, 1] (arclength in the ranges scaled to 1).
    max_angle : float
        Largest turn of the tangent per step, in (0, pi/2) radians.

    Returns
    -------
    xarray.Dataset
        The traced curve (:func:`continuation.neutral_curve`).
    """
    import continuation

    _check_setting(max_step, max_angle)
    return continuation.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=ALPHA_V, mu=MU),
                                      max_step=max_step, max_angle=max_angle)


def continuation_errors(ds: Any, samples: int = 32) -> dict[str, float]:
    """Errors of a traced curve against the closed form.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`trace`.
    samples : int
        Dense-output samples per step.

    Returns
    -------
    dict
        ``points``; ``point``: largest ``|sigma - sigma_ref(q)|`` at the traced points;
        ``fold``: ``max(|q - q*|, |sigma - sigma*|)`` of the located fold (inf if none);
        ``dense``: the largest ``|sigma - sigma_ref(q)|`` over the dense output.
    """
    import continuation

    q, s = ds.q.values, ds.sigma.values
    kinds = ds.kind.values
    folds = np.nonzero(kinds == "fold")[0]
    fold = (max(abs(float(q[folds[0]]) - Q_STAR), abs(float(s[folds[0]]) - SIGMA_STAR)) if folds.size
            else math.inf)
    d = continuation.dense(ds, samples)
    return {"points": int(ds.sizes["point"]), "point": float(np.max(np.abs(s - sigma_ref(q)))), "fold": fold,
            "dense": float(np.max(np.abs(d.sigma.values - sigma_ref(d.q.values))))}


def leading_growth_rate(q: float, sigma: float) -> float:
    """Largest ``Re s`` of the sliding model at ``fr_inv = 0`` over the modes that are not
    structurally zero (the kernel's structural zero root is exactly 0: it is dropped)."""
    from .spectra import spectrum

    ev = spectrum("sliding", q=q, fr_inv=0.0, sigma=sigma, alpha_v=ALPHA_V, mu=MU).eigenvalues
    return float(np.delete(ev, np.argmin(np.abs(ev))).real.max())


def columns_in_sigma(n: int) -> np.ndarray:
    """The brentq-per-column baseline: ``(q_j, sigma_j)`` on the curve for ``n`` columns.

    Parameters
    ----------
    n : int
        Columns ``q_j``, evenly spaced inside ``|q| < 1/sqrt(mu)`` (at least 4, for the spline).

    Returns
    -------
    numpy.ndarray, shape (m, 2)
        The columns where the leading growth rate changes sign, with the root in sigma.
    """
    from scipy.optimize import brentq

    if not (isinstance(n, (int, np.integer)) and n >= 4):
        raise ValueError(f"n = {n!r} columns: need an integer >= 4 (a cubic spline through them)")
    b = 1.0 / math.sqrt(MU)
    out = []
    for q in np.linspace(-b, b, n + 2)[1:-1]:
        lo, hi = 1e-9, 2.0 * (1.0 - MU * q * q) * (1.0 - 1e-12)
        if leading_growth_rate(q, lo) * leading_growth_rate(q, hi) < 0:
            out.append((q, brentq(lambda s: leading_growth_rate(q, s), lo, hi, xtol=1e-14, rtol=1e-15)))
    return np.array(out)


def column_errors(pts: np.ndarray) -> dict[str, float]:
    """Errors of the columns' curve (cubic spline) and fold (the spline's maximum).

    Returns
    -------
    dict
        ``point`` (at the column roots), ``cubic`` (the spline, 20 samples per interval) and
        ``fold`` (``max(|q - q*|, |sigma - sigma*|)``).
    """
    from scipy.interpolate import CubicSpline

    q, s = pts[:, 0], pts[:, 1]
    qq = np.linspace(q[0], q[-1], 20 * len(q))
    spline = CubicSpline(q, s)
    crit = spline.derivative().roots(extrapolate=False)
    k = int(np.argmax(spline(crit)))
    return {"point": float(np.max(np.abs(s - sigma_ref(q)))),
            "cubic": float(np.max(np.abs(spline(qq) - sigma_ref(qq)))),
            "fold": max(abs(float(crit[k]) - Q_STAR), abs(float(spline(crit[k])) - SIGMA_STAR))}


def continuation_work_precision(repeat: int = 5, quick: bool = False,
                                settings: tuple[tuple[float, float], ...] = SETTINGS,
                                columns: tuple[int, ...] = COLUMNS) -> list[WorkPrecision]:
    """Work-precision points of the continuation settings and of the brentq baseline.

    Parameters
    ----------
    repeat : int
        Timed runs per configuration (the best is kept), after one warm-up.
    quick : bool
        Fewer repeats (at most 2) and columns only up to 100.
    settings : tuple of (max_step, max_angle)
        Continuation settings.
    columns : tuple of int
        Column counts of the baseline.

    Returns
    -------
    list of WorkPrecision
        ``error``: the fold error; ``extra["curve_error"]``: the curve's error (dense output
        or spline); ``extra["points"]``: traced points or columns found.
    """
    if quick:
        repeat = min(repeat, 2)
        columns = tuple(n for n in columns if n <= 100)
    for st in settings:
        _check_setting(*st)
    results = []
    for st in settings:
        t, ds = best_time(lambda: trace(*st), repeat)
        e = continuation_errors(ds)
        results.append(WorkPrecision(
            "continuation", t, e["fold"], 1, default=st == DEFAULT_SETTING, series="continuation",
            setting=f"max_step {st[0]:g}, max_angle {st[1]:g}",
            note="continuation.neutral_curve, the whole call (start, both directions, fold, edges)",
            extra={"curve_error": e["dense"], "points": e["points"], "point_error": e["point"],
                   "max_step": st[0], "max_angle": st[1]}))
    for n in columns:
        t, pts = best_time(lambda: columns_in_sigma(n), repeat)
        e = column_errors(pts)
        results.append(WorkPrecision(
            "brentq per column", t, e["fold"], 1, baseline=True, series="brentq per column", setting=f"N = {n}",
            note="scipy.optimize.brentq in sigma per column q_j (xtol 1e-14), cubic spline, fold its maximum",
            extra={"curve_error": e["cubic"], "points": int(len(pts)), "point_error": e["point"], "columns": n}))
    return results
