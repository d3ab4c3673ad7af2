"""The family of tilted steady states traced against Jellett's integral by continuation.

Equations (docs/steady_states.md, sec. 3.4). A no-slip steady state of tilt ``theta`` and
precession rate ``lam`` is the state of :func:`stability.steady.family.state_core`
(``k = (sin theta, 0, cos theta)``, ``omega = lam (K + q k)``, ``V0 = omega x K``). On it, the
nonlinear model's right-hand side in the precessing frame, ``F(y) = f(y) - lam G y``
(:func:`stability.nonlinear.kernels.rhs`: the same compiled function :func:`stability.simulate`
integrates), vanishes in every component but one, the ``omega`` component along
``K x k = sin(theta) e_2``: the torque balance about G, which carries the factor
``sin(theta)`` of the vertical states (steady at every spin). The continuation problem is that
one component with the vertical branch divided out,

    R(theta, lam) = (F(y(theta, lam)) . e_2) / sin(theta)  /  (1 + lam^2)       (1 equation, 2 unknowns),

evaluated at the complex tilt ``theta + i h`` (``h = 1e-30``): the real part is ``R``, the
imaginary part ``h dR/dtheta``, both exact to rounding, at ``theta = 0`` too (the limit is
analytic). All terms of the rotational equations are ``O(sin theta)`` on the no-slip manifold,
so the division loses nothing near the branch points. ``dR/dlam`` comes from a complex step in
``lam`` (a central difference at ``sin theta = 0``). The closed form (S3) is not used: it
checks the traced branch (tests/test_steady_branch.py).

Start: the branch point on the upright spin, ``R(0, lam_b) = 0`` (solved by Newton's method on
the nonlinear rhs; ``R(0, lam)`` is a quadratic in ``lam``, which gives the first guess), or,
if the family does not reach the upright spin, the one on the inverted spin. The engine
(:func:`continuation.trace`) follows the family until a constraint ends it exactly: the other
vertical state (``theta = pi``: the inverted branch point) or ``|J| = jellett_max`` (the family
runs to ``J = inf`` at ``c0``); a fold in ``J`` is located as the zero of the test function
``dJ/ds`` (``J`` by :func:`stability.nonlinear.quantities.h_cg` on the state, its gradient by
the complex step). After tracing, every point's spectrum (:mod:`stability.steady.linearisation`,
batched) and flag (:mod:`stability.steady.verdicts`); a change of flag between two points that
is not at a fold or a branch point is marked ``stability_change`` (the theory says there is
none: docs/steady_states.md, sec. 4.1).

Degenerate parameters (``fr_inv = 0`` or ``q = 0``): the normal force has no moment about G,
``R`` is ``lam^2`` times a function of ``theta`` alone, and the family is the line
``theta = theta0`` for every ``lam`` (a vertical line in the ``(J, tilt)`` plane); it is traced
with ``R / lam^2`` from ``jellett_max / 1000`` to ``jellett_max`` (both ends kind ``end``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from continuation.engine import TraceOptions, trace
from stability.jit import python

from ..errors import ConvergenceError, DomainError
from ..execution import pick
from ..linear.neutral_curves import CURVE_MAX_ANGLE
from ..nonlinear import get_nonlinear_model
from ..nonlinear.kernels import CODES
from ..parameters import DEFAULT_MU, check_flag, check_interval, check_positive
from . import branch_compiled as kernels
from . import family
from .products import check_scales, product_attrs, sliding_parameters, state_variables, variable
from .states import state_values

#: branches of at least this many points (``~pi / max_step``) run the compiled step by default;
#: fewer run the engine's Python path on the interpreted residual (stability.execution's rule;
#: the crossover measured by benchmarks/cold_start.py, docs/performance.md)
BRANCH_COMPILED_FROM = 1000

__all__ = ["SteadyBranchProblem", "branch_points", "points_dataset", "steady_branch"]

#: the smallest max_step (a branch is ~pi / max_step points, within the trace's 100000)
MIN_MAX_STEP = 1e-4

#: kinds of points of a branch ("regular" for an ordinary point, as neutral_curve says)
KINDS = ("regular", "branch_point", "fold", "stability_change", "end")


class SteadyBranchProblem:
    """Continuation problem of the tilted family: ``u = (theta, log lam)``, one equation.

    The unknown ``log lam`` (``lam > 0``: the branch with ``J > 0``) keeps the arclength
    bounded where the family runs to ``J = inf`` (``lam -> inf`` at ``c0``).

    Parameters
    ----------
    params : dict of float
        ``q, sigma, fr_inv, alpha_v, mu``.
    p : numpy.ndarray
        The kernels' parameter vector.
    compiled : bool
        The compiled residual, or its interpreted execution.

    Attributes
    ----------
    jellett_max, jellett_min : float
        Where the branch is cut if it runs to ``J = inf``, and (degenerate parameters only) the
        lower cut of the vertical line; set by :func:`steady_branch`.
    constraint_names : tuple of str
        ``"upright"`` (``theta >= 0``), ``"inverted"`` (``theta <= pi``), ``"jellett_max"``
        (``|J| <= jellett_max``) and, degenerate, ``"jellett_min"``.
    test_function_names : tuple of str
        ``"jellett_fold"``: ``dJ/ds`` along the branch.
    """

    test_function_names = ("jellett_fold",)

    def __init__(self, params: dict[str, float], p: np.ndarray, compiled: bool = True):
        m = get_nonlinear_model("sliding")
        #: the residual's functions: compiled, or their interpreted execution (stability.jit.python)
        self.kernels = kernels if compiled else python(kernels)
        self.params, self.p, self.q = dict(params), p, params["q"]
        self.code, self.n_full = CODES[m.name], len(m.state)
        #: the residual's model arguments (:mod:`stability.steady.branch_compiled`)
        self.model = (p, self.q, self.code, self.n_full)
        self.degenerate = params["fr_inv"] == 0.0 or params["q"] == 0.0
        #: the scale of lam^2 on the family, mu fr_inv |q| (lam^2 P(c) = mu fr_inv q, S3; 0 if degenerate):
        #: what branch_compiled.residual_and_jacobian divides by
        self.weight = 0.0 if self.degenerate else params["mu"] * params["fr_inv"] * abs(params["q"])
        self.jellett_max, self.jellett_min = math.inf, 0.0  # the cuts of J, set by steady_branch
        self.constraint_names = ("upright", "inverted", "jellett_max") + (("jellett_min",) if self.degenerate else ())
        self._last: tuple[tuple[float, float], tuple[float, np.ndarray]] | None = None
        #: the compiled step's arguments that stay (the cuts of J are set after construction)
        sigma, mu = params["sigma"], params["mu"]
        self._step_head = (p, self.q, sigma, mu, self.code, self.n_full, self.degenerate, self.weight)

    # --- the residual -------------------------------------------------------------------
    def divided_residual(self, theta: float, lam: float) -> float:
        """``(F . e_2) / sin(theta)`` (unscaled), at ``theta = 0`` the limit."""
        return self.kernels.divided(float(theta), float(lam), *self.model)[0]

    def residual_and_jacobian(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``R`` (1,) and ``dR/d(theta, log lam)`` (1, 2)."""
        r, rt, rl = self.kernels.residual_and_jacobian(float(u[0]), float(u[1]), *self.model, self.weight)
        return np.array([r]), np.array([[rt, rl]])

    def residual(self, u: np.ndarray) -> np.ndarray:
        """``R(theta, log lam)`` (1,)."""
        return self.residual_and_jacobian(u)[0]

    def jacobian(self, u: np.ndarray) -> np.ndarray:
        """``dR/d(theta, log lam)`` (1, 2)."""
        return self.residual_and_jacobian(u)[1]

    # --- Jellett's integral, constraints, test function ------------------------------------
    def jellett(self, u: np.ndarray) -> tuple[float, np.ndarray]:
        """``J`` at the state of ``u`` and its gradient (complex step of the nonlinear layer's
        formula), cached for the last ``u``."""
        key = (float(u[0]), float(u[1]))
        if self._last is not None and self._last[0] == key:
            return self._last[1]
        j, jt, jl = self.kernels.jellett(key[0], key[1], self.q, self.params["sigma"], self.params["mu"])
        out = (j, np.array([jt, jl]))
        self._last = (key, out)
        return out

    def constraints(self, u: np.ndarray) -> np.ndarray:
        """``[theta, pi - theta, jellett_max - |J|(, |J| - jellett_min)]``, ``>= 0`` on the branch."""
        return self.kernels.constraint_values(
            float(u[0]), self.jellett(u)[0], self.jellett_max, self.jellett_min, self.degenerate
        )

    def test_functions(self, u: np.ndarray, t: np.ndarray) -> np.ndarray:
        """``[d(log |J|)/ds]``: zero at a fold of the family in ``J`` (relative to ``J``, so that
        the engine's rounding floor of events means the same at every scale of ``J``)."""
        j, g = self.jellett(u)
        return np.array([(g[0] * t[0] + g[1] * t[1]) / abs(j)])

    def compiled_step(self, *corrector: Any) -> tuple:
        """The engine's hook (:mod:`continuation.problem`, which lists the arguments):
        :func:`stability.steady.branch_compiled.step` (corrector, tangent, constraints and test
        function in one compiled call)."""
        return self.kernels.step(*self._step_head, float(self.jellett_max), float(self.jellett_min), *corrector)

    # --- start points -------------------------------------------------------------------
    def branch_point(self, orientation: str) -> float | None:
        """The precession rate ``lam_b > 0`` at which the family leaves the vertical state
        (``R(theta_v, lam_b) = 0``), or None if it does not reach it.

        ``R(theta_v, lam)`` is ``A lam^2 + B`` (the rhs is quadratic in the rates on the no-slip
        manifold, ``B ~ mu fr_inv q``): the guess ``lam^2 = -B / A`` from evaluations at ``0`` and
        at the family's own scale ``lam_w = sqrt(weight)`` (so that ``A lam_w^2`` and ``B`` are of
        one size at every scale), then Newton's method on ``R`` itself to the rounding floor."""
        theta = 0.0 if orientation == "upright" else math.pi
        w = self.weight
        b = self.divided_residual(theta, 0.0)
        a = (self.divided_residual(theta, math.sqrt(w)) - b) / w  # w > 0: not degenerate here
        if a == 0.0 or not -b / a > 0.0:
            return None
        lam = math.sqrt(-b / a)
        for _ in range(20):
            _, _, rl = self.kernels.residual_and_jacobian(theta, math.log(lam), *self.model, w)
            r = self.divided_residual(theta, lam)
            step = r / (rl / lam * (lam * lam + w))
            lam -= step
            if abs(step) <= 4e-16 * abs(lam):
                break
        return lam if lam > 0 else None

    def degenerate_tilt(self) -> float | None:
        """(Degenerate parameters) the tilt ``theta0`` of the vertical line: the sign change of
        ``R(theta, 1)`` on ``(0, pi)`` (64 samples, then Brent), or None."""
        from scipy.optimize import brentq

        th = np.linspace(0.0, math.pi, 65)[1:-1]
        r = np.array([self.divided_residual(t, 1.0) for t in th])
        idx = np.nonzero(np.sign(r[:-1]) * np.sign(r[1:]) < 0)[0]
        if idx.size != 1:
            exact = np.nonzero(r == 0.0)[0]
            return float(th[exact[0]]) if exact.size == 1 and idx.size == 0 else None
        i = int(idx[0])
        return float(brentq(lambda t: self.divided_residual(t, 1.0), th[i], th[i + 1], xtol=1e-16, rtol=8.9e-16))


