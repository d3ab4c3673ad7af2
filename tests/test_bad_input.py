"""Bad input to every public function and CLI command: each message names the parameter, the
value and the allowed range (or type), and the CLI answers with one line and no traceback.

Reference: docs/input_checks.md (the table of checks) and the physical domain of NOTES.md.
"""

from __future__ import annotations

import numpy as np
import pytest

import stability
from stability.cli import main
from stability.errors import DomainError
from stability.grids.chunked import normalize_chunks
from stability.parameters import check_domain

GOOD = dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5, mu=2.28)
SIM = dict(t_end=1.0, omega=[0.02, 0.0, 1.0], k=[0.05, 0.0, 1.0], q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)


@pytest.mark.parametrize(
    "name,value,fragment",
    [
        ("mu", 1e-300, "mu = 1e-300 is outside the computable range: 1e-30 <= mu <= 1e+30"),
        ("fr_inv", 1e150, "fr_inv = 1e+150 is outside the computable range: |fr_inv| <= 1e+30"),
        ("alpha_v", 1e31, "alpha_v = 1e+31 is outside the computable range: |alpha_v| <= 1e+30"),
    ],
)
def test_computable_range_instead_of_silent_nan(name, value, fragment):
    # (the sliding model's default kernel path tests the domain itself; see the report)
    with pytest.raises(DomainError, match=fragment.replace("+", r"\+").replace("|", r"\|")):
        check_domain(**{**GOOD, name: value})
    if name != "alpha_v":
        with pytest.raises(DomainError, match=f"^{name} = "):
            stability.eigenvalues("fixed_pivot", **{k: v for k, v in {**GOOD, name: value}.items() if k != "alpha_v"})


@pytest.mark.parametrize(
    "value,fragment",
    [
        ("0.3", "fr_inv = '0.3' is a str; fr_inv must be a real number or an array of reals"),
        (1 + 2j, r"fr_inv = \(1\+2j\) is complex; fr_inv must be real"),
        ([["a"], ["b", "c"]], "fr_inv = .* is not a rectangular array"),
        (["a", "b"], r"fr_inv = \['a', 'b'\] has dtype <U1; fr_inv must be a real number"),
    ],
)
def test_wrong_types_name_value_and_type(value, fragment):
    with pytest.raises(TypeError, match=fragment):
        stability.check_domain(**{**GOOD, "fr_inv": value})


def test_scalar_required_names_the_right_parameter():
    with pytest.raises(TypeError, match=r"fr_inv must be a single number here, got an array of shape \(2,\)"):
        stability.jacobian_eigenvalues("sliding", **{**GOOD, "fr_inv": [0.1, 0.2]})
    with pytest.raises(TypeError, match=r"alpha_v must be a single number here, got an array of shape \(2,\)"):
        stability.simulate("sliding", **{**SIM, "alpha_v": [0.1, 0.2]})


def test_mask_flag_must_be_bool():
    with pytest.raises(TypeError, match="mask_unphysical = 'yes' is a str; mask_unphysical must be True or False"):
        stability.atlas("fixed_pivot", q=-0.1, fr_inv=0.3, sigma=1.0, mask_unphysical="yes")


@pytest.mark.parametrize(
    "chunks,exc,fragment",
    [
        (0, DomainError, "chunks = 0 is outside the allowed range: chunks >= 1"),
        (1.5, TypeError, "chunks = 1.5 is a float; chunks must be an integer >= 1"),
        (True, TypeError, "chunks = True is a bool; chunks must be an integer >= 1"),
        ({"q": 0}, DomainError, r"chunks\['q'\] = 0 is outside the allowed range: chunks\['q'\] >= 1"),
        ({"x": 2}, ValueError, "chunks name 'x', not grid dimensions"),
    ],
)
def test_chunk_sizes(chunks, exc, fragment):
    with pytest.raises(exc, match=fragment):
        normalize_chunks(chunks, ["q"], {"q": 4})


