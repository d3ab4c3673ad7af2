"""Work-precision of the steady layer: the final state, the branch, the class map.

Used by ``python benchmarks/run.py --suite steady`` (:data:`suites.SUITES`). Three measurements,
each against a named baseline measured in the same run:

* **final state** (:func:`stability.final_state` by Jellett's integral) against a simulation
  long enough for the same accuracy. Cases: the thirteen long runs of
  tests/test_steady_final.py (three classes; tops that stay upright, invert, hang).
  Reference end tilt of each case: a run at ``rtol = 1e-11`` (``atol = 1e-14``) three times as
  long as the test's run, sampled every ``t / 2000``; ``t_0.01`` is the time after which it
  stays within 0.01 degree of its end. Baseline: :func:`stability.simulate` at its default
  ``rtol = 1e-9`` to ``t_0.01`` (two output times), its error measured against the reference.
  The prediction is timed twice: the whole public call (input checks, integrals, candidate
  table) and its core (the candidate table and the decision from ``(J0, E0)``,
  :func:`stability.steady.final.predict`). For the chart, the paper's case at several
  simulation lengths (a work-precision series) and the prediction.
* **branch** (:func:`continuation.steady_branch` of the paper's top, about 200 points with
  their spectra and flags) against its closed form (S3); baselines: the same 200 tilts solved
  one by one with ``scipy.optimize.brentq`` in the precession rate on the same nonlinear
  residual (stability.steady.branch_compiled.divided), with the same batched spectra and
  flags; and the engine's Python path (``compiled=False``).
* **class map**: :func:`stability.top_class` on ``1e4, 1e5, 1e6`` random tops; baseline: the
  same call per top on 2000 tops (per-top time); error: mismatches against Hugenholtz's band
  (0 is drawn at the chart's floor).

Times: the minimum wall time; the branch's three paths and the prediction's two are timed in
alternating rounds (:func:`suites.timing.best_times`), the simulations by
:func:`suites.records.best_time` (the best of ``repeat`` after a warm-up).
"""

from __future__ import annotations

import functools
import math
import time
from typing import Any

import numpy as np

from stability import execution

from .records import Panel, Suite, WorkPrecision
from .timing import best_times

__all__ = [
    "BRANCH_TARGET",
    "CASES",
    "FINAL_TARGET",
    "STEADY_TITLE",
    "branch_measurements",
    "class_map_measurements",
    "final_state_cases",
    "format_table",
    "steady_work_precision",
]

#: required accuracy of the final tilt (degrees; the issue's "at 0.01 degrees")
FINAL_TARGET = 0.01
#: required agreement of the traced branch with its closed form (the issue)
BRANCH_TARGET = 1e-12
STEADY_TITLE = (
    "steady states of the sliding top: final state by Jellett's integral vs simulation, the branch "
    "of tilted states, the class map"
)


def _start(theta_deg: float, spin: float = 1.0, transverse: float = 0.0, velocity=(0.0, 0.0)) -> dict[str, list]:
    t = math.radians(theta_deg)
    k = np.array([math.sin(t), 0.0, math.cos(t)])
    e = np.array([math.cos(t), 0.0, -math.sin(t)])
    return dict(omega=list(spin * k + transverse * e), k=list(k), velocity=list(velocity))


