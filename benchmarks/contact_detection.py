"""What watching the normal force costs a run: A/B in one process, the same integration with and
without ``watch_contact`` (:func:`stability.nonlinear.integrators.integrate`).

The runs keep their contact to the end (the paper's Fr^-1 = 0.3 run, a sliding run with
Coulomb friction and a rolling run on the LSODA path), so both arms do the same steps and the
ratio is the price of the check after every step (the compiled path: a dozen flops from the
state and its FSAL derivative; scipy's path: the closed-form lower bound of ``N``, ~40 flops,
in batches of ``integrators.WATCH_BATCH`` steps by one compiled call, the 6 x 6 solve only
where the bound is not positive). On the scipy path two more arms: one compiled call per step,
and the batched check without the screen (the right-hand side at every step, the previous
check, :func:`_first_event_solved`). A last line times a run
that loses contact (the issue's reproducer) to its event, and the same integration unwatched
to the same time, for the cost of locating the zero. Accuracy: the event time against the
independent DOP853 reference of tests/test_contact_loss.py agrees to ~1e-11 relative at rtol
1e-9 (that test prints nothing; run it for the check).

Usage: python benchmarks/contact_detection.py
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import LSODA
from suites.timing import best_times

from stability.jit import njit
from stability.nonlinear import integrators
from stability.nonlinear.integrators import event_value_at, integrate
from stability.nonlinear.kernels import CODES, rhs
from stability.nonlinear.runs import initial_state, model_parameter_vector
from stability.nonlinear.scene import INITIAL_CONDITIONS


@njit(cache=True)
def _first_event_solved(code, ts, ys, p, watch, c_stick):
    """The batched check without the closed-form screen: the right-hand side (6 x 6 solve) at
    every row (the check before the screen)."""
    for i in range(ts.shape[0]):
        if event_value_at(code, ts[i], ys[i], p, watch, c_stick) <= 0.0:
            return i
    return -1


_SCREENED = integrators.first_event
_BATCH = integrators.WATCH_BATCH


def _case(model, t_end, method, omega, k, velocity=None, **params):
    _, p = model_parameter_vector(model, params)
    y0 = initial_state(model, omega, k, velocity)
    t_eval = np.linspace(0.0, t_end, int(t_end / 0.1) + 1)

    def run(watch, batch=_BATCH, screen=True):
        def go():
            integrators.WATCH_BATCH = batch  # scipy's path: steps per batched check of N
            integrators.first_event = _SCREENED if screen else _first_event_solved
            try:
                return integrate(model, y0, t_eval, p, method=method, rtol=1e-9, atol=1e-12, watch_contact=watch)
            finally:
                integrators.WATCH_BATCH, integrators.first_event = _BATCH, _SCREENED

        return go

    return run


def _check_alone(model, t_end, omega, k, velocity=None, **params):
    """CPU seconds per accepted step of the batched check alone (``first_event`` on the run's own
    accepted LSODA states, batches of ``WATCH_BATCH``), screened and solved, best of 51: a tight
    compiled loop, steadier on a loaded machine than the difference of two runs."""
    code = CODES[model]
    _, p = model_parameter_vector(model, params)
    y0 = initial_state(model, omega, k, velocity)
    solver = LSODA(lambda t, y: rhs(code, t, y, p), 0.0, y0, t_end, rtol=1e-9, atol=1e-12)
    ts, ys = [], []
    while solver.status == "running":
        solver.step()
        ts.append(solver.t)
        ys.append(solver.y)
    ts, ys = np.array(ts), np.array(ys)
    b = integrators.WATCH_BATCH
    out = {}
    for arm, fn in (("screened", _SCREENED), ("solved", _first_event_solved)):
        best = np.inf
        for _ in range(51):
            t0 = time.process_time()
            for i in range(0, ts.size, b):
                assert fn(code, ts[i : i + b], ys[i : i + b], p, 1, -2.0) == -1
            best = min(best, time.process_time() - t0)
        out[arm] = best / ts.size
    return out, ts.size


def _cpu_best(arms, repeat):
    """Minimum CPU seconds of this process per call of each arm (interleaved rounds): on a shared
    machine the CPU time of the process is steadier than the wall time."""
    best = dict.fromkeys(arms, np.inf)
    for _ in range(repeat):
        for name, fn in arms.items():
            t0 = time.process_time()
            fn()
            best[name] = min(best[name], time.process_time() - t0)
    return best


def main() -> None:
    """Print, per case, the best time of each arm and the ratio watched / unwatched."""
    ic = INITIAL_CONDITIONS[0.3]
    k_lost = np.array([0.3, 0.0, 1.0]) / np.hypot(0.3, 1.0)
    cases = {
        "paper Fr^-1 = 0.3, sliding, dopri5, t = 1000 (contact holds)": _case(
            "sliding",
            1000.0,
            "dopri5",
            ic["omega"],
            ic["k"],
            ic.get("velocity"),
            q=-0.1,
            fr_inv=0.3,
            sigma=1.0,
            alpha_v=0.5,
        ),
        "paper Fr^-1 = 0.3, rolling, dopri5, t = 1000 (contact holds)": _case(
            "rolling", 1000.0, "dopri5", ic["omega"], ic["k"], None, q=-0.1, fr_inv=0.3, sigma=1.0
        ),
        "Coulomb alpha_k = 0.05, sliding, LSODA, t = 200 (contact holds)": _case(
            "sliding",
            200.0,
            "LSODA",
            ic["omega"],
            ic["k"],
            ic.get("velocity"),
            q=-0.1,
            fr_inv=0.3,
            sigma=1.0,
            alpha_v=0.5,
            alpha_k=0.05,
        ),
        "paper Fr^-1 = 0.3, rolling, LSODA, t = 200 (contact holds)": _case(
            "rolling", 200.0, "LSODA", ic["omega"], ic["k"], None, q=-0.1, fr_inv=0.3, sigma=1.0
        ),
    }
    alone = {  # the scipy cases again, for the check alone
        "Coulomb alpha_k = 0.05, sliding, LSODA, t = 200 (contact holds)": lambda: _check_alone(
            "sliding",
            200.0,
            ic["omega"],
            ic["k"],
            ic.get("velocity"),
            q=-0.1,
            fr_inv=0.3,
            sigma=1.0,
            alpha_v=0.5,
            alpha_k=0.05,
        ),
        "paper Fr^-1 = 0.3, rolling, LSODA, t = 200 (contact holds)": lambda: _check_alone(
            "rolling", 200.0, ic["omega"], ic["k"], None, q=-0.1, fr_inv=0.3, sigma=1.0
        ),
    }
    for name, run in cases.items():
        arms = {"watched": run(True), "unwatched": run(False)}
        if "LSODA" in name:  # scipy's path: batched screened check (default) against the others
            arms["watched every step"] = run(True, 1)
            arms["watched, no screen"] = run(True, screen=False)
        times, res = best_times(arms, repeat=21)
        assert np.isnan(res["watched"].event_time)
        extra = "".join(
            f", {arm} {times[arm] * 1e3:.3f} ms (ratio {times[arm] / times['unwatched']:.3f})"
            for arm in ("watched every step", "watched, no screen")
            if arm in times
        )
        print(
            f"{name}: watched {times['watched'] * 1e3:.3f} ms, unwatched {times['unwatched'] * 1e3:.3f} ms, "
            f"ratio {times['watched'] / times['unwatched']:.3f}{extra}"
        )
        cpu = _cpu_best(arms, 21)
        print(
            "    CPU time of the process (best of 21): "
            + ", ".join(f"{arm} {sec * 1e3:.3f} ms (ratio {sec / cpu['unwatched']:.3f})" for arm, sec in cpu.items())
        )
        if name in alone:
            per, steps = alone[name]()
            step = cpu["unwatched"] / res["unwatched"].naccept
            print(
                f"    the check alone ({steps} steps): screened {per['screened'] * 1e9:.0f} ns per step "
                f"({per['screened'] / step:.1%} of an unwatched step, {step * 1e6:.2f} us), "
                f"solved {per['solved'] * 1e9:.0f} ns ({per['solved'] / step:.1%})"
            )
    # the reproducer: watched to its event, unwatched to the same time
    lost = _case(
        "sliding", 50.0, "dopri5", [2.0, 0.0, 1.0], k_lost, [0.0, 0.0], q=-0.1, fr_inv=0.05, sigma=1.0, alpha_v=0.5
    )(True)
    t_ev = lost().event_time
    same = _case(
        "sliding",
        float(t_ev),
        "dopri5",
        [2.0, 0.0, 1.0],
        k_lost,
        [0.0, 0.0],
        q=-0.1,
        fr_inv=0.05,
        sigma=1.0,
        alpha_v=0.5,
    )(False)
    times, _ = best_times({"watched": lost, "unwatched": same}, repeat=15)
    print(
        f"reproducer (contact lost at t = {t_ev:.12g}): watched to the event {times['watched'] * 1e6:.1f} us, "
        f"unwatched to the same time {times['unwatched'] * 1e6:.1f} us, "
        f"ratio {times['watched'] / times['unwatched']:.3f}"
    )


if __name__ == "__main__":
    main()