@pytest.mark.parametrize(
    "kw,exc,fragment",
    [
        (dict(t_end=-1.0), DomainError, "t_end = -1 is outside the allowed range: t_end > 0"),
        (dict(t_end=True), TypeError, "t_end = True is a bool"),
        (dict(rtol=2.0), DomainError, "rtol = 2 is outside the allowed range: 0 < rtol < 1"),
        (dict(dt=0.0), DomainError, "dt = 0 is outside the allowed range: dt > 0"),
        (dict(max_steps=1.5), TypeError, "max_steps = 1.5 is a float; max_steps must be an integer >= 1"),
        (dict(method="euler"), ValueError, "method = 'euler' is not known; choose one of auto, dopri5, rk4"),
        (dict(friction=None), ValueError, "friction = None is not known; choose one of isotropic, componentwise"),
        (dict(omega=[np.nan, 0, 1]), DomainError, "omega = nan is not finite"),
        (dict(omega=[0, 1]), ValueError, r"omega = \[0, 1\] has shape \(2,\); omega must be a vector of 3 components"),
        (dict(omega=[1e300, 0, 1]), ValueError, "omega = .* is outside the computable range"),
        (dict(slip_scale=-1.0), DomainError, "slip_scale = -1 is outside the allowed range: slip_scale > 0"),
    ],
)
def test_simulate_arguments(kw, exc, fragment):
    with pytest.raises(exc, match=fragment):
        stability.simulate("sliding", **{**SIM, **kw})


def test_validate_arguments():
    v = dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    with pytest.raises(DomainError, match="amplitude = 0.5 is outside the allowed range: 0 < amplitude < 0.1"):
        stability.validate("sliding", **v, amplitude=0.5)
    with pytest.raises(DomainError, match="max_time = 0 is outside the allowed range: max_time > 0"):
        stability.validate("sliding", **v, max_time=0.0)
    with pytest.raises(ValueError, match="method = 'rk4'.*dopri5"):
        stability.validate("sliding", **v, method="rk4")
    with pytest.raises(DomainError, match="sigma = 3 is outside the physical domain: sigma <= 2"):
        stability.validate("sliding", **{**v, "sigma": 3.0})


def test_top_arguments():
    t = dict(mass=0.018, radius=0.016, com_offset=-0.0016, inertia_transverse=1.5e-6, inertia_axial=1.5e-6)
    with pytest.raises(DomainError, match="mass = -1 is outside the allowed range: mass > 0"):
        stability.Top(**{**t, "mass": -1.0})
    with pytest.raises(TypeError, match=r"mu_v must be a single number here, got an array of shape \(2,\)"):
        stability.Top(**t, mu_v=[0.1, 0.2])
    with pytest.raises(DomainError, match="radius = 1e\\+300 m"):
        stability.Top(**{**t, "radius": 1e300})  # was an OverflowError
    with pytest.raises(DomainError, match="radius = 1e\\+300 m|inertia_transverse = nan"):
        stability.Top.from_nondimensional(mass=0.01, radius=1e300, q=-0.1, mu=2.28, sigma=1.0)
    with pytest.raises(TypeError, match="mass = 'heavy' is a str"):
        stability.Top.from_nondimensional(mass="heavy", radius=0.01, q=-0.1, mu=2.28, sigma=1.0)
    top = stability.Top.table1(mu_v=0.01)
    with pytest.raises(DomainError, match="spin = -3 rpm is outside the allowed range: spin > 0"):
        top.alpha_v(-3.0, unit="rpm")  # was a silent negative alpha_v
    with pytest.raises(ValueError, match="unit = 'rad' is not known; choose one of rad/s, rpm, rev/s"):
        top.fr_inv(1.0, unit="rad")


# --- the command line: one line, no traceback, exit status 2 ------------------------------------

ATLAS = ["atlas", "--q", "0.1", "--fr-inv", "0.1", "--sigma", "1", "--alpha-v", "0.5"]