@functools.cache
def _cases() -> list[tuple[str, dict[str, float], dict[str, list], float]]:
    """:data:`CASES` (made on first use: the paper's initial conditions come with the nonlinear
    runs, whose import costs a second; ``tippe --help`` lists the suites without it)."""
    from stability.nonlinear.scene import INITIAL_CONDITIONS

    paper = dict(q=-0.1, sigma=1.0, alpha_v=0.5)
    return [
        ("paper Fr^-1 = 0.3 (hangs)", dict(paper, fr_inv=0.3), INITIAL_CONDITIONS[0.3], 15600),
        ("paper Fr^-1 = 0.1 (inverts)", dict(paper, fr_inv=0.1), INITIAL_CONDITIONS[0.1], 22000),
        ("paper top slow (upright)", dict(paper, fr_inv=0.6), _start(8.0, 1.0, 0.02), 1300),
        ("hangs q=-0.3 s=0.5", dict(q=-0.3, sigma=0.5, fr_inv=0.1, alpha_v=0.5), _start(3.0), 15000),
        ("hangs alpha_v=1", dict(q=-0.2, sigma=0.6, fr_inv=0.3, alpha_v=1.0), _start(10.0, 1.2, -0.03), 5600),
        ("inverts class, hangs", dict(q=-0.3, sigma=0.7, fr_inv=0.2, alpha_v=0.5), _start(5.0), 6200),
        ("never_inverts q>0 (upright)", dict(q=0.2, sigma=1.0, fr_inv=0.3, alpha_v=0.5), _start(15.0, 1.0, 0.03), 1400),
        ("hangs q>0", dict(q=0.3, sigma=0.9, fr_inv=0.5, alpha_v=0.5), _start(5.0), 400),
        ("hangs at 37.5 deg", dict(q=-0.25, sigma=0.9, fr_inv=1.0, alpha_v=0.5), _start(5.0, 1.5), 800),
        ("clockwise from 60 deg (upright)", dict(paper, fr_inv=0.3), _start(60.0, -1.0, 0.1, (0.0, 0.05)), 2200),
        ("started inverted (upright)", dict(paper, fr_inv=1.0), _start(175.0), 900),
        ("inverts fast", dict(q=-0.3, sigma=0.7, fr_inv=0.02, alpha_v=0.5), _start(5.0), 34800),
        ("fr_inv = 0 hangs", dict(q=-0.3, sigma=0.5, fr_inv=0.0, alpha_v=0.5), _start(5.0), 18800),
    ]


def __getattr__(name: str) -> Any:
    """``CASES``: (name, parameters, initial state, the test's run length), made on first use."""
    if name == "CASES":
        return _cases()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


_QUICK = (0, 2, 7)


def _settle_time(t: np.ndarray, tilt: np.ndarray, end: float, tol: float) -> float:
    bad = np.nonzero(np.abs(tilt - end) > tol)[0]
    return 0.0 if bad.size == 0 else float(t[min(bad[-1] + 1, t.size - 1)])


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def final_state_cases(repeat: int = 3, quick: bool = False) -> list[dict[str, Any]]:
    """Per case: the reference end tilt, ``t_0.01``, the simulation's cost and error to ``t_0.01``,
    and the prediction's cost and error (module docstring)."""
    from stability.nonlinear.runs import initial_state, simulate
    from stability.steady.final import final_state, predict
    from stability.steady.states import state_integrals

    rows = []
    for i, (name, params, start, t_test) in enumerate(_cases()):
        if quick and i not in _QUICK:
            continue
        t_ref = 3.0 * t_test
        ref = simulate(
            "sliding", t_end=t_ref, t_eval=np.linspace(0.0, t_ref, 2001), rtol=1e-11, atol=1e-14, **params, **start
        )
        tilt, t = ref.polar_angle.values, ref.time.values
        end = float(tilt[-1])
        t001 = max(_settle_time(t, tilt, end, FINAL_TARGET), t[1])
        sec, out = best_times(
            {"run": lambda: simulate("sliding", t_end=t001, t_eval=np.array([0.0, t001]), **params, **start)},
            repeat,
            warmup="first",
        )
        sim_time, sim = sec["run"], out["run"]
        y = initial_state("sliding", start["omega"], start["k"], start.get("velocity"))
        j0, e0 = (
            float(v[0])
            for v in state_integrals(y[:8], q=params["q"], sigma=params["sigma"], fr_inv=params["fr_inv"], mu=2.28)
        )
        times, outs = best_times(
            {"call": lambda: final_state(**params, **start), "core": lambda: predict(j0, e0, mu=2.28, **params)},
            max(repeat, 5),
            min_time=0.2,
        )
        pred_time, core_time, pred = times["call"], times["core"], outs["call"]
        rows.append(
            dict(
                name=name,
                params=params,
                reference=end,
                t_001=t001,
                sim_seconds=sim_time,
                sim_error=abs(float(sim.polar_angle[-1]) - end),
                pred_seconds=pred_time,
                core_seconds=core_time,
                pred_error=abs(pred.tilt - end),
                method=pred.method,
                kind=pred.kind,
                reference_drift=abs(float(ref.h_cg[-1] - ref.h_cg[0])) / abs(float(ref.h_cg[0])),
            )
        )
    return rows


