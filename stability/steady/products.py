"""Inputs and dataset attributes shared by the products of the steady layer.

One place for: the check of the model name and of the physical parameters (through
:func:`stability.nonlinear.runs.model_parameter_vector` and
:func:`stability.parameters.check_domain`, whose messages name the parameter, its value and the
allowed range), the CF attributes of the products ``steady_states``, ``steady_branch``,
``final_state`` and ``top_classes`` (global attribute :data:`stability.products.PRODUCT_ATTR`),
and the curve of the effective potential that the figures of ``steady_states`` and
``final_state`` draw (:func:`potential_curve`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._version import package_version
from ..errors import DomainError, InputError
from ..nonlinear.runs import model_parameter_vector
from ..parameters import LONG_NAMES, check_domain
from ..products import FLAG_MEANINGS, FLAG_VALUES, PRODUCT_ATTR
from . import family
from .linearisation import REMOVED_NEUTRAL
from .verdicts import RULE

__all__ = ["FLAGS", "check_scales", "flag_attrs", "potential_curve", "product_attrs", "sliding_parameters"]

#: the models whose steady states the layer analyses (docs/steady_states.md says why only this one)
MODELS = ("sliding",)

UNITLESS = "1"
DEGREE = "degree"
#: number of tilts (0 to 180 degrees, every 0.25 degree) at which :func:`potential_curve` samples U_J
TILT_GRID_POINTS = 721


def sliding_parameters(
    model: Any, *, q: Any, sigma: Any, fr_inv: Any, alpha_v: Any, mu: Any, kernel: bool = True
) -> tuple[dict[str, float], np.ndarray | None]:
    """Check ``model`` and the parameters (single numbers in the physical domain).

    Parameters
    ----------
    model : {"sliding"}
    q, sigma, fr_inv, alpha_v, mu : float
    kernel : bool, default True
        Also pack the compiled kernels' parameter vector
        (:func:`stability.nonlinear.runs.model_parameter_vector`, which checks the point with
        :func:`stability.parameters.check_domain`). False: only that check of the point (the
        same check and messages), for callers that need the numbers alone
        (:func:`stability.final_state`, whose deciding run packs its own).

    Returns
    -------
    params : dict of float
        ``q, fr_inv, sigma, mu, alpha_v`` (``alpha_k = 0``).
    p : numpy.ndarray or None
        Parameter vector of the compiled kernels (None if not ``kernel``).

    Raises
    ------
    ValueError
        ``model`` is not one of :data:`MODELS` (the message says why the rolling model is not
        offered), or a parameter outside the physical domain.
    TypeError
        A missing or non-real parameter, or an array where a number is needed.
    """
    if not isinstance(model, str) or model not in MODELS:
        raise InputError(
            f"model = {model!r:.60} is not known; choose one of {', '.join(MODELS)} (the rolling "
            "sphere has the same steady states, but it conserves energy: no final state, and no "
            "steady state of it is asymptotically stable)"
        )
    if not kernel:
        checked, _ = check_domain(scalar=True, q=q, fr_inv=fr_inv, sigma=sigma, mu=mu, alpha_v=alpha_v)
        return {name: float(v) for name, v in checked.items()}, None
    params, p = model_parameter_vector("sliding", dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu))
    params.pop("alpha_k", None)
    return params, p


#: the range of the scales the steady layer computes with (:func:`check_scales`): their squares
#: and products of a few stay normal doubles, so no term underflows or overflows
SCALE_RANGE = (1e-100, 1e100)


def check_scales(params: dict[str, float], jellett: float | None = None, *, jellett_name: str = "jellett") -> None:
    """Refuse scales at which the steady layer's doubles would underflow or overflow.

    The family is scale invariant (``J^2 / (mu fr_inv)`` and ``lam^2 / (mu fr_inv |q|)`` are
    functions of ``q, sigma, mu, c`` only, S3-S4), and every computation of the layer is
    relative to those scales; what it cannot do is carry a scale whose square is not a normal
    double. So each of ``sigma``, ``mu``, ``mu fr_inv``, ``mu fr_inv |q|`` (the scale of
    ``lam^2`` on the family), ``|J|`` and ``|J| / sigma`` (the spin of the vertical states) that
    is not zero must lie in :data:`SCALE_RANGE`; the message names the parameter that leaves
    it, its value and the range (``jellett_name``: the caller's name of ``jellett``). (``|q|`` so small that ``mu fr_inv |q|`` is below the range is
    the ``q = 0`` family to far below rounding: pass ``q = 0``.)

    Raises
    ------
    stability.errors.DomainError
    """
    lo, hi = SCALE_RANGE
    q, sigma, fr_inv, mu = (params[k] for k in ("q", "sigma", "fr_inv", "mu"))
    gravity = f"fr_inv = {fr_inv:.6g}, mu = {mu:.6g}"
    checks = [("sigma", sigma, "sigma", ""), ("mu", mu, "mu", ""), ("mu fr_inv", mu * fr_inv, "fr_inv", gravity)]
    below = "below it the family is q = 0's to far below rounding: pass q = 0"
    why = f"q = {q:.6g}, {gravity}; the scale of the precession rate squared on the tilted family; {below}"
    checks.append(("mu fr_inv |q|", mu * fr_inv * abs(q), "q" if abs(q) < 1e-3 else "fr_inv", why))
    if jellett is not None:
        j = jellett_name
        vertical = f"{j} = {jellett:.6g}, sigma = {sigma:.6g}; the spin of the vertical states"
        checks += [(f"|{j}|", abs(jellett), j, ""), (f"|{j}| / sigma", abs(jellett) / sigma, j, vertical)]
    for label, value, name, why in checks:
        if value != 0.0 and not lo <= value <= hi:
            raise DomainError(
                f"{label} = {value:.6g} is outside the steady layer's range [{lo:g}, {hi:g}] "
                f"(parameter {name}{'; ' + why if why else ''}): its square would underflow or "
                "overflow a double"
            )


def var_attrs(long_name: str, units: str = UNITLESS, *, short: str | None = None, **extra: Any) -> dict[str, Any]:
    """CF attributes of a variable. With ``short``, that is the ``long_name`` (what xarray prints
    on an axis, "long_name [units]", within its 30-character wrap) and ``long_name`` opens the
    ``comment``."""
    if short is None:
        return {"long_name": long_name, "units": units, **extra}
    comment = long_name + (f"; {extra.pop('comment')}" if "comment" in extra else "")
    return {"long_name": short, "units": units, "comment": comment, **extra}


def variable(
    dims: Any, values: Any, long_name: str, units: str = UNITLESS, **kw: Any
) -> tuple[Any, Any, dict[str, Any]]:
    """A dataset variable ``(dims, values, attrs)`` with the CF attributes of :func:`var_attrs`."""
    return (dims, values, var_attrs(long_name, units, **kw))


#: the variables of a steady state that steady_states and steady_branch share: name -> (long_name,
#: units, short name); ``{vertical}`` is what each calls its vertical points
STATE_VARIABLES = {
    "tilt": ("polar angle of the axis k from the upward vertical (0 upright, 180 inverted)", DEGREE, "tilt"),
    "precession_rate": ("precession rate of the axis about the vertical", "Omega", "precession rate"),
    "axial_spin": ("spin about the axis, omega . k", "Omega", "axial spin"),
    "energy": ("total energy of the state", "A0 Omega^2", "energy"),
    "jellett": ("Jellett's integral J = (K + q k) . I_G omega", "A0 Omega", "Jellett's J"),
    "growth_rate": (
        "leading growth rate of the linearisation about the state (frame precessing with it), structural "
        "neutral directions removed",
        "Omega",
        "leading growth rate",
    ),
    "growth_rate_bound": (
        "absolute error bound of growth_rate ({vertical}: |n| times eq. (11)'s bound at the equivalent point; "
        "tilted states: 1e3 u ||A||_F)",
        "Omega",
        "growth rate bound",
    ),
    "n_neutral": ("number of physical modes neutral within rounding", UNITLESS, "neutral modes"),
}


def state_variables(dim: str, values: dict[str, Any], vertical: str, **comments: str) -> dict[str, Any]:
    """The variables of :data:`STATE_VARIABLES` over ``dim`` from their ``values`` by name, and
    the flags ``stability`` and ``stability_jacobian`` (``values`` too); ``comments`` by name."""
    data = {}
    for name, (long_name, units, short) in STATE_VARIABLES.items():
        extra = {"comment": comments[name]} if name in comments else {}
        data[name] = variable(dim, values[name], long_name.format(vertical=vertical), units, short=short, **extra)
    data["stability"] = (dim, values["stability"], flag_attrs("stability of the steady state"))
    jacobian = flag_attrs(
        "Jacobian verdict",
        comment="verdict of the spectrum alone: the reduced Jacobian's (neutral if |Re s| <= 1e3 u ||A||_F) for "
        f"tilted states, eq. (11)'s at the equivalent point for {vertical}",
    )
    data["stability_jacobian"] = (dim, values["stability_jacobian"], jacobian)
    return data


#: the CF flag attributes of every stability variable of the layer (stability.products' flags)
_FLAG_VALUES = np.array(FLAG_VALUES, dtype=np.int8)
_FLAG_VALUES.setflags(write=False)  # shared by every dataset: read-only
FLAGS: dict[str, Any] = {"flag_values": _FLAG_VALUES, "flag_meanings": FLAG_MEANINGS}


def flag_attrs(long_name: str, comment: str = RULE) -> dict[str, Any]:
    """CF flag attributes of a stability variable (0 stable, 1 marginal, 2 unstable)."""
    return {"long_name": long_name, **FLAGS, "comment": comment}


def product_attrs(
    product: str, title: str, function: str, params: dict[str, float] | None = None, removed_neutral: bool = False
) -> dict[str, Any]:
    """Global attributes: CF conventions, the product name, the source and the parameters."""
    attrs: dict[str, Any] = {
        "Conventions": "CF-1.10",
        "title": title,
        PRODUCT_ATTR: product,
        "source": f"{function} (tippe-stability {package_version()})",
        "units_convention": "length R, time 1/Omega, inertia A0, energy A0 Omega^2, "
        "Jellett's integral A0 Omega (simulate's units)",
    }
    for name, value in (params or {}).items():
        attrs[name] = float(value)
        attrs[f"{name}_long_name"] = LONG_NAMES[name]
    if removed_neutral:
        attrs["removed_neutral"] = ", ".join(REMOVED_NEUTRAL)
        for name, text in REMOVED_NEUTRAL.items():
            attrs[f"removed_neutral_{name}"] = text
        attrs["frame"] = (
            "tilted states: the frame precessing with the state at its precession rate; "
            "vertical states: the fixed frame (their spectrum is eq. (11)'s at the "
            "equivalent spin, times |n|)"
        )
        attrs["stability_rule"] = RULE
    return attrs


def potential_curve(jellett: float, params: dict[str, float]) -> tuple[dict[str, Any], dict[str, Any]]:
    """The effective potential of the level ``J`` against the tilt, for the figures.

    ``U_J(c) = J^2 / (2 D(c)) + mu fr_inv (1 + q c)`` (S5;
    :func:`stability.steady.family.effective_potential`) at :data:`TILT_GRID_POINTS` tilts from 0
    to 180 degrees: a lower bound of the energy of every state of the level with that tilt,
    equal to it exactly at the steady states, which are its critical points and the two ends
    (docs/steady_states.md, sec. 2, the energy principle).

    Returns
    -------
    data_vars, coords : dict
        ``{"effective_potential": ("tilt_grid", ...)}`` and ``{"tilt_grid": ...}`` (degrees),
        entries for an :class:`xarray.Dataset`.
    """
    grid = np.linspace(0.0, 180.0, TILT_GRID_POINTS)
    q, sigma, fr_inv, mu = (params[k] for k in ("q", "sigma", "fr_inv", "mu"))
    u = family.effective_potential(np.cos(np.radians(grid)), jellett, q, sigma, fr_inv, mu)
    comment = (
        "U_J = J^2 / (2 D) + mu fr_inv (1 + q cos(tilt)), D = sigma (cos(tilt) + q)^2 + A_G sin(tilt)^2; "
        "a lower bound of the energy of every state of the level with this tilt, "
        "reached at the steady states (its critical points and the two ends)"
    )
    long_name = "effective potential U_J of the Jellett level"
    data = {
        "effective_potential": variable(
            "tilt_grid", u, long_name, "A0 Omega^2", short="U_J of the level", comment=comment
        )
    }
    long_name = "tilt at which U_J is sampled (0 upright, 180 inverted)"
    return data, {"tilt_grid": variable("tilt_grid", grid, long_name, DEGREE, short="tilt")}
