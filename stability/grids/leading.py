"""The leading growth rate of an atlas: the largest over the modes that are not structurally zero.

One home for the rule that :func:`stability.grids.atlases.leading_growth_rate`, the
``leading_growth_rate`` variable of every atlas (:func:`stability.atlas`, and the chunked writer
:func:`stability.grids.chunked.write_atlas`) and the stability maps use.

``max_growth_rate`` includes the structural zero mode (``s = 0`` exactly with an error bound of
exactly 0, :func:`stability.linear.modes.structural_zeros`: the sliding top's zero root at
``fr_inv = 0``), so at ``fr_inv = 0`` it is 0 on the whole stable side of the sliding top. The
zero mode is left out only when every point of the atlas inside the domain has one (a plane at
``fr_inv = 0``): an atlas that crosses ``fr_inv = 0`` keeps it on that line, because there it is
the end of the small mode ``s ~ -i c fr_inv`` (real part ``-O(fr_inv^2)``), and leaving it out on
one line only would draw a discontinuity that is not in the physics. The rule therefore depends
on the whole grid, which is why it is decided in two steps here: :func:`zero_everywhere` on each
part, then :func:`leading` with the decision.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from ..linear.modes import structural_zeros

__all__ = ["ATTRS", "leading", "zero_everywhere"]

#: the attributes of the ``leading_growth_rate`` variable
ATTRS: dict[str, str] = {
    "long_name": "leading growth rate",
    "units": "Omega",
    "comment": "max Re s over the modes that are not structurally zero: the s = 0 mode (at "
    "Fr^-1 = 0) is left out where every point of the grid inside the domain has it; "
    "units of the spin rate; equals max_growth_rate elsewhere",
}


def _zeros(growth: xr.DataArray, frequency: xr.DataArray, bound: xr.DataArray | None) -> xr.DataArray:
    args = [growth, frequency] + ([] if bound is None else [bound])
    return xr.apply_ufunc(lambda *a: structural_zeros(*a), *args, dask="parallelized", output_dtypes=[bool])


def zero_everywhere(
    growth: xr.DataArray, frequency: xr.DataArray, bound: xr.DataArray | None = None
) -> tuple[Any, Any]:
    """For one part of an atlas (dimension ``mode`` last or anywhere): whether every point inside
    the domain has a structural zero mode, and whether any point is inside (0-d, lazy for dask).
    The zero mode is left out of the whole atlas iff the first holds for every part and the
    second for one."""
    zero = _zeros(growth, frequency, bound)
    inside = np.isfinite(growth.max("mode", skipna=False))
    return (zero.any("mode") | ~inside).all(), inside.any()


def leading(
    growth: xr.DataArray, frequency: xr.DataArray, bound: xr.DataArray | None, max_growth: xr.DataArray, *, drop: Any
) -> xr.DataArray:
    """The leading growth rate over the grid, given the decision ``drop`` (leave the structural
    zero mode out, a bool or a 0-d array); NaN outside the domain. Works on numpy- and
    dask-backed arrays alike."""
    if getattr(drop, "chunks", None) is None and not bool(drop):
        out = max_growth.copy()  # decided, and nothing left out: no temporaries the size of the grid
    else:
        zero = _zeros(growth, frequency, bound)
        out = xr.where(drop, growth.where(~zero).max("mode").fillna(max_growth), max_growth)
    out = out.transpose(*max_growth.dims)
    out.attrs = dict(ATTRS)
    return out.rename("leading_growth_rate")