def _paper_series(reference: float, repeat: int, quick: bool) -> list[tuple[float, float, float]]:
    """The paper's case simulated to several lengths: ``(t_end, seconds, error)``."""
    from stability.nonlinear.runs import simulate

    name, params, start, _ = _cases()[0]
    out = []
    for t_end in (4000.0, 12000.0) if quick else (2000.0, 4000.0, 7000.0, 10000.0, 13000.0, 16000.0, 20000.0):
        sec, runs = best_times(
            {"run": lambda: simulate("sliding", t_end=t_end, t_eval=np.array([0.0, t_end]), **params, **start)},
            repeat,
            warmup="first",
        )
        out.append((t_end, sec["run"], abs(float(runs["run"].polar_angle[-1]) - reference)))
    return out


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def branch_measurements(repeat: int = 5, max_step: float = 0.0155) -> dict[str, Any]:
    """The paper's branch (about 200 points with spectra and flags) by continuation (compiled
    step and Python path) and by brentq per tilt, each with its error against the closed form."""
    from scipy.optimize import brentq

    from stability.nonlinear.kernels import CODES
    from stability.steady import branch_compiled, family
    from stability.steady.branch import points_dataset, steady_branch
    from stability.steady.products import sliding_parameters

    q, sigma, fr, av, mu = -0.1, 1.0, 0.3, 0.5, 2.28

    def error(theta: np.ndarray, lam: np.ndarray) -> float:
        c = np.cos(theta)
        ref = family.precession_rate(c, q=q, sigma=sigma, fr_inv=fr, mu=mu)
        inner = np.abs(np.sin(theta)) > 1e-12
        return float(np.max(np.abs(lam[inner] - ref[inner]) / ref[inner]))

    ds = steady_branch(q=q, sigma=sigma, fr_inv=fr, alpha_v=av, mu=mu, max_step=max_step)
    n = ds.sizes["point"]
    params, p = sliding_parameters("sliding", q=q, sigma=sigma, fr_inv=fr, alpha_v=av, mu=mu)
    code, n_full = CODES["sliding"], 10
    lam_b = float(ds.precession_rate[0])
    lam_e = float(ds.precession_rate[-1])
    thetas = np.linspace(1e-3, math.pi - 1e-3, n)

    def columns():
        lam = np.empty(n)
        for i, th in enumerate(thetas):
            f = lambda la: branch_compiled.divided(th, la, p, q, code, n_full)[0]  # noqa: E731
            lam[i] = brentq(f, 0.5 * min(lam_b, lam_e), 2.0 * max(lam_b, lam_e), xtol=1e-15, rtol=8.9e-16)
        from stability.steady.branch import SteadyBranchProblem

        prob = SteadyBranchProblem(params, p)
        return lam, points_dataset(prob, np.column_stack([thetas, np.log(lam)]), ["regular"] * n, [""] * n, {})

    t, out = best_times(
        {
            "compiled": lambda: steady_branch(q=q, sigma=sigma, fr_inv=fr, alpha_v=av, mu=mu, max_step=max_step),
            "python": lambda: steady_branch(
                q=q, sigma=sigma, fr_inv=fr, alpha_v=av, mu=mu, max_step=max_step, compiled=False
            ),
            "brentq": columns,
        },
        repeat,
        min_time=1.0,
    )
    ds, ds_py, (lam_cols, _) = out["compiled"], out["python"], out["brentq"]
    return dict(
        points=n,
        compiled=(t["compiled"], error(np.radians(ds.tilt.values), ds.precession_rate.values)),
        python=(t["python"], error(np.radians(ds_py.tilt.values), ds_py.precession_rate.values)),
        brentq=(t["brentq"], error(thetas, lam_cols)),
    )


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def class_map_measurements(repeat: int = 3, quick: bool = False) -> dict[str, Any]:
    """:func:`stability.top_class` on random tops (shapes 1e4, 1e5, 1e6), and per top."""
    from stability.steady.classes import top_class

    rng = np.random.default_rng(0)
    out: dict[str, Any] = {"sizes": []}
    for n in (10_000, 100_000) if quick else (10_000, 100_000, 1_000_000):
        q = rng.uniform(-0.66, 0.66, n)
        sigma = rng.uniform(0.0, 2.0, n)
        sec, res = best_times(
            {"map": lambda: top_class(q=q, sigma=sigma, mask_unphysical=True)}, repeat, warmup="first"
        )
        sec, names = sec["map"], res["map"]
        inside = names != "outside_domain"
        gamma = (1 - 2.28 * q * q) / sigma
        hug = (q < 0) & (1 + q < gamma) & (gamma < 1 - q)
        out["sizes"].append((n, sec, int(np.sum((names == "inverts")[inside] != hug[inside]))))
    q = rng.uniform(-0.4, 0.4, 2000)
    sigma = rng.uniform(0.1, 1.5, 2000)
    t0 = time.perf_counter()
    for a, b in zip(q, sigma):
        top_class(q=float(a), sigma=float(b), mask_unphysical=True)
    out["per_top"] = (time.perf_counter() - t0) / 2000
    return out


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def steady_work_precision(repeat: int = 3, quick: bool = False) -> list[WorkPrecision]:
    """All three measurements as work-precision records (module docstring)."""
    results: list[WorkPrecision] = []
    rows = final_state_cases(repeat=repeat, quick=quick)
    for r in rows:
        results.append(
            WorkPrecision(
                "final_state (Jellett)",
                r["pred_seconds"],
                r["pred_error"],
                1,
                default=r["name"].startswith("paper Fr^-1 = 0.3"),
                series=f"final_state: {r['name']}",
                setting=r["name"],
                panel="final" if r["name"].startswith("paper Fr^-1 = 0.3") else "cases",
                note="the whole public call: checks, J0 and E0, the steady states of the level, the decision",
                extra={
                    "core_seconds": r["core_seconds"],
                    "sim_seconds_to_0.01": r["sim_seconds"],
                    "sim_error": r["sim_error"],
                    "t_0.01": r["t_001"],
                    "ratio": r["sim_seconds"] / r["pred_seconds"],
                    "ratio_core": r["sim_seconds"] / r["core_seconds"],
                    "reference": r["reference"],
                    "reference_jellett_drift": r["reference_drift"],
                },
            )
        )
    paper = next(r for r in rows if r["name"].startswith("paper Fr^-1 = 0.3"))
    results.append(
        WorkPrecision(
            "final_state core (J0, E0 -> end)",
            paper["core_seconds"],
            paper["pred_error"],
            1,
            series="final_state core",
            setting="paper Fr^-1 = 0.3",
            panel="final",
            component=True,
            note="stability.steady.final.predict: the candidates and the decision from the integrals (no input checks)",
        )
    )
    for t_end, sec, err in _paper_series(paper["reference"], repeat, quick):
        results.append(
            WorkPrecision(
                "simulate to t_end",
                sec,
                err,
                1,
                baseline=True,
                series="simulate (rtol 1e-9)",
                setting=f"t_end {t_end:g}",
                panel="final",
                note="stability.simulate of the paper's Fr^-1 = 0.3 run, default rtol 1e-9",
                extra={"t_end": t_end},
            )
        )
    b = branch_measurements(repeat=max(repeat, 7))
    for key, label, base in (
        ("compiled", "steady_branch (compiled step)", False),
        ("python", "steady_branch (engine's Python path)", True),
        ("brentq", "brentq per tilt on the nonlinear residual", True),
    ):
        sec, err = b[key]
        results.append(
            WorkPrecision(
                label,
                sec,
                err,
                b["points"],
                baseline=base,
                default=key == "compiled",
                panel="branch",
                note=f"{b['points']} points with spectra and flags",
                extra={"points": float(b["points"])},
            )
        )
    c = class_map_measurements(repeat=repeat, quick=quick)
    for n, sec, mism in c["sizes"]:
        results.append(
            WorkPrecision(
                "top_class (vectorised)",
                sec,
                float(mism),
                n,
                default=n == max(s[0] for s in c["sizes"]),
                series="top_class",
                setting=f"{n:g} tops",
                panel="classes",
                note="mismatches against Hugenholtz's band",
                extra={"tops": float(n)},
            )
        )
    for n, _, _ in c["sizes"]:
        results.append(
            WorkPrecision(
                "top_class per top (loop)",
                c["per_top"] * n,
                0.0,
                n,
                baseline=True,
                series="top_class per top",
                setting=f"{n:g} tops (2000 timed)",
                panel="classes",
                extra={"tops": float(n)},
            )
        )
    return results


