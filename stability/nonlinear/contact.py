"""Where the contact model holds: the first time the normal force reaches zero.

The sliding and rolling models keep the sphere's centre O at height R (``V0 . K = 0``); the
normal force ``N`` is whatever the vertical component of eq. (1) needs for that,

    N = mu fr_inv + mu q (omega' x k + omega x (omega x k)) . K,

and nothing in the equations stops it from becoming negative: the floor would then pull the
top down. A real top leaves the floor there (Shimomura, Branicki and Moffatt 2005). So every
run of a model with a contact point ends at the first zero of ``N(t)`` (the event
``"contact_lost"``), located to integrator tolerance by the integrators themselves
(:mod:`stability.nonlinear.integrators`, ``watch_contact``):

1. after every accepted step, ``N`` at the step's end from the state and the derivative the
   integrator already holds (first same as last; :func:`~stability.nonlinear.integrators.normal_force_of`,
   the vertical component of eq. 1), no extra right-hand side;
2. at the first step that ends with ``N <= 0``, the zero is located on the step's interpolant
   (dopri5's dense output, rk4's Hermite cubic, scipy's dense output) with ``N`` evaluated
   exactly at each interpolated state: Illinois regula falsi (compiled) or Brent's method
   (scipy), to round-off in time; the event time carries the integrator's error only.

A dip of ``N`` below zero that starts and ends within one step is not seen (the steps follow
the motion to the tolerance, so such a dip is shorter than a step).

``on_contact_loss="continue"`` goes on after the loss of contact with a free flight and a
plastic landing (:mod:`stability.nonlinear.flight`), then on the floor again.
"""

from __future__ import annotations

__all__ = ["ON_CONTACT_LOSS"]

#: the choices of ``simulate(on_contact_loss=...)``
ON_CONTACT_LOSS = ("stop", "continue")
