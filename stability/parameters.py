"""The nondimensional parameters of the Tippe top and their physical domain.

One spelling everywhere (API keywords, CLI flags ``--fr-inv``, dataset coordinates and
attributes):

==========  =====================================================  ==========================
name        meaning (paper, Sec. 2, eqs. 3 and 7)                  domain
==========  =====================================================  ==========================
``q``       centre-of-mass offset along k, G = O + q R k           ``1 - mu q**2 > 0``
``fr_inv``  inverse Froude number g / (Omega**2 R)                  ``fr_inv >= 0``
``sigma``   axial to transverse inertia about O, C / A0            ``0 < sigma <= 2 (1 - mu q**2)``
``alpha_v`` viscous friction parameter mu Omega R Fr^-1 mu_v        ``alpha_v >= 0``
``mu``      scaled mass M R**2 / A0                                ``mu > 0``
``alpha_k`` Coulomb friction parameter mu Fr^-1 mu_K               ``alpha_k >= 0``
==========  =====================================================  ==========================

Why these bounds: the transverse moment about G is ``A_G = A0 - M R^2 q^2``, positive only for
``1 - mu q^2 > 0`` (at equality the mass matrix of eq. 11 is singular); the principal moments
about G obey the triangle inequality ``C <= 2 A_G``, i.e. ``sigma <= 2 (1 - mu q^2)``.

The bounds are one table, :data:`DOMAIN` (one row per bound: the parameter a violation is
reported for, the parameters involved, strict or not, the text, a slack), whose sides are
computed by :func:`domain_sides` (plain arithmetic registered with numba's
``register_jitable``: Python floats, numpy arrays, compiled kernels; ``A_G`` compensated,
:func:`stability.models.inertia.inertia_g`). From it derive the test of a point
(:func:`bound_holds`; :func:`check_domain` and :func:`domain_mask` on arrays, the spectral
kernel compiled, :func:`inside_domain`), the signed margins ``upper - lower`` (``>= 0`` inside)
that the neutral curves' continuation uses as constraints, and the messages.

Besides the physical domain, every parameter must lie in the *computable range*
:data:`COMPUTABLE_RANGE` (``|x| <= 1e30``, and ``mu >= 1e-30``): beyond it the coefficients of the
characteristic polynomials overflow double precision and the eigenvalues would come out as
NaN or inf. A value outside it is refused whatever ``mask`` says.

Every check raises :class:`~stability.errors.DomainError` (a :class:`ValueError`) or :class:`TypeError` whose
message names the parameter, its offending value and the bound. The helpers below
(:func:`as_scalar`, :func:`check_positive`, :func:`check_flag`, :func:`check_integer`,
:func:`check_choice`, :func:`check_interval`) produce the messages of every other argument check
of the package, so that they read the same everywhere (docs/input_checks.md lists them).
"""

from __future__ import annotations

import functools
import math
import numbers
from collections.abc import Callable, Iterable, Mapping
from typing import Any, NamedTuple

import numpy as np

from continuation.jit import register_jitable

from .errors import DomainError
from .models.inertia import inertia_g

__all__ = [
    "PARAMETERS",
    "DEFAULT_MU",
    "LONG_NAMES",
    "COMPUTABLE_RANGE",
    "DOMAIN",
    "Bound",
    "SIGMA_SLACK",
    "domain_sides",
    "bound_holds",
    "inside_domain",
    "domain_applies",
    "domain_text",
    "as_parameter",
    "as_scalar",
    "check_domain",
    "check_positive",
    "check_flag",
    "check_integer",
    "check_choice",
    "check_interval",
    "domain_mask",
]

#: Canonical order of the linear-analysis parameters (also the dimension order of atlases).
PARAMETERS: tuple[str, ...] = ("q", "fr_inv", "sigma", "alpha_v", "mu")

#: The paper's scaled mass (Table 1 and Sec. 3).
DEFAULT_MU: float = 2.28

LONG_NAMES: dict[str, str] = {
    "q": "centre-of-mass offset along the symmetry axis, in units of R",
    "fr_inv": "inverse Froude number g / (Omega^2 R)",
    "sigma": "axial to transverse moment of inertia about the sphere centre, C / A0",
    "alpha_v": "viscous friction parameter mu Omega R Fr^-1 mu_v",
    "alpha_k": "Coulomb friction parameter mu Fr^-1 mu_K",
    "mu": "scaled mass M R^2 / A0",
}

