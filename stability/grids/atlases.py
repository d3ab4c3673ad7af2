"""Stability atlases: spectra over parameter grids as CF-annotated xarray datasets.

Every parameter given as a 1-D array becomes a dimension (in the canonical order q, fr_inv,
sigma, alpha_v, mu) with a coordinate of the same name; a scalar becomes a scalar coordinate.
Convention: ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, fixed frame; ``growth_rate = Re s``
and ``frequency = Im s`` in units of the spin rate.

:func:`leading_growth_rate` reads off an atlas the growth rate a stability map colours (the
structural zero mode left out).
"""

from __future__ import annotations

from datetime import UTC, datetime
from itertools import product
from typing import Any

import numpy as np
import xarray as xr

from .._version import package_version
from ..errors import ParameterTypeError, require_extra
from ..interrupts import checkpoint, deferred
from ..linear.spectra import DEFAULT_METHOD, model_parameters, spectrum
from ..models import get_model
from ..parameters import DEFAULT_MU, PARAMETERS, as_parameter, check_domain, domain_text, parameter_attrs
from ..products import FLAG_MEANINGS, MARGINAL, PRODUCT_ATTR, STABLE, UNSTABLE
from ..resources import atlas_bytes, check_memory
from .leading import leading, zero_everywhere
from .schema import require_atlas

__all__ = ["MARGINAL_RULE", "TIME_CONVENTION", "atlas", "leading_growth_rate"]

TIME_CONVENTION = (
    "x ~ exp(s t), t in units of 1/Omega, components in the non-rotating frame; "
    "growth_rate = Re s, frequency = Im s, in units of the spin rate Omega"
)
MARGINAL_RULE = (
    "a mode is neutral if Re s = 0 by structure (exact zero root, or real root nu of a "
    "conservative p(i nu)) or |Re s| <= 4 e + 16 u max|s| (e: the root's error bound, "
    "u = 2^-53); unstable if a mode grows beyond that, stable if all decay beyond it"
)


