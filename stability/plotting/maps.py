"""Stability maps: the leading growth rate over a parameter plane, with its neutral contour;
continued neutral curves and fold curves (:mod:`stability.linear.neutral_curves`)."""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.colors import TwoSlopeNorm
from matplotlib.figure import Figure

from ..errors import InputError
from ..grids.atlases import leading_growth_rate
from ..parameters import SYMBOLS
from ._layout import axes_or_new

__all__ = ["NEUTRAL_STYLE", "growth_norm", "plot_fold_curve", "plot_neutral_curve", "plot_stability_map"]

#: the type of the keywords naming a curve's variables (None: the curve's own plane)
_Var = str | None

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


def plot_stability_map(
    ds: xr.Dataset,
    x: str,
    y: str,
    *,
    ax: Axes | None = None,
    colorbar: bool = True,
    norm: TwoSlopeNorm | None = None,
    curve: xr.Dataset | None = None,
) -> tuple[Figure, Axes]:
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
    curve : xarray.Dataset, optional
        Continued neutral curves of the same plane (``stability.neutral_curve``); drawn
        with their special points instead of the grid's contour.

    Returns
    -------
    (Figure, Axes)

    Notes
    -----
    The colour is :func:`stability.grids.atlases.leading_growth_rate`: the structural zero mode (the
    sliding top's ``s = 0`` at ``fr_inv = 0``, marginal by structure) is left out, so the stable
    side shows how fast the other modes decay instead of a flat zero.
    The line drawn here is the zero contour of the leading growth rate interpolated on the grid
    (for the conservative models, whose stable side is exactly neutral, the boundary of the
    unstable region); continued neutral curves (``continuation``), exact to
    round-off, are drawn on top by :func:`plot_neutral_curve` where available.
    """
    g = leading_growth_rate(ds)  # checks that ds is an atlas
    if set(g.dims) != {x, y}:
        raise InputError(f"the atlas has grid dimensions {', '.join(g.dims)}; a map needs exactly {x!r} and {y!r}")
    fig, ax = axes_or_new(ax)
    z = g.transpose(y, x).values
    finite = z[np.isfinite(z)]
    norm = norm or growth_norm(z)
    has_both_signs = (finite < 0).any() and (finite > 0).any()
    mesh = ax.pcolormesh(ds[x].values, ds[y].values, z, cmap="cividis", norm=norm, shading="auto", rasterized=True)
    if curve is not None:
        plot_neutral_curve(curve, ax=ax)
    elif has_both_signs:
        ax.contour(ds[x].values, ds[y].values, z, levels=[0.0], **NEUTRAL_STYLE)
    else:
        # conservative models: the stable side is neutral (Re s = 0 exactly), so there is no
        # zero crossing to interpolate; draw the boundary of the unstable region instead
        unstable = (ds["stability"] == 2).transpose(y, x).values.astype(float)
        unstable[(ds["stability"] == -1).transpose(y, x).values] = np.nan  # outside (= physical == 0)
        if np.nanmin(unstable) < 0.5 < np.nanmax(unstable):
            ax.contour(ds[x].values, ds[y].values, unstable, levels=[0.5], **NEUTRAL_STYLE)
    ax.set(xlabel=SYMBOLS.get(x, x), ylabel=SYMBOLS.get(y, y))
    ax.set_title(f"{ds.attrs.get('model', '')}, eq. {ds.attrs.get('model_equations', '')}", fontsize=9)
    if colorbar:
        cb = fig.colorbar(mesh, ax=ax, extend="both")
        ticks = [norm.vmin, norm.vmin / 2, 0.0, norm.vmax / 2, norm.vmax]
        cb.set_ticks(ticks, labels=[f"{v:.2g}" for v in ticks])
        cb.set_label("leading growth rate Re $s$ / $\\Omega$")
    return fig, ax


#: marker of each special-point kind of a continued neutral curve
SPECIAL_MARKERS = {
    "fold": ("^", "fold"),
    "zero_frequency": ("D", "w = 0"),
    "double_crossing": ("o", "double crossing"),
    "branch_point": ("s", "branch point"),
}
#: how every special point is drawn (an open marker, no line)
_SPECIAL_STYLE = dict(linestyle="none", markersize=7, markerfacecolor="white", markeredgecolor="black")


def plot_neutral_curve(
    curve: xr.Dataset,
    *,
    ax: Axes | None = None,
    x: str | None = None,
    y: str | None = None,
    label: str = "neutral curve (continued)",
) -> tuple[Figure, Axes]:
    """Draw a continued neutral curve (:func:`stability.neutral_curve`) and its special points.

    Parameters
    ----------
    curve : xarray.Dataset
        Along ``point``, with the variables named by its ``x`` and ``y`` attributes, ``branch``
        and ``kind`` (and ``leading``: parts where the traced mode is not the leading one are
        dashed, since there the curve is not the stability boundary). The dense output of
        :func:`continuation.dense` (along ``sample``, no ``kind``) is drawn without markers.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into (e.g. a stability map's); a new figure if omitted.
    x, y : str, optional
        The variables drawn; default the curve's plane (its ``x`` and ``y`` attributes).
    label : str
        Legend label of the curve.

    Returns
    -------
    (Figure, Axes)
    """
    return _draw_curve(curve, ax, x, y, label, ("x", "y"))


def plot_fold_curve(
    curve: xr.Dataset, *, ax: Axes | None = None, x: _Var = None, y: _Var = None, label: str = "fold curve (continued)"
) -> tuple[Figure, Axes]:
    """Draw a continued fold curve (:func:`stability.fold_curve`): where a neutral curve's
    fold sits as a third parameter varies.

    Parameters
    ----------
    curve : xarray.Dataset
        Along ``point``, with the variables named by its ``x``, ``y``, ``z`` and ``fold_in``
        attributes, ``branch`` and ``kind`` (``"fold"`` marks an extremum of ``z`` along the
        fold curve).
    ax : matplotlib.axes.Axes, optional
    x, y : str, optional
        The variables drawn; default ``z`` (the parameter varied) across and ``fold_in`` (the
        parameter whose extremum the fold is) up: the fold's value against ``z``.
    label : str
        Legend label of the curve.

    Returns
    -------
    (Figure, Axes)
    """
    return _draw_curve(curve, ax, x, y, label, ("z", "fold_in"))


def _draw_curve(
    curve: xr.Dataset, ax: Axes | None, x: str | None, y: str | None, label: str, plane: tuple[str, str]
) -> tuple[Figure, Axes]:
    """Branches of a continued curve in the (x, y) plane (solid where the traced mode leads,
    dashed elsewhere) and its special points (:data:`SPECIAL_MARKERS`); an ``x`` or ``y`` not
    given is the variable named by the curve's attribute ``plane[0]`` or ``plane[1]``."""
    x = curve.attrs[plane[0]] if x is None else x
    y = curve.attrs[plane[1]] if y is None else y
    fig, ax = axes_or_new(ax)
    first = True
    for b in np.unique(curve["branch"].values):
        sel = curve["branch"].values == b
        xs, ys = curve[x].values[sel], curve[y].values[sel]
        lead = curve["leading"].values[sel] if "leading" in curve else np.ones(sel.sum(), bool)
        solid = np.where(lead, ys, np.nan)
        dashed = np.where(lead, np.nan, ys)
        colour = NEUTRAL_STYLE["colors"]  # the line style explicit: the style cycles line styles
        ax.plot(xs, solid, color=colour, linewidth=2.0, linestyle="-", label=label if first else None)
        if np.isfinite(dashed).any():
            not_leading = "neutral, not the leading mode" if first else None
            ax.plot(xs, dashed, color=colour, linewidth=1.2, linestyle="--", label=not_leading)
        first = False
    kinds = curve["kind"].values.astype(str) if "kind" in curve else np.array([], dtype=str)
    for kind, (marker, text) in SPECIAL_MARKERS.items():
        sel = kinds == kind
        if sel.any():
            ax.plot(curve[x].values[sel], curve[y].values[sel], marker=marker, **_SPECIAL_STYLE, label=text)
    ax.set(xlabel=SYMBOLS.get(x, x), ylabel=SYMBOLS.get(y, y))
    ax.legend(loc="best", fontsize=8)
    return fig, ax
