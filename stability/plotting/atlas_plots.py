"""Line plots of an atlas: growth rate (or frequency) of a mode against one parameter."""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError
from ..files import atomic_output
from ..grids.netcdf import require_atlas
from ..linear.modes import principal_mode
from ..parameters import PARAMETERS, SYMBOLS, check_choice
from ._layout import axes_or_new

__all__ = ["STYLE_FILE", "plot_growth_rate", "save_figure", "style"]

STYLE_FILE = Path(__file__).with_name("tippe.mplstyle")

QUANTITIES = {
    "growth_rate": "growth rate Re $s$ / $\\Omega$",
    "frequency": "frequency Im $s$ / $\\Omega$ (fixed frame)",
}
MODES = ("principal", "leading")


def _line(da_s: np.ndarray, quantity: str, mode: str) -> np.ndarray:
    """Values along one line: ``da_s`` is (m, n_modes) complex."""
    s = principal_mode(da_s) if mode == "principal" else da_s[:, 0]
    return s.real if quantity == "growth_rate" else s.imag


@contextlib.contextmanager
def style() -> Iterator[None]:
    """Context manager applying the package's figure style."""
    import matplotlib.pyplot as plt

    with plt.style.context(str(STYLE_FILE)):
        yield


def plot_growth_rate(
    ds: xr.Dataset, x: str = "q", *, quantity: str = "growth_rate", mode: str = "principal", ax: Axes | None = None
) -> tuple[Figure, Axes]:
    """Plot a mode's growth rate (or frequency) against ``x``, one line per family.

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas (:func:`stability.atlas`) with ``x`` as a dimension and at most one other
        grid dimension (the family, one line per value, named in the legend).
    x : str, default "q"
        The abscissa (a grid dimension).
    quantity : {"growth_rate", "frequency"}
        ``Re s`` or ``Im s`` of the mode drawn.
    mode : {"principal", "leading"}
        ``"principal"``: the mode followed continuously along ``x``
        (:func:`stability.linear.modes.track_modes`) that reaches the largest growth rate; its growth
        rate and frequency are smooth curves. ``"leading"``: the largest growth rate at each
        point (``max_growth_rate``), whose frequency jumps where the leading mode changes.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made if omitted.

    Returns
    -------
    (Figure, Axes)
    """
    require_atlas(ds)
    if "growth_rate" not in ds:
        raise InputError(
            "ds is a map atlas (atlas_variables = 'map': leading_growth_rate and stability only); "
            "growth rates and frequencies per mode need an atlas written with variables='all'"
        )
    check_choice("quantity", quantity, QUANTITIES)
    check_choice("mode", mode, MODES)
    grid = list(ds["max_growth_rate"].dims)
    if x not in grid:
        raise InputError(f"x = {x!r} is not a grid dimension of the atlas (it has {', '.join(grid) or 'none'})")
    others = [d for d in grid if d != x]
    if len(others) > 1:
        raise InputError(f"the atlas has grid dimensions {', '.join(grid)}; select all but {x!r} and one family first")
    fig, ax = axes_or_new(ax)
    s = ds["growth_rate"] + 1j * ds["frequency"]
    if others:
        fam = others[0]
        for v in ds[fam].values:
            line = s.sel({fam: v}).transpose(x, "mode").values
            ax.plot(ds[x].values, _line(line, quantity, mode), label=f"{SYMBOLS.get(fam, fam)} = {v:g}")
    else:
        ax.plot(ds[x].values, _line(s.transpose(x, "mode").values, quantity, mode), label=ds.attrs.get("model", ""))
    if quantity == "growth_rate":
        ax.axhline(0.0, color="0.3", linewidth=0.8, linestyle="-", zorder=0)
    ax.set(xlabel=SYMBOLS.get(x, x), ylabel=QUANTITIES[quantity])
    fixed = [f"{SYMBOLS.get(k, k)} = {float(ds[k]):g}" for k in PARAMETERS if k in ds.coords and ds[k].ndim == 0]
    ax.set_title(
        f"{ds.attrs.get('model', '')} model, eq. {ds.attrs.get('model_equations', '')}: " + ", ".join(fixed), fontsize=9
    )
    ax.legend()
    return fig, ax


#: the resolution to which drawn data are rounded before a figure is saved: this fraction of
#: the axis span (lines) or of the colour range (maps); ~1e-9, far below a pixel and far above
#: the rounding-level differences of the numbers between machines
QUANTUM = 2.0**-30

#: metadata that would make the same figure's bytes differ between matplotlib versions or runs
_NO_METADATA = {
    "png": {"Software": None},
    "pdf": {"Creator": None, "Producer": None, "CreationDate": None},
    "svg": {"Creator": None, "Date": None},
}


def _rounded(values: np.ndarray, span: float) -> np.ndarray:
    q = QUANTUM * span
    if not (np.isfinite(q) and q > 0):
        return values
    with np.errstate(invalid="ignore"):
        return np.round(values / q) * q


def settle_data(fig: Figure) -> None:
    """Round the data of every line and colour map of ``fig`` to :data:`QUANTUM` of its axis
    span or colour range.

    Why: the same figure drawn on two machines gets numbers that differ in their last bits
    (numba compiles for each CPU; a continuation places its points after step decisions taken
    on rounding-level quantities), and antialiased edges and colour levels turn that into
    pixels (hundreds of pixels of ``map_sigma_fr_inv.png``, 1/255 each, along its neutral line).
    Rounded to ~1e-9 of the span, the drawn data are the same bits unless a value lies within
    rounding of a quantum's edge (probability ~1e-7 per value), and no pixel can move."""
    for ax in fig.axes:
        spans = [abs(float(b) - float(a)) for a, b in (ax.get_xlim(), ax.get_ylim())]
        for line in ax.get_lines():
            x, y = line.get_data(orig=True)
            x, y = np.asarray(x), np.asarray(y)
            if x.dtype.kind == "f" and y.dtype.kind == "f":
                line.set_data(_rounded(x, spans[0]), _rounded(y, spans[1]))
        for artist in [*ax.collections, *ax.images]:
            arr = artist.get_array() if hasattr(artist, "get_array") else None
            if arr is None or np.asarray(arr).dtype.kind != "f":
                continue
            norm = getattr(artist, "norm", None)
            lo, hi = (
                (norm.vmin, norm.vmax)
                if norm is not None and norm.vmin is not None
                else (np.nanmin(arr), np.nanmax(arr))
            )
            rounded = _rounded(np.ma.getdata(arr), abs(float(hi) - float(lo)))
            artist.set_array(np.ma.array(rounded, mask=np.ma.getmask(arr)) if np.ma.isMaskedArray(arr) else rounded)


def save_figure(fig: Figure, path: str | os.PathLike, *, overwrite: bool = True) -> Path:
    """Save ``fig`` to ``path`` atomically (no partial file); the format comes from the suffix.

    The same figure gives the same bytes on every machine: its data are rounded first
    (:func:`settle_data`) and no metadata that names a version or a date is written."""
    settle_data(fig)
    fmt = Path(path).suffix.lstrip(".").lower()
    with atomic_output(path, overwrite=overwrite) as tmp:
        fig.savefig(tmp, format=fmt or None, metadata=_NO_METADATA.get(fmt))
    return Path(path)
