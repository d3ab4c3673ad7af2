"""Recipes and figures: artists are inspected, not pixels.

References: the lines drawn must carry the data of the dataset they were drawn from, mode by
mode as tracked by stability.linear.modes (checked against a closed form below); labels name the
parameters; recipes refuse malformed files with the file and key named.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import stability
from stability.errors import RecipeError
from stability.grids.atlases import leading_growth_rate
from stability.linear.modes import principal_mode, track_modes
from stability.plotting import plot_growth_rate, style
from stability.plotting.maps import plot_stability_map
from stability.plotting.recipe_figures import recipe_figure
from stability.recipes import compute, find_recipes, load_recipe

ATLASES = Path(__file__).resolve().parents[1] / "atlases"


def test_track_modes_follows_crossing_branches():
    """Two straight branches s = t and s = 1 - t cross at t = 1/2; sorting by real part swaps
    them there, tracking must not (closed form: each column stays linear in t)."""
    t = np.linspace(0, 1, 21)
    a, b = t + 0.1j, (1 - t) - 0.1j
    sorted_rows = np.sort_complex(np.stack([a, b], axis=1))[:, ::-1]
    tr = track_modes(sorted_rows)
    col = 0 if tr[0, 0] == a[0] else 1
    assert np.allclose(tr[:, col], a) and np.allclose(tr[:, 1 - col], b)


def test_principal_mode_closed_form_at_zero_gravity():
    """fr_inv = 0, alpha_v = 0 (free top): s = 0 and A_G s^2 - i sigma s = 0, so the non-zero
    neutral mode is i sigma / A_G; the principal (tracked) branch's frequency must be it."""
    q = np.linspace(-0.3, 0.3, 31)
    ev = stability.eigenvalues("sliding", q=q, fr_inv=0.0, sigma=1.0, alpha_v=0.0)
    s = principal_mode(ev)
    nonzero = np.abs(s) > 0
    assert np.allclose(s[nonzero], 1j / (1 - 2.28 * q[nonzero] ** 2), rtol=1e-13)


def _quadratic_roots_at_zero_gravity(q, sigma, alpha_v, mu=2.28):
    """fr_inv = 0: eq. (11)'s characteristic cubic is s times the quadratic
    mu A_G s^2 + (alpha_v A_C - i mu sigma) s - i alpha_v (sigma + mu (1 + q)) = 0
    (A_G = 1 - mu q^2, A_C = 1 + mu (1 + 2q); tests/test_neutral.py), solved by the formula."""
    a = mu * (1 - mu * q * q)
    b = alpha_v * (1 + mu * (1 + 2 * q)) - 1j * mu * sigma
    c = -1j * alpha_v * (sigma + mu * (1 + q))
    d = np.sqrt(b * b - 4 * a * c + 0j)
    return (-b + d) / (2 * a), (-b - d) / (2 * a)


def test_principal_mode_and_map_colour_skip_the_structural_zero():
    """Fig. 3(c)-(d) at sigma = 1.2 (stable for every q): the structural zero root s = 0 is
    neutral everywhere, so it used to be the "principal" (largest growth) mode, and the figure
    showed a flat zero. The principal mode must be a root of the quadratic factor (closed form
    above; relative 1e-12: the kernel's roots are good to ~1e-15, the formula to ~1e-14 here)
    and decay; the maps' colour (leading_growth_rate) is the larger real part of the two
    quadratic roots, while max_growth_rate stays 0 and the flag marginal (by structure)."""
    q = np.linspace(-0.4, 0.4, 41)
    ds = stability.atlas("sliding", q=q, fr_inv=0.0, sigma=1.2, alpha_v=0.5)
    s = principal_mode((ds.growth_rate + 1j * ds.frequency).transpose("q", "mode").values)
    r1, r2 = _quadratic_roots_at_zero_gravity(q, 1.2, 0.5)
    near = np.minimum(np.abs(s - r1) / np.abs(r1), np.abs(s - r2) / np.abs(r2))
    assert np.all(near < 1e-12) and np.all(s.real < 0)
    lead = leading_growth_rate(ds).values
    np.testing.assert_allclose(lead, np.maximum(r1.real, r2.real), rtol=1e-11)
    assert np.all(ds.max_growth_rate.values == 0) and np.all(ds.stability.values == 1)
    fig, ax = plot_growth_rate(ds, "q", mode="principal")
    assert np.array_equal(ax.get_lines()[0].get_ydata(), s.real)
    # an atlas that crosses fr_inv = 0 keeps the zero mode on that line (it continues into the
    # small mode of real part -1.57e-2 fr_inv^2 at q = -0.1: a colour jump there would be false)
    cross = stability.atlas(
        "sliding", q=-0.1, fr_inv=np.linspace(0, 0.2, 5), sigma=np.linspace(1.1, 1.9, 5), alpha_v=0.5
    )
    assert np.array_equal(leading_growth_rate(cross).values, cross.max_growth_rate.values)


