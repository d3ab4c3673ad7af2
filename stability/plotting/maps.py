"""Stability maps: the leading growth rate over a parameter plane, with its neutral contour."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.colors import TwoSlopeNorm
from matplotlib.figure import Figure

from ..parameters import SYMBOLS

__all__ = ["plot_stability_map", "growth_norm", "NEUTRAL_STYLE"]

#: the neutral curve's line: contrasting with the cividis colour map, also in grey
NEUTRAL_STYLE = dict(colors="#D55E00", linewidths=2.0)


def growth_norm(*growth_rates: np.ndarray) -> TwoSlopeNorm:
    """Colour normalisation centred on zero growth, shared by all the arrays given.

    Each sign gets half of the colour map up to the 98th percentile of its own magnitudes, so
    small decay rates stay visible beside large growth rates (colour bars are extended to
    show the clipping).
    """
    values = np.concatenate([np.ravel(g) for g in growth_rates])
    finite = values[np.isfinite(values)]
    neg, pos = -finite[finite < 0], finite[finite > 0]
    vmin = -float(np.percentile(neg, 98)) if neg.size else -1e-3
    vmax = float(np.percentile(pos, 98)) if pos.size else 1e-3
    return TwoSlopeNorm(vcenter=0.0, vmin=min(vmin, -1e-12), vmax=max(vmax, 1e-12))


def plot_stability_map(ds: xr.Dataset, x: str, y: str, *, ax: Axes | None = None,
                       colorbar: bool = True, norm: TwoSlopeNorm | None = None) -> tuple[Figure, Axes]:
    """Colour the leading growth rate over the (x, y) plane and draw where it is zero.

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas with exactly the grid dimensions ``x`` and ``y``.
    x, y : str
        Abscissa and ordinate (grid dimensions).
    ax : matplotlib.axes.Axes, optional
    colorbar : bool
        Add a colour bar labelled with the quantity and its units.
    norm : matplotlib.colors.TwoSlopeNorm, optional
        Shared colour normalisation (:func:`growth_norm`); by default from this atlas alone.

    Returns
    -------
    (Figure, Axes)

    Notes
    -----
    The line drawn here is the zero contour of the leading growth rate interpolated on the grid
    (for the conservative models, whose stable side is exactly neutral, the boundary of the
    unstable region); continued neutral curves (``continuation``), exact to
    round-off, are drawn on top by :func:`plot_neutral_curve` where available.
    """
    g = ds["max_growth_rate"]
    if set(g.dims) != {x, y}:
        raise ValueError(f"the atlas has grid dimensions {', '.join(g.dims)}; a map needs exactly {x!r} and {y!r}")
    if ax is None:
        fig = Figure()
        ax = fig.add_subplot()
    fig = ax.figure
    z = g.transpose(y, x).values
    finite = z[np.isfinite(z)]
    norm = norm or growth_norm(z)
    has_both_signs = (finite < 0).any() and (finite > 0).any()
    mesh = ax.pcolormesh(ds[x].values, ds[y].values, z, cmap="cividis", norm=norm, shading="auto",
                         rasterized=True)
    if has_both_signs:
        ax.contour(ds[x].values, ds[y].values, z, levels=[0.0], **NEUTRAL_STYLE)
    else:
        # conservative models: the stable side is neutral (Re s = 0 exactly), so there is no
        # zero crossing to interpolate; draw the boundary of the unstable region instead
        unstable = (ds["stability"] == 2).transpose(y, x).values.astype(float)
        unstable[ds["physical"].transpose(y, x).values == 0] = np.nan
        if np.nanmin(unstable) < 0.5 < np.nanmax(unstable):
            ax.contour(ds[x].values, ds[y].values, unstable, levels=[0.5], **NEUTRAL_STYLE)
    ax.set_xlabel(SYMBOLS.get(x, x))
    ax.set_ylabel(SYMBOLS.get(y, y))
    ax.set_title(f"{ds.attrs.get('model', '')}, eq. {ds.attrs.get('model_equations', '')}", fontsize=9)
    if colorbar:
        cb = fig.colorbar(mesh, ax=ax, extend="both")
        lo, hi = norm.vmin, norm.vmax
        cb.set_ticks([lo, lo / 2, 0.0, hi / 2, hi])
        cb.set_ticklabels([f"{v:.2g}" for v in (lo, lo / 2, 0.0, hi / 2, hi)])
        cb.set_label("leading growth rate Re $s$ / $\\Omega$")
    return fig, ax
