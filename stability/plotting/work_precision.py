"""Work-precision charts: time per point against error, one marker per method.

Takes the results of any suite of :mod:`stability.performance` (a list of
:class:`~stability.performance.WorkPrecision`), so the eigenvalue, continuation and integrator
charts are drawn by the same function.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..performance import WorkPrecision

__all__ = ["work_precision_figure"]


def work_precision_figure(results: Sequence[WorkPrecision], *, target: float | None = None,
                          title: str = "", xlabel: str = "error against the reference",
                          ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Draw time per point (y) against error (x), both logarithmic.

    Parameters
    ----------
    results : sequence of WorkPrecision
        One marker each; baselines hollow, the default path a star.
    target : float, optional
        Required accuracy, drawn as a vertical line; the fastest point left of it is named.
    title : str
        Axes title.
    xlabel : str
        What the error is (e.g. "largest relative error per eigenvalue vs mpmath").
    ax : matplotlib.axes.Axes, optional
        Draw into these axes; a new figure otherwise.

    Returns
    -------
    (Figure, Axes)
    """
    if ax is None:
        fig, ax = plt.subplots(figsize=(7.0, 4.6))
    else:
        fig = ax.figure
    floor = 1e-17  # an error of exactly 0 (or below) is drawn at the floor
    for i, r in enumerate(results):
        x = max(r.error, floor)
        marker = "*" if r.default else ("o" if not r.baseline else "s")
        face = "none" if r.baseline else f"C{i % 10}"
        ax.plot([x], [r.seconds_per_point], marker=marker, markersize=13 if r.default else 8,
                linestyle="none", markerfacecolor=face, markeredgecolor=f"C{i % 10}",
                label=f"{r.method}{' [default]' if r.default else ''}: {r.seconds_per_point * 1e9:.3g} ns, "
                      f"err {r.error:.1e}")
    if target is not None:
        ax.axvline(target, color="0.4", linestyle="--", linewidth=0.8)
        ok = [r for r in results if r.error <= target]
        best = min(ok, key=lambda r: r.seconds_per_point) if ok else None
        if best is not None:
            ax.annotate(f"{best.method}: fastest at error <= {target:g}", (max(best.error, floor), best.seconds_per_point),
                        xytext=(12, -14), textcoords="offset points", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("wall time per point [s]")
    if title:
        ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="best")
    return fig, ax
