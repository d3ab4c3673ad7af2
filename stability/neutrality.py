"""The neutral condition of a linear model, ``det(i w M - A) = 0``, as real equations.

A mode ``x ~ exp(s t)`` is neutral when ``s = i w`` with ``w`` real (its frequency, fixed frame,
units of the spin rate). With ``p(s) = det(s M - A) = sum_k c_k s^k`` (eq. 11 for the sliding
model, eq. 8 for the fixed-pivot and rolling models; coefficients from the model, mass matrix
included) there are two forms:

*crossing* (dissipative models)
    ``F = [Re p(i w), Im p(i w)] / S`` with ``S = ||c||_1 max(1, |w|)^n``: two real equations;
    with two free parameters the solutions form curves in ``(x, y, w)``, along which one mode
    sits on the imaginary axis. ``||F||`` is a normwise relative backward error of ``i w`` as a
    root (about ``1e-16`` at a rounded root). ``S`` never vanishes (the leading coefficient is
    nonzero), unlike the componentwise ``sum_k |c_k| |w|^k``, which tends to zero where a root
    passes through ``s = 0`` (``c_0 -> 0`` and ``w -> 0``) and would spoil Newton's method there.
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

Derivatives with respect to the parameters use the fourth-order central stencil
``(f(x-2h) - 8 f(x-h) + 8 f(x+h) - f(x+2h)) / 12h`` with ``h = 1e-3 max(1, |x|)`` on the
coefficients (all in one batched call of the model): exact for coefficients polynomial of degree
<= 4 in the parameter (true for eq. 11), truncation ``O(h^4) ~ 1e-12`` otherwise (the rational
``kappa``, ``sigma_hat`` of eq. 8), rounding about ``1e-13`` relative. The derivative in ``w`` is
analytic. Accuracy of points depends only on the residual; the Jacobian's accuracy sets
Newton's rate and the tangent.
"""

from __future__ import annotations

import cmath
from collections.abc import Mapping, Sequence

import numpy as np

from .models import LinearModel, get_model

__all__ = ["NeutralCondition", "conservative_phase", "other_roots"]

_STENCIL = np.array([-2.0, -1.0, 1.0, 2.0])
_WEIGHTS = np.array([1.0, -8.0, 8.0, -1.0]) / 12.0
_REL_H = 1e-3


def _i_power(k: np.ndarray) -> np.ndarray:
    """``i**k`` exactly (a table lookup, no complex power)."""
    return np.array([1.0, 1j, -1.0, -1j])[np.asarray(k) % 4]


def conservative_phase(c: np.ndarray) -> int | None:
    """Common phase of ``c_k i^k`` (0: all real, 1: all imaginary), or None if there is none.

    Parameters
    ----------
    c : numpy.ndarray of complex, shape (..., n+1)
        Coefficients, highest power first.
    """
    c = np.asarray(c, dtype=complex)
    n = c.shape[-1] - 1
    d = c * _i_power(np.arange(n, -1, -1))
    # exact products with 1, i, -1, -i: an exact zero imaginary (real) part is structure
    if np.all(d.imag == 0):
        return 0
    if np.all(d.real == 0):
        return 1
    return None


def _divide_root(c: list[complex], r: complex) -> list[complex]:
    """Synthetic division of ``c`` (highest first) by ``(s - r)``; the remainder is dropped."""
    out = [c[0]]
    for ck in c[1:-1]:
        out.append(ck + r * out[-1])
    return out


def other_roots(c: Sequence[complex], w: float, multiplicity: int = 1) -> np.ndarray:
    """Roots of ``p(s) / (s - i w)^multiplicity`` (the modes other than the neutral one)."""
    q = [complex(x) for x in c]
    for _ in range(multiplicity):
        q = _divide_root(q, 1j * w)
    m = len(q) - 1
    if m <= 0:
        return np.zeros(0, dtype=complex)
    if m == 1:
        return np.array([-q[1] / q[0]])
    if m == 2:
        a, b, k = q
        sq = cmath.sqrt(b * b - 4 * a * k)
        big = -(b + sq) / 2 if (b.conjugate() * sq).real >= 0 else -(b - sq) / 2
        if big == 0:
            return np.array([0j, 0j])
        return np.array([big / a, k / big])
    return np.roots(q)