SYMBOLS: dict[str, str] = {
    "q": "q",
    "fr_inv": "Fr$^{-1}$",
    "sigma": r"$\sigma$",
    "alpha_v": r"$\alpha_v$",
    "alpha_k": r"$\alpha_K$",
    "mu": r"$\mu$",
}


#: name -> (smallest, largest) magnitude accepted (the computable range, module docstring)
COMPUTABLE_RANGE: dict[str, tuple[float, float]] = {
    "q": (0.0, 1e30), "fr_inv": (0.0, 1e30), "sigma": (0.0, 1e30), "alpha_v": (0.0, 1e30),
    "alpha_k": (0.0, 1e30), "mu": (1e-30, 1e30),
}


def _show(value: Any, width: int = 60) -> str:
    """A short ``repr`` of a user's value for a message."""
    text = repr(value)
    return text if len(text) <= width else text[:width - 3] + "..."


def as_parameter(name: str, value: Any) -> np.ndarray:
    """Convert one parameter value to a float array, refusing what is not a real number.

    Parameters
    ----------
    name : str
        The parameter's name, used in error messages.
    value : float or array_like of float
        A real scalar or a (non-empty) array of reals.

    Returns
    -------
    numpy.ndarray
        ``float64`` array (0-d for a scalar).

    Raises
    ------
    TypeError
        For strings, booleans, complex numbers, ``None`` and other non-real input.
    DomainError
        For an empty array or a non-finite entry (NaN, inf).
    """
    if value is None:
        raise TypeError(f"{name} is required (got None); give a real number or an array of reals")
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise TypeError(f"{name} = {_show(value)} is a {type(value).__name__}; "
                        f"{name} must be a real number or an array of reals")
    if isinstance(value, numbers.Number) and not isinstance(value, numbers.Real):
        raise TypeError(f"{name} = {_show(value)} is {type(value).__name__}; {name} must be real")
    try:
        arr = np.asarray(value)
    except Exception:  # ragged lists and the like
        raise TypeError(f"{name} = {_show(value)} is not a rectangular array; "
                        f"{name} must be a real number or an array of reals") from None
    if arr.dtype.kind not in "iuf":
        what = "holds complex numbers" if arr.dtype.kind == "c" else f"has dtype {arr.dtype}"
        raise TypeError(f"{name} = {_show(value)} {what}; {name} must be a real number or an array of reals")
    arr = arr.astype(np.float64)
    if arr.size == 0:
        raise DomainError(f"{name} is empty; give at least one value")
    bad = ~np.isfinite(arr)
    if bad.any():
        first = arr[bad].flat[0]
        raise DomainError(f"{name} = {first} is not finite; {name} must be a finite real number")
    return arr


# --- the physical domain: one table ---------------------------------------------------------

#: slack of the bound ``sigma <= 2 A_G`` in the test of a point (not in the margins): a few units
#: of round-off in the caller's own evaluation of the bound are not a physical violation
SIGMA_SLACK: float = 1.0 + 8 * 2.0**-53


class Bound(NamedTuple):
    """One bound of the physical domain, ``lower < upper`` (strict) or ``lower <= upper``.

    Attributes
    ----------
    parameter : str
        The parameter a violation is reported for.
    involves : tuple of str
        Every parameter the bound depends on; it applies where all of them are given.
    strict : bool
        ``<`` (True) or ``<=``.
    text : str
        The bound as messages print it (and the name of the continuation constraint).
    slack : float
        The test of a point is ``lower <= upper * slack`` (1 but for ``sigma <= 2 A_G``).
    explain : callable or None
        ``explain(values) -> str``: what a message adds after ``text``, from the values of the
        involved parameters at the violating point (floats).
    """

    parameter: str
    involves: tuple[str, ...]
    strict: bool
    text: str
    slack: float = 1.0
    explain: Callable[[Mapping[str, float]], str] | None = None


