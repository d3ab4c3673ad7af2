"""Neutral curves of the linear models and their folds: a client of the continuation engine.

A mode is neutral where ``det(i w M - A) = 0`` with ``w`` real (:mod:`stability.linear.neutrality`):
two real equations in three unknowns ``u = (x, y, w)``, ``x`` and ``y`` two parameters of
``{q, fr_inv, sigma, alpha_v, mu}`` and ``w`` the neutral mode's frequency (``Im s``, fixed
frame, units of the spin rate). :func:`neutral_curve` follows that mode by pseudo-arclength
continuation (:func:`continuation.trace_both`), not the non-smooth maximum over modes, and marks

``fold``
    a turning point of ``x`` or ``y`` along the curve (an extremum of a threshold; at
    ``fr_inv = 0`` the fold in ``sigma`` of the ``(q, sigma)`` curve is the paper's
    "sigma ~ 1.14");
``zero_frequency``
    ``w`` changes sign: a root crosses the imaginary axis at ``s = 0`` (Bogdanov-Takens type);
``double_crossing``
    another mode is neutral at the same point (the leading mode changes there; the data
    variable ``leading`` says on which parts the traced mode is the leading one, i.e. where the
    curve is the stability boundary);
``domain_edge``
    the curve leaves the physical domain (:mod:`stability.parameters`; strict bounds are
    applied with a margin ``edge_margin``);
``endpoint``
    the requested range ends, or continuation stopped (``detail`` says why).

Conservative models (fixed_pivot and rolling, eqs. 8-9, and the sliding model at
``alpha_v = 0``) have every real root of ``p(i w)`` neutral, so the set ``p(i w) = 0`` is a
region, not a curve. For them the traced curve is the boundary of that region: the collision of
two neutral modes, ``P(w) = P'(w) = 0`` (for eq. 8 the discriminant ``sigma_hat^2 = 4 kappa``,
``w = sigma_hat / 2``); the dataset's attribute ``form`` says ``"collision"``.

Start points come from a coarse atlas of the model: on every grid edge where the number of
growing modes changes, the mode that crossed gives a guess that minimum-norm Newton projects
onto the curve. The modes are counted by the sign of each growth rate against its own scale
(:mod:`stability.linear.growth`), not by the atlas's stability flag, whose floor
``16 u max|s|`` (relative to the largest mode) flags every slow mode marginal once a fast mode
is ``~1e8`` times larger (the sliding top at ``alpha_v >= 1e8``: no edge changed, and an empty
curve was returned). A grid point where some mode's sign cannot be decided counts as unknown;
if no point of the grid is decided, :func:`neutral_curve` refuses (pass ``start=``), and if
the signs are decided and the count never changes, the empty curve is returned with a
``UserWarning`` and the attribute ``note`` saying so. Each start point not already on a traced
branch starts a new branch, traced in both directions. A curve that never changes the number
of growing modes across the coarse grid (a closed curve inside one cell, or a curve along which
a mode touches the axis without crossing) is not found from the atlas; pass ``start=`` then.
"""

from __future__ import annotations

import functools
import math
import sys
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np
import xarray as xr

from continuation.engine import Branch, TraceOptions, project, trace_both
from continuation.errors import ConvergenceError as EngineConvergenceError

from .. import execution
from .._version import package_version
from ..errors import ConvergenceError, DomainError, InputError, ParameterTypeError
from ..models import LinearModel, get_model
from ..parameters import (
    LONG_NAMES,
    UPPER_BOUND,
    WINDOW_UPPER_BOUND,
    as_scalar,
    check_choice,
    check_flag,
    check_integer,
    check_positive,
    check_range,
    domain_range,
    domain_text,
    parameter_attrs,
)
from ..products import PRODUCT_ATTR
from ..resources import check_start_grid
from .growth import GROWS, UNRESOLVED, growth, mode_signs
from .modes import structural_zeros
from .neutral_constraints import constraint_values, constraints_of
from .neutrality import NeutralCondition, crossing_kernels
from .roots import root_bound
from .spectra import fixed_parameters, lapack_eigenvalues, parameter_name, spectrum

__all__ = ["DEFAULT_RANGES", "FoldProblem", "NeutralProblem", "fold_curve", "neutral_curve"]

#: default ends of the ranges where the physical domain sets none (its bounds come from the table
#: :data:`stability.parameters.DOMAIN`, :func:`stability.parameters.domain_range`: ``|q| < 1/sqrt(mu)``,
#: ``0 < sigma <= 2 (1 - mu q^2)``, or ``<= 2`` where q or mu is traced; ``q`` here only for a traced mu)
#: closed at :data:`stability.parameters.WINDOW_UPPER_BOUND`, beside threshold's wider bracket
DEFAULT_RANGES: dict[str, tuple[float, float]] = {
    **dict.fromkeys(UPPER_BOUND, (0.0, WINDOW_UPPER_BOUND)),
    "q": (-1.0, 1.0),
}

#: the largest coarse grid for start points, per axis (the spectra of its points are held in memory)
MAX_GRID = 2000

#: the largest number of points per direction of a branch
MAX_POINTS = 10**6

#: the largest turn of the tangent per step (radians) of the application's traced curves: the
#: default of neutral_curve, fold_curve and steady_branch (finer than the engine's generic
#: ``continuation.TraceOptions.max_angle``, 0.15, since these curves are drawn and interpolated)
CURVE_MAX_ANGLE = 0.1

_KIND_DETAIL = {
    "branch_point": ("branch_point", "two neutral curves cross here (the Jacobian loses rank)"),
    "frequency": ("zero_frequency", "the frequency changes sign: a root crosses the axis at s = 0"),
    "other_modes": ("double_crossing", "a second mode is neutral here"),
}


