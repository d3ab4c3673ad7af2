"""Figures of the steady layer and their recipes: the artists carry the data (no pixel comparison).

References: the datasets drawn (stability flags -> solid / dashed lines and filled / open /
half-filled markers, kinds -> markers and labels, the predicted tilt and the initial energy ->
horizontal lines), the closed-form class boundaries, and for the effective potential the
datasets carry, an independent evaluation at 30 digits (mpmath) from its definition: at each
tilt, the kinetic energy of the no-slip state ``omega = lam (K + q k)`` with ``I_G`` built as a
matrix and ``lam`` fixed by ``(K + q k) . I_G omega = J``, plus the potential energy.
"""

from __future__ import annotations

from pathlib import Path

import mpmath
import numpy as np
import pytest
import xarray as xr

import stability
from stability.errors import RecipeError
from stability.nonlinear.scene import INITIAL_CONDITIONS
from stability.plotting.steady_plots import (
    FILL_STYLES,
    plot_bifurcation,
    plot_class_map,
    plot_final_state,
    plot_settle,
    plot_settle_approach,
    plot_steady_states,
)
from stability.recipes import compute, find_recipes, load_recipe, output_paths

ATLASES = Path(__file__).resolve().parents[1] / "atlases"


PAPER = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
MU = 2.28


def potential_reference(tilts_deg, jellett, *, q, sigma, fr_inv, mu=MU):
    """``U_J`` at each tilt from its definition, at 30 digits: ``I_G = A_G 1 + (sigma - A_G) k k^T``
    as a matrix, the no-slip state ``omega = lam r`` (``r = K + q k``) with ``r . I_G omega = J``,
    its kinetic energy ``omega . I_G omega / 2`` (``V_G = 0``) plus ``mu fr_inv z_G``,
    ``z_G = 1 + q cos(tilt)``. No use of the closed form ``D(c)`` or of the package."""
    out = []
    with mpmath.workdps(30):
        q_, s_, f_, m_, j_ = (mpmath.mpf(x) for x in (q, sigma, fr_inv, mu, jellett))
        a_g = 1 - m_ * q_**2
        for t in tilts_deg:
            th = mpmath.radians(mpmath.mpf(float(t)))
            k = mpmath.matrix([mpmath.sin(th), 0, mpmath.cos(th)])
            inertia = a_g * mpmath.eye(3) + (s_ - a_g) * (k * k.T)
            r = mpmath.matrix([0, 0, 1]) + q_ * k
            lam = j_ / (r.T * inertia * r)[0]
            omega = lam * r
            kinetic = (omega.T * inertia * omega)[0] / 2
            out.append(float(kinetic + m_ * f_ * (1 + q_ * k[2])))
    return np.array(out)


def _state_markers(ax):
    """The single-point markers of the states (circles), by tilt."""
    return sorted(
        (ln for ln in ax.get_lines() if ln.get_marker() == "o" and len(ln.get_xdata()) == 1),
        key=lambda ln: ln.get_xdata()[0],
    )


@pytest.fixture(scope="module")
def fold_branch():
    """A never_inverts top whose branch has a fold: stable beyond it, unstable before."""
    return stability.steady_branch(q=-0.2, sigma=1.3, fr_inv=0.5, alpha_v=0.5)


def _lines(ax, style):
    return [ln for ln in ax.get_lines() if ln.get_linestyle() == style and len(ln.get_xdata()) > 1]


def test_bifurcation_lines_follow_the_flags(fold_branch):
    fig, ax = plot_bifurcation(fold_branch)
    assert fig is ax.figure
    solid, dashed = _lines(ax, "-"), _lines(ax, "--")
    assert solid and dashed
    flags = fold_branch.stability.values
    tilt = fold_branch.tilt.values
    # every point drawn solid is stable or marginal, every dashed one unstable or marginal
    for lines, bad in ((solid, 2), (dashed, 0)):
        for ln in lines:
            for y in ln.get_ydata():
                assert flags[np.argmin(np.abs(tilt - y))] != bad
    fold = fold_branch.where(fold_branch.kind == "fold", drop=True)
    markers = {ln.get_marker(): ln for ln in ax.get_lines() if ln.get_linestyle() in ("None", "none")}
    assert np.allclose(markers["D"].get_ydata(), fold.tilt.values)
    bp = fold_branch.where(fold_branch.kind == "branch_point", drop=True)
    assert np.allclose(markers["o"].get_ydata(), bp.tilt.values)
    assert "|" in markers  # the cut at jellett_max


