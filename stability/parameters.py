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

Every check raises :class:`DomainError` (a :class:`ValueError`) or :class:`TypeError` whose
message names the parameter, its offending value and the bound.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from typing import Any

import numpy as np

from .inertia import transverse_inertia_g

__all__ = [
    "PARAMETERS",
    "DEFAULT_MU",
    "LONG_NAMES",
    "DomainError",
    "as_parameter",
    "check_domain",
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


class DomainError(ValueError):
    """A parameter lies outside the physical domain (or is not finite, or is empty)."""


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
        raise TypeError(f"{name} must be a real number or an array of reals, got {type(value).__name__} {value!r}")
    if isinstance(value, numbers.Number) and not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be real, got {type(value).__name__} {value!r}")
    try:
        arr = np.asarray(value)
    except Exception as exc:  # ragged lists and the like
        raise TypeError(f"{name} must be a real number or an array of reals: {exc}") from None
    if arr.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be a real number or an array of reals, got dtype {arr.dtype} ({value!r:.60})")
    arr = arr.astype(np.float64)
    if arr.size == 0:
        raise DomainError(f"{name} is empty; give at least one value")
    bad = ~np.isfinite(arr)
    if bad.any():
        first = arr[bad].flat[0]
        raise DomainError(f"{name} = {first} is not finite; {name} must be a finite real number")
    return arr


def _violations(p: Mapping[str, np.ndarray]) -> list[tuple[str, np.ndarray, str]]:
    """List (parameter, violating mask, bound text) for every domain bound."""
    out: list[tuple[str, np.ndarray, str]] = []
    mu = p.get("mu")
    if mu is not None:
        out.append(("mu", mu <= 0, "mu > 0"))
    for name in ("fr_inv", "alpha_v", "alpha_k"):
        if name in p:
            out.append((name, p[name] < 0, f"{name} >= 0"))
    a_g = transverse_inertia_g(p["q"], mu) if "q" in p and mu is not None else None
    if a_g is not None:
        out.append(("q", ~(a_g > 0), "1 - mu q^2 > 0, i.e. |q| < 1/sqrt(mu)"))
    if "sigma" in p:
        out.append(("sigma", p["sigma"] <= 0, "sigma > 0"))
        if a_g is not None:
            # equality (a flat disc) is allowed; a few units of round-off in the caller's own
            # evaluation of the bound are not a physical violation
            out.append(("sigma", p["sigma"] > 2.0 * a_g * (1.0 + 8 * 2.0**-53), "sigma <= 2 (1 - mu q^2)"))
    return out


def _describe(name: str, p: Mapping[str, np.ndarray], where: tuple, bound: str) -> str:
    """Build the message for the first violating point."""
    val = float(p[name][where])
    msg = f"{name} = {val:.6g} is outside the physical domain: {bound}"
    mu = float(p["mu"][where]) if "mu" in p else None
    if name == "q" and mu is not None and mu > 0:
        msg += f" = {1 / math.sqrt(mu):.6g} (mu = {mu:.6g})"
    if name == "sigma" and bound.startswith("sigma <= 2") and mu is not None:
        qv = float(p["q"][where])
        msg += f" = {2 * float(transverse_inertia_g(qv, mu)):.6g} at q = {qv:.6g}, mu = {mu:.6g}"
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
    for _, bad, _ in _violations(p):
        ok &= ~bad
    return ok


def check_domain(*, mask: bool = False, **params: Any) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Validate parameters against the physical domain.

    Parameters
    ----------
    mask : bool, default False
        If False, any point outside the domain refuses the whole request. If True,
        unphysical points are only reported in the returned mask.
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
        For a value that is not real.
    DomainError
        For an empty or non-finite value, incompatible shapes, or (``mask=False``) a point
        outside the domain; the message names the parameter, its value and the bound.
    """
    p = {k: as_parameter(k, v) for k, v in params.items()}
    try:
        b = np.broadcast_arrays(*p.values())
    except ValueError:
        shapes = ", ".join(f"{k}: {v.shape}" for k, v in p.items())
        raise DomainError(f"parameter shapes do not broadcast together ({shapes})") from None
    p = {k: np.asarray(v) for k, v in zip(p.keys(), b)}
    inside = np.ones(b[0].shape, dtype=bool)
    for name, bad, bound in _violations(p):
        if bad.any():
            if not mask:
                where = tuple(int(i[0]) for i in np.nonzero(bad)) if bad.ndim else ()
                msg = _describe(name, p, where, bound)
                if bad.size > 1:
                    msg += (f" ({int(bad.sum())} of {bad.size} grid points violate it; "
                            "pass mask_unphysical=True (--mask-unphysical) to compute the rest)")
                raise DomainError(msg)
            inside &= ~bad
    return p, inside
