"""A real top in SI units on every command, in a TOML file, in a recipe, and its bifurcation
diagram in the user's spin unit (docs/your_top.md).

Reference throughout: the nondimensional set computed here by hand from the paper's definitions,
independently of :class:`stability.Top` (eq. 3: ``A0 = A_G + M d^2``, ``q = d/R``,
``mu = M R^2/A0``, ``sigma = C/A0``, ``fr_inv = g/(Omega^2 R)``; eq. 7:
``alpha_v = mu mu_v g / Omega``), and the spin units from their definitions (1 rev/s = 2 pi
rad/s, 1 rpm = 2 pi/60 rad/s). The SI path and the nondimensional path given those hand values
must agree to the rounding of the few operations that form them (tolerance 1e-13 relative on the
parameters; the outputs computed from them then agree to the solver's own reproducibility,
stated per test).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stability
from stability.cli import main
from stability.errors import InputError, RecipeError
from stability.recipes import compute, find_recipes, load_recipe

ATLASES = Path(__file__).resolve().parents[1] / "atlases"

#: the issue's top: 15 g, R = 15 mm, G 3 mm below O, A_G = 1.3e-6, C = 1.5e-6 kg m^2
M, R, D, AG, C, G = 0.015, 0.015, -0.003, 1.3e-6, 1.5e-6, 9.80665
SI = [
    "--mass",
    "0.015",
    "--radius",
    "0.015",
    "--com-offset",
    "-0.003",
    "--inertia-transverse",
    "1.3e-6",
    "--inertia-axial",
    "1.5e-6",
]
REV = 2.0 * math.pi  # rad/s per rev/s


def hand(spin_rad_s=None, mu_v=None):
    """The nondimensional set of the issue's top, from eqs. 3 and 7, written out here."""
    a0 = AG + M * D**2
    out = {"q": D / R, "mu": M * R**2 / a0, "sigma": C / a0}
    if spin_rad_s is not None:
        out["fr_inv"] = G / (spin_rad_s**2 * R)
        if mu_v is not None:
            out["alpha_v"] = out["mu"] * mu_v * G / spin_rad_s
    return out


def nd_flags(p):
    return [x for k, v in p.items() for x in ("--" + k.replace("_", "-"), repr(float(v)))]


def one_line_error(capsys, argv):
    try:
        rc = main(argv)
    except SystemExit as exc:  # argparse's own errors (an invalid choice)
        rc = exc.code
    err = capsys.readouterr().err
    assert rc == 2, err
    assert err.count("\n") == 1, err
    return err


# ---------------------------------------------------------------- the top in a table / file
def test_from_mapping_gives_eq3():
    top = stability.Top.from_mapping(
        {"mass": M, "radius": R, "com_offset": D, "inertia_transverse": AG, "inertia_axial": C, "mu_v": 0.01}
    )
    ref = hand(15 * REV, mu_v=0.01)
    for k in ("q", "mu", "sigma"):
        assert getattr(top, k) == pytest.approx(ref[k], rel=1e-14)
    nd = top.nondimensional(15, "rev/s")
    assert nd["fr_inv"] == pytest.approx(ref["fr_inv"], rel=1e-14)
    assert nd["alpha_v"] == pytest.approx(ref["alpha_v"], rel=1e-14)
    assert stability.Top.from_mapping({"preset": "table1"}) == stability.Top.table1()


def test_from_toml(tmp_path):
    f = tmp_path / "mytop.toml"
    f.write_text(
        "[top]\nmass = 0.015\nradius = 0.015\ncom_offset = -0.003\ninertia_transverse = 1.3e-6\n"
        "inertia_axial = 1.5e-6\ng = 9.81\n"
    )
    top = stability.Top.from_toml(f)
    assert (top.mass, top.radius, top.com_offset, top.g) == (M, R, D, 9.81)


@pytest.mark.parametrize(
    "table, fragment",
    [
        ({"mass": M}, "missing radius, com_offset, inertia_transverse, inertia_axial"),
        ({"preset": "table1", "mass": M}, "preset = 'table1' and mass conflict"),
        ({"preset": "table2"}, "preset = 'table2' is not one of table1, table1_measured"),
        ({"preset": "table1", "weight": 1.0}, "unknown keys weight"),
        ({"preset": "table1", "mu_v": "0.01"}, "mu_v = '0.01' is not a number"),
    ],
)
def test_from_mapping_refusals(table, fragment):
    with pytest.raises(InputError, match=fragment):
        stability.Top.from_mapping(table)


