"""Issue 20: no wrong number without a flag in the steady layer (scales, vertical states, starts).

References: the closed form of the family (S3-S4: ``J(c)^2 = mu fr_inv q D^2 / P``,
:func:`stability.steady.family.jellett_of_c`, which shares nothing with the traced branch's
nonlinear residual), eq. (11) through :func:`stability.eigenvalues` (the linear layer's own
polynomial roots), and the family's scale invariance.
"""

import math

import numpy as np
import pytest

import stability
from stability.errors import DomainError
from stability.steady import family


def _closed_form_error(ds, q, sigma, fr_inv, mu=2.28):
    c = np.cos(np.radians(ds.tilt.values[1:-1]))
    j = family.jellett_of_c(c, q=q, sigma=sigma, fr_inv=fr_inv, mu=mu)
    return float(np.max(np.abs(j / ds.jellett.values[1:-1] - 1.0)))


@pytest.mark.parametrize(
    "q, sigma, fr_inv",
    [
        (-0.1, 1.0, 1e-12),
        (1e-12, 0.8, 0.3),
        (-0.1, 1.0, 1e16),
        (-0.1, 1.0, 1e30),
        (-1e-40, 1.2, 0.3),
        (1e-60, 0.8, 0.3),
    ],
)
@pytest.mark.parametrize("compiled", [True, False])
def test_branch_points_on_the_closed_form_at_every_scale(q, sigma, fr_inv, compiled):
    """Every traced point (the first step included) lies on S3-S4's J(c) to 1e-12 relative:
    the corrector's tolerance is relative to the size of the terms (the residual divided by
    lam^2 + mu fr_inv |q|), so a 1e-13 residual means 1e-13 of the terms at every scale
    (the reproducers had 1e-5 to 1e-4 before: the first step accepted uncorrected); the
    compiled step and the engine's Python path alike."""
    ds = stability.steady_branch(q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=0.5, compiled=compiled)
    assert ds.sizes["point"] > 100
    assert _closed_form_error(ds, q, sigma, fr_inv) < 1e-12


def test_branch_scale_invariance():
    """J^2 / (mu fr_inv) is a function of q, sigma, mu, c only: the tilts of the branch at
    fr_inv = 1e20 equal those at 0.3 (the same trace in log lam shifted by a constant), and
    J scales by sqrt(1e20 / 0.3). Tolerance: 1e-9 deg (rounding of the trace's steps)."""
    a = stability.steady_branch(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    b = stability.steady_branch(q=-0.1, sigma=1.0, fr_inv=1e20, alpha_v=0.5)
    assert a.sizes["point"] == b.sizes["point"]
    np.testing.assert_allclose(b.tilt.values, a.tilt.values, atol=1e-9)
    np.testing.assert_allclose(b.jellett.values, a.jellett.values * math.sqrt(1e20 / 0.3), rtol=1e-12)
    assert list(a.kind.values) == list(b.kind.values)


@pytest.mark.parametrize(
    "kw, name",
    [(dict(q=1e-300), "q"), (dict(q=-5e-324), "q"), (dict(sigma=1e-170), "sigma"), (dict(fr_inv=1e120), "fr_inv")],
)
def test_scales_that_do_not_fit_a_double_are_refused(kw, name):
    """Beyond SCALE_RANGE a square underflows or overflows: every steady entry point refuses,
    naming the parameter (never a ZeroDivisionError, an empty branch or a missed state)."""
    p = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5) | kw
    for call in (
        lambda: stability.steady_branch(**p),
        lambda: stability.steady_states(**p),
        lambda: stability.final_state(**p, omega=[0.1, 0, 1], k=[0, 0, 1]),
    ):
        with pytest.raises(DomainError, match=name):
            call()
    with pytest.raises(DomainError, match="parameter jellett"):
        stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, jellett=1e155)


