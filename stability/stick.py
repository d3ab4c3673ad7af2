"""The stick of a real Tippe top: where it touches the floor, and the top standing on it.

A real toy is a sphere of radius ``R`` truncated by a plane at distance ``t`` from its centre
O (on the stick's side), with a stick along the symmetry axis ``k`` ending in a small sphere
(the tip) of radius ``rho`` centred at distance ``s`` from O. Lengths in metres; ``k`` points
from O along the stick; the tilt ``theta`` is the polar angle of ``k`` from the upward vertical
``K`` (0: stick up, 180 degrees: stick down), as in :func:`stability.simulate`.

Derivation (closed form). With the big sphere on the floor, O is at height ``R``, and a point at
``a`` along ``k`` and ``b`` across it is at height ``R + a cos(theta) - b sin(theta)`` at its
lowest (``0 <= theta <= pi``).

* The tip's lowest point is at height ``R + s cos(theta) - rho``: it reaches the floor at
  ``cos(theta_tip) = -(R - rho) / s``, which exists (a tilt below 180 degrees) only if
  ``s > R - rho``.
* The truncation's rim, a circle of radius ``sqrt(R^2 - t^2)`` at ``a = t``, has its lowest point
  at ``R + t cos(theta) - sqrt(R^2 - t^2) sin(theta)``; with ``cos(theta) = -t / R`` and
  ``sin(theta) = sqrt(R^2 - t^2) / R`` this is ``R - t^2 / R - (R^2 - t^2) / R = 0``; indeed the
  height is ``R (1 - cos(theta - theta_rim))`` with ``theta_rim = arccos(-t / R)``, positive on
  either side: the rim touches the floor tangentially there. (It is also the tilt at which the big sphere's
  contact point, at ``a = -R cos(theta)``, reaches the cut: the sphere model ends there in any
  case.)

The stick touches at the smaller of the two tilts (``"tip"`` or ``"rim"``); the shaft between
the cut and the tip is taken thinner than the tip (it cannot touch first).

On its stick (the tip on the floor, the stick down) the top is again a sphere on a plane: the
tip, radius ``rho``, with the centre of mass G at ``s - d`` from the tip's centre, away from the
stick (``d`` the signed ``com_offset`` of :class:`stability.Top`, along ``k``). Its symmetry axis
is ``k' = -k`` (from the tip towards G), so that ``q' = (s - d) / rho > 0`` and its "upright"
state ``k' = K`` is the top spinning on its stick with G above the tip. ``A_G`` and ``C`` are
unchanged; ``A0' = A_G + M (s - d)^2``, ``mu' = M rho^2 / A0'`` is small and
``1 - mu' q'^2 = A_G / A0' > 0``: the models' domain admits it however large ``q'`` is.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import DomainError
from .parameters import as_scalar, check_positive

__all__ = ["STICK_PARTS", "Stick"]

#: the part of the stick that touches the floor first
STICK_PARTS = ("tip", "rim")


@dataclass(frozen=True)
class Stick:
    """The stick of a real top (metres, from the sphere's centre O, on the stick's side).

    Parameters
    ----------
    tip_center : float
        Distance from O to the centre of the tip's small sphere (> 0).
    tip_radius : float
        Radius of the tip (> 0).
    truncation : float
        Signed distance from O to the truncation plane (on the stick's side positive).

    Notes
    -----
    Whether the stick fits its sphere is checked against the sphere's radius
    (:meth:`check_fits`, called by :class:`stability.Top`).
    """

    tip_center: float
    tip_radius: float
    truncation: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "tip_center", check_positive("tip_center", self.tip_center))
        object.__setattr__(self, "tip_radius", check_positive("tip_radius", self.tip_radius))
        object.__setattr__(self, "truncation", as_scalar("truncation", self.truncation))

    def check_fits(self, radius: float) -> None:
        """Refuse a stick that does not fit a sphere of radius ``radius`` (m).

        Raises
        ------
        stability.errors.DomainError
            A tip not smaller than the sphere (``tip_radius < radius``), a truncation plane
            outside the sphere (``-radius < truncation < radius``), or a tip not wholly beyond
            the truncation plane (``tip_center - tip_radius > truncation``: the stick would not
            come out of the body).
        """
        if not self.tip_radius < radius:
            raise DomainError(
                f"tip_radius = {self.tip_radius:.6g} m is outside the allowed range: "
                f"tip_radius < radius = {radius:.6g} m (the tip is smaller than the sphere)"
            )
        if not -radius < self.truncation < radius:
            raise DomainError(
                f"truncation = {self.truncation:.6g} m is outside the allowed range: "
                f"-radius < truncation < radius = {radius:.6g} m (the plane cuts the sphere)"
            )
        if not self.tip_center - self.tip_radius > self.truncation:
            raise DomainError(
                f"tip_center = {self.tip_center:.6g} m is outside the allowed range: "
                f"tip_center > truncation + tip_radius = {self.truncation + self.tip_radius:.6g} m "
                "(the tip lies wholly beyond the truncation plane: the stick fits the sphere)"
            )

    def contact_tilts(self, radius: float) -> tuple[float, float]:
        """``(theta_tip, theta_rim)`` in degrees (module docstring); ``theta_tip`` is NaN when the
        tip cannot reach the floor (``tip_center <= radius - tip_radius``)."""
        self.check_fits(radius)
        c = -(radius - self.tip_radius) / self.tip_center
        tip = math.degrees(math.acos(c)) if c >= -1.0 else math.nan
        return tip, math.degrees(math.acos(-self.truncation / radius))

    def contact(self, radius: float) -> tuple[float, str]:
        """The tilt (degrees) at which the stick first touches the floor, and which part:
        ``"tip"`` or ``"rim"`` (the smaller of :meth:`contact_tilts`; the tip on a tie)."""
        tip, rim = self.contact_tilts(radius)
        return (tip, "tip") if tip <= rim else (rim, "rim")