def test_bifurcation_with_vertical_states_and_runs(fold_branch):
    x = fold_branch.jellett.values
    vertical = xr.Dataset(
        {
            "stability_upright": ("level", np.array([0, 0, 1, 2, 2], np.int8)),
            "stability_inverted": ("level", np.array([2, 2, 1, 0, 0], np.int8)),
        },
        coords={"jellett": ("level", np.linspace(x.min(), x.max(), 5))},
    )
    runs = xr.Dataset({"end_tilt": ("run", [0.0, 120.0]), "jellett": ("run", [x.min(), x.max()])})
    _, ax = plot_bifurcation(fold_branch, vertical=vertical, runs=runs)
    flat = [ln for ln in ax.get_lines() if len(ln.get_ydata()) > 1 and np.ptp(ln.get_ydata()) == 0]
    up = [ln for ln in flat if ln.get_ydata()[0] == 0.0]
    assert {ln.get_linestyle() for ln in up} == {"-", "--"}
    star = [ln for ln in ax.get_lines() if ln.get_marker() == "*"]
    assert len(star) == 1 and list(star[0].get_ydata()) == [0.0, 120.0]


def test_class_map_draws_the_closed_form_boundaries():
    q = np.linspace(-0.6, 0.6, 121)
    ds = stability.class_atlas(q=q, sigma=np.linspace(0.01, 2, 60))
    _, ax = plot_class_map(ds)
    ag = 1 - 2.28 * q * q
    solid = [ln for ln in ax.get_lines() if ln.get_linestyle() == "-" and len(ln.get_xdata()) == q.size]
    assert np.allclose(solid[0].get_ydata(), np.minimum(ag / (1 + q), 2 * ag))
    dashed = next(ln for ln in ax.get_lines() if ln.get_linestyle() == "--")
    assert np.allclose(dashed.get_ydata(), (ag / (1 - q))[q < 0])
    assert any(c.get_hatch() == "///" for c in ax.collections)  # Hugenholtz's band
    assert len(ax.collections) >= 2  # the map and the band


def test_settle_plots_mark_the_predicted_tilt():
    t = np.linspace(0, 2000, 401)
    run = xr.Dataset({"polar_angle": ("time", 166.0 - 160 * np.exp(-t / 300))}, coords={"time": t})
    _, ax = plot_settle(run, predicted_tilt=166.0)
    level = [ln for ln in ax.get_lines() if ln.get_linestyle() == "--"]
    assert len(level) == 1 and set(level[0].get_ydata()) == {166.0}
    _, ax2 = plot_settle_approach(run, predicted_tilt=166.0, rate=-1 / 300)
    dist, ref = ax2.get_lines()[:2]
    assert np.allclose(dist.get_ydata()[1:], ref.get_ydata()[1:], rtol=1e-9)  # exp(g t) through the data


def test_steady_recipes_load():
    names = {r.name: r for r in find_recipes(ATLASES)}
    assert {"bifurcation_toy", "top_classes", "settle_fr03"} <= set(names)
    assert names["bifurcation_toy"].kind == "bifurcation" and names["bifurcation_toy"].runs_rpm
    assert names["settle_fr03"].t_end > 0
    assert len(output_paths(names["bifurcation_toy"])) == 4


def test_bifurcation_recipe_compute_and_draw(tmp_path):
    """A small recipe (one run) end to end: the datasets, their cache, the figure."""
    from stability.plotting import style
    from stability.plotting.recipe_figures import recipe_figure

    path = tmp_path / "bif.toml"
    path.write_text(
        'title = "t"\nkind = "bifurcation"\npreset = "table1_measured"\nruns_rpm = [300]\n[grid]\nalpha_v = 0.5\n'
    )
    r = load_recipe(path)
    ds = compute(r)
    assert set(ds) == {"branch", "vertical", "runs"}
    runs = ds["runs"]
    assert float(runs.end_tilt[0]) == pytest.approx(float(runs.predicted_tilt[0]), abs=0.05)
    mtime = r.dataset_path.stat().st_mtime_ns
    compute(r)
    assert r.dataset_path.stat().st_mtime_ns == mtime  # reused
    with style():
        fig, _ = recipe_figure(r, ds)
    assert fig.axes[0].get_xlabel().startswith("equivalent upright spin (rpm)")


