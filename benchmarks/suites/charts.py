"""Work-precision charts: time per unit of work against error, one marker per measurement.

Takes the results of any suite of :mod:`suites` (a list of records with the attributes
of :class:`~suites.records.WorkPrecision`: ``method``, ``seconds_per_point``, ``error``,
``baseline``, ``default``, ``series``, ``setting``, ``panel``, ``extra``, ``component``), so the
eigenvalue, continuation and integrator charts are drawn by the same functions. Points of one
series (a method at several settings) are joined by a line and share one legend entry;
baselines are hollow squares, the package's default path a large star.

Plotting convention of the package (stability/plotting/__init__.py): data and an optional
``ax`` in, ``(Figure, Axes)`` out; the records' classes are named for the type checker only.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from matplotlib.axes import Axes
from matplotlib.figure import Figure

if TYPE_CHECKING:  # annotations only: the charts take any objects with these attributes
    from .records import Suite, WorkPrecision

__all__ = ["suite_figure", "verdict", "work_precision_figure"]

_FLOOR = 1e-17  # an error of exactly 0 (or below) is drawn at the floor


def _x(r: WorkPrecision, x: str) -> float:
    v = r.error if x == "error" else r.extra[x]
    return max(v, _FLOOR) if x == "error" else v


def _fastest(results: Sequence[WorkPrecision], target: float) -> WorkPrecision | None:
    """The fastest path (components not ranked) with ``error <= target``."""
    ok = [r for r in results if r.error <= target and not r.component]
    return min(ok, key=lambda r: r.seconds_per_point) if ok else None


def _shown(r: WorkPrecision, x: str) -> str:
    """The point's x value for a legend entry."""
    if x == "error":
        return f"err {r.error:.1e}"
    v = r.extra[x]
    return f"err {v:.1e}" if "error" in x else f"{x} {v:g}"


def verdict(results: Sequence[WorkPrecision], target: float | None) -> str:
    """One sentence: which point is the default, and the fastest at ``error <= target``.

    Parameters
    ----------
    results : sequence of WorkPrecision
    target : float, optional
        Required accuracy.

    Returns
    -------
    str
        E.g. ``"default: kernel; fastest at error <= 1e-13: the default"``.
    """
    default = next((r for r in results if r.default), None)
    name = (
        "none marked"
        if default is None
        else f"{default.method} ({default.setting})"
        if default.setting
        else default.method
    )
    text = f"default: {name}"
    if target is None:
        return text
    best = _fastest(results, target)
    if best is None:
        return text + f"; nothing reaches error <= {target:g}"
    if default is not None and default.error > target:
        return text + f" MISSES error <= {target:g}; fastest there: {best.method} {best.setting}".rstrip()
    if best is default or (
        default is not None
        and (best.series or best.method) == (default.series or default.method)
        and best.seconds_per_point >= 0.8 * default.seconds_per_point
    ):
        # a setting of the default's own method within timing noise of it counts as the default
        if best is default:
            return text + f"; fastest at error <= {target:g}: the default"
        return text + (
            f"; fastest at error <= {target:g}: the default's method, {best.setting} "
            f"({default.seconds_per_point / best.seconds_per_point:.2f}x: within timing noise)"
        )
    return text + f"; fastest at error <= {target:g}: {best.method} {best.setting}".rstrip()


