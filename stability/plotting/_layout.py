"""Where a plotting function draws: the caller's Axes, or a new figure's (the one place of that rule)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError

__all__ = ["axes_or_new", "panels_or_new"]


def axes_or_new(
    ax: Axes | None, *, figsize: tuple[float, float] | None = None, layout: str | None = None, **subplot_kw: Any
) -> tuple[Figure, Axes]:
    """``ax`` and its figure, or a new figure (``figsize``, ``layout``) with one Axes
    (``Figure.add_subplot(**subplot_kw)``, e.g. ``projection="3d"``)."""
    if ax is None:
        fig = Figure(figsize=figsize, layout=layout)
        return fig, fig.add_subplot(**subplot_kw)
    return ax.figure, ax


def panels_or_new(
    axes: Sequence[Axes] | None, n: int, figsize: tuple[float, float], *, row: bool = False, **subplots_kw: Any
) -> tuple[Figure, list[Axes]]:
    """The caller's ``n`` Axes and their figure, or a new figure (constrained layout) of ``n``
    panels in a column (a row if ``row``; ``Figure.subplots(**subplots_kw)``, e.g.
    ``sharex=True``).

    Raises
    ------
    ValueError
        If ``axes`` does not hold exactly ``n`` Axes.
    """
    if axes is not None:
        axes = list(axes)
        if len(axes) != n:
            raise InputError(f"axes has {len(axes)} Axes; this figure draws {n} panels")
        return axes[0].figure, axes
    fig = Figure(figsize=figsize, layout="constrained")
    grid = fig.subplots(1 if row else n, n if row else 1, squeeze=False, **subplots_kw)
    return fig, list(grid.ravel())