@pytest.mark.parametrize(
    "argv,fragment",
    [
        ([*ATLAS[:2], "a:b:c", *ATLAS[3:]], "--q = 'a:b:c': 'a' is not a number; give a number, a comma list"),
        ([*ATLAS[:2], "0:1:0", *ATLAS[3:]], "--q = '0:1:0': the number of points is 0; the allowed range is num >= 1"),
        ([*ATLAS[:2], "", *ATLAS[3:]], "--q = '' is empty"),
        (
            [*ATLAS[:6], "3", *ATLAS[7:]],
            "--sigma = 3 is outside the physical domain: --sigma <= 2 (1 - mu q^2) = 1.9544",
        ),
        ([*ATLAS, "--model", "spinning"], "argument --model: invalid choice: 'spinning'"),
        ([*ATLAS, "--mu", "inf"], "mu = inf is not finite"),
        ([*ATLAS, "--chunks", "q=x"], "--chunks = 'q=x' is not a size or a list dim=size"),
        (
            [
                "simulate",
                "--t-end",
                "-1",
                "--omega",
                "0,0,1",
                "--k",
                "0,0,1",
                "--q",
                "-0.1",
                "--fr-inv",
                "0.3",
                "--sigma",
                "1",
                "--alpha-v",
                "0.5",
            ],
            "--t-end = -1 is outside the allowed range: --t-end > 0",
        ),
        (
            ["validate", "--q", "-0.1", "--fr-inv", "0.3", "--sigma", "1", "--alpha-v", "0.5", "--amplitude", "1"],
            "--amplitude = 1 is outside the allowed range: 0 < --amplitude < 0.1",
        ),
        (
            ["threshold", "sigma", "--q", "-0.1", "--fr-inv", "-1", "--alpha-v", "0.5"],
            "--fr-inv = -1 is outside the physical domain: --fr-inv >= 0",
        ),
        (
            [
                "threshold",
                "spin",
                "--mass",
                "-1",
                "--radius",
                "0.01",
                "--com-offset",
                "0",
                "--inertia-transverse",
                "1",
                "--inertia-axial",
                "1",
            ],
            "--mass = -1 is outside the allowed range: --mass > 0",
        ),
        (["neutral", "--x", "q", "--y", "q"], "--x and --y must be two different parameters"),
        (["figures", "no/such/recipe.toml"], "recipe 'no/such/recipe.toml' does not exist"),
        (["bogus"], "invalid choice: 'bogus'"),
    ],
)
def test_cli_errors_are_one_line(argv, fragment, tmp_path, capsys):
    if "-o" not in argv and argv[0] in ("atlas", "simulate"):
        argv = [*argv, "-o", str(tmp_path / "out.nc")]
    try:
        rc = main(argv)
    except SystemExit as exc:  # argparse's own errors
        rc = exc.code
    err = capsys.readouterr().err
    assert rc == 2, err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert fragment in err
    assert list(tmp_path.iterdir()) == []


def test_cli_internal_error_is_one_line_unless_debug(monkeypatch, capsys, tmp_path):
    import stability.grids.atlases as atlases  # the command imports atlas() from here when it runs

    def bug(*args, **kwargs):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(atlases, "atlas", bug)
    argv = [*ATLAS, "-o", str(tmp_path / "a.nc")]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "tippe atlas: internal error: ZeroDivisionError: a bug (rerun with --debug or TIPPE_DEBUG=1" in err
    with pytest.raises(ZeroDivisionError):
        main([*argv, "--debug"])
    monkeypatch.setenv("TIPPE_DEBUG", "1")
    with pytest.raises(ZeroDivisionError):
        main(argv)


