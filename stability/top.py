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
import warnings
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .errors import DomainError, InputError, ParameterTypeError
from .parameters import as_parameter, as_scalar, check_choice, check_domain, check_positive
from .stick import Stick

__all__ = [
    "INCH",
    "OUNCE",
    "PLAUSIBLE",
    "PRESETS",
    "SI_UNITS",
    "SPIN_UNITS",
    "ImplausibleTopWarning",
    "Top",
    "check_launch_spin",
    "from_rad_per_s",
    "spin_text",
    "to_rad_per_s",
]

#: avoirdupois ounce and inch in SI
OUNCE = 0.028349523125
INCH = 0.0254

#: the SI data of a top (the constructor's required fields, in order) and their units
SI_UNITS: dict[str, str] = dict(
    mass="kg", radius="m", com_offset="m", inertia_transverse="kg m^2", inertia_axial="kg m^2"
)

#: rad/s per unit of spin rate: the one table of spin units ("Hz" is rev/s)
SPIN_UNITS: dict[str, float] = {"rad/s": 1.0, "rpm": 2.0 * math.pi / 60.0, "rev/s": 2.0 * math.pi, "Hz": 2.0 * math.pi}

#: Plausible ranges of a real tippe top (docs/launch.md, "Plausible units"). Each row:
#: quantity -> (refuse below, warn below, warn above, refuse above). Real tippe tops have
#: R = 10-30 mm, M = 5-30 g, mu = M R^2 / A0 ~ 2-4, sigma = C / A0 ~ 0.6-1.4, |q| ~ 0.05-0.4;
#: the warning band is an order of magnitude wider than that, the refusal band three or more
#: (a unit slip g <-> kg is 1e3, mm <-> m 1e3, g mm^2 <-> kg m^2 1e9). Launch spins: a spin
#: below 0.1 rev/s or above 1e4 rev/s is refused (:func:`check_launch_spin`).
PLAUSIBLE: dict[str, tuple[float, float, float, float]] = {
    "mass": (1e-5, 1e-3, 1.0, 1e3),  # kg
    "radius": (1e-4, 2e-3, 0.2, 10.0),  # m
    "mu": (1e-2, 0.1, 100.0, 1e4),
    "sigma": (1e-3, 0.05, math.inf, math.inf),  # sigma <= 2 A_G / A0 < 2 (the domain)
    "abs_q": (0.0, 1e-3, math.inf, math.inf),  # q = 0 (G at O) is an idealisation, kept
}
#: launch spins, rev/s: refuse below, refuse above
LAUNCH_SPIN_REV_S: tuple[float, float] = (0.1, 1e4)

_CAUSES = {
    ("mass", "high"): "mass looks like grams: pass kilograms (15 g is 0.015)",
    ("mass", "low"): "mass looks like tonnes or a slipped exponent: pass kilograms",
    ("radius", "high"): "radius looks like millimetres: pass metres (15 mm is 0.015)",
    ("radius", "low"): "radius looks like kilometres or a slipped exponent: pass metres",
    ("mu", "low"): (
        "the inertias look too large for the mass and radius: pass kg m^2 (1 g mm^2 is 1e-9 kg m^2), "
        "the mass in kg and the radius in m"
    ),
    ("mu", "high"): (
        "the inertias look too small for the mass and radius: pass kg m^2, the mass in kg and the radius in m"
    ),
    ("sigma", "low"): (
        "the axial moment looks too small against the transverse one (or the offset of G too large): "
        "pass both moments in kg m^2 and com_offset in m"
    ),
    ("abs_q", "low"): "com_offset looks tiny against the radius: pass both in metres",
}


class ImplausibleTopWarning(UserWarning):
    """A top whose SI data or derived parameters lie outside the ranges of real tippe tops but
    within an order of magnitude or so of them (:data:`PLAUSIBLE`)."""


#: the named tops (classmethods of :class:`Top`)
PRESETS = ("table1", "table1_measured")


def _unit(unit: str) -> float:
    return SPIN_UNITS[check_choice("unit", unit, SPIN_UNITS)]


def to_rad_per_s(spin: Any, unit: str) -> Any:
    """A spin rate given in ``unit`` (:data:`SPIN_UNITS`) in rad/s."""
    return spin * _unit(unit)


def from_rad_per_s(spin: Any, unit: str) -> Any:
    """A spin rate in rad/s expressed in ``unit`` (:data:`SPIN_UNITS`)."""
    return spin / _unit(unit)


def spin_text(spin: float, unit: str, digits: int = 6) -> str:
    """A spin rate in rad/s as text in ``unit`` and, unless that is a frequency, in rev/s too:
    ``"600 rpm = 10 rev/s"`` (``digits`` significant digits)."""
    text = f"{from_rad_per_s(spin, unit):.{digits}g} {unit}"
    return text if unit in ("rev/s", "Hz") else f"{text} = {from_rad_per_s(spin, 'rev/s'):.{digits}g} rev/s"


