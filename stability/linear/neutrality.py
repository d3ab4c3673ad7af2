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

Derivatives with respect to the parameters. For the sliding model (eq. 11) the coefficients
are low-degree polynomials in the parameters and both they and their derivatives are written
out here (:func:`sliding_coefficients`, scalar Python arithmetic, the same operations as
:meth:`stability.models.sliding.Sliding.coefficients` so the values agree bit for bit, including
the compensated ``A_G = 1 - mu q^2``). Any other model uses the fourth-order central stencil
``(f(x-2h) - 8 f(x-h) + 8 f(x+h) - f(x+2h)) / 12h`` with ``h = 1e-3 max(1, |x|)`` on the
coefficients (all in one batched call of the model): exact for coefficients polynomial of degree
<= 4 in the parameter, truncation ``O(h^4) ~ 1e-12`` otherwise (the rational ``kappa``,
``sigma_hat`` of eq. 8), rounding about ``1e-13`` relative. The derivative in ``w`` is analytic
(Horner's scheme with its derivative). Accuracy of points depends only on the residual; the
Jacobian's accuracy sets Newton's rate and the tangent.

Evaluation at one point (:meth:`NeutralCondition.residual_and_jacobian`, the continuation's inner
loop) is scalar: Python floats and complex numbers, no batched numpy call on one-element arrays.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Mapping, Sequence

import numpy as np
from numba import njit

from ..models import LinearModel, get_model
from ..models.sliding import Sliding
from .kernel import _transverse_inertia_g

__all__ = ["NeutralCondition", "conservative_phase", "other_roots", "sliding_coefficients",
           "sliding_crossing_residual", "sliding_crossing_residuals", "sliding_crossing_other_growth",
           "sliding_crossing_other_modes"]

_STENCIL = np.array([-2.0, -1.0, 1.0, 2.0])
_WEIGHTS = np.array([1.0, -8.0, 8.0, -1.0]) / 12.0
_REL_H = 1e-3
_IPOW = (1.0 + 0j, 1j, -1.0 + 0j, -1j)


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


def _inertia_g(q: float, mu: float) -> float:
    """``A_G = 1 - mu q^2`` compensated (Dekker's product, Knuth's sum): the compiled helper of
    the spectral kernel, :func:`stability.linear.kernel._transverse_inertia_g` (the operations of
    :func:`stability.models.inertia.transverse_inertia_g`, bit for bit), called with floats."""
    return _transverse_inertia_g(float(q), float(mu))


#: parameters of eq. (11) in the order of the derivative table
_SLIDING_PARAMS = ("q", "fr_inv", "sigma", "alpha_v", "mu")


def sliding_coefficients(q: float, fr_inv: float, sigma: float, alpha_v: float, mu: float,
                         derivatives: bool = True, which: Sequence[str] | None = None
                         ) -> tuple[list[complex], dict[str, list[complex]] | None]:
    """Coefficients of eq. (11), ``mu det(s M - A)``, and their exact parameter derivatives.

    ``c3 = mu A_G``, ``c2 = alpha_v A_C - i mu sigma``,
    ``c1 = -mu^2 q fr_inv - i alpha_v (sigma + mu (1 + q))``, ``c0 = -mu alpha_v q fr_inv`` with
    ``A_G = 1 - mu q^2`` (compensated) and ``A_C = A_G + mu (1 + q)^2 = 1 + mu (1 + 2 q)``.

    Parameters
    ----------
    q, fr_inv, sigma, alpha_v, mu : float
        One point (scalars).
    derivatives : bool
        Also return ``dc/dparameter``.
    which : sequence of str, optional
        The parameters to differentiate by (default all five); the continuation's inner loop
        asks only for the two it traces.

    Returns
    -------
    c : list of complex
        ``[c3, c2, c1, c0]``, the same values as
        :meth:`stability.models.sliding.Sliding.coefficients` (same operations).
    dc : dict of str to list of complex, or None
        ``{name: [dc3, dc2, dc1, dc0]}`` for each parameter of ``which``.
    """
    a_g = _inertia_g(q, mu)
    a_c = a_g + mu * (1.0 + q) ** 2
    c = [complex(mu * a_g, 0.0), complex(alpha_v * a_c, -(mu * sigma)),
         complex(-mu * mu * q * fr_inv, -(alpha_v * (sigma + mu * (1.0 + q)))),
         complex(-mu * alpha_v * q * fr_inv, 0.0)]
    if not derivatives:
        return c, None
    dc: dict[str, list[complex]] = {}
    for name in _SLIDING_PARAMS if which is None else which:
        if name == "q":
            dc[name] = [complex(-2.0 * mu * mu * q), complex(2.0 * mu * alpha_v),
                        complex(-mu * mu * fr_inv, -alpha_v * mu), complex(-mu * alpha_v * fr_inv)]
        elif name == "fr_inv":
            dc[name] = [0j, 0j, complex(-mu * mu * q), complex(-mu * alpha_v * q)]
        elif name == "sigma":
            dc[name] = [0j, complex(0.0, -mu), complex(0.0, -alpha_v), 0j]
        elif name == "alpha_v":
            dc[name] = [0j, complex(a_c), complex(0.0, -(sigma + mu * (1.0 + q))), complex(-mu * q * fr_inv)]
        elif name == "mu":
            dc[name] = [complex(1.0 - 2.0 * mu * q * q), complex(alpha_v * (1.0 + 2.0 * q), -sigma),
                        complex(-2.0 * mu * q * fr_inv, -alpha_v * (1.0 + q)), complex(-alpha_v * q * fr_inv)]
        else:
            raise ValueError(f"{name!r} is not a parameter of eq. (11); use {', '.join(_SLIDING_PARAMS)}")
    return c, dc


def _horner(c: Sequence[complex], z: complex) -> tuple[complex, complex]:
    """``p(z)`` and ``p'(z)`` of ``c`` (highest first)."""
    p, dp = 0j, 0j
    for ck in c:
        dp = dp * z + p
        p = p * z + ck
    return p, dp


def _divide_root(c: list[complex], r: complex) -> list[complex]:
    """Synthetic division of ``c`` (highest first) by ``(s - r)``; the remainder is dropped.

    Composite deflation: the coefficients from the top (forward), except the last, which is
    taken from the bottom, ``-c_n / r`` (backward; ``c_n = -r q_last`` exactly when ``r`` is a
    root). Forward division gives that coefficient an absolute error ``~u max|c_k r^k|``; when
    the quotient has a root much smaller than ``r`` (the sliding top's ``~ i c fr_inv`` as
    ``fr_inv -> 0``, whose real part is ``O(fr_inv^2)``) that error decides the root's sign
    (measured: ``+3.8e-15`` for a true ``-3e-34``, a false double crossing). From the bottom it
    is relative, ``u``."""
    out = [c[0]]
    for ck in c[1:-1]:
        out.append(ck + r * out[-1])
    if r != 0 and len(out) >= 2:
        out[-1] = -c[-1] / r
    return out


def other_roots(c: Sequence[complex], w: float, multiplicity: int = 1) -> np.ndarray:
    """Roots of ``p(s) / (s - i w)^multiplicity`` (the modes other than the neutral one).

    The division is composite (:func:`_divide_root`), so a root much smaller than ``i w`` keeps
    its relative accuracy, and an exact zero root (``c0 = -mu alpha_v q fr_inv = 0`` at
    ``fr_inv = 0`` or ``q = 0``) comes out exactly zero: ``Re s = 0``, which brackets no sign
    change of the double-crossing test (removing it instead made that test jump at ``c0 = 0``
    from ~0 to the next mode's growth rate, and the jump was reported as a double crossing)."""
    return np.array(_other_roots_list(c, w, multiplicity), dtype=complex)


def _other_roots_list(c: Sequence[complex], w: float, multiplicity: int = 1) -> list[complex]:
    """:func:`other_roots` as a list (closed forms up to degree 2, ``numpy.roots`` beyond)."""
    q = [complex(x) for x in c]
    for _ in range(multiplicity):
        q = _divide_root(q, 1j * w)
    m = len(q) - 1
    if m <= 0:
        return []
    if m == 1:
        return [-q[1] / q[0]]
    if m == 2:
        a, b, k = q
        sq = cmath.sqrt(b * b - 4 * a * k)
        big = -(b + sq) / 2 if (b.conjugate() * sq).real >= 0 else -(b - sq) / 2
        if big == 0:
            return [0j, 0j]
        return [big / a, k / big]
    return [complex(r) for r in np.roots(q)]


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
    compiled : bool, default True
        Evaluate :meth:`residuals` and :meth:`other_modes_many` (many points at once) by their
        compiled twins where they exist (the sliding model's crossing form); False keeps numpy.

    Attributes
    ----------
    form : str
    deflate : int
        Number of structural zero roots removed.
    phase : int or None
        Common phase of ``c_k i^k`` (collision form).
    """

    def __init__(self, model: str | LinearModel, free: Sequence[str], fixed: Mapping[str, float],
                 samples: np.ndarray | None = None, form: str | None = None, compiled: bool = True):
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
        # the common phase of all samples (None as soon as one has none or two differ)
        self.phase = conservative_phase(c[0])
        for ci in c[1:]:
            if self.phase is None:
                break
            if conservative_phase(ci) != self.phase:
                self.phase = None
        if form is None:
            form = "collision" if self.phase is not None else "crossing"
        if form not in ("crossing", "collision"):
            raise ValueError(f"form = {form!r}; use 'crossing' or 'collision'")
        if form == "collision" and self.phase is None:
            raise ValueError(f"model {self.model.name!r} with {self.fixed} is not conservative; "
                             "the collision form needs p(i w) = e^(i theta) P(w) with P real")
        self.form = form
        self.degree = n - self.deflate
        # scalar analytic path (exact derivatives) for the sliding model itself
        self._analytic = type(self.model) is Sliding
        self._ncoef = self.degree + 1
        #: (point, free_index, ncoef) of the compiled twins (sliding model, crossing form), or None
        self._compiled: tuple[np.ndarray, np.ndarray, int] | None = None
        if self._analytic:
            # the parameters of eq. (11) in the order of sliding_coefficients, free ones at 0
            self._point = [self.fixed.get(name, 0.0) for name in _SLIDING_PARAMS]
            self._free_index = [_SLIDING_PARAMS.index(name) for name in self.free]
            if self.form == "crossing" and compiled:
                self._compiled = (np.array(self._point, dtype=float),
                                  np.array(self._free_index, dtype=np.int64), int(self._ncoef))

    def _scalar(self, values: Sequence[float], derivatives: bool
                ) -> tuple[list[complex], list[list[complex]] | None]:
        """Deflated coefficients at one point (list) and ``dc/d free`` (one list per free)."""
        if self._analytic:
            p = self._point.copy()
            for i, v in zip(self._free_index, values):
                p[i] = float(v)
            c, dc = sliding_coefficients(*p, derivatives, self.free)
            m = self._ncoef
            if m == 4:
                return c, None if dc is None else [dc[name] for name in self.free]
            return c[:m], None if dc is None else [dc[name][:m] for name in self.free]
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
        c, dc = self._scalar(values, jacobian)
        w = float(w)
        n = len(c) - 1
        if self.form == "crossing":
            z = 1j * w
            p, dpz = _horner(c, z)
            S = sum(abs(ck) for ck in c) * max(1.0, abs(w)) ** n or 1.0
            F = np.array([p.real / S, p.imag / S])
            if not jacobian:
                return F, None
            re, im = [], []
            for row in dc:
                d = 0j
                for ck in row:  # Horner, value only
                    d = d * z + ck
                re.append(d.real / S)
                im.append(d.imag / S)
            dpw = 1j * dpz
            re.append(dpw.real / S)
            im.append(dpw.imag / S)
            return F, np.array([re, im])
        a = self._real_poly_list(c)
        norm = sum(abs(x) for x in a)
        S0 = norm * max(1.0, abs(w)) ** n or 1.0
        S1 = n * norm * max(1.0, abs(w)) ** max(n - 1, 0) or 1.0
        P, dP = _horner(a, w)
        F = np.array([P.real / S0, dP.real / S1])
        if not jacobian:
            return F, None
        d1 = [x * (n - k) for k, x in enumerate(a[:-1])]  # P' (highest first)
        J = np.empty((2, len(dc) + 1))
        for i, row in enumerate(dc):
            da = self._real_poly_list(row)
            v, dv = _horner(da, w)
            J[0, i], J[1, i] = v.real / S0, dv.real / S1
        J[0, -1] = dP.real / S0
        J[1, -1] = _horner(d1, w)[1].real / S1 if d1 else 0.0
        return F, J

    def _real_poly_list(self, c: Sequence[complex]) -> list[complex]:
        """``a_k`` of ``P(w) = e^{-i theta} p(i w)`` (highest first), as complex with zero imag."""
        n = len(c) - 1
        out = []
        for k, ck in enumerate(c):
            d = ck * _IPOW[(n - k) % 4]
            out.append(complex(d.real if self.phase == 0 else d.imag))
        return out

    def backward_error(self, values: np.ndarray, w: float) -> float:
        """``||F||``: ``|p(i w)| / (||c||_1 max(1, |w|)^n)`` (with ``P'`` in the collision form)."""
        F, _ = self.residual_and_jacobian(values, w, jacobian=False)
        return float(np.linalg.norm(F))

    def residuals(self, values: np.ndarray, w: np.ndarray) -> np.ndarray:
        """``F`` at many points at once: the batched twin of :meth:`residual_and_jacobian`.

        One call of the model's batched coefficients (the same values as the scalar path) and
        Horner's scheme on arrays; used after tracing, for the backward error of every point.

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
            return sliding_crossing_residuals(*self._compiled, values, w)
        c = self.coefficients(values)
        n = c.shape[-1] - 1
        big = np.maximum(1.0, np.abs(w))
        if self.form == "crossing":
            z = 1j * w
            p = np.zeros(len(w), dtype=complex)
            for k in range(n + 1):
                p = p * z + c[:, k]
            S = np.abs(c).sum(axis=-1) * big**n
            S = np.where(S == 0, 1.0, S)
            return np.stack([p.real / S, p.imag / S], axis=-1)
        a = self._real_poly(c)
        norm = np.abs(a).sum(axis=-1)
        S0 = norm * big**n
        S1 = n * norm * big ** max(n - 1, 0)
        P = np.zeros(len(w))
        dP = np.zeros(len(w))
        for k in range(n + 1):
            dP = dP * w + P
            P = P * w + a[:, k]
        return np.stack([P / np.where(S0 == 0, 1.0, S0), dP / np.where(S1 == 0, 1.0, S1)], axis=-1)

    def backward_errors(self, values: np.ndarray, w: np.ndarray) -> np.ndarray:
        """:meth:`backward_error` at many points at once, shape ``(m,)``."""
        return np.linalg.norm(self.residuals(values, w), axis=-1)

    def other_modes_many(self, values: np.ndarray, w: np.ndarray) -> np.ndarray:
        """:meth:`other_modes` at many points at once, shape ``(m, k)``.

        The neutral root(s) ``i w`` are divided out by synthetic division on arrays; the
        quotient's roots are the closed forms for degree 1 and 2 (the stable quadratic formula
        of :func:`other_roots`) and LAPACK on the companion matrices otherwise.
        """
        values = np.asarray(values, dtype=float).reshape(-1, len(self.free))
        w = np.asarray(w, dtype=float).reshape(-1)
        if self._compiled is not None:
            return sliding_crossing_other_modes(*self._compiled, values, w)
        c = self.coefficients(values).astype(complex)
        r = 1j * w
        for _ in range(1 if self.form == "crossing" else 2):
            out = [c[:, 0]]
            for k in range(1, c.shape[1] - 1):
                out.append(c[:, k] + r * out[-1])
            c = np.stack(out, axis=-1)
        m = c.shape[1] - 1
        if m <= 0:
            return np.zeros((len(w), 0), dtype=complex)
        if m == 1:
            return (-c[:, 1] / c[:, 0])[:, None]
        if m == 2:
            a, b, k = c[:, 0], c[:, 1], c[:, 2]
            sq = np.sqrt(b * b - 4 * a * k)
            big = np.where((b.conj() * sq).real >= 0, -(b + sq) / 2, -(b - sq) / 2)
            safe = np.where(big == 0, 1.0, big)
            return np.stack([np.where(big == 0, 0j, big / a), np.where(big == 0, 0j, k / safe)], axis=-1)
        comp = np.zeros((len(w), m, m), dtype=complex)
        comp[:, 0, :] = -c[:, 1:] / c[:, :1]
        comp[:, np.arange(1, m), np.arange(m - 1)] = 1.0
        return np.linalg.eigvals(comp)

    def other_modes(self, values: np.ndarray, w: float) -> np.ndarray:
        """The modes other than the neutral one(s) at ``i w`` (deflated structural zeros excluded)."""
        return np.array(self.other_modes_list(values, w), dtype=complex)

    def other_modes_list(self, values: Sequence[float], w: float) -> list[complex]:
        """:meth:`other_modes` as a list of Python complex numbers (the scalar inner loop)."""
        c, _ = self._scalar(values, False)
        return _other_roots_list(c, float(w), 1 if self.form == "crossing" else 2)


# ------------------------------------------------------------------------------------------
# compiled twins (numba) of the sliding model's crossing form, for the continuation's
# compiled corrector (stability.linear.neutral_compiled)
# ------------------------------------------------------------------------------------------
#: numba options: IEEE arithmetic (no fastmath: no reassociation or contraction, so the
#: compiled twins do the same floating-point operations as the scalar Python code above)
_JIT = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")


@njit(**_JIT)
def _sliding_coefficients_c(point: np.ndarray, c: np.ndarray) -> float:
    """Eq. (11)'s ``[c3, c2, c1, c0]`` at ``point = (q, fr_inv, sigma, alpha_v, mu)`` into ``c``
    (the operations of :func:`sliding_coefficients`); returns ``A_C``."""
    q, fr_inv, sigma, alpha_v, mu = point[0], point[1], point[2], point[3], point[4]
    a_g = _transverse_inertia_g(q, mu)
    a_c = a_g + mu * ((1.0 + q) * (1.0 + q))
    c[0] = complex(mu * a_g, 0.0)
    c[1] = complex(alpha_v * a_c, -(mu * sigma))
    c[2] = complex(-mu * mu * q * fr_inv, -(alpha_v * (sigma + mu * (1.0 + q))))
    c[3] = complex(-mu * alpha_v * q * fr_inv, 0.0)
    return a_c


@njit(**_JIT)
def _sliding_derivative_c(point: np.ndarray, a_c: float, k: int, d: np.ndarray) -> None:
    """``dc/d parameter k`` (k indexes ``(q, fr_inv, sigma, alpha_v, mu)``) into ``d``, as
    :func:`sliding_coefficients`."""
    q, fr_inv, sigma, alpha_v, mu = point[0], point[1], point[2], point[3], point[4]
    if k == 0:
        d[0] = complex(-2.0 * mu * mu * q, 0.0)
        d[1] = complex(2.0 * mu * alpha_v, 0.0)
        d[2] = complex(-mu * mu * fr_inv, -alpha_v * mu)
        d[3] = complex(-mu * alpha_v * fr_inv, 0.0)
    elif k == 1:
        d[0] = 0j
        d[1] = 0j
        d[2] = complex(-mu * mu * q, 0.0)
        d[3] = complex(-mu * alpha_v * q, 0.0)
    elif k == 2:
        d[0] = 0j
        d[1] = complex(0.0, -mu)
        d[2] = complex(0.0, -alpha_v)
        d[3] = 0j
    elif k == 3:
        d[0] = 0j
        d[1] = complex(a_c, 0.0)
        d[2] = complex(0.0, -(sigma + mu * (1.0 + q)))
        d[3] = complex(-mu * q * fr_inv, 0.0)
    else:
        d[0] = complex(1.0 - 2.0 * mu * q * q, 0.0)
        d[1] = complex(alpha_v * (1.0 + 2.0 * q), -sigma)
        d[2] = complex(-2.0 * mu * q * fr_inv, -alpha_v * (1.0 + q))
        d[3] = complex(-alpha_v * q * fr_inv, 0.0)


@njit(**_JIT)
def sliding_crossing_residual(point: np.ndarray, free_index: np.ndarray, ncoef: int, u: np.ndarray,
                              jacobian: bool, F: np.ndarray, J: np.ndarray) -> None:
    """Crossing form of eq. (11) at one point, compiled: the twin of
    :meth:`NeutralCondition.residual_and_jacobian` for the sliding model (same operations).

    Parameters
    ----------
    point : numpy.ndarray, shape (5,)
        ``(q, fr_inv, sigma, alpha_v, mu)``; the entries ``free_index`` are replaced by ``u``
        (a copy is made, ``point`` is not changed).
    free_index : numpy.ndarray of int, shape (k,)
        Positions of the free parameters in ``point``.
    ncoef : int
        Number of coefficients kept (4, or fewer after deflating structural zero roots).
    u : numpy.ndarray, shape (k + 1,)
        The free parameters, then the frequency ``w``.
    jacobian : bool
        Also fill ``J``.
    F : numpy.ndarray, shape (2,)
        Output ``[Re p(i w), Im p(i w)] / S``.
    J : numpy.ndarray, shape (2, k + 1)
        Output ``dF/du`` (with ``S`` held fixed, as the Python path).
    """
    k = free_index.shape[0]
    p = point.copy()
    for i in range(k):
        p[free_index[i]] = u[i]
    w = u[k]
    c = np.empty(4, dtype=np.complex128)
    a_c = _sliding_coefficients_c(p, c)
    n = ncoef - 1
    z = complex(0.0, w)
    val = 0j
    dpz = 0j
    norm = 0.0
    for j in range(ncoef):
        dpz = dpz * z + val
        val = val * z + c[j]
        norm += abs(c[j])
    S = norm * math.pow(max(1.0, abs(w)), float(n))
    if S == 0.0:
        S = 1.0
    F[0] = val.real / S
    F[1] = val.imag / S
    if not jacobian:
        return
    d = np.empty(4, dtype=np.complex128)
    for i in range(k):
        _sliding_derivative_c(p, a_c, free_index[i], d)
        acc = 0j
        for j in range(ncoef):
            acc = acc * z + d[j]
        J[0, i] = acc.real / S
        J[1, i] = acc.imag / S
    J[0, k] = -dpz.imag / S
    J[1, k] = dpz.real / S


@njit(**_JIT)
def sliding_crossing_other_growth(point: np.ndarray, free_index: np.ndarray, ncoef: int,
                                  u: np.ndarray) -> float:
    """Largest growth rate of the modes other than ``i w`` (-inf if none), compiled: the twin
    of :func:`other_roots` (multiplicity 1) for the sliding model, whose quotient has degree
    <= 2 (closed forms: the same stable quadratic formula).
    """
    k = free_index.shape[0]
    p = point.copy()
    for i in range(k):
        p[free_index[i]] = u[i]
    c = np.empty(4, dtype=np.complex128)
    _sliding_coefficients_c(p, c)
    r = np.empty(2, dtype=np.complex128)
    _other_roots_c(c, ncoef, u[k], r)
    g = -np.inf
    for j in range(ncoef - 2):
        g = max(g, r[j].real)
    return g


@njit(**_JIT)
def _other_roots_c(c: np.ndarray, ncoef: int, w: float, out: np.ndarray) -> None:
    """Roots of ``p(s) / (s - i w)`` for ``ncoef <= 4`` coefficients into ``out``
    (``ncoef - 2`` of them): :func:`other_roots` with multiplicity 1, compiled."""
    r = complex(0.0, w)
    m = ncoef - 2
    qq = np.empty(3, dtype=np.complex128)
    qq[0] = c[0]
    for j in range(1, ncoef - 1):
        qq[j] = c[j] + r * qq[j - 1]
    if w != 0.0 and ncoef - 1 >= 2:  # composite deflation: the last from the bottom (_divide_root)
        qq[ncoef - 2] = -c[ncoef - 1] / r
    if m <= 0:
        return
    if m == 1:
        out[0] = -qq[1] / qq[0]
        return
    a, b, kk = qq[0], qq[1], qq[2]
    sq = cmath.sqrt(b * b - 4 * a * kk)
    if (b.conjugate() * sq).real >= 0:
        big = -(b + sq) / 2
    else:
        big = -(b - sq) / 2
    if big == 0:
        out[0] = 0j
        out[1] = 0j
        return
    out[0] = big / a
    out[1] = kk / big


@njit(**_JIT)
def sliding_crossing_residuals(point: np.ndarray, free_index: np.ndarray, ncoef: int,
                               values: np.ndarray, w: np.ndarray) -> np.ndarray:
    """:meth:`NeutralCondition.residuals` of the sliding model's crossing form, compiled:
    ``F`` (m, 2) at the points ``values`` (m, k), ``w`` (m,)."""
    m, k = values.shape
    out = np.empty((m, 2))
    u = np.empty(k + 1)
    F = np.empty(2)
    J = np.empty((2, k + 1))
    for i in range(m):
        for j in range(k):
            u[j] = values[i, j]
        u[k] = w[i]
        sliding_crossing_residual(point, free_index, ncoef, u, False, F, J)
        out[i, 0] = F[0]
        out[i, 1] = F[1]
    return out


@njit(**_JIT)
def sliding_crossing_other_modes(point: np.ndarray, free_index: np.ndarray, ncoef: int,
                                 values: np.ndarray, w: np.ndarray) -> np.ndarray:
    """:meth:`NeutralCondition.other_modes_many` of the sliding model's crossing form,
    compiled: the roots other than ``i w``, (m, ncoef - 2)."""
    m, k = values.shape
    out = np.zeros((m, max(ncoef - 2, 0)), dtype=np.complex128)
    p = point.copy()
    c = np.empty(4, dtype=np.complex128)
    for i in range(m):
        for j in range(k):
            p[free_index[j]] = values[i, j]
        _sliding_coefficients_c(p, c)
        _other_roots_c(c, ncoef, w[i], out[i])
    return out
