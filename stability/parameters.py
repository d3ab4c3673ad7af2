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
reported for, the parameters involved, strict or not, the text, how a message explains it),
whose sides are computed by :func:`domain_sides` (plain arithmetic registered with numba's
``register_jitable``: Python floats, numpy arrays, compiled kernels). From it derive the test
of a point (:func:`bound_holds`; :func:`check_domain` on arrays (its ``mask=True``), the
spectral kernel compiled, :func:`inside_domain`), the signed margins ``upper - lower``
(``>= 0`` inside) that the neutral curves' continuation uses as constraints, and the messages.

The two bounds through ``A_G = 1 - mu q^2`` are decided *exactly* for the double-precision
numbers given, as the docs state them (``1 - mu q^2 > 0``, ``sigma <= 2 (1 - mu q^2)``,
equality allowed), with no slack: :func:`domain_sides` forms ``mu q^2`` as an exact sum of four
doubles (Dekker's products) and ``A_G`` and ``A_G - sigma/2`` as nonoverlapping expansions
(Shewchuk's grow-expansion of Knuth's two-sums), whose sign is the sign of their largest
nonzero component; the side is a double with that exact sign and within a few ulp of the exact
value. (Comparing ``sigma`` with ``2 A_G`` computed even to a few ulp would refuse points on the
bound or accept points a few ulp beyond it.) :func:`sigma_max` gives the largest ``sigma``
allowed, the exact ``2 (1 - mu q^2)`` rounded down, for callers that want to sit on the bound.
Exact as long as the products' error terms do not underflow (``|q| >= 1e-140`` or ``q = 0``, and
``mu`` in the computable range); below that ``mu q^2 < 1e-250`` is treated as its rounded
value.

Besides the physical domain, every parameter must lie in the *computable range*
:data:`COMPUTABLE_RANGE` (``|x| <= 1e30``, and ``mu >= 1e-30``): beyond it the coefficients of the
characteristic polynomials overflow double precision and the eigenvalues would come out as
NaN or inf. A value outside it is refused whatever ``mask`` says.

Every check raises :class:`~stability.errors.DomainError` (a :class:`ValueError`) or :class:`TypeError` whose
message names the parameter, its offending value and the bound; the two numbers are printed
with as many digits as it takes for them to differ (:func:`fmt_against`: six where that
suffices, up to the shortest round-trip form, so a value one ulp outside a bound does not read
as the bound). Python integers too large for a double, and numpy masked arrays with masked
entries, are refused by name (a masked array without masked entries is its data). The helpers below
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

from stability.jit import register_jitable

from .errors import DomainError, InputError, ParameterTypeError
from .models.inertia import inertia_g, two_product

__all__ = [
    "COMMENTS",
    "COMPUTABLE_RANGE",
    "DEFAULT_MU",
    "DOMAIN",
    "LONG_NAMES",
    "PARAMETERS",
    "UNITS",
    "Bound",
    "as_parameter",
    "as_scalar",
    "bound_holds",
    "check_choice",
    "check_domain",
    "check_flag",
    "check_integer",
    "check_interval",
    "check_positive",
    "check_range",
    "domain_applies",
    "domain_clearly_inside",
    "domain_range",
    "domain_sides",
    "domain_sides_quick",
    "domain_text",
    "fmt_against",
    "inside_domain",
    "parameter_attrs",
    "sigma_max",
]

#: Canonical order of the linear-analysis parameters (also the dimension order of atlases).
PARAMETERS: tuple[str, ...] = ("q", "fr_inv", "sigma", "alpha_v", "mu")

#: The paper's scaled mass (Table 1 and Sec. 3).
DEFAULT_MU: float = 2.28

#: upper ends of the default ranges of the parameters the physical domain leaves unbounded above,
#: one home for both uses: threshold's default bracket (sampled uniform + geometric, so a wide end
#: is cheap; at 10 it misses fr_inv thresholds of tilted-state branch points above 10) and
#: neutral_curve's default window (WINDOW_UPPER_BOUND, a 25 x 25 uniform start grid: at 1e3 its
#: points are 42 apart in fr_inv and the branch point at (q, fr_inv) = (0, 1/mu) is missed)
UPPER_BOUND: dict[str, float] = {"fr_inv": 1e3, "alpha_v": 1e3, "mu": 1e3}
WINDOW_UPPER_BOUND = 10.0

LONG_NAMES: dict[str, str] = {
    "q": "centre-of-mass offset q",
    "fr_inv": "inverse Froude number",
    "sigma": "inertia ratio sigma = C/A0",
    "alpha_v": "viscous friction alpha_v",
    "alpha_k": "Coulomb friction alpha_K",
    "mu": "scaled mass mu = M R^2/A0",
}

#: units of each parameter as datasets write them (xarray prints ``long_name [units]``)
UNITS: dict[str, str] = {"q": "R", "fr_inv": "1", "sigma": "1", "alpha_v": "1", "alpha_k": "1", "mu": "1"}