def _ranges(
    names: Sequence[str], given: Sequence[Any], fixed: Mapping[str, float]
) -> tuple[dict[str, tuple[float, float]], np.ndarray, np.ndarray]:
    """The ranges of the traced ``names`` (each checked; default: the domain's range given the
    fixed parameters, :func:`stability.parameters.domain_range`, its open ends closed by
    :data:`DEFAULT_RANGES`), their widths (the scale of those unknowns) and eight seeded points
    inside them (for the form and the deflation)."""
    ranges = {}
    for n, r in zip(names, given):
        lo, hi = domain_range(n, fixed) if r is None else check_range(f"{n}_range", r)
        dlo, dhi = DEFAULT_RANGES.get(n, (lo, hi))
        ranges[n] = (lo if math.isfinite(lo) else dlo, hi if math.isfinite(hi) else dhi)
    width = np.array([ranges[n][1] - ranges[n][0] for n in names])
    low = np.array([ranges[n][0] for n in names])
    return ranges, width, low + np.random.default_rng(12345).random((8, len(names))) * width


class _CurveProblem:
    """What the neutral and fold problems share: the traced parameters ``names`` (the columns
    ``_columns`` of ``u``), the fixed ones, the neutral condition ``cond`` (its free parameters
    ``names``) and the constraints (the domain's, with the margin ``edge_margin``, and the
    ``ranges``)."""

    test_function_names: tuple[str, ...] = ()
    _columns: tuple[int, ...] = (0, 1)
    compiled_step: Callable[..., tuple] | None = None
    _compiled: tuple | None = None

    def __init__(self, cond: NeutralCondition, ranges: Mapping[str, tuple[float, float]], edge_margin: float):
        self.cond, self.model, self.names, self.fixed = cond, cond.model, cond.free, cond.fixed
        constraints = constraints_of(self.model, self.names, ranges, edge_margin)
        self.constraint_names = tuple(c.name for c in constraints)
        self.constraint_rows = constraints
        self._rows = tuple(list(r) for r in zip(*((c.code, c.index, c.a) for c in constraints)))

    def constraints(self, u: np.ndarray) -> np.ndarray:
        """Domain and range bounds, ``>= 0`` inside (compiled twin if any)."""
        if self._compiled is not None:
            from .neutral_compiled import constraint_values as compiled

            point, free, _, codes, index, a = self._compiled
            return compiled(point, free, np.asarray(u, dtype=float), codes, index, a)
        values = [float(u[i]) for i in self._columns]
        return constraint_values(self.cond._point, self.cond._free_index, values, *self._rows)


