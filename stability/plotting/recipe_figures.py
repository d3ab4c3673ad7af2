"""Draw the figure a recipe asks for (stability.recipes), from its computed datasets."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError
from ..grids.atlases import leading_growth_rate
from ..recipes import Recipe
from . import scene_plots
from ._layout import panels_or_new
from .figures import _quantity_panels
from .launch_plots import plot_critical_spin
from .maps import growth_norm, plot_stability_map
from .steady_plots import plot_bifurcation, plot_class_map, plot_settle, plot_settle_approach

__all__ = ["recipe_figure"]


def recipe_figure(
    recipe: Recipe, datasets: dict[str, xr.Dataset], *, axes: Sequence[Axes] | None = None
) -> tuple[Figure, list[Axes]]:
    """The figure of ``recipe`` drawn from ``datasets`` (model name -> atlas), titled with the
    recipe's title.

    Parameters
    ----------
    recipe : Recipe
    datasets : dict
        As returned by :func:`stability.recipes.compute`.
    axes : sequence of Axes, optional
        Where to draw: as many Axes as the figure has panels (one per quantity for ``lines``,
        one per model for ``models``, one for ``map`` and ``critical_spin``, the panels of the
        paper's figure for ``scene``; Fig. 8's is 3-D); a new figure by default.

    Returns
    -------
    (Figure, list of Axes)
        The figure and its panels.
    """
    if recipe.kind in _ONE_PANEL:
        size, draw = _ONE_PANEL[recipe.kind]
        fig, axes = panels_or_new(axes, 1, size)
        draw(recipe, datasets, axes[0])
    elif recipe.kind == "settle":
        run = datasets["run"]
        fig, axes = panels_or_new(axes, 2, (7.4, 5.6))
        plot_settle(run, predicted_tilt=run.attrs["predicted_tilt"], label=run.attrs.get("label", ""), ax=axes[0])
        rate = run.attrs.get("predicted_growth_rate")
        plot_settle_approach(run, predicted_tilt=run.attrs["predicted_tilt"], rate=rate, ax=axes[1])
    elif recipe.kind == "scene":
        fig, axes = _scene_figure(recipe.figure, datasets, axes)
    elif recipe.kind == "lines":
        n = len(recipe.quantities)
        fig, axes = panels_or_new(axes, n, (6.4, 3.4 * n), sharex=True)
        _quantity_panels(datasets[recipe.model], recipe.x, recipe.quantities, axes)
    else:  # models side by side
        names = [k for k in datasets if not k.endswith("_neutral")]
        fig, axes = panels_or_new(axes, len(names), (4.2 * len(names), 4.0), row=True, sharey=True)
        norm = growth_norm(*(leading_growth_rate(datasets[k]).values for k in names))
        for ax, name in zip(axes, names):
            curve, last = datasets.get(f"{name}_neutral"), name == names[-1]
            plot_stability_map(datasets[name], recipe.x, recipe.y, ax=ax, colorbar=last, norm=norm, curve=curve)
            if name != names[0]:
                ax.set_ylabel("")
    fig.suptitle(recipe.title, fontsize=10)
    return fig, axes


#: the recipes of one panel: kind -> (figure size, ``draw(recipe, datasets, ax)``)
_ONE_PANEL: dict[str, tuple[tuple[float, float], Callable[[Recipe, dict[str, xr.Dataset], Axes], object]]] = {
    "critical_spin": ((6.4, 4.2), lambda r, d, ax: plot_critical_spin(d[r.model], ax=ax)),
    "map": (
        (6.4, 4.8),
        lambda r, d, ax: plot_stability_map(d[r.model], r.x, r.y, ax=ax, curve=d.get(f"{r.model}_neutral")),
    ),
    "bifurcation": (
        (7.4, 4.8),
        lambda r, d, ax: plot_bifurcation(d["branch"], vertical=d["vertical"], runs=d["runs"], x="spin", ax=ax),
    ),
    "classes": ((6.8, 5.0), lambda r, d, ax: plot_class_map(d["classes"], ax=ax)),
}


def _scene_figure(
    figure: str | None, runs: dict[str, xr.Dataset], axes: Sequence[Axes] | None
) -> tuple[Figure, list[Axes]]:
    """One of Figs. 5-9 from the runs of :func:`stability.recipes.scene_runs`."""
    main = runs["fr_inv_0.3"]
    if figure == "fig5":
        return scene_plots.fig5({runs[k].attrs["label"]: runs[k] for k in ("fr_inv_0.3", "fr_inv_0.1")}, axes=axes)
    if figure in ("fig6", "fig8"):  # one panel
        if axes is not None and len(axes) != 1:
            raise InputError(f"axes has {len(axes)} Axes; this figure draws 1 panel")
        draw = scene_plots.fig6 if figure == "fig6" else scene_plots.fig8
        fig, ax = draw(main, ax=None if axes is None else axes[0])
        return fig, [ax]
    if figure == "fig7":
        return scene_plots.fig7(main, axes=axes)
    cases = {runs[k].attrs["label"]: runs[k] for k in sorted(runs) if k.startswith("case") and "paper" not in k}
    paper = {runs[k].attrs["label"]: runs[k] for k in sorted(runs) if k.endswith("_paper_scheme")}
    return scene_plots.fig9(main, runs["rolling"], cases, paper, slip_case=list(cases)[-1], axes=axes)