#: what each parameter is, beyond its short long_name (the ``comment`` attribute)
COMMENTS: dict[str, str] = {
    "q": "offset of the centre of mass G from the sphere's centre O along the symmetry axis, "
    "G = O + q R k, in units of the radius R (q < 0: G below O)",
    "fr_inv": "g / (Omega^2 R), eq. (3)",
    "sigma": "axial to transverse moment of inertia about the sphere's centre, C / A0, eq. (3)",
    "alpha_v": "viscous friction parameter mu Omega R Fr^-1 mu_v, eq. (7)",
    "alpha_k": "Coulomb friction parameter mu Fr^-1 mu_K, eq. (7)",
    "mu": "scaled mass M R^2 / A0, eq. (3)",
}


def parameter_attrs(name: str) -> dict[str, str]:
    """The netCDF attributes of a parameter coordinate: short ``long_name``, ``units``, ``comment``."""
    return {"long_name": LONG_NAMES[name], "units": UNITS[name], "comment": COMMENTS[name]}


SYMBOLS: dict[str, str] = {
    "q": "q",
    "fr_inv": "Fr$^{-1}$",
    "sigma": r"$\sigma$",
    "alpha_v": r"$\alpha_v$",
    "alpha_k": r"$\alpha_K$",
    "mu": r"$\mu$",
}


#: the largest magnitude of any parameter or state component the package computes with (the
#: computable range, module docstring)
COMPUTABLE_MAX = 1e30

#: name -> (smallest, largest) magnitude accepted (the computable range, module docstring)
COMPUTABLE_RANGE: dict[str, tuple[float, float]] = dict.fromkeys(
    ("q", "fr_inv", "sigma", "alpha_v", "alpha_k"), (0.0, COMPUTABLE_MAX)
) | {"mu": (1e-30, COMPUTABLE_MAX)}


def _show(value: Any, width: int = 60) -> str:
    """A short ``repr`` of a user's value for a message."""
    text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


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
        raise ParameterTypeError(f"{name} is required (got None); give a real number or an array of reals")
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise ParameterTypeError(
            f"{name} = {_show(value)} is a {type(value).__name__}; {name} must be a real number or an array of reals"
        )
    if isinstance(value, numbers.Number) and not isinstance(value, numbers.Real):
        raise ParameterTypeError(f"{name} = {_show(value)} is {type(value).__name__}; {name} must be real")
    if isinstance(value, np.ma.MaskedArray):
        value = _unmasked(name, value)
    try:
        arr = np.asarray(value)
    except Exception:  # ragged lists and the like
        raise ParameterTypeError(
            f"{name} = {_show(value)} is not a rectangular array; {name} must be a real number or an array of reals"
        ) from None
    if arr.dtype.kind == "O":
        arr = _integers_as_floats(name, arr)
    if arr.dtype.kind not in "iuf":
        what = "holds complex numbers" if arr.dtype.kind == "c" else f"has dtype {arr.dtype}"
        raise ParameterTypeError(f"{name} = {_show(value)} {what}; {name} must be a real number or an array of reals")
    arr = arr.astype(np.float64)
    if arr.size == 0:
        raise DomainError(f"{name} is empty; give at least one value")
    bad = ~np.isfinite(arr)
    if bad.any():
        first = arr[bad].flat[0]
        raise DomainError(f"{name} = {first} is not finite; {name} must be a finite real number")
    return arr


def _unmasked(name: str, value: np.ma.MaskedArray) -> np.ndarray:
    """The data of a masked array with no masked entry; a :class:`DomainError` naming the masked
    entries otherwise (the data under a mask is not the user's value)."""
    mask = np.ma.getmaskarray(value)
    if mask.any():
        where = np.argwhere(mask)
        first = tuple(int(i) for i in where[0]) if mask.ndim else ()
        index = first[0] if len(first) == 1 else first
        raise DomainError(
            f"{name} is a masked array with {int(mask.sum())} masked entr"
            f"{'y' if mask.sum() == 1 else 'ies'} (the first at index {index}); the values "
            f"under a mask are not used: pass {name}.compressed() or {name}.filled(value)"
        )
    return np.ma.getdata(value)


def _integer_text(v: int) -> str:
    """A huge Python integer for a message: its magnitude and number of digits."""
    digits = len(str(abs(v)))
    return f"{'-' if v < 0 else ''}1e+{digits - 1} (an integer of {digits} digits)"


def _integers_as_floats(name: str, arr: np.ndarray) -> np.ndarray:
    """An object array of Python integers (numpy's dtype for integers beyond int64, also mixed
    with floats) as floats (numpy's cast: ``float()`` of each);
    a :class:`DomainError` naming the first item too large for a double (an integer, or a
    ``Fraction`` among them: ``float()`` overflows). Other object arrays
    are returned unchanged (their dtype is refused by the caller)."""
    items = arr.reshape(-1)
    if (
        items.size == 0
        or not all(isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_)) for v in items)
        or not any(isinstance(v, numbers.Integral) for v in items)
    ):
        return arr
    try:
        return arr.astype(np.float64)
    except OverflowError:
        for v in items:  # the first item float() refuses (an integer, or a Fraction beside them)
            try:
                float(v)
            except OverflowError:
                raise DomainError(
                    f"{name} = {_integer_text(int(v))} is outside the computable range: "
                    f"{computable_range_text(name)} (it does not even fit a double)"
                ) from None
        raise