def _q_limit(v: Mapping[str, float]) -> str:
    mu = v["mu"]
    return ", i.e. |q| < 1/sqrt(mu)" + (f" = {1 / math.sqrt(mu):.6g} (mu = {mu:.6g})" if mu > 0 else "")


def _sigma_limit(v: Mapping[str, float]) -> str:
    return f" = {2 * float(inertia_g(v['q'], v['mu'])):.6g} at q = {v['q']:.6g}, mu = {v['mu']:.6g}"


#: The physical domain, one row per bound, in the order a violation is reported. Row ``k``
#: compares the sides ``domain_sides(...)[2 k]`` (lower) and ``[2 k + 1]`` (upper): the test of
#: a point (:func:`bound_holds`: numpy arrays in :func:`check_domain` and :func:`domain_mask`,
#: compiled in the spectral kernel), the signed margins ``upper - lower`` (``>= 0`` inside) that
#: the neutral curves' continuation uses as constraints, and the messages all come from here.
DOMAIN: tuple[Bound, ...] = (
    Bound("mu", ("mu",), True, "mu > 0"),
    Bound("fr_inv", ("fr_inv",), False, "fr_inv >= 0"),
    Bound("alpha_v", ("alpha_v",), False, "alpha_v >= 0"),
    Bound("alpha_k", ("alpha_k",), False, "alpha_k >= 0"),
    Bound("q", ("q", "mu"), True, "1 - mu q^2 > 0", explain=_q_limit),
    Bound("sigma", ("sigma",), True, "sigma > 0"),
    # equality (a flat disc) is allowed
    Bound("sigma", ("sigma", "q", "mu"), False, "sigma <= 2 (1 - mu q^2)", SIGMA_SLACK, _sigma_limit),
)

#: the columns ``strict`` and ``slack`` of :data:`DOMAIN` as constants for compiled callers
DOMAIN_STRICT: tuple[bool, ...] = tuple(b.strict for b in DOMAIN)
DOMAIN_SLACK: tuple[float, ...] = tuple(b.slack for b in DOMAIN)

#: the arguments of :func:`domain_sides`, in order
DOMAIN_ARGUMENTS: tuple[str, ...] = ("q", "fr_inv", "sigma", "alpha_v", "mu", "alpha_k")


@register_jitable
def domain_sides(q, fr_inv, sigma, alpha_v, mu, alpha_k):
    """The sides ``(lower, upper)`` of every bound of :data:`DOMAIN`, flat, in its order.

    Plain arithmetic (Python floats, numpy arrays, numba): ``A_G = 1 - mu q^2`` is the
    compensated one of :func:`stability.models.inertia.inertia_g`, the same bits everywhere.
    """
    a_g = inertia_g(q, mu)
    return (0.0, mu, 0.0, fr_inv, 0.0, alpha_v, 0.0, alpha_k, 0.0, a_g, 0.0, sigma, sigma, 2.0 * a_g)


@register_jitable
def bound_holds(lower, upper, strict, slack):
    """The test of one bound: ``lower < upper`` (strict) or ``lower <= upper * slack``.

    Written as the sign of ``upper * slack - lower``, which for finite floats is exactly the
    comparison (a difference of two floats is zero only if they are equal); NaN fails.
    Floats, numpy arrays, numba (``strict`` is a constant of the table, no data-dependent
    branch).
    """
    m = (upper * slack if slack != 1.0 else upper) - lower
    return m > 0.0 if strict else m >= 0.0


@register_jitable
def inside_domain(sides, applies):
    """All bounds of :data:`DOMAIN` whose ``applies[k]`` is true hold (compiled callers; every
    test evaluated, no short circuit)."""
    ok = True
    for k in range(len(DOMAIN_STRICT)):
        ok &= bound_holds(sides[2 * k], sides[2 * k + 1], DOMAIN_STRICT[k], DOMAIN_SLACK[k]) | (not applies[k])
    return ok


def domain_applies(names: Iterable[str]) -> tuple[bool, ...]:
    """For each bound of :data:`DOMAIN`, whether it applies to a point that gives ``names``."""
    return _applies(frozenset(names))


@functools.lru_cache(maxsize=64)
def _applies(given: frozenset[str]) -> tuple[bool, ...]:
    return tuple(given.issuperset(b.involves) for b in DOMAIN)


