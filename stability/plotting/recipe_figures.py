"""Draw the figure a recipe asks for (stability.recipes), from its computed datasets."""

from __future__ import annotations

import xarray as xr
from matplotlib.figure import Figure

from ..grids.atlases import leading_growth_rate
from ..recipes import Recipe
from .atlas_plots import plot_growth_rate
from . import scene_plots
from .maps import growth_norm, plot_stability_map
from .spin_plots import plot_critical_spin
from .steady_plots import plot_bifurcation, plot_class_map, plot_settle, plot_settle_approach

__all__ = ["recipe_figure"]


def recipe_figure(recipe: Recipe, datasets: dict[str, xr.Dataset]) -> Figure:
    """The figure of ``recipe`` drawn from ``datasets`` (model name -> atlas).

    Parameters
    ----------
    recipe : Recipe
    datasets : dict
        As returned by :func:`stability.recipes.compute`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if recipe.kind in ("bifurcation", "classes", "settle"):
        fig = _steady_figure(recipe, datasets)
    elif recipe.kind == "scene":
        fig = _scene_figure(recipe.figure, datasets)
    elif recipe.kind == "critical_spin":
        fig = Figure(figsize=(6.4, 4.2), layout="constrained")
        ax = fig.add_subplot()
        plot_critical_spin(datasets[recipe.model], ax=ax)
    elif recipe.kind == "lines":
        n = len(recipe.quantities)
        fig = Figure(figsize=(6.4, 3.4 * n), layout="constrained")
        axes = fig.subplots(n, 1, sharex=True, squeeze=False)[:, 0]
        ds = datasets[recipe.model]
        for k, (ax, quantity) in enumerate(zip(axes, recipe.quantities)):
            plot_growth_rate(ds, recipe.x, quantity=quantity, ax=ax)
            if k:
                ax.set_title("")
                ax.get_legend().remove()
            if k < n - 1:
                ax.set_xlabel("")
    elif recipe.kind == "map":
        fig = Figure(figsize=(6.4, 4.8), layout="constrained")
        ax = fig.add_subplot()
        plot_stability_map(datasets[recipe.model], recipe.x, recipe.y, ax=ax,
                           curve=datasets.get(f"{recipe.model}_neutral"))
    else:  # models side by side
        names = [k for k in datasets if not k.endswith("_neutral")]
        fig = Figure(figsize=(4.2 * len(names), 4.0), layout="constrained")
        axes = fig.subplots(1, len(names), sharey=True)
        norm = growth_norm(*(leading_growth_rate(datasets[k]).values for k in names))
        for ax, name in zip(axes, names):
            plot_stability_map(datasets[name], recipe.x, recipe.y, ax=ax, colorbar=name == names[-1], norm=norm,
                               curve=datasets.get(f"{name}_neutral"))
            if name != names[0]:
                ax.set_ylabel("")
    fig.suptitle(recipe.title, fontsize=10)
    return fig


def _scene_figure(figure: str | None, runs: dict[str, xr.Dataset]) -> Figure:
    """One of Figs. 5-9 from the runs of :func:`stability.recipes.scene_runs`."""
    main = runs["fr_inv_0.3"]
    if figure == "fig5":
        return scene_plots.fig5({runs[k].attrs["label"]: runs[k] for k in ("fr_inv_0.3", "fr_inv_0.1")})
    if figure == "fig6":
        return scene_plots.fig6(main)
    if figure == "fig7":
        return scene_plots.fig7(main)
    if figure == "fig8":
        return scene_plots.fig8(main)
    cases = {runs[k].attrs["label"]: runs[k] for k in sorted(runs) if k.startswith("case") and "paper" not in k}
    paper = {runs[k].attrs["label"]: runs[k] for k in sorted(runs) if k.endswith("_paper_scheme")}
    return scene_plots.fig9(main, runs["rolling"], cases, paper, slip_case=list(cases)[-1])


def _steady_figure(recipe: Recipe, datasets: dict[str, xr.Dataset]) -> Figure:
    """The steady-state figures (stability.recipes' bifurcation, classes and settle kinds)."""
    if recipe.kind == "bifurcation":
        fig = Figure(figsize=(7.4, 4.8), layout="constrained")
        plot_bifurcation(datasets["branch"], vertical=datasets["vertical"], runs=datasets["runs"], x="spin_rpm",
                         ax=fig.add_subplot())
        return fig
    if recipe.kind == "classes":
        fig = Figure(figsize=(6.8, 5.0), layout="constrained")
        plot_class_map(datasets["classes"], ax=fig.add_subplot())
        return fig
    run = datasets["run"]
    fig = Figure(figsize=(7.4, 5.6), layout="constrained")
    top, bottom = fig.subplots(2, 1)
    plot_settle(run, predicted_tilt=run.attrs["predicted_tilt"], label=run.attrs.get("label", ""), ax=top)
    plot_settle_approach(run, predicted_tilt=run.attrs["predicted_tilt"], rate=run.attrs.get("predicted_growth_rate"),
                         ax=bottom)
    return fig
