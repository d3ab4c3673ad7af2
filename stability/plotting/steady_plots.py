"""Figures of the steady states: the states of a level, the final state, the bifurcation
diagram, the class map, a run settling.

Every function takes datasets (computed by :mod:`stability.steady` and the recipes) and an
optional ``ax``, and returns ``(Figure, Axes)``; none computes anything. Lines: stable states
solid, unstable ones dashed, marginal points (branch points, folds) markers. The states of a
level (:func:`plot_steady_states`, :func:`plot_final_state`) are drawn on the effective
potential ``U_J`` against the tilt (the curve the dataset carries): stable filled, unstable
open, marginal half filled (:data:`FILL_STYLES`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from ..errors import InputError
from ..parameters import SYMBOLS
from ..products import FLAG_NAMES
from ._layout import PERIODS_LABEL, axes_or_new, periods

__all__ = [
    "FILL_STYLES",
    "FLAG_COLOURS",
    "STABLE_STYLE",
    "UNSTABLE_STYLE",
    "X_AXES",
    "plot_bifurcation",
    "plot_class_map",
    "plot_final_state",
    "plot_settle",
    "plot_settle_approach",
    "plot_steady_states",
]

#: size of a new figure (inches)
FIGSIZE = (6.4, 4.6)
#: line styles of stable and unstable states
STABLE_STYLE = dict(linestyle="-", linewidth=2.0, color="C0")
UNSTABLE_STYLE = dict(linestyle="--", linewidth=1.3, color="C3")
#: abscissae a bifurcation diagram can use: variable of the branch -> axis label
X_AXES = {
    "jellett": "Jellett's integral J (units A0 Omega)",
    "upright_equivalent_spin": "equivalent upright spin J / (sigma (1 + q)) (units of Omega)",
    "spin_rpm": "equivalent upright spin (rpm): the launch spin of an upright top with this J",
    "spin": "equivalent upright spin ({units}): the launch spin of an upright top with this J",
}

#: marker fill style of a steady state by its stability flag (0 stable, 1 marginal, 2 unstable)
FILL_STYLES = {0: "full", 1: "left", 2: "none"}
#: marker colour of a steady state by its flag (those of the stable and unstable lines; marginal grey)
FLAG_COLOURS = {0: STABLE_STYLE["color"], 1: "0.35", 2: UNSTABLE_STYLE["color"]}
_TILT_LABEL = "tilt of the axis (deg): 0 upright, 180 inverted"

#: the special points of a branch by kind: (marker, size, colour, face colour (None: the colour), label)
_MARKERS = {
    "branch_point": ("o", 7, "k", "w", "branch point (on a vertical state)"),
    "fold": ("D", 6, "k", None, "fold in J"),
    "stability_change": ("X", 7, "m", None, "stability change"),
    "end": ("|", 12, "0.3", None, "end of the branch (cut)"),
}


def _parameters_text(attrs: dict, names: tuple[str, ...] = ("q", "sigma", "fr_inv", "alpha_v")) -> str:
    """``q = .., sigma = .., Fr^-1 = .., alpha_v = ..`` from a dataset's attributes (those it has)."""
    return ", ".join(f"{SYMBOLS.get(name, name)} = {float(attrs[name]):g}" for name in names if name in attrs)


