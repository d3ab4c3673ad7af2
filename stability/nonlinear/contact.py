"""Where the contact model holds: the first time the normal force reaches zero.

The sliding and rolling models keep the sphere's centre O at height R (``V0 . K = 0``); the
normal force ``N`` is whatever the vertical component of eq. (1) needs for that,

    N = mu fr_inv + mu q (omega' x k + omega x (omega x k)) . K,

and nothing in the equations stops it from becoming negative: the floor would then pull the
top down. A real top leaves the floor there (Shimomura, Branicki and Moffatt 2005). So every
run of a model with a contact point ends at the first zero of ``N(t)`` (the event
``"contact_lost"``), located to integrator tolerance:

1. ``N`` is evaluated at the run's output samples (the models' ``contact_forces``, the same
   6 x 6 solve as the right-hand side, so the same ``N``);
2. if a sample has ``N <= 0``, the interval from the sample before it is integrated again by
   scipy's DOP853 (with the run's tolerances and the compiled right-hand side) with ``N(y)`` as a
   terminal event: scipy finds the root of ``N`` on its dense output (Brent's method to round-off
   in time), so the event time carries the integrator's error only.

Limitation (stated, not hidden): a dip of ``N`` below zero that starts and ends between two
output samples is not seen; the output interval ``dt`` bounds the duration of a missed dip.

A flight phase after the loss of contact (``on_contact_loss="continue"``) is not built: the run
refuses it (:func:`check_on_contact_loss`), naming what is missing.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import InputError
from . import get_nonlinear_model
from .kernels import CODES, rhs as _model_rhs

__all__ = ["EVENTS", "ON_CONTACT_LOSS", "ContactEvent", "first_contact_loss", "check_on_contact_loss"]

#: the values of a run's attribute ``event``
EVENTS = ("none", "contact_lost", "stick_contact")
#: the choices of ``simulate(on_contact_loss=...)``
ON_CONTACT_LOSS = ("stop", "continue")


class ContactEvent:
    """The first zero of the normal force: index of the first sample at or past it, time and state.

    Attributes
    ----------
    index : int
        The first output sample with ``N <= 0``.
    time : float
        The located zero of ``N(t)``.
    state : numpy.ndarray
        The state there.
    """

    __slots__ = ("index", "time", "state")

    def __init__(self, index: int, time: float, state: np.ndarray) -> None:
        self.index, self.time, self.state = index, time, state


def check_on_contact_loss(value: str) -> str:
    """Check ``on_contact_loss``; ``"continue"`` is refused (the flight phase is not built).

    Raises
    ------
    stability.errors.InputError
        An unknown value, or ``"continue"``.
    """
    if value not in ON_CONTACT_LOSS:
        raise InputError(f"on_contact_loss = {value!r} is not known; choose one of "
                         f"{', '.join(map(repr, ON_CONTACT_LOSS))}")
    if value == "continue":
        raise InputError("on_contact_loss = 'continue' is not available: it needs a flight phase "
                         "(free fall of the rigid body with its spin, the height of O as a new state) "
                         "and a landing impact law (e.g. Newton's restitution at the contact point), "
                         "neither of which is built yet; use on_contact_loss = 'stop' (the default), "
                         "which ends the run where the normal force reaches zero")
    return value


def normal_force(model: str, y: np.ndarray, p: np.ndarray) -> np.ndarray:
    """``N`` at each row of ``y`` (the model's ``contact_forces``); NaN on non-finite rows."""
    m = get_nonlinear_model(model)
    y = np.ascontiguousarray(np.atleast_2d(y), dtype=np.float64)
    out = np.full(y.shape[0], np.nan)
    good = np.isfinite(y).all(axis=1)
    if good.any():
        out[good] = m.contact_forces(np.ascontiguousarray(y[good]), p)[:, 2]
    return out


def first_contact_loss(model: str, t: np.ndarray, y: np.ndarray, p: np.ndarray, *, rtol: float,
                       atol: float, n_samples: np.ndarray | None = None) -> ContactEvent | None:
    """The first zero of the normal force along a run, or None if ``N > 0`` at every sample.

    Parameters
    ----------
    model : str
        A model with a contact point (sliding or rolling).
    t, y : numpy.ndarray
        The run's output times and states.
    p : numpy.ndarray
        Parameter vector.
    rtol, atol : float
        Tolerances of the refinement (the run's).
    n_samples : numpy.ndarray, optional
        ``N`` at the samples, if already computed.
    """
    big_n = normal_force(model, y, p) if n_samples is None else n_samples
    hit = np.flatnonzero(big_n <= 0.0)
    if hit.size == 0:
        return None
    j = int(hit[0])
    if j == 0:
        return ContactEvent(0, float(t[0]), np.array(y[0], dtype=float))
    code = CODES[model]
    m = get_nonlinear_model(model)

    def f(_t: float, s: np.ndarray) -> np.ndarray:
        return _model_rhs(code, _t, s, p)

    def event(_t: float, s: np.ndarray) -> float:
        return float(m.contact_forces(np.ascontiguousarray(s[None, :]), p)[0, 2])

    event.terminal = True  # type: ignore[attr-defined]
    event.direction = -1  # type: ignore[attr-defined]
    sol = solve_ivp(f, (float(t[j - 1]), float(t[j])), np.array(y[j - 1], dtype=float), method="DOP853",
                    rtol=rtol, atol=atol, events=event)
    if sol.t_events[0].size:
        return ContactEvent(j, float(sol.t_events[0][0]), np.array(sol.y_events[0][0], dtype=float))
    # the refinement kept N > 0 to its end (N of the sample within tolerance of 0): the sample
    return ContactEvent(j, float(t[j]), np.array(y[j], dtype=float))