def test_lines_carry_the_data():
    ds = stability.atlas("sliding", q=np.linspace(-0.4, 0.4, 41), fr_inv=[0.0, 1.0], sigma=1.0, alpha_v=0.5)
    fig, ax = plot_growth_rate(ds, "q", mode="leading")
    lines = ax.get_lines()[:2]
    assert [ln.get_label() for ln in lines] == ["Fr$^{-1}$ = 0", "Fr$^{-1}$ = 1"]
    for ln, f in zip(lines, (0.0, 1.0)):
        assert np.array_equal(ln.get_xdata(), ds.q.values)
        assert np.array_equal(ln.get_ydata(), ds.max_growth_rate.sel(fr_inv=f).values)
    assert "growth rate" in ax.get_ylabel() and ax.get_xlabel() == "q"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["Fr$^{-1}$ = 0", "Fr$^{-1}$ = 1"]


def test_map_draws_the_neutral_contour():
    ds = stability.atlas(
        "sliding",
        q=np.linspace(-0.6, 0.6, 61),
        fr_inv=0.0,
        sigma=np.linspace(0.05, 1.9, 38),
        alpha_v=0.5,
        mask_unphysical=True,
    )
    fig, ax = plot_stability_map(ds, "q", "sigma")
    assert ax.get_xlabel() == "q" and ax.get_ylabel() == r"$\sigma$"
    # the neutral contour approximates sigma = (1 - mu q^2)/(1 + q) (closed form, docs/models.md)
    cs = [c for c in ax.collections if c.__class__.__name__ in ("QuadContourSet", "ContourSet")]
    assert cs, "no neutral contour drawn"
    verts = np.concatenate([p.vertices for p in cs[0].get_paths() if len(p.vertices)])
    qq, ss = verts[:, 0], verts[:, 1]
    closed = (1 - 2.28 * qq**2) / (1 + qq)
    inside = ss < 2 * (1 - 2.28 * qq**2) - 0.05  # away from the masked domain edge
    # the contour of the grid's linear interpolant lies within one cell of the true zero set
    # where the growth rate is monotone across the cell: one sigma spacing, 0.05
    assert np.max(np.abs(ss[inside] - closed[inside])) < 0.05


def test_all_recipes_load():
    recipes = find_recipes(ATLASES)
    assert {r.name for r in recipes} >= {
        "fig3ab",
        "fig3cd",
        "fig4",
        "map_q_sigma",
        "map_q_fr_inv",
        "map_sigma_fr_inv",
        "models_q_fr_inv",
    }


def test_recipe_compute_reuse_and_draw(tmp_path):
    src = (ATLASES / "fig4.toml").read_text().replace('q = "-0.46:0.46:369"', 'q = "-0.4:0.4:21"')
    path = tmp_path / "fig4.toml"
    path.write_text(src)
    r = load_recipe(path)
    ds = compute(r)["sliding"]
    assert r.dataset_path.exists() and ds.attrs["recipe_digest"] == r.digest
    mtime = r.dataset_path.stat().st_mtime_ns
    compute(r)  # up to date: reused, not rewritten
    assert r.dataset_path.stat().st_mtime_ns == mtime
    with style():
        fig, _ = recipe_figure(r, {"sliding": ds})
    ax = fig.axes[0]
    assert len(ax.get_legend().get_texts()) == 6  # alpha_v = 0.1 ... 5