def _level(ax: Axes, ds: xr.Dataset, prefix: str, tilt_range: tuple[float, float] | None) -> None:
    """The curve ``U_J(tilt)`` of ``ds`` and every steady state on it (its variables ``prefix +``
    ``tilt``, ``energy``, ``stability``, ``kind``), marked by its flag and labelled by kind."""
    tilt_grid, potential = ds.tilt_grid.values, ds.effective_potential.values
    ax.plot(tilt_grid, potential, color="k", linewidth=1.2, label=r"effective potential $U_J$(tilt)")
    for tilt, energy, flag, kind in zip(*(ds[prefix + v].values for v in ("tilt", "energy", "stability", "kind"))):
        flag, kind = int(flag), str(kind)
        where = f"{kind} {tilt:.4g} deg" if kind == "tilted" else kind
        style = dict(markersize=9, markeredgewidth=1.5, fillstyle=FILL_STYLES[flag], color=FLAG_COLOURS[flag])
        ax.plot([tilt], [energy], "o", **style, zorder=5, label=f"{where}: {FLAG_NAMES[flag]}")
        offset = (0, -15) if kind == "tilted" else (0, 9)
        ax.annotate(kind, (tilt, energy), xytext=offset, textcoords="offset points", ha="center", fontsize=8)
    ax.set_xlabel(_TILT_LABEL)
    ax.set_ylabel(r"$U_J = J^2/(2D) + \mu\,$Fr$^{-1}(1 + q\cos\theta)$ (units $A_0\Omega^2$)", fontsize=9)
    if tilt_range is None:
        ax.set_xlim(-5, 185)
        ax.set_xticks([0, 30, 60, 90, 120, 150, 180])
    else:
        lo, hi = float(min(tilt_range)), float(max(tilt_range))
        inside = (tilt_grid >= lo) & (tilt_grid <= hi)
        ax.set_xlim(lo, hi)
        if inside.any():
            u_lo, u_hi = float(np.min(potential[inside])), float(np.max(potential[inside]))
            pad = 0.08 * (u_hi - u_lo) or 1e-12 * max(1.0, abs(u_hi))
            ax.set_ylim(u_lo - pad, u_hi + 2 * pad)


def plot_steady_states(
    ds: xr.Dataset, *, ax: Axes | None = None, tilt_range: tuple[float, float] | None = None
) -> tuple[Figure, Axes]:
    """Every steady state of one Jellett level on its effective potential.

    The steady states of the level ``J`` are the critical points of ``U_J(c) = J^2 / (2 D(c))
    + mu Fr^-1 (1 + q c)`` on ``(-1, 1)`` and its two ends (docs/steady_states.md, the energy
    principle): a minimum is stable, a maximum unstable. The curve is the dataset's
    ``effective_potential`` over ``tilt_grid``; each state is marked at its tilt and energy
    (stable filled, unstable open, marginal half filled) and labelled by its kind.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`stability.steady_states` (``effective_potential`` over ``tilt_grid``; ``tilt``,
        ``energy``, ``stability``, ``kind`` over ``state``).
    ax : matplotlib.axes.Axes, optional
    tilt_range : (float, float), optional
        Degrees: draw only this range of tilts, the energy axis fitted to the curve there
        (the differences of energy between neighbouring states can be 1e-5 of the whole range).

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax, figsize=FIGSIZE, layout="constrained")
    _level(ax, ds, "", tilt_range)
    ax.set_title(
        f"steady states on the Jellett level J = {float(ds.attrs['jellett']):.6g}: {_parameters_text(ds.attrs)}",
        fontsize=9,
    )
    ax.legend(fontsize=7, loc="best")
    return fig, ax


def plot_final_state(
    ds: xr.Dataset, *, ax: Axes | None = None, tilt_range: tuple[float, float] | None = None
) -> tuple[Figure, Axes]:
    """Where a motion ends, on the effective potential of its Jellett level.

    The motion keeps ``J`` and loses energy, and ``E >= U_J(tilt)`` always: it ends on a steady
    state of its level below its initial energy ``E0`` (docs/steady_states.md, sec. 5). Drawn:
    ``U_J`` of the level (the dataset's ``effective_potential``), the steady states of the level
    (stable filled, unstable open, marginal half filled, labelled by kind), the initial energy
    ``E0`` (a horizontal line; the tilts where ``U_J <= E0`` shaded: the states there are
    reachable), the initial state (a cross at its tilt and ``E0``), the end (a star) and the
    method (``"jellett"`` or ``"simulation"``) in the title.

    Parameters
    ----------
    ds : xarray.Dataset
        :meth:`stability.steady.final.FinalState.to_dataset` (product ``final_state``).
    ax : matplotlib.axes.Axes, optional
    tilt_range : (float, float), optional
        Degrees: draw only this range of tilts, the energy axis fitted to the curve there.

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax, figsize=FIGSIZE, layout="constrained")
    grid, u = ds.tilt_grid.values, ds.effective_potential.values
    e0 = float(ds.initial_energy)
    reachable = dict(where=u <= e0, interpolate=True, facecolor="C2", alpha=0.15, linewidth=0.0)
    ax.fill_between(grid, u, e0, **reachable, label=r"$U_J \leq E_0$: reachable")
    ax.axhline(e0, color="C2", linestyle="--", linewidth=1.0, label=f"initial energy E0 = {e0:.8g}")
    _level(ax, ds, "candidate_", tilt_range)
    start = float(ds.initial_tilt)
    ax.plot([start], [e0], "x", markersize=8, color="C2", label=f"initial state, tilt {start:.4g} deg")
    tilt, kind, method = float(ds.tilt), str(ds.attrs["kind"]), str(ds.attrs["method"])
    if np.isfinite(tilt):
        star = dict(markersize=22, color="gold", markeredgecolor="k", zorder=4)
        ax.plot([tilt], [float(ds.energy)], "*", **star, label=f"end: {kind}, tilt {tilt:.6g} deg")
        end = f"{kind} at {tilt:.6g} deg"
    else:
        end = kind
    ax.set_title(
        f"final state (method: {method}): {end}; J = {float(ds.jellett):.6g}\n{_parameters_text(ds.attrs)}", fontsize=9
    )
    ax.legend(fontsize=7, loc="best")
    return fig, ax


