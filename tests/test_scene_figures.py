"""Scene recipes (Figs. 5-9): the drawn lines carry the runs' data; recipes are checked.

Reference for the data: the simulate() datasets themselves (the figures only draw; the runs
are checked against conserved quantities and the paper in tests/test_nonlinear_*.py). The
crossing near 78 spin periods is the paper's number, held by those tests; here we check the
time axis is in spin periods (t / 2 pi, a unit conversion stated in Sec. 3(ii)).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from stability.errors import RecipeError
from stability.plotting import style
from stability.plotting.recipe_figures import recipe_figure
from stability.recipes import compute, load_recipe

ATLASES = Path(__file__).resolve().parents[1] / "atlases"


def test_fig5_recipe_lines_carry_the_runs(tmp_path):
    path = tmp_path / "fig5.toml"
    path.write_text((ATLASES / "fig5.toml").read_text())
    r = load_recipe(path)
    runs = compute(r)
    assert set(runs) == {"fr_inv_0.3", "fr_inv_0.1"}
    with style():
        fig, _ = recipe_figure(r, runs)
    ax_spin, ax_rate, ax_angle = fig.axes
    lines = ax_angle.get_lines()
    ds = runs["fr_inv_0.3"]
    assert np.allclose(lines[0].get_xdata(), ds.time.values / (2 * np.pi), rtol=0, atol=1e-12)
    assert np.array_equal(lines[0].get_ydata(), ds.polar_angle.values)
    assert [t.get_text() for t in ax_spin.get_legend().get_texts()] == ["Fr$^{-1}$ = 0.3", "Fr$^{-1}$ = 0.1"]
    assert "spin" in ax_spin.get_ylabel() and "polar angle" in ax_angle.get_ylabel()


def test_scene_recipe_checks(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('title = "x"\nkind = "scene"\nfigure = "fig10"\n')
    with pytest.raises(RecipeError, match="figure = 'fig10' is not one of fig5"):
        load_recipe(p)
    p.write_text('title = "x"\nkind = "scene"\nfigure = "fig5"\n[grid]\nq = 0.1\n')
    with pytest.raises(RecipeError, match="has no \\[grid\\]"):
        load_recipe(p)


def _scene(name: str, tmp_path):
    path = tmp_path / f"{name}.toml"
    path.write_text((ATLASES / f"{name}.toml").read_text())
    r = load_recipe(path)
    runs = compute(r)
    with style():
        return recipe_figure(r, runs)[0], runs


def test_fig8_path_coloured_by_time_until_the_flip(tmp_path):
    """Fig. 8: the drawn path is the run's k from the start to the first sample at 150 degrees
    (segments joining consecutive samples), coloured by time in spin periods (the colour
    bar's quantity), on the unit sphere."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    fig, runs = _scene("fig8", tmp_path)
    ds = runs["fr_inv_0.3"]
    ax = fig.axes[0]
    (path,) = [c for c in ax.collections if isinstance(c, Line3DCollection) and c.get_array() is not None]
    end = int(np.nonzero(ds.polar_angle.values >= 150.0)[0][0]) + 1
    periods = ds.time.values[:end] / (2 * np.pi)
    np.testing.assert_allclose(path.get_array(), 0.5 * (periods[:-1] + periods[1:]), rtol=0, atol=1e-12)
    assert path.get_array().min() >= 0 and ds.polar_angle.values[end - 2] < 150.0
    assert "spin periods" in fig.axes[1].get_ylabel()  # the colour bar
    assert ax.get_xlim() == (-1.0, 1.0) and ax.get_zlabel() == "$K_3$"


def test_fig9_panels_carry_the_cases_and_clip_the_transient(tmp_path):
    """Fig. 9: (a) friction of the sliding and rolling runs, scaled to the run after two
    periods with the off-scale initial peak named; (b) the polar angle of every case, solid
    (integrated to tolerance, with a marker each, since the sticking cases coincide) and dotted
    (the paper's scheme), the legend naming all eight; (c) the slip speed of case 4."""
    fig, runs = _scene("fig9", tmp_path)
    ax_a, ax_b, ax_c = fig.axes[:3]
    sliding = runs["fr_inv_0.3"]
    peak = float(sliding.friction_magnitude.max())
    assert ax_a.get_ylim()[1] < peak and any(f"{peak:.3g}" in t.get_text() for t in ax_a.texts)
    assert np.array_equal(ax_a.get_lines()[0].get_ydata(), sliding.friction_magnitude.values)
    lines = ax_b.get_lines()
    assert len(lines) == 8 and [ln.get_linestyle() for ln in lines] == ["-"] * 4 + [":"] * 4
    assert all(ln.get_marker() not in ("None", "", None) for ln in lines[:4])
    for k, ln in enumerate(lines[:4], start=1):
        assert np.array_equal(ln.get_ydata(), runs[f"case{k}"].polar_angle.values)
    for k, ln in enumerate(lines[4:], start=1):
        assert np.array_equal(ln.get_ydata(), runs[f"case{k}_paper_scheme"].polar_angle.values)
    assert len(ax_b.get_legend().get_texts()) == 8
    assert ax_c.get_yscale() == "log"


def test_fig6_energy_lines_carry_the_parts_and_add_up(tmp_path):
    """Fig. 6: one line per energy part, the run's values; independent check of the data
    drawn: the total is the sum of the four parts (kinetic energy of spin, transverse rotation
    and translation, and potential energy, eqs. 1-2: they are computed separately in
    stability.nonlinear.quantities), to rounding relative to the total."""
    fig, runs = _scene("fig6", tmp_path)
    ds = runs["fr_inv_0.3"]
    ax = fig.axes[0]
    names = ["energy", "kinetic_spin", "kinetic_transverse", "kinetic_translational", "potential"]
    lines = ax.get_lines()
    assert len(lines) == len(names) and len(ax.get_legend().get_texts()) == len(names)
    for ln, name in zip(lines, names):
        assert np.array_equal(ln.get_ydata(), ds[name].values)
    parts = sum(ds[n].values for n in names[1:])
    assert np.max(np.abs(parts - ds.energy.values)) <= 1e-13 * np.max(np.abs(ds.energy.values))


def test_fig7_locus_is_the_centre_position(tmp_path):
    """Fig. 7: (a) the whole locus of the centre (X0, Y0), (b) its first ten spin periods, with
    velocity arrows; equal aspect so that the locus is not distorted."""
    fig, runs = _scene("fig7", tmp_path)
    ds = runs["fr_inv_0.3"]
    ax_a, ax_b = fig.axes[:2]
    x, y = ds.position.sel(axis=1).values, ds.position.sel(axis=2).values
    assert np.array_equal(ax_a.get_lines()[0].get_xdata(), x) and np.array_equal(ax_a.get_lines()[0].get_ydata(), y)
    first = ds.time.values <= 10 * 2 * np.pi
    assert np.array_equal(ax_b.get_lines()[0].get_xdata(), x[first])
    assert ax_a.get_aspect() == 1.0 and len(ax_a.collections) == 1  # the quiver


def test_models_figure_one_panel_per_model_on_one_colour_scale(tmp_path):
    """The models side by side: one map per linear model, all on the same colour normalisation
    (so colours compare across panels), each coloured by its atlas's leading growth rate, the
    continued neutral curve on top, one colour bar."""
    from stability.grids.atlases import leading_growth_rate

    fig, data = _scene("models_q_fr_inv", tmp_path)
    names = [k for k in data if not k.endswith("_neutral")]
    assert names == ["fixed_pivot", "rolling", "rolling_eq8", "sliding"]
    maps = [ax for ax in fig.axes if ax.collections and ax.get_label() != "<colorbar>"][:4]
    assert len(maps) == 4
    norms = {(m.collections[0].norm.vmin, m.collections[0].norm.vmax) for m in maps}
    assert len(norms) == 1
    for ax, name in zip(maps, names):
        assert name in ax.get_title()
        mesh = ax.collections[0]
        z = leading_growth_rate(data[name]).transpose("fr_inv", "q").values
        assert np.array_equal(np.ma.filled(mesh.get_array(), np.nan).ravel(), z.ravel(), equal_nan=True)
        assert any(ln.get_label() == "neutral curve (continued)" for ln in ax.get_lines())
    assert sum(ax.get_label() == "<colorbar>" for ax in fig.axes) == 1