def domain_text(names: Iterable[str]) -> str:
    """The bounds that apply to ``names``, as text (``"mu > 0, fr_inv >= 0, ..."``)."""
    return ", ".join(b.text for b, a in zip(DOMAIN, domain_applies(names)) if a)


#: values for parameters a caller does not give (the bounds that involve them do not apply)
_ABSENT = {"q": 0.0, "fr_inv": 0.0, "sigma": 1.0, "alpha_v": 0.0, "mu": 1.0, "alpha_k": 0.0}


def _violations(p: Mapping[str, np.ndarray]) -> list[tuple[Bound, np.ndarray]]:
    """(bound, violating mask) for every bound of :data:`DOMAIN` that applies to ``p`` (arrays of
    one shape; a single point is evaluated in Python floats, the same operations, faster than
    numpy on 0-d arrays)."""
    if all(np.ndim(v) == 0 for v in p.values()):
        args = [float(p[k]) if k in p else _ABSENT[k] for k in DOMAIN_ARGUMENTS]
    else:
        args = [p.get(k, _ABSENT[k]) for k in DOMAIN_ARGUMENTS]
    sides = domain_sides(*args)
    out: list[tuple[Bound, np.ndarray]] = []
    for k, (b, applies) in enumerate(zip(DOMAIN, domain_applies(p))):
        if applies:
            out.append((b, np.logical_not(bound_holds(sides[2 * k], sides[2 * k + 1], b.strict, b.slack))))
    return out


def _describe(b: Bound, p: Mapping[str, np.ndarray], where: tuple) -> str:
    """The message for the first point ``where`` violating ``b``."""
    msg = f"{b.parameter} = {float(p[b.parameter][where]):.6g} is outside the physical domain: {b.text}"
    if b.explain is not None:
        msg += b.explain({k: float(p[k][where]) for k in b.involves})
    return msg


def domain_mask(**params: Any) -> np.ndarray:
    """Boolean mask of the points inside the physical domain (broadcast shape).

    Parameters
    ----------
    **params
        Any of q, fr_inv, sigma, alpha_v, alpha_k, mu (converted with :func:`as_parameter`).

    Returns
    -------
    numpy.ndarray of bool
        True where every bound holds.
    """
    p = {k: as_parameter(k, v) for k, v in params.items()}
    b = np.broadcast_arrays(*p.values())
    p = dict(zip(p.keys(), b))
    ok = np.ones(b[0].shape, dtype=bool)
    for _, bad in _violations(p):
        ok &= ~bad
    return ok


def _check_computable(p: Mapping[str, np.ndarray]) -> None:
    """Refuse magnitudes outside :data:`COMPUTABLE_RANGE` (always, whatever the mask)."""
    for name, v in p.items():
        if name not in COMPUTABLE_RANGE:
            continue
        lo, hi = COMPUTABLE_RANGE[name]
        mag = np.abs(v)
        bad = (mag > hi) | ((mag < lo) & (v > 0))
        if bad.any():
            val = float(v[bad].flat[0])
            rng = f"|{name}| <= {hi:g}" if lo == 0 else f"{lo:g} <= {name} <= {hi:g}"
            raise DomainError(f"{name} = {val:.6g} is outside the computable range: {rng} "
                              "(beyond it the eigenvalues overflow double precision)")


def as_scalar(name: str, value: Any) -> float:
    """One real, finite number (a 0-d or one-element array is accepted).

    Raises
    ------
    TypeError
        Not a real number, or an array of several values (the message gives its shape).
    DomainError
        NaN, inf or empty.
    """
    arr = as_parameter(name, value)
    if arr.size != 1:
        raise TypeError(f"{name} must be a single number here, got an array of shape {arr.shape}")
    return float(arr.reshape(()))


def check_positive(name: str, value: Any, *, strict: bool = True, unit: str = "") -> float:
    """A single finite number ``> 0`` (``strict``) or ``>= 0``; the message names the bound.

    Parameters
    ----------
    name : str
        Parameter name for the message.
    value : float
    strict : bool, default True
        ``> 0`` if True, ``>= 0`` otherwise.
    unit : str, optional
        Unit shown after the value in the message.

    Returns
    -------
    float
    """
    v = as_scalar(name, value)
    if (v <= 0) if strict else (v < 0):
        u = f" {unit}" if unit else ""
        raise DomainError(f"{name} = {v:.6g}{u} is outside the allowed range: {name} {'>' if strict else '>='} 0")
    return v