def _pieces(x: np.ndarray, y: np.ndarray, stable: np.ndarray, marginal: np.ndarray):
    """Polylines of consecutive points with one verdict: each segment takes the verdict of its
    end that is not marginal (a marginal point, a fold or a branch point, joins both sides)."""
    n = len(x)
    if n < 2:
        return
    verdict = []
    for i in range(n - 1):
        if not marginal[i]:
            verdict.append(bool(stable[i]))
        elif not marginal[i + 1]:
            verdict.append(bool(stable[i + 1]))
        else:
            verdict.append(verdict[-1] if verdict else True)
    start = 0
    for i in range(1, n):
        if i == n - 1 or verdict[i] != verdict[start]:
            yield x[start : i + 1], y[start : i + 1], verdict[start]
            start = i


def plot_bifurcation(
    branch: xr.Dataset | dict,
    *,
    vertical: xr.Dataset | None = None,
    runs: xr.Dataset | None = None,
    x: str | None = None,
    launch: object = None,
    ax: Axes | None = None,
) -> tuple[Figure, Axes]:
    """Tilt of every steady state against Jellett's integral (or an equivalent spin).

    The diagram of a real top in the user's spin unit is
    ``plot_bifurcation(stability.bifurcation_diagram(top, unit="rev/s"), launch=result)``.

    Parameters
    ----------
    branch : xarray.Dataset or dict
        :func:`stability.steady_branch` (``tilt``, ``stability``, ``kind`` over ``point``,
        and the abscissa ``x``), or the dict of :func:`stability.bifurcation_diagram`
        (``"branch"``, ``"vertical"``, ``"runs"``; abscissa ``spin`` in its unit).
    vertical : xarray.Dataset, optional
        The vertical states along the same abscissa: ``x``, ``stability_upright``,
        ``stability_inverted`` over one dimension (the bifurcation recipe's ``*_vertical.nc``).
    runs : xarray.Dataset, optional
        End points of nonlinear runs: ``x`` and ``end_tilt`` over ``run`` (optionally
        ``predicted_tilt``).
    x : str, optional
        The abscissa: a key of :data:`X_AXES` present in the datasets (default ``"spin"`` when
        the branch has it, else ``"jellett"``).
    launch : object, optional
        A launch to mark, duck-typed: ``spin`` (rad/s) and ``end_tilt`` (degrees) (the result of
        ``stability.launch``); drawn at its spin in the abscissa's unit (``x = "spin"`` only),
        a vertical line at the launch's equivalent upright spin (with its ``tilt`` in degrees when
        it has one, :func:`_mark_launch`) and a marker at the tilt where its run ends.
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    (Figure, Axes)
    """
    if isinstance(branch, dict):
        vertical = branch.get("vertical") if vertical is None else vertical
        runs = branch.get("runs") if runs is None else runs
        branch = branch["branch"]
    x = ("spin" if "spin" in branch else "jellett") if x is None else x
    units = str(branch[x].attrs.get("units", "")) if x in branch else ""
    fig, ax = axes_or_new(ax, figsize=FIGSIZE, layout="constrained")
    xs = branch[x].values
    tilt = branch.tilt.values
    flags = branch.stability.values
    labelled: set[str] = set()

    def draw(pieces) -> None:  # stable solid, unstable dashed; each label once
        for px, py, stable in pieces:
            label = "stable" if stable else "unstable"
            ax.plot(px, py, **(STABLE_STYLE if stable else UNSTABLE_STYLE), label=None if label in labelled else label)
            labelled.add(label)

    draw(_pieces(xs, tilt, flags == 0, flags == 1))
    if vertical is not None:
        vx = vertical[x].values
        for name, level in (("stability_upright", 0.0), ("stability_inverted", 180.0)):
            vf = vertical[name].values
            draw(_pieces(vx, np.full(vx.shape, level), vf == 0, vf == 1))
    kinds = branch.kind.values
    for kind, (marker, size, colour, face, label) in _MARKERS.items():
        sel = kinds == kind
        if sel.any():
            style = dict(marker=marker, markersize=size, color=colour, markerfacecolor=face, linestyle="none")
            ax.plot(xs[sel], tilt[sel], **style, label=label, zorder=5)
    if runs is not None and runs.sizes.get("run", 0):
        ax.plot(runs[x].values, runs.end_tilt.values, marker="*", **_END_MARK, zorder=6, label="end of a nonlinear run")
        if "paper_run" in runs:
            for i in np.nonzero(runs.paper_run.values == 1)[0]:
                xi, yi = float(runs[x][i]), float(runs.end_tilt[i])
                ax.annotate(f"the paper's Fr$^{{-1}}$ = 0.3 run: {yi:.1f} deg", (xi, yi), **_PAPER_ARROW)
    if "stick_tilt" in branch.attrs:  # a toy with a stick: no state beyond this tilt
        st = float(branch.attrs["stick_tilt"])
        ax.axhline(st, color="C3", ls="--", lw=1.0, label=f"the stick touches ({st:.4g} deg)")
    if launch is not None:
        _mark_launch(ax, launch, x, units, float(branch.attrs.get("q", float("nan"))))
    ax.set_xlabel(X_AXES.get(x, x).format(units=units), fontsize=9)
    ax.set_ylabel(_TILT_LABEL)
    ax.set_ylim(-8, 188)
    ax.set_yticks([0, 30, 60, 90, 120, 150, 180])
    attrs = {name: float("nan") for name in ("q", "sigma", "mu", "alpha_v")} | dict(branch.attrs)
    ax.set_title(_parameters_text(attrs, ("q", "sigma", "mu", "alpha_v")), fontsize=9)
    ax.legend(fontsize=7, loc="best")
    return fig, ax


