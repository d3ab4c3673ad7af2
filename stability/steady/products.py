"""Inputs and dataset attributes shared by the products of the steady layer.

One place for: the check of the model name and of the physical parameters (through
:func:`stability.nonlinear.runs.model_parameter_vector`, whose messages name the parameter, its
value and the allowed range), and the CF attributes of the products ``steady_states``,
``steady_branch``, ``final_state`` and ``top_classes`` (global attribute
:data:`stability.grids.netcdf.PRODUCT_ATTR`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._version import package_version
from ..grids.netcdf import PRODUCT_ATTR
from ..nonlinear.runs import model_parameter_vector
from ..errors import InputError
from ..parameters import LONG_NAMES
from .linearisation import REMOVED_NEUTRAL
from .verdicts import FLAG_MEANINGS, FLAG_VALUES, RULE

__all__ = ["MODELS", "sliding_parameters", "product_attrs", "var_attrs", "flag_attrs", "UNITLESS", "DEGREE"]

#: the models whose steady states the layer analyses (docs/steady_states.md says why only this one)
MODELS = ("sliding",)

UNITLESS = "1"
DEGREE = "degree"


def sliding_parameters(model: Any, *, q: Any, sigma: Any, fr_inv: Any, alpha_v: Any, mu: Any
                       ) -> tuple[dict[str, float], np.ndarray]:
    """Check ``model`` and the parameters (single numbers in the physical domain).

    Returns
    -------
    params : dict of float
        ``q, fr_inv, sigma, mu, alpha_v`` (``alpha_k = 0``).
    p : numpy.ndarray
        Parameter vector of the compiled kernels.

    Raises
    ------
    ValueError
        ``model`` is not one of :data:`MODELS` (the message says why the rolling model is not
        offered), or a parameter outside the physical domain.
    TypeError
        A missing or non-real parameter, or an array where a number is needed.
    """
    if not isinstance(model, str) or model not in MODELS:
        raise InputError(f"model = {model!r:.60} is not known; choose one of {', '.join(MODELS)} (the rolling "
                         "sphere has the same steady states, but it conserves energy: no final state, and no "
                         "steady state of it is asymptotically stable)")
    params, p = model_parameter_vector("sliding", q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu)
    params.pop("alpha_k", None)
    return params, p


def var_attrs(long_name: str, units: str = UNITLESS, *, short: str | None = None, **extra: Any) -> dict[str, Any]:
    """CF attributes of a variable. With ``short``, that is the ``long_name`` (what xarray prints
    on an axis, "long_name [units]", within its 30-character wrap) and ``long_name`` opens the
    ``comment``."""
    if short is None:
        return {"long_name": long_name, "units": units, **extra}
    comment = long_name + (f"; {extra.pop('comment')}" if "comment" in extra else "")
    return {"long_name": short, "units": units, "comment": comment, **extra}


def flag_attrs(long_name: str, comment: str = RULE) -> dict[str, Any]:
    """CF flag attributes of a stability variable (0 stable, 1 marginal, 2 unstable)."""
    return {"long_name": long_name, "flag_values": np.array(FLAG_VALUES, dtype=np.int8),
            "flag_meanings": FLAG_MEANINGS, "comment": comment}


def product_attrs(product: str, title: str, function: str, params: dict[str, float] | None = None,
                  removed_neutral: bool = False) -> dict[str, Any]:
    """Global attributes: CF conventions, the product name, the source and the parameters."""
    attrs: dict[str, Any] = {"Conventions": "CF-1.10", "title": title, PRODUCT_ATTR: product,
                             "source": f"{function} (tippe-stability {package_version()})",
                             "units_convention": "length R, time 1/Omega, inertia A0, energy A0 Omega^2, "
                                                 "Jellett's integral A0 Omega (simulate's units)"}
    for name, value in (params or {}).items():
        attrs[name] = float(value)
        attrs[f"{name}_long_name"] = LONG_NAMES[name]
    if removed_neutral:
        attrs["removed_neutral"] = ", ".join(REMOVED_NEUTRAL)
        for name, text in REMOVED_NEUTRAL.items():
            attrs[f"removed_neutral_{name}"] = text
        attrs["frame"] = ("tilted states: the frame precessing with the state at its precession rate; "
                          "vertical states: the fixed frame (their spectrum is eq. (11)'s at the "
                          "equivalent spin, times |n|)")
        attrs["stability_rule"] = RULE
    return attrs
