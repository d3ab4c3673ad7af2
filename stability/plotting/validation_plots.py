"""Validation of the linear predictions by nonlinear runs (:mod:`stability.nonlinear.validation`)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError, ParameterTypeError
from ._layout import PERIODS_LABEL, axes_or_new, panels_or_new, periods

__all__ = ["plot_coulomb_growth", "plot_validation"]

_VALIDATION = ("predicted_growth_rate", "jacobian_growth_rate", "measured_growth_rate")


def _require(ds: object, names: Sequence[str], made_by: str) -> xr.Dataset:
    if not isinstance(ds, xr.Dataset):
        raise ParameterTypeError(f"ds is a {type(ds).__name__}; it must be an xarray.Dataset from {made_by}")
    missing = [v for v in names if v not in ds]
    if missing:
        raise InputError(f"ds has no {', '.join(missing)}: it is not a dataset of {made_by}")
    return ds


def plot_validation(ds: xr.Dataset, *, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """The growth rate fitted to each nonlinear run against the linear predictions.

    One marker per point and prediction: the Jacobian of the nonlinear model (filled) and the
    registered linear operator (hollow); on the diagonal a prediction is exact.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`stability.validate`.
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    (Figure, Axes)
    """
    _require(ds, _VALIDATION, "stability.validate")
    fig, ax = axes_or_new(ax)
    measured = ds["measured_growth_rate"].values
    model = ds.attrs.get("model", "")
    styles: tuple[tuple[str, dict[str, Any], str], ...] = (
        ("jacobian_growth_rate", {"marker": "o"}, "Jacobian of the nonlinear model"),
        ("predicted_growth_rate", {"marker": "s", "markerfacecolor": "none"}, f"linear operator ({model})"),
    )
    for name, style, label in styles:
        ax.plot(ds[name].values, measured, linestyle="none", label=label, **style)
    values = np.concatenate([ds[v].values for v in _VALIDATION])
    values = values[np.isfinite(values)]
    if values.size:
        lo, hi = float(values.min()), float(values.max())
        ax.plot([lo, hi], [lo, hi], color="0.4", linewidth=0.8, linestyle="-", zorder=0, label="measured = predicted")
    ax.set(xlabel="predicted growth rate Re $s$ / $\\Omega$", ylabel="growth rate fitted to the run / $\\Omega$")
    ax.set_title(f"{ds.attrs.get('title', '')}: {ds.sizes.get('point', 1)} points", fontsize=9)
    ax.legend(fontsize=8)
    return fig, ax


def plot_coulomb_growth(ds: xr.Dataset, *, axes: Sequence[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """Coulomb friction alone: (a) the tilt and (b) the sliding speed against time.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`stability.coulomb_growth`; its attributes name the scheme and the reading of
        the growth (exponential or algebraic, by the residuals of the two fits).
    axes : sequence of 2 Axes, optional

    Returns
    -------
    (Figure, list of 2 Axes)
    """
    _require(ds, ("tilt", "slip_speed"), "stability.coulomb_growth")
    fig, (ax1, ax2) = panels_or_new(axes, 2, (6.4, 6.0), sharex=True)
    t = periods(ds)
    ax1.plot(t, ds["tilt"].values)
    ax1.set_ylabel(r"tilt $|\Phi|$")
    ax2.semilogy(t, np.maximum(ds["slip_speed"].values, 1e-12))
    ax2.set(ylabel=r"sliding speed $|V_c|$ / $\Omega R$", xlabel=PERIODS_LABEL)
    a = ds.attrs
    fits = ", ".join(
        f"{name} fit {a[key]:.2g}"
        for name, key in (("exponential", "exponential_residual"), ("algebraic", "algebraic_residual"))
        if key in a
    )
    ax1.set_title(
        f"(a) {a.get('scheme', '')} scheme: growth {a.get('growth', 'not classified')}"
        + (f" (RMS residuals: {fits})" if fits else ""),
        loc="left",
        fontsize=8,
    )
    ax2.set_title("(b)", loc="left", fontsize=9)
    return fig, [ax1, ax2]