#: the marker style of where a run ends (a nonlinear run's, a launch's) on the diagram
_END_MARK = {"markersize": 11, "color": "C2", "markeredgecolor": "k", "linestyle": "none"}
#: the arrow naming the paper's run on the diagram
_PAPER_ARROW = dict(
    xytext=(-210, -70), textcoords="offset points", fontsize=7, arrowprops={"arrowstyle": "->", "linewidth": 0.6}
)


def _mark_launch(ax: Axes, launch: object, x: str, units: str, q: float) -> None:
    """A launch on the diagram: a dotted vertical line at its equivalent upright spin, a marker at
    its end tilt.

    A launch spun at ``n`` about its own axis tilted by ``theta`` has Jellett's integral
    ``J = L . (G - Q) = C n R (cos theta + q)`` (angular momentum ``C n k``; from the contact
    point Q = O - R K to G = O + q R k), and an upright launch at ``n'`` has ``C n' R (1 + q)``:
    its equivalent upright spin is ``n (cos theta + q) / (1 + q)``. Without a ``tilt`` attribute
    the launch is drawn at its spin (1.7e-4 relative to the right of it at 1 degree, q = -0.1).
    """
    import math

    from ..top import SPIN_UNITS

    if x != "spin" or units not in SPIN_UNITS:
        raise InputError(
            f"a launch is drawn on a diagram against the spin (x = 'spin' with a spin unit); this one "
            f"is against {x!r}{f' ({units})' if units else ''}"
        )
    spin = float(launch.spin) / SPIN_UNITS[units]
    tilt = getattr(launch, "tilt", None)
    if tilt is not None and math.isfinite(q):
        spin *= (math.cos(math.radians(float(tilt))) + q) / (1.0 + q)
    end = float(launch.end_tilt)
    ax.axvline(spin, color="C2", linestyle=":", linewidth=1.2, label=f"launch: {spin:.4g} {units}", zorder=4)
    ax.plot([spin], [end], marker="P", **_END_MARK, zorder=7, label=f"end of the launch's run: {end:.1f} deg")


