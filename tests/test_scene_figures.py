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

from stability.plotting import style
from stability.plotting.recipe_figures import recipe_figure
from stability.recipes import RecipeError, compute, load_recipe

ATLASES = Path(__file__).resolve().parents[1] / "atlases"


def test_fig5_recipe_lines_carry_the_runs(tmp_path):
    path = tmp_path / "fig5.toml"
    path.write_text((ATLASES / "fig5.toml").read_text())
    r = load_recipe(path)
    runs = compute(r)
    assert set(runs) == {"fr_inv_0.3", "fr_inv_0.1"}
    with style():
        fig = recipe_figure(r, runs)
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