class NeutralProblem(_CurveProblem):
    """Continuation problem of a neutral curve: ``u = (x, y, w)``, ``F`` of :mod:`stability.linear.neutrality`.

    Parameters
    ----------
    model : str or LinearModel
    x, y : str
        The two traced parameters.
    fixed : mapping
        All other parameters (validated).
    ranges : mapping
        ``{x: (lo, hi), y: (lo, hi)}``.
    edge_margin : float
        Margin of the strict domain bounds.
    samples : numpy.ndarray, optional
        ``(m, 2)`` points used to decide the form and structural deflation.
    form : {"crossing", "collision"}, optional
    compiled : bool, optional
        Offer the engine the compiled step (:mod:`stability.linear.neutral_compiled`) and evaluate
        constraints and test functions by their compiled twins, where they exist (the sliding
        model's crossing form); False keeps everything in Python. None (default): the rule of
        :func:`stability.execution.use_compiled`.

    Attributes
    ----------
    compiled_step : callable or None
        The engine's hook (:mod:`continuation.problem`): the step of
        :func:`stability.linear.neutral_compiled.step_kernel` with this problem's arguments;
        None without a compiled path.
    """

    test_function_names = ("frequency", "other_modes")

    def __init__(
        self,
        model: str | LinearModel,
        x: str,
        y: str,
        fixed: Mapping[str, float],
        ranges: Mapping[str, tuple[float, float]],
        edge_margin: float = 1e-9,
        samples: np.ndarray | None = None,
        form: str | None = None,
        compiled: bool | None = None,
    ):
        model = get_model(model)
        if compiled is None:  # the rule of stability.execution: the compiled step if in memory (or forced)
            step = sys.modules.get(__package__ + ".neutral_compiled")  # nothing imported to find out
            f, d = (getattr(model, k, None) for k in ("point_coefficients", "point_derivatives"))
            known = step and f and d and step.step_kernel(crossing_kernels(f, d, int(model.n_modes)))
            compiled = execution.use_compiled(known or None, 1)
        super().__init__(NeutralCondition(model, (x, y), fixed, samples, form, compiled), ranges, edge_margin)
        self._kernels = kernels = self.cond.kernels
        if kernels is not None:  # the crossing form of a model with formulas, compiled
            from .neutral_compiled import step_kernel

            rows = (np.array(r, dtype=t) for r, t in zip(self._rows, (np.int64, np.int64, float)))
            self._compiled = (*self.cond._compiled, *rows)
            self.compiled_step = functools.partial(step_kernel(kernels), *self._compiled)

    def residual_and_jacobian(self, u: np.ndarray, jacobian: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``F`` (2,) and ``dF/d(x, y, w)`` (2, 3) from one evaluation of the coefficients
        (compiled twin if any; no Jacobian if not ``jacobian``)."""
        if self._compiled is not None:
            return self._kernels.residual_and_jacobian(*self._compiled[:3], np.asarray(u, dtype=float), jacobian)
        return self.cond.residual_and_jacobian(u[:2], float(u[2]), jacobian)

    def residual(self, u: np.ndarray) -> np.ndarray:
        """``F(x, y, w)`` (2,)."""
        return self.residual_and_jacobian(u, False)[0]

    def jacobian(self, u: np.ndarray) -> np.ndarray:
        """``dF/d(x, y, w)`` (2, 3)."""
        return self.residual_and_jacobian(u)[1]

    def traced_modes_lead(self, U: np.ndarray) -> np.ndarray:
        """Whether no other mode grows at the points ``U`` (m, 3), so that the curve is the
        stability boundary there.

        Each other mode's growth rate is signed against its own scale
        (:func:`stability.linear.growth.mode_signs`: its real part against its own error
        bound, else the structured estimate on the undeflated-by-``i w`` polynomial), not
        against a tolerance relative to the largest mode (which, at ``alpha_v = 1e12``, made
        every O(1) mode count as "not growing" beside the slip mode). A mode whose sign cannot
        be decided (within rounding of the axis: a second neutral mode) does not count as
        growing; a structural zero root is neutral.
        """
        U = np.asarray(U, dtype=float).reshape(-1, 3)
        r = self.cond.other_modes_many(U[:, :2], U[:, 2])
        if r.shape[1] == 0:
            return np.ones(len(U), dtype=bool)
        c = self.cond.coefficients(U[:, :2])
        sign, _ = mode_signs(c, r, root_bound(c, r))
        return ~(sign == GROWS).any(axis=1)

    def test_functions(self, u: np.ndarray, t: np.ndarray) -> np.ndarray:
        """``[w, max Re(other modes)]`` (-1 for the second if there is no other mode)."""
        if self._compiled is not None:
            g = self._kernels.other_growth(*self._compiled[:3], np.asarray(u, dtype=float))
        else:
            g = max((z.real for z in self.cond.other_modes_list(u[:2], float(u[2]))), default=-np.inf)
        return np.array([u[2], g if math.isfinite(g) else -1.0])


class FoldProblem(_CurveProblem):
    """Continuation of a fold of a neutral curve in a third parameter: ``u = (x, y, w, z)``.

    Equations: the neutral condition ``F(x, y, w; z) = 0`` (two) and the fold condition
    ``det [dF/d other, dF/d w] = 0`` (the tangent of the ``(x, y)`` curve has no component in
    ``fold_in``, ``other`` being the plane's other parameter). The engine uses central
    differences for the Jacobian (:func:`continuation.finite_difference_jacobian`). Arguments:
    ``fold_in``, then those of :class:`_CurveProblem` (the condition's free parameters
    ``(x, y, z)``).
    """

    _columns = (0, 1, 3)

    def __init__(
        self, fold_in: str, cond: NeutralCondition, ranges: Mapping[str, tuple[float, float]], edge_margin: float
    ):
        super().__init__(cond, ranges, edge_margin)
        self.other = 1 if fold_in == self.names[0] else 0

    def residual(self, u: np.ndarray) -> np.ndarray:
        """``[F1, F2, det]`` at ``u = (x, y, w, z)``."""
        vals = np.array([u[0], u[1], u[3]])
        F, J = self.cond.residual_and_jacobian(vals, float(u[2]))
        B = J[:, [self.other, 3]]
        return np.array([F[0], F[1], B[0, 0] * B[1, 1] - B[0, 1] * B[1, 0]])


# ------------------------------------------------------------------------------------------
# start points
# ------------------------------------------------------------------------------------------
class _Guesses(NamedTuple):
    """Start guesses from the coarse atlas, and how many of its points decided every sign."""

    points: list[np.ndarray]
    inside: int
    decided: int


def _atlas_guesses(
    model: LinearModel,
    x: str,
    y: str,
    fixed: Mapping[str, float],
    ranges: Mapping[str, tuple[float, float]],
    grid: tuple[int, int],
) -> _Guesses:
    """Guesses ``(x, y, w)`` on grid edges where the number of growing modes changes (the
    modes' signs of :mod:`stability.linear.growth`; points with an undecided sign are left
    out)."""
    xs = np.linspace(*ranges[x], grid[0])
    ys = np.linspace(*ranges[y], grid[1])
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    # the compiled kernel (stability.linear.kernel), its serial loop: on a thread pool, start-up
    # and contention on a busy machine cost more than the 625 points of a coarse grid (serial,
    # it is ~5x faster than the batched polynomial root finder, the cross-check method)
    gr = growth(model, parallel=False, **{**fixed, x: X, y: Y})
    sp = gr.spectrum
    if not sp.inside.any():  # tracing finds nothing: an input error, not "no neutral curve"
        fx = ", ".join(f"{k} = {v:g}" for k, v in fixed.items())
        raise DomainError(
            f"{x}_range = {_pair(ranges[x])} and {y}_range = {_pair(ranges[y])} lie outside the physical "
            f"domain at {fx} ({domain_text(model.parameters)})"
        )
    ev = sp.eigenvalues
    grows = gr.sign == GROWS
    decided = sp.inside & ~(gr.sign == UNRESOLVED).any(axis=-1)
    count = np.where(decided, grows.sum(axis=-1), -1)
    # grid edges (a, b) on which the number of growing modes changes: axis 0 first, then
    # axis 1, each in row-major order; an edge joins neighbouring decided points of a grid line,
    # across the undecided points between them (a curve through grid points, e.g. q = 0 on a
    # grid that holds it, leaves those points within rounding of neutral), never across a point
    # outside the domain
    flat: np.ndarray = np.arange(count.size).reshape(count.shape)
    pa_list, pb_list = [], []
    for F in (flat.T, flat):  # rows of F: the grid lines along axis 0, then axis 1
        C, n = count.flat[F], F.shape[1]
        # the next decided point after each point of its line (n: none), and no outside point between
        after = np.minimum.accumulate(np.where(C >= 0, np.arange(n), n)[:, ::-1], axis=1)[:, ::-1][:, 1:]
        b = np.minimum(after, n - 1)
        out_before = np.cumsum(~sp.inside.flat[F], axis=1)
        ok = (C[:, :-1] >= 0) & (after < n) & (np.take_along_axis(out_before, b, 1) == out_before[:, :-1])
        order = np.argsort(F[:, :-1][ok], kind="stable")
        pa, pb = F[:, :-1][ok][order], np.take_along_axis(F, b, 1)[ok][order]
        sel = count.flat[pa] != count.flat[pb]
        pa_list.append(pa[sel])
        pb_list.append(pb[sel])
    PA, PB = np.concatenate(pa_list), np.concatenate(pb_list)
    # a: the end with more growing modes
    swap = count.flat[PA] < count.flat[PB]
    PA, PB = np.where(swap, PB, PA), np.where(swap, PA, PB)
    EV = ev.reshape(count.size, -1)
    EST = gr.estimate.reshape(count.size, -1)
    ea, eb = EV[PA], EV[PB]
    k = np.arange(len(PA))
    # the mode that crossed: the least growing of the growing modes at a, and the eigenvalue
    # nearest to it at b; linear interpolation of its growth estimate to zero along the edge
    ia = np.argmin(np.where(grows.reshape(count.size, -1)[PA], EST[PA], np.inf), axis=-1)
    ra = ea[k, ia]
    ib = np.argmin(np.abs(eb - ra[:, None]), axis=-1)
    rb = eb[k, ib]
    ga, gb = EST[PA][k, ia], EST[PB][k, ib]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(gb < ga, ga / (ga - gb), 0.5)
    t = np.clip(np.nan_to_num(t, nan=0.5), 0.0, 1.0)
    ua = np.stack([X.flat[PA], Y.flat[PA], ra.imag], axis=-1)
    ub = np.stack([X.flat[PB], Y.flat[PB], rb.imag], axis=-1)
    return _Guesses(list(ua + t[:, None] * (ub - ua)), int(sp.inside.sum()), int(decided.sum()))


def _feet(V: np.ndarray, pts: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The feet (m, segments, 3) of the scaled points ``V`` (m, 3) on the segments of the scaled
    polyline ``pts``, projected in the first ``k`` columns, and the segments' squared lengths there."""
    a, d = pts[:-1, :], pts[1:] - pts[:-1]
    L2 = (d[:, :k] * d[:, :k]).sum(axis=1)
    lam = np.clip(((V[:, None, :k] - a[:, :k]) * d[:, :k]).sum(axis=2) / np.where(L2 > 0, L2, 1.0), 0.0, 1.0)
    return a + lam[..., None] * d, L2


def _on_branch(v: np.ndarray, pts: np.ndarray) -> bool:
    """Whether scaled point ``v`` lies on the scaled polyline ``pts`` (within its chord error)."""
    if len(pts) == 1:
        return bool(np.linalg.norm(v - pts[0]) < 1e-7)
    foot, L2 = _feet(v[None], pts, 3)
    return bool(np.any(np.linalg.norm(v - foot[0], axis=1) <= 0.05 * np.sqrt(L2) + 1e-7))


def _near_branch_mask(G: np.ndarray, pts: np.ndarray, cell: float) -> np.ndarray:
    """For each scaled guess ``(x, y, w)`` (rows of ``G``), whether it lies within ``cell`` of a
    scaled branch in ``(x, y)`` with a frequency within 0.1 (all guesses at once)."""
    foot, _ = _feet(G, pts, 2)
    dxy = G[:, None, :2] - foot[..., :2]
    return (((dxy * dxy).sum(axis=2) <= cell * cell) & (np.abs(G[:, None, 2] - foot[..., 2]) <= 0.1)).any(axis=1)


# ------------------------------------------------------------------------------------------
# the dataset
# ------------------------------------------------------------------------------------------
def _branch_records(br: Branch, prob: Any, names: Sequence[str]) -> tuple[list[str], list[str]]:
    """Per-point kinds and details of one branch (``names``: its columns)."""
    kinds, details = [], []
    m = len(br.points)
    for k, (kind, det) in enumerate(zip(br.kinds, br.details)):
        if kind == "fold":
            kd, text = "fold", f"fold in {names[int(det)] if int(det) < len(names) else det}"
        elif kind in ("test", "branch_point"):
            kd, text = _KIND_DETAIL[det or kind]
        elif kind == "boundary":
            c = prob.constraint_rows[prob.constraint_names.index(det)]
            kd, text = c.kind, det
            if c.bound is not None:
                # put the point exactly on a simple bound (it is within ~1e-16 of it) unless
                # that would spoil the residual (near a corner where everything is tiny)
                moved = br.points[k].copy()
                moved[list(names).index(c.bound[0])] = c.bound[1]
                if np.linalg.norm(prob.residual(moved)) <= max(1e-13, np.linalg.norm(prob.residual(br.points[k]))):
                    br.points[k] = moved
        elif kind == "closed":
            kd, text = "regular", "closes the curve (repeats the branch's first point)"
        else:
            kd, text = "regular", ""
        kinds.append(kd)
        details.append(text)
    for end, k in zip(br.end_reasons if len(br.end_reasons) == 2 else [None] + br.end_reasons, (0, m - 1)):
        if end in ("step_failure", "max_points", "max_arclength", "callback") and kinds[k] == "regular":
            kinds[k] = "endpoint"
            details[k] = f"continuation stopped: {end.replace('_', ' ')}"
    return kinds, details


def _check_points(
    model: LinearModel, names: Sequence[str], fixed: Mapping[str, float], cols: Sequence[np.ndarray], w: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Independent check: Re of the LAPACK eigenvalue of ``M^-1 A`` nearest to ``i w``, and its
    error bound.

    The model's matrices (eq. 8 or 11), not its characteristic polynomial, and LAPACK's
    ``geev`` on ``M^-1 A`` for all points in one call; the traced points lie inside the domain
    (``det M = A_G > 0``). Should ``M`` be singular at some point, :func:`stability.spectrum`
    (method ``"lapack"``, points outside the domain masked) is used instead. The bound is that
    of the LAPACK method (:func:`stability.linear.spectra.lapack_eigenvalues`): ``max(8 n u ||M^-1 A||, r)`` with
    ``r`` the inclusion radius of the eigenvalue as a root of the model's polynomial
    (:func:`stability.linear.roots.inclusion_radius`): LAPACK's error is absolute, ``~u`` of
    the largest mode, so at ``alpha_v = 1e12`` (slip mode ``-1.3e12``) the check of an O(1)
    neutral mode is good to ``~1e-4``, not ``1e-16``, and says so.
    """
    p: dict[str, Any] = {**fixed, **dict(zip(names, cols))}
    try:
        ev, bound, _ = lapack_eigenvalues(
            model, {n: np.broadcast_to(np.asarray(v, float), w.shape) for n, v in p.items()}
        )
    except np.linalg.LinAlgError:
        sp = spectrum(model, mask_unphysical=True, method="lapack", **p)
        ev, bound = sp.eigenvalues, sp.error_bound
    k = np.nanargmin(np.where(np.isnan(ev), np.inf, np.abs(ev - 1j * w[:, None])), axis=-1)[:, None]
    return np.take_along_axis(ev, k, -1)[:, 0].real, np.take_along_axis(bound, k, -1)[:, 0]


#: the attributes of the dataset's variables other than the traced parameters
_DATA_ATTRS: dict[str, dict[str, str]] = {
    "frequency": {
        "long_name": "neutral frequency",
        "units": "Omega",
        "comment": "Im s of the neutral mode, fixed frame, in units of the spin rate",
    },
    "tangent": {  # of each column {n}
        "long_name": "tangent, {n}",
        "units": "1",
        "comment": "{n} component of the unit tangent of the curve (oriented along the branch; continuation.dense "
        "interpolates with it)",
    },
    "branch": {"long_name": "branch", "comment": "index of the traced branch"},
    "kind": {
        "long_name": "kind of point",
        "comment": "regular, fold, zero_frequency, double_crossing, domain_edge or endpoint",
    },
    "detail": {"long_name": "what the special point is"},
    "residual": {
        "long_name": "backward error",
        "units": "1",
        "comment": "relative backward error of the neutral condition: the larger of its two rows, "
        "|Re p(i w)| / S_a and |Im p(i w)| / S_b, each scaled by its own size "
        "(stability.linear.neutrality)",
    },
    "leading": {
        "long_name": "traced mode leads",
        "comment": "the traced mode is the leading one (the curve is the stability boundary)",
    },
    "check_growth_rate": {
        "long_name": "check: LAPACK Re s",
        "units": "Omega",
        "comment": "independent check: Re s of the LAPACK eigenvalue of M^-1 A nearest to i w "
        "(zero within check_bound on a neutral curve)",
    },
    "check_bound": {
        "long_name": "check error bound",
        "units": "Omega",
        "comment": "error bound of check_growth_rate: max(8 n u ||M^-1 A||, inclusion radius of the "
        "eigenvalue as a root of the model's polynomial); absolute, so ~u |largest mode| "
        "(about 1e-8 at a collision, ~1e-4 at alpha_v = 1e12)",
    },
}


_POINT_ATTRS = {"long_name": "point", "comment": "index of the point along the traced branches"}


def _assemble(
    model: LinearModel,
    names: Sequence[str],
    fixed: Mapping[str, float],
    prob: Any,
    branches: list[Branch],
    ranges: Mapping[str, tuple[float, float]],
    attrs: Mapping[str, Any],
) -> xr.Dataset:
    """The dataset of the traced branches (columns of ``u``: ``names`` with the frequency at
    2): points, tangents, kinds, details, the backward error, where the traced mode leads
    (neutral curves) and the independent check (:func:`_check_points`), all points at once;
    its attributes: the parameters, the traced ``names`` (as ``x``, ``y``, ``z``), the form,
    the ``ranges`` and ``attrs``."""
    order = [*names[:2], "frequency", *names[2:]]
    kinds, details = [], []
    for br in branches:
        k, d = _branch_records(br, prob, order)
        kinds += k
        details += d
    points = np.concatenate([br.points for br in branches]) if branches else np.zeros((0, len(order)))
    tangents = np.concatenate([br.tangents for br in branches]) if branches else np.zeros((0, len(order)))
    branch = np.repeat(np.arange(len(branches)), [len(br.points) for br in branches])
    cols = [points[:, i] for i in range(points.shape[1]) if i != 2]
    w = points[:, 2]
    # the larger of the two rows' normwise relative backward errors (stability.linear.neutrality)
    residual = np.abs(prob.cond.residuals(np.delete(points, 2, axis=1), w)).max(axis=-1)
    leading = prob.traced_modes_lead(points) if isinstance(prob, NeutralProblem) else None
    if leading is not None:  # the double crossings where the leading mode changes
        details = [d + "; the leading mode changes" if k == "double_crossing" else d for k, d in zip(kinds, details)]
    data: dict[str, Any] = {
        n: (c, parameter_attrs(n) if n in LONG_NAMES else {"long_name": n, "units": "1"}) for n, c in zip(names, cols)
    }
    data["frequency"] = (w, _DATA_ATTRS["frequency"])
    for i, n in enumerate(order):
        data[f"tangent_{n}"] = (tangents[:, i], {k: v.format(n=n) for k, v in _DATA_ATTRS["tangent"].items()})
    data["branch"] = (branch.astype(np.int32), _DATA_ATTRS["branch"])
    data["kind"] = (np.array(kinds, dtype=object), _DATA_ATTRS["kind"])
    data["detail"] = (np.array(details, dtype=object), _DATA_ATTRS["detail"])
    data["residual"] = (residual, _DATA_ATTRS["residual"])
    if leading is not None:
        data["leading"] = (leading, _DATA_ATTRS["leading"])
    check, check_bound = _check_points(model, names, fixed, cols, w) if len(points) else (np.zeros(0), np.zeros(0))
    data["check_growth_rate"] = (check, _DATA_ATTRS["check_growth_rate"])
    data["check_bound"] = (check_bound, _DATA_ATTRS["check_bound"])
    # Variables from plain numpy arrays (fastpath: no conversion), one Dataset
    variables = {k: xr.Variable(("point",), np.asarray(v[0]), dict(v[1]), fastpath=True) for k, v in data.items()}
    ds_attrs = {
        "Conventions": "CF-1.10",
        "source": f"continuation.neutral_curve (tippe-stability {package_version()})",
        "model": model.name,
        "equations": model.equations,
        **{k: float(v) for k, v in fixed.items()},
        "fixed": ", ".join(sorted(fixed)),
        PRODUCT_ATTR: attrs[PRODUCT_ATTR],
        **dict(zip("xyz", names)),
        **{k: attrs[k] for k in ("fold_in",) if k in attrs},
        "form": prob.cond.form,
        **{k: attrs[k] for k in ("deflated_zero_roots",) if k in attrs},
        **{f"{n}_range": list(ranges[n]) for n in names},
        **attrs,  # the rest (title, note) last; a key placed above keeps its place
    }
    return xr.Dataset(variables, coords={"point": ("point", np.arange(len(points)), _POINT_ATTRS)}, attrs=ds_attrs)


# ------------------------------------------------------------------------------------------
# public functions
# ------------------------------------------------------------------------------------------
def neutral_curve(
    model: str | LinearModel,
    x: str,
    y: str,
    *,
    fixed: Mapping[str, Any],
    x_range: Sequence[float] | None = None,
    y_range: Sequence[float] | None = None,
    start: Sequence[Sequence[float]] | None = None,
    grid: tuple[int, int] = (25, 25),
    step: float | None = None,
    max_step: float = 0.05,
    max_angle: float = CURVE_MAX_ANGLE,
    max_points: int = 4000,
    tol: float = 1e-13,
    edge_margin: float = 1e-9,
    form: str | None = None,
    compiled: bool | None = None,
) -> xr.Dataset:
    """Trace the neutral curves of a linear model in the plane of two parameters.

    Parameters
    ----------
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"} or LinearModel
        Eqs. (8)-(9) or eq. (11).
    x, y : str
        The two traced parameters, from the model's ``q, fr_inv, sigma, alpha_v, mu``.
    fixed : mapping
        Values of the model's other parameters (``mu`` defaults to 2.28).
    x_range, y_range : pair of float, optional
        Ranges to trace in (default: the physical domain for ``q`` and ``sigma``,
        :data:`DEFAULT_RANGES` otherwise); the curves end where the ranges or the physical
        domain end.
    start : sequence of points, optional
        Start points ``(x, y)`` or ``(x, y, w)`` (projected onto the curve; without ``w`` the
        mode of smallest ``|Re s|`` gives it); default: from a coarse atlas.
    grid : pair of int
        Size of the coarse atlas for start points (2 to :data:`MAX_GRID` each).
    step, max_step : float
        Initial (default ``max_step``; halved by the engine when too long) and largest
        continuation step (arclength in the ranges scaled to 1).
    max_angle : float
        Largest turn of the tangent per step (radians): the chord error of the polyline is
        about ``max_angle * step / 8`` of the range; the dense output
        (:func:`continuation.dense`, cubic Hermite with the tangents) is far more accurate,
        ``O(step^4)``: about 6e-7 at the defaults for the sliding model's ``(q, sigma)`` curve.
    max_points : int
        Largest number of points per direction of a branch (at most :data:`MAX_POINTS`).
    tol : float
        Points satisfy the neutral condition to a relative backward error ``<= tol`` (each of
        its two rows scaled by its own size, :mod:`stability.linear.neutrality`).
    edge_margin : float
        Strict domain bounds (``1 - mu q^2 > 0``, ``sigma > 0``, ``mu > 0``) are applied as
        ``>= edge_margin``.
    form : {"crossing", "collision"}, optional
        Force the form (see :mod:`stability.linear.neutrality`); default from the model.
    compiled : bool, optional
        Use the compiled corrector of :mod:`stability.linear.neutral_compiled` where there is one
        (the sliding model's crossing form; numba, compiled on first use and cached on disk);
        False forces the engine's Python path. The two give the same points to rounding. None
        (default): the rule of :mod:`stability.execution` (:func:`~stability.execution.use_compiled`: the
        compiled corrector only if this process has compiled it already, unless
        ``TIPPE_KERNEL`` says otherwise); a first curve in a fresh process then compiles nothing.

    Returns
    -------
    xarray.Dataset
        Along dimension ``point``: ``x`` and ``y`` (named after the parameters), ``frequency``,
        the unit tangent ``tangent_<x>``, ``tangent_<y>``, ``tangent_frequency`` (for
        :func:`continuation.dense`), ``branch``, ``kind``, ``detail``, ``residual``, ``leading``,
        ``check_growth_rate`` and its bound ``check_bound``;
        CF attributes, the fixed parameters as attributes. Empty (no points) if no curve
        crosses the ranges: then with a ``UserWarning`` and the attribute ``note`` saying why
        (the start grid's signs are decided and the number of growing modes never changes, or
        no start guess converged).

    Raises
    ------
    ValueError, TypeError
        Unknown model or parameter, ``x == y``, bad range, fixed values outside the domain; a
        start grid that decides the sign of no growth rate at all (``start=`` is needed).

    Examples
    --------
    >>> import stability
    >>> ds = stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))
    >>> float(ds.sigma[ds.kind == "fold"].max())  # doctest: +ELLIPSIS
    1.1433...
    """
    m = get_model(model)
    x = parameter_name(m, x, "x")
    y = parameter_name(m, y, "y")
    if x == y:
        raise InputError(f"x and y must be two different parameters, got {x!r} twice")
    fixed = fixed_parameters(m, (x, y), fixed)
    max_step = check_positive("max_step", max_step)
    step = max_step if step is None else check_positive("step", step)
    max_angle = check_positive("max_angle", max_angle)
    tol = check_positive("tol", tol)
    edge_margin = check_positive("edge_margin", edge_margin)
    max_points = check_integer("max_points", max_points, minimum=2, maximum=MAX_POINTS)
    compiled = None if compiled is None else check_flag("compiled", compiled)
    if form is not None:
        form = check_choice("form", form, ("crossing", "collision"))
    if isinstance(grid, (str, bytes)) or not hasattr(grid, "__len__") or len(grid) != 2:
        raise ParameterTypeError(f"grid = {grid!r} must be a pair of integers >= 2")
    grid = tuple(check_integer("grid", g, minimum=2, maximum=MAX_GRID) for g in grid)
    check_start_grid(*grid)
    ranges, width, samples = _ranges((x, y), (x_range, y_range), fixed)
    scale = np.append(width, 1.0)
    prob = NeutralProblem(m, x, y, fixed, ranges, edge_margin, samples, form, compiled)

    note = None
    if start is None:
        found = _atlas_guesses(m, x, y, fixed, ranges, grid)
        if found.decided == 0:
            raise InputError(
                f"the start grid ({grid[0]} x {grid[1]} points over {x}_range = {_pair(ranges[x])} and "
                f"{y}_range = {_pair(ranges[y])}) could not decide the sign of a growth rate at any of its "
                f"{found.inside} points inside the domain (every point has a mode within rounding of neutral); "
                "pass start=[(x, y), ...] near the curve, or other ranges"
            )
        guesses = found.points
        if not guesses:
            undecided = found.inside - found.decided
            left_out = (
                f" ({undecided} points inside the domain have a mode within rounding of neutral and were left out)"
            )
            note = (
                f"no neutral curve crosses the ranges: the number of growing modes is the same at all "
                f"{found.decided} points of the {grid[0]} x {grid[1]} start grid where every sign is decided"
                f"{left_out if undecided else ''}; a closed curve inside one grid cell is not found this way: "
                "pass start= or a finer grid"
            )
    else:
        guesses = []
        if isinstance(start, (str, bytes)) or not hasattr(start, "__iter__"):
            raise ParameterTypeError(f"start = {start!r} must be a sequence of points (x, y) or (x, y, w)")
        for s in start:
            if isinstance(s, (str, bytes)) or not hasattr(s, "__len__") or len(s) not in (2, 3):
                raise InputError(f"start point {s!r}: a start point has 2 or 3 values (x, y[, w])")
            s = [as_scalar("start", v) for v in s]
            if len(s) == 2:
                p = {**fixed, x: np.asarray(s[0]), y: np.asarray(s[1])}
                sp0 = spectrum(m, mask_unphysical=True, **p)
                ev = sp0.eigenvalues
                if np.isnan(ev).all():
                    raise InputError(f"start point {x} = {s[0]:g}, {y} = {s[1]:g} is outside the physical domain")
                # the mode nearest the axis, structural zeros (s = 0 exactly, bound 0: the
                # sliding top's zero root at fr_inv = 0) excepted: they are neutral everywhere
                dist = np.where(structural_zeros(ev.real, ev.imag, sp0.error_bound), np.inf, np.abs(ev.real))
                s.append(float(ev[int(np.nanargmin(dist))].imag))  # every mode structural: 0, as any
            guesses.append(np.array(s))
        if not guesses:
            raise InputError("start = [] is empty: give at least one point, or None for starts from an atlas")
    trace = dict(step=step, max_step=max_step, max_angle=max_angle, max_points=max_points)
    options = TraceOptions(fold_components=(0, 1), scale=scale, tol=tol, **trace)
    branches: list[Branch] = []
    cell = 1.5 / (min(grid) - 1)
    skip = np.zeros(len(guesses), dtype=bool)
    G = np.array(guesses).reshape(len(guesses), 3) / scale
    for i, g in enumerate(guesses):
        # an atlas guess lies within a grid cell of its curve: skip it if a traced branch passes
        # that close (with a frequency within 0.1); the projection would only find it again
        if skip[i]:
            continue
        try:
            u = project(prob, g, scale=scale, max_move=0.25 if start is None else np.inf, tol=tol)
        except EngineConvergenceError:
            if start is None:
                continue
            raise ConvergenceError(
                f"start point ({x}, {y}, w) = ({g[0]:g}, {g[1]:g}, {g[2]:g}): Newton's method did not "
                f"reach a neutral point (backward error <= {tol:g}) from there; give a start closer "
                "to the curve (or without w, which then comes from the mode of smallest |Re s|)"
            ) from None
        if not np.all(prob.constraints(u) >= 0):
            if start is None:
                continue
            bad = [n for n, gv in zip(prob.constraint_names, prob.constraints(u)) if gv < 0]
            raise InputError(
                f"start point ({x}, {y}, w) = ({g[0]:g}, {g[1]:g}, {g[2]:g}) converged to the neutral "
                f"point ({u[0]:.6g}, {u[1]:.6g}, {u[2]:.6g}), outside the ranges or the physical "
                f"domain ({'; '.join(bad)})"
            )
        if any(_on_branch(u / scale, b.points / scale) for b in branches):
            continue
        br = trace_both(prob, u, options)
        branches.append(br)
        if start is None:
            skip[i + 1 :] |= _near_branch_mask(G[i + 1 :], br.points / scale, cell)
    if not branches and note is None:
        note = (
            f"no neutral curve traced: none of the {len(guesses)} start guesses of the start grid "
            f"converged to a neutral point (backward error <= {tol:g}) inside the ranges; pass start= "
            "near the curve"
        )
    attrs = {
        PRODUCT_ATTR: "neutral_curve",
        "deflated_zero_roots": prob.cond.deflate,
        "title": f"neutral curves of the {m.name} model in the ({x}, {y}) plane",
    }
    if note is not None:
        attrs["note"] = note
        warnings.warn(note, UserWarning, stacklevel=2)
    return _assemble(m, (x, y), fixed, prob, branches, ranges, attrs)


def _pair(r: tuple[float, float]) -> str:
    return f"({r[0]:g}, {r[1]:g})"


def fold_curve(
    model: str | LinearModel,
    x: str,
    y: str,
    z: str,
    *,
    fold_in: str,
    fixed: Mapping[str, Any],
    x_range: Sequence[float] | None = None,
    y_range: Sequence[float] | None = None,
    z_range: Sequence[float] | None = None,
    step: float = 0.01,
    max_step: float = 0.05,
    max_angle: float = CURVE_MAX_ANGLE,
    max_points: int = 4000,
    tol: float = 1e-12,
    edge_margin: float = 1e-9,
) -> xr.Dataset:
    """Follow the folds of the ``(x, y)`` neutral curves as a third parameter ``z`` varies.

    The folds of the curve at ``z = fixed[z]`` (extrema of ``fold_in``, one of ``x`` and
    ``y``) are found by :func:`neutral_curve` and each is continued in ``(x, y, w, z)`` with the
    equations of :class:`FoldProblem`. Example: the largest unstable ``sigma`` as a function of
    ``fr_inv`` is ``fold_curve("sliding", "q", "sigma", "fr_inv", fold_in="sigma", ...)``.

    Parameters
    ----------
    model : str or LinearModel
    x, y : str
        The plane of the neutral curve.
    z : str
        The third parameter; ``fixed[z]`` is where the folds are first found.
    fold_in : str
        ``x`` or ``y``: the parameter whose extremum is followed.
    fixed : mapping
        All the model's other parameters, including the start value of ``z``.
    x_range, y_range, z_range : pair of float, optional
        Ranges (defaults as in :func:`neutral_curve`).
    step, max_step, max_angle, max_points, edge_margin
        As in :func:`neutral_curve`.
    tol : float
        Residual tolerance of the three equations.

    Returns
    -------
    xarray.Dataset
        Along ``point``: ``x``, ``y``, ``z``, ``frequency``, ``branch``, ``kind`` (``fold``
        marks an extremum of ``z`` along the fold curve), ``detail``, ``residual`` (backward
        error of the neutral condition) and ``check_growth_rate``.
    """
    m = get_model(model)
    x, y, z = (parameter_name(m, n, w_) for n, w_ in ((x, "x"), (y, "y"), (z, "z")))
    if len({x, y, z}) != 3:
        raise InputError(f"x, y and z must be three different parameters, got {x!r}, {y!r}, {z!r}")
    check_choice("fold_in", fold_in, (x, y))
    if not isinstance(fixed, Mapping) or z not in fixed:
        raise ParameterTypeError(f"fixed must give the start value of z = {z!r}")
    full = fixed_parameters(m, (x, y), fixed)
    trace = dict(step=step, max_step=max_step, max_angle=max_angle, max_points=max_points)
    plane = neutral_curve(m, x, y, fixed=full, x_range=x_range, y_range=y_range, edge_margin=edge_margin, **trace)
    rest = {k: v for k, v in full.items() if k != z}
    ranges, width, samples = _ranges((x, y, z), (x_range, y_range, z_range), full)
    scale = np.insert(width, 2, 1.0)
    prob = FoldProblem(fold_in, NeutralCondition(m, (x, y, z), rest, samples, plane.attrs["form"]), ranges, edge_margin)
    options = TraceOptions(fold_components=(3,), scale=scale, tol=tol, **trace)
    folds = plane.where(plane.detail == f"fold in {fold_in}", drop=True)
    branches: list[Branch] = []
    for k in range(folds.sizes["point"]):
        u = np.array([float(folds[x][k]), float(folds[y][k]), float(folds.frequency[k]), float(full[z])])
        if any(_on_branch(u / scale, b.points / scale) for b in branches):
            continue
        branches.append(trace_both(prob, u, options))
    title = f"folds in {fold_in} of the ({x}, {y}) neutral curves of the {m.name} model as {z} varies"
    attrs = {PRODUCT_ATTR: "fold_curve", "fold_in": fold_in, "title": title}
    return _assemble(m, (x, y, z), rest, prob, branches, ranges, attrs)
