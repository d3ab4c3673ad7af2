"""Every steady state of the sliding top on one Jellett level, with its stability.

:func:`steady_states` answers: at a given Jellett integral ``J`` (conserved by every contact
force, so fixed by the initial state of a motion), which steady states exist, with what
tilt, precession, spin and energy, and which are stable. The upright and inverted spins exist
at every ``J``; the tilted ones are the roots of the quartic (S6), all found with their energy
test in one compiled call (:func:`stability.steady.family.level_states`). Their energies and
``J`` are evaluated on the state vectors with the nonlinear layer's own formulas
(:mod:`stability.nonlinear.quantities`, :func:`state_integrals`), their spectra by
:mod:`stability.steady.linearisation`, their flags by :mod:`stability.steady.verdicts`; the
dataset also carries the effective potential ``U_J`` of the level against the tilt, which its
figure draws. docs/steady_states.md has the derivation.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from stability.jit import njit, register_jitable

from ..execution import pick
from ..nonlinear.quantities import centre_velocity, energy_terms, jellett_integral
from ..parameters import DEFAULT_MU, as_scalar
from . import family
from .linearisation import state_modes
from .products import (
    UNITLESS,
    check_scales,
    potential_curve,
    product_attrs,
    sliding_parameters,
    state_variables,
    variable,
)
from .verdicts import flag_of

__all__ = ["level_spins", "point_integrals", "state_integrals", "state_values", "steady_states"]


@register_jitable
def _integrals_of(w0, w1, w2, k0, k1, k2, v0, v1, q, sigma, fr_inv, mu):
    """``J`` and ``E`` of one state ``(omega, k, V0_h)`` of the sliding model (``V0`` horizontal,
    ``z_G = 1 + q k_3``): the nonlinear layer's formulas."""
    g0, g1, g2 = centre_velocity(w0, w1, w2, k0, k1, k2, v0, v1, 0.0, q)
    energy = energy_terms(w0, w1, w2, k0, k1, k2, g0, g1, g2, 1.0 + q * k2, q, fr_inv, sigma, mu)[4]
    return jellett_integral(w0, w1, w2, k0, k1, k2, q, sigma, mu), energy


@njit(cache=True)
def _integrals(y, q, sigma, fr_inv, mu):
    n = y.shape[0]
    jel = np.empty(n)
    energy = np.empty(n)
    for i in range(n):
        jel[i], energy[i] = _integrals_of(
            y[i, 0], y[i, 1], y[i, 2], y[i, 3], y[i, 4], y[i, 5], y[i, 6], y[i, 7], q, sigma, fr_inv, mu
        )
    return jel, energy


@njit(cache=True)
def point_integrals(y, q, sigma, fr_inv, mu):
    """``(J, E)`` of one state ``y = (omega, k, V0_h, ...)`` (1-D float array, the first 8
    entries used; floats ``q, sigma, fr_inv, mu``): :func:`state_integrals` of one state,
    without its array handling (what :func:`stability.final_state` calls)."""
    return _integrals_of(y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], q, sigma, fr_inv, mu)


def state_integrals(
    y: np.ndarray, *, q: float, sigma: float, fr_inv: float, mu: float
) -> tuple[np.ndarray, np.ndarray]:
    """Jellett's integral and the energy of states ``(omega, k, V0_h)`` (shape ``(n, 8)`` or
    ``(8,)``), by the nonlinear layer's formulas (:func:`~stability.nonlinear.quantities.jellett_integral`,
    :func:`~stability.nonlinear.quantities.energy_terms`, the ones :func:`stability.simulate`
    reports ``h_cg`` and ``energy`` with), compiled."""
    y = np.ascontiguousarray(np.atleast_2d(y)[:, :8], dtype=np.float64)
    return pick(_integrals, y.shape[0])(y, float(q), float(sigma), float(fr_inv), float(mu))