_CLASS_COLOURS = ListedColormap(["white", "#9ecae1", "#fdae6b", "#a1d99b"])


def plot_class_map(
    ds: xr.Dataset, *, ax: Axes | None = None, mark: tuple[float, float] | None = (-0.1, 1.0)
) -> tuple[Figure, Axes]:
    """The high-spin classes over ``(q, sigma)`` with the closed-form boundaries.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`stability.class_atlas` over ``(q, sigma)`` (``top_class``, ``sigma_never_inverts``,
        ``sigma_hangs``, ``sigma_domain``).
    ax : matplotlib.axes.Axes, optional
    mark : (q, sigma), optional
        A top to mark with a star (default the paper's, ``q = -0.1``, ``sigma = 1``).

    Returns
    -------
    (Figure, Axes)

    Raises
    ------
    ValueError
        If the dataset's grid is not ``(q, sigma)`` (select the other dimensions first).
    """
    if set(ds.top_class.dims) != {"q", "sigma"}:
        raise InputError(
            f"the class map is drawn over (q, sigma); this dataset's grid is "
            f"({', '.join(map(str, ds.top_class.dims)) or 'none'}): give class_atlas 1-D grids of q and "
            "sigma, or select the other dimensions first (ds.sel(...))"
        )
    fig, ax = axes_or_new(ax, figsize=FIGSIZE, layout="constrained")
    q, sigma = ds.q.values, ds.sigma.values
    code = ds.top_class.transpose("sigma", "q").values
    ax.pcolormesh(q, sigma, code, cmap=_CLASS_COLOURS, vmin=-1.5, vmax=2.5, shading="nearest")
    b1 = ds.sigma_never_inverts.values
    b2 = ds.sigma_hangs.values
    top = ds.sigma_domain.values
    ax.plot(q, np.minimum(b1, top), color="k", linewidth=1.2, label=r"$\sigma = A_G/(1+q)$: never inverts above")
    neg = q < 0
    ax.plot(q[neg], b2[neg], color="k", linewidth=1.2, linestyle="--", label=r"$\sigma = A_G/(1-q)$: hangs below")
    ax.plot(q, top, color="0.4", linewidth=0.8, linestyle=":", label=r"$\sigma = 2 A_G$ (domain)")
    band = neg & np.isfinite(b2)
    hatched = dict(facecolor="none", edgecolor="0.25", hatch="///", linewidth=0.0)
    hugenholtz = r"Hugenholtz: $1-\alpha < A_G/C < 1+\alpha$"
    ax.fill_between(q[band], b2[band], np.minimum(b1, top)[band], **hatched, label=hugenholtz)
    if mark is not None:
        ax.plot([mark[0]], [mark[1]], "*", markersize=12, color="k", label="the paper's top")
    handles, labels = ax.get_legend_handles_labels()
    for name, colour in zip(("never inverts", "inverts", "hangs at a tilt"), _CLASS_COLOURS.colors[1:]):
        handles.append(Patch(facecolor=colour, edgecolor="0.5"))
        labels.append(name)
    ax.legend(handles, labels, fontsize=7, loc="upper left", ncol=2)
    ax.set(xlabel="q (centre-of-mass offset; q < 0: G below O)", ylabel=r"$\sigma = C/A_0$")
    ax.set_ylim(0, max(2.0, float(np.nanmax(sigma))))
    ax.set_xlim(q.min(), q.max())
    ax.set_title(f"high-spin classes, {SYMBOLS['mu']} = {float(ds.mu):g}", fontsize=9)
    return fig, ax


