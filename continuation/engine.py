"""Pseudo-arclength continuation of a curve ``F(u) = 0``, ``u`` in ``R^(n+1)``.

Algorithm (Keller's pseudo-arclength; e.g. Allgower & Georg, *Introduction to Numerical
Continuation Methods*, ch. 2 and 6). One step from the accepted point ``(v, t)``:

1. predictor: the cubic Hermite curve of the last step extrapolated by ``h`` (error ``O(h^3)``
   to ``O(h^4)``), or the tangent ``v + h t`` after a rejected step
   (:func:`continuation.interpolation.predict`);
2. corrector: Newton's method on ``[F(u); t . (u - v) - h] = 0``, i.e. on the hyperplane
   orthogonal to ``t`` at distance ``h``, until ``||F(u)||_2 <= tol``, then one polishing step;
   at the solution the unit tangent from the bordered system ``[J; t^T] y = e_(n+1)`` (so
   consecutive tangents keep their orientation) and, from its pivots, the branch-point test
   ``det [J; t^T]`` (:func:`continuation.linalg.tangent_det`);
3. step control: a step is rejected and halved if Newton fails or the tangent turns by more
   than ``max_angle``; after an accepted step ``h`` grows by ``grow`` (easy step), stays, or
   shrinks, and is capped so that the next turn stays below ``max_angle``;
   ``min_step <= h <= max_step``;
4. boundary: a constraint ``g_j >= 0`` of the problem that becomes negative over the step ends
   the branch exactly where it reaches zero (Newton's method on ``[F; g_j] = 0``, or Brent);
5. events: sign changes of the fold tests (tangent components), of the problem's test functions
   and of the branch-point test over the step (up to the boundary, if one ends it) are located
   exactly (:func:`continuation.events.locate`: Brent on the pseudo-arclength, each evaluation a
   corrector solve predicted by the Hermite curve of the step);
6. closure: a branch whose step passes its start point again is closed there;
7. the located points, then the new point, are appended (the result is assembled into a
   :class:`Branch` at the end).

The parts are methods of :class:`_Tracer` (one traced direction), in that order. All lengths
are measured in scaled variables ``v = u / scale`` so that unknowns of different magnitudes
weigh alike. The engine knows nothing about the problem beyond :mod:`continuation.problem`. A
problem may provide ``compiled_step``, the corrector and tangent of step 2 in one compiled call
(:mod:`continuation.problem`, :mod:`continuation.compiled`); the engine then uses it (with the
predictor compiled too) for every step and every corrector solve of steps 4-5, and its Python
path otherwise (``trace(..., compiled=False)`` forces the Python path). Nothing here prints.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from typing import NamedTuple

import numpy as np

from . import interpolation
from .corrector import FLOOR, newton, step
from .errors import ConvergenceError
from .events import locate
from .interpolation import hermite
from .linalg import bordered_det, bordered_solve, tangent_det
from .linalg import norm as _norm
from .problem import ContinuationProblem, StepResult, finite_difference_jacobian, problem_dimension

__all__ = ["Branch", "TraceOptions", "hermite", "project", "tangent", "trace", "trace_both"]

EPS = float(np.finfo(float).eps)


@dataclass
class Branch:
    """One traced branch of a curve ``F(u) = 0``.

    Attributes
    ----------
    points : numpy.ndarray, shape (m, n+1)
        Accepted points in the problem's own variables, in order along the branch.
    tangents : numpy.ndarray, shape (m, n+1)
        Unit tangents in the problem's variables (same orientation along the branch).
    arclength : numpy.ndarray, shape (m,)
        Cumulative chord length in scaled variables.
    kinds : list of str
        ``"regular"``, ``"fold"`` (turning point of a component), ``"test"`` (a zero of a test
        function), ``"branch_point"`` (two curves cross), ``"boundary"`` (a constraint reached
        zero; the branch ends there), ``"closed"`` (the start point again, at the end of a
        closed branch), ``"start"`` for the start point.
    details : list of str
        For special points: which component folds, which test function or constraint.
    closed : bool
        True if the branch came back to its start (the last point repeats the first).
    end_reasons : list of str
        Why each end of the branch stopped: ``"boundary"``, ``"closed"``, ``"max_points"``,
        ``"step_failure"``, ``"max_arclength"`` or ``"callback"``.
    n_newton, n_residual, n_jacobian : int
        Work counters (Newton iterations, residual and Jacobian evaluations).
    """

    points: np.ndarray
    tangents: np.ndarray
    arclength: np.ndarray
    kinds: list[str]
    details: list[str]
    closed: bool = False
    end_reasons: list[str] = field(default_factory=list)
    n_newton: int = 0
    n_residual: int = 0
    n_jacobian: int = 0


class _Scaled:
    """The problem in scaled variables ``v = u / scale`` (with work counters)."""

    def __init__(self, problem: ContinuationProblem, scale: np.ndarray):
        self.p = problem
        self.scale = scale
        self.n_residual = 0
        self.n_jacobian = 0
        self.test_names: tuple[str, ...] = tuple(getattr(problem, "test_function_names", ()))
        self.constraint_names: tuple[str, ...] = tuple(getattr(problem, "constraint_names", ()))
        self._has_rj = hasattr(problem, "residual_and_jacobian")
        self._jac = getattr(problem, "jacobian", None) or partial(finite_difference_jacobian, problem.residual)

    def into(self, u: np.ndarray, jacobian: bool, F: np.ndarray, J: np.ndarray) -> None:
        """``F(u)`` into ``F`` and, if ``jacobian``, ``dF/du`` into ``J``, at the problem's ``u``:
        the residual of :func:`continuation.corrector.newton`, which counts the calls."""
        if jacobian and self._has_rj:
            F[:], J[:] = self.p.residual_and_jacobian(u)
        else:
            F[:] = self.p.residual(u)
            if jacobian:
                J[:] = self._jac(u)

    def residual(self, v: np.ndarray) -> np.ndarray:
        self.n_residual += 1
        return np.asarray(self.p.residual(v * self.scale), dtype=float)

    def jacobian(self, v: np.ndarray) -> np.ndarray:
        self.n_jacobian += 1
        return np.asarray(self._jac(v * self.scale), dtype=float) * self.scale

    def residual_and_jacobian(self, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        F, J = np.empty(v.size - 1), np.empty((v.size - 1, v.size))
        self.into(v * self.scale, True, F, J)
        self.count(1, 0)
        return F, J * self.scale

    def count(self, n_rj: int, n_r: int) -> None:
        """Add the work of a corrector solve (:func:`continuation.corrector.newton`)."""
        self.n_residual += n_rj + n_r
        self.n_jacobian += n_rj

    def project(self, v: np.ndarray, tol: float, max_iter: int, max_move: float) -> tuple[np.ndarray, bool, int]:
        """Minimum-norm Newton steps from ``v`` onto the curve: ``(v, ok, iterations)``."""
        ok, it, n_rj, n_r, v, _ = newton(_Scaled.into, (self,), v, None, v, 0.0, self.scale, tol, max_iter, max_move)
        self.count(n_rj, n_r)
        return v, ok, it

    def unscaled_tangent(self, t: np.ndarray) -> np.ndarray:
        tu = t * self.scale
        return tu / _norm(tu)

    def tests(self, v: np.ndarray, t: np.ndarray) -> np.ndarray:
        if not self.test_names:
            return _EMPTY
        return np.asarray(self.p.test_functions(v * self.scale, self.unscaled_tangent(t)), float)

    def constraints(self, v: np.ndarray) -> np.ndarray:
        if not self.constraint_names:
            return _EMPTY
        return np.asarray(self.p.constraints(v * self.scale), dtype=float)


_EMPTY = np.zeros(0)


def _tangent_det(J: np.ndarray, t_ref: np.ndarray) -> tuple[np.ndarray, float]:
    """:func:`tangent` oriented by ``t_ref``, and the branch-point test ``det [J; t^T]``
    (:func:`continuation.linalg.tangent_det`; from the SVD if the bordered matrix is singular)."""
    ok, t, d = tangent_det(J, t_ref)
    if ok:
        return t, d
    _, _, vh = np.linalg.svd(J)
    t = vh[-1] * np.sign(vh[-1] @ t_ref or 1.0)
    t = t / _norm(t)
    return t, bordered_det(J, t)


def tangent(J: np.ndarray, t_ref: np.ndarray | None = None) -> np.ndarray:
    """Unit null vector of ``J`` (n, n+1), oriented so that ``t @ t_ref > 0``.

    Parameters
    ----------
    J : numpy.ndarray, shape (n, n+1)
        Jacobian of full rank ``n``.
    t_ref : numpy.ndarray, optional
        Previous tangent; without it the sign is the one of the SVD.
    """
    if t_ref is None:
        _, _, vh = np.linalg.svd(J)
        return vh[-1] / np.linalg.norm(vh[-1])
    return _tangent_det(J, t_ref)[0]


def project(
    problem: ContinuationProblem,
    u0: np.ndarray,
    *,
    tol: float = 1e-13,
    max_iter: int = 30,
    scale: Sequence[float] | None = None,
    max_move: float = np.inf,
) -> np.ndarray:
    """Nearest point of the curve by minimum-norm (Gauss-)Newton steps from ``u0``.

    Raises
    ------
    ConvergenceError
        If ``||F|| <= tol`` is not reached within ``max_iter`` steps (or the iterate moves
        farther than ``max_move`` in scaled variables).
    """
    u0 = np.asarray(u0, float)
    sc = np.ones(u0.size) if scale is None else np.asarray(scale, float)
    problem_dimension(problem, u0)
    v, ok, _ = _Scaled(problem, sc).project(u0 / sc, tol, max_iter, max_move)
    if not ok:
        raise ConvergenceError(f"no point of the curve with ||F|| <= {tol:g} found near {u0}")
    return v * sc


# ------------------------------------------------------------------------------------------
# the stepper
# ------------------------------------------------------------------------------------------
class _Event(NamedTuple):
    """A special point located on a step, at pseudo-arclength ``h`` from the current point."""

    h: float
    kind: str
    detail: str
    v: np.ndarray
    t: np.ndarray


@dataclass(frozen=True)
class TraceOptions:
    """The settings of :func:`trace`: step control, accuracy and what is detected.

    One immutable object, like BifurcationKit's ``ContinuationPar``: a client builds it once
    (``TraceOptions(max_step=0.05, max_angle=0.1)``) and derives variants with
    :func:`dataclasses.replace`; the defaults below are the engine's, for a problem of order-1
    scaled unknowns. Checked when made (a ``ValueError`` naming the setting).

    Attributes
    ----------
    step, min_step, max_step : float, default 0.02, 1e-9, 0.1
        Initial, smallest and largest step (scaled arclength); ``0 < min_step <= step <=
        max_step``.
    max_points : int, default 2000
        Largest number of accepted points.
    max_arclength : float, default inf
        Stop after this scaled arclength.
    tol : float, default 1e-13
        Accept a point when ``||F(u)||_2 <= tol``.
    max_iter : int, default 8
        Newton iterations per corrector.
    max_angle : float, default 0.15
        Largest angle (radians) between consecutive tangents; bounds the chord error of the
        polyline by about ``max_angle * h / 8``.
    grow : float, default 1.6
        Step growth factor after an easy step.
    fold_components : tuple of int, default ()
        Components ``i`` of ``u`` whose turning points (``t_i = 0``) are located and marked
        ``"fold"``.
    scale : tuple of float, optional
        Typical magnitude of each unknown (default all 1); lengths are measured in
        ``u / scale``.
    detect_closed : bool, default True
        Stop when the branch returns to its start.
    detect_branch_points : bool, default True
        Locate sign changes of ``det [J; t^T]`` (a simple branch point, where two curves of
        solutions cross and ``J`` loses rank; the engine continues on the same branch).
    event_floor : float, default 1e-9
        Sign changes of a test function (or tangent component) whose values at both ends are
        below this in magnitude are rounding noise (e.g. ``t_i`` along a curve on which ``u_i``
        is constant) and are ignored.
    start_slack : float, default 1e-12
        A start point violating a constraint by at most this much (rounding errors of the
        projection onto a curve that starts on a bound) counts as lying on it.
    compiled : bool, default True
        Use the problem's ``compiled_step`` (:mod:`continuation.problem`) for the corrector
        and the tangent, if it has one; False forces the Python path (the same points to
        rounding).
    """

    step: float = 0.02
    min_step: float = 1e-9
    max_step: float = 0.1
    max_points: int = 2000
    max_arclength: float = math.inf
    tol: float = 1e-13
    max_iter: int = 8
    max_angle: float = 0.15
    grow: float = 1.6
    fold_components: tuple[int, ...] = ()
    scale: tuple[float, ...] | None = None
    detect_closed: bool = True
    detect_branch_points: bool = True
    event_floor: float = 1e-9
    start_slack: float = 1e-12
    compiled: bool = True

    def __post_init__(self) -> None:
        if not (0 < self.min_step <= self.step <= self.max_step):
            raise ValueError(
                f"steps must satisfy 0 < min_step <= step <= max_step, got "
                f"{self.min_step}, {self.step}, {self.max_step}"
            )
        object.__setattr__(self, "fold_components", tuple(int(i) for i in self.fold_components))
        if self.scale is not None:
            object.__setattr__(self, "scale", tuple(float(x) for x in np.ravel(self.scale)))


#: the engine's default settings
DEFAULT_OPTIONS = TraceOptions()


class _Tracer:
    """One traced direction of a branch: the state of :func:`trace` and the parts of a step.

    Reading order: :meth:`run` (the loop) calls :meth:`_step` (predictor, corrector, rejection:
    :meth:`_correct`) and :meth:`_advance` for an accepted step, which calls :meth:`_boundary`
    (constraints; :meth:`_boundary_point`), :meth:`_special_points` (folds, test functions,
    branch points; each located by :meth:`_locate`, :func:`continuation.events.locate` on
    :meth:`_point_on_step`), :meth:`_closure`, :meth:`_append` (the points kept) and
    :meth:`_adapt_step` (step control); :meth:`_branch` assembles the result.

    State: the current (last accepted) point ``v`` with its tangent ``t``, constraints ``g``,
    test functions ``tests`` and branch-point test ``bp``; the point before it (``prev``, for
    the Hermite predictor); the step length ``h``; the accepted points so far (``pts``,
    ``tans``, ``kinds``, ``details``, ``arc``, in scaled variables); why and whether the branch
    ended (``end``, ``done``, ``closed``); the work counters (``n_newton`` here, the residual
    and Jacobian evaluations in ``sp``). Arguments: those of :func:`trace`, checked there.
    """

    def __init__(self, problem: ContinuationProblem, sc: np.ndarray, o: TraceOptions, callback: Callable | None):
        self.sp = _Scaled(problem, sc)
        self.sc = sc
        self.o = o  # the settings (TraceOptions)
        self.h = o.step
        self.callback = callback
        # the problem's compiled corrector (continuation.problem), if it has one and may use it;
        # then the predictor is compiled too
        self.cstep = getattr(problem, "compiled_step", None) if o.compiled else None
        if self.cstep is not None:
            from . import compiled as _compiled

            self.predictor = _compiled.predict
        else:
            self.predictor = interpolation.predict
        self.n_newton = 0
        self.end = "max_points"
        self.done = False
        self.closed = False
        self.prev: tuple[np.ndarray, np.ndarray] | None = None  # the accepted point before v
        self.use_hermite = True  # False after a rejected step: the tangent predictor
        # points of the current step already corrected, (h, v, t) sorted by h: the predictor of
        # a new one is the cubic Hermite curve between its two neighbours (error O(dh^4)), so as
        # Brent's iterates close in on a special point one Newton step (or none) suffices
        self.known: list[tuple[float, np.ndarray, np.ndarray]] = []

    def start(self, u0: np.ndarray, direction: int, tangent0: Sequence[float] | None, project_start: bool) -> _Tracer:
        """The start point: on the curve, inside the constraints, with its tangent and tests."""
        sp, sc, tol = self.sp, self.sc, self.o.tol
        v = u0 / sc
        if project_start:
            v, ok, it = sp.project(v, tol, 30, np.inf)
            self.n_newton += it
            if not ok:
                raise ConvergenceError(
                    f"the start point {u0} is not on the curve (||F|| > {tol:g} after 30 Newton steps)"
                )
        g0 = sp.constraints(v)
        # a start point on a constraint (e.g. a fold found at fr_inv = 0, projected with rounding
        # errors) may sit a few ulp outside it: that is "on the boundary"
        g0 = np.where((g0 < 0) & (g0 >= -self.o.start_slack), 0.0, g0)
        if np.any(g0 < 0):
            j = int(np.argmin(g0))
            raise ValueError(f"the start point violates constraint {sp.constraint_names[j]!r} (value {g0[j]:.3g} < 0)")
        if tangent0 is None:
            t = tangent(sp.jacobian(v))
        else:
            t0 = np.asarray(tangent0, float) / sc
            t = tangent(sp.jacobian(v), t0 / np.linalg.norm(t0))
        t = direction * t
        self.pts, self.tans, self.kinds, self.details, self.arc = [v.copy()], [t.copy()], ["start"], [""], [0.0]
        self.v_start, self.t_start = v.copy(), t.copy()
        self.v, self.t = v, t
        self.g = g0
        self.tests = sp.tests(v, t)
        self.bp = bordered_det(sp.jacobian(v), t)
        if self.callback is not None and self.callback(v * sc, sp.unscaled_tangent(t), "start") is False:
            self._finish("callback")
        return self

    # --- the loop ----------------------------------------------------------------------------
    def run(self) -> Branch:
        """Step until the branch ends (a boundary, closure, a failure, a limit, the callback)."""
        while not self.done and len(self.pts) < self.o.max_points:
            if self.arc[-1] >= self.o.max_arclength:
                self._finish("max_arclength")
                break
            step = self._step()
            if step is not None:
                self._advance(step)
        return self._branch()

    def _finish(self, reason: str) -> None:
        self.end = reason
        self.done = True

    # --- predictor, corrector, rejection -------------------------------------------------------
    def _step(self) -> StepResult | None:
        """Predict and correct a step of length ``h`` (:meth:`_correct`); None if it was rejected
        (``h`` halved, the tangent predictor next) or failed at ``min_step`` (the branch ends).
        Sets ``angle``, the turn of the tangent over the step."""
        v, t, h, prev = self.v, self.t, self.h, self.prev
        guess = self.predictor(v, t, *(prev or (v, t)), prev is not None and self.use_hermite, h)
        r = self._correct(guess, h, self.o.max_iter, 2.0 * h + 1e-12)
        self.n_newton += r.iterations
        self.angle = math.acos(min(1.0, max(-1.0, float(t @ r.tangent)))) if r.ok else 0.0
        if r.ok and (self.angle <= self.o.max_angle or h <= self.o.min_step):
            self.use_hermite = True
            return r
        if h <= self.o.min_step:
            self._finish("step_failure")
        else:
            self.h = max(h / 2.0, self.o.min_step)
            self.use_hermite = False
        return None

    def _correct(self, guess: np.ndarray, h: float, max_it: int, max_move: float) -> StepResult:
        """Corrector from ``guess`` on the plane ``t . (v' - v) = h`` of the current point, then
        the tangent and ``det [J; t^T]`` at the solution: the problem's compiled step if it has
        one, else :func:`continuation.corrector.step` on the Python residual; the tangent from
        the SVD where the bordered matrix is singular (then without the compiled step's
        constraints and test functions)."""
        sp, t = self.sp, self.t
        args = (guess, t, self.v, float(h), self.sc, float(self.o.tol), int(max_it), float(max_move))
        r = StepResult(*(self.cstep(*args) if self.cstep is not None else step(_Scaled.into, (sp,), *args)))
        sp.count(r.n_residual_and_jacobian, r.n_residual)
        if r.ok and not r.tangent_ok:  # singular bordered matrix: the SVD fallback
            tt, d = _tangent_det(r.jacobian, t)
            return r._replace(tangent=tt, det=d, constraints=None, tests=None)
        return r

    def _point_on_step(self, h: float) -> tuple[np.ndarray, np.ndarray]:
        """The point of the curve and its tangent at pseudo-arclength ``h`` of the current step
        (for :func:`continuation.events.locate`): a corrector solve predicted by the Hermite
        curve between the nearest points of the step already known."""
        known, v, t = self.known, self.v, self.t
        k = 1
        while k < len(known) - 1 and known[k][0] < h:
            k += 1
        # hb > ha: known starts at h = 0, ends at the step's h > 0 and gains points strictly between
        (ha, va, ta), (hb, vb, tb) = known[k - 1], known[k]
        guess = hermite(va, ta, vb, tb, (h - ha) / (hb - ha))
        guess = guess + (h - float(t @ (guess - v))) * t  # onto the plane exactly
        r = self._correct(guess, h, self.o.max_iter + 4, 4 * abs(h) + 1e-12)
        if not r.ok:
            r = self._correct(v + h * t, h, self.o.max_iter + 4, 4 * abs(h) + 1e-12)
        if not r.ok:
            raise ConvergenceError("corrector failed while locating a special point")
        if ha < h < hb:
            known.insert(k, (h, r.v, r.tangent))
        return r.v, r.tangent

    # --- one accepted step: boundary, events, closure, the new points, the next step length ----
    def _advance(self, s: StepResult) -> None:
        """Everything after an accepted corrector step ``s``: where a constraint ends the
        branch on it, the special points on it, whether it closes the branch; the points to
        keep, and the next step length."""
        sp = self.sp
        self.known[:] = [(0.0, self.v, self.t), (self.h, s.v, s.tangent)]
        # the constraints and test functions at the new point: from the compiled step if it gave them
        g_new = s.constraints if s.constraints is not None and sp.constraint_names else sp.constraints(s.v)
        stop, v_b, t_b = self._boundary(s, g_new)
        tests_new = s.tests if s.tests is not None and sp.test_names else sp.tests(s.v, s.tangent)
        events, at_new = self._special_points(s, stop, v_b, t_b, tests_new)
        seg = _norm(s.v - self.v)  # the step's chord (also the arclength increment)
        close_at = self._closure(s, seg)
        if self._append(s, events, stop, close_at, at_new, seg):
            return
        self.prev = (self.v, self.t)
        self.v, self.t, self.g, self.tests, self.bp = s.v, s.tangent, g_new, tests_new, s.det
        self._adapt_step(s)

    def _adapt_step(self, s: StepResult) -> None:
        """Step control after an accepted step: grow after an easy corrector (<= 3 Newton
        iterations), keep after a moderate one, shrink after a hard one; and keep the next turn
        of the tangent below ``max_angle`` (if it turns by ``angle`` over ``h``, about ``0.9
        max_angle`` next)."""
        factor = self.o.grow if s.iterations <= 3 else (1.0 if s.iterations <= 5 else 0.7)
        if self.angle > 0:
            factor = min(factor, 0.9 * self.o.max_angle / self.angle)
        self.h = min(max(self.h * factor, self.o.min_step), self.o.max_step)

    # --- boundary handling (constraints) ---------------------------------------------------
    def _boundary(self, s: StepResult, g_new: np.ndarray) -> tuple[_Event | None, np.ndarray, np.ndarray]:
        """Where the step leaves the constraints, if it does: ``(stop, v_b, t_b)``, the
        boundary point that ends the branch (None if none) and the end of the part of the step
        that counts (the boundary point, or the new point).

        Each constraint ``j`` with ``g_j >= 0`` at the current point and ``< 0`` at the new one
        is located, the earliest crossing (by linear interpolation) first; the others only if
        they are still violated at the located point (ties go to the constraint listed first).
        """
        negative = np.nonzero(g_new < 0)[0]
        if negative.size == 0:  # most steps
            return None, s.v, s.tangent
        sp, g = self.sp, self.g
        stop = None
        crossed = [j for j in negative if g[j] >= 0]
        crossed.sort(key=lambda j: (g[j] / (g[j] - g_new[j]), j))
        h_b, at_b, g_b = self.h, (s.v, s.tangent), g_new
        while crossed:
            j = crossed.pop(0)
            phi = lambda vv, tt, j=j: sp.constraints(vv)[j]  # noqa: E731
            hs, vs, ts = (
                self._boundary_point(s, j, h_b, float(g[j]), float(g_b[j]))
                or self._locate(phi, h_b, float(g[j]), float(g_b[j]), at_b)
                or (h_b, *at_b)
            )
            # j is violated at the current stop point, so its zero comes first (ties included)
            if stop is None or hs <= stop.h + 1e-9 * self.h:
                stop = _Event(hs, "boundary", sp.constraint_names[j], vs, ts)
                g_s = sp.constraints(vs)
                crossed = [k for k in crossed if g_s[k] < 0]
                h_b, at_b, g_b = hs, (vs, ts), g_s
        return stop, at_b[0], at_b[1]

    def _boundary_point(
        self, s: StepResult, j: int, h_b: float, ga: float, gb: float
    ) -> tuple[float, np.ndarray, np.ndarray] | None:
        """Where constraint ``j`` reaches zero between ``h = 0`` and ``h_b``: Newton's method on
        the square system ``[F(u); g_j(u)] = 0`` (``grad g_j`` by central differences, exact
        for the linear and quadratic bounds of a box or a domain) from the Hermite point at the
        linear interpolate of ``g_j``; None if it does not converge inside the step (the caller
        then brackets with :func:`continuation.events.locate`)."""
        if not (ga > 0 > gb):
            return None
        sp, v, t, h, tol = self.sp, self.v, self.t, self.h, self.o.tol
        h0 = h_b * ga / (ga - gb)
        uu = hermite(v, t, s.v, s.tangent, h0 / h) if h > 0 else v + h0 * t
        gscale = max(1.0, abs(ga), abs(gb))
        delta = 1e-6
        eye = np.eye(uu.size) * delta
        grad = None
        for _ in range(8):
            f, JJ = sp.residual_and_jacobian(uu)
            gj = float(sp.constraints(uu)[j])
            fn = _norm(f)
            if not math.isfinite(fn) or not math.isfinite(gj):
                return None
            converged = fn <= tol and abs(gj) <= 8 * EPS * gscale
            if grad is None:
                # once: the bounds are linear or quadratic and the start is within O(h^4) of the
                # point, so a fixed gradient converges as fast (the accuracy is set by the
                # residual tests above, not by the gradient)
                grad = np.array([(sp.constraints(uu + e)[j] - sp.constraints(uu - e)[j]) / (2 * delta) for e in eye])
            solved, du, _ = bordered_solve(JJ, grad, f, gj)
            if not solved:
                return None
            if converged:
                if fn > FLOOR:  # polish, as the corrector does
                    u2 = uu - du
                    if _norm(sp.residual(u2)) < fn and abs(float(sp.constraints(u2)[j])) <= 8 * EPS * gscale:
                        uu = u2
                hs = float(t @ (uu - v))
                if not (-1e-12 * h <= hs <= h_b * (1 + 1e-12)):
                    return None
                return min(max(hs, 0.0), h_b), uu, tangent(JJ, t)
            uu = uu - du
        return None

    # --- event location: folds, test functions, branch points -------------------------------
    def _special_points(
        self, s: StepResult, stop: _Event | None, v_b: np.ndarray, t_b: np.ndarray, tests_new: np.ndarray
    ) -> tuple[list[_Event], list[tuple[str, str]]]:
        """The special points strictly inside the step (up to the boundary ``v_b`` if ``stop``),
        located, and ``at_new``: the ``(kind, detail)`` of the tests that are exactly 0.0 at the
        new point.

        Candidates are the tests that change sign over the step: the fold tests ``t_i``, the
        problem's test functions, the branch-point test ``det [J; t^T]``. A sign change whose
        values are both below ``event_floor`` is rounding noise. A test at the start point of
        the branch that is zero to rounding (``|value| <= event_floor``, whatever its sign or its
        last bits) and not at the end of the first step makes the start that special point, in
        both directions alike, so a start on a special point is reported once, at the start, on
        every machine (its sign there is rounding, and deciding by it would report the point
        in one direction or the other, or as the start and again a rounding away from it); a test exactly 0.0 at the new point (and not at the current one) makes
        the new point that special point (the next step then starts from 0.0 and brackets
        nothing, so it is reported once), unless a boundary cuts the step short.
        """
        sp, t, floor = self.sp, self.t, self.o.event_floor
        at_start = len(self.pts) == 1 and self.kinds[0] == "start"
        # (kind, detail, test function phi(v, t), its value at the current point and at v_b)
        folds = self.o.fold_components
        tests = [("fold", str(i), lambda vv, tt, i=i: tt[i], float(t[i]), float(t_b[i])) for i in folds]
        tests_b = tests_new if stop is None else sp.tests(v_b, t_b)
        for k in range(self.tests.size):
            phi = lambda vv, tt, k=k: sp.tests(vv, tt)[k]  # noqa: E731
            tests.append(("test", sp.test_names[k], phi, float(self.tests[k]), float(tests_b[k])))
        if self.o.detect_branch_points:
            bp_b = s.det if stop is None else bordered_det(sp.jacobian(v_b), t_b)
            tests.append(("branch_point", "", lambda vv, tt: bordered_det(sp.jacobian(vv), tt), self.bp, bp_b))
        h_b = self.h if stop is None else stop.h
        events: list[_Event] = []
        at_new: list[tuple[str, str]] = []
        for kind, name, phi, pa, pb in tests:
            if at_start and abs(pa) <= floor and abs(pb) > floor:
                self.kinds[0], self.details[0] = kind, name
            elif pa * pb < 0:
                # one that cannot be located is not reported, nor one at the end of the branch
                # (within 1e-6 of the last step) apart from the end point
                found = self._locate(phi, h_b, pa, pb, (v_b, t_b)) if max(abs(pa), abs(pb)) > floor else None
                if found is not None and (stop is None or found[0] < stop.h - 1e-6 * self.h):
                    events.append(_Event(found[0], kind, name, *found[1:]))
            elif pb == 0.0 and abs(pa) > floor and stop is None:
                at_new.append((kind, name))
        return events, at_new

    def _locate(
        self, phi: Callable, h_b: float, pa: float, pb: float, at_b: tuple[np.ndarray, np.ndarray]
    ) -> tuple[float, np.ndarray, np.ndarray] | None:
        """The zero of ``phi`` on the step between ``h = 0`` (value ``pa``) and ``h_b`` (``pb``,
        point and tangent ``at_b``) by :func:`continuation.events.locate` on
        :meth:`_point_on_step`; None if it cannot be located (a corrector failure inside)."""
        try:
            return locate(self._point_on_step, phi, 0.0, h_b, pa, pb, (self.v, self.t), at_b)
        except (ConvergenceError, ValueError):
            return None

    # --- closure detection ---------------------------------------------------------------------
    def _closure(self, s: StepResult, seg: float) -> float | None:
        """Pseudo-arclength on the step where the branch passes its start point again (within 5%
        of the step's chord ``seg``, in the start's direction), or None. Only once the branch
        has at least 4 points and has gone more than 3 steps' length."""
        if not (self.o.detect_closed and len(self.pts) >= 4 and self.arc[-1] > 3.0 * self.h):
            return None
        v, v_start = self.v, self.v_start
        # the distance to the segment is at least |v_start - v| - seg: most steps stop here
        if _norm(v_start - v) > 1.05 * seg + 1e-9:
            return None
        d = s.v - v  # the foot of v_start on the segment [v, s.v] at v + lam d
        L2 = float(d @ d)
        lam = 0.0 if L2 == 0 else min(1.0, max(0.0, float((v_start - v) @ d) / L2))
        if lam > 0.0 and _norm(v_start - (v + lam * d)) <= 0.05 * seg + 1e-9 and d @ self.t_start > 0:
            return lam * self.h
        return None

    # --- the points kept ---------------------------------------------------------------------
    def _append(
        self,
        s: StepResult,
        events: list[_Event],
        stop: _Event | None,
        close_at: float | None,
        at_new: list[tuple[str, str]],
        seg: float,
    ) -> bool:
        """Append the step's points: the special points before the branch ends (at a boundary
        or closure), then the end point or the new point; True if the branch ended."""
        events.sort(key=lambda e: e.h)
        limit = min(stop.h if stop is not None else np.inf, close_at if close_at is not None else np.inf)
        for e in events:
            if e.h < limit and self._add(e.v, e.t, e.kind, e.detail) is False:
                self.end = "callback"  # the other special points of the step still come
        if self.end == "callback":
            self.done = True
            return True
        if close_at is not None and (stop is None or close_at <= stop.h):
            self._add(self.v_start.copy(), self.t_start.copy(), "closed", "", call=False)
            self.closed = True
            self._finish("closed")
            return True
        if stop is not None:
            if stop.h <= 1e-12 * self.h and len(events) == 0:  # the boundary is the current point itself
                self.kinds[-1], self.details[-1] = stop.kind, stop.detail
            else:
                self._add(stop.v, stop.t, stop.kind, stop.detail)
            self._finish("boundary")
            return True
        kind, detail = at_new[0] if at_new else ("regular", "")
        if self._add(s.v, s.tangent, kind, detail, seg) is False:
            self._finish("callback")
            return True
        return False

    def _add(
        self, v: np.ndarray, t: np.ndarray, kind: str, detail: str, seg: float | None = None, call: bool = True
    ) -> bool | None:
        """Append an accepted point (``seg``: its chord from the last one, if known) and tell the
        callback; returns what the callback returned."""
        self.pts.append(v)
        self.tans.append(t)
        self.kinds.append(kind)
        self.details.append(detail)
        self.arc.append(self.arc[-1] + (_norm(v - self.pts[-2]) if seg is None else seg))
        if call and self.callback is not None:
            return self.callback(v * self.sc, self.sp.unscaled_tangent(t), kind)
        return None

    # --- result assembly ---------------------------------------------------------------------
    def _branch(self) -> Branch:
        """The branch in the problem's variables, with the unscaled unit tangents."""
        P = np.array(self.pts) * self.sc
        T = np.array(self.tans) * self.sc  # the unscaled unit tangents, all at once
        T /= np.sqrt(np.einsum("ij,ij->i", T, T))[:, None]
        counts = (self.n_newton, self.sp.n_residual, self.sp.n_jacobian)
        return Branch(P, T, np.array(self.arc), self.kinds, self.details, self.closed, [self.end], *counts)


def trace(
    problem: ContinuationProblem,
    u0: Sequence[float],
    options: TraceOptions | None = None,
    *,
    direction: int = 1,
    tangent0: Sequence[float] | None = None,
    callback: Callable[[np.ndarray, np.ndarray, str], bool | None] | None = None,
    project_start: bool = True,
) -> Branch:
    """Trace one direction of the curve through ``u0``.

    Parameters
    ----------
    problem : ContinuationProblem
        See :mod:`continuation.problem`.
    u0 : sequence of float
        Start point (projected onto the curve first if ``project_start``).
    options : TraceOptions, optional
        Step control, accuracy and detection (:class:`TraceOptions`; default: its defaults).
    direction : {1, -1}
        Follow the initial tangent or its opposite.
    tangent0 : sequence of float, optional
        Initial tangent (problem variables); default: the null vector of ``J(u0)``.
    callback : callable, optional
        ``callback(u, t, kind)`` after each accepted point; returning False stops the branch.
    project_start : bool
        Project ``u0`` onto the curve first.

    Returns
    -------
    Branch
    """
    o = DEFAULT_OPTIONS if options is None else options
    if not isinstance(o, TraceOptions):
        raise TypeError(f"options = {options!r} must be a continuation.TraceOptions")
    if direction not in (1, -1):
        raise ValueError(f"direction = {direction!r}; use 1 or -1")
    u0 = np.asarray(u0, dtype=float)
    problem_dimension(problem, u0)
    sc = np.ones(u0.size) if o.scale is None else np.asarray(o.scale, float)
    if sc.shape != u0.shape or np.any(sc <= 0):
        raise ValueError(f"scale must be {u0.size} positive numbers, got {o.scale!r}")
    return _Tracer(problem, sc, o, callback).start(u0, direction, tangent0, project_start).run()


def trace_both(
    problem: ContinuationProblem,
    u0: Sequence[float],
    options: TraceOptions | None = None,
    *,
    callback: Callable[[np.ndarray, np.ndarray, str], bool | None] | None = None,
) -> Branch:
    """Trace the curve through ``u0`` in both directions and join the two halves.

    Parameters
    ----------
    problem : ContinuationProblem
    u0 : sequence of float
        Start point (projected onto the curve first).
    options : TraceOptions, optional
        As in :func:`trace`.
    callback : callable, optional
        As in :func:`trace`, for both halves.

    Returns
    -------
    Branch
        Ordered from the end reached backwards to the end reached forwards; the start point
        keeps kind ``"start"``. A closed curve is traced once.
    """
    fwd = trace(problem, u0, options, callback=callback)
    if fwd.closed:
        return fwd
    bwd = trace(problem, fwd.points[0], options, tangent0=-fwd.tangents[0], callback=callback, project_start=False)
    pts = np.concatenate([bwd.points[::-1], fwd.points[1:]])
    tans = np.concatenate([-bwd.tangents[::-1], fwd.tangents[1:]])
    arc_b = bwd.arclength[-1] - bwd.arclength[::-1]
    arc = np.concatenate([arc_b, arc_b[-1] + fwd.arclength[1:]])
    kinds = bwd.kinds[::-1] + fwd.kinds[1:]
    details = bwd.details[::-1] + fwd.details[1:]
    if bwd.kinds[0] == "start" and fwd.kinds[0] != "start":  # the start is a special point
        kinds[len(bwd.kinds) - 1], details[len(bwd.kinds) - 1] = fwd.kinds[0], fwd.details[0]
    counts = (fwd.n_newton + bwd.n_newton, fwd.n_residual + bwd.n_residual, fwd.n_jacobian + bwd.n_jacobian)
    return Branch(pts, tans, arc, kinds, details, False, [bwd.end_reasons[0], fwd.end_reasons[0]], *counts)