def state_values(
    kinds: list[str], theta: Any, lam: Any, spins: Any, p: np.ndarray, params: dict[str, float], tests: Any = None
) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """The states ``(omega, k, V0_h)`` of steady states given by kind (``"upright"``,
    ``"inverted"``, ``"tilted"``), tilt (radians), precession rate (of the tilted ones) and spin
    (of the vertical ones), their eigenvalues (:func:`~stability.steady.linearisation.state_modes`)
    and the values of :data:`~stability.steady.products.STATE_VARIABLES` but the tilt and the
    precession rate, with the flags (:func:`~stability.steady.verdicts.flag_of`; the energy
    criterion ``tests = (tests, scales)`` if given, else :func:`~stability.steady.family.energy_test`
    at each state's own ``J``): what :func:`steady_states` and
    :func:`stability.steady_branch` report."""
    q, sigma, fr_inv, alpha_v, mu = (params[k] for k in ("q", "sigma", "fr_inv", "alpha_v", "mu"))
    vertical = np.array([k != "tilted" for k in kinds], dtype=bool)
    y = family.state_vector(theta, lam, q)
    for i in np.nonzero(vertical)[0]:
        y[i] = family.vertical_state(kinds[i], spins[i])
    cosines = np.array([family.ORIENTATIONS.get(k, math.nan) for k in kinds])
    ev, growth, bound, n_neutral, jac = state_modes(y, lam, vertical, cosines, spins, p, params)  # lam: tilted only
    jel, energy = state_integrals(y, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu)
    if tests is None:  # the energy criterion at each state's own J
        c = np.cos(theta)
        rows = [
            family.energy_test(k, float(c[i]), float(jel[i]), q=q, sigma=sigma, fr_inv=fr_inv, mu=mu)
            for i, k in enumerate(kinds)
        ]
        tests = np.reshape(rows, (-1, 2)).T
    verdicts = zip(kinds, *tests, jac)
    flags = [flag_of(k, t, s, q=q, fr_inv=fr_inv, alpha_v=alpha_v, jacobian_verdict=int(v)) for k, t, s, v in verdicts]
    axial = np.einsum("ij,ij->i", y[:, 0:3], y[:, 3:6])
    values = dict(axial_spin=axial, energy=energy, jellett=jel, growth_rate=growth, growth_rate_bound=bound)
    values.update(n_neutral=n_neutral.astype(np.int8), stability=np.array(flags, dtype=np.int8), stability_jacobian=jac)
    return y, ev, values


def level_spins(kinds: list[str], jellett: float, params: dict[str, float]) -> np.ndarray:
    """The spins of the vertical states among ``kinds`` on the level ``J``
    (:func:`~stability.steady.family.vertical_spin`; NaN for the tilted ones)."""
    q, sigma = params["q"], params["sigma"]
    return np.array([math.nan if k == "tilted" else family.vertical_spin(k, jellett, q=q, sigma=sigma) for k in kinds])