def _time_axis(ax: Axes, run: xr.Dataset, in_periods: bool) -> np.ndarray:
    """A run's times in spin periods (``t / 2 pi``) or in ``1 / Omega``, and the axis labelled so."""
    ax.set_xlabel(PERIODS_LABEL if in_periods else r"time ($1/\Omega$)")
    return periods(run) if in_periods else run.time.values


def plot_settle(
    run: xr.Dataset, *, predicted_tilt: float, ax: Axes | None = None, label: str = "", periods: bool = True
) -> tuple[Figure, Axes]:
    """The polar angle of a run against time, with the predicted final tilt as a line.

    Parameters
    ----------
    run : xarray.Dataset
        :func:`stability.simulate` (``polar_angle`` over ``time``).
    predicted_tilt : float
        :func:`stability.final_state`'s tilt, degrees (a horizontal dashed line).
    ax : matplotlib.axes.Axes, optional
    label : str
        Legend text of the run.
    periods : bool
        Time in spin periods (``t / 2 pi``) rather than ``1 / Omega``.

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax, figsize=FIGSIZE, layout="constrained")
    t = _time_axis(ax, run, periods)
    ax.plot(t, run.polar_angle.values, color="C0", linewidth=1.0, label=label or "nonlinear run")
    predicted = f"predicted final tilt {predicted_tilt:.3f} deg (Jellett's integral)"
    ax.axhline(predicted_tilt, color="C3", linestyle="--", linewidth=1.2, label=predicted)
    ax.axhline(180.0, color="0.5", linestyle=":", linewidth=0.8, label="complete inversion (180 deg)")
    ax.set_ylabel("polar angle of the axis (deg)")
    ax.legend(fontsize=7, loc="lower right")
    return fig, ax


def plot_settle_approach(
    run: xr.Dataset, *, predicted_tilt: float, rate: float | None = None, ax: Axes | None = None, periods: bool = True
) -> tuple[Figure, Axes]:
    """Distance of the polar angle from the predicted final tilt against time (log scale).

    Parameters
    ----------
    run : xarray.Dataset
        :func:`stability.simulate`.
    predicted_tilt : float
        Degrees.
    rate : float, optional
        The end state's slowest decay rate (``growth_rate`` of :func:`stability.steady_states`,
        negative, units of ``Omega``): drawn as ``exp(rate t)`` through the last sample.
    ax : matplotlib.axes.Axes, optional
    periods : bool
        Time in spin periods.

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax, figsize=FIGSIZE, layout="constrained")
    t = run.time.values
    tt = _time_axis(ax, run, periods)
    dist = np.abs(run.polar_angle.values - predicted_tilt)
    ax.semilogy(tt, dist, color="C0", linewidth=0.8, label="|polar angle - predicted tilt|")
    if rate is not None and rate < 0:
        ref = dist[-1] * np.exp(rate * (t - t[-1]))
        slowest = f"exp(g t), g = {rate:.3g}: the end state's slowest mode"
        ax.semilogy(tt, ref, color="C3", linestyle="--", linewidth=1.0, label=slowest)
    for level, style in ((0.05, ":"), (0.01, "-.")):
        ax.axhline(level, color="0.4", linestyle=style, linewidth=0.8, label=f"{level:g} deg")
    ax.set_ylim(max(1e-6, float(np.nanmin(dist[dist > 0])) / 3 if np.any(dist > 0) else 1e-6), 200.0)
    ax.set_ylabel("distance from the predicted tilt (deg)")
    ax.legend(fontsize=7, loc="upper right")
    return fig, ax