def test_from_toml_without_top_table(tmp_path):
    f = tmp_path / "t.toml"
    f.write_text("mass = 0.015\n")
    with pytest.raises(InputError, match=r"no \[top\] table"):
        stability.Top.from_toml(f)


# ---------------------------------------------------------------- the commands: SI == hand values
def test_steady_si_equals_nondimensional(tmp_path, capsys):
    """`tippe steady` with the SI top at 15 rev/s and with the hand-computed set: the same states
    (the same code on parameters equal to 1e-15: identical to 1e-12 relative)."""
    a, b = tmp_path / "si.nc", tmp_path / "nd.nc"
    assert main(["steady", *SI, "--spin", "15", "--unit", "rev/s", "--alpha-v", "0.5", "-o", str(a)]) == 0
    assert main(["steady", *nd_flags(hand(15 * REV)), "--alpha-v", "0.5", "-o", str(b)]) == 0
    capsys.readouterr()
    with xr.open_dataset(a) as x, xr.open_dataset(b) as y:
        for name in ("tilt", "energy", "growth_rate"):
            np.testing.assert_allclose(x[name].values, y[name].values, rtol=1e-12, atol=1e-14)
        assert x.attrs["fr_inv"] == pytest.approx(hand(15 * REV)["fr_inv"], rel=1e-14)