def atlas(
    model: str,
    *,
    q: Any,
    fr_inv: Any,
    sigma: Any,
    alpha_v: Any = None,
    mu: Any = DEFAULT_MU,
    mask_unphysical: bool = False,
    method: str = DEFAULT_METHOD,
    chunks: int | dict[str, int] | None = None,
) -> xr.Dataset:
    """Spectra of a linear model over a grid of parameters, as an xarray Dataset.

    Parameters
    ----------
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"}
        Eqs. (8)-(9) or eq. (11).
    q, fr_inv, sigma, alpha_v, mu : float or 1-D array_like
        Scalars become scalar coordinates, 1-D arrays dimensions. ``alpha_v`` only for
        ``"sliding"``.
    mask_unphysical : bool, default False
        If False, any grid point outside the physical domain refuses the whole request
        (:class:`~stability.errors.DomainError`, no partial dataset). If True, those
        points get NaN and ``physical = 0``.
    method : {"kernel", "polynomial", "lapack"}
        Eigenvalue method (:data:`stability.linear.spectra.METHODS`).
    chunks : int or dict of str to int, optional
        If given, the dataset is lazy and dask-backed (:mod:`stability.grids.chunked`): chunk
        sizes along the grid dimensions (an int: the same along each; a dict: by dimension,
        the others whole). Nothing is computed until the values are used; the domain is
        checked at once. Write it chunk by chunk with
        :func:`stability.grids.chunked.write_atlas` (or ``write_dataset``).

    Returns
    -------
    xarray.Dataset
        ``growth_rate`` and ``frequency`` (grid + ``mode``), ``eigenvalue_error_bound``
        (grid + ``mode``), ``max_growth_rate``, ``stability`` (flag: -1 outside the domain,
        0 stable, 1 marginal, 2 unstable) and ``physical`` (flag), with CF attributes.

    Examples
    --------
    >>> import numpy as np, stability
    >>> ds = stability.atlas("sliding", q=np.linspace(-0.4, 0.4, 81), fr_inv=[0, 0.1, 0.3],
    ...                      sigma=1.0, alpha_v=0.5)
    >>> ds.growth_rate.dims
    ('q', 'fr_inv', 'mode')
    """
    m = get_model(model)
    given = model_parameters(m, dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu))
    values = {k: as_parameter(k, v) for k, v in given.items()}
    for k, v in values.items():
        if v.ndim > 1:
            raise ParameterTypeError(f"{k} must be a scalar or a 1-D array for an atlas, got shape {v.shape}")
    dims = [k for k in PARAMETERS if k in values and values[k].ndim == 1]
    if chunks is not None:
        require_extra("dask", "cluster", "an atlas in chunks (chunks=)")
        from .chunked import lazy_spectra

        growth, freq, bound, stab, inside = lazy_spectra(
            m, values, dims, chunks, mask_unphysical=mask_unphysical, method=method
        )
    else:
        full = tuple(values[d].size for d in dims)
        n_points = int(np.prod(full, dtype=np.int64))
        check_memory(
            atlas_bytes(m.n_modes, n_points, BLOCK_POINTS, domain_check=not mask_unphysical),
            what=f"atlas: {n_points} grid points ({' x '.join(f'{d}({n})' for d, n in zip(dims, full))})",
            parameter="the grid's ranges",
            way_out="pass chunks=100 (or another chunk size) to compute and write it chunk by chunk, "
            "or use fewer points",
        )
        growth, freq, bound, stab, inside = _spectra_in_blocks(m, values, dims, full, mask_unphysical, method)

    mdims = (*dims, "mode")

    def rate(dims: tuple[str, ...], data: np.ndarray, long_name: str, comment: str) -> tuple:
        # xarray labels axes "long_name [units]": rates in units of the spin rate
        return dims, data, {"long_name": long_name, "units": "Omega", "comment": comment}

    coords: dict[str, Any] = {}
    for k in PARAMETERS:
        if k in values:
            cf = parameter_attrs(k)
            coords[k] = (k, values[k], cf) if values[k].ndim == 1 else ((), float(values[k]), cf)
    coords["mode"] = (
        "mode",
        np.arange(m.n_modes),
        {"long_name": "mode", "comment": "mode index, modes sorted by decreasing growth rate"},
    )
    data_vars = {
        "growth_rate": rate(
            mdims, growth, "growth rate Re s", "growth rate of each mode, x ~ exp(s t), in units of the spin rate"
        ),
        "frequency": rate(
            mdims, freq, "frequency Im s", "frequency of each mode, fixed frame, in units of the spin rate"
        ),
        "eigenvalue_error_bound": rate(mdims, bound, "error bound of s", "absolute error bound of each eigenvalue s"),
        "max_growth_rate": rate(
            tuple(dims),
            growth[..., 0].copy(),
            "max growth rate",
            "largest growth rate max Re s over every mode, the structural s = 0 mode included "
            "(leading_growth_rate leaves it out)",
        ),
        "stability": (
            tuple(dims),
            stab,
            {
                "long_name": "stability",
                "flag_values": np.array([-1, STABLE, MARGINAL, UNSTABLE], dtype=np.int8),
                "flag_meanings": "outside_domain " + FLAG_MEANINGS,
                "comment": "linear stability of the upright spin; " + MARGINAL_RULE,
            },
        ),
        "physical": (
            tuple(dims),
            inside,
            {
                "long_name": "in physical domain",
                "flag_values": np.array([0, 1], dtype=np.int8),
                "flag_meanings": "outside_domain inside_domain",
                "comment": "the point lies in the physical domain: " + domain_text(m.parameters),
            },
        ),
    }
    attrs: dict[str, Any] = {
        "Conventions": "CF-1.10",
        "title": f"Linear stability atlas of the Tippe top: {m.name} model",
        PRODUCT_ATTR: "atlas",
        "model": m.name,
        "model_equations": m.equations,
        "model_description": m.description,
        "time_convention": TIME_CONVENTION,
        "marginal_rule": MARGINAL_RULE,
        "eigenvalue_method": method,
        "mask_unphysical": int(mask_unphysical),
        "source": f"tippe-stability {package_version()}",
        "history": f"{datetime.now(UTC).isoformat(timespec='seconds')} stability.atlas",
        "parameters": " ".join(values),
        "grid_dimensions": " ".join(dims),
    }
    attrs.update({k: float(v) for k, v in values.items() if v.ndim == 0})
    ds = xr.Dataset(data_vars, coords=coords, attrs=attrs)
    ds["leading_growth_rate"] = leading_growth_rate(ds)
    return ds


#: grid points per call of the spectrum in an in-memory atlas: a bounded piece of compiled work
#: (tens of milliseconds) between interruption points, and bounded temporaries
BLOCK_POINTS = 2**16