def branch_points(*, q: Any, sigma: Any, fr_inv: Any, alpha_v: Any = 0.5, mu: Any = DEFAULT_MU) -> dict[str, float]:
    """Jellett's integral ``|J|`` at the branch points of the tilted family, located on the
    nonlinear right-hand side (:meth:`SteadyBranchProblem.branch_point`), NaN where the family
    does not reach the state. Keys ``"upright"``, ``"inverted"``."""
    params, p = sliding_parameters("sliding", q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=alpha_v, mu=mu)
    prob = SteadyBranchProblem(params, p)
    out = {}
    for orientation in ("upright", "inverted"):
        lam = None if prob.degenerate else prob.branch_point(orientation)
        theta = 0.0 if orientation == "upright" else math.pi
        out[orientation] = math.nan if lam is None else abs(prob.jellett(np.array([theta, math.log(lam)]))[0])
    return out


def steady_branch(
    model: str = "sliding",
    *,
    q: Any,
    sigma: Any,
    fr_inv: Any,
    alpha_v: Any,
    mu: Any = DEFAULT_MU,
    jellett_max: Any = None,
    max_step: Any = 0.02,
    max_angle: Any = CURVE_MAX_ANGLE,
    compiled: bool | None = None,
) -> xr.Dataset:
    """The family of tilted steady states, traced by continuation against Jellett's integral.

    Parameters
    ----------
    model : {"sliding"}
    q, sigma, fr_inv, alpha_v, mu : float
        Parameters (docs/conventions.md), single numbers in the physical domain.
    jellett_max : float, optional
        Where a family that runs to ``J = inf`` (at ``c0``) is cut, simulate's units; default
        10 times ``|J|`` at the branch point the trace starts from (degenerate parameters:
        10 times the upright spin 1's ``sigma (1 + q)``).
    max_step, max_angle : float
        The engine's largest step (arclength in ``(theta, log lam)``) and the
        largest turn of the tangent per step (radians): about ``pi / max_step`` points.
    compiled : bool, optional
        Let the engine use the problem's compiled step
        (:func:`stability.steady.branch_compiled.step`); False: the engine's Python path on the
        interpreted residual; None (default): compiled if it is in memory or the branch has
        :data:`BRANCH_COMPILED_FROM` points or more (:func:`stability.execution.pick`) (the
        same points to rounding).

    Returns
    -------
    xarray.Dataset
        Over ``point``, in the order traced (from the branch point where the trace starts):
        ``tilt`` (degrees), ``jellett`` (``J > 0``: the mirror branch ``J -> -J`` has the
        same tilts and stability), ``precession_rate``, ``axial_spin``, ``energy``,
        ``upright_equivalent_spin`` (``J / (sigma (1 + q))``: the upright spin with this
        ``J``), ``growth_rate``, ``n_neutral``, ``stability`` (flag), ``stability_jacobian``,
        ``kind`` ("branch_point", "fold", "stability_change", "end" or "regular" for an ordinary point, as :func:`stability.neutral_curve`)
        and ``detail``; attributes: the parameters, ``start`` (the branch point traced from),
        ``ends``, ``jellett_max``, the engine's work counts. No points if the family does not
        exist (attribute ``note`` says why).

    Raises
    ------
    ValueError, TypeError
        Bad parameters or options.
    stability.errors.ConvergenceError
        The continuation failed. Not expected in the physical domain except where the
        residual's rounding (``~u / sin(tilt)`` of its terms, from the division by
        ``sin(tilt)``, or ``~u / A_G`` from the mass matrix) exceeds the corrector's tolerance:
        a family that lies within ``~1e-4`` rad of a vertical state (``sigma (1 +- q)`` within
        ``~1e-9`` of ``A_G``, next to a high-spin class boundary) or ``A_G < ~1e-8``. The message
        says which; :func:`stability.steady_states` (closed forms) answers at any ``J`` there.
    """
    params, p = sliding_parameters(model, q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=alpha_v, mu=mu)
    # a branch is at most ~pi / max_step points (the engine's max_points is 100000): 1e-4 or more
    max_step = check_interval("max_step", max_step, MIN_MAX_STEP, math.inf, closed="left")
    max_angle = check_interval("max_angle", max_angle, 1e-6, math.pi, closed="both")
    if compiled is None:  # by size (stability.execution.pick); the compiled step if in memory
        compiled = pick(kernels.step, math.pi / max_step, below=BRANCH_COMPILED_FROM) is kernels.step
    compiled = check_flag("compiled", compiled)
    q, sigma, mu = params["q"], params["sigma"], params["mu"]
    jmax = None if jellett_max is None else check_positive("jellett_max", jellett_max)
    check_scales(params, jmax, jellett_name="jellett_max")
    prob = SteadyBranchProblem(params, p, compiled=compiled)
    title = "Tilted steady states of the sliding Tippe top against Jellett's integral"
    attrs = product_attrs("steady_branch", title, "continuation.steady_branch", params, removed_neutral=True)
    attrs["model"] = "sliding"
    options = TraceOptions(
        step=min(max_step, 0.02), max_step=max_step, max_angle=max_angle, max_points=100000, compiled=compiled
    )
    if prob.degenerate:
        theta0 = prob.degenerate_tilt()
        if theta0 is None:
            note = (
                "no tilted steady state: with fr_inv = 0 or q = 0 the family is one tilt at every "
                "J, and here there is none (or every tilt is steady: q = 0, sigma = 1 - mu q^2)"
            )
            return points_dataset(prob, np.zeros((0, 2)), [], [], dict(attrs, note=note))
        j_unit = abs(prob.jellett(np.array([theta0, 0.0]))[0])  # J is linear in lam: J(lam = 1)
        jmax = 10.0 * abs(family.upright_jellett(q=q, sigma=sigma)) if jmax is None else jmax
        prob.jellett_max, prob.jellett_min = jmax, jmax / 1000.0
        ell0 = math.log(math.sqrt(jmax * prob.jellett_min) / j_unit)
        lo, hi = branches = [
            trace(prob, [theta0, ell0], options, tangent0=[0.0, d], project_start=True) for d in (-1, 1)
        ]
        pts = np.concatenate([lo.points[::-1], hi.points[1:]])
        raw = list(zip(lo.kinds[::-1] + hi.kinds[1:], lo.details[::-1] + hi.details[1:]))
        ends = [half.end_reasons[0] for half in branches]
        start = "vertical line (fr_inv = 0 or q = 0)"
    else:
        lam_b = prob.branch_point(start := "upright")
        if lam_b is None:
            lam_b = prob.branch_point(start := "inverted")
        if lam_b is None:
            note = "the tilted family reaches neither vertical state (it does not exist here)"
            return points_dataset(prob, np.zeros((0, 2)), [], [], dict(attrs, note=note))
        theta_b, t0 = (0.0, 1.0) if start == "upright" else (math.pi, -1.0)
        j_b = abs(prob.jellett(np.array([theta_b, math.log(lam_b)]))[0])
        if jmax is not None and not jmax > j_b:
            raise DomainError(
                f"jellett_max = {jmax:.6g} is outside the allowed range: jellett_max > {j_b:.6g}, "
                f"the Jellett integral at the {start} branch point where the family starts"
            )
        prob.jellett_max = 10.0 * j_b if jmax is None else jmax
        branches = [trace(prob, [theta_b, math.log(lam_b)], options, tangent0=[t0, 0.0], project_start=False)]
        pts = branches[0].points.copy()
        raw = [("branch_point", f"{start} spin")] + list(zip(branches[0].kinds[1:], branches[0].details[1:]))
        ends = branches[0].end_reasons
    kinds, details = [], []
    for i, (k, d) in enumerate(raw):  # the engine's kinds of points (module docstring) in the branch's words
        if k == "boundary" and d.startswith("jellett"):
            k, d = "end", f"|J| = {prob.jellett_max if d == 'jellett_max' else prob.jellett_min:.6g} (cut)"
        elif k == "boundary":  # a vertical state: the branch point, on the bound (within rounding of it)
            k, d, pts[i, 0] = "branch_point", f"{d} spin", 0.0 if d == "upright" else math.pi
        elif k == "test" and abs(math.sin(pts[i, 0])) < 1e-6:
            # dJ/ds vanishes at the branch point itself (J is even in the tilt about a vertical
            # state: the vertex of the pitchfork); rounding there is no fold
            k, d = "regular", ""
        elif k == "test":
            k, d = "fold", "fold in J (dJ/ds = 0)"
        elif k != "branch_point" or (d == "" and prob.degenerate):
            k = "regular"
        kinds.append(k)
        details.append(d)
    for k, end in ((0, ends[0]), (-1, ends[-1])) if len(ends) == 2 else ((-1, ends[-1]),):
        if end != "boundary" and kinds[k] == "regular":
            kinds[k], details[k] = "end", f"continuation stopped: {end.replace('_', ' ')}"
    if "step_failure" in ends:
        a_g = family.a_g(q, mu)
        why = []
        if abs(math.sin(pts[-1, 0])) < 1e-4:
            why.append(
                f"the family stays within {abs(math.sin(pts[-1, 0])):.2g} rad of the vertical state, where the "
                "residual (divided by sin(tilt)) loses ~u / sin(tilt) of its digits: sigma (1 + q) = "
                f"{sigma * (1 + q):.17g} and sigma (1 - q) = {sigma * (1 - q):.17g} against A_G = {a_g:.17g} "
                "(a high-spin class boundary is sigma (1 +- q) = A_G)"
            )
        if a_g < 1e-8:
            why.append(f"A_G = 1 - mu q^2 = {a_g:.3g} is near the domain edge, where the mass matrix is singular")
        raise ConvergenceError(
            f"steady_branch: the continuation failed after {len(pts)} points "
            f"(tilt {math.degrees(pts[-1, 0]):.6g} deg); parameters {params}"
            + (f": {'; '.join(why)}. stability.steady_states (closed forms) answers at any J there" if why else "")
        )
    attrs.update(start=start, ends=", ".join(ends), jellett_max=prob.jellett_max)
    attrs.update({n: sum(getattr(b, n) for b in branches) for n in ("n_newton", "n_residual", "n_jacobian")})
    attrs["degenerate"] = int(prob.degenerate)
    return points_dataset(prob, pts, kinds, details, attrs)


