"""High-spin classes of tops: never inverts, inverts, or hangs at a tilt.

Derivation (docs/steady_states.md, sec. 6). At a large spin the gravity term of the effective
potential ``U_J(c) = J^2 / (2 D(c)) + mu fr_inv (1 + q c)`` becomes negligible (the only
combination is ``mu fr_inv / J^2 -> 0``): the stable steady states are the maxima of ``D`` on
``[-1, 1]``, ``D'(c) = 2 P(c)``, ``P(1) = sigma (1 + q) - A_G``, ``P(-1) = A_G - sigma (1 - q)``:

* upright stable  <=>  ``P(1) > 0``   <=>  ``sigma (1 + q) > A_G``: the top **never inverts**;
* else inverted stable  <=>  ``P(-1) < 0``  <=>  ``sigma (1 - q) > A_G`` (only for ``q < 0``):
  it **inverts** completely;
* else the maximum of ``D`` is inside, at ``c0 = sigma q / (A_G - sigma)``: it **hangs** at the
  tilt ``arccos(c0)`` (beyond 90 degrees for ``q < 0``, short of it for ``q > 0``).

Boundaries in closed form: ``sigma = A_G / (1 + q)`` and (``q < 0``) ``sigma = A_G / (1 - q)``,
``A_G = 1 - mu q^2``. On a boundary the class is that of every large *finite* spin, where eq.
(11)'s gravity term ``mu q (1 +- q)^2 fr_inv / n^2`` breaks the tie: ``sigma (1 + q) = A_G`` is
``never_inverts`` for ``q < 0`` and ``hangs`` for ``q > 0``; ``sigma (1 - q) = A_G`` (``q < 0``)
is ``hangs`` (at a tilt that tends to 180 degrees); ``q = 0``, ``sigma = 1`` (dynamically
spherical: every tilt is steady) is ``never_inverts`` by convention.

In the notation of the literature (``alpha = -q`` the eccentricity of G, ``gamma = A_G / sigma``
the ratio of the transverse and axial moments about G) the ``inverts`` band is
``1 - alpha < gamma < 1 + alpha``, the condition of Hugenholtz (1952) as cited by Rutstam and by
Rauch-Wojciechowski & Rutstam (2014) (tests/test_steady_classes.py checks the identity).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from ..errors import ParameterTypeError
from ..parameters import DEFAULT_MU, DOMAIN, as_parameter, check_domain, check_flag, domain_sides, parameter_attrs
from ..resources import check_class_atlas
from . import family
from .products import DEGREE, product_attrs, var_attrs

__all__ = ["CLASSES", "class_atlas", "class_boundaries", "class_codes", "top_class"]

#: class names by code (-1: outside the physical domain)
CLASSES: tuple[str, ...] = ("never_inverts", "inverts", "hangs")
OUTSIDE = -1
_NAMES = np.array(CLASSES + ("outside_domain",))
#: the row of the physical domain's table that bounds sigma from above, sigma <= 2 A_G (its one home)
_SIGMA_TOP = next(i for i, b in enumerate(DOMAIN) if b.parameter == "sigma" and "q" in b.involves)


def class_codes(q: np.ndarray, sigma: np.ndarray, mu: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Codes (0 never_inverts, 1 inverts, 2 hangs) and the high-spin end tilt (degrees) of an
    upright launch, for checked, broadcast parameter arrays (no domain mask applied).

    The tilt is 0 (never_inverts), 180 (inverts) or ``arccos(c0)`` (hangs)."""
    p1 = family.p_of_c(1.0, q, sigma, mu)  # sigma (1 + q) - A_G
    pm1 = family.p_of_c(-1.0, q, sigma, mu)  # A_G - sigma (1 - q)
    up_unstable = (p1 < 0) | ((p1 == 0) & (q > 0))
    inv_stable = (pm1 < 0) | ((pm1 == 0) & (q > 0))
    code = np.where(~up_unstable, 0, np.where(inv_stable, 1, 2)).astype(np.int8)
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.clip(np.nan_to_num(family.c0(q, sigma, mu), nan=0.0), -1.0, 1.0)
    tilt = np.where(code == 0, 0.0, np.where(code == 1, 180.0, np.degrees(np.arccos(c))))
    return code, tilt


def top_class(*, q: Any, sigma: Any, mu: Any = DEFAULT_MU, mask_unphysical: bool = False) -> Any:
    """The high-spin class of tops: ``"never_inverts"``, ``"inverts"`` or ``"hangs"``.

    Parameters
    ----------
    q, sigma, mu : float or array_like
        Broadcast together (docs/conventions.md); ``fr_inv`` and ``alpha_v`` do not enter (the
        high-spin limit is ``mu fr_inv / J^2 -> 0``; the end state does not depend on the
        friction coefficient).
    mask_unphysical : bool, default False
        Points outside the physical domain refuse the request (a ``DomainError`` naming the
        parameter) unless True, when they get ``"outside_domain"``.

    Returns
    -------
    str or numpy.ndarray of str
        A str for scalar input.

    Examples
    --------
    >>> import stability
    >>> stability.top_class(q=-0.1, sigma=1.0)   # the paper's top
    'inverts'
    >>> stability.top_class(q=[-0.1, -0.1, 0.2], sigma=[1.2, 0.8, 0.7]).tolist()
    ['never_inverts', 'hangs', 'hangs']
    """
    p, inside = check_domain(q=q, sigma=sigma, mu=mu, mask=check_flag("mask_unphysical", mask_unphysical))
    code, _ = class_codes(p["q"], p["sigma"], p["mu"])
    out = _NAMES[np.where(inside, code, len(CLASSES))]
    return str(out) if out.ndim == 0 else out


