"""Spectra of the linear models over parameter grids, and the stability decision.

Convention: ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, fixed frame; growth rate
``Re s``, frequency ``Im s`` in units of the spin rate. Modes are sorted by decreasing real
part (ties by decreasing imaginary part).

How *marginal* is decided (docs/conventions.md):

* a mode whose real part is zero by structure (an exactly zero root of ``det(s M - A)``, or a
  neutral root of a conservative polynomial, see :mod:`stability.linear.roots`) is neutral;
* otherwise a mode is neutral when ``|Re s| <= 4 e + 16 u max|s|``, with ``e`` the root's own
  error bound and ``u = 2**-53`` (the second term is a floor relative to the spectrum's scale;
  the rule's one home is :func:`stability.linear.roots.neutral_tolerance`);
* a point is *unstable* if any mode has ``Re s`` above that tolerance, *stable* if every mode is
  below minus it, and *marginal* otherwise.

So the sliding model's zero eigenvalue at ``fr_inv = 0`` is exactly zero and the point is
marginal (if no other mode grows), never unstable by a round-off sign.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError, ParameterTypeError
from ..models import LinearModel, get_model
from ..parameters import DEFAULT_MU, check_choice, check_domain, check_flag
from ..products import MARGINAL, STABLE, UNSTABLE
from . import kernel
from .roots import UNIT_ROUNDOFF, inclusion_radius, neutral_tolerance, polynomial_roots

__all__ = [
    "DEFAULT_METHOD",
    "MARGINAL",
    "METHODS",
    "STABLE",
    "UNSTABLE",
    "Spectrum",
    "eigenvalues",
    "spectrum",
]


#: eigenvalue methods: "kernel" (default: the compiled one-pass kernel of stability.linear.kernel,
#: Cardano + Weierstrass polishing, the fastest at full accuracy, docs/performance.md),
#: "polynomial" (structured roots of det(sM - A) by batched companion eigenvalues + Newton) and
#: "lapack" (batched numpy.linalg.eigvals of solve(M, A)); the last two are cross-checks
METHODS = ("kernel", "polynomial", "lapack")

#: the default eigenvalue method
DEFAULT_METHOD = "kernel"


@dataclass(frozen=True)
class Spectrum:
    """Eigenvalues of a model over a broadcast parameter grid.

    Attributes
    ----------
    model : LinearModel
    params : dict of numpy.ndarray
        Parameters used, broadcast to the grid shape.
    eigenvalues : numpy.ndarray of complex, shape grid + (n_modes,)
        Sorted by decreasing real part; NaN at masked (unphysical) points.
    error_bound : numpy.ndarray of float, shape grid + (n_modes,)
        Absolute error bound of each eigenvalue.
    neutral : numpy.ndarray of bool, shape grid + (n_modes,)
        Mode decided neutral (``Re s = 0`` within its tolerance, or exactly by structure).
    stability : numpy.ndarray of int8, shape grid
        ``STABLE`` (0), ``MARGINAL`` (1), ``UNSTABLE`` (2); -1 at masked points.
    inside : numpy.ndarray of bool, shape grid
        True where the point lies in the physical domain.
    """

    model: LinearModel
    params: dict[str, np.ndarray]
    eigenvalues: np.ndarray
    error_bound: np.ndarray
    neutral: np.ndarray
    stability: np.ndarray
    inside: np.ndarray

    @property
    def growth_rate(self) -> np.ndarray:
        """``Re s`` of each mode."""
        return self.eigenvalues.real

    @property
    def frequency(self) -> np.ndarray:
        """``Im s`` of each mode (fixed frame, units of the spin rate)."""
        return self.eigenvalues.imag

    @property
    def max_growth_rate(self) -> np.ndarray:
        """Leading growth rate (of mode 0)."""
        return self.eigenvalues[..., 0].real


def model_parameters(model: LinearModel, given: dict[str, Any]) -> dict[str, Any]:
    """Select the parameters a model takes, refusing missing or foreign ones."""
    for name, value in given.items():
        if name not in model.parameters and value is not None:
            raise ParameterTypeError(
                f"model {model.name!r} takes no parameter {name} (it takes {', '.join(model.parameters)})"
            )
    for name in model.parameters:
        if given.get(name) is None:
            raise ParameterTypeError(f"{name} is required for model {model.name!r}")
    return {k: v for k, v in given.items() if k in model.parameters}


def parameter_name(model: LinearModel, name: Any, what: str) -> str:
    """``name`` (the argument ``what``) if it is one of the model's parameters."""
    if not isinstance(name, str) or name not in model.parameters:
        raise InputError(
            f"{what} = {name!r} is not a parameter of model {model.name!r}; choose one of {', '.join(model.parameters)}"
        )
    return name