def steady_states(
    model: str = "sliding", *, q: Any, sigma: Any, fr_inv: Any, alpha_v: Any, mu: Any = DEFAULT_MU, jellett: Any = None
) -> xr.Dataset:
    """Every steady state (upright, inverted, each tilted one) on one Jellett level.

    Parameters
    ----------
    model : {"sliding"}
        The sliding sphere with viscous friction (eqs. 1, 2, 4, 5, 7).
    q, sigma, fr_inv, alpha_v, mu : float
        Parameters (docs/conventions.md), single numbers in the physical domain.
    jellett : float, optional
        Jellett's integral ``J = (K + q k) . I_G omega`` in simulate's units (``A0 Omega``);
        default: the upright spin 1 (``omega = K``), ``J = sigma (1 + q)``, the state the linear
        atlases describe. Its sign is the sense of rotation (tilt, energy and stability depend
        on ``J^2`` only).

    Returns
    -------
    xarray.Dataset
        Over ``state`` (ordered by tilt): ``kind`` ("upright", "inverted", "tilted"), ``tilt``
        (polar angle of ``k``, degrees: 0 upright, 180 inverted), ``precession_rate`` (NaN for
        the vertical states), ``axial_spin`` (``omega . k``), ``omega_vertical``
        (``omega . K``), ``energy``, ``jellett``, ``growth_rate`` (leading real part of the
        physical eigenvalues in the frame precessing with the state, simulate's time unit:
        a vertical state's is ``|n|`` times eq. (11)'s at the equivalent spin), ``n_neutral``,
        ``stability`` (flag: 0 stable, 1 marginal, 2 unstable), ``stability_jacobian`` (the
        reduced Jacobian's own verdict), ``energy_test`` (the energy criterion, positive at a
        minimum of ``U_J``), ``mode_growth_rate`` and ``mode_frequency`` (``state``, ``mode``),
        and for the vertical states ``equivalent_fr_inv``, ``equivalent_alpha_v``,
        ``equivalent_q`` (the point of eq. (11) with the same verdict: ``fr_inv / n^2``,
        ``alpha_v / |n|``, ``+-q``: :func:`stability.steady.family.equivalent_point`); over
        ``tilt_grid`` (0 to 180 degrees), ``effective_potential``: ``U_J`` of the level against the
        tilt, whose critical points and ends are the states (the figure, ``ds.tippe.plot()``,
        :func:`stability.plotting.plot_steady_states`). The attributes name the removed neutral
        directions (``removed_neutral_*``) and the stability rule.

    Raises
    ------
    ValueError, TypeError
        A parameter outside the physical domain, not a single real number, an unknown model,
        or a ``jellett`` that is not a finite real number.

    Examples
    --------
    >>> import stability
    >>> ds = stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, jellett=-0.900118587)
    >>> [str(k) for k in ds.kind.values]
    ['upright', 'tilted', 'inverted']
    >>> round(float(ds.tilt[1]), 3)
    166.018
    """
    params, p = sliding_parameters(model, q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=alpha_v, mu=mu)
    q, sigma, fr_inv, alpha_v, mu = (params[k] for k in ("q", "sigma", "fr_inv", "alpha_v", "mu"))
    J = family.upright_jellett(q=q, sigma=sigma) if jellett is None else as_scalar("jellett", jellett)
    check_scales(params, J)
    table = pick(family.level_states, 1)(J, q, sigma, fr_inv, mu)  # upright, tilted by increasing tilt, inverted
    n = table.shape[0]
    kinds = ["upright"] + ["tilted"] * (n - 2) + ["inverted"]
    cosines, tests, scales, lam = table[:, 0], table[:, 2], table[:, 3], table[:, 4]
    theta = [math.acos(c) for c in cosines]
    spin = level_spins(kinds, J, params)
    y, ev, values = state_values(kinds, theta, lam, spin, p, params, (tests, scales))
    vertical = np.array([k != "tilted" for k in kinds])
    with np.errstate(divide="ignore", invalid="ignore"):
        point = family.equivalent_point(cosines, spin, q=q, fr_inv=fr_inv, alpha_v=alpha_v)
    values.update(tilt=np.degrees(np.arccos(np.clip(cosines, -1.0, 1.0))), precession_rate=lam)
    kind = "upright, inverted or tilted"
    test = "energy criterion: -U_J'(1) (upright), U_J'(-1) (inverted), U_J'' (tilted); > 0 at a minimum"
    note = "NaN for the vertical states; units of the spin rate Omega (simulate's time unit 1/Omega)"
    frequency = (
        "frequency Im s of each physical mode (frame precessing with the state; fixed frame for the vertical states)"
    )
    data = {
        "kind": ("state", np.array(kinds, dtype=str), {"long_name": "kind of steady state", "comment": kind}),
        **state_variables("state", values, "vertical states", precession_rate=note),
        "omega_vertical": variable(
            "state", y[:, 2], "vertical component of the angular velocity, omega . K", "Omega", short="vertical omega"
        ),
        "energy_test": variable("state", tests, test, short="energy criterion"),
        "mode_growth_rate": variable(
            ("state", "mode"), ev.real, "growth rate Re s of each physical mode", "Omega", short="growth rate Re s"
        ),
        "mode_frequency": variable(("state", "mode"), ev.imag, frequency, "Omega", short="frequency Im s"),
    }
    for what, i, units in (("fr_inv", 1, UNITLESS), ("alpha_v", 2, UNITLESS), ("q", 0, "R")):
        long_name = f"{what} of eq. (11) at the equivalent spin (vertical states)"
        v = np.where(vertical, point[i], np.nan)
        data[f"equivalent_{what}"] = variable("state", v, long_name, units, short=f"equivalent {what}")
    curve, curve_coords = potential_curve(J, params)
    mode_index = "index of the physical mode, by decreasing growth rate (tilted states have 5: the 6th is NaN)"
    coords = {
        "state": ("state", np.arange(n), {"long_name": "state", "comment": "index of the steady state"}),
        "mode": ("mode", np.arange(6), {"long_name": "mode", "comment": mode_index}),
        **curve_coords,
    }
    title = "Steady states of the sliding Tippe top on one Jellett level"
    attrs = product_attrs("steady_states", title, "stability.steady_states", params, removed_neutral=True)
    attrs.update(model="sliding", jellett=J)
    return xr.Dataset(data | curve, coords=coords, attrs=attrs)