def class_boundaries(q: Any, mu: Any = DEFAULT_MU) -> dict[str, np.ndarray]:
    """The class boundaries in ``sigma`` at given ``q`` (closed form): ``P(1) = 0`` and ``P(-1) = 0``.

    Returns
    -------
    dict
        ``"never_inverts"``: ``A_G / (1 + q)`` (never_inverts above it); ``"hangs"``:
        ``A_G / (1 - q)`` for ``q < 0`` (hangs below it; NaN for ``q >= 0``, where every top
        below the first boundary hangs); ``"domain"``: ``2 A_G``, the top of the physical domain.
    """
    q = as_parameter("q", q)
    mu = as_parameter("mu", mu)
    return {
        "never_inverts": family.sigma_of_c0(1.0, q, mu),
        "hangs": np.where(q < 0, family.sigma_of_c0(-1.0, q, mu), np.nan),
        "domain": domain_sides(q, 0.0, 0.0, 0.0, mu, 0.0)[2 * _SIGMA_TOP + 1],
    }


def class_atlas(*, q: Any, sigma: Any, mu: Any = DEFAULT_MU, mask_unphysical: bool = True) -> xr.Dataset:
    """The high-spin classes over a grid of ``(q, sigma, mu)``, as a Dataset (product ``top_classes``).

    Parameters
    ----------
    q, sigma, mu : float or 1-D array_like
        1-D arrays become dimensions (in this order), scalars scalar coordinates.
    mask_unphysical : bool, default True
        Points outside the physical domain get ``top_class = -1`` (False: refused).

    Returns
    -------
    xarray.Dataset
        ``top_class`` (flag: -1 outside_domain, 0 never_inverts, 1 inverts, 2 hangs),
        ``high_spin_tilt`` (degrees: the end tilt of an upright launch at high spin) and, over
        ``q`` (and ``mu``), the closed-form boundaries ``sigma_never_inverts = A_G / (1 + q)``,
        ``sigma_hangs = A_G / (1 - q)`` (``q < 0``) and ``sigma_domain = 2 A_G``.
    """
    values = {name: as_parameter(name, v) for name, v in (("q", q), ("sigma", sigma), ("mu", mu))}
    for name, arr in values.items():
        if arr.ndim > 1:
            raise ParameterTypeError(f"{name} must be a number or a 1-D array here, got shape {arr.shape}")
    dims = [k for k, v in values.items() if v.ndim == 1]
    check_class_atlas(int(np.prod([values[d].size for d in dims], dtype=np.int64)))
    grids = np.meshgrid(*(values[d] for d in dims), indexing="ij") if dims else []
    full = {k: (grids[dims.index(k)] if k in dims else values[k]) for k in values}
    p, inside = check_domain(mask=check_flag("mask_unphysical", mask_unphysical), **full)
    code, tilt = class_codes(p["q"], p["sigma"], p["mu"])
    code = np.where(inside, code, OUTSIDE).astype(np.int8)
    tilt = np.where(inside, tilt, np.nan)
    coords = {
        k: (k, v, parameter_attrs(k)) if v.ndim == 1 else ((), float(v), parameter_attrs(k)) for k, v in values.items()
    }
    comment = (
        "high-spin class of the top (launched near upright with a large spin); never_inverts: sigma (1 + q) > A_G; "
        "inverts: sigma (1 + q) < A_G < sigma (1 - q); hangs: otherwise (ties: the class of every large finite spin)"
    )
    flags = dict(
        flag_values=np.array([OUTSIDE, 0, 1, 2], dtype=np.int8), flag_meanings="outside_domain " + " ".join(CLASSES)
    )
    high = "end tilt of an upright launch at high spin: 0, 180 or arccos(sigma q / (A_G - sigma))"
    data: dict[str, Any] = {
        "top_class": (tuple(dims), code, {"long_name": "high-spin class", **flags, "comment": comment}),
        "high_spin_tilt": (tuple(dims), tilt, var_attrs(high, DEGREE, short="high-spin end tilt")),
    }
    bdims = tuple(d for d in dims if d in ("q", "mu"))
    if bdims:
        grid = np.meshgrid(*(values[d] for d in bdims), indexing="ij")
        qg, mg = (
            grid[bdims.index(k)] if k in bdims else np.broadcast_to(values[k], grid[0].shape) for k in ("q", "mu")
        )
        with np.errstate(invalid="ignore", divide="ignore"):
            ok = family.a_g(qg, mg) > 0
            b = class_boundaries(qg, mg)
        for name, short, text in (
            ("never_inverts", "sigma, never_inverts above", "boundary sigma = A_G / (1 + q): never_inverts above"),
            ("hangs", "sigma, hangs below", "boundary sigma = A_G / (1 - q), q < 0: hangs below, inverts above"),
            ("domain", "sigma, domain top", "top of the physical domain, sigma = 2 A_G"),
        ):
            data[f"sigma_{name}"] = (bdims, np.where(ok, b[name], np.nan), var_attrs(text, short=short))
    attrs = product_attrs("top_classes", "High-spin classes of sliding tops", "stability.class_atlas")
    attrs["grid_dimensions"] = " ".join(dims)
    attrs["literature"] = (
        "inverts <=> 1 - alpha < A_G/C < 1 + alpha (alpha = -q): Hugenholtz's condition; "
        "never_inverts / inverts / hangs: groups I / II / III of Ueda, Sasaki and Watanabe (2005)"
    )
    return xr.Dataset(data, coords=coords, attrs=attrs)
