"""Work-precision of the integrators of the nonlinear runs (:func:`stability.simulate`).

Three problems, all the sliding top (eqs. 1, 2, 4, 5, 7) with ``q = -0.1``, ``sigma = 1``,
``mu = 2.28``, ``alpha_k = 0``:

* *the paper's run* (Sec. 3(ii), ``fr_inv = 0.3``, ``alpha_v = 0.5``, the printed initial
  conditions, 650 time units sampled every 0.05): the error is that of the time of the axis'
  90-degree crossing (:func:`stability.nonlinear.scene.crossing_time`, linear interpolation between
  samples, the same for every method, so the interpolation error cancels to first order),
  against a DOP853 reference at ``rtol = 1e-13``, ``atol = 1e-16``. Methods: the compiled
  Dormand-Prince 5(4) (``dopri5``, the package's default, ``simulate(method="auto")`` at its
  default ``rtol = 1e-9``, ``atol = 1e-12``), scipy's RK45, DOP853, LSODA, Radau and BDF (all
  on the compiled right-hand side) at several ``rtol`` (``atol = 1e-3 rtol``), the paper's
  fixed-step RK4 at several steps, and the first thing a user would write, scipy RK45 calling
  the numpy right-hand side (:mod:`suites.reference`);
* *the stiff slip mode*: a linear-regime run (tilt 1e-3, spin +1, 200 time units) at large
  ``alpha_v``, where the slip decays at ``alpha_v A_C / (mu A_G)``: explicit methods are held
  to steps of ``~3 / rate`` by stability, not accuracy, so their cost grows like ``alpha_v``;
  implicit ones (Radau, BDF, LSODA's stiff mode) do not. Measured at ``rtol = 1e-6``: wall time
  and evaluations against ``alpha_v``; error: relative error of the final tilt against Radau
  at ``rtol = 1e-10``;
* *the fitted growth rate* of a validation run (:func:`stability.validate` at ``fr_inv = 0.3``,
  ``alpha_v = 0.5``: a tilt of 1e-4 along the leading eigenvector, 4 e-folding times = 628
  time units, ``log|Phi|`` fitted by least squares): relative error of the fitted growth rate
  against the same fit of a DOP853 run at ``rtol = 1e-13`` (which agrees with Radau at
  ``rtol = 1e-12`` to 2e-13), ``atol = 1e-4 rtol`` (the perturbation is 1e-4). The star is
  ``validate()``'s default (dopri5, ``rtol = 1e-11``); the baseline scipy's RK45 (what
  ``solve_ivp`` does unless told otherwise). Required: :data:`GROWTH_TARGET`.

Times are the best of ``repeat`` runs (:func:`suites.timing.best_times`, no warm-up
of its own: every method is warmed up once at the start, numba's compilation and caches). This
is the measuring code of ``benchmarks/work_precision.py`` (a thin wrapper now).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from stability import execution

from .records import Panel, Suite, WorkPrecision
from .timing import best_times

__all__ = [
    "CROSSING_TARGET",
    "FR_INV",
    "GROWTH_TARGET",
    "RK4_STEPS",
    "STIFF_ALPHA_V",
    "SUITE",
    "TOLERANCES",
    "T_END",
    "crossing_run",
    "growth_run",
    "integrator_work_precision",
    "numpy_rhs_crossing_run",
    "stiff_run",
]

#: required accuracy of the 90-degree crossing time, in time units 1/Omega: the level at which
#: docs/nonlinear.md calls the scene's run converged (2e-7 from rtol 1e-9 to 1e-13)
CROSSING_TARGET = 1e-6

#: required relative accuracy of the growth rate fitted to a validation run: the agreement of
#: the fit with the linear operator at the benchmark's point (8.8e-7), so that the integrator
#: does not decide a validation's reading (module docstring)
GROWTH_TARGET = 1e-6

#: the paper's run: fr_inv, alpha_v, final time (the crossing is at ~500), output interval
FR_INV, ALPHA_V, T_END, DT = 0.3, 0.5, 650.0, 0.05
#: rtol settings per method (atol = 1e-3 rtol), and the quick subset
TOLERANCES: dict[str, tuple[float, ...]] = {
    "dopri5": (1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11),
    "RK45": (1e-5, 1e-7, 1e-9),
    "DOP853": (1e-5, 1e-7, 1e-9, 1e-11),
    "LSODA": (1e-5, 1e-7, 1e-9),
    "Radau": (1e-4, 1e-6, 1e-8),
    "BDF": (1e-4, 1e-6, 1e-8),
}
QUICK_TOLERANCES: dict[str, tuple[float, ...]] = {
    "dopri5": (1e-6, 1e-9),
    "RK45": (1e-6,),
    "DOP853": (1e-7,),
    "LSODA": (1e-7,),
    "Radau": (1e-5,),
    "BDF": (1e-5,),
}
#: steps of the paper's fixed-step RK4 (and the quick subset)
RK4_STEPS: tuple[float, ...] = (0.4, 0.2, 0.1, 0.05, 0.025)
QUICK_RK4_STEPS: tuple[float, ...] = (0.2, 0.05)
#: rtol of the numpy-right-hand-side baseline (slow: a few runs only)
NUMPY_RHS_TOLERANCES: tuple[float, ...] = (1e-5, 1e-7)
#: alpha_v of the stiff problem; the scipy explicit methods stop at 500 (2.7M evaluations,
#: ~30 s a run, at 5000)
STIFF_ALPHA_V: tuple[float, ...] = (5.0, 50.0, 500.0, 5000.0)
QUICK_STIFF_ALPHA_V: tuple[float, ...] = (5.0, 500.0)
STIFF_EXPLICIT_SCIPY_MAX = 500.0
#: the package's default (simulate's defaults)
DEFAULT_RTOL, DEFAULT_ATOL = 1e-9, 1e-12
#: the fitted-growth-rate problem: rtol settings per method (atol = 1e-4 rtol), quick subset,
#: validate()'s default tolerance
GROWTH_TOLERANCES: dict[str, tuple[float, ...]] = {
    "dopri5": (1e-5, 1e-7, 1e-8, 1e-9, 1e-11),
    "RK45": (1e-5, 1e-7, 1e-9),
    "DOP853": (1e-5, 1e-7, 1e-9, 1e-11),
    "LSODA": (1e-5, 1e-7, 1e-9),
    "Radau": (1e-4, 1e-6, 1e-8),
    "BDF": (1e-4, 1e-6, 1e-8),
}
QUICK_GROWTH_TOLERANCES: dict[str, tuple[float, ...]] = {"dopri5": (1e-7, 1e-9), "RK45": (1e-7,), "LSODA": (1e-7,)}
VALIDATE_RTOL = 1e-11

_LABEL = {
    "dopri5": "dopri5 (compiled)",
    "RK45": "scipy RK45",
    "DOP853": "scipy DOP853",
    "LSODA": "scipy LSODA",
    "Radau": "scipy Radau",
    "BDF": "scipy BDF",
    "rk4": "RK4 fixed step (paper)",
    "numpy": "scipy RK45 + numpy RHS",
    "auto": "simulate default (auto)",
}


def _check_tol(rtol: float) -> None:
    if not (isinstance(rtol, float) and 0 < rtol < 1):
        raise ValueError(f"rtol = {rtol!r} must be a float in (0, 1)")


def crossing_run(
    method: str, rtol: float = DEFAULT_RTOL, atol: float | None = None, step: float | None = None
) -> tuple[float, int]:
    """The paper's ``fr_inv = 0.3`` run: 90-degree crossing time and right-hand-side evaluations.

    Parameters
    ----------
    method : str
        A method of :func:`stability.simulate` (``"dopri5"``, ``"rk4"``, a scipy method, ``"auto"``).
    rtol : float
        Relative tolerance, in (0, 1) (ignored by ``"rk4"``).
    atol : float, optional
        Absolute tolerance; default ``1e-3 rtol``.
    step : float, optional
        Step of ``"rk4"``.

    Returns
    -------
    (float, int)
        Crossing time (units of ``1/Omega``; NaN if the axis never reaches 90 degrees) and nfev.
    """
    from stability.nonlinear.runs import simulate
    from stability.nonlinear.scene import INITIAL_CONDITIONS, PAPER, crossing_time

    _check_tol(rtol)
    ds = simulate(
        "sliding",
        t_end=T_END,
        dt=DT,
        fr_inv=FR_INV,
        alpha_v=ALPHA_V,
        **PAPER,
        **INITIAL_CONDITIONS[FR_INV],
        method=method,
        rtol=rtol,
        atol=rtol * 1e-3 if atol is None else atol,
        step=step,
    )
    return crossing_time(ds), int(ds.attrs["nfev"])


def numpy_rhs_crossing_run(rtol: float) -> tuple[float, int]:
    """The same run by ``scipy.integrate.solve_ivp(RK45)`` on the numpy right-hand side
    (:func:`suites.reference.sliding_rhs`), ``atol = 1e-3 rtol``."""
    import xarray as xr
    from scipy.integrate import solve_ivp

    from stability.nonlinear.runs import initial_state
    from stability.nonlinear.scene import INITIAL_CONDITIONS, PAPER, crossing_time

    from .reference import sliding_rhs

    _check_tol(rtol)
    ic = INITIAL_CONDITIONS[FR_INV]
    y0 = initial_state("sliding", ic["omega"], ic["k"], ic["velocity"])
    t_eval = np.linspace(0.0, T_END, int(round(T_END / DT)) + 1)
    args = (PAPER["q"], FR_INV, PAPER["sigma"], PAPER["mu"], ALPHA_V)
    r = solve_ivp(
        lambda t, y: sliding_rhs(t, y, *args),
        (0.0, T_END),
        y0,
        method="RK45",
        t_eval=t_eval,
        rtol=rtol,
        atol=rtol * 1e-3,
    )
    k = r.y[3:6].T  # the state's axis k (stability.nonlinear.sliding.STATE), polar angle as simulate()
    polar = np.degrees(np.arccos(np.clip(k[:, 2] / np.linalg.norm(k, axis=1), -1.0, 1.0)))
    return crossing_time(xr.Dataset({"polar_angle": ("time", polar)}, coords={"time": r.t})), int(r.nfev)


def stiff_run(method: str, alpha_v: float, rtol: float = 1e-6) -> tuple[float, int, int]:
    """Linear-regime run (tilt 1e-3, spin +1, 200 time units) at large ``alpha_v``.

    Parameters
    ----------
    method : str
        A method of :func:`stability.simulate`.
    alpha_v : float
        Viscous friction parameter, > 0.
    rtol : float
        Relative tolerance, in (0, 1); ``atol = 1e-3 rtol``.

    Returns
    -------
    (float, int, int)
        Final tilt ``|k_1 + i k_2|``, nfev and the integrator's status.
    """
    from stability.nonlinear.runs import simulate

    if not (isinstance(alpha_v, float) and alpha_v > 0):
        raise ValueError(f"alpha_v = {alpha_v!r} must be a float > 0")
    _check_tol(rtol)
    ds = simulate(
        "sliding",
        t_end=200.0,
        dt=1.0,
        omega=[0.0, 0.0, 1.0],
        k=[1e-3, 0.0, 1.0],
        q=-0.1,
        fr_inv=FR_INV,
        sigma=1.0,
        alpha_v=alpha_v,
        method=method,
        rtol=rtol,
        atol=rtol * 1e-3,
        max_steps=20_000_000,
    )
    return float(np.hypot(*ds.k.values[-1, :2])), int(ds.attrs["nfev"]), int(ds.attrs["status"])


def growth_run(method: str, rtol: float = VALIDATE_RTOL) -> float:
    """Growth rate fitted to a validation run at the paper's ``fr_inv = 0.3``, ``alpha_v = 0.5``.

    Parameters
    ----------
    method : str
        ``"dopri5"`` or a scipy method (:func:`stability.validate`).
    rtol : float
        Relative tolerance, in (0, 1); ``atol = 1e-4 rtol`` (the initial tilt is 1e-4).

    Returns
    -------
    float
        The fitted growth rate ``measured_growth_rate`` (units of the spin rate).
    """
    from stability.nonlinear.scene import PAPER
    from stability.nonlinear.validation import validate

    _check_tol(rtol)
    ds = validate(
        "sliding",
        q=PAPER["q"],
        fr_inv=FR_INV,
        sigma=PAPER["sigma"],
        mu=PAPER["mu"],
        alpha_v=ALPHA_V,
        method=method,
        rtol=rtol,
        atol=rtol * 1e-4,
    )
    return float(ds.measured_growth_rate[0])


def _timed(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """:func:`~suites.timing.best_times` of one function, without warm-up (each method
    is warmed up once at the start): its best time of ``repeat`` calls and its last result."""
    best, out = best_times({"run": fn}, repeat, warmup="none")
    return best["run"], out["run"]


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def integrator_work_precision(repeat: int = 3, quick: bool = False) -> list[WorkPrecision]:
    """Work-precision points of the integrators (module docstring).

    Parameters
    ----------
    repeat : int
        Timed runs per setting, the best kept (runs longer than 2 s: one run).
    quick : bool
        A few settings per method, alpha_v 5 and 500 only, one timed run.

    Returns
    -------
    list of WorkPrecision
        Panel ``""``: the crossing-time error (``error``, time units) of the paper's run;
        panel ``"stiff"``: the stiff problem, ``extra["alpha_v"]``, error the final tilt's
        relative error; panel ``"growth"``: the fitted growth rate's relative error.
    """
    if not (isinstance(repeat, int) and repeat >= 1):
        raise ValueError(f"repeat = {repeat!r} must be an integer >= 1")
    if quick:
        repeat = 1
    tolerances = QUICK_TOLERANCES if quick else TOLERANCES
    steps = QUICK_RK4_STEPS if quick else RK4_STEPS
    for method in ("dopri5", "rk4", "RK45", "DOP853", "LSODA", "Radau", "BDF"):  # compile, load caches
        crossing_run(method, 1e-3, step=0.5)
    reference, _ = crossing_run("DOP853", 1e-13, atol=1e-16)
    results = []

    def point(method: str, label: str, t: float, tc: float, nfev: int, setting: str, **kw: Any) -> None:
        results.append(
            WorkPrecision(
                label,
                t,
                abs(tc - reference) if np.isfinite(tc) else np.inf,
                1,
                series=label,
                setting=setting,
                extra={"nfev": nfev, "crossing_time": tc, "reference": reference},
                **kw,
            )
        )

    def reps(t_first: float) -> int:
        return 1 if t_first > 2.0 else repeat

    for method, tols in tolerances.items():
        for rtol in tols:
            t, (tc, nfev) = _timed(lambda: crossing_run(method, rtol), 1)
            if reps(t) > 1:
                t, (tc, nfev) = _timed(lambda: crossing_run(method, rtol), reps(t))
            point(
                method,
                _LABEL[method],
                t,
                tc,
                nfev,
                f"rtol {rtol:g}",
                note=f"simulate(method={method!r}), atol = 1e-3 rtol",
            )
    t, (tc, nfev) = _timed(lambda: crossing_run("auto", DEFAULT_RTOL, DEFAULT_ATOL), repeat)
    point(
        "auto",
        _LABEL["dopri5"],
        t,
        tc,
        nfev,
        "simulate() defaults, rtol 1e-9",
        default=True,
        note="simulate() with its defaults (method auto -> dopri5 here)",
    )
    for h in steps:
        t, (tc, nfev) = _timed(lambda: crossing_run("rk4", step=h), repeat)
        point("rk4", _LABEL["rk4"], t, tc, nfev, f"h {h:g}", baseline=True, note="the paper's fixed-step RK4")
    for rtol in NUMPY_RHS_TOLERANCES[:1] if quick else NUMPY_RHS_TOLERANCES:
        t, (tc, nfev) = _timed(lambda: numpy_rhs_crossing_run(rtol), 1)
        point(
            "numpy",
            _LABEL["numpy"],
            t,
            tc,
            nfev,
            f"rtol {rtol:g}",
            baseline=True,
            note="solve_ivp(RK45) on the numpy right-hand side: what a user writes first",
        )

    alphas = QUICK_STIFF_ALPHA_V if quick else STIFF_ALPHA_V
    methods = ("dopri5", "RK45", "DOP853", "LSODA", "Radau", "BDF", "auto")
    for a in alphas:
        ref_tilt, _, _ = stiff_run("Radau", a, 1e-10)
        for method in methods:
            if method in ("RK45", "DOP853") and a > STIFF_EXPLICIT_SCIPY_MAX:
                continue
            t, (tilt, nfev, status) = _timed(lambda: stiff_run(method, a), 1)
            results.append(
                WorkPrecision(
                    _LABEL[method],
                    t,
                    abs(tilt - ref_tilt) / ref_tilt if status >= 0 else np.inf,
                    1,
                    default=method == "auto",
                    series=_LABEL[method],
                    setting=f"alpha_v {a:g}",
                    panel="stiff",
                    note="linear-regime run, 200 time units, rtol 1e-6; error: final tilt vs Radau rtol 1e-10",
                    extra={"alpha_v": a, "nfev": nfev, "status": status},
                )
            )

    g_ref = growth_run("DOP853", 1e-13)
    for method, tols in (QUICK_GROWTH_TOLERANCES if quick else GROWTH_TOLERANCES).items():
        for rtol in tols:
            t, g = _timed(lambda: growth_run(method, rtol), 1)
            if reps(t) > 1:
                t, g = _timed(lambda: growth_run(method, rtol), reps(t))
            results.append(
                WorkPrecision(
                    _LABEL[method],
                    t,
                    abs(g - g_ref) / abs(g_ref),
                    1,
                    series=_LABEL[method],
                    setting=f"rtol {rtol:g}",
                    panel="growth",
                    baseline=method == "RK45",
                    note="validate(method=...), atol = 1e-4 rtol; error: fitted growth rate vs DOP853 rtol 1e-13",
                    extra={"growth_rate": g, "reference": g_ref},
                )
            )
    t, g = _timed(lambda: growth_run("dopri5", VALIDATE_RTOL), repeat)
    results.append(
        WorkPrecision(
            _LABEL["dopri5"],
            t,
            abs(g - g_ref) / abs(g_ref),
            1,
            series=_LABEL["dopri5"],
            setting="validate() defaults, rtol 1e-11",
            panel="growth",
            default=True,
            note="validate() with its defaults (dopri5, rtol 1e-11, atol 1e-15)",
            extra={"growth_rate": g, "reference": g_ref},
        )
    )
    return results


#: the suite: ``python benchmarks/run.py --suite integrators``
SUITE = Suite(
    "integrators",
    integrator_work_precision,
    "nonlinear sliding top, the paper's Fr^-1 = 0.3 run (Sec. 3(ii)), the stiff slip mode and a validation "
    "run: integrators",
    (
        Panel(
            "error of the 90-degree crossing time vs DOP853 rtol 1e-13 [1/Omega]",
            "wall time per run [s]",
            target=CROSSING_TARGET,
        ),
        Panel(
            "alpha_v (stiff slip mode, linear regime, 200 time units, rtol 1e-6)",
            "wall time per run [s]",
            x="alpha_v",
            select="stiff",
            title="cost against stiffness: explicit methods' time grows like alpha_v",
        ),
        Panel(
            "relative error of the fitted growth rate vs DOP853 rtol 1e-13",
            "wall time per validation run [s]",
            select="growth",
            target=GROWTH_TARGET,
            title="validate(): growth rate fitted to a run (4 e-folds)",
        ),
    ),
    unit="run",
    compare_at=("error",),
    quick={"quick": True},
)