@pytest.mark.parametrize("alpha_v, jellett", [(0.5, None), (1e9, None), (1e6, None), (0.5, 1e12), (0.5, -0.9)])
def test_vertical_growth_rates_are_eq11s(alpha_v, jellett):
    """The vertical states' growth rates are |n| times eq. (11)'s at the equivalent point
    (q c, fr_inv / n^2, alpha_v / |n|), here through stability.eigenvalues (the linear layer,
    which the steady layer's reduced Jacobian shares nothing with), at the issue's hard point
    A_G ~ 2e-15 where the reduced Jacobian's eigenvalues lost every digit (343.9 against
    -0.195). Tolerance: the reported bound plus 1e-12 relative (the same roots, spin applied)."""
    q = -(1 - 1e-15) / math.sqrt(2.28)
    sigma = 1 - 2.28 * q * q
    ds = stability.steady_states(q=q, sigma=sigma, fr_inv=0.3, alpha_v=alpha_v, jellett=jellett)
    for i in np.nonzero(ds.kind.values != "tilted")[0]:
        c = 1.0 if ds.kind.values[i] == "upright" else -1.0
        n = abs(float(ds.omega_vertical[i]))
        s = stability.eigenvalues("sliding", q=q * c, fr_inv=0.3 / n**2, sigma=sigma, alpha_v=alpha_v / n) * n
        ref = float(s.real.max())
        assert abs(float(ds.growth_rate[i]) - ref) <= float(ds.growth_rate_bound[i]) + 1e-12 * abs(ref)