@pytest.mark.parametrize(
    "text,msg",
    [
        (
            'title = "x"\nkind = "bifurcation"\nruns_rpm = [-1]\n',
            "runs_rpm = \\[-1\\] must be a list of spin rates > 0",
        ),
        ('title = "x"\nkind = "bifurcation"\n[grid]\nq = 0.1\n', "grid takes alpha_v, not q"),
        ('title = "x"\nkind = "classes"\n[grid]\nq = 0.1\nsigma = "0:1:3"\n', "needs grid.q as a 1-D grid"),
        ('title = "x"\nkind = "settle"\n[grid]\nfr_inv = 0.2\n', "grid.fr_inv = 0.2 must be one of 0.3, 0.1"),
        ('title = "x"\nkind = "settle"\nt_end = -5\n', "t_end = -5 must be a number > 0"),
    ],
)
def test_bad_steady_recipes(tmp_path, text, msg):
    p = tmp_path / "r.toml"
    p.write_text(text)
    with pytest.raises(RecipeError, match=msg):
        load_recipe(p)


def test_steady_states_carry_the_effective_potential():
    """``effective_potential`` over ``tilt_grid`` (0 to 180 degrees) is U_J of the level: against
    the 30-digit evaluation from the definition (module docstring), within 1e-14 relative (the
    float evaluation takes about ten roundings of an O(1) quantity, and the angle is rounded
    once: a few 1e-16; measured 2.2e-16 here, 4.4e-16 on other tops). The states sit at its
    critical points and ends: the tilted one, stable, is a minimum of the reference curve."""
    ds = stability.steady_states(**PAPER, jellett=-0.9001185873)
    grid = ds.tilt_grid.values
    assert grid[0] == 0.0 and grid[-1] == 180.0 and ds.effective_potential.dims == ("tilt_grid",)
    ref = potential_reference(grid, -0.9001185873, **{k: PAPER[k] for k in ("q", "sigma", "fr_inv")})
    assert np.max(np.abs(ds.effective_potential.values / ref - 1)) < 1e-14
    tilted = ds.isel(state=1)
    t = float(tilted.tilt)
    around = potential_reference(
        [t - 0.25, t, t + 0.25], -0.9001185873, **{k: PAPER[k] for k in ("q", "sigma", "fr_inv")}
    )
    assert around[1] < around[0] and around[1] < around[2] and int(tilted.stability) == 0
    assert float(tilted.energy) == pytest.approx(around[1], rel=1e-14)


def test_steady_states_figure_marks_every_state_on_the_curve():
    """The curve is the dataset's; each state a circle at (tilt, energy), filled when stable,
    open when unstable, half filled when marginal, labelled by its kind."""
    ds = stability.steady_states(**PAPER, jellett=-0.9001185873)
    fig, ax = plot_steady_states(ds)
    assert fig is ax.figure
    (curve,) = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 1]
    assert np.array_equal(curve.get_xdata(), ds.tilt_grid.values)
    assert np.array_equal(curve.get_ydata(), ds.effective_potential.values)
    markers = _state_markers(ax)
    assert [ln.get_xdata()[0] for ln in markers] == list(ds.tilt.values)
    assert [ln.get_ydata()[0] for ln in markers] == list(ds.energy.values)
    assert [ln.get_fillstyle() for ln in markers] == ["none", "full", "none"]  # unstable, stable, unstable
    assert [ln.get_label() for ln in markers] == ["upright: unstable", "tilted 166 deg: stable", "inverted: unstable"]
    assert sorted(t.get_text() for t in ax.texts) == ["inverted", "tilted", "upright"]
    assert "J = -0.900119" in ax.get_title() and ax.get_xlabel().startswith("tilt of the axis (deg)")


def test_marginal_states_are_half_filled():
    """At fr_inv = 0 a vertical state at a minimum of U_J is marginal, not stable (a structural
    zero: the continua of rolling motions next to it, docs/steady_states.md sec. 4.2); its marker
    is half filled (FILL_STYLES[1]). A never_inverts top (sigma (1 + q) > A_G): both vertical
    states marginal, the tilted one between them unstable."""
    ds = stability.steady_states(q=-0.1, sigma=1.2, fr_inv=0.0, alpha_v=0.5, jellett=0.4)
    flags = list(ds.stability.values)
    assert flags == [1, 2, 1]
    _, ax = plot_steady_states(ds)
    assert [ln.get_fillstyle() for ln in _state_markers(ax)] == [FILL_STYLES[f] for f in flags]
    assert FILL_STYLES == {0: "full", 1: "left", 2: "none"}


