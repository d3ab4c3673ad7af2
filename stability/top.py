"""A real top in SI units, and its nondimensional parameters at a given spin (eqs. 3 and 7).

The nondimensional set follows the paper's Sec. 2::

    A0    = A_G + M d^2            transverse moment about the sphere centre O (d = com_offset)
    q     = d / R                  eq. (3) geometry, G = O + q R k
    mu    = M R^2 / A0             eq. (3)
    sigma = C / A0                 eq. (3) (the axial moment is the same about G and O)
    fr_inv = g / (Omega^2 R)       eq. (3)
    alpha_K = mu fr_inv mu_K       eq. (7)
    alpha_v = mu Omega R fr_inv mu_v = mu mu_v g / Omega     eq. (7), mu_v in s/m

so q, mu and sigma are properties of the top, while fr_inv (~ Omega^-2) and alpha_v
(~ Omega^-1) change with the spin.

Table 1 of the paper is not internally consistent (NOTES.md): its mass, radius and moments
give mu ~ 3.7, not the 2.28 it lists and the simulations use. Two presets are offered:

* :meth:`Top.table1` (the default "toy top"): mass 0.64 oz and radius 0.6366 in (the radius
  with which the paper's 1/Froude rows and its Sec. 3(ii) spin rates hold), with the inertias
  chosen so that the nondimensional set is the one the paper computes with: ``q = -0.1``,
  ``mu = 2.28``, ``sigma = 1.0``.
* :meth:`Top.table1_measured`: the table's measured entries taken literally (mass 0.64 oz,
  R = 0.63 in, q = -0.094, transverse moment about G 0.066 oz in^2, axial 0.066 oz in^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .errors import DomainError
from .parameters import as_parameter, as_scalar, check_choice, check_domain, check_positive

__all__ = ["Top", "SPIN_UNITS", "OUNCE", "INCH"]

#: avoirdupois ounce and inch in SI
OUNCE = 0.028349523125
INCH = 0.0254

#: rad/s per unit of spin rate
SPIN_UNITS: dict[str, float] = {"rad/s": 1.0, "rpm": 2.0 * math.pi / 60.0, "rev/s": 2.0 * math.pi}


def _unit(unit: str) -> float:
    return SPIN_UNITS[check_choice("unit", unit, SPIN_UNITS)]


def _positive(name: str, value: Any) -> float:
    return check_positive(name, value)


def _spin(spin: Any, unit: str) -> np.ndarray:
    """Spin rates in rad/s, each > 0 (the message gives the value in the caller's unit)."""
    factor = _unit(unit)
    w = as_parameter("spin", spin)
    if np.any(w <= 0):
        raise DomainError(f"spin = {float(np.min(w)):.6g} {unit} is outside the allowed range: spin > 0")
    return w * factor


@dataclass(frozen=True)
class Top:
    """A spherical top described in SI units.

    Parameters
    ----------
    mass : float
        Mass M in kg (> 0).
    radius : float
        Sphere radius R in m (> 0).
    com_offset : float
        Signed distance from the sphere centre O to the centre of mass G along the symmetry
        axis, in m; negative when G lies below O with the stick pointing up.
    inertia_transverse : float
        Transverse principal moment about G, A_G, in kg m^2 (> 0).
    inertia_axial : float
        Axial moment C in kg m^2 (> 0, and C <= 2 A_G).
    g : float, default 9.80665
        Gravity in m/s^2.
    mu_k : float, optional
        Coulomb (kinetic) friction coefficient (dimensionless, >= 0).
    mu_v : float, optional
        Viscous friction coefficient in s/m (>= 0): f = -N (mu_K + mu_v V_c) e_v (eq. 6).
    """

    mass: float
    radius: float
    com_offset: float
    inertia_transverse: float
    inertia_axial: float
    g: float = 9.80665
    mu_k: float | None = None
    mu_v: float | None = None

    def __post_init__(self) -> None:
        for name in ("mass", "radius", "inertia_transverse", "inertia_axial", "g"):
            object.__setattr__(self, name, _positive(name, getattr(self, name)))
        object.__setattr__(self, "com_offset", as_scalar("com_offset", self.com_offset))
        for name in ("mu_k", "mu_v"):
            v = getattr(self, name)
            if v is not None:
                object.__setattr__(self, name, check_positive(name, v, strict=False))
        # the nondimensional set must be representable and lie in the physical domain
        with np.errstate(all="ignore"):
            try:
                nd: dict[str, Any] = {"q": self.q, "sigma": self.sigma, "mu": self.mu}
            except (OverflowError, ZeroDivisionError):
                nd = {"q": math.nan}
        if not all(math.isfinite(v) for v in nd.values()):
            raise DomainError(f"the nondimensional parameters of this top are not finite numbers "
                              f"(mass = {self.mass:g} kg, radius = {self.radius:g} m, com_offset = "
                              f"{self.com_offset:g} m, inertias {self.inertia_transverse:g}, "
                              f"{self.inertia_axial:g} kg m^2); give SI values of a real top")
        check_domain(**nd)

    # -- spin-independent nondimensional parameters (eq. 3) --------------------------------
    @property
    def inertia_centre(self) -> float:
        """Transverse moment about the sphere centre O, ``A0 = A_G + M d^2`` (kg m^2)."""
        return self.inertia_transverse + self.mass * self.com_offset**2

    @property
    def q(self) -> float:
        """Centre-of-mass offset ``d / R``."""
        return self.com_offset / self.radius

    @property
    def mu(self) -> float:
        """Scaled mass ``M R^2 / A0`` (eq. 3)."""
        return self.mass * self.radius**2 / self.inertia_centre

    @property
    def sigma(self) -> float:
        """Inertia ratio ``C / A0`` (eq. 3)."""
        return self.inertia_axial / self.inertia_centre

    # -- spin-dependent ones ---------------------------------------------------------------
    def fr_inv(self, spin: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Inverse Froude number ``g / (Omega^2 R)`` at spin rate ``spin`` (in ``unit``)."""
        w = _spin(spin, unit)
        out = self.g / (w**2 * self.radius)
        return float(out) if out.ndim == 0 else out

    def spin_rate(self, fr_inv: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Spin rate (in ``unit``) at which the inverse Froude number is ``fr_inv`` (> 0)."""
        f = as_parameter("fr_inv", fr_inv)
        if np.any(f <= 0):
            raise DomainError(f"fr_inv = {float(np.min(f)):.6g} is outside the allowed range: fr_inv > 0 "
                             "(fr_inv = 0 is an infinite spin)")
        out = np.sqrt(self.g / (f * self.radius)) / _unit(unit)
        return float(out) if out.ndim == 0 else out

    def alpha_v(self, spin: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Viscous friction parameter ``mu mu_v g / Omega`` (eq. 7); needs ``mu_v``."""
        if self.mu_v is None:
            raise ValueError("mu_v is not set on this Top; give mu_v (s/m) to compute alpha_v")
        w = _spin(spin, unit)
        out = self.mu * self.mu_v * self.g / w
        return float(out) if out.ndim == 0 else out

    def alpha_k(self, spin: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Coulomb friction parameter ``mu fr_inv mu_K`` (eq. 7); needs ``mu_k``."""
        if self.mu_k is None:
            raise ValueError("mu_k is not set on this Top; give mu_k to compute alpha_k")
        return self.mu * self.fr_inv(spin, unit) * self.mu_k

    def nondimensional(self, spin: Any, unit: str = "rad/s", *, alpha_v: Any = None,
                       model: Any = None) -> dict[str, Any]:
        """The nondimensional parameters at a spin rate: q, fr_inv, sigma, mu (+ alpha_v, alpha_k).

        Parameters
        ----------
        spin : float or array
            Spin rate, in ``unit``.
        unit : {"rad/s", "rpm", "rev/s", "Hz"}
            Unit of ``spin``.
        alpha_v : float, optional
            The viscous parameter (eq. 7) to use when the top has no ``mu_v``; with ``mu_v`` set
            it is computed from the spin (``mu mu_v g / Omega``) and giving it too is an error.
            The threshold of the sliding model does not depend on ``alpha_v > 0`` but its
            eigenvalues do, hence no silent default.
        model : str or LinearModel, optional
            Return exactly the parameters of this model (e.g. no ``alpha_v`` for
            ``"rolling"``); a model that needs ``alpha_v`` when neither ``mu_v`` nor
            ``alpha_v`` is given is a ``TypeError`` naming both ways.

        Returns
        -------
        dict
            ``q, fr_inv, sigma, mu``, plus ``alpha_v`` (from ``mu_v`` or the argument) and
            ``alpha_k`` (when ``mu_k`` is set), so that
            ``eigenvalues("sliding", **top.nondimensional(w, alpha_v=0.5))`` works.
        """
        out: dict[str, Any] = {"q": self.q, "fr_inv": self.fr_inv(spin, unit),
                               "sigma": self.sigma, "mu": self.mu}
        if self.mu_v is not None:
            if alpha_v is not None:
                raise TypeError(f"alpha_v = {alpha_v!r} conflicts with this Top's mu_v = {self.mu_v:g} "
                                "s/m, from which alpha_v follows (eq. 7); give one of them")
            out["alpha_v"] = self.alpha_v(spin, unit)
        elif alpha_v is not None:
            a = as_parameter("alpha_v", alpha_v)
            if np.any(a < 0):
                raise DomainError(f"alpha_v = {alpha_v!r} is outside the physical domain: alpha_v >= 0")
            out["alpha_v"] = float(a) if np.ndim(a) == 0 else a
        if self.mu_k is not None:
            out["alpha_k"] = self.alpha_k(spin, unit)
        if model is not None:
            from .models import get_model

            m = get_model(model)
            if "alpha_v" in m.parameters and "alpha_v" not in out:
                raise TypeError(f"the {m.name} model needs alpha_v, and this Top has no mu_v: pass "
                                "alpha_v=... or build the Top with mu_v=... (s/m)")
            out = {k: v for k, v in out.items() if k in m.parameters}
        return out

    def inverted(self) -> "Top":
        """The same top standing on its stick: the offset of G reversed (q -> -q)."""
        return replace(self, com_offset=-self.com_offset)

    @classmethod
    def from_nondimensional(cls, *, mass: float, radius: float, q: float, mu: float, sigma: float,
                            **kwargs: Any) -> "Top":
        """Build a top from its mass and radius and the nondimensional q, mu, sigma (eq. 3)."""
        mass, radius = check_positive("mass", mass), check_positive("radius", radius)
        p, _ = check_domain(scalar=True, q=q, sigma=sigma, mu=mu)
        q, sigma, mu = (float(p[k]) for k in ("q", "sigma", "mu"))
        with np.errstate(all="ignore"):
            m_, r_ = np.float64(mass), np.float64(radius)
            a0 = m_ * r_**2 / mu
            d = q * r_
            a_g = a0 - m_ * d**2
        return cls(mass=mass, radius=radius, com_offset=float(d), inertia_transverse=float(a_g),
                   inertia_axial=float(sigma * a0), **kwargs)

    @classmethod
    def table1(cls, **kwargs: Any) -> "Top":
        """The paper's toy top as its simulations use it: q = -0.1, mu = 2.28, sigma = 1.

        Mass 0.64 oz, radius 0.6366 in (Sec. 3(ii)); see the module docstring for why the
        inertias are derived from the nondimensional set rather than read off Table 1.
        """
        return cls.from_nondimensional(mass=0.64 * OUNCE, radius=0.6366 * INCH,
                                       q=-0.1, mu=2.28, sigma=1.0, **kwargs)

    @classmethod
    def table1_measured(cls, **kwargs: Any) -> "Top":
        """Table 1's measured entries taken literally (gives mu ~ 3.7, not the listed 2.28)."""
        r = 0.63 * INCH
        return cls(mass=0.64 * OUNCE, radius=r, com_offset=-0.094 * r,
                   inertia_transverse=0.066 * OUNCE * INCH**2,
                   inertia_axial=0.066 * OUNCE * INCH**2, **kwargs)