def fmt_against(value: float, bound: float) -> tuple[str, str]:
    """``value`` and ``bound`` as text for a message, with the digits it takes for them to differ.

    Six significant digits (``.6g``) where the two strings differ; otherwise more, up to the
    shortest representation that round-trips (``repr``), so a value one ulp outside a bound
    reads as different from it. Equal numbers print equal.

    Examples
    --------
    >>> fmt_against(0.5, 0.25)
    ('0.5', '0.25')
    >>> import numpy as np
    >>> fmt_against(float(np.nextafter(1.0, 2.0)), 1.0)
    ('1.0000000000000002', '1')
    """
    v, b = float(value), float(bound)
    for digits in range(6, 18):
        a, c = f"{v:.{digits}g}", f"{b:.{digits}g}"
        if a != c or v == b:
            return a, c
    return repr(v), repr(b)


# --- the physical domain: one table ---------------------------------------------------------


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
    limit : callable or None
        ``limit(values) -> float``: the bound as a value of ``parameter`` at the violating point
        (the involved parameters as floats): the value a message prints against the parameter's
        own (:func:`fmt_against`); None: 0.
    explain : callable or None
        ``explain(values, bound_text) -> str``: what a message adds after ``text``, with the
        bound as formatted against the value.
    interval : callable or None
        ``interval(values) -> (lo, hi)``: the values of ``parameter`` the bound allows, given
        those of the other involved parameters that are known (a missing one: the loosest
        bound over its domain); the ends are the bound itself (outside for a strict bound) or
        the largest double inside; None: ``(0, inf)`` (a sign bound).
    """

    parameter: str
    involves: tuple[str, ...]
    strict: bool
    text: str
    limit: Callable[[Mapping[str, float]], float] | None = None
    explain: Callable[[Mapping[str, float], str], str] | None = None
    interval: Callable[[Mapping[str, float]], tuple[float, float]] | None = None


def _q_largest(v: Mapping[str, float]) -> float:
    """The largest ``|q|`` with ``1 - mu q^2 > 0`` exactly (a double), for ``mu > 0``."""
    mu = v["mu"]
    if not mu > 0:
        return math.inf
    # 1/sqrt(mu) is within an ulp or two of the bound
    return float(_largest_holding(np.float64(1.0 / math.sqrt(mu)), lambda b: _exact_margins(b, mu, 0.0)[0] > 0))


def _largest_holding(x: Any, holds: Callable[[Any], Any]) -> Any:
    """The largest double(s) at which ``holds`` is true (elementwise), from a start ``x`` within
    a few ulp of them: down while it fails, then up while the next double holds."""
    for _ in range(64):
        ok = holds(x)
        if np.all(ok):
            break
        x = np.where(ok, x, np.nextafter(x, -np.inf))
    for _ in range(64):
        up = np.nextafter(x, np.inf)
        more = holds(up)
        if not np.any(more):
            break
        x = np.where(more, up, x)
    return x


def _q_limit(v: Mapping[str, float], bound: str) -> str:
    mu = v["mu"]
    return ", i.e. |q| < 1/sqrt(mu)" + (f" (the largest |q| allowed at mu = {mu!r} is {bound})" if mu > 0 else "")


def _sigma_limit(v: Mapping[str, float], bound: str) -> str:
    return f" = {bound} at q = {v['q']!r}, mu = {v['mu']!r} (rounded down: the largest sigma allowed)"


def _sigma_largest(v: Mapping[str, float]) -> float:
    return float(sigma_max(v["q"], v["mu"], _checked=True))


def _q_interval(v: Mapping[str, float]) -> tuple[float, float]:
    """``|q| < 1/sqrt(mu)`` (unbounded without mu: mu may be as small as it likes)."""
    if v.get("mu") is None:
        return (-math.inf, math.inf)
    b = 1.0 / math.sqrt(v["mu"])
    return (-b, b)


def _sigma_interval(v: Mapping[str, float]) -> tuple[float, float]:
    """``sigma <= 2 (1 - mu q^2)``: ``sigma_max(q, mu)``, or 2 (its largest value, at
    ``mu q^2 = 0``) if q or mu is not given."""
    return (-math.inf, 2.0 if v.get("q") is None or v.get("mu") is None else _sigma_largest(v))


#: the unit round-off of double precision (the margins of :func:`domain_sides_quick`)
_U_DOMAIN = 2.0**-53

#: the threshold below which :func:`domain_sides_quick`'s plain ``mu q^2`` and ``sigma/2 + mu q^2``
#: prove ``A_G > 0`` and ``sigma <= 2 A_G`` (its docstring derives the margin ``4u``)
_PLAIN_BELOW = 1.0 - 4.0 * _U_DOMAIN


@register_jitable
def _exact_margins(q: Any, mu: Any, sigma: Any) -> tuple[Any, Any]:
    """``A_G = 1 - mu q^2`` and ``A_G - sigma/2`` as doubles whose signs are exact.

    ``q q = t + te``, ``mu t = u + ue``,
    ``mu te = v + ve`` (:func:`stability.models.inertia.two_product`, exact):
    ``mu q^2 = u + ue + v + ve`` exactly. ``1 - u - ue - v - ve`` is grown
    into a nonoverlapping expansion by Knuth's two-sums (Shewchuk's grow-expansion), then
    ``-sigma/2`` added the same way. The sign of an expansion is that of its largest nonzero
    component; its value, the components summed from the smallest, is within a few ulp (and
    replaced by that largest component in the rare case where the rounding of the sum loses
    the sign). Plain arithmetic without data-dependent branches: Python floats, numpy arrays,
    numba (the same operations in each).
    """
    t, te = two_product(q, q)
    u, ue = two_product(mu, t)
    v, ve = two_product(mu, te)
    # 1 - u, then + (-ue), + (-v), + (-ve) (grow-expansion: components from the smallest)
    x1, x0 = _two_sum(1.0, -u)
    Q, h0 = _two_sum(-ue, x0)
    h2, h1 = _two_sum(Q, x1)
    Q, k0 = _two_sum(-v, h0)
    Q, k1 = _two_sum(Q, h1)
    k3, k2 = _two_sum(Q, h2)
    Q, m0 = _two_sum(-ve, k0)
    Q, m1 = _two_sum(Q, k1)
    Q, m2 = _two_sum(Q, k2)
    m4, m3 = _two_sum(Q, k3)  # [m0, ..., m4] = A_G
    Q, n0 = _two_sum(-(0.5 * sigma), m0)
    Q, n1 = _two_sum(Q, m1)
    Q, n2 = _two_sum(Q, m2)
    Q, n3 = _two_sum(Q, m3)
    n5, n4 = _two_sum(Q, m4)  # [n0, ..., n5] = A_G - sigma/2
    return _expansion_value((m0, m1, m2, m3, m4)), _expansion_value((n0, n1, n2, n3, n4, n5))


@register_jitable
def _two_sum(a: Any, b: Any) -> tuple[Any, Any]:
    """``s + e = a + b`` exactly, ``s = fl(a + b)`` (Knuth's two-sum)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


@register_jitable
def _expansion_value(e: tuple[float, ...]) -> Any:
    """The sum of the expansion ``e`` from its smallest component, replaced by its largest
    nonzero component where the rounding of the sum loses that component's sign."""
    top = e[0]
    val = e[0]
    for c in e[1:]:
        top = c + (c == 0.0) * top
        val = val + c
    return val + ((val * top <= 0.0) & (top != 0.0)) * (top - val)


#: The physical domain, one row per bound, in the order a violation is reported. Row ``k``
#: compares the sides ``domain_sides(...)[2 k]`` (lower) and ``[2 k + 1]`` (upper): the test of
#: a point (:func:`bound_holds`: numpy arrays in :func:`check_domain` (also with ``mask=True``),
#: compiled in the spectral kernel), the signed margins ``upper - lower`` (``>= 0`` inside) that
#: the neutral curves' continuation uses as constraints, and the messages all come from here.
DOMAIN: tuple[Bound, ...] = (
    Bound("mu", ("mu",), True, "mu > 0"),
    Bound("fr_inv", ("fr_inv",), False, "fr_inv >= 0"),
    Bound("alpha_v", ("alpha_v",), False, "alpha_v >= 0"),
    Bound("alpha_k", ("alpha_k",), False, "alpha_k >= 0"),
    # exact (module docstring): the sides are 0 and A_G with its exact sign
    Bound(
        "q", ("q", "mu"), True, "1 - mu q^2 > 0", lambda v: math.copysign(_q_largest(v), v["q"]), _q_limit, _q_interval
    ),
    Bound("sigma", ("sigma",), True, "sigma > 0"),
    # equality (a flat disc) is allowed; exact, without slack (module docstring): the sides are 0
    # and 2 (A_G - sigma/2) with its exact sign
    Bound(
        "sigma", ("sigma", "q", "mu"), False, "sigma <= 2 (1 - mu q^2)", _sigma_largest, _sigma_limit, _sigma_interval
    ),
)

#: the column ``strict`` of :data:`DOMAIN` as constants for compiled callers
DOMAIN_STRICT: tuple[bool, ...] = tuple(b.strict for b in DOMAIN)

#: the arguments of :func:`domain_sides`, in order
DOMAIN_ARGUMENTS: tuple[str, ...] = (*PARAMETERS, "alpha_k")


@register_jitable
def domain_sides(q: Any, fr_inv: Any, sigma: Any, alpha_v: Any, mu: Any, alpha_k: Any) -> tuple[Any, ...]:
    """The sides ``(lower, upper)`` of every bound of :data:`DOMAIN`, flat, in its order.

    Plain arithmetic (Python floats, numpy arrays, numba). The bounds through ``A_G`` have
    ``lower = 0`` and as ``upper`` a double with the *exact* sign of ``1 - mu q^2`` and of
    ``2 (1 - mu q^2) - sigma`` for the doubles given, within a few ulp of their values
    (:func:`_exact_margins`, module docstring).
    """
    a_g, room = _exact_margins(q, mu, sigma)
    return (0.0, mu, 0.0, fr_inv, 0.0, alpha_v, 0.0, alpha_k, 0.0, a_g, 0.0, sigma, 0.0, 2.0 * room)


@register_jitable
def domain_sides_quick(q: Any, fr_inv: Any, sigma: Any, alpha_v: Any, mu: Any, alpha_k: Any) -> tuple[Any, ...]:
    """Sides of every bound of :data:`DOMAIN` with the *same signs* as :func:`domain_sides`
    (so :func:`inside_domain` decides the same), cheaply: the two bounds through ``A_G`` are
    decided by a plain floating-point comparison where its rounding cannot change the answer,
    and by the exact :func:`_exact_margins` only where it can (points within a few ulp of
    ``1 - mu q^2 = 0`` or ``sigma = 2 (1 - mu q^2)``, and any point with ``mu < 0``,
    ``sigma < 0`` or NaN). The values of the two ``A_G`` sides are then ``+-1`` rather than the
    margins: for the test only (compiled kernels), not for continuation constraints or messages.

    The margin (round to nearest, unit round-off ``u = 2**-53``, ``mu >= 0``, ``sigma >= 0``):
    ``t = fl(q q) = q^2 (1 + d1)``, ``a = fl(mu t) = mu q^2 (1 + d1)(1 + d2)``,
    ``w = fl(sigma/2 + a) = (sigma/2 + a)(1 + d3)``, ``|dk| <= u`` (``sigma/2`` is exact), so
    with ``X = mu q^2`` and ``Y = sigma/2 + X`` (both ``>= 0``)::

        a / (1 + u)^2 <= X <= a / (1 - u)^2,    w / (1 + u)^3 <= Y <= w / (1 - u)^3.

    Hence ``a <= 1 - 4u`` gives ``X <= (1 - 4u)/(1 - u)^2 < 1`` (``A_G > 0``), ``a >= 1 + 4u``
    gives ``X >= (1 + 4u)/(1 + u)^2 > 1`` (``A_G < 0``); ``w <= 1 - 4u`` gives ``Y < 1``
    (``sigma < 2 A_G``) and ``w >= 1 + 4u`` gives ``Y >= (1 + 4u)/(1 + u)^3 > 1`` (``sigma > 2 A_G``). Underflow in
    ``t`` or ``a`` adds at most ``2**-1074 (1 + mu)`` absolutely (``mu <= 1e30`` in the
    computable range), far below the slack ``~2u`` of these thresholds; overflow to inf makes
    ``a`` or ``w`` inf, which the thresholds decide as outside, as the exact test does.
    Between the thresholds (and for ``mu < 0``, ``sigma < 0``, NaN, where the comparisons
    fail) the exact sign is computed. tests/test_parameters.py checks the decision against
    :mod:`fractions` on the bounds and one ulp either side.
    """
    a = mu * (q * q)
    w = 0.5 * sigma + a
    plain = (mu >= 0.0) & (sigma >= 0.0)
    lo = _PLAIN_BELOW
    q_easy = plain & ((a <= lo) | (a >= 1.0 + 4.0 * _U_DOMAIN))
    s_easy = plain & ((w <= lo) | (w >= 1.0 + 4.0 * _U_DOMAIN))
    if q_easy & s_easy:
        a_g = 1.0 if a <= lo else -1.0
        room = 1.0 if w <= lo else -1.0
    else:
        a_g, room = _exact_margins(q, mu, sigma)
    return (0.0, mu, 0.0, fr_inv, 0.0, alpha_v, 0.0, alpha_k, 0.0, a_g, 0.0, sigma, 0.0, 2.0 * room)


@register_jitable
def domain_clearly_inside(q: Any, fr_inv: Any, sigma: Any, alpha_v: Any, mu: Any, alpha_k: Any, applies: Any) -> Any:
    """Whether the plain comparisons alone put a point inside every bound of :data:`DOMAIN` whose
    ``applies[k]`` is true: no branch on data (``&``, ``|``), so that a compiled loop over many
    points packs it; false where the exact test is needed (or the point is outside).

    True only if :func:`inside_domain` of :func:`domain_sides_quick` is true, by construction:
    it is :func:`inside_domain` of the same sides, except that the two through ``A_G`` are
    ``+1`` (hold) only in :func:`domain_sides_quick`'s plain case
    ``mu >= 0``, ``sigma >= 0``, ``fl(mu fl(q q)) <= 1 - 4u``, ``fl(sigma/2 + fl(mu fl(q q))) <= 1 - 4u``,
    where its derivation gives ``1 - mu q^2 > 0`` and ``sigma < 2 (1 - mu q^2)`` exactly (the
    rounding of the three operations moves each value by a factor within ``(1 +- u)^3``, less
    than the ``4u`` of the threshold) and it returns the sides ``1`` and ``2``, which hold.
    NaN fails every comparison (false). tests/test_domain_quick.py checks it against the exact
    rule within a few ulp of every bound.
    """
    a = mu * (q * q)
    w = 0.5 * sigma + a
    plain = (mu >= 0.0) & (sigma >= 0.0)
    a_g = 1.0 if plain & (a <= _PLAIN_BELOW) else -1.0  # selects: the sides of the plain case
    room = 1.0 if plain & (w <= _PLAIN_BELOW) else -1.0
    return inside_domain(
        (0.0, mu, 0.0, fr_inv, 0.0, alpha_v, 0.0, alpha_k, 0.0, a_g, 0.0, sigma, 0.0, 2.0 * room), applies
    )


@register_jitable
def bound_holds(lower: Any, upper: Any, strict: bool) -> Any:
    """The test of one bound: ``lower < upper`` (strict) or ``lower <= upper``.

    Written as the sign of ``upper - lower``, which for finite floats is exactly the
    comparison (a difference of two floats is zero only if they are equal); NaN fails.
    Floats, numpy arrays, numba (``strict`` is a constant of the table, no data-dependent
    branch).
    """
    m = upper - lower
    return m > 0.0 if strict else m >= 0.0


@register_jitable
def inside_domain(sides: Any, applies: Any) -> Any:
    """All bounds of :data:`DOMAIN` whose ``applies[k]`` is true hold (compiled callers; every
    test evaluated, no short circuit)."""
    ok = True
    for k in range(len(DOMAIN_STRICT)):
        ok &= bound_holds(sides[2 * k], sides[2 * k + 1], DOMAIN_STRICT[k]) | (not applies[k])
    return ok


def sigma_max(q: Any, mu: Any = DEFAULT_MU, *, _checked: bool = False) -> float | np.ndarray:
    """The largest ``sigma`` allowed at ``q``, ``mu``: the exact ``2 (1 - mu q^2)`` rounded down to
    a double (the test of :data:`DOMAIN` accepts it and refuses the next double up).

    Parameters
    ----------
    q, mu : float or array_like
        Inside the domain (``mu > 0``, ``1 - mu q^2 > 0``); broadcast together.

    Returns
    -------
    float or numpy.ndarray

    Raises
    ------
    DomainError, TypeError
        As :func:`check_domain` for ``q`` and ``mu``.

    Examples
    --------
    >>> import stability
    >>> s = stability.sigma_max(0.3, 2.28)
    >>> stability.eigenvalues("sliding", q=0.3, fr_inv=0.1, sigma=s, alpha_v=0.5).shape
    (3,)
    """
    if _checked:
        qa, ma = np.asarray(q, dtype=float), np.asarray(mu, dtype=float)
    else:
        p, _ = check_domain(q=q, mu=mu)
        qa, ma = p["q"], p["mu"]
    # 2 A_G is within a few ulp of the bound
    s = _largest_holding(2.0 * inertia_g(qa, ma), lambda x: _exact_margins(qa, ma, x)[1] >= 0.0)
    return float(s) if np.ndim(s) == 0 else s


def domain_applies(names: Iterable[str]) -> tuple[bool, ...]:
    """For each bound of :data:`DOMAIN`, whether it applies to a point that gives ``names``."""
    return _applies(frozenset(names))


@functools.lru_cache(maxsize=64)
def _applies(given: frozenset[str]) -> tuple[bool, ...]:
    return tuple(given.issuperset(b.involves) for b in DOMAIN)


def domain_range(name: str, given: Mapping[str, float]) -> tuple[float, float]:
    """The values of ``name`` the domain allows given the other parameters ``given`` (floats; a
    missing one is free): the intersection of the ``interval`` of every row of :data:`DOMAIN`
    reported for ``name`` (ends as :class:`Bound` says; infinite where nothing bounds it).

    Examples
    --------
    >>> domain_range("q", {"mu": 4.0})
    (-0.5, 0.5)
    >>> domain_range("sigma", {"q": 0.0, "mu": 2.28})
    (0.0, 2.0)
    """
    lo, hi = -math.inf, math.inf
    for b in DOMAIN:
        if b.parameter != name:
            continue
        a, c = b.interval(given) if b.interval is not None else (0.0, math.inf)
        lo, hi = max(lo, a), min(hi, c)
    return lo, hi


def domain_text(names: Iterable[str]) -> str:
    """The bounds that apply to ``names``, as text (``"mu > 0, fr_inv >= 0, ..."``)."""
    return ", ".join(b.text for b, a in zip(DOMAIN, domain_applies(names)) if a)


#: values for parameters a caller does not give (the bounds that involve them do not apply)
_ABSENT = {"q": 0.0, "fr_inv": 0.0, "sigma": 1.0, "alpha_v": 0.0, "mu": 1.0, "alpha_k": 0.0}


def _violations(p: Mapping[str, np.ndarray]) -> list[tuple[Bound, np.ndarray]]:
    """(bound, violating mask) for every bound of :data:`DOMAIN` that applies to ``p`` (arrays of
    one shape; a single point of plain numbers inside the domain never comes here:
    :func:`_plain_point_inside`)."""
    applies = domain_applies(p)
    # in blocks, so that the few dozen temporaries of the exact margins stay small
    shape = np.broadcast_shapes(*(np.shape(v) for v in p.values()))
    flat = {k: np.broadcast_to(v, shape).reshape(-1) for k, v in p.items()}
    n = int(np.prod(shape, dtype=np.int64))
    bad = {k: np.zeros(n, dtype=bool) for k in range(len(DOMAIN)) if applies[k]}
    for start in range(0, n, _DOMAIN_BLOCK):
        stop = min(n, start + _DOMAIN_BLOCK)
        sides = domain_sides(*[flat[k][start:stop] if k in flat else _ABSENT[k] for k in DOMAIN_ARGUMENTS])
        for k, out in bad.items():
            out[start:stop] = np.logical_not(bound_holds(sides[2 * k], sides[2 * k + 1], DOMAIN[k].strict))
    return [(DOMAIN[k], out.reshape(shape)) for k, out in bad.items()]


#: points per block of the domain test of arrays (:func:`_violations`): the exact margins keep
#: about 60 temporaries alive, 60 x 8 B x 65536 = 31 MB at most
_DOMAIN_BLOCK = 65536


def _describe(b: Bound, p: Mapping[str, np.ndarray], where: tuple[Any, ...]) -> str:
    """The message for the first point ``where`` violating ``b`` (value and bound printed with
    the digits it takes to tell them apart, :func:`fmt_against`)."""
    values = {k: float(p[k][where]) for k in b.involves}
    value = values[b.parameter]
    limit = b.limit(values) if b.limit is not None else 0.0
    v_text, b_text = fmt_against(value, limit)
    msg = f"{b.parameter} = {v_text} is outside the physical domain: {b.text}"
    if b.explain is not None:
        msg += b.explain(values, b_text)
    return msg


@register_jitable
def outside_range(x: Any, lo: Any, hi: Any) -> Any:
    """Whether ``x`` (a float, an array, or a number in compiled code) lies outside the range
    ``lo <= |x| <= hi`` of magnitudes (``|x| < lo`` counts only for ``x > 0``; NaN is outside).
    The one home of the computable-range test (:data:`COMPUTABLE_RANGE`), without branches so
    that it works elementwise."""
    m = abs(x)
    return (m > hi) | (m != m) | ((m < lo) & (x > 0))


def computable_range_text(name: str) -> str:
    """``name``'s computable range as a message states it (``|q| <= 1e+30``)."""
    lo, hi = COMPUTABLE_RANGE.get(name, (0.0, float(np.finfo(float).max)))
    return f"|{name}| <= {hi:g}" if lo == 0 else f"{lo:g} <= {name} <= {hi:g}"


def _check_computable(p: Mapping[str, np.ndarray]) -> None:
    """Refuse magnitudes outside :data:`COMPUTABLE_RANGE` (always, whatever the mask)."""
    for name, v in p.items():
        if name not in COMPUTABLE_RANGE:
            continue
        lo, hi = COMPUTABLE_RANGE[name]
        bad = outside_range(v, lo, hi)
        if bad.any():
            val = float(v[bad].flat[0])
            v_text, edge = fmt_against(val, math.copysign(hi, val) if abs(val) > hi else lo)
            rng = computable_range_text(name) if abs(val) > hi else f"{edge} <= {name} <= {hi:g}"
            raise DomainError(
                f"{name} = {v_text} is outside the computable range: {rng} "
                "(beyond it the eigenvalues overflow double precision)"
            )


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
        raise ParameterTypeError(f"{name} must be a single number here, got an array of shape {arr.shape}")
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
        raise DomainError(
            f"{name} = {fmt_against(v, 0.0)[0]}{u} is outside the allowed range: {name} {'>' if strict else '>='} 0"
        )
    return v


def check_range(name: str, value: Any) -> tuple[float, float]:
    """A pair ``(lo, hi)`` of finite reals with ``lo < hi``; the messages name ``name``."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise ParameterTypeError(f"{name} = {value!r} must be a pair (lo, hi) of real numbers")
    lo, hi = (as_scalar(name, v) for v in value)
    if not lo < hi:
        a, b = fmt_against(lo, hi)
        raise InputError(f"{name} = ({a}, {b}) is outside the allowed range: lo < hi")
    return lo, hi


def check_interval(name: str, value: Any, lo: float, hi: float, *, closed: str = "neither") -> float:
    """A single finite number inside ``(lo, hi)``; ``closed`` in {"neither", "left", "right", "both"}."""
    v = as_scalar(name, value)
    left_ok = v >= lo if closed in ("left", "both") else v > lo
    right_ok = v <= hi if closed in ("right", "both") else v < hi
    if not (left_ok and right_ok):
        lb = "<=" if closed in ("left", "both") else "<"
        rb = "<=" if closed in ("right", "both") else "<"
        v_text, edge = fmt_against(v, lo if not left_ok else hi)
        lo_text, hi_text = (edge, f"{hi:g}") if not left_ok else (f"{lo:g}", edge)
        raise DomainError(f"{name} = {v_text} is outside the allowed range: {lo_text} {lb} {name} {rb} {hi_text}")
    return v


def check_flag(name: str, value: Any) -> bool:
    """``True`` or ``False`` (also numpy booleans); anything else is a :class:`TypeError`."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ParameterTypeError(f"{name} = {_show(value)} is a {type(value).__name__}; {name} must be True or False")


def check_integer(name: str, value: Any, *, minimum: int | None = None, maximum: int | None = None) -> int:
    """An integer (Python or numpy, not bool) in ``[minimum, maximum]``; the message names the
    bounds (a huge integer by its number of digits)."""
    top = str(maximum)  # a round maximum of 10^5 or more as 1e9, 5e5
    if maximum is not None and maximum >= 10**5 and f"{maximum:.0e}" == f"{maximum:.1e}".replace(".0e", "e"):
        top = f"{maximum:.0e}".replace("e+0", "e").replace("e+", "e")
    if minimum is not None and maximum is not None:
        both, rng = f" in [{minimum}, {top}]", f"{minimum} <= {name} <= {top}"
    else:  # one bound or none: ``>= 1`` after "an integer" and after the name
        bound = f">= {minimum}" if minimum is not None else f"<= {top}" if maximum is not None else ""
        both, rng = f" {bound}" if bound else "", f"{name} {bound}"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)):
        if isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
            value = int(value)
        else:
            raise ParameterTypeError(
                f"{name} = {_show(value)} is a {type(value).__name__}; {name} must be an integer{both}"
            )
    v = int(value)
    if (minimum is not None and v < minimum) or (maximum is not None and v > maximum):
        shown = _integer_text(v) if len(str(abs(v))) > 18 else str(v)
        raise DomainError(f"{name} = {shown} is outside the allowed range: {rng}")
    return v