def check_launch_spin(spin: Any, unit: str) -> float:
    """A launch spin (one number, in ``unit``) in rad/s; refused (:class:`DomainError`) outside
    0.1-1e4 rev/s (:data:`LAUNCH_SPIN_REV_S`), the message in the caller's unit and in rev/s."""
    factor = _unit(unit)
    w = as_scalar("spin", spin)
    lo, hi = LAUNCH_SPIN_REV_S
    rev = w * factor / (2.0 * math.pi)
    if not lo <= rev <= hi:
        raise DomainError(
            f"spin = {w:.6g} {unit} ({rev:.6g} rev/s) is outside the allowed range: "
            f"{lo:g} to {hi:g} rev/s ({lo * 2 * math.pi / factor:.6g} to {hi * 2 * math.pi / factor:.6g} "
            f"{unit}); is the unit right?"
        )
    return w * factor


def _positive(name: str, value: Any, shown: str = "", note: str = "") -> np.ndarray:
    """``value`` as a float array, each entry > 0 (the message gives the smallest as ``shown``, e.g.
    with the caller's unit, and a ``note``)."""
    v = as_parameter(name, value)
    if np.any(v <= 0):
        raise DomainError(f"{name} = {float(np.min(v)):.6g}{shown} is outside the allowed range: {name} > 0{note}")
    return v


def _spin(spin: Any, unit: str) -> np.ndarray:
    """Spin rates in rad/s, each > 0 (the message gives the value in the caller's unit; the unit
    checked first)."""
    return _unit(unit) * _positive("spin", spin, f" {unit}")