def work_precision_figure(
    results: Sequence[WorkPrecision],
    *,
    target: float | None = None,
    title: str = "",
    xlabel: str = "error against the reference",
    ylabel: str = "wall time per point [s]",
    x: str = "error",
    ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Draw time per unit of work (y) against error (x), both logarithmic.

    Parameters
    ----------
    results : sequence of WorkPrecision
        One marker each; a series of several points is one line with markers.
    target : float, optional
        Required accuracy, drawn as a vertical line; the fastest point left of it is named.
    title : str
        Axes title.
    xlabel, ylabel : str
        What the error is, and the unit of work of the time.
    x : str
        ``"error"``, or a key of ``WorkPrecision.extra`` to draw along x instead (e.g.
        ``"alpha_v"``; no floor applied).
    ax : matplotlib.axes.Axes, optional
        Draw into these axes; a new figure otherwise.

    Returns
    -------
    (Figure, Axes)
    """
    fig = ax.figure if ax is not None else Figure(figsize=(7.0, 4.6))
    ax = ax if ax is not None else fig.add_subplot()
    series: dict[str, list[WorkPrecision]] = {}
    for r in results:
        series.setdefault(r.series or r.method, []).append(r)
    for i, (name, rs) in enumerate(series.items()):
        colour = f"C{i % 10}"
        base = rs[0].baseline
        default = [r for r in rs if r.default]
        all_default = len(default) == len(rs)
        marker = "s" if base else ("*" if all_default else "o")
        if len(rs) == 1:
            r = rs[0]
            label = (
                f"{name}{' [default]' if r.default else ''}{' [baseline]' if base else ''}: "
                f"{r.seconds_per_point:.3g} s, {_shown(r, x)}"
            )
        else:
            label = f"{name}{' [default]' if all_default else ''}{' [baseline]' if base else ''} ({len(rs)} settings)"
        pts = rs  # in the order measured (the settings' order)
        ax.plot(
            [_x(r, x) for r in pts],
            [r.seconds_per_point for r in pts],
            marker=marker,
            markersize=13 if all_default else 6,
            linestyle="-" if len(rs) > 1 else "none",
            linewidth=0.8,
            color=colour,
            markerfacecolor="none" if base else colour,
            markeredgecolor=colour,
            label=label,
        )
        if len(rs) > 1 and x == "error":
            for r in pts:
                ax.annotate(
                    r.setting,
                    (_x(r, x), r.seconds_per_point),
                    xytext=(3, 3),
                    textcoords="offset points",
                    fontsize=5,
                    color=colour,
                )
        if default and not all_default:
            d = default[0]
            ax.plot(
                [_x(d, x)],
                [d.seconds_per_point],
                marker="*",
                markersize=15,
                linestyle="none",
                color=colour,
                markeredgecolor="k",
                label=f"{d.method} [default] ({d.setting}): {d.seconds_per_point:.3g} s, {_shown(d, x)}",
            )
    if target is not None:
        ax.axvline(target, color="0.4", linestyle="--", linewidth=0.8)
        best = _fastest(results, target)
        if best is not None:
            ax.annotate(
                f"fastest at error <= {target:g}: {best.method} {best.setting}".rstrip(),
                (_x(best, x), best.seconds_per_point),
                xytext=(14, 8),
                textcoords="offset points",
                fontsize=7,
                arrowprops={"arrowstyle": "-", "color": "0.5", "linewidth": 0.5},
            )
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel, fontsize=8)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=8)
    if len(series) > 4:  # room above the points for a two-column legend
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi * (hi / lo) ** 0.6)
        ax.legend(fontsize=6, loc="upper center", ncol=2)
    else:
        ax.legend(fontsize=6, loc="best")
    return fig, ax


def suite_figure(
    suite: Suite, results: Sequence[WorkPrecision], *, subtitle: str = "", axes: Sequence[Axes] | None = None
) -> tuple[Figure, list[Axes]]:
    """The chart of one suite: one panel per :class:`~suites.records.Panel`, the title
    naming the default and the fastest method at the required accuracy (:func:`verdict`).

    Parameters
    ----------
    suite : Suite
        The suite (its ``title`` and ``panels``; each panel's ``select``, ``target``, ``xlabel``,
        ``ylabel``, ``x`` and ``title``).
    results : sequence of WorkPrecision
        What its ``run`` returned.
    subtitle : str
        Run conditions (points, cores, peak memory), appended to the title.
    axes : sequence of Axes, optional
        One per panel; a new figure (a row of panels, laid out tightly) by default.

    Returns
    -------
    (Figure, list of Axes)
    """
    n = len(suite.panels)
    if axes is None:
        fig = Figure(figsize=(7.4 * n, 5.2))
        axes = list(fig.subplots(1, n, squeeze=False)[0])
        new = True
    else:
        axes = list(axes)
        if len(axes) != n:
            raise ValueError(f"axes has {len(axes)} Axes; the chart of suite {suite.name!r} draws {n} panels")
        fig, new = axes[0].figure, False
    lines = [suite.title]
    for panel, ax in zip(suite.panels, axes):
        rs = [r for r in results if r.panel == panel.select]
        work_precision_figure(rs, target=panel.target, xlabel=panel.xlabel, ylabel=panel.ylabel, x=panel.x, ax=ax)
        if panel.target is not None:
            lines.append(verdict(rs, panel.target))
        if panel.title:
            ax.set_title(panel.title, fontsize=8)
    if subtitle:
        lines.append(subtitle)
    fig.suptitle("\n".join(dict.fromkeys(lines)), fontsize=9)
    if new:
        fig.tight_layout()
    return fig, axes