def points_dataset(
    prob: SteadyBranchProblem, pts: np.ndarray, kinds: list[str], details: list[str], attrs: dict[str, Any]
) -> xr.Dataset:
    """Spectra, flags and the Dataset of points ``(theta, log lam)`` of the family (traced, or
    solved otherwise, e.g. by the benchmark's baseline), with their kinds and details."""
    theta, lam = pts[:, 0], np.exp(pts[:, 1])
    q, sigma = prob.params["q"], prob.params["sigma"]
    vertical = np.array([k == "branch_point" and d.endswith("spin") for k, d in zip(kinds, details)], dtype=bool)
    c = np.where(vertical, np.sign(np.cos(theta)), np.cos(theta))
    states = [("upright" if c[i] > 0 else "inverted") if vertical[i] else "tilted" for i in range(len(pts))]
    # a branch point is the vertical state of spin omega . K = lam (1 + q c)
    _, _, values = state_values(states, theta, lam, family.omega_vertical(c, lam, q), prob.p, prob.params)
    for i in range(1, len(pts)):  # a change of flag that is no fold or branch point (never expected)
        if values["stability"][i] != values["stability"][i - 1] and kinds[i] == kinds[i - 1] == "regular":
            kinds[i], details[i] = "stability_change", "the flag changes away from a fold or branch point"
    values.update(tilt=np.degrees(theta), precession_rate=lam)
    note = "at a branch point: spin / (1 + q cos(tilt))"
    kind_attrs = {"long_name": "kind of point", "comment": "branch_point, fold, stability_change, end, or regular"}
    equivalent = "spin of the upright state with the same J, J / (sigma (1 + q))"
    j_upright = family.upright_jellett(q=q, sigma=sigma)
    data = {
        **state_variables("point", values, "branch points", precession_rate=note),
        "upright_equivalent_spin": variable(
            "point", values["jellett"] / j_upright, equivalent, "Omega", short="upright-equiv. spin"
        ),
        "kind": ("point", np.array(kinds, dtype=str), kind_attrs),
        "detail": ("point", np.array(details, dtype=str), {"long_name": "what the special point is"}),
    }
    index = {"long_name": "point", "comment": "index along the branch"}
    return xr.Dataset(data, coords={"point": ("point", np.arange(len(pts)), index)}, attrs=attrs)