def _number(out: np.ndarray) -> np.ndarray | float:
    """A 0-d result as a float, an array as itself."""
    return float(out) if out.ndim == 0 else out


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
    stick : stability.Stick, optional
        The toy's stick and truncation (:mod:`stability.stick`): :meth:`stick_contact`,
        :meth:`on_stick`; refused if it does not fit the sphere.
    plausible : bool, default True
        Keyword only. Check the SI data against the ranges of real tippe tops
        (:data:`PLAUSIBLE`: refused far off, :class:`ImplausibleTopWarning` in the grey zone).
    """

    mass: float
    radius: float
    com_offset: float
    inertia_transverse: float
    inertia_axial: float
    g: float = 9.80665
    mu_k: float | None = None
    mu_v: float | None = None
    stick: Stick | None = None
    #: Check the SI data against real tippe tops (:data:`PLAUSIBLE`); False for a body that is
    #: deliberately not one, such as the stick's tip of :meth:`on_stick`.
    plausible: bool = field(default=True, repr=False, compare=False, kw_only=True)

    def __post_init__(self) -> None:
        for name in ("mass", "radius", "inertia_transverse", "inertia_axial", "g"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(self, "com_offset", as_scalar("com_offset", self.com_offset))
        for name in ("mu_k", "mu_v"):
            v = getattr(self, name)
            if v is not None:
                object.__setattr__(self, name, check_positive(name, v, strict=False))
        # the nondimensional set must be representable and lie in the physical domain (Python
        # floats, checked above: an overflow raises or gives inf, never a numpy warning)
        try:
            nd: dict[str, Any] = {"q": self.q, "sigma": self.sigma, "mu": self.mu}
        except (OverflowError, ZeroDivisionError):
            nd = {"q": math.nan}
        if not all(math.isfinite(v) for v in nd.values()):
            raise DomainError(
                f"the nondimensional parameters of this top are not finite numbers ({self._si_text()}); "
                "give SI values of a real top"
            )
        check_domain(**nd)
        if self.stick is not None:
            self.stick.check_fits(self.radius)
        if self.plausible:
            self._check_plausible()

    def _check_plausible(self) -> None:
        """Refuse a top orders of magnitude off real tippe tops, warn in the grey zone
        (:data:`PLAUSIBLE`), with the SI data, the derived values and the likely cause."""
        values = {"mass": self.mass, "radius": self.radius, "mu": self.mu, "sigma": self.sigma, "abs_q": abs(self.q)}
        refuse: list[str] = []
        warn: list[str] = []
        for name, (r_lo, w_lo, w_hi, r_hi) in PLAUSIBLE.items():
            v = values[name]
            side = "low" if v < w_lo else "high" if v > w_hi else None
            if side is not None and not (name == "abs_q" and v == 0.0):
                text = f"{'|q|' if name == 'abs_q' else name} = {v:.3g} ({_CAUSES[(name, side)]})"
                (refuse if (v < r_lo or v > r_hi) else warn).append(text)
        if not refuse and not warn:
            return
        data = f"{self._si_text()} give q = {self.q:.3g}, mu = {self.mu:.3g}, sigma = {self.sigma:.3g}"
        ranges = (
            "real tippe tops: mass 5-30 g, radius 10-30 mm, mu 2-4, sigma 0.6-1.4, |q| 0.05-0.4; SI units throughout"
        )
        if refuse:
            raise DomainError(
                f"this top is outside the plausible range of real tops: {'; '.join(refuse + warn)}. "
                f"The data: {data}; {ranges}"
            )
        warnings.warn(
            f"this top is unusual for a tippe top: {'; '.join(warn)}. The data: {data}; {ranges}",
            ImplausibleTopWarning,
            stacklevel=4,
        )

    def _si_text(self) -> str:
        """The top's SI data as a message shows them (``mass = 0.015 kg, radius = ...``)."""
        return ", ".join(f"{name} = {getattr(self, name):g} {unit}" for name, unit in SI_UNITS.items())

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
        return _number(self.g / (_spin(spin, unit) ** 2 * self.radius))

    def spin_rate(self, fr_inv: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Spin rate (in ``unit``) at which the inverse Froude number is ``fr_inv`` (> 0)."""
        f = _positive("fr_inv", fr_inv, note=" (fr_inv = 0 is an infinite spin)")
        return _number(np.sqrt(self.g / (f * self.radius)) / _unit(unit))

    def alpha_v(self, spin: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Viscous friction parameter ``mu mu_v g / Omega`` (eq. 7); needs ``mu_v``."""
        if self.mu_v is None:
            raise InputError("mu_v is not set on this Top; give mu_v (s/m) to compute alpha_v")
        return _number(self.mu * self.mu_v * self.g / _spin(spin, unit))

    def alpha_k(self, spin: Any, unit: str = "rad/s") -> np.ndarray | float:
        """Coulomb friction parameter ``mu fr_inv mu_K`` (eq. 7); needs ``mu_k``."""
        if self.mu_k is None:
            raise InputError("mu_k is not set on this Top; give mu_k to compute alpha_k")
        return self.mu * self.fr_inv(spin, unit) * self.mu_k

    def nondimensional(
        self, spin: Any, unit: str = "rad/s", *, alpha_v: Any = None, model: Any = None
    ) -> dict[str, Any]:
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
        out: dict[str, Any] = {"q": self.q, "fr_inv": self.fr_inv(spin, unit), "sigma": self.sigma, "mu": self.mu}
        if self.mu_v is not None:
            if alpha_v is not None:
                raise ParameterTypeError(
                    f"alpha_v = {alpha_v!r} conflicts with this Top's mu_v = {self.mu_v:g} "
                    "s/m, from which alpha_v follows (eq. 7); give one of them"
                )
            out["alpha_v"] = self.alpha_v(spin, unit)
        elif alpha_v is not None:
            out["alpha_v"] = _number(check_domain(maskable=False, alpha_v=alpha_v)[0]["alpha_v"])
        if self.mu_k is not None:
            out["alpha_k"] = self.alpha_k(spin, unit)
        if model is not None:
            from .models import get_model

            m = get_model(model)
            if "alpha_v" in m.parameters and "alpha_v" not in out:
                raise ParameterTypeError(
                    f"the {m.name} model needs alpha_v, and this Top has no mu_v: pass "
                    "alpha_v=... or build the Top with mu_v=... (s/m)"
                )
            out = {k: v for k, v in out.items() if k in m.parameters}
        return out

    def inverted(self) -> Top:
        """The same top standing on its stick: the offset of G reversed (q -> -q)."""
        return replace(self, com_offset=-self.com_offset)

    @classmethod
    def from_nondimensional(
        cls, *, mass: float, radius: float, q: float, mu: float, sigma: float, **kwargs: Any
    ) -> Top:
        """Build a top from its mass and radius and the nondimensional q, mu, sigma (eq. 3)."""
        mass, radius = check_positive("mass", mass), check_positive("radius", radius)
        p, _ = check_domain(scalar=True, q=q, sigma=sigma, mu=mu)
        q, sigma, mu = (float(p[k]) for k in ("q", "sigma", "mu"))
        with np.errstate(all="ignore"):
            m_, r_ = np.float64(mass), np.float64(radius)
            a0 = m_ * r_**2 / mu
            d = q * r_
            a_g = a0 - m_ * d**2
        return cls(mass, radius, float(d), float(a_g), float(sigma * a0), **kwargs)  # com_offset, A_G, C

    @classmethod
    def from_mapping(cls, data: Any, *, source: str = "top") -> Top:
        """A top from a mapping of SI values (a TOML ``[top]`` table, a dict).

        Keys: the constructor's (``mass``, ``radius``, ``com_offset``, ``inertia_transverse``,
        ``inertia_axial``, optional ``g``, ``mu_k``, ``mu_v``), or ``preset = "table1"`` /
        ``"table1_measured"`` alone with only the optional keys beside it.

        Parameters
        ----------
        data : mapping
            The table.
        source : str
            What the table is called in messages (a file name and table, e.g. ``"top.toml [top]"``).

        Raises
        ------
        InputError
            An unknown or missing key, a non-number, or a preset with SI data beside it.
        """
        from collections.abc import Mapping

        if not isinstance(data, Mapping):
            raise InputError(f"{source} must be a table of SI values, not {type(data).__name__}")
        required = tuple(SI_UNITS)
        optional = ("g", "mu_k", "mu_v")
        unknown = sorted(set(data) - {*required, *optional, "preset"})
        if unknown:
            raise InputError(
                f"{source}: unknown keys {', '.join(unknown)} (allowed: preset, {', '.join(required + optional)})"
            )
        for k, v in data.items():
            if k != "preset" and (isinstance(v, bool) or not isinstance(v, (int, float))):
                raise InputError(f"{source}: {k} = {v!r} is not a number (SI units)")
        extra = {k: float(data[k]) for k in optional if k in data}
        if "preset" in data:
            preset = data["preset"]
            if preset not in PRESETS:
                raise InputError(f"{source}: preset = {preset!r} is not one of {', '.join(PRESETS)}")
            clash = [k for k in required if k in data]
            if clash:
                raise InputError(
                    f"{source}: preset = {preset!r} and {', '.join(clash)} conflict: give a "
                    "preset or the top's SI data, not both"
                )
            return getattr(cls, preset)(**extra)  # type: ignore[no-any-return]
        missing = [k for k in required if k not in data]
        if missing:
            raise InputError(
                f"{source}: missing {', '.join(missing)} (SI units), or give preset = "
                f"{' or '.join(repr(p) for p in PRESETS)}"
            )
        return cls(**{k: float(data[k]) for k in required}, **extra)  # type: ignore[arg-type]

    @classmethod
    def from_toml(cls, path: Any) -> Top:
        """A top from the ``[top]`` table of a TOML file (keys of :meth:`from_mapping`).

        Raises
        ------
        InputError
            A file that is not valid TOML or has no ``[top]`` table, and every error of
            :meth:`from_mapping`.
        OSError
            The file cannot be read.
        """
        import tomllib
        from pathlib import Path

        p = Path(path)
        try:
            raw = tomllib.loads(p.read_bytes().decode())
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            raise InputError(f"{p}: not valid TOML ({exc})") from None
        if "top" not in raw:
            raise InputError(
                f"{p}: no [top] table (give mass, radius, com_offset, inertia_transverse, "
                "inertia_axial in SI units under [top])"
            )
        return cls.from_mapping(raw["top"], source=f"{p} [top]")

    @classmethod
    def table1(cls, **kwargs: Any) -> Top:
        """The paper's toy top as its simulations use it: q = -0.1, mu = 2.28, sigma = 1.

        Mass 0.64 oz, radius 0.6366 in (Sec. 3(ii)); see the module docstring for why the
        inertias are derived from the nondimensional set rather than read off Table 1.
        """
        return cls.from_nondimensional(mass=0.64 * OUNCE, radius=0.6366 * INCH, q=-0.1, mu=2.28, sigma=1.0, **kwargs)

    @classmethod
    def table1_measured(cls, **kwargs: Any) -> Top:
        """Table 1's measured entries taken literally (gives mu ~ 3.7, not the listed 2.28)."""
        r, moment = 0.63 * INCH, 0.066 * OUNCE * INCH**2
        return cls(0.64 * OUNCE, r, -0.094 * r, moment, moment, **kwargs)  # mass, radius, com_offset, A_G, C

    def stick_contact(self) -> tuple[float, str]:
        """The tilt (degrees) at which the stick first touches the floor, and the part that
        touches, ``"tip"`` or ``"rim"`` (closed form: :mod:`stability.stick`).

        Raises
        ------
        stability.errors.InputError
            The top has no stick.
        """
        return self._stick().contact(self.radius)

    def on_stick(self) -> Top:
        """The top standing on its stick's tip: a sphere of radius ``tip_radius`` with G at
        ``tip_center - com_offset`` from its centre, away from the stick (``q = (tip_center -
        com_offset) / tip_radius > 0``; its "upright" state spins on the stick with G above the
        tip; :mod:`stability.stick`). Same mass, moments about G, gravity and friction; no stick."""
        st = self._stick()
        return replace(
            self, radius=st.tip_radius, com_offset=st.tip_center - self.com_offset, stick=None, plausible=False
        )

    def _stick(self) -> Stick:
        if self.stick is None:
            raise InputError(
                "this Top has no stick; build it with stick=stability.Stick(tip_center, "
                "tip_radius, truncation) (metres)"
            )
        return self.stick
