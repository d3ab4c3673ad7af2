"""What an atlas is: the one validator used wherever an atlas is read or drawn.

:func:`validate_atlas` checks a dataset against the layout :func:`stability.atlas` writes, the
facts the rest of the package relies on (counts of stable points, maps, the leading growth rate,
resuming and rewriting):

=====================================  ==========================================================
what                                   rule
=====================================  ==========================================================
variables                              ``growth_rate``, ``frequency``, ``max_growth_rate``,
                                       ``stability`` (``eigenvalue_error_bound`` and ``physical``
                                       are checked when present)
grid                                   the dimensions of ``stability``; each has a 1-D floating
                                       coordinate of its own name, finite
``growth_rate``, ``frequency``,        floating; dimensions the grid and ``mode``
``eigenvalue_error_bound``
``max_growth_rate``                    floating; dimensions the grid; equal to ``growth_rate`` of
                                       mode 0 (bit for bit, NaN where NaN)
``stability``                          integer; dimensions the grid; values in its flags
                                       {-1, 0, 1, 2} (``flag_values``, if given, exactly these)
                                       (``flag_meanings``, if given, "outside_domain stable
                                       marginal unstable"); flagged stable only where
                                       ``max_growth_rate < -eigenvalue_error_bound`` (mode 0),
                                       unstable only where ``max_growth_rate > 0`` (counted)
``physical``                           integer; dimensions the grid; values in {0, 1}
consistency                            outside the domain (``stability == -1``) exactly where
                                       ``physical == 0``, and there every growth rate, frequency
                                       and bound is NaN; inside none is; bounds >= 0
``model`` attribute                    a registered linear model (if given); the ``mode``
                                       dimension has its number of modes
=====================================  ==========================================================

Values are checked in slabs along the first grid dimension (:data:`SLAB_POINTS` points at a
time), so a file opened lazily is never read whole to be checked; a dask-backed (lazy, not yet
computed) dataset gets the structural checks only. The first violation is reported, naming the
variable and the rule ("variable 'stability' has dtype float64; an atlas stores integer flags").
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError, ParameterTypeError

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["ATLAS_VARIABLES", "FLAG_VALUES", "MAP_VARIABLES", "SLAB_POINTS", "STORED_ATTR", "require_atlas"]
__all__ += ["required_variables", "validate_atlas"]

#: the variables every atlas has
ATLAS_VARIABLES = ("growth_rate", "frequency", "max_growth_rate", "stability")

#: the variables of a *map* atlas file (``write_atlas(..., variables="map")``, ``tippe atlas
#: --variables map``): the smallest that draws a stability map; its global attribute
#: :data:`STORED_ATTR` is ``"map"``
MAP_VARIABLES = ("leading_growth_rate", "stability")

#: global attribute naming what an atlas file stores: ``"all"`` (or absent) or ``"map"``
STORED_ATTR = "atlas_variables"


def required_variables(ds: xr.Dataset) -> tuple[str, ...]:
    """The variables ``ds`` must have: :data:`MAP_VARIABLES` for a map atlas (its attribute
    :data:`STORED_ATTR` is ``"map"``), else :data:`ATLAS_VARIABLES`."""
    return MAP_VARIABLES if str(ds.attrs.get(STORED_ATTR, "all")) == "map" else ATLAS_VARIABLES


#: the values of the ``stability`` flag: outside the domain, stable, marginal, unstable
FLAG_VALUES = (-1, 0, 1, 2)
#: what they mean (the ``flag_meanings`` attribute, if given, says exactly this)
FLAG_MEANINGS = ("outside_domain", "stable", "marginal", "unstable")

#: grid points checked at a time (its temporaries: ~30 bytes per point and mode, ~8 MB for
#: three modes; 2e6 points made them a third of an in-memory atlas's peak)
SLAB_POINTS = 2**17

_MODAL = ("growth_rate", "frequency", "eigenvalue_error_bound")


def require_atlas(ds: object, name: str = "ds") -> xr.Dataset:
    """``ds`` itself if it is an atlas dataset (:func:`validate_atlas`); otherwise a
    ``TypeError`` (not a Dataset) or ``ValueError`` naming what is wrong."""
    import xarray as xr  # here: importing the checks imports no xarray (tippe --help)

    if not isinstance(ds, xr.Dataset):
        raise ParameterTypeError(
            f"{name} is a {type(ds).__name__}; it must be an atlas, an xarray.Dataset from "
            "stability.atlas or stability.open_atlas"
        )
    if missing := [v for v in required_variables(ds) if v not in ds]:
        raise InputError(
            f"{name} has no {', '.join(missing)}: it is not an atlas (stability.atlas or "
            f"stability.open_atlas; a simulate() run or a neutral curve has its own plots)"
        )
    validate_atlas(ds, lambda text: InputError(f"{name} is not a valid atlas: {text}"))
    return ds


def validate_atlas(ds: xr.Dataset, error: Callable[[str], Exception]) -> None:
    """Check ``ds`` against the atlas layout (module docstring); raise ``error(text)`` at the
    first violation.

    Parameters
    ----------
    ds : xarray.Dataset
        In memory, opened lazily from a file, or dask-backed (structure only).
    error : callable
        Makes the exception from the violation's text (the caller names the file or argument).
    """
    missing = [v for v in required_variables(ds) if v not in ds]
    if missing:
        raise error(f"missing variables {', '.join(missing)}")
    grid = tuple(ds["stability"].dims)
    if "mode" in grid:
        raise error("variable 'stability' has the dimension 'mode'; it is one flag per grid point")
    _structure(ds, grid, error)
    if any(ds[v].chunks is not None for v in _present(ds)):
        return  # lazy and not computed: reading the values would compute them
    _values(ds, grid, error)


def _present(ds: xr.Dataset) -> list[str]:
    return [v for v in (*ATLAS_VARIABLES, "eigenvalue_error_bound", "physical", "leading_growth_rate") if v in ds]


def _structure(ds: xr.Dataset, grid: tuple[str, ...], error: Callable[[str], Exception]) -> None:
    for v in _present(ds):
        var = ds[v]
        modal = v in _MODAL
        want = set(grid) | ({"mode"} if modal else set())
        if set(var.dims) != want or var.ndim != len(want):
            raise error(
                f"variable {v!r} has dimensions {var.dims}; an atlas has {v} on "
                f"{tuple(grid) + (('mode',) if modal else ())} (the dimensions of 'stability'"
                f"{' and mode' if modal else ''})"
            )
        kind = var.dtype.kind
        if v in ("stability", "physical"):
            if kind not in "iu":
                raise error(f"variable {v!r} has dtype {var.dtype}; an atlas stores it as integer flags (int8)")
        elif kind != "f":
            raise error(f"variable {v!r} has dtype {var.dtype}; an atlas stores it as floating-point numbers")
    flags = ds["stability"].attrs.get("flag_values")
    if flags is not None and [int(f) for f in np.atleast_1d(flags)] != list(FLAG_VALUES):
        raise error(
            f"variable 'stability' has flag_values {[int(f) for f in np.atleast_1d(flags)]}; an atlas's flags are "
            f"{list(FLAG_VALUES)} (outside the domain, stable, marginal, unstable)"
        )
    meanings = ds["stability"].attrs.get("flag_meanings")
    if meanings is not None and str(meanings).split() != list(FLAG_MEANINGS):
        raise error(
            f"variable 'stability' has flag_meanings {str(meanings)!r}; an atlas's flags mean "
            f"{' '.join(FLAG_MEANINGS)!r} (for {list(FLAG_VALUES)})"
        )
    for d in grid:
        if d not in ds.coords or ds[d].dims != (d,):
            raise error(f"grid dimension {d!r} has no coordinate of its own name")
        c = ds[d]
        if c.dtype.kind != "f":
            raise error(f"coordinate {d!r} has dtype {c.dtype}; a grid coordinate is floating-point")
        if not np.isfinite(c.values).all():
            raise error(f"coordinate {d!r} has values that are not finite")
    model = ds.attrs.get("model")
    if model is not None:
        from ..models import MODELS

        if str(model) not in MODELS:
            raise error(f"its attribute model = {model!r} is not a linear model of this package ({', '.join(MODELS)})")
        n = MODELS[str(model)].n_modes
        if "mode" in ds.dims and ds.sizes["mode"] != n:
            raise error(f"it has {ds.sizes['mode']} modes; the {model} model has {n}")


def _slabs(ds: xr.Dataset, grid: tuple[str, ...]) -> list[dict[str, slice]]:
    if not grid:
        return [{}]
    first = grid[0]
    n0 = ds.sizes[first]
    per_row = max(1, int(np.prod([ds.sizes[d] for d in grid[1:]], dtype=np.int64)))
    step = max(1, SLAB_POINTS // per_row)
    return [{first: slice(i, min(i + step, n0))} for i in range(0, n0, step)]


def _values(ds: xr.Dataset, grid: tuple[str, ...], error: Callable[[str], Exception]) -> None:
    n_stable_bad = n_unstable_bad = 0
    first_bad: dict[str, float] | None = None
    for sl in _slabs(ds, grid):
        part = ds[_present(ds)].isel(sl)
        stab = part["stability"].transpose(*grid).values
        bad = ~np.isin(stab, FLAG_VALUES)
        if bad.any():
            raise error(f"variable 'stability' holds {_example(stab[bad])}, outside its flags {list(FLAG_VALUES)}")
        outside = stab == -1
        if "physical" in part:
            phys = part["physical"].transpose(*grid).values
            if not np.isin(phys, (0, 1)).all():
                raise error(f"variable 'physical' holds {_example(phys[~np.isin(phys, (0, 1))])}, not a flag 0 or 1")
            if not np.array_equal(phys == 0, outside):
                raise error(
                    "variables 'physical' and 'stability' disagree: physical == 0 must hold exactly where "
                    "stability == -1 (outside the domain)"
                )
        for v in (m for m in _MODAL if m in part):
            a = part[v].transpose(*grid, "mode").values
            nan = np.isnan(a)
            if not (nan.all(axis=-1) == outside).all() or not (nan.any(axis=-1) == outside).all():
                raise error(
                    f"variable {v!r} has NaN where 'stability' is not -1, or a number where it is -1 "
                    "(NaN marks exactly the points outside the domain)"
                )
            if v == "eigenvalue_error_bound" and (a < 0).any():  # NaN < 0 is False: no copy of the numbers
                raise error("variable 'eigenvalue_error_bound' has negative values; a bound is >= 0")
        if "leading_growth_rate" in part:
            lead = part["leading_growth_rate"].transpose(*grid).values
            if not np.array_equal(np.isnan(lead), outside):
                raise error(
                    "variable 'leading_growth_rate' has NaN where 'stability' is not -1, or a number where "
                    "it is -1 (NaN marks exactly the points outside the domain)"
                )
        if "growth_rate" not in part or "max_growth_rate" not in part:
            continue  # a map atlas
        g0 = part["growth_rate"].transpose(*grid, "mode").values[..., 0]
        mx = part["max_growth_rate"].transpose(*grid).values
        if not np.array_equal(g0, mx, equal_nan=True):
            raise error(
                "variable 'max_growth_rate' differs from growth_rate of mode 0 (the modes are sorted by "
                "decreasing growth rate)"
            )
        # the flags against the stored numbers (the rule of stability.linear.spectra: a mode is
        # neutral within tol >= its bound, so a stable point has max Re s < -bound_0 and an
        # unstable one max Re s > 0, whatever the rest of the rule)
        b0 = (
            part["eigenvalue_error_bound"].transpose(*grid, "mode").values[..., 0]
            if "eigenvalue_error_bound" in part
            else np.zeros_like(mx)
        )
        bad_s = (stab == 0) & ~(mx + b0 < 0)
        bad_u = (stab == 2) & ~(mx > 0)
        n_stable_bad += int(bad_s.sum())
        n_unstable_bad += int(bad_u.sum())
        if first_bad is None and (bad_s.any() or bad_u.any()):
            idx = np.argwhere(bad_s | bad_u)[0]
            first_bad = {d: float(part[d].values[i]) for d, i in zip(grid, idx)}
            first_bad["max_growth_rate"] = float(mx[tuple(idx)])
            first_bad["stability"] = int(stab[tuple(idx)])
    if n_stable_bad or n_unstable_bad:
        where = ", ".join(f"{k} = {v:.6g}" for k, v in first_bad.items())
        raise error(
            f"its flags disagree with its own growth rates: {n_stable_bad} points flagged stable (0) have "
            f"max_growth_rate >= -eigenvalue_error_bound and {n_unstable_bad} flagged unstable (2) have "
            f"max_growth_rate <= 0 (first: {where}); the file was edited or damaged. Recompute it "
            "(stability.atlas or tippe atlas), or read the numbers alone with xarray.open_dataset"
        )


def _example(values: np.ndarray) -> str:
    u = np.unique(values)
    return ", ".join(repr(x.item()) for x in u[:3]) + (" ..." if u.size > 3 else "")
