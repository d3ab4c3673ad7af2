"""The steady states' contact margin: how large a perturbation loses the contact (issue 19).

A steady state keeps its centre of mass at a constant height, so its normal force is the
equilibrium one, ``N = mu fr_inv`` (units ``A0 Omega^2 / R``; ``M g`` in SI), always positive. A
perturbed state's is not: the run from ``y* + eps d`` (``d`` the least stable mode, below)
has a smallest normal force ``N_min(eps)`` over ``duration`` time units
(:func:`stability.nonlinear.min_force.min_normal_force`), and the contact is lost from the
size ``eps*`` where ``N_min(eps*) = 0`` (Brent's method on ``eps``).

The direction. In the frame precessing with the state, ``A = Df(y*) - lam G``
(:func:`stability.steady.linearisation.precessing_jacobians`); its least stable mode is the
eigenvalue ``s`` of largest real part (``mode="least_stable"``; or the largest ``|Im s|``,
``mode="nutation"``, the fast mode that moves ``N`` most) among those off the structural zeros (``|s| > 1e-6
||A||``: a mode with ``s != 0`` lies in ``ker l1 ∩ ker l2`` by itself, ``l A = 0`` giving
``s l v = 0``), eigenvector ``v``; ``d = Re(v) / |Re(v)_k|`` (or the imaginary part, if its
``k`` part is larger): a perturbation of size ``eps`` turns the axis by ``eps`` radians to first
order (the size is reported in degrees).

The linearised change (closed form). ``N`` is a function of the state alone,
``N(y) = mu fr_inv + mu q (f_omega(y) x k + omega x (omega x k))_3`` (the vertical component of
eq. 1, :func:`stability.nonlinear.integrators.normal_force_of`), invariant under rotations
about ``K``; so in the precessing frame, where the perturbation evolves as
``eps Re(d_c e^{s t})`` (``d_c = v / |Re(v)_k|``), the first-order change is

    delta N(t) = eps Re(c e^{s t}),   c = grad N(y*) . d_c,

and contact is lost, to first order, from ``eps_lin = mu fr_inv / max over [0, T] of
(-Re(c e^{s t}))``. At a vertical state ``grad N = 0`` (``k = +-K``, ``f(y*) = 0``: every term of
``N - mu fr_inv`` is of second order in the tilt), so ``delta N`` is of second order there and
``eps_lin`` is infinite: only the runs answer. ``grad N`` by central differences of the model's
contact force (``h = 1e-6``, error ``~1e-10``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import DomainError
from ..nonlinear import get_nonlinear_model
from ..nonlinear.integrators import check_tolerances
from ..nonlinear.min_force import min_normal_force
from ..parameters import DEFAULT_MU, as_scalar, check_choice, check_interval, check_positive
from . import family
from .linearisation import precessing_jacobians
from .products import sliding_parameters

__all__ = ["MODES", "ContactMargin", "contact_margin"]

#: the perturbation directions of :func:`contact_margin`
MODES = ("least_stable", "nutation")


@dataclass(frozen=True)
class ContactMargin:
    """The contact margin of a steady state (:func:`contact_margin`).

    Attributes
    ----------
    size : float or None
        Perturbation (degrees of the axis, along ``direction``) from which the run's smallest
        normal force over ``duration`` is below zero; None if not within ``max_size``.
    linear_size : float
        The first-order estimate ``eps_lin`` (degrees; inf where ``delta N`` is of second order).
    eigenvalue : complex
        The least stable mode's ``s``.
    direction : numpy.ndarray, shape (8,)
        ``d`` (module docstring), ``(omega, k, V0_h)``.
    normal_force : float
        The steady state's ``mu fr_inv``.
    duration : float
        Time units of the runs.
    """

    size: float | None
    linear_size: float
    eigenvalue: complex
    direction: np.ndarray
    normal_force: float
    duration: float


#: sizes scanned in ``(0, max_size]`` before Brent's method refines the first sign change
SCAN_SIZES = 8


def contact_margin(
    *,
    tilt: float,
    q: Any,
    sigma: Any,
    fr_inv: Any,
    alpha_v: Any,
    mu: Any = DEFAULT_MU,
    spin: float = 1.0,
    duration: float = 100.0,
    max_size: float = 30.0,
    rtol: float = 1e-10,
    mode: str = "least_stable",
) -> ContactMargin:
    """The perturbation size at which a steady state's perturbed run loses its contact.

    Parameters
    ----------
    tilt : float
        The steady state's tilt, degrees: 0 or 180 the vertical states (spinning at ``spin``,
        ``omega = spin K``), otherwise the tilted state at that tilt (``lam > 0``, (S3)).
    q, sigma, fr_inv, alpha_v, mu : float
        The sliding model's parameters (``fr_inv > 0``).
    spin : float, default 1.0
        The vertical states' spin (units of ``Omega``).
    duration : float, default 100.0
        Time units of each run over which the smallest normal force is taken.
    max_size : float, default 30.0
        Largest perturbation tried, degrees: :data:`SCAN_SIZES` equal steps up to it, the first
        step whose run loses the contact refined by Brent's method (the smallest such size, to
        the scan's resolution: ``N_min`` need not fall monotonically with the size).
    rtol : float
        Integrator tolerance of the runs.
    mode : {"least_stable", "nutation"}
        The direction: the least stable mode (largest ``Re s``), or the fastest one (largest
        ``|Im s|``, the nutation), which moves ``N`` most.

    Returns
    -------
    ContactMargin

    Raises
    ------
    stability.errors.DomainError
        A tilt outside ``[0, 180]``, a tilted state that does not exist at these parameters
        (``q P(c) <= 0``), ``fr_inv = 0`` (no weight: ``N = 0`` at equilibrium), a ``spin``
        not finite, ``rtol`` outside ``(0, 1)``.
    stability.errors.ParameterTypeError
        A ``tilt``, ``spin`` or ``rtol`` that is not a real number.
    """
    from scipy.optimize import brentq

    params, p = sliding_parameters("sliding", q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=alpha_v, mu=mu)
    if not params["fr_inv"] > 0:
        raise DomainError("fr_inv = 0 is outside the allowed range of contact_margin: fr_inv > 0 (N = 0 at rest)")
    tilt = check_interval("tilt", tilt, 0.0, 180.0, closed="both")
    spin = as_scalar("spin", spin)
    (rtol,) = check_tolerances(rtol=rtol)
    duration = check_positive("duration", duration)
    check_choice("mode", mode, MODES)
    max_size = check_positive("max_size", max_size)
    q, sg, fr, mu_ = (params[k] for k in ("q", "sigma", "fr_inv", "mu"))
    if tilt in (0.0, 180.0):
        y = family.vertical_state("upright" if tilt == 0.0 else "inverted", float(spin))
        lam = 0.0
    else:
        th = math.radians(tilt)
        lam = float(family.precession_rate(math.cos(th), q=q, sigma=sg, fr_inv=fr, mu=mu_))
        if not math.isfinite(lam):
            raise DomainError(
                f"tilt = {tilt:g} degrees: no tilted steady state at this tilt for q = {q:g}, sigma = {sg:g}, "
                f"fr_inv = {fr:g}, mu = {mu_:g} (q P(cos tilt) <= 0, (S3))"
            )
        y = family.state_vector(th, lam, q)
    a = precessing_jacobians(y[None, :], np.array([lam]), p)[0]
    s_all, v_all = np.linalg.eig(a)
    off = np.abs(s_all) > 1e-6 * np.linalg.norm(a)
    key = s_all.real if mode == "least_stable" else np.abs(s_all.imag)
    j = int(np.argmax(np.where(off, key, -np.inf)))
    s, v = complex(s_all[j]), v_all[:, j]
    re, im = v.real, v.imag
    part = re if np.linalg.norm(re[3:6]) >= np.linalg.norm(im[3:6]) else im
    scale = float(np.linalg.norm(part[3:6]))
    d = part / scale
    d_c = v / scale if part is re else -1j * v / scale  # Re(d_c) = d
    model = get_nonlinear_model("sliding")
    n0 = mu_ * fr

    def force(z: np.ndarray) -> float:
        return float(model.contact_forces(np.ascontiguousarray(z[None, :]), p)[0, 2])

    h = 1e-6
    grad = np.array([(force(y + h * e) - force(y - h * e)) / (2 * h) for e in np.eye(8)])
    c = complex(grad @ d_c)
    ts = np.linspace(0.0, duration, 4001)
    dip = float(np.max(-(c * np.exp(s * ts)).real))
    linear = math.degrees(n0 / dip) if dip > 1e-9 * n0 else math.inf

    def n_min(size_deg: float) -> float:
        z = y + math.radians(size_deg) * d
        z[3:6] /= np.linalg.norm(z[3:6])
        return min_normal_force("sliding", np.concatenate([z, [0.0, 0.0]]), p, duration, rtol=rtol)[0]

    # N_min(eps) need not be monotone: the first sign change on a scan of SCAN_SIZES sizes
    # brackets the smallest size (a loss between two scanned sizes that is regained before the
    # next one is not seen)
    size, below = None, 0.0
    for above in np.linspace(0.0, max_size, SCAN_SIZES + 1)[1:]:
        if n_min(float(above)) < 0.0:
            size = float(brentq(n_min, below, float(above), xtol=1e-9, rtol=1e-10))
            break
        below = float(above)
    return ContactMargin(size, linear, s, d, n0, duration)