def test_recipe_cache_invalidated_by_other_code(tmp_path, monkeypatch):
    """A dataset computed by other code (another version, a local edit) is recomputed: the
    digest covers the package source as well as the recipe."""
    import stability.recipes as recipes

    src = (ATLASES / "fig4.toml").read_text().replace('q = "-0.46:0.46:369"', 'q = "-0.4:0.4:5"')
    path = tmp_path / "fig4.toml"
    path.write_text(src)
    r = load_recipe(path)
    compute(r)
    mtime = r.dataset_path.stat().st_mtime_ns
    monkeypatch.setattr(recipes, "code_fingerprint", lambda: "other code")
    r2 = load_recipe(path)
    assert r2.digest != r.digest
    ds = compute(r2)["sliding"]
    assert ds.attrs["recipe_digest"] == r2.digest
    assert r.dataset_path.stat().st_mtime_ns != mtime


@pytest.mark.parametrize(
    "text,msg",
    [
        ('title = "x"\nkind = "pie"\n[grid]\nq = 0.1', "kind = 'pie' is not one of"),
        (
            'title = "x"\nkind = "lines"\n[grid]\nq = 0.1\nfr_inv = 0.0\nsigma = 1.0\nalpha_v = 0.5',
            "'q' must be a 1-D grid",
        ),
        ('title = "x"\nkind = "lines"\ncolour = 1\n[grid]\nq = "0:1:3"', "unknown keys colour"),
        ('kind = "lines"\n[grid]\nq = "0:1:3"', "the key 'title' is required"),
        ('title = "x"\nkind = "lines"\n[grid]\nq = "0:1"', "grid.q = '0:1'"),
        ('title = "x" kind', "not valid TOML"),
    ],
)
def test_bad_recipes(tmp_path, text, msg):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(RecipeError, match=msg):
        load_recipe(p)


def test_neutral_curve_overlay_and_fold_marker():
    """The continued curve drawn on a map passes through the closed-form fold
    (q*, sigma*) = (-1 + sqrt(1 - 1/mu), 2 (mu - sqrt(mu (mu - 1)))) (docs/models.md), marked."""
    import stability

    mu = 2.28
    curve = stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5, mu=mu))
    ds = stability.atlas(
        "sliding",
        q=np.linspace(-0.6, 0.6, 25),
        fr_inv=0.0,
        sigma=np.linspace(0.05, 1.9, 20),
        alpha_v=0.5,
        mask_unphysical=True,
    )
    fig, ax = plot_stability_map(ds, "q", "sigma", curve=curve)
    folds = [ln for ln in ax.get_lines() if ln.get_label() == "fold"]
    assert len(folds) == 1
    qf, sf = folds[0].get_xdata()[0], folds[0].get_ydata()[0]
    # the fold is located by continuation to ~1e-14 (docs/continuation.md); 1e-10 leaves margin
    assert abs(qf - (-1 + np.sqrt(1 - 1 / mu))) < 1e-10
    assert abs(sf - 2 * (mu - np.sqrt(mu * (mu - 1)))) < 1e-10
    curve_line = next(ln for ln in ax.get_lines() if ln.get_label() == "neutral curve (continued)")
    assert np.array_equal(curve_line.get_xdata(), curve.q.values[curve.branch.values == curve.branch.values[0]])


def test_every_branch_of_a_leading_neutral_curve_is_solid():
    """In the (q, fr_inv) plane at sigma = 1 both branches (the curve through the fold and the
    line q = 0, where p(i w) = (w - w^2)(alpha_v (1 + mu) + i mu w): no other mode grows) are
    stability boundaries and must be drawn solid; the style sheet cycles line styles, so a
    second branch drawn without an explicit style came out dashed, like a non-leading part."""
    import stability

    curve = stability.neutral_curve(
        "sliding", "q", "fr_inv", fixed=dict(sigma=1.0, alpha_v=0.5), x_range=(-0.4, 0.4), y_range=(0.0, 1.0)
    )
    assert len(np.unique(curve.branch.values)) == 2 and bool(curve.leading.all())
    ds = stability.atlas("sliding", q=np.linspace(-0.4, 0.4, 9), fr_inv=np.linspace(0, 1, 5), sigma=1.0, alpha_v=0.5)
    with style():
        fig, ax = plot_stability_map(ds, "q", "fr_inv", curve=curve)
    drawn = [ln for ln in ax.get_lines() if ln.get_linestyle() != "None"]  # markers have none
    assert len(drawn) == 2
    assert all(ln.get_linestyle() == "-" for ln in drawn)