def test_simulate_si_with_mu_v(tmp_path, capsys):
    """alpha_v from mu_v and alpha_k from mu_K (eq. 7), fr_inv from the spin in rpm, land in the
    run's attributes."""
    out = tmp_path / "run.nc"
    assert (
        main(
            [
                "simulate",
                *SI,
                "--mu-v",
                "0.02",
                "--mu-k",
                "0.3",
                "--spin",
                "900",
                "--unit",
                "rpm",
                "--t-end",
                "1",
                "--omega",
                "0,0,1",
                "--k",
                "0.01,0,1",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    capsys.readouterr()
    ref = hand(900 * 2 * math.pi / 60, mu_v=0.02)
    ref["alpha_k"] = ref["mu"] * ref["fr_inv"] * 0.3
    with xr.open_dataset(out) as ds:
        for k, v in ref.items():
            assert float(ds.attrs[k]) == pytest.approx(v, rel=1e-13), k


def test_atlas_spin_grid_is_a_spin_coordinate(tmp_path, capsys):
    """A grid of spins: fr_inv = g / (Omega^2 R) along the grid, the spin (in the unit given) a
    coordinate along it; q, sigma, mu of the top."""
    out = tmp_path / "a.nc"
    assert main(["atlas", *SI, "--spin", "5:20:4", "--unit", "rev/s", "--alpha-v", "0.5", "-o", str(out)]) == 0
    capsys.readouterr()
    spins = np.linspace(5, 20, 4)
    ds = stability.open_atlas(out)
    np.testing.assert_allclose(ds.spin.values, spins, rtol=0)
    assert ds.spin.attrs["units"] == "rev/s"
    np.testing.assert_allclose(ds.fr_inv.values, [hand(s * REV)["fr_inv"] for s in spins], rtol=1e-14)
    ref = hand()
    for k in ("q", "sigma", "mu"):
        assert float(ds[k]) == pytest.approx(ref[k], rel=1e-14)
    nd = stability.atlas(
        "sliding",
        q=ref["q"],
        sigma=ref["sigma"],
        mu=ref["mu"],
        fr_inv=[hand(s * REV)["fr_inv"] for s in spins],
        alpha_v=0.5,
    )
    np.testing.assert_allclose(ds.max_growth_rate.values, nd.max_growth_rate.values, rtol=1e-12, atol=1e-15)


def test_validate_and_final_take_a_preset(capsys):
    """--preset table1 at 10 and 15 rev/s: validate's points carry the fr_inv of eq. 3 with the
    preset's radius (0.6366 in), q = -0.1; final's answer equals the nondimensional one."""
    assert main(["validate", "--preset", "table1", "--spin", "10,15", "--unit", "rev/s", "--alpha-v", "0.5"]) == 0
    text = capsys.readouterr().out
    r = 0.6366 * 0.0254
    for s in (10, 15):
        assert f"fr_inv = {G / ((s * REV) ** 2 * r):.6g}" in text
    assert "q = -0.1" in text
    assert (
        main(
            [
                "final",
                "--preset",
                "table1",
                "--spin",
                "15",
                "--unit",
                "rev/s",
                "--alpha-v",
                "0.5",
                "--omega",
                "0,0,1",
                "--k",
                "0.0174524,0,0.9998477",
                "--no-simulation",
            ]
        )
        == 0
    )
    si = capsys.readouterr().out
    nd = dict(q=-0.1, sigma=1.0, mu=2.28, fr_inv=G / ((15 * REV) ** 2 * r))
    assert (
        main(
            [
                "final",
                *nd_flags(nd),
                "--alpha-v",
                "0.5",
                "--omega",
                "0,0,1",
                "--k",
                "0.0174524,0,0.9998477",
                "--no-simulation",
            ]
        )
        == 0
    )
    assert capsys.readouterr().out.splitlines()[0] == si.splitlines()[0]


def test_neutral_takes_a_top_for_the_fixed_parameters(capsys):
    """The top fixes what is not traced: tracing (q, sigma), fr_inv and mu come from the top."""
    assert (
        main(["neutral", *SI, "--spin", "15", "--unit", "rev/s", "--alpha-v", "0.5", "--x", "q", "--y", "sigma"]) == 0
    )
    si = capsys.readouterr().out
    ref = hand(15 * REV)
    assert (
        main(
            [
                "neutral",
                "--fr-inv",
                repr(ref["fr_inv"]),
                "--mu",
                repr(ref["mu"]),
                "--alpha-v",
                "0.5",
                "--x",
                "q",
                "--y",
                "sigma",
            ]
        )
        == 0
    )
    assert capsys.readouterr().out == si


def test_threshold_spin_reads_a_top_file(tmp_path, capsys):
    f = tmp_path / "mytop.toml"
    f.write_text(
        "[top]\nmass = 0.015\nradius = 0.015\ncom_offset = -0.003\ninertia_transverse = 1.3e-6\n"
        "inertia_axial = 1.5e-6\n"
    )
    assert main(["threshold", "spin", "--top", str(f)]) == 0
    a = capsys.readouterr().out
    assert main(["threshold", "spin", *SI]) == 0
    assert capsys.readouterr().out == a


# ---------------------------------------------------------------- the CLI's one-line refusals
@pytest.mark.parametrize(
    "argv, fragments",
    [
        (["steady", *SI, "--spin", "15", "--alpha-v", "0.5", "--q", "-0.1"], ["--mass", "--q -0.1", "conflict"]),
        (
            ["steady", "--preset", "table1", "--spin", "15", "--alpha-v", "0.5", "--fr-inv", "0.3"],
            ["--preset table1", "--fr-inv 0.3", "conflict"],
        ),
        (["steady", *SI, "--mu-v", "0.02", "--spin", "15", "--alpha-v", "0.5"], ["--mu-v 0.02", "--alpha-v 0.5"]),
        (["steady", *SI, "--spin", "15", "--alpha-v", "0.5", "--fr-inv", "0"], ["--mass", "--fr-inv 0.0", "conflict"]),
        (
            [
                "simulate",
                *SI,
                "--mu-k",
                "0.3",
                "--spin",
                "15",
                "--alpha-v",
                "0.5",
                "--alpha-k",
                "0",
                "--t-end",
                "1",
                "--omega",
                "0,0,1",
                "--k",
                "0,0,1",
                "-o",
                "x.nc",
            ],
            ["--mass", "--alpha-k 0.0", "conflict"],
        ),
        (["steady", *SI, "--alpha-v", "0.5"], ["--mass", "needs --spin"]),
        (["steady", "--q", "-0.1", "--sigma", "1", "--alpha-v", "0.5", "--spin", "15"], ["--spin 15 needs a top"]),
        (["steady", "--mass", "0.015", "--spin", "15", "--alpha-v", "0.5"], ["--mass given without", "--radius"]),
        (["steady", "--preset", "table1", *SI, "--spin", "15", "--alpha-v", "0.5"], ["--preset table1 and --mass"]),
        (["steady", *SI, "--spin", "5:20:3", "--alpha-v", "0.5"], ["--spin = '5:20:3' must be one number"]),
        (
            ["steady", "--q", "-0.1", "--sigma", "1", "--fr-inv", "0.3", "--alpha-v", "0.5", "--mu-v", "0.1"],
            ["--mu-v", "describe a real top"],
        ),
        (["steady", *SI, "--spin", "15", "--unit", "rps", "--alpha-v", "0.5"], ["--unit", "rps"]),
        (["steady", *SI, "--unit", "rev/s", "--alpha-v", "0.5"], ["--unit rev/s is the unit of --spin"]),
        (["atlas", *SI, "--mu-v", "0.02", "--spin", "5:20:4", "-o", "x.nc"], ["--spin 5:20:4", "--mu-v 0.02"]),
        (
            [
                "simulate",
                *SI,
                "--spin",
                "15",
                "--alpha-v",
                "0.5",
                "--sigma",
                "1",
                "--t-end",
                "1",
                "--omega",
                "0,0,1",
                "--k",
                "0,0,1",
                "-o",
                "x.nc",
            ],
            ["--mass", "--sigma 1.0", "conflict"],
        ),
    ],
)
def test_cli_refusals_are_one_line(argv, fragments, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    err = one_line_error(capsys, argv)
    for f in fragments:
        assert f in err, err


def test_cli_top_file_errors(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text("[top]\nmass = 15\nradius = 0.015\n")
    err = one_line_error(capsys, ["steady", "--top", str(f), "--spin", "15", "--alpha-v", "0.5"])
    assert "bad.toml [top]: missing com_offset" in err
    good = tmp_path / "good.toml"
    good.write_text('[top]\npreset = "table1"\n')
    err = one_line_error(capsys, ["steady", "--top", str(good), "--mass", "0.015", "--spin", "15", "--alpha-v", "0.5"])
    assert f"--top {good} and --mass conflict" in err


# ---------------------------------------------------------------- recipes with a [top]
def _recipe(tmp_path, text, name="mine.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


TOP_TABLE = (
    "[top]\nmass = 0.015\nradius = 0.015\ncom_offset = -0.003\ninertia_transverse = 1.3e-6\ninertia_axial = 1.5e-6\n"
)


def test_recipe_with_top_and_spin_grid(tmp_path):
    p = _recipe(
        tmp_path,
        'title = "growth rate of my top against its spin"\nkind = "lines"\nx = "fr_inv"\n'
        'spin = "5:20:7"\nunit = "rev/s"\n[grid]\nalpha_v = 0.5\n' + TOP_TABLE,
    )
    r = load_recipe(p)
    spins = np.linspace(5, 20, 7)
    ref = hand()
    for k in ("q", "sigma", "mu"):
        assert r.grid[k] == pytest.approx(ref[k], rel=1e-14)
    np.testing.assert_allclose(r.grid["fr_inv"], [hand(s * REV)["fr_inv"] for s in spins], rtol=1e-14)
    ds = compute(r)["sliding"]
    np.testing.assert_allclose(ds.spin.values, spins, rtol=0)
    assert ds.attrs["mass_kg"] == M


@pytest.mark.parametrize(
    "text, fragment",
    [
        (
            'kind = "lines"\nx = "fr_inv"\nspin = "5:20:7"\n[grid]\nalpha_v = 0.5\nq = -0.1\n' + TOP_TABLE,
            r"\[top\] and grid.q conflict",
        ),
        (
            'kind = "lines"\nx = "fr_inv"\nspin = "5:20:7"\n[grid]\nalpha_v = 0.5\nfr_inv = 0.1\n' + TOP_TABLE,
            r"\[top\] and grid.fr_inv conflict",
        ),
        (
            'kind = "lines"\nx = "q"\nspin = 10\n[grid]\nq = "-0.3:0.3:5"\nsigma = 1\nfr_inv = 0.1\n',
            r"spin = 10 needs a \[top\]",
        ),
        ('kind = "bifurcation"\npreset = "table1"\n' + TOP_TABLE, r"preset = 'table1' and \[top\] conflict"),
        (
            'kind = "lines"\nx = "fr_inv"\nspin = "5:20:7"\nunit = "rev/s"\n[grid]\n' + TOP_TABLE + "mu_v = 0.02\n",
            "alpha_v = mu mu_v g / Omega would change along the spin grid",
        ),
    ],
)
def test_recipe_top_refusals(tmp_path, text, fragment):
    with pytest.raises(RecipeError, match=fragment):
        load_recipe(_recipe(tmp_path, 'title = "t"\n' + text))


def test_existing_recipes_load_unchanged():
    """Every recipe of atlases/ still loads; the bifurcation recipe's runs stay in rpm."""
    recipes = {r.name: r for r in find_recipes(ATLASES)}
    toy = recipes["bifurcation_toy"]
    assert toy.top is None and toy.unit == "rpm" and toy.runs_rpm == (330, 370, 410, 420, 425, 440, 480)


# ---------------------------------------------------------------- the bifurcation diagram of any top
class _Launch:
    """The duck type plot_bifurcation takes (the launch helper's result has these attributes)."""

    spin = 15 * REV
    end_tilt = 179.0


@pytest.fixture(scope="module")
def diagram():
    top = stability.Top(mass=M, radius=R, com_offset=D, inertia_transverse=AG, inertia_axial=C)
    return top, stability.bifurcation_diagram(top, unit="rev/s", alpha_v=0.5, points=61, spin_range=(5.0, 16.0))


def test_bifurcation_of_any_top_in_rev_per_s(diagram):
    """The upright line is solid up to the critical spin and dashed above it, at the critical spin
    of stability.critical_spin converted to rev/s here (rad/s / 2 pi); the reference is the linear
    threshold (a different method from the branch's continuation), hence 1e-6 relative."""
    import matplotlib as mpl

    mpl.use("Agg")
    from stability.plotting import plot_bifurcation

    top, d = diagram
    fig, ax = plot_bifurcation(d, launch=_Launch())
    assert "rev/s" in ax.get_xlabel()
    crit = stability.critical_spin(top, alpha_v=0.5).spin / (2 * math.pi)
    up = [ln for ln in ax.get_lines() if len(ln.get_ydata()) > 1 and np.all(np.asarray(ln.get_ydata()) == 0.0)]
    solid = [ln for ln in up if ln.get_linestyle() == "-"]
    dashed = [ln for ln in up if ln.get_linestyle() == "--"]
    assert len(solid) == 1 and len(dashed) == 1
    assert max(solid[0].get_xdata()) == pytest.approx(crit, rel=1e-6)
    assert min(dashed[0].get_xdata()) == pytest.approx(crit, rel=1e-6)
    inv = [ln for ln in ax.get_lines() if len(ln.get_ydata()) > 1 and np.all(np.asarray(ln.get_ydata()) == 180.0)]
    assert {ln.get_linestyle() for ln in inv} == {"-", "--"}
    tilted = [ln for ln in ax.get_lines() if len(ln.get_ydata()) > 1 and np.ptp(ln.get_ydata()) > 10]
    assert tilted  # the tilted family
    circles = [ln for ln in ax.get_lines() if ln.get_marker() == "o"]
    assert circles and min(circles[0].get_xdata()) == pytest.approx(crit, rel=1e-6)
    launch = [ln for ln in ax.get_lines() if ln.get_marker() == "P"]
    assert list(launch[0].get_xdata()) == pytest.approx([15.0], rel=1e-15) and list(launch[0].get_ydata()) == [179.0]


def test_bifurcation_launch_with_tilt_is_at_its_equivalent_spin(diagram):
    """A launch with a ``tilt`` is drawn at its equivalent upright spin n (cos t + q)/(1 + q)
    (J = C n R (cos t + q), docstring of _mark_launch), here checked against J computed from
    L = C n k and the lever G - Q with vectors."""
    import matplotlib as mpl

    mpl.use("Agg")
    from stability.plotting import plot_bifurcation

    _, d = diagram

    class Tilted(_Launch):
        tilt = 10.0

    _, ax = plot_bifurcation(d, launch=Tilted())
    t = math.radians(10.0)
    k = np.array([math.sin(t), 0, math.cos(t)])
    q = D / R
    j = C * 15 * np.dot(k, np.array([0, 0, R]) + q * R * k)  # L . (G - Q)
    j_up = C * np.dot([0, 0, 1], np.array([0, 0, R]) + q * R * np.array([0, 0, 1]))  # per rev/s, upright
    x = next(ln for ln in ax.get_lines() if ln.get_marker() == "P").get_xdata()[0]
    assert x == pytest.approx(j / j_up, rel=1e-13)


def test_bifurcation_recipe_with_top(tmp_path):
    p = _recipe(
        tmp_path,
        'title = "my top"\nkind = "bifurcation"\nunit = "rev/s"\n[grid]\nalpha_v = 0.5\n' + TOP_TABLE,
        name="bif.toml",
    )
    r = load_recipe(p)
    assert r.unit == "rev/s" and r.top.mass == M
    import matplotlib as mpl

    from stability.plotting.recipe_figures import recipe_figure

    mpl.use("Agg")
    datasets = compute(r)
    fig, axes = recipe_figure(r, datasets)
    assert "rev/s" in axes[0].get_xlabel()
    assert datasets["branch"].spin.attrs["units"] == "rev/s"