def format_table(rows: list[dict[str, Any]]) -> str:
    """The per-case table of :func:`final_state_cases` (what docs/performance.md quotes)."""
    lines = [
        "final state by Jellett's integral vs a simulation to 0.01 degree (its error measured against a "
        "run at rtol 1e-11, three times as long)",
        f"{'case':<34} {'method':<8} {'kind':<9} {'end (deg)':>11} {'J err':>8} {'t_0.01':>8} {'sim s':>8} "
        f"{'sim err':>8} {'call us':>8} {'core us':>8} {'ratio':>8} {'core':>8}",
    ]
    for r in rows:
        lines.append(
            f"{r['name']:<34} {r['method']:<8} {r['kind']:<9} {r['reference']:11.5f} {r['pred_error']:8.1e} "
            f"{r['t_001']:8.0f} {r['sim_seconds']:8.3f} {r['sim_error']:8.1e} {r['pred_seconds'] * 1e6:8.0f} "
            f"{r['core_seconds'] * 1e6:8.1f} {r['sim_seconds'] / r['pred_seconds']:8.0f} "
            f"{r['sim_seconds'] / r['core_seconds']:8.0f}"
        )
    ratios = np.array([r["sim_seconds"] / r["pred_seconds"] for r in rows])
    core = np.array([r["sim_seconds"] / r["core_seconds"] for r in rows])
    lines.append(
        f"ratio simulation / final_state: min {ratios.min():.0f}, median {np.median(ratios):.0f}; "
        f"simulation / core prediction: min {core.min():.0f}, median {np.median(core):.0f}; "
        f"largest prediction error {max(r['pred_error'] for r in rows):.1e} deg"
    )
    return "\n".join(lines)


#: the suite of ``python benchmarks/run.py --suite steady`` (registered in :data:`suites.SUITES`)
SUITE = Suite(
    "steady",
    steady_work_precision,
    STEADY_TITLE,
    (
        Panel(
            "error of the final tilt against a settled reference run [deg] (the paper's Fr^-1 = 0.3 run of Sec. 3(ii))",
            "wall time per prediction or run [s]",
            select="final",
            target=FINAL_TARGET,
            title="final state: Jellett's integral vs simulations of increasing length",
        ),
        Panel(
            "largest relative error of the precession rate vs the closed form (S3)",
            "wall time per branch (~200 points, spectra and flags) [s]",
            select="branch",
            target=BRANCH_TARGET,
            title="the branch of tilted states (the paper's top)",
        ),
        Panel(
            "number of tops",
            "wall time per call [s]",
            x="tops",
            select="classes",
            title="class map: stability.top_class",
        ),
    ),
    unit="call",
    quick={"quick": True},
)