def _blocks(dims: list[str], full: tuple[int, ...]) -> list[dict[str, slice]]:
    """Slices of the grid of at most :data:`BLOCK_POINTS` points: whole trailing dimensions, a
    run of rows of one dimension, single indices of the leading ones."""
    if not dims:
        return [{}]
    k = 0
    while int(np.prod(full[k + 1 :], dtype=np.int64)) > BLOCK_POINTS:
        k += 1
    rows = max(1, BLOCK_POINTS // int(np.prod(full[k + 1 :], dtype=np.int64)))
    ranges = [[slice(i, i + 1) for i in range(full[j])] for j in range(k)]
    ranges.append([slice(i, min(i + rows, full[k])) for i in range(0, full[k], rows)])
    ranges.extend([[slice(0, full[j])] for j in range(k + 1, len(dims))])
    return [dict(zip(dims, combo)) for combo in product(*ranges)]


def _spectra_in_blocks(
    m: Any, values: dict[str, np.ndarray], dims: list[str], full: tuple[int, ...], mask: bool, method: str
) -> tuple[np.ndarray, ...]:
    """Growth rate, frequency, bound (grid + mode), stability and physical flags (int8) of the
    whole grid, one spectrum per block (:func:`_blocks`) with an interruption point before
    each. Each point's arithmetic does not depend on the block it is in, so the values are
    those of one call over the whole grid."""
    n = m.n_modes

    def grid(sl: dict[str, slice]) -> dict[str, np.ndarray]:  # the parameters of a block, broadcastable
        return {k: v[sl[k]].reshape([-1 if d == k else 1 for d in dims]) if k in sl else v for k, v in values.items()}

    blocks = _blocks(dims, full)
    if not mask and len(blocks) > 1:  # the whole grid refused at once, as one call would
        check_domain(mask=False, **grid({d: slice(None) for d in dims}))
    growth, freq, bound = (np.empty(full + (n,)) for _ in range(3))
    stab, inside = np.empty(full, dtype=np.int8), np.empty(full, dtype=np.int8)
    with deferred():
        for sl in blocks:
            checkpoint()
            sp = spectrum(m, mask_unphysical=mask, method=method, **grid(sl))
            idx = tuple(sl[d] for d in dims)  # the block's values broadcast to it by the assignments
            growth[idx], freq[idx] = sp.eigenvalues.real, sp.eigenvalues.imag
            bound[idx] = sp.error_bound
            stab[idx] = sp.stability
            inside[idx] = sp.inside
        checkpoint()
    return growth, freq, bound, stab, inside


def leading_growth_rate(ds: xr.Dataset) -> xr.DataArray:
    """Largest growth rate over the modes of an atlas that are not structurally zero.

    ``max_growth_rate`` includes the structural zero mode, so at ``fr_inv = 0`` it is 0 on the
    whole stable side of the sliding top (marginal by structure: the ``stability`` flag says
    so); this is the growth rate of the least stable of the other modes, what a stability map
    colours, and what atlases store as ``leading_growth_rate``. The zero mode is left out only
    when every point of the atlas has one (the rule and why: :mod:`stability.grids.leading`).
    Where it is not left out this equals ``max_growth_rate``.

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas (``growth_rate``, ``frequency`` along ``mode``; ``eigenvalue_error_bound`` if
        present; ``max_growth_rate``).

    Returns
    -------
    xarray.DataArray
        Over the grid; NaN outside the domain.
    """
    require_atlas(ds)
    if "growth_rate" not in ds:  # a map atlas file: the leading growth rate is what it stores
        return ds["leading_growth_rate"]
    g, f = ds["growth_rate"], ds["frequency"]
    bound = ds.get("eigenvalue_error_bound")
    dims = list(ds["max_growth_rate"].dims)
    if g.ndim <= 1:
        drop: Any = False
    elif g.chunks is None:  # in memory: decided block by block, so its temporaries stay block-sized
        parts = [
            zero_everywhere(*(None if x is None else x.isel(sl) for x in (g, f, bound)))
            for sl in _blocks(dims, tuple(ds.sizes[d] for d in dims))
        ]
        drop = all(bool(e) for e, _ in parts) and any(bool(a) for _, a in parts)
    else:
        everywhere, any_inside = zero_everywhere(g, f, bound)
        drop = everywhere & any_inside
    return leading(g, f, bound, ds["max_growth_rate"], drop=drop)
