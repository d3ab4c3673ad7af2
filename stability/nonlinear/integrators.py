"""Integrators for the nonlinear models: compiled Dormand-Prince, fixed-step RK4, and scipy.

* ``"dopri5"`` (default for non-stiff runs): the Dormand-Prince 5(4) pair with its free
  fourth-order continuous extension (the coefficients of scipy's ``RK45``), compiled with
  numba together with the right-hand side; error norm and step control as in Hairer, Norsett
  and Wanner, *Solving ODEs I*, Sec. II.4 (RMS norm of ``err / (atol + rtol max(|y|, |y_new|))``,
  safety 0.9, factor limits 0.2 and 10, no growth right after a rejection).
* ``"rk4"``: the classical fixed-step fourth-order Runge-Kutta the paper used (Sec. 3(ii)),
  compiled; output between steps by cubic Hermite interpolation (fourth-order accurate).
* scipy's ``solve_ivp`` methods (``"RK45"``, ``"DOP853"``, ``"Radau"``, ``"BDF"``,
  ``"LSODA"``) with the compiled right-hand side: the reference path, and the implicit path for
  stiff runs (large ``alpha_v``: a fast slip mode with rate about
  ``alpha_v A_C / (mu A_G)``). Their solver objects are stepped as ``solve_ivp`` does (same
  steps, same dense output) but with the step limit ``max_steps``, so that an explicit method
  on a stiff run stops and reports instead of running for hours (docs/hard_cases.md).

Every integrator returns the states at the requested times and the work counters.

The compiled integrators run in slices of at most :data:`SLICE_STEPS` steps (one kernel for
both, :func:`run_slice`, compiled once for each, ``dopri5_slice`` and ``rk4_slice``: the whole state of the run, step size, first-same-as-last stage, rejection flag
and counters, is carried from one slice to the next, so the steps and the results are those of
one uninterrupted call, bit for bit). Between slices the run reports its progress and checks for
an interruption (:func:`stability.interrupts.checkpoint`): Ctrl-C or SIGTERM ends a run of hours
within milliseconds, with an ordinary exception, never from inside compiled code. The kernels
hold no GIL and assign no array slices (a slice assignment makes numba compile its
shape-mismatch message formatting, seconds of compile time for nothing).

A short run (:data:`INTERPRETED_SPAN`) runs the same slices interpreted
(:func:`stability.jit.python`) unless the compiled ones are in memory: it compiles nothing; a
long one runs compiled (:mod:`stability.execution`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.jit import njit

from ..errors import InputError
from ..execution import engine, pick
from ..interrupts import checkpoint
from ..parameters import check_interval
from .kernels import CODES
from .kernels import normal_force_lower_bound as _normal_force_lower_bound
from .kernels import rhs as _model_rhs
from .parameters import FR_INV, MU, Q
from .vectors import cross

__all__ = ["COMPILED_METHODS", "SCIPY_METHODS", "STATUS_MESSAGES", "Solution", "check_tolerances", "integrate"]

COMPILED_METHODS = ("dopri5", "rk4")
SCIPY_METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA")
#: the allowed range of a run's relative and absolute tolerances (open at both ends)
TOLERANCE_RANGE = (0.0, 1.0)


def check_tolerances(**tolerances: Any) -> tuple[float, ...]:
    """The tolerances given by name (``rtol=..., atol=...``) checked against
    :data:`TOLERANCE_RANGE` (the message names the one outside), as floats in that order."""
    return tuple(check_interval(name, value, *TOLERANCE_RANGE) for name, value in tolerances.items())


# Dormand-Prince 5(4): nodes, stages, 5th-order weights, error weights, dense-output matrix
_C = np.array([0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1])
_A = np.array(
    [
        [0, 0, 0, 0, 0],
        [1 / 5, 0, 0, 0, 0],
        [3 / 40, 9 / 40, 0, 0, 0],
        [44 / 45, -56 / 15, 32 / 9, 0, 0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    ]
)
_B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
_E = np.array([-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
_P = np.array(
    [
        [1, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
        [0, 0, 0, 0],
        [0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
        [0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
        [0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
        [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
        [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
    ]
)

#: status codes of the compiled integrators
SUCCESS, MAX_STEPS, STEP_TOO_SMALL, NOT_FINITE = 0, -1, -2, -3
#: status codes of the hybrid runs (flights: :mod:`stability.nonlinear.flight`; stick and slip:
#: :mod:`stability.nonlinear.stickslip`), which stop there with a warning
TOO_MANY_FLIGHTS, GRAZE, CHATTERING = -4, -5, -6
STATUS_MESSAGES = {
    SUCCESS: "success",
    MAX_STEPS: "maximum number of steps reached",
    STEP_TOO_SMALL: "step size fell below the round-off level",
    NOT_FINITE: "the solution became non-finite",
    TOO_MANY_FLIGHTS: "too many flights: the top bounces ever more often",
    GRAZE: "the normal force reached zero but the top does not rise: a graze, neither on the floor nor in flight",
    CHATTERING: "too many stick/slip switches: chattering",
}


@dataclass(frozen=True)
class Solution:
    """States at the requested times and the work done.

    Attributes
    ----------
    t : numpy.ndarray, shape (m,)
    y : numpy.ndarray, shape (m, n)
        States; rows after a failure are NaN.
    nfev, naccept, nreject : int
        Right-hand-side evaluations, accepted and rejected steps.
    status : int
        0 on success, negative on failure (see ``message``).
    method : str
    event_time : float
        The first zero of the normal force of a watched run (``watch_contact``), NaN if none:
        then ``t`` ends at it and the last row of ``y`` is the state there.
    event : str
        ``"none"``, ``"contact_lost"`` or ``"stick_contact"``.
    """

    t: np.ndarray
    y: np.ndarray
    nfev: int
    naccept: int
    nreject: int
    status: int
    method: str
    event_time: float = float("nan")
    event: str = "none"

    @property
    def message(self) -> str:
        """Text of the status code."""
        return STATUS_MESSAGES.get(self.status, "scipy: failed")


#: scipy steps between two interruption points (each step is a Python call of a few hundred us)
SCIPY_REPORT_STEPS = 200

#: return code of a slice that used up its step budget (the run continues in the next slice)
CONTINUE = 1
#: return code of a run that stopped at the first zero of the normal force (``watch`` on)
EVENT = 2

#: attempted steps per compiled slice: a few milliseconds to a few tens of milliseconds of work
#: between two interruption points (and progress reports), whatever the run's length
SLICE_STEPS = 20_000

# layout of the integer state of a compiled run (``cnt``): output index, counters, flags
_J, _NFEV, _NACCEPT, _NREJECT, _STEPS, _STATUS, _REJECTED, _STARTED = range(8)
# layout of the float state (``fs``): time reached, current step, the normal force at the time
# reached (watched runs), the event's time
_T, _H, _N, _TEV = 0, 1, 2, 3
#: Illinois iterations at most when locating the zero of N within a step (each one right-hand
#: side; the bracket shrinks superlinearly, to round-off in a dozen)
_ROOT_ITERATIONS = 100


@njit(cache=True, nogil=True)
def normal_force_of(y, dy, p):
    """The normal force from the state ``y`` and its derivative ``dy`` (sliding and rolling).

    The vertical component of eq. (1) with O at height R (``V0 . K = 0``, ``V0' . K = 0``):
    ``N = mu fr_inv + mu q (k'')_3``, ``k'' = omega' x k + omega x (omega x k)``, so
    ``N = mu fr_inv + mu q (omega'_1 k_2 - omega'_2 k_1 + (omega x (omega x k))_3)``. The
    integrators watch it after every step from the derivative they already have (first same as
    last), at no extra right-hand side.
    """
    q, fr, mu = p[Q], p[FR_INV], p[MU]
    c0, c1, c2 = cross(y[0], y[1], y[2], y[3], y[4], y[5])
    d2 = y[0] * c1 - y[1] * c0
    return mu * fr + mu * q * ((dy[0] * y[4] - dy[1] * y[3]) + d2)


@njit(cache=True, nogil=True)
def event_value(y, dy, p, watch, c_stick):
    """The watched quantity whose first zero ends a run: the smaller of the normal force
    (``watch != 0``) and the stick's gap ``k_3 - c_stick |k|`` (``c_stick >= -1``: the cosine
    of the tilt at which the stick touches; positive while the tilt is below it). The first zero
    of the minimum is the first zero of either; +inf when nothing is watched."""
    g = np.inf
    if watch != 0:
        g = normal_force_of(y, dy, p)
    if c_stick >= -1.0:
        gap = y[5] - c_stick * np.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5])
        if gap < g:
            g = gap
    return g


@njit(cache=True, nogil=True)
def event_value_at(code, t, y, p, watch, c_stick):
    """:func:`event_value` at a state alone (one right-hand side when ``N`` is watched)."""
    if watch == 0:
        return event_value(y, y, p, watch, c_stick)
    return event_value(y, _model_rhs(code, t, y, p), p, watch, c_stick)


#: accepted steps of a scipy solver per batched check of the normal force (:func:`first_event`):
#: one compiled call per batch instead of one per step (a call's dispatch, ~1 us, outweighs the
#: closed-form check of a step); ``python benchmarks/contact_detection.py`` measures it against 1
WATCH_BATCH = 64


@njit(cache=True, nogil=True)
def first_event(code, ts, ys, p, watch, c_stick):
    """The index of the first row of ``ys`` (states at the times ``ts``) where
    :func:`event_value` is <= 0, or -1: one compiled call for a batch of scipy's steps.

    A state whose normal force is certainly positive by the model's closed-form lower bound
    (:func:`stability.nonlinear.kernels.normal_force_lower_bound`, no 6 x 6 solve) skips the
    right-hand side; the others are decided by :func:`event_value_at`, so the answer is the
    same as with the solve at every row."""
    for i in range(ts.shape[0]):
        if watch != 0 and _normal_force_lower_bound(code, ys[i], p) > 0.0:
            if event_value(ys[i], ys[i], p, 0, c_stick) <= 0.0:  # the stick's gap alone
                return i
            continue
        if event_value_at(code, ts[i], ys[i], p, watch, c_stick) <= 0.0:
            return i
    return -1


def _locate_dense(solver, n_of):
    """The first zero of ``n_of`` in a scipy solver's last step (``> 0`` at ``t_old``, ``<= 0`` at
    ``t``): Brent's method on the step's dense output (as ``solve_ivp``'s events), then the first
    representable time with ``N <= 0``."""
    from scipy.optimize import brentq

    dense = solver.dense_output()
    t_new = solver.t
    t_ev = brentq(lambda tt: n_of(tt, dense(tt)), solver.t_old, t_new, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    y_ev = dense(t_ev)
    for _ in range(64):  # the first time N <= 0 (Brent's answer may be just before it)
        if n_of(t_ev, y_ev) <= 0.0 or t_ev >= t_new:
            break
        t_ev = min(t_new, np.nextafter(t_ev, np.inf))
        y_ev = dense(t_ev)
    return float(t_ev), np.asarray(y_ev, dtype=float)


def _relocate(make_solver, n_of, t_a, y_a, t_b, y_b, max_steps):
    """The first zero of ``n_of`` after ``t_a`` (``> 0`` there, ``<= 0`` at ``t_b``) when a batch
    found it in a step whose dense output is gone: the same method restarted from the accepted
    state ``(t_a, y_a)`` at the run's tolerances, watched at every step, located by
    :func:`_locate_dense` (the event time carries the integrator's error only). Should the
    restart not see the zero (a graze shorter than its steps), ``(t_b, y_b)`` is the event."""
    solver = make_solver(t_a, y_a)
    for _ in range(max_steps):
        solver.step()
        if solver.status == "failed":
            break
        if n_of(solver.t, solver.y) <= 0.0:
            return _locate_dense(solver, n_of)
        if solver.status == "finished" or solver.t > t_b + (t_b - t_a):
            break
    return float(t_b), np.asarray(y_b, dtype=float)


@njit(cache=True, nogil=True)
def _interpolate(y, k, yn, f1, h, th, hermite, res):
    """The state at the fraction ``th`` of the step ``[t, t + h]`` into ``res``: rk4's cubic
    Hermite interpolant of ``y, k[0]`` and ``yn, f1`` (fourth-order accurate), or dopri5's
    dense output (the stages ``k``, the matrix ``_P``)."""
    if hermite:
        h00 = (1 + 2 * th) * (1 - th) ** 2
        h10 = th * (1 - th) ** 2
        h01 = th * th * (3 - 2 * th)
        h11 = th * th * (th - 1)
        for i in range(y.shape[0]):
            res[i] = h00 * y[i] + h10 * h * k[0, i] + h01 * yn[i] + h11 * h * f1[i]
        return
    for i in range(y.shape[0]):
        acc = 0.0
        for r in range(7):
            acc += k[r, i] * th * (_P[r, 0] + th * (_P[r, 1] + th * (_P[r, 2] + th * _P[r, 3])))
        res[i] = y[i] + h * acc


@njit(cache=True, nogil=True)
def _to_event(code, p, t, h, n_new, y, k, yn, f1, hermite, ys, t_eval, j, out, fs, watch, c_stick):
    """The event in the accepted step ``[t, t + h]`` (the watched quantity ``fs[_N] > 0`` at ``t``,
    ``n_new <= 0`` at its end; new state ``yn``, derivative ``f1``), located on the step's
    interpolant (:func:`_interpolate`) with the watched quantity exact at each interpolated
    state (one right-hand side): Illinois regula falsi on the step fraction, to round-off in
    time; the event is the first time it is <= 0, the bracket's right end. The outputs before
    it are written, ``y`` is the state and ``fs[_TEV]`` the time there; returns the next output
    index and the event's time."""
    a, b = 0.0, 1.0
    fa, fb = fs[_N], n_new
    side = 0
    x = 1.0
    for _ in range(_ROOT_ITERATIONS):
        x = b - fb * (b - a) / (fb - fa) if fb != fa else 0.5 * (a + b)
        if not (a < x < b):
            x = 0.5 * (a + b)
        _interpolate(y, k, yn, f1, h, x, hermite, ys)
        fx = event_value(ys, _model_rhs(code, t + x * h, ys, p), p, watch, c_stick)
        if fx > 0.0:
            a, fa = x, fx
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb = x, fx
            if side == 1:
                fa *= 0.5
            side = 1
        if (b - a) * abs(h) <= 4e-16 * max(1.0, abs(t)):
            break
    if x != b:
        _interpolate(y, k, yn, f1, h, b, hermite, ys)
    t_ev = t + b * h
    while j < t_eval.shape[0] and t_eval[j] < t_ev:
        _interpolate(y, k, yn, f1, h, (t_eval[j] - t) / h, hermite, out[j])
        j += 1
    for i in range(y.shape[0]):
        y[i] = ys[i]
    fs[_TEV] = t_ev
    return j, t_ev


@njit(cache=True, nogil=True)
def _copy_row(dst, i, src):
    for c in range(src.shape[0]):
        dst[i, c] = src[c]


@njit(cache=True, nogil=True, inline="always")
def run_slice(code, t_eval, p, rtol, atol, max_steps, fixed, budget, y, k, fs, cnt, out, watch, c_stick):
    """At most ``budget`` attempted steps of a compiled run (without the GIL), continuing the run
    held in the state arrays: adaptive Dormand-Prince 5(4) with its dense output at ``t_eval``
    (``fixed`` False), or the classical fixed-step fourth-order Runge-Kutta of the paper
    (``fixed`` True: steps of ``fs[_H]``, the last one shortened to end at ``t_eval[-1]``,
    outputs by cubic Hermite interpolation, no step rejected).

    A run is a sequence of calls on the same state: its steps, and so its results, do not depend
    on how it is cut into slices (nothing is clipped at a slice's end; the state carries
    everything the next step needs).

    Parameters
    ----------
    code : int
        Model code (:data:`stability.nonlinear.kernels.CODES`).
    t_eval : numpy.ndarray, shape (m,)
        Increasing output times.
    p : numpy.ndarray
        Parameter vector passed to ``rhs``.
    rtol, atol : float
        Tolerances (dopri5).
    max_steps : int
        Limit on attempted steps over the whole run.
    fixed : bool
        rk4 (True) or dopri5 (False).
    budget : int
        Attempted steps in this call.
    y : numpy.ndarray, shape (n,)
        The state at ``fs[_T]`` (the initial state before the first call); updated.
    k : numpy.ndarray, shape (7, n)
        Stages (``k[0]``: the derivative at ``y``, first-same-as-last); updated.
    fs : numpy.ndarray, shape (4,)
        ``[t, h, N, t_event]``: the time of ``y`` (``t_eval[0]`` at first), the next step (at
        first the initial step, 0 for the automatic choice of Hairer et al. II.4; rk4's step),
        the watched quantity at ``t`` and the time of the event; updated.
    cnt : numpy.ndarray of int64, shape (8,)
        Output index, evaluations, accepted, rejected and attempted steps, status, the
        "rejected last" flag, "started" (0 before the first call); updated.
    out : numpy.ndarray, shape (m, n)
        Outputs, written from row ``cnt[_J]`` on (rows not reached stay as they are).
    watch : int
        1: watch the normal force (:func:`normal_force_of`) after every accepted step and stop
        at its first zero, located on the step's interpolant (:func:`_to_event`): status
        :data:`EVENT`, ``y`` the state and ``fs[_TEV]`` the time of the zero, outputs written
        before it only. 0: no watching (a model without a contact point).
    c_stick : float
        The cosine of the tilt at which the stick touches the floor, watched with ``N``
        (:func:`event_value`: the run stops at the first zero of either); < -1: no stick.

    Returns
    -------
    int
        :data:`CONTINUE` if the budget was used up before the end, else the final status
        (0 success, :data:`EVENT`, or a failure code).
    """
    n = y.shape[0]
    m = t_eval.shape[0]
    ys = np.empty(n)
    yn = np.empty(n)
    err = np.empty(n)
    t_end = t_eval[m - 1]
    watching = watch != 0 or c_stick >= -1.0
    if cnt[_STARTED] == 0:  # the first call: output row 0, the derivative at y in k[0]
        cnt[_STARTED] = 1
        t = fs[_T] = t_eval[0]
        _copy_row(out, 0, y)
        cnt[_J] = 1
        _copy_row(k, 0, _model_rhs(code, t, y, p))
        cnt[_NFEV] = 1
        h = fs[_H]
        if not fixed and h <= 0.0:
            # Hairer, Norsett & Wanner II.4: starting step size
            d0 = 0.0
            d1 = 0.0
            for i in range(n):
                sc = atol + rtol * abs(y[i])
                d0 += (y[i] / sc) ** 2
                d1 += (k[0, i] / sc) ** 2
            d0 = np.sqrt(d0 / n)
            d1 = np.sqrt(d1 / n)
            h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
            for i in range(n):
                ys[i] = y[i] + h0 * k[0, i]
            f1 = _model_rhs(code, t + h0, ys, p)
            cnt[_NFEV] += 1
            d2 = 0.0
            for i in range(n):
                sc = atol + rtol * abs(y[i])
                d2 += ((f1[i] - k[0, i]) / sc) ** 2
            d2 = np.sqrt(d2 / n) / h0
            dm = max(d1, d2)
            h1 = max(1e-6, h0 * 1e-3) if dm <= 1e-15 else (0.01 / dm) ** 0.2
            h = min(100.0 * h0, h1)
        if not fixed:
            fs[_H] = min(h, t_end - t)
        if watching:  # the watched quantity <= 0 at the start: the event is the initial state
            fs[_N] = event_value(y, k[0], p, watch, c_stick)
            if fs[_N] <= 0.0:
                fs[_TEV] = fs[_T]
                cnt[_STATUS] = EVENT
                return EVENT
    t, h, j, steps, nfev = fs[_T], fs[_H], cnt[_J], cnt[_STEPS], cnt[_NFEV]
    naccept, nreject, rejected = cnt[_NACCEPT], cnt[_NREJECT], cnt[_REJECTED] != 0
    status = used = 0
    while j < m and used < budget:
        if steps >= max_steps:
            status = -1
            break
        steps += 1
        used += 1
        if fixed:
            hh = min(h, t_end - t)
            last = t + 1.0000001 * hh >= t_end
            for s in range(1, 4):  # the classical stages at t + hh / 2, t + hh / 2, t + hh
                c = 0.5 if s < 3 else 1.0
                for i in range(n):
                    ys[i] = y[i] + c * hh * k[s - 1, i]
                _copy_row(k, s, _model_rhs(code, t + c * hh, ys, p))
            for i in range(n):
                yn[i] = y[i] + hh / 6.0 * (k[0, i] + 2.0 * k[1, i] + 2.0 * k[2, i] + k[3, i])
        else:
            last = False
            if t + h >= t_end or t + 1.0000001 * h >= t_end:
                h = t_end - t
                last = True
            if h <= 1e-14 * max(1.0, abs(t)):
                status = -2
                break
            hh = h
            for s in range(1, 6):
                for i in range(n):
                    acc = 0.0
                    for r in range(s):
                        acc += _A[s, r] * k[r, i]
                    ys[i] = y[i] + h * acc
                _copy_row(k, s, _model_rhs(code, t + _C[s] * h, ys, p))
            for i in range(n):
                acc = 0.0
                for r in range(6):
                    acc += _B[r] * k[r, i]
                yn[i] = y[i] + h * acc
        _copy_row(k, 6, _model_rhs(code, t + hh, yn, p))
        nfev += 4 if fixed else 6
        en = 0.0  # dopri5: the RMS norm of the error estimate (Hairer et al. II.4); rk4 accepts every step
        if not fixed:
            for i in range(n):
                acc = 0.0
                for r in range(7):
                    acc += _E[r] * k[r, i]
                err[i] = h * acc
                en += (err[i] / (atol + rtol * max(abs(y[i]), abs(yn[i])))) ** 2
            en = np.sqrt(en / n)
            if not np.isfinite(en):
                if h < 1e-12:
                    status = -3
                    break
                h *= 0.2
                nreject += 1
                rejected = True
                continue
        if en <= 1.0:
            t_new = t_end if last else t + hh
            naccept += 1
            if watching:
                n_new = event_value(yn, k[6], p, watch, c_stick)
                if n_new <= 0.0:
                    j, t = _to_event(
                        code, p, t, hh, n_new, y, k, yn, k[6], fixed, ys, t_eval, j, out, fs, watch, c_stick
                    )
                    status = EVENT
                    break
                fs[_N] = n_new
            while j < m and t_eval[j] <= t_new:
                _interpolate(y, k, yn, k[6], hh, (t_eval[j] - t) / hh, fixed, out[j])
                j += 1
            t = t_new
            for i in range(n):
                y[i] = yn[i]
                k[0, i] = k[6, i]
            if fixed:
                for i in range(n):
                    if not np.isfinite(y[i]):
                        status = -3
                if status != 0:
                    break
                continue
            fac = 10.0 if en == 0.0 else min(10.0, max(0.2, 0.9 * en**-0.2))
            if rejected:
                fac = min(1.0, fac)
            rejected = False
            h *= fac
        else:
            nreject += 1
            rejected = True
            h *= max(0.2, 0.9 * en**-0.2)
    if status == 0 and j < m:  # the budget is used up before the end
        status = CONTINUE
    fs[_T], fs[_H] = t, h
    cnt[_J], cnt[_STEPS], cnt[_NFEV], cnt[_NACCEPT], cnt[_NREJECT] = j, steps, nfev, naccept, nreject
    cnt[_REJECTED] = 1 if rejected else 0
    cnt[_STATUS] = 0 if status == CONTINUE else status
    return status


@njit(cache=True, nogil=True)
def dopri5_slice(code, t_eval, p, rtol, atol, max_steps, budget, y, k, fs, cnt, out, watch, c_stick):
    """:func:`run_slice` of dopri5, compiled apart (the slice inlined with ``fixed`` False: the
    compiled code of rk4's branch is dropped)."""
    return run_slice(code, t_eval, p, rtol, atol, max_steps, False, budget, y, k, fs, cnt, out, watch, c_stick)


@njit(cache=True, nogil=True)
def rk4_slice(code, t_eval, p, rtol, atol, max_steps, budget, y, k, fs, cnt, out, watch, c_stick):
    """:func:`run_slice` of rk4, compiled apart (inlined with ``fixed`` True)."""
    return run_slice(code, t_eval, p, rtol, atol, max_steps, True, budget, y, k, fs, cnt, out, watch, c_stick)


#: a run over at most this span of time (units of the model) runs interpreted
#: (:func:`stability.jit.python`) unless the compiled slice is in memory; a longer one compiled
#: from its first step. Measured (``python benchmarks/cold_start.py --crossover``,
#: docs/performance.md): ~15 dopri5 steps per unit of time at the default tolerances, 0.35 ms
#: per interpreted step against 0.0046 ms compiled, 7.9 s to compile on a cold cache (~22,600
#: steps, ~1500 units) and 0.32 s to load on a warm one (~900 steps, ~60 units); the README's
#: t_end = 50 (692 steps, 0.26 s interpreted) runs interpreted.
INTERPRETED_SPAN = 100.0
#: ... and an interpreted run that takes more steps than this (a stiff or fast one) goes on
#: compiled from where it is
INTERPRETED_STEPS = 2000


def _compiled(code, y0, t_eval, p, rtol, atol, max_steps, step, fixed, progress, watch, c_stick):
    """A compiled run: :func:`run_slice` called in slices of :data:`SLICE_STEPS` steps until it
    returns a final status, with an interruption point and a progress report (the time
    reached) between calls. The first slice runs interpreted if the span is at most
    :data:`INTERPRETED_SPAN` and :func:`stability.execution.pick` chooses it, for at most
    :data:`INTERPRETED_STEPS` steps; then compiled (with the compile notice); every slice
    interpreted if ``TIPPE_KERNEL=python``. The slices carry the whole state of the run, so a
    switch changes nothing but the execution. Returns as :func:`_scipy`."""
    y = np.array(y0, dtype=np.float64)
    out = np.full((t_eval.size, y.size), np.nan)
    k = np.empty((7, y.size))
    fs = np.array([t_eval[0], step, np.nan, np.nan])
    cnt = np.zeros(8, dtype=np.int64)
    small = float(t_eval[-1] - t_eval[0]) <= INTERPRETED_SPAN
    kernel = rk4_slice if fixed else dopri5_slice
    while True:
        checkpoint()
        fn = pick(kernel, 0 if small else math.inf)  # the first slice by size, then compiled
        small = False
        budget = min(SLICE_STEPS, INTERPRETED_STEPS) if fn is not kernel and engine() != "python" else SLICE_STEPS
        status = fn(code, t_eval, p, rtol, atol, max_steps, budget, y, k, fs, cnt, out, watch, c_stick)
        if progress is not None:
            progress(fs[_T])
        if status != CONTINUE:
            break
    work = (out, int(cnt[_NFEV]), int(cnt[_NACCEPT]), int(cnt[_NREJECT]))
    if cnt[_STATUS] == EVENT:
        return *work, SUCCESS, (float(fs[_TEV]), y.copy(), int(cnt[_J]))
    return *work, int(cnt[_STATUS]), None


def _scipy(code, y0, t_eval, p, method, rtol, atol, step, max_steps, progress=None, watch=False, c_stick=-2.0):
    """A scipy ``OdeSolver`` stepped as ``solve_ivp`` does (same steps, dense output at
    ``t_eval``), but stopped after ``max_steps`` accepted steps with status ``MAX_STEPS``; an
    interruption point (and a progress report) every :data:`SCIPY_REPORT_STEPS` steps. With
    ``watch``, the normal force is checked at every accepted step, in batches of
    :data:`WATCH_BATCH` steps (:func:`first_event`), and the run stops at its first zero,
    located on the step's dense output by Brent's method (as ``solve_ivp``'s events; a step
    before the last of its batch is integrated again from its start, :func:`_relocate`)."""

    def fun(t, yy):
        return _model_rhs(code, t, yy, p)

    w = 1 if watch else 0

    def n_of(t, yy):
        return event_value_at(code, t, yy, p, w, c_stick)

    watch = watch or c_stick >= -1.0

    import scipy.integrate  # here: a second of imports that the compiled methods do not need

    def make(t0, y_start, **kw):
        return getattr(scipy.integrate, method)(fun, t0, y_start, t_eval[-1], rtol=rtol, atol=atol, **kw)

    solver = make(t_eval[0], y0, **({"first_step": step} if step else {}))
    y = np.full((t_eval.size, y0.size), np.nan)
    y[0] = y0
    j, steps, status = 1, 0, SUCCESS
    event = None
    if watch and n_of(t_eval[0], y0) <= 0.0:
        return y, 1, 0, 0, status, (float(t_eval[0]), np.array(y0, dtype=float), 1)
    # the accepted steps not yet checked, copied into preallocated rows (the solver's arrays are
    # not kept: a list of them, stacked per batch, cost as much as the check itself), and the
    # last checked one (N > 0 there)
    batch = max(1, int(WATCH_BATCH))
    pend_t = np.empty(batch if watch else 0)
    pend_y = np.empty((batch if watch else 0, y0.size))
    npend = 0
    ok_t, ok_y = float(t_eval[0]), np.array(y0, dtype=float)

    def check(last_step: bool):
        """The event among the pending steps, or None; they are checked after."""
        nonlocal ok_t, ok_y, npend
        n_p, npend = npend, 0
        i = int(first_event(code, pend_t[:n_p], pend_y[:n_p], p, w, c_stick))
        if i < 0:
            ok_t, ok_y = float(pend_t[n_p - 1]), pend_y[n_p - 1].copy()
            return None
        if last_step and i == n_p - 1:  # the solver's own last step: its dense output
            return _locate_dense(solver, n_of)
        t_a, y_a = (float(pend_t[i - 1]), pend_y[i - 1].copy()) if i > 0 else (ok_t, ok_y)
        return _relocate(make, n_of, t_a, y_a, float(pend_t[i]), pend_y[i].copy(), max_steps)

    while j < t_eval.size:
        if steps >= max_steps:
            status = MAX_STEPS
            break
        if steps % SCIPY_REPORT_STEPS == 0:
            checkpoint()
            if progress is not None:
                progress(solver.t)
        message = solver.step()
        steps += 1
        if solver.status == "failed":
            status = STEP_TOO_SMALL if message and "step size" in message else NOT_FINITE
            break
        t_new = solver.t
        if watch:
            pend_t[npend] = t_new
            pend_y[npend] = solver.y
            npend += 1
            if npend >= batch and (event := check(True)) is not None:
                break
        k = int(np.searchsorted(t_eval, t_new, side="right"))  # the outputs up to t_new (from j on)
        if k > j:
            y[j:k] = solver.dense_output()(t_eval[j:k]).T
            j = k
        if solver.status == "finished" and j < t_eval.size:
            y[j:] = solver.y
            j = t_eval.size
    if watch and event is None and npend:
        # the steps since the last batch (the run's end, or its failure: an event before it wins)
        event = check(status == SUCCESS)
        if event is not None:
            status = SUCCESS
    if event is not None:
        t_ev, y_ev = event
        # the outputs before the event are the run's; those at or after it are dropped
        j = int(np.searchsorted(t_eval, t_ev, side="left"))
        y[j:] = np.nan
        event = (t_ev, y_ev, j)
    return y, int(solver.nfev), steps, 0, status, event


def integrate(
    model: str,
    y0: np.ndarray,
    t_eval: np.ndarray,
    p: np.ndarray,
    *,
    method: str = "dopri5",
    rtol: float = 1e-9,
    atol: float = 1e-12,
    step: float | None = None,
    max_steps: int = 10_000_000,
    progress: Callable[[float], None] | None = None,
    watch_contact: bool = False,
    stick_tilt: float | None = None,
) -> Solution:
    """Integrate a nonlinear model and return its states at ``t_eval``.

    Parameters
    ----------
    model : {"sliding", "rolling", "fixed_pivot"}
        The model (its compiled right-hand side, :mod:`stability.nonlinear.kernels`).
    y0 : numpy.ndarray
        Initial state.
    t_eval : numpy.ndarray
        Increasing output times, the first one the initial time.
    p : numpy.ndarray
        Parameter vector (:func:`stability.nonlinear.parameters.pack`).
    method : str
        One of :data:`COMPILED_METHODS` or :data:`SCIPY_METHODS`.
    rtol, atol : float
        Tolerances (ignored by ``"rk4"``).
    step : float, optional
        Step size of ``"rk4"`` (required there); initial step of the adaptive methods.
    max_steps : int
        Step limit of ``"dopri5"`` and of the scipy methods (attempted steps of the compiled
        integrator, accepted steps of scipy's): an explicit method on a stiff run (large
        ``alpha_v``, or Coulomb friction at sticking) stops there with status -1
        (``MAX_STEPS``) and the states computed so far, instead of running for hours.
    progress : callable, optional
        Called with the time reached after each slice of work (a few milliseconds apart).
    watch_contact : bool, default False
        Stop at the first zero of the normal force (sliding and rolling models:
        :func:`normal_force_of` after every step, the zero located on the step's interpolant):
        ``Solution.event_time``, and ``t`` and ``y`` end there.
    stick_tilt : float, optional
        Also stop where the tilt of ``k`` first reaches this (degrees, the stick touches the
        floor: ``Solution.event = "stick_contact"``).

    Returns
    -------
    Solution
    """
    code = CODES[model]
    c_stick = -2.0 if stick_tilt is None else float(np.cos(np.radians(stick_tilt)))
    y0 = np.ascontiguousarray(y0, dtype=np.float64)
    t_eval = np.ascontiguousarray(t_eval, dtype=np.float64)
    if method in COMPILED_METHODS:
        fixed = method == "rk4"
        if fixed and (step is None or not step > 0):
            raise InputError(f"step = {step!r}: the fixed-step rk4 method needs a step > 0")
        limit = np.iinfo(np.int64).max if fixed else int(max_steps)  # rk4 runs to its end
        run = (float(rtol), float(atol), limit, float(step or 0.0), fixed)
        y, nfev, na, nr, st, ev = _compiled(code, y0, t_eval, p, *run, progress, 1 if watch_contact else 0, c_stick)
    else:  # a scipy method (the public entries check the name: simulate's ``method``)
        y, nfev, na, nr, st, ev = _scipy(
            code, y0, t_eval, p, method, rtol, atol, step, max_steps, progress, watch_contact, c_stick
        )
    if ev is not None:
        t_ev, y_ev, rows = ev
        rows = rows - 1 if rows > 0 and t_eval[rows - 1] >= t_ev else rows  # an event at an output time
        # which watched quantity reached zero: the stick's gap, or else the normal force
        gap = event_value(y_ev, y_ev, p, 0, c_stick)
        kind = "stick_contact" if gap <= 0.0 else "contact_lost"
        t_out, y_out = np.append(t_eval[:rows], t_ev), np.vstack([y[:rows], y_ev[None, :]])
        return Solution(t_out, y_out, int(nfev), int(na), int(nr), int(st), method, t_ev, kind)
    return Solution(t_eval, y, int(nfev), int(na), int(nr), int(st), method)