def test_tilt_range_zooms_on_the_curve():
    """``tilt_range`` limits the tilt axis and fits the energy axis to the curve there (the
    tilted and the inverted state differ by 6.6e-6 in energy, invisible on the whole range)."""
    ds = stability.steady_states(**PAPER, jellett=-0.9001185873)
    _, ax = plot_steady_states(ds, tilt_range=(150.0, 180.0))
    assert ax.get_xlim() == (150.0, 180.0)
    inside = ds.effective_potential.values[ds.tilt_grid.values >= 150.0]
    lo, hi = ax.get_ylim()
    assert lo < inside.min() and hi > inside.max() and hi - lo < 2 * np.ptp(inside)


def test_final_state_figure():
    """The paper's Fr^-1 = 0.3 run: U_J of its level (the independent reference at J0, 1e-14),
    the initial energy E0 as a dashed line, the reachable tilts (U_J <= E0) shaded, the initial
    state, the end (a star at the final tilt and energy) and the method in the title."""
    end = stability.final_state(**PAPER, **INITIAL_CONDITIONS[0.3])
    ds = end.to_dataset()
    ref = potential_reference(ds.tilt_grid.values, end.jellett, **{k: PAPER[k] for k in ("q", "sigma", "fr_inv")})
    assert np.max(np.abs(ds.effective_potential.values / ref - 1)) < 1e-14
    fig, ax = plot_final_state(ds)
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    e0 = lines[f"initial energy E0 = {end.initial_energy:.8g}"]
    assert list(e0.get_ydata()) == [end.initial_energy] * 2 and e0.get_linestyle() == "--"
    (star,) = [ln for ln in ax.get_lines() if ln.get_marker() == "*"]
    assert star.get_xdata()[0] == end.tilt and star.get_ydata()[0] == end.energy
    assert star.get_label() == f"end: tilted, tilt {end.tilt:.6g} deg"
    (start,) = [ln for ln in ax.get_lines() if ln.get_marker() == "x"]
    assert start.get_xdata()[0] == pytest.approx(end.initial_tilt) and start.get_ydata()[0] == end.initial_energy
    assert [ln.get_fillstyle() for ln in _state_markers(ax)] == ["none", "full", "none"]
    assert ax.get_title().startswith("final state (method: jellett): tilted at 166.018 deg")
    (shade,) = ax.collections
    verts = np.concatenate([p.vertices for p in shade.get_paths()])
    assert verts[:, 1].max() <= end.initial_energy * (1 + 1e-15)


def test_final_state_figure_without_an_end():
    """A bistable level with simulation=False: method "simulation", kind "undecided", no end
    marker; the two stable states are filled, the unstable tilted one between them open."""
    end = stability.final_state(
        q=-0.1,
        sigma=1.2,
        fr_inv=0.3,
        alpha_v=0.5,
        omega=[0.1, 0.0, 1.0],
        k=[0.34, 0.0, 0.94],
        velocity=[0.05, 0.0],
        simulation=False,
    )
    assert end.method == "simulation" and end.kind == "undecided"
    _, ax = plot_final_state(end.to_dataset())
    assert not [ln for ln in ax.get_lines() if ln.get_marker() == "*"]
    assert ax.get_title().startswith("final state (method: simulation): undecided")
    assert [ln.get_fillstyle() for ln in _state_markers(ax)] == ["full", "none", "full"]


def test_class_map_needs_a_q_sigma_grid():
    ds = stability.class_atlas(q=np.linspace(-0.5, 0.5, 5), sigma=np.linspace(0.1, 1.5, 4), mu=[2.0, 2.28])
    with pytest.raises(
        ValueError,
        match=r"the class map is drawn over \(q, sigma\); this dataset's grid is "
        r"\(q, sigma, mu\)",
    ):
        ds.tippe.plot()
    fig, _ = ds.sel(mu=2.28).tippe.plot()
    assert fig.axes
