"""Every steady state of the sliding top on one Jellett level, with its stability.

:func:`steady_states` answers: at a given Jellett integral ``J`` (conserved by every contact
force, so fixed by the initial state of a motion), which steady states exist, with what
tilt, precession, spin and energy, and which are stable. The upright and inverted spins exist
at every ``J``; the tilted ones are the roots of the quartic (S6) of
:func:`stability.steady.family.tilted_cosines`. Their energies and ``J`` are evaluated on the
state vectors with the nonlinear layer's own formulas (:mod:`stability.nonlinear.quantities`),
their spectra by :mod:`stability.steady.linearisation`, their flags by
:mod:`stability.steady.verdicts`. docs/steady_states.md has the derivation.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from ..nonlinear.quantities import centre_of_mass_velocity, energy_parts, h_cg
from ..parameters import DEFAULT_MU, as_scalar
from . import family
from .linearisation import modes_verdict, reduced_spectrum
from .products import DEGREE, UNITLESS, flag_attrs, product_attrs, sliding_parameters, var_attrs
from .verdicts import flag_of

__all__ = ["steady_states", "state_integrals", "upright_jellett"]


def upright_jellett(*, q: float, sigma: float) -> float:
    """Jellett's integral of the upright spin ``omega = K`` (spin 1, the linear atlases' state):
    ``J = sigma (1 + q)``."""
    return sigma * (1.0 + q)


def state_integrals(y: np.ndarray, *, q: float, sigma: float, fr_inv: float, mu: float
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Jellett's integral and the energy of states ``(omega, k, V0_h)`` (shape ``(n, 8)``), by the
    nonlinear layer's formulas (:func:`~stability.nonlinear.quantities.h_cg`,
    :func:`~stability.nonlinear.quantities.energy_parts`), as :func:`stability.simulate` reports them."""
    y = np.atleast_2d(y)
    w, k = y[:, 0:3], y[:, 3:6]
    v0 = np.zeros_like(w)
    v0[:, :2] = y[:, 6:8]
    vg = centre_of_mass_velocity(w, k, v0, q)
    e = energy_parts(w, k, vg, 1.0 + q * k[:, 2], q=q, fr_inv=fr_inv, sigma=sigma, mu=mu)["energy"]
    return h_cg(w, k.copy(), q=q, sigma=sigma, mu=mu), e


