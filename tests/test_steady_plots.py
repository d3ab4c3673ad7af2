"""Figures of the steady layer and their recipes: the artists carry the data (no pixel comparison).

References: the datasets drawn (stability flags -> solid / dashed lines, kinds -> markers, the
predicted tilt -> a horizontal line), and the closed-form class boundaries.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import continuation
import stability
from stability.errors import RecipeError
from stability.plotting.steady_plots import plot_bifurcation, plot_class_map, plot_settle, plot_settle_approach
from stability.recipes import compute, find_recipes, load_recipe, output_paths

ATLASES = Path(__file__).resolve().parents[1] / "atlases"


@pytest.fixture(scope="module")
def fold_branch():
    """A never_inverts top whose branch has a fold: stable beyond it, unstable before."""
    return continuation.steady_branch(q=-0.2, sigma=1.3, fr_inv=0.5, alpha_v=0.5)


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
    assert "|" in markers    # the cut at jellett_max


def test_bifurcation_with_vertical_states_and_runs(fold_branch):
    x = fold_branch.jellett.values
    vertical = xr.Dataset({"stability_upright": ("level", np.array([0, 0, 1, 2, 2], np.int8)),
                           "stability_inverted": ("level", np.array([2, 2, 1, 0, 0], np.int8))},
                          coords={"jellett": ("level", np.linspace(x.min(), x.max(), 5))})
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
    dashed = [ln for ln in ax.get_lines() if ln.get_linestyle() == "--"][0]
    assert np.allclose(dashed.get_ydata(), (ag / (1 - q))[q < 0])
    assert any(c.get_hatch() == "///" for c in ax.collections)   # Hugenholtz's band
    assert len(ax.collections) >= 2                              # the map and the band


def test_settle_plots_mark_the_predicted_tilt():
    t = np.linspace(0, 2000, 401)
    run = xr.Dataset({"polar_angle": ("time", 166.0 - 160 * np.exp(-t / 300))}, coords={"time": t})
    _, ax = plot_settle(run, predicted_tilt=166.0)
    level = [ln for ln in ax.get_lines() if ln.get_linestyle() == "--"]
    assert len(level) == 1 and set(level[0].get_ydata()) == {166.0}
    _, ax2 = plot_settle_approach(run, predicted_tilt=166.0, rate=-1 / 300)
    dist, ref = ax2.get_lines()[:2]
    assert np.allclose(dist.get_ydata()[1:], ref.get_ydata()[1:], rtol=1e-9)   # exp(g t) through the data


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
    path.write_text('title = "t"\nkind = "bifurcation"\npreset = "table1_measured"\nruns_rpm = [300]\n'
                    '[grid]\nalpha_v = 0.5\n')
    r = load_recipe(path)
    ds = compute(r)
    assert set(ds) == {"branch", "vertical", "runs"}
    runs = ds["runs"]
    assert float(runs.end_tilt[0]) == pytest.approx(float(runs.predicted_tilt[0]), abs=0.05)
    mtime = r.dataset_path.stat().st_mtime_ns
    compute(r)
    assert r.dataset_path.stat().st_mtime_ns == mtime    # reused
    with style():
        fig, _ = recipe_figure(r, ds)
    assert fig.axes[0].get_xlabel().startswith("equivalent upright spin (rpm)")


@pytest.mark.parametrize("text,msg", [
    ('title = "x"\nkind = "bifurcation"\nruns_rpm = [-1]\n', "runs_rpm = \\[-1\\] must be a list of spin rates > 0"),
    ('title = "x"\nkind = "bifurcation"\n[grid]\nq = 0.1\n', "grid takes alpha_v, not q"),
    ('title = "x"\nkind = "classes"\n[grid]\nq = 0.1\nsigma = "0:1:3"\n', "needs grid.q as a 1-D grid"),
    ('title = "x"\nkind = "settle"\n[grid]\nfr_inv = 0.2\n', "grid.fr_inv = 0.2 must be one of 0.3, 0.1"),
    ('title = "x"\nkind = "settle"\nt_end = -5\n', "t_end = -5 must be a number > 0"),
])
def test_bad_steady_recipes(tmp_path, text, msg):
    p = tmp_path / "r.toml"
    p.write_text(text)
    with pytest.raises(RecipeError, match=msg):
        load_recipe(p)