def check_interval(name: str, value: Any, lo: float, hi: float, *, closed: str = "neither") -> float:
    """A single finite number inside ``(lo, hi)``; ``closed`` in {"neither", "left", "right", "both"}."""
    v = as_scalar(name, value)
    left_ok = v >= lo if closed in ("left", "both") else v > lo
    right_ok = v <= hi if closed in ("right", "both") else v < hi
    if not (left_ok and right_ok):
        lb = "<=" if closed in ("left", "both") else "<"
        rb = "<=" if closed in ("right", "both") else "<"
        raise DomainError(f"{name} = {v:.6g} is outside the allowed range: {lo:g} {lb} {name} {rb} {hi:g}")
    return v


def check_flag(name: str, value: Any) -> bool:
    """``True`` or ``False`` (also numpy booleans); anything else is a :class:`TypeError`."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"{name} = {_show(value)} is a {type(value).__name__}; {name} must be True or False")


def check_integer(name: str, value: Any, *, minimum: int | None = None) -> int:
    """An integer (Python or numpy, not bool), at least ``minimum``; the message names the bound."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)):
        if isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
            value = int(value)
        else:
            raise TypeError(f"{name} = {_show(value)} is a {type(value).__name__}; {name} must be an integer"
                            + (f" >= {minimum}" if minimum is not None else ""))
    v = int(value)
    if minimum is not None and v < minimum:
        raise DomainError(f"{name} = {v} is outside the allowed range: {name} >= {minimum}")
    return v


def check_choice(name: str, value: Any, choices: Iterable[str]) -> str:
    """One of ``choices`` (strings); the message lists them."""
    options = list(choices)
    if not isinstance(value, str) or value not in options:
        raise ValueError(f"{name} = {_show(value)} is not known; choose one of {', '.join(options)}")
    return value


def check_domain(*, mask: bool = False, scalar: bool = False,
                 **params: Any) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Validate parameters against the physical domain.

    Parameters
    ----------
    mask : bool, default False
        If False, any point outside the domain refuses the whole request. If True,
        unphysical points are only reported in the returned mask.
    scalar : bool, default False
        Require every parameter to be a single number (the message names the one that is not).
    **params
        Parameter values (scalars or arrays, broadcast together).

    Returns
    -------
    params : dict of numpy.ndarray
        The parameters as float arrays, broadcast to a common shape.
    inside : numpy.ndarray of bool
        True where the point lies in the physical domain.

    Raises
    ------
    TypeError
        For a value that is not real, or (``scalar=True``) not a single number; for a ``mask``
        that is not a bool.
    DomainError
        For an empty or non-finite value, a value outside the computable range
        (:data:`COMPUTABLE_RANGE`), incompatible shapes, or (``mask=False``) a point outside
        the domain; the message names the parameter, its value and the bound.
    """
    mask = check_flag("mask_unphysical", mask)
    if scalar:
        p = {k: np.asarray(as_scalar(k, v)) for k, v in params.items()}
    else:
        p = {k: as_parameter(k, v) for k, v in params.items()}
    _check_computable(p)
    try:
        b = np.broadcast_arrays(*p.values())
    except ValueError:
        shapes = ", ".join(f"{k}: {v.shape}" for k, v in p.items())
        raise DomainError(f"parameter shapes do not broadcast together ({shapes})") from None
    p = {k: np.asarray(v) for k, v in zip(p.keys(), b)}
    inside = np.ones(b[0].shape, dtype=bool)
    for bound, bad in _violations(p):
        if bad.any():
            if not mask:
                where = tuple(int(i[0]) for i in np.nonzero(bad)) if bad.ndim else ()
                msg = _describe(bound, p, where)
                if bad.size > 1:
                    msg += (f" ({int(bad.sum())} of {bad.size} grid points violate it; "
                            "pass mask_unphysical=True to compute the rest)")
                raise DomainError(msg)
            inside &= ~bad
    return p, inside