def test_branch_point_growth_rate_is_eq11s():
    """A branch's first point (the vertical state where the family leaves it) carries eq. (11)'s
    growth rate at its equivalent point, as stability.eigenvalues gives it; at a branch point
    eq. (11) is neutral (the neutral curve), so |growth| is within its bound."""
    ds = stability.steady_branch(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    n = float(ds.precession_rate[0]) * (1 - 0.1)  # spin = lam (1 + q c), c = 1
    s = stability.eigenvalues("sliding", q=-0.1, fr_inv=0.3 / n**2, sigma=1.0, alpha_v=0.5 / n) * n
    assert float(ds.growth_rate[0]) == pytest.approx(float(s.real.max()), abs=1e-12)
    assert abs(float(ds.growth_rate[0])) < 1e-9


def _atlas_file(tmp_path):
    return stability.atlas(
        "sliding", q=np.linspace(-0.3, 0.3, 13), fr_inv=np.linspace(0.0, 1.0, 11), sigma=1.0, alpha_v=0.5
    )


def test_open_atlas_checks_its_flags_against_its_own_growth_rates(tmp_path):
    """Item 4: an atlas whose unstable flags were set to stable opens with an error that counts
    them. Reference: the file's own max_growth_rate and eigenvalue_error_bound (a stable point
    has every Re s < -4 bound, an unstable one a growing mode)."""
    from stability.errors import AtlasFileError

    ds = _atlas_file(tmp_path)
    n_unstable = int((ds.stability == 2).sum())
    assert n_unstable > 0
    good = tmp_path / "good.nc"
    ds.to_netcdf(good)
    stability.open_atlas(good)  # the untouched file opens
    bad = ds.copy(deep=True)
    bad["stability"] = bad.stability.where(bad.stability != 2, 0).astype(np.int8)
    bad.to_netcdf(tmp_path / "bad.nc")
    with pytest.raises(AtlasFileError, match=f"{n_unstable} points flagged stable"):
        stability.open_atlas(tmp_path / "bad.nc")
    perm = ds.copy(deep=True)
    perm.stability.attrs["flag_meanings"] = "outside_domain unstable marginal stable"
    perm.to_netcdf(tmp_path / "perm.nc")
    with pytest.raises(AtlasFileError, match="flag_meanings"):
        stability.open_atlas(tmp_path / "perm.nc")


def test_a_start_on_a_steady_state_says_so():
    """Item 5: a launch from an exact steady state (upright: unstable; inverted: stable; the
    tilted state of the paper's level: stable) says in ``reason`` that the start is itself that
    state. Reference: the state built from the closed form (S1, family.state_vector) and its
    flag from steady_states; a start 0.01 off the vertical is no steady state."""
    p = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    up = stability.final_state(**p, omega=[0, 0, 1], k=[0, 0, 1])
    assert "start is itself a steady state (the upright one, unstable)" in up.reason
    inv = stability.final_state(**p, omega=[0, 0, 1], k=[0, 0, -1])
    assert "start is itself a steady state (the inverted one, stable)" in inv.reason and inv.kind == "inverted"
    ds = stability.steady_states(**p, jellett=-0.900118587)
    i = int(np.nonzero(ds.kind.values == "tilted")[0][0])
    y = family.state_vector(math.radians(float(ds.tilt[i])), float(ds.precession_rate[i]), -0.1)
    tilted = stability.final_state(**p, omega=y[0:3], k=y[3:6], velocity=[y[6], y[7], 0.0])
    assert "start is itself a steady state (the tilted one, stable)" in tilted.reason
    off = stability.final_state(**p, omega=[0.01, 0, 1], k=[0, 0, 1])
    assert "start is itself" not in off.reason


def test_class_boundary_exactly_and_next_to_it():
    """Item 7: at sigma (1 + q) = A_G exactly (P(1) = 0: no upright branch point, J_up = inf)
    the family is traced from the inverted branch point and its points lie on the closed form
    S3-S4 (1e-12 relative, as above); 1e-10 below the boundary the family lies within ~1e-9 rad
    of the upright state, where the residual divided by sin(tilt) has no digits left: the error
    says so and names the boundary (no ZeroDivisionError, no bare 'failed after 2 points')."""
    from stability.errors import ConvergenceError
    from stability.models.inertia import inertia_g

    sigma = inertia_g(-0.1, 2.28) / 0.9
    ds = stability.steady_branch(q=-0.1, sigma=sigma, fr_inv=0.3, alpha_v=0.5)
    assert ds.attrs["start"] == "inverted" and ds.sizes["point"] > 100
    assert _closed_form_error(ds, -0.1, sigma, 0.3) < 1e-12
    with pytest.raises(ConvergenceError, match="class boundary"):
        stability.steady_branch(q=-0.1, sigma=sigma * (1 - 1e-10), fr_inv=0.3, alpha_v=0.5)


@pytest.mark.parametrize(
    "kw, name",
    [(dict(jellett_max=1e150), "jellett_max"), (dict(max_step=1e-300), "max_step"), (dict(max_angle=0.0), "max_angle")],
)
def test_branch_options_refused_by_their_own_names(kw, name):
    """Item 8: options outside their range are refused naming the option (not the engine's
    min_step, not 'SVD did not converge')."""
    with pytest.raises(DomainError, match=name):
        stability.steady_branch(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **kw)


def test_a_stiff_deciding_run_says_its_cost_first(capsys):
    """Item 9: a deciding run that is stiff (alpha_v = 1e8: LSODA) announces on stderr, before
    it starts, its cost per time unit and the bound t_max puts on it; a non-stiff one says
    nothing. (The cost is a measured constant, docs/hard_cases.md: no timing here.)"""
    end = stability.final_state(q=0.0, sigma=0.8, fr_inv=0.3, alpha_v=1e8, omega=[0.1, 0, 1], k=[0, 0, 1], t_max=50.0)
    err = capsys.readouterr().err
    assert end.method == "simulation" and "stiff" in err and "t_max = 50" in err
    stability.final_state(q=0.0, sigma=0.8, fr_inv=0.3, alpha_v=0.5, omega=[0.1, 0, 1], k=[0, 0, 1], t_max=50.0)
    assert "stiff" not in capsys.readouterr().err