def steady_states(model: str = "sliding", *, q: Any, sigma: Any, fr_inv: Any, alpha_v: Any,
                  mu: Any = DEFAULT_MU, jellett: Any = None) -> xr.Dataset:
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
        ``alpha_v / |n|``, ``+-q``). The attributes name the removed neutral directions
        (``removed_neutral_*``) and the stability rule.

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
    J = upright_jellett(q=q, sigma=sigma) if jellett is None else as_scalar("jellett", jellett)
    rows = []
    for kind in ("upright", "inverted"):
        n = family.vertical_spin(kind, J, q=q, sigma=sigma)
        rows.append((kind, family.ORIENTATIONS[kind], math.nan, family.vertical_state(kind, n), n))
    for c in family.tilted_cosines(J, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu):
        lam = J / family.d_of_c(c, q, sigma, mu)
        rows.append(("tilted", c, lam, family.state_vector(math.acos(c), lam, q), math.nan))
    rows.sort(key=lambda r: -r[1])
    kinds = [r[0] for r in rows]
    cosines = np.array([r[1] for r in rows])
    lam = np.array([r[2] for r in rows])
    y = np.array([r[3] for r in rows])
    vertical = np.array([k != "tilted" for k in kinds])
    ev, scale = reduced_spectrum(y, np.nan_to_num(lam), vertical, p, q=q, sigma=sigma, mu=mu)
    growth, n_neutral, jac = modes_verdict(ev, scale)
    tests = [family.energy_test(k, float(c), J, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu)
             for k, c in zip(kinds, cosines)]
    flags = np.array([flag_of(k, t, s, q=q, fr_inv=fr_inv, alpha_v=alpha_v, jacobian_verdict=int(v))
                      for k, (t, s), v in zip(kinds, tests, jac)], dtype=np.int8)
    jel, energy = state_integrals(y, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu)
    spin = np.array([r[4] for r in rows])
    with np.errstate(divide="ignore"):
        eq = {"equivalent_fr_inv": np.where(vertical, fr_inv / spin ** 2, np.nan),
              "equivalent_alpha_v": np.where(vertical, alpha_v / np.abs(spin), np.nan),
              "equivalent_q": np.where(vertical, q * cosines, np.nan)}
    axial = np.einsum("ij,ij->i", y[:, 0:3], y[:, 3:6])
    data = {
        "kind": ("state", np.array(kinds, dtype=str), {"long_name": "kind of steady state", "comment": "upright, inverted or tilted"}),
        "tilt": ("state", np.degrees(np.arccos(np.clip(cosines, -1.0, 1.0))),
                 var_attrs("polar angle of the axis k from the upward vertical (0 upright, 180 inverted)", DEGREE, short="tilt")),
        "precession_rate": ("state", lam, var_attrs(
            "precession rate of the axis about the vertical (NaN for the vertical states)", "Omega",
            short="precession rate", comment="units of the spin rate Omega (simulate's time unit 1/Omega)")),
        "axial_spin": ("state", axial, var_attrs("spin about the axis, omega . k", "Omega", short="axial spin")),
        "omega_vertical": ("state", y[:, 2], var_attrs("vertical component of the angular velocity, omega . K", "Omega", short="vertical omega")),
        "energy": ("state", energy, var_attrs("total energy of the state", "A0 Omega^2", short="energy")),
        "jellett": ("state", jel, var_attrs("Jellett's integral J = (K + q k) . I_G omega", "A0 Omega", short="Jellett's J")),
        "growth_rate": ("state", growth, var_attrs(
            "leading growth rate of the linearisation about the state (frame precessing with it), "
            "structural neutral directions removed", "Omega", short="leading growth rate")),
        "n_neutral": ("state", n_neutral.astype(np.int8), var_attrs("number of physical modes neutral within rounding", short="neutral modes")),
        "stability": ("state", flags, flag_attrs("stability of the steady state")),
        "stability_jacobian": ("state", jac, flag_attrs(
            "Jacobian verdict", comment="verdict of the reduced Jacobian alone; neutral if |Re s| <= 1e3 u ||A||_F")),
        "energy_test": ("state", np.array([t for t, _ in tests]), var_attrs(
            "energy criterion: -U_J'(1) (upright), U_J'(-1) (inverted), U_J'' (tilted); > 0 at a minimum",
            short="energy criterion")),
        "mode_growth_rate": (("state", "mode"), ev.real, var_attrs("growth rate Re s of each physical mode", "Omega", short="growth rate Re s")),
        "mode_frequency": (("state", "mode"), ev.imag, var_attrs(
            "frequency Im s of each physical mode (frame precessing with the state; fixed frame for the vertical states)",
            "Omega", short="frequency Im s")),
    }
    for name, values in eq.items():
        data[name] = ("state", values, var_attrs(f"{name.split('_', 1)[1]} of eq. (11) at the equivalent spin "
                                                  "(vertical states)", "R" if name == "equivalent_q" else UNITLESS,
                                                  short=f"equivalent {name.split('_', 1)[1]}"))
    coords = {"state": ("state", np.arange(len(rows)), {"long_name": "state", "comment": "index of the steady state"}),
              "mode": ("mode", np.arange(6), {"long_name": "mode", "comment": "index of the physical mode, by "
                                              "decreasing growth rate (tilted states have 5: the 6th is NaN)"})}
    attrs = product_attrs("steady_states", "Steady states of the sliding Tippe top on one Jellett level",
                          "stability.steady_states", params, removed_neutral=True)
    attrs["model"] = "sliding"
    attrs["jellett"] = J
    return xr.Dataset(data, coords=coords, attrs=attrs)
