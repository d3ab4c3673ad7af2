"""The neutral condition of a linear model, ``det(i w M - A) = 0``, as real equations.

A mode ``x ~ exp(s t)`` is neutral when ``s = i w`` with ``w`` real (its frequency, fixed frame,
units of the spin rate). With ``p(s) = det(s M - A) = sum_k c_k s^k`` (eq. 11 for the sliding
model, eq. 8 for the fixed-pivot and rolling models; coefficients from the model, mass matrix
included) there are two forms:

*crossing* (dissipative models)
    Write ``p(i w) = A(w) + i B(w)`` with the real polynomials ``a_k = Re(c_k i^k)`` and
    ``b_k = Im(c_k i^k)``. The equations are ``F = [A(w) / S_a, B(w) / S_b]``, each row scaled by
    its own size,

    ``S_a = max(1, |w|)^n (||a||_1 + sum_j |x_j| ||da/dx_j||_1)``

    (and ``S_b`` from ``b``), the sum over the free parameters ``x_j``: two real equations;
    with two free parameters the solutions form curves in ``(x, y, w)``, along which one mode
    sits on the imaginary axis. Each ``|F_i|`` is the normwise relative backward error of its
    row with respect to its coefficients and to relative perturbations of the free parameters
    (about ``1e-16`` at a rounded root); the residual reported is the larger of the two.

    Why one scale per row: for eq. 11, ``p(i w) = alpha_v P_r(w) + i mu w P_f(w)``, so with one
    scale for both rows (``||c||_1``, as before) the real row is ``O(alpha_v)`` of it when
    alpha_v is small and the imaginary row ``O(1/alpha_v)`` when it is large, and a tolerance on
    the pair is then met by any point that satisfies the dominant row alone (32,717 spurious
    points of the rolling limit ``P_r = 0`` were traced at ``alpha_v = 1e12``, and the curve was
    off by ``7e-12`` at ``1e-12``). Row by row, ``F`` does not change when the dissipative part
    is scaled: any alpha_v > 0 gives the same equations, as the closed form says. Why the
    parameter term: a row whose coefficients cancel (``A_G = 1 - mu q^2`` at the corner
    ``q -> 1/sqrt(mu)`` of the ``(q, sigma)`` plane, where ``||a||_1 ~ mu (A_G + sigma) ~ 1e-9``)
    moves by far more than its own rounding when a free parameter moves by one ulp (here
    ``5e-8`` of ``S_a`` per ulp of ``q``): no double solves that row to ``1e-13`` of
    ``||a||_1``, while relative to what one ulp of the parameters does to it, it is solved to
    rounding.

    The scales are evaluated at the point and held constant in the Jacobian. The Newton and
    minimum-norm steps do not depend on them at all (scaling the rows of a full-row-rank system
    leaves its solution set unchanged), so the scales only decide what ``||F|| <= tol``
    accepts, and that is a property of the point alone (the same number as the stored residual,
    whatever the corrector started from). ``S_a`` and ``S_b`` do not vanish in this form (a
    model whose ``a`` or ``b`` vanishes identically is conservative and takes the collision
    form; at a point where one does, e.g. ``alpha_v = 0`` reached along a traced ``alpha_v``,
    the domain's edge, the row uses 1). The normwise ``max(1, |w|)^n`` rather than the
    componentwise ``sum_k |a_k| |w|^k``, which tends to zero where a root passes through
    ``s = 0`` (``c_0 -> 0`` and ``w -> 0``) and would spoil Newton's method there.
*collision* (conservative models, where every ``c_k i^k`` has one common phase, so
    ``p(i w) = e^{i theta} P(w)`` with ``P`` real)
    Such a model has ``Re s = 0`` exactly for every real root of ``P`` (a whole region is
    neutral); it loses stability only where two real roots collide and leave the axis,
    ``P(w) = P'(w) = 0`` (eq. 8: the discriminant ``sigma_hat^2 = 4 kappa``). This form
    solves ``F = [P(w) / S_0, P'(w) / S_1]`` (``S_0 = ||a||_1 max(1, |w|)^n``,
    ``S_1 = n ||a||_1 max(1, |w|)^(n-1)``). The fixed-pivot and rolling models are of this kind,
    and so is the sliding model at ``alpha_v = 0`` (the free top).

Structural zero roots (the sliding model's ``c0 = -mu alpha_v q fr_inv`` vanishing identically
when ``fr_inv``, ``q`` or ``alpha_v`` is held at 0) are deflated when the trailing coefficient
is exactly zero at every sample point: ``p(s) / s`` is then used, so the structural mode does
not make every point neutral.

Derivatives with respect to the parameters. A model that offers its coefficients and their
exact parameter derivatives as formulas (the optional capabilities ``point_coefficients`` and
``point_derivatives`` of :mod:`stability.models.base`; the sliding model, eq. 11, whose
coefficients are low-degree polynomials in the parameters) has them evaluated here in Python
floats, from the model's own source, so the values agree bit for bit with its numpy
:meth:`~stability.models.base.LinearModel.coefficients` and with the compiled twins below. Any
other model uses the fourth-order central stencil
``(f(x-2h) - 8 f(x-h) + 8 f(x+h) - f(x+2h)) / 12h`` with ``h = 1e-3 max(1, |x|)`` on the
coefficients (all in one batched call of the model): exact for coefficients polynomial of degree
<= 4 in the parameter, truncation ``O(h^4) ~ 1e-12`` otherwise (the rational ``kappa``,
``sigma_hat`` of eq. 8), rounding about ``1e-13`` relative. The derivative in ``w`` is analytic
(Horner's scheme with its derivative). Accuracy of points depends only on the residual; the
Jacobian's accuracy sets Newton's rate and the tangent.

Evaluation at one point (:meth:`NeutralCondition.residual_and_jacobian`, the continuation's inner
loop) is scalar: Python floats and complex numbers, no batched numpy call on one-element arrays.
For a model with both formulas and the crossing form, :func:`crossing_kernels` compiles the same
evaluation (numba; closures over the model's formulas, cached on disk), which the compiled
continuation step (:mod:`stability.linear.neutral_compiled`) and the batched checks use.

The modes other than the neutral one come from one source for every engine,
:func:`_other_roots_into`: the neutral root divided out by composite synthetic division and the
quotient solved by the stable quadratic formula (:func:`stability.linear.roots.divide_root`,
:func:`~stability.linear.roots.quadratic_roots`), run in Python floats (one point,
:func:`_other_roots_list`), compiled (the continuation step) and over a batch of coefficients
(:meth:`NeutralCondition.other_modes_many`, compiled or interpreted by the rule of
:mod:`stability.execution`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from typing import NamedTuple

import numpy as np

from stability.jit import OPTIONS, cached, njit, register_jitable
from stability.jit import active as jit_active

from .. import execution
from ..errors import InputError
from ..models import LinearModel, get_model
from ..parameters import PARAMETERS
from .growth import axis_products, conservative_phases
from .roots import axis_norms, divide_root, horner_scheme, quadratic_roots

__all__ = [
    "CrossingKernels",
    "NeutralCondition",
    "crossing_kernels",
]

_STENCIL = np.array([-2.0, -1.0, 1.0, 2.0])
_WEIGHTS = np.array([1.0, -8.0, 8.0, -1.0]) / 12.0
_REL_H = 1e-3
_IPOW = (1.0 + 0j, 1j, -1.0 + 0j, -1j)
#: numba options: IEEE arithmetic (no fastmath: no reassociation or contraction, so the
#: compiled twins do the same floating-point operations as the scalar Python code)
_JIT = dict(OPTIONS, cache=True)


# ------------------------------------------------------------------------------------------
# the modes other than the neutral one: one source for every engine
# ------------------------------------------------------------------------------------------
@register_jitable
def _other_roots_into(c, ncoef, w, multiplicity, out):
    """Roots of ``p(s) / (s - i w)^multiplicity`` for ``p = c[0..ncoef-1]`` (highest first).

    The quotient replaces ``c`` (composite division, :func:`stability.linear.roots.divide_root`,
    in place); its roots, if its degree ``m`` is 1 or 2, go to ``out[:m]`` (the stable quadratic
    formula). Returns ``m`` (a larger ``m`` is left to the caller, with the quotient in
    ``c[:m + 1]``). Lists of Python numbers or numba arrays.
    """
    r = complex(0.0, w)
    n = ncoef - 1
    for _ in range(multiplicity):
        if n < 1:
            return 0
        divide_root(c, n, r, c)
        n -= 1
    if n == 1:
        out[0] = -c[1] / c[0]
    elif n == 2:
        r1, r2, _ = quadratic_roots(c[0], c[1], c[2])
        out[0] = r1
        out[1] = r2
    return n


def _other_roots_list(c: Sequence[complex], w: float, multiplicity: int = 1) -> list[complex]:
    """Roots of ``p(s) / (s - i w)^multiplicity`` (the modes other than the neutral one), as a list
    of Python numbers (``numpy.roots`` beyond degree 2).

    The division is composite (:func:`stability.linear.roots.divide_root`), so a root much
    smaller than ``i w`` keeps its relative accuracy, and an exact zero root
    (``c0 = -mu alpha_v q fr_inv = 0`` at ``fr_inv = 0`` or ``q = 0``) comes out exactly zero:
    ``Re s = 0``, which brackets no sign change of the double-crossing test (removing it instead
    made that test jump at ``c0 = 0`` from ~0 to the next mode's growth rate, and the jump was
    reported as a double crossing)."""
    work = [complex(x) for x in c]
    out = [0j, 0j]
    m = _other_roots_into(work, len(work), float(w), multiplicity, out)
    if m <= 0:
        return []
    if m <= 2:
        return out[:m]
    return [complex(r) for r in np.roots(work[: m + 1])]


def _other_roots_many(c, ncoef, w, multiplicity, out):
    """:func:`_other_roots_into` over a batch: ``c`` (m, >= ncoef; not changed), ``w`` (m,),
    ``out`` (m, k) with ``k`` the quotient's degree (<= 2). Compiled (:func:`stability.jit.cached`);
    the interpreted execution runs :func:`_other_roots_into` on lists row by row
    (:meth:`NeutralCondition.other_modes_many`)."""
    work = np.empty(ncoef, dtype=np.complex128)
    roots = np.empty(2, dtype=np.complex128)
    for i in range(c.shape[0]):
        for j in range(ncoef):
            work[j] = c[i, j]
        k = _other_roots_into(work, ncoef, w[i], multiplicity, roots)
        for j in range(k):
            out[i, j] = roots[j]


class NeutralCondition:
    """``det(i w M - A) = 0`` for a model with some parameters free and the rest fixed.

    Parameters
    ----------
    model : str or LinearModel
        A registered model.
    free : sequence of str
        Names of the free parameters (the unknowns are ``(*free, w)``).
    fixed : mapping
        Values of all other parameters of the model (checked by the caller,
        :func:`stability.linear.spectra.fixed_parameters`).
    samples : array_like, shape (m, len(free)), optional
        Points used to decide the form and the deflation (default: the centre of a unit box).
    form : {"crossing", "collision"}, optional
        Force the form (default: decided from the samples, see the module docstring).
    compiled : bool, optional
        Evaluate :meth:`residuals` (many points at once) by its compiled twin where it exists (a model with ``point_coefficients`` and
        ``point_derivatives``, crossing form); False keeps numpy and the interpreter. None
        (default): the rule of :mod:`stability.execution` (``TIPPE_KERNEL``; by default only if
        this process has compiled them already, :func:`stability.execution.use_compiled`).

    Attributes
    ----------
    form : str
    deflate : int
        Number of structural zero roots removed.
    phase : int or None
        Common phase of ``c_k i^k`` (collision form).
    kernels : CrossingKernels or None
        The compiled twins (:func:`crossing_kernels`), or None.
    """

    def __init__(
        self,
        model: str | LinearModel,
        free: Sequence[str],
        fixed: Mapping[str, float],
        samples: np.ndarray | None = None,
        form: str | None = None,
        compiled: bool | None = None,
    ):
        self.model = get_model(model)
        self.free = tuple(free)
        self.fixed = {k: float(v) for k, v in fixed.items()}
        if samples is None:
            samples = np.full((1, len(self.free)), 0.1)
        samples = np.atleast_2d(np.asarray(samples, dtype=float))
        c = self._raw(samples)
        self.deflate = 0
        n = c.shape[-1] - 1
        while self.deflate < n - 1 and np.all(c[..., n - self.deflate] == 0):
            self.deflate += 1
        c = c[..., : n + 1 - self.deflate]
        phases = np.unique(conservative_phases(c))  # the common phase of all samples (None if none)
        self.phase = int(phases[0]) if len(phases) == 1 and phases[0] >= 0 else None
        if form is None:
            form = "collision" if self.phase is not None else "crossing"
        if form == "collision" and self.phase is None:
            raise InputError(
                f"model {self.model.name!r} with {self.fixed} is not conservative; "
                "the collision form needs p(i w) = e^(i theta) P(w) with P real"
            )
        self.form = form
        self._ncoef = n - self.deflate + 1
        # exact derivatives from the model's formulas, if it offers them (stability.models.base)
        self._formula = getattr(self.model, "point_coefficients", None)
        self._derivative = getattr(self.model, "point_derivatives", None)
        self._analytic = self._formula is not None and self._derivative is not None
        self.kernels: CrossingKernels | None = None
        #: (point, free_index, ncoef): the arguments of the compiled twins, or None
        self._compiled: tuple[np.ndarray, np.ndarray, int] | None = None
        # the five linear parameters (the formulas' and the constraints' arguments), free ones
        # at 0, and 0.0 for those the model does not take
        self._point = [self.fixed.get(name, 0.0) for name in PARAMETERS]
        self._free_index = [PARAMETERS.index(name) for name in self.free]
        if self._analytic:
            if compiled is None and self.form == "crossing":  # in memory (numba active) or forced
                degree = int(self.model.n_modes)
                kernels = crossing_kernels(self._formula, self._derivative, degree) if jit_active() else None
                compiled = execution.use_compiled(kernels and kernels.residuals, 1)
            if self.form == "crossing" and compiled and self._ncoef - 2 <= 2:
                self.kernels = crossing_kernels(self._formula, self._derivative, int(self.model.n_modes))
                self._compiled = (
                    np.array(self._point, dtype=float),
                    np.array(self._free_index, dtype=np.int64),
                    int(self._ncoef),
                )

    def _scalar(self, values: Sequence[float], derivatives: bool) -> tuple[list[complex], list[list[complex]] | None]:
        """Deflated coefficients at one point (list) and ``dc/d free`` (one list per free)."""
        if self._analytic:
            p = self._point.copy()
            for i, v in zip(self._free_index, values):
                p[i] = float(v)
            m = self._ncoef
            it = iter(self._formula(*p))
            c = list(map(complex, it, it))[:m]  # (re, im) pairs -> complex numbers
            if not derivatives:
                return c, None
            dc = []
            for k in self._free_index:
                it = iter(self._derivative(*p, k))
                dc.append(list(map(complex, it, it))[:m])
            return c, dc
        if derivatives:
            c, dc = self.coefficients_and_derivatives(np.asarray(values, dtype=float))
            return c.tolist(), [row.tolist() for row in dc]
        return self.coefficients(np.asarray(values, dtype=float)[None, :])[0].tolist(), None

    # -- coefficients ---------------------------------------------------------------------
    def _raw(self, values: np.ndarray) -> np.ndarray:
        values = np.asarray(values, dtype=float)
        params = dict(self.fixed)
        for i, name in enumerate(self.free):
            params[name] = values[..., i]
        shape = values.shape[:-1]
        params = {k: np.broadcast_to(np.asarray(v, float), shape) for k, v in params.items()}
        return np.asarray(self.model.coefficients(**params), dtype=complex)

    def coefficients(self, values: np.ndarray) -> np.ndarray:
        """Deflated coefficients (highest power first) at ``values`` (..., len(free))."""
        c = self._raw(values)
        return c[..., : c.shape[-1] - self.deflate]

    def coefficients_and_derivatives(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients at one point and their derivatives along each free parameter.

        Returns
        -------
        c : numpy.ndarray, shape (n+1,)
        dc : numpy.ndarray, shape (len(free), n+1)
        """
        values = np.asarray(values, dtype=float)
        k = values.size
        h = _REL_H * np.maximum(1.0, np.abs(values))
        pts = np.repeat(values[None, :], 1 + 4 * k, axis=0)
        for i in range(k):
            pts[1 + 4 * i : 5 + 4 * i, i] += _STENCIL * h[i]
        c = self.coefficients(pts)
        dc = np.empty((k, c.shape[-1]), dtype=complex)
        for i in range(k):
            dc[i] = _WEIGHTS @ c[1 + 4 * i : 5 + 4 * i] / h[i]
        return c[0], dc

    # -- the equations --------------------------------------------------------------------
    def _real_poly(self, c: np.ndarray) -> np.ndarray:
        """Real coefficients ``a_k`` of ``P(w) = e^{-i theta} p(i w)`` (highest first)."""
        d = axis_products(c)
        return d.real if self.phase == 0 else d.imag

    def residual_and_jacobian(
        self, values: np.ndarray, w: float, jacobian: bool = True
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """``F`` (2,) and ``dF/d(free..., w)`` (2, len(free)+1) at one point."""
        crossing = self.form == "crossing"
        c, dc = self._scalar(values, jacobian or crossing)
        w = float(w)
        n = len(c) - 1
        if crossing:
            z = 1j * w
            p, dpz, _ = horner_scheme(c, z, 1)
            na, nb = axis_norms(c, n + 1)  # plain loops, as the compiled twin
            for x, row in zip(values, dc):
                da, db = axis_norms(row, n + 1)
                ax = abs(float(x))
                na += ax * da
                nb += ax * db
            big = max(1.0, abs(w)) ** n
            Sa = na * big or 1.0
            Sb = nb * big or 1.0
            F = np.array([p.real / Sa, p.imag / Sb])
            if not jacobian:
                return F, None
            re, im = [], []
            for row in dc:
                d = horner_scheme(row, z, 0)[0]
                re.append(d.real / Sa)
                im.append(d.imag / Sb)
            dpw = 1j * dpz
            re.append(dpw.real / Sa)
            im.append(dpw.imag / Sb)
            return F, np.array([re, im])
        a = self._real_poly_list(c)
        norm = sum(abs(x) for x in a)
        S0 = norm * max(1.0, abs(w)) ** n or 1.0
        S1 = n * norm * max(1.0, abs(w)) ** max(n - 1, 0) or 1.0
        P, dP, _ = horner_scheme(a, w, 1)
        F = np.array([P.real / S0, dP.real / S1])
        if not jacobian:
            return F, None
        d1 = [x * (n - k) for k, x in enumerate(a[:-1])]  # P' (highest first)
        J = np.empty((2, len(dc) + 1))
        for i, row in enumerate(dc):
            v, dv, _ = horner_scheme(self._real_poly_list(row), w, 1)
            J[0, i], J[1, i] = v.real / S0, dv.real / S1
        J[0, -1] = dP.real / S0
        J[1, -1] = horner_scheme(d1, w, 1)[1].real / S1 if d1 else 0.0
        return F, J

    def _real_poly_list(self, c: Sequence[complex]) -> list[complex]:
        """``a_k`` of ``P(w) = e^{-i theta} p(i w)`` (highest first), as complex with zero imag."""
        n = len(c) - 1
        out = []
        for k, ck in enumerate(c):
            d = ck * _IPOW[(n - k) % 4]
            out.append(complex(d.real if self.phase == 0 else d.imag))
        return out

    def residuals(self, values: np.ndarray, w: np.ndarray) -> np.ndarray:
        """``F`` at many points at once: the batched twin of :meth:`residual_and_jacobian`.

        One call of the model's batched coefficients (the same values as the scalar path) and
        Horner's scheme on arrays (:func:`stability.linear.roots.horner`); used after tracing,
        for the backward error of every point.

        Parameters
        ----------
        values : numpy.ndarray, shape (m, len(free))
        w : numpy.ndarray, shape (m,)

        Returns
        -------
        numpy.ndarray, shape (m, 2)
        """
        values = np.asarray(values, dtype=float).reshape(-1, len(self.free))
        w = np.asarray(w, dtype=float).reshape(-1)
        if len(w) == 0:
            return np.zeros((0, 2))
        if self._compiled is not None:
            return self.kernels.residuals(*self._compiled, values, w)
        c = self.coefficients(values)
        n = c.shape[-1] - 1
        big = np.maximum(1.0, np.abs(w))
        if self.form == "crossing":
            p = horner_scheme(c.T, 1j * w, 0)[0]
            na, nb = axis_norms(c.T, n + 1)
            for j, dcj in enumerate(self._derivatives_many(values)):
                da, db = axis_norms(dcj.T, n + 1)
                ax = np.abs(values[:, j])
                na = na + ax * da
                nb = nb + ax * db
            Sa = na * big**n
            Sb = nb * big**n
            return np.stack([p.real / np.where(Sa == 0, 1.0, Sa), p.imag / np.where(Sb == 0, 1.0, Sb)], axis=-1)
        a = self._real_poly(c)
        norm = np.abs(a).sum(axis=-1)
        S0 = norm * big**n
        S1 = n * norm * big ** max(n - 1, 0)
        P, dP, _ = horner_scheme(a.T, w, 1)
        return np.stack([P / np.where(S0 == 0, 1.0, S0), dP / np.where(S1 == 0, 1.0, S1)], axis=-1)

    def _derivatives_many(self, values: np.ndarray) -> list[np.ndarray]:
        """``dc/d free_j`` at many points, one array (m, ncoef) per free parameter (deflated):
        the model's formula on arrays, or the stencil point by point."""
        m = len(values)
        if self._analytic:
            p = [np.full(m, v) for v in self._point]
            for i, k in enumerate(self._free_index):
                p[k] = values[:, i]
            out = []
            for k in self._free_index:
                parts = self._derivative(*p, k)
                d = np.empty((m, len(parts) // 2), dtype=complex)
                for j in range(d.shape[1]):
                    d.real[:, j] = parts[2 * j]
                    d.imag[:, j] = parts[2 * j + 1]
                out.append(d[:, : self._ncoef])
            return out
        rows = [self.coefficients_and_derivatives(v)[1] for v in values]
        return [np.array([r[j] for r in rows]).reshape(m, -1) for j in range(len(self.free))]

    def other_modes_many(self, values: np.ndarray, w: np.ndarray) -> np.ndarray:
        """:meth:`other_modes_list` at many points at once, shape ``(m, k)``.

        The neutral root(s) ``i w`` are divided out and the quotient solved by the same source
        as the one-point path (:func:`_other_roots_into`, composite division, the stable
        quadratic formula), compiled over the batch or :func:`_other_roots_list` row by row
        (``numpy.roots`` beyond degree 2).
        """
        values = np.asarray(values, dtype=float).reshape(-1, len(self.free))
        w = np.asarray(w, dtype=float).reshape(-1)
        c = np.ascontiguousarray(self.coefficients(values), dtype=np.complex128)
        multiplicity = 1 if self.form == "crossing" else 2
        m = c.shape[1] - 1 - multiplicity
        if m <= 0:
            return np.zeros((len(w), 0), dtype=complex)
        if m <= 2 and execution.use_compiled(_other_roots_many, len(w)):
            out = np.empty((len(w), m), dtype=np.complex128)
            cached(_other_roots_many)(c, c.shape[1], np.ascontiguousarray(w), multiplicity, out)
            return out
        # interpreted: the one-point source on Python numbers, row by row
        rows = [_other_roots_list(c[i].tolist(), w[i], multiplicity) for i in range(len(w))]
        return np.array(rows, dtype=np.complex128).reshape(len(w), m)

    def other_modes_list(self, values: Sequence[float], w: float) -> list[complex]:
        """The modes other than the neutral one(s) at ``i w`` (deflated structural zeros
        excluded), as a list of Python complex numbers (the scalar inner loop)."""
        c, _ = self._scalar(values, False)
        return _other_roots_list(c, float(w), 1 if self.form == "crossing" else 2)


# ------------------------------------------------------------------------------------------
# compiled twins of the crossing form, for a model with point_coefficients and
# point_derivatives (the continuation's compiled step, stability.linear.neutral_compiled, and
# the batched checks)
# ------------------------------------------------------------------------------------------
class CrossingKernels(NamedTuple):
    """The compiled crossing form of one model (:func:`crossing_kernels`).

    ``residual_into`` and ``other_growth_of`` are ``register_jitable`` functions (for compiled
    callers to build on, e.g. :mod:`stability.linear.neutral_compiled`); the others are
    compiled entry points callable from Python. Their arguments ``(point, free_index, ncoef)``
    are :attr:`NeutralCondition._compiled`: the five linear parameters (free ones replaced),
    the positions of the free ones, and the number of coefficients kept after deflation.
    """

    residual_into: Callable[..., None]
    other_growth_of: Callable[..., float]
    residual_and_jacobian: Callable[..., tuple[np.ndarray, np.ndarray]]
    other_growth: Callable[..., float]
    residuals: Callable[..., np.ndarray]


@functools.cache
def crossing_kernels(formula: Callable[..., tuple], derivative: Callable[..., tuple], n: int) -> CrossingKernels:
    """Compiled twins of :meth:`NeutralCondition.residual_and_jacobian`,
    :meth:`~NeutralCondition.residuals` and the largest growth rate of the other modes
    (:func:`_other_roots_list`) (crossing form) for the formulas ``formula`` and
    ``derivative`` of a model of degree ``n`` (its ``point_coefficients`` and
    ``point_derivatives``): the same floating-point operations as the scalar Python path, so the
    same bits. Closures over the formulas, compiled on first use and cached on disk (numba keys
    a closure's cache by its captured values; the local functions refer to plain
    ``register_jitable`` functions only, see :mod:`stability.linear.kernel`).
    """

    @register_jitable
    def fill(p, c):
        """The coefficients at ``p`` (the five parameters) into ``c`` (n + 1 complex)."""
        parts = formula(p[0], p[1], p[2], p[3], p[4])
        for j in range(n + 1):
            c[j] = complex(parts[2 * j], parts[2 * j + 1])

    @register_jitable
    def fill_derivative(p, k, d):
        """Their derivatives by parameter ``k`` into ``d``."""
        parts = derivative(p[0], p[1], p[2], p[3], p[4], k)
        for j in range(n + 1):
            d[j] = complex(parts[2 * j], parts[2 * j + 1])

    @register_jitable
    def residual_into(point, free_index, ncoef, u, jacobian, F, J):
        """``F`` and (if ``jacobian``) ``dF/du`` at ``u = (free..., w)`` into ``F`` (2,) and ``J``
        (2, k + 1), with the row scales ``S_a``, ``S_b`` held fixed in ``J`` as in the Python path."""
        k = free_index.shape[0]
        p = point.copy()
        for i in range(k):
            p[free_index[i]] = u[i]
        w = u[k]
        c = np.empty(n + 1, dtype=np.complex128)
        fill(p, c)
        z = complex(0.0, w)
        val, dpz, _ = horner_scheme(c[:ncoef], z, 1)
        na, nb = axis_norms(c, ncoef)
        d = np.empty(n + 1, dtype=np.complex128)
        for i in range(k):
            fill_derivative(p, free_index[i], d)
            da, db = axis_norms(d, ncoef)
            ax = abs(u[i])
            na += ax * da
            nb += ax * db
        big = math.pow(max(1.0, abs(w)), float(ncoef - 1))
        Sa = na * big
        Sb = nb * big
        if Sa == 0.0:
            Sa = 1.0
        if Sb == 0.0:
            Sb = 1.0
        F[0] = val.real / Sa
        F[1] = val.imag / Sb
        if not jacobian:
            return
        for i in range(k):
            fill_derivative(p, free_index[i], d)
            acc = horner_scheme(d[:ncoef], z, 0)[0]
            J[0, i] = acc.real / Sa
            J[1, i] = acc.imag / Sb
        J[0, k] = -dpz.imag / Sa
        J[1, k] = dpz.real / Sb

    @register_jitable
    def other_growth_of(point, free_index, ncoef, u):
        """Largest growth rate of the modes other than ``i w`` (-inf if none)."""
        k = free_index.shape[0]
        p = point.copy()
        for i in range(k):
            p[free_index[i]] = u[i]
        c = np.empty(n + 1, dtype=np.complex128)
        fill(p, c)
        roots = np.empty(2, dtype=np.complex128)
        m = _other_roots_into(c, ncoef, u[k], 1, roots)
        g = -np.inf
        for j in range(m):
            g = max(g, roots[j].real)
        return g

    @njit(**_JIT)
    def residual_and_jacobian(point, free_index, ncoef, u, jacobian):
        F = np.empty(2)
        J = np.empty((2, u.shape[0]))
        residual_into(point, free_index, ncoef, u, jacobian, F, J)
        return F, J

    @njit(**_JIT)
    def other_growth(point, free_index, ncoef, u):
        return other_growth_of(point, free_index, ncoef, u)

    @njit(**_JIT)
    def residuals(point, free_index, ncoef, values, w):
        m, k = values.shape
        out = np.empty((m, 2))
        u = np.empty(k + 1)
        F = np.empty(2)
        J = np.empty((2, k + 1))
        for i in range(m):
            for j in range(k):
                u[j] = values[i, j]
            u[k] = w[i]
            residual_into(point, free_index, ncoef, u, False, F, J)
            out[i, 0] = F[0]
            out[i, 1] = F[1]
        return out

    return CrossingKernels(residual_into, other_growth_of, residual_and_jacobian, other_growth, residuals)