def test_threshold_and_state_space_name_the_array_parameter():
    """A single value is required; the message names the parameter given as an array (the
    broadcast used to make every parameter an array, and the first one, q, was blamed)."""
    with pytest.raises(TypeError, match=r"^fr_inv must be a single number here, got an array of shape \(2,\)"):
        stability.threshold("sigma", q=-0.1, fr_inv=[0.1, 0.2], alpha_v=0.5)
    with pytest.raises(TypeError, match=r"^alpha_v must be a single number here"):
        stability.state_space("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=np.array([0.5, 1.0]))


@pytest.mark.parametrize(
    "kw,exc,fragment",
    [
        (dict(samples=float("inf")), TypeError, "samples = inf is a float; samples must be an integer in \\[3, 1e6\\]"),
        (dict(samples=2), DomainError, "samples = 2 is outside the allowed range: 3 <= samples <= 1e6"),
        (dict(samples=True), TypeError, "samples = True is a bool; samples must be an integer in \\[3, 1e6\\]"),
        (
            dict(fr_inv_range=(0.0, 1.0)),
            DomainError,
            r"fr_inv_range = \(0, 1\) is outside the allowed range: 0 < lo < hi",
        ),
        (dict(fr_inv_range=(1e-6, float("nan"))), DomainError, "^fr_inv_range = nan"),
        (dict(fr_inv_range=0.3), TypeError, "fr_inv_range = 0.3 must be a pair"),
        (
            dict(orientation="sideways"),
            ValueError,
            "orientation = 'sideways' is not known; choose one of upright, inverted, both",
        ),
    ],
)
def test_critical_spin_arguments(kw, exc, fragment):
    with pytest.raises(exc, match=fragment):
        stability.critical_spin(stability.Top.table1(), **kw)


def test_thresholds_flags():
    with pytest.raises(TypeError, match="return_details = 'yes' is a str; return_details must be True or False"):
        stability.thresholds("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5, return_details="yes")


NEUTRAL = dict(fixed=dict(fr_inv=0.0, alpha_v=0.5))


@pytest.mark.parametrize(
    "kw,exc,fragment",
    [
        (dict(x_range=(0.2, -0.2)), ValueError, r"q_range = \(0.2, -0.2\) is outside the allowed range: lo < hi"),
        (dict(x_range=(0.0, float("nan"))), DomainError, "^q_range = nan"),
        (dict(x_range=0.3), TypeError, "q_range = 0.3 must be a pair"),
        (dict(max_step=0.0), DomainError, "max_step = 0 is outside the allowed range: max_step > 0"),
        (dict(step=-1.0), DomainError, "step = -1 is outside the allowed range: step > 0"),
        (dict(tol=float("inf")), DomainError, "^tol = inf"),
        (dict(max_points=1), DomainError, "max_points = 1 is outside the allowed range: 2 <= max_points <= 1e6"),
        (dict(max_points=2.5), TypeError, r"max_points = 2.5 is a float; max_points must be an integer in \[2, 1e6\]"),
        (dict(form="other"), ValueError, "form = 'other' is not known; choose one of crossing, collision"),
        (dict(grid=(25,)), TypeError, r"grid = \(25,\) must be a pair of integers >= 2"),
        (dict(start=[]), ValueError, r"start = \[\] is empty"),
        (dict(start=[(0.1,)]), ValueError, r"start point \(0.1,\): a start point has 2 or 3 values"),
        (dict(start=[(0.1, "x")]), TypeError, "start = 'x' is a str"),
        (dict(fixed=dict(fr_inv=[0.0, 0.1], alpha_v=0.5)), TypeError, "^fr_inv must be a single number here"),
    ],
)
def test_neutral_curve_arguments(kw, exc, fragment):
    import stability

    with pytest.raises(exc, match=fragment):
        stability.neutral_curve("sliding", "q", "sigma", **{**NEUTRAL, **kw})


def test_fold_curve_fold_in():
    import stability

    with pytest.raises(ValueError, match="fold_in = 'mu' is not known; choose one of q, sigma"):
        stability.fold_curve("sliding", "q", "sigma", "fr_inv", fold_in="mu", fixed=dict(fr_inv=0.0, alpha_v=0.5))


def test_plotting_and_mode_functions_name_what_they_need():
    """Public plotting and mode functions: a wrong object is a TypeError/ValueError that says
    what is expected (they used to fail with "'NoneType' object is not subscriptable",
    KeyError 'max_growth_rate' or an unpacking error)."""
    from stability.linear.modes import principal_mode, track_modes
    from stability.plotting import plot_growth_rate
    from stability.plotting.maps import plot_stability_map

    with pytest.raises(TypeError, match="ds is a NoneType; it must be an atlas"):
        plot_growth_rate(None)
    run = stability.simulate(
        "sliding", t_end=1.0, omega=[0, 0, 1], k=[1e-3, 0, 1], q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5
    )
    with pytest.raises(ValueError, match="ds has no growth_rate, frequency, max_growth_rate, stability"):
        plot_growth_rate(run)
    with pytest.raises(ValueError, match="it is not an atlas"):
        plot_stability_map(run, "q", "sigma")
    with pytest.raises(ValueError, match=r"eigenvalues has shape \(3,\); it must be \(points, modes\)"):
        track_modes(np.array([1, 2, 3]))
    assert np.isnan(principal_mode(np.full((3, 3), np.nan + 0j))).all()  # outside the domain: NaN, no warning