class NeutralCondition:
    """``det(i w M - A) = 0`` for a model with some parameters free and the rest fixed.

    Parameters
    ----------
    model : str or LinearModel
        A registered model.
    free : sequence of str
        Names of the free parameters (the unknowns are ``(*free, w)``).
    fixed : mapping
        Values of all other parameters of the model.
    samples : array_like, shape (m, len(free)), optional
        Points used to decide the form and the deflation (default: the centre of a unit box).
    form : {"crossing", "collision"}, optional
        Force the form (default: decided from the samples, see the module docstring).

    Attributes
    ----------
    form : str
    deflate : int
        Number of structural zero roots removed.
    phase : int or None
        Common phase of ``c_k i^k`` (collision form).
    """

    def __init__(self, model: str | LinearModel, free: Sequence[str], fixed: Mapping[str, float],
                 samples: np.ndarray | None = None, form: str | None = None):
        self.model = get_model(model)
        self.free = tuple(free)
        self.fixed = {k: float(v) for k, v in fixed.items()}
        missing = set(self.model.parameters) - set(self.free) - set(self.fixed)
        extra = (set(self.free) | set(self.fixed)) - set(self.model.parameters)
        if missing or extra:
            raise TypeError(f"model {self.model.name!r} takes {', '.join(self.model.parameters)}; "
                            f"missing {sorted(missing)}, unknown {sorted(extra)}")
        if samples is None:
            samples = np.full((1, len(self.free)), 0.1)
        samples = np.atleast_2d(np.asarray(samples, dtype=float))
        c = self._raw(samples)
        self.deflate = 0
        n = c.shape[-1] - 1
        while self.deflate < n - 1 and np.all(c[..., n - self.deflate] == 0):
            self.deflate += 1
        c = c[..., : n + 1 - self.deflate]
        phases = {conservative_phase(ci) for ci in c}
        self.phase = phases.pop() if len(phases) == 1 else None
        if form is None:
            form = "collision" if self.phase is not None else "crossing"
        if form not in ("crossing", "collision"):
            raise ValueError(f"form = {form!r}; use 'crossing' or 'collision'")
        if form == "collision" and self.phase is None:
            raise ValueError(f"model {self.model.name!r} with {self.fixed} is not conservative; "
                             "the collision form needs p(i w) = e^(i theta) P(w) with P real")
        self.form = form
        self.degree = n - self.deflate

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
            pts[1 + 4 * i: 5 + 4 * i, i] += _STENCIL * h[i]
        c = self.coefficients(pts)
        dc = np.empty((k, c.shape[-1]), dtype=complex)
        for i in range(k):
            dc[i] = _WEIGHTS @ c[1 + 4 * i: 5 + 4 * i] / h[i]
        return c[0], dc

    # -- the equations --------------------------------------------------------------------
    def _real_poly(self, c: np.ndarray) -> np.ndarray:
        """Real coefficients ``a_k`` of ``P(w) = e^{-i theta} p(i w)`` (highest first)."""
        n = c.shape[-1] - 1
        d = c * _i_power(np.arange(n, -1, -1))
        return d.real if self.phase == 0 else d.imag

    def residual_and_jacobian(self, values: np.ndarray, w: float, jacobian: bool = True
                              ) -> tuple[np.ndarray, np.ndarray | None]:
        """``F`` (2,) and ``dF/d(free..., w)`` (2, len(free)+1) at one point."""
        values = np.asarray(values, dtype=float)
        if jacobian:
            c, dc = self.coefficients_and_derivatives(values)
        else:
            c, dc = self.coefficients(values[None, :])[0], None
        n = c.size - 1
        powers = np.arange(n, -1, -1)
        if self.form == "crossing":
            z = (1j * w) ** powers
            p = c @ z
            S = float(np.sum(np.abs(c))) * max(1.0, abs(w)) ** n or 1.0
            F = np.array([p.real, p.imag]) / S
            if not jacobian:
                return F, None
            dp = dc @ z
            dz = np.where(powers > 0, powers * (1j * w) ** np.maximum(powers - 1, 0), 0.0)
            dpw = 1j * (c @ dz)
            J = np.empty((2, values.size + 1))
            J[0, :-1], J[1, :-1] = dp.real, dp.imag
            J[0, -1], J[1, -1] = dpw.real, dpw.imag
            return F, J / S
        a = self._real_poly(c)
        P = np.polynomial.polynomial
        ar = a[::-1]  # lowest first
        d1 = P.polyder(ar)
        d2 = P.polyder(d1) if d1.size > 1 else np.zeros(1)
        S0 = float(np.sum(np.abs(ar))) * max(1.0, abs(w)) ** n or 1.0
        S1 = n * float(np.sum(np.abs(ar))) * max(1.0, abs(w)) ** max(n - 1, 0) or 1.0
        F = np.array([P.polyval(w, ar) / S0, P.polyval(w, d1) / S1])
        if not jacobian:
            return F, None
        da = np.array([self._real_poly(x)[::-1] for x in dc])  # (k, n+1) lowest first
        J = np.empty((2, values.size + 1))
        J[0, :-1] = [P.polyval(w, x) / S0 for x in da]
        J[1, :-1] = [P.polyval(w, P.polyder(x)) / S1 for x in da]
        J[0, -1] = P.polyval(w, d1) / S0
        J[1, -1] = P.polyval(w, d2) / S1
        return F, J

    def backward_error(self, values: np.ndarray, w: float) -> float:
        """``||F||``: ``|p(i w)| / (||c||_1 max(1, |w|)^n)`` (with ``P'`` in the collision form)."""
        F, _ = self.residual_and_jacobian(values, w, jacobian=False)
        return float(np.linalg.norm(F))

    def other_modes(self, values: np.ndarray, w: float) -> np.ndarray:
        """The modes other than the neutral one(s) at ``i w`` (deflated structural zeros excluded)."""
        c = self.coefficients(np.asarray(values, float)[None, :])[0]
        return other_roots(c, w, 1 if self.form == "crossing" else 2)