def check_choice(name: str, value: Any, choices: Iterable[str]) -> str:
    """One of ``choices`` (strings); the message lists them."""
    options = list(choices)
    if not isinstance(value, str) or value not in options:
        raise InputError(f"{name} = {_show(value)} is not known; choose one of {', '.join(options)}")
    return value


#: the plain scalar types that :func:`_plain_point_inside` reads without numpy (``bool`` is not
#: one of them: it is refused by :func:`as_parameter`)
_PLAIN = (float, int, np.float64)


def _plain_point_inside(params: Mapping[str, Any]) -> dict[str, np.ndarray] | None:
    """The fast path of :func:`check_domain` for one point given as plain numbers.

    Returns the parameters as 0-d float arrays when every value is a Python ``float``/``int``
    (or ``numpy.float64``) whose float is finite, inside :data:`COMPUTABLE_RANGE` and every
    bound of :data:`DOMAIN` holds (the same :func:`domain_sides` and :func:`bound_holds`
    evaluated in Python floats); ``None`` otherwise, and the general path then decides and
    words the message. It accepts nothing the general path refuses (the same tests on the same
    doubles) and never refuses: a point that fails any test goes to the general path.
    A single point is what ``final_state``, ``steady_states`` and ``simulate`` check (what
    this path saves them: docs/performance.md, the final-state table).
    """
    vals: dict[str, float] = {}
    for k, v in params.items():
        if type(v) not in _PLAIN or k not in COMPUTABLE_RANGE:
            return None
        if type(v) is int and not -(2**53) <= v <= 2**53:
            return None
        x = float(v)
        if outside_range(x, *COMPUTABLE_RANGE[k]):  # NaN too
            return None
        vals[k] = x
    if not vals:
        return None
    sides = domain_sides(*[vals.get(k, _ABSENT[k]) for k in DOMAIN_ARGUMENTS])
    for i, (b, applies) in enumerate(zip(DOMAIN, domain_applies(vals))):
        if applies and not bound_holds(sides[2 * i], sides[2 * i + 1], b.strict):
            return None
    return {k: np.asarray(x) for k, x in vals.items()}


def check_domain(
    *, mask: bool = False, scalar: bool = False, maskable: bool = True, **params: Any
) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Validate parameters against the physical domain.

    Parameters
    ----------
    mask : bool, default False
        If False, any point outside the domain refuses the whole request. If True,
        unphysical points are only reported in the returned mask.
    scalar : bool, default False
        Require every parameter to be a single number (the message names the one that is not).
    maskable : bool, default True
        Whether the caller offers ``mask_unphysical``: only then does the message of a grid
        with points outside suggest it.
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
    fast = _plain_point_inside(params)
    if fast is not None:
        return fast, np.ones((), dtype=bool)
    p = {k: np.asarray(as_scalar(k, v)) if scalar else as_parameter(k, v) for k, v in params.items()}
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
                    msg += f" ({int(bad.sum())} of {bad.size} grid points violate it; " + (
                        "pass mask_unphysical=True to compute the rest)" if maskable else "every point must lie inside)"
                    )
                raise DomainError(msg)
            inside &= ~bad
    return p, inside