def fixed_parameters(model: LinearModel, free: Sequence[str], fixed: Mapping[str, Any]) -> dict[str, float]:
    """The parameters held fixed while those of ``free`` vary, as floats: ``fixed`` without its
    None values, ``mu`` defaulting to 2.28, checked by :func:`model_parameters` (with the free
    ones) and :func:`~stability.parameters.check_domain` (scalars)."""
    if not isinstance(fixed, Mapping):
        raise ParameterTypeError(f"fixed must be a mapping of parameter names to values, got {type(fixed).__name__}")
    given = {k: v for k, v in fixed.items() if v is not None}
    for name in free:
        if name in given:
            raise ParameterTypeError(f"{name} is varied and cannot also be given a value")
    if "mu" in model.parameters and "mu" not in free:
        given.setdefault("mu", DEFAULT_MU)
    missing = [n for n in model.parameters if n not in free and n not in given]
    if missing:
        raise ParameterTypeError(f"fixed must give {', '.join(missing)} for model {model.name!r}")
    given = model_parameters(model, {**given, **dict.fromkeys(free, 0.0)})
    p, _ = check_domain(scalar=True, **{k: v for k, v in given.items() if k not in free})
    return {k: float(v) for k, v in p.items()}


def lapack_eigenvalues(model: LinearModel, p: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ``"lapack"`` method: eigenvalues of ``M^-1 A`` (unsorted), their error bounds
    ``max(8 n u ||M^-1 A||, r)`` (``r`` the inclusion radius of each as a root of the model's
    polynomial) and the flags of exact real parts (none); ``numpy.linalg.LinAlgError`` where
    ``M`` is singular."""
    M, A = model.matrices(**p)
    MA = np.linalg.solve(M, A)
    ev = np.linalg.eigvals(MA)
    scale = np.linalg.norm(MA, axis=(-2, -1))
    bound = 8 * model.n_modes * UNIT_ROUNDOFF * scale[..., None] * np.ones(ev.shape)
    # the backward-error bound above ignores the conditioning of each eigenvalue (colliding
    # modes, near-singular M): take the rigorous inclusion radius of the computed roots of
    # det(sM - A) as well (docs/hard_cases.md)
    bound = np.maximum(bound, inclusion_radius(model.coefficients(**p), ev))
    return ev, bound, np.zeros(ev.shape, dtype=bool)


def _kernel(
    m: LinearModel, p: dict[str, np.ndarray], inside: np.ndarray, parallel: bool | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """The compiled kernel over the whole grid (outside points: NaN, flag -1), or None if the
    model's degree is beyond it. A model that offers ``point_coefficients``
    (:mod:`stability.models.base`) has them formed in the kernel; any other passes its
    coefficients in."""
    if kernel.accepts(m):
        return kernel.model_spectrum(m, p, inside, parallel=parallel)
    if m.n_modes > kernel.MAX_DEGREE:
        return None
    shape = inside.shape
    c = np.zeros(shape + (m.n_modes + 1,), dtype=complex)
    c[..., 0] = 1.0  # placeholder leading coefficient at points outside the domain
    if inside.all():
        c = m.coefficients(**p)
    elif inside.any():
        c[inside] = m.coefficients(**{k: v[inside] for k, v in p.items()})
    return kernel.coefficient_spectrum(c, inside, parallel=parallel)


def _plain_float(value: Any) -> np.ndarray | None:
    """``value`` as a float64 array without a copy if it plainly is one (a non-empty float64
    array, or a Python or numpy real scalar that is not a bool); None for anything else (which
    then goes through :func:`~stability.parameters.as_parameter` and its messages)."""
    if isinstance(value, np.ndarray):  # not a masked array: as_parameter checks its mask
        return (
            value if value.dtype == np.float64 and value.size > 0 and not isinstance(value, np.ma.MaskedArray) else None
        )
    if isinstance(value, (float, int, np.floating, np.integer)) and not isinstance(value, (bool, np.bool_)):
        try:
            return np.asarray(value, dtype=np.float64)
        except OverflowError:  # a Python integer beyond the doubles: as_parameter names it
            return None
    return None


def _fused(m: LinearModel, given: dict[str, Any], mask_unphysical: bool, parallel: bool | None) -> Spectrum | None:
    """The default path for a model that offers ``point_coefficients`` (the sliding model): one
    kernel pass that also tests the domain (:func:`stability.linear.kernel.checked_model_spectrum`).
    Where a point is outside and the request is not masked, or a parameter is not finite,
    :func:`check_domain` is called to raise its error (the messages live there only). None if
    the fused path does not apply (a model without the formula, input that is not plain
    float64, shapes that do not broadcast): the caller then takes the general path, which
    reports such input."""
    if not kernel.accepts(m) or not isinstance(mask_unphysical, (bool, np.bool_)):
        return None
    plain = {k: _plain_float(v) for k, v in given.items()}
    arrays = {k: v for k, v in plain.items() if v is not None}
    if len(arrays) < len(plain):
        return None
    try:
        shape = np.broadcast_shapes(*(v.shape for v in arrays.values()))
    except ValueError:
        return None
    out = kernel.checked_model_spectrum(m, arrays, parallel=parallel)
    if out.n_not_finite or (out.n_outside and not mask_unphysical):
        # a parameter not finite or beyond the computable range, or an unmasked point outside:
        # check_domain raises the canonical DomainError
        check_domain(mask=mask_unphysical, **given)
        return None  # not reached while the two tests agree (tests/test_kernel.py)
    p = {k: np.broadcast_to(v, shape) for k, v in arrays.items()}
    ev, bound, neutral, stab = out.spectrum
    return Spectrum(m, p, ev, bound, neutral, stab, out.inside)


def mode_order(ev: np.ndarray) -> np.ndarray:
    """The indices that sort eigenvalues along the last axis by the module's convention:
    decreasing real part, ties by decreasing imaginary part."""
    return np.lexsort((-ev.imag, -ev.real), axis=-1)


def _classify(ev: np.ndarray, bound: np.ndarray, exact: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    scale = np.max(np.abs(ev), axis=-1, keepdims=True)
    tol = neutral_tolerance(bound, scale)
    re = ev.real
    neutral = (exact & (re == 0)) | (np.abs(re) <= tol)
    grows = (re > tol) & ~neutral
    stab = np.where(grows.any(axis=-1), UNSTABLE, np.where(neutral.any(axis=-1), MARGINAL, STABLE))
    return neutral, stab.astype(np.int8)


def spectrum(
    model: str | LinearModel,
    *,
    q: Any,
    fr_inv: Any,
    sigma: Any,
    alpha_v: Any = None,
    mu: Any = DEFAULT_MU,
    mask_unphysical: bool = False,
    method: str = DEFAULT_METHOD,
    parallel: bool | None = None,
) -> Spectrum:
    """Eigenvalues, error bounds and the stability decision over a parameter grid.

    Parameters
    ----------
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"} or LinearModel
        Eqs. (8)-(9) for the first two, eq. (11) for ``"sliding"``.
    q, fr_inv, sigma, alpha_v, mu : float or array_like
        Parameters (broadcast together); ``alpha_v`` only for ``"sliding"``.
    mask_unphysical : bool, default False
        If False, a point outside the physical domain refuses the whole request
        (:class:`~stability.errors.DomainError`); if True, such points get NaN.
    method : {"kernel", "polynomial", "lapack"}
        Root finder (see :data:`METHODS`); the default, ``"kernel"``, is the compiled kernel
        of :mod:`stability.linear.kernel` (models of degree <= 3; others fall back to
        ``"polynomial"``).
    parallel : bool, optional
        The kernel's threads: True runs its loop on numba's thread pool, False in this thread
        only (e.g. for a small grid on a busy machine), None (default) decides by size (serial
        below :data:`stability.linear.kernel.SERIAL_BELOW` points). The numbers are the same;
        the other methods ignore it.

    Returns
    -------
    Spectrum
    """
    m = get_model(model)
    check_choice("method", method, METHODS)
    given = model_parameters(m, dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu))
    if parallel is not None:
        parallel = check_flag("parallel", parallel)
    if method == "kernel":
        fused = _fused(m, given, mask_unphysical, parallel)
        if fused is not None:
            return fused
    p, inside = check_domain(mask=mask_unphysical, **given)
    if method == "kernel":
        out = _kernel(m, p, inside, parallel)  # the kernel writes every point (NaN, flag -1 outside)
        if out is not None:
            ev, bound, neutral, stab = out
            return Spectrum(m, p, ev, bound, neutral, stab, inside)
        method = "polynomial"
    shape = inside.shape
    n = m.n_modes
    ev = np.full(shape + (n,), complex(np.nan, np.nan))
    bound = np.full(shape + (n,), np.nan)
    neutral = np.zeros(shape + (n,), dtype=bool)
    stab = np.full(shape, -1, dtype=np.int8)
    if inside.any():
        sub = {k: v[inside] for k, v in p.items()}
        if method == "polynomial":
            r = polynomial_roots(m.coefficients(**sub))
            e, b, x = r.roots, r.error_bound, r.exact_real
        else:
            e, b, x = lapack_eigenvalues(m, sub)
        order = mode_order(e)
        e, b, x = (np.take_along_axis(a, order, -1) for a in (e, b, x))
        nt, st = _classify(e, b, x)
        ev[inside], bound[inside], neutral[inside], stab[inside] = e, b, nt, st
    return Spectrum(m, p, ev, bound, neutral, stab, inside)


def eigenvalues(
    model: str | LinearModel,
    *,
    q: Any,
    fr_inv: Any,
    sigma: Any,
    alpha_v: Any = None,
    mu: Any = DEFAULT_MU,
    method: str = DEFAULT_METHOD,
) -> np.ndarray:
    """Eigenvalues ``s`` of a linear model, ``x ~ exp(s t)``.

    Parameters
    ----------
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"}
        Eqs. (8)-(9) (two modes) or eq. (11) (three modes).
    q, fr_inv, sigma : float or array_like
        Centre-of-mass offset, inverse Froude number, inertia ratio (broadcast together).
    alpha_v : float or array_like, optional
        Viscous friction parameter; required for ``"sliding"``, refused otherwise.
    mu : float or array_like, default 2.28
        Scaled mass.
    method : {"kernel", "polynomial", "lapack"}
        Root finder (see :data:`METHODS`).

    Returns
    -------
    numpy.ndarray of complex, shape broadcast(parameters) + (n_modes,)
        Sorted by decreasing real part. Growth rate ``Re s``, frequency ``Im s`` (fixed
        frame, units of the spin rate, time in ``1/Omega``).

    Raises
    ------
    DomainError
        A point outside the physical domain (the message names parameter, value and bound).
    TypeError
        A missing, foreign or non-real parameter.

    Examples
    --------
    >>> import stability
    >>> stability.eigenvalues("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5).shape
    (3,)
    """
    return spectrum(model, q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu, method=method).eigenvalues
