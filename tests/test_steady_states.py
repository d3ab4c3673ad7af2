"""Steady states of the sliding top: they solve the nonlinear equations, their integrals, and
their stability against eq. (11) and against the energy criterion.

References (each independent of what it checks):

* the compiled right-hand sides of the nonlinear models (stability.nonlinear.sliding, .rolling:
  the equations simulate integrates) for the closed forms (S1)-(S3) of stability.steady.family;
* the nonlinear layer's integrals (quantities.h_cg, energy_parts, used by steady_states on the
  state vectors) against the closed forms (S4)-(S5);
* eq. (11) (stability.eigenvalues / spectrum, the linear model, a separate code path) for the
  Jacobian spectra and verdicts of the vertical states at the equivalent spin;
* the energy criterion (closed form, S8) against the reduced Jacobian for the tilted states.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import stability
from stability.nonlinear import rolling, sliding
from stability.nonlinear.parameters import pack
from stability.steady import family
from stability.steady.linearisation import (
    ROTATION,
    modes_verdict,
    neutral_covectors,
    precessing_jacobians,
    reduced_spectrum,
)

MU = 2.28


def random_tops(n, seed, fr_max=2.0):
    """Tops spread over the physical domain (mu near the paper's 30 % of the time, otherwise in
    [0.5, 5]); alpha_v log-uniform in [0.05, 5]."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        mu = MU if rng.random() < 0.7 else rng.uniform(0.5, 5.0)
        qm = min(0.45, 0.95 / math.sqrt(mu))
        q = rng.uniform(-qm, qm)
        sigma = rng.uniform(0.05, 2.0 * (1.0 - mu * q * q))
        out.append(
            dict(
                q=q,
                sigma=sigma,
                fr_inv=rng.uniform(0.01, fr_max),
                alpha_v=math.exp(rng.uniform(math.log(0.05), math.log(5.0))),
                mu=mu,
            )
        )
    return out, rng


def _precessing_residual(y8, lam, t, model):
    """``f(y) - lam G y`` of a compiled rhs (sliding: 8 components; rolling: omega and k)."""
    p = pack(q=t["q"], fr_inv=t["fr_inv"], sigma=t["sigma"], mu=t["mu"], alpha_v=t["alpha_v"])
    g = ROTATION @ y8
    if model == "sliding":
        return sliding.rhs(0.0, np.concatenate([y8, [0.0, 0.0]]), p)[:8] - lam * g
    return rolling.rhs(0.0, np.concatenate([y8[:6], [0.0, 0.0]]), p)[:6] - lam * g[:6]


def test_closed_form_states_solve_the_sliding_and_rolling_equations():
    """(S1)-(S3) make the compiled rhs vanish in the precessing frame, for both models, any azimuth
    and either sense of rotation, and at fr_inv = 0 for any lam at c0. Tolerance: the 6 x 6
    solve rounds at ~10 u times the size of its terms, ~lam^2; measured 1.4e-15 max(1, lam^2)."""
    tops, rng = random_tops(400, 1)
    worst = {"sliding": 0.0, "rolling": 0.0}
    n = 0
    for t in tops:
        if rng.random() < 0.15:
            t = dict(t, fr_inv=0.0)
            c = float(family.c0(t["q"], t["sigma"], t["mu"]))
            if not -1 < c < 1:
                continue
            lam = rng.uniform(-3, 3)
        else:
            c = rng.uniform(-1, 1)
            lam = family.precession_rate(
                c, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"], sign=rng.choice([-1.0, 1.0])
            )
            if not math.isfinite(lam):
                continue
        y = family.state_vector(math.acos(c), lam, t["q"], phi=rng.uniform(0, 2 * np.pi))
        for model in worst:
            r = np.max(np.abs(_precessing_residual(y, lam, t, model))) / max(1.0, lam * lam)
            worst[model] = max(worst[model], r)
        n += 1
    assert n > 200
    assert worst["sliding"] < 1e-13
    assert worst["rolling"] < 1e-13


def test_a_state_off_the_family_is_not_steady():
    """The check above can fail: the same state with lam off (S3) by 1 % leaves a residual of
    the size of the torque imbalance, 2 % of mu fr_inv |q| sin(theta) = 6e-4 here (over A_G ~ 1)."""
    t = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, mu=MU)
    c = -0.9
    lam = 1.01 * family.precession_rate(c, q=-0.1, sigma=1.0, fr_inv=0.3, mu=MU)
    y = family.state_vector(math.acos(c), lam, t["q"])
    assert np.max(np.abs(_precessing_residual(y, lam, t, "sliding"))) > 3e-4


def test_steady_states_integrals_match_the_closed_forms():
    """J and E computed by steady_states on the state vectors (quantities.h_cg, energy_parts)
    equal J = lam D(c) and U_J(c) (S4, S5); rounding: a few u of the terms (measured 7.7e-16)."""
    tops, rng = random_tops(60, 2)
    worst = 0.0
    for t in tops:
        J = rng.uniform(-3, 3)
        ds = stability.steady_states(jellett=J, **t)
        c = np.cos(np.radians(ds.tilt.values))
        u = family.effective_potential(c, J, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"])
        worst = max(worst, np.max(np.abs(ds.energy.values - u)) / max(1.0, np.max(np.abs(u))))
        worst = max(worst, np.max(np.abs(ds.jellett.values - J)) / max(1.0, abs(J)))
        tilted = ds.kind.values == "tilted"
        lam = ds.precession_rate.values[tilted]
        assert np.allclose(lam * family.d_of_c(c[tilted], t["q"], t["sigma"], t["mu"]), J, rtol=1e-13, atol=0)
        assert np.allclose(ds.axial_spin.values[tilted], lam * (c[tilted] + t["q"]), rtol=1e-13, atol=1e-15)
    assert worst < 1e-14


def test_default_level_is_the_upright_spin_and_states_are_ordered_by_tilt():
    ds = stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    assert ds.attrs["tippe_stability_product"] == "steady_states"
    assert float(ds.jellett[0]) == pytest.approx(0.9, rel=1e-15)  # sigma (1 + q), spin 1
    assert list(ds.kind.values) == ["upright", "tilted", "inverted"]
    assert np.all(np.diff(ds.tilt.values) > 0)
    up = ds.isel(state=0)
    assert float(up.omega_vertical) == 1.0 and np.isnan(float(up.precession_rate))
    assert ds.tilt.attrs["units"] == "degree" and ds.attrs["Conventions"] == "CF-1.10"
    for name in ("k_norm", "jellett", "rotation"):
        assert f"removed_neutral_{name}" in ds.attrs


def test_vertical_states_agree_with_eq11_at_the_equivalent_spin():
    """At a vertical state of spin n the 6 physical eigenvalues (fixed frame) are eq. (11)'s s at
    (fr_inv / n^2, alpha_v / |n|, +-q) times |n|, and their conjugates (real 6-dimensional form);
    the verdicts equal stability.spectrum's. Tolerance 1e-12 max(1, |s|): the complex-step
    Jacobian and the 6 x 6 eigenproblem round at ~1e3 u (measured 2.8e-15)."""
    tops, rng = random_tops(120, 3)
    worst = 0.0
    for t in tops:
        ds = stability.steady_states(jellett=rng.uniform(0.2, 3.0) * rng.choice([-1, 1]), **t)
        for i in np.nonzero(ds.kind.values != "tilted")[0]:
            s = ds.isel(state=i)
            n = float(s.omega_vertical)
            ref = stability.spectrum(
                "sliding",
                q=float(s.equivalent_q),
                fr_inv=float(s.equivalent_fr_inv),
                sigma=t["sigma"],
                alpha_v=float(s.equivalent_alpha_v),
                mu=t["mu"],
            )
            lin = ref.eigenvalues * abs(n)
            both = np.sort_complex(np.concatenate([lin, lin.conj()]))
            got = np.sort_complex(s.mode_growth_rate.values + 1j * s.mode_frequency.values)
            worst = max(worst, np.max(np.abs(got - both)) / max(1.0, np.max(np.abs(both))))
            assert int(s.stability) == int(ref.stability), (t, str(s.kind.values), n)
            assert float(s.growth_rate) == pytest.approx(float(lin.real.max()), abs=1e-12 * max(1, np.abs(lin).max()))
    assert worst < 1e-12


def _tilted_samples(n_tops, seed):
    tops, rng = random_tops(n_tops, seed)
    for t in tops:
        cs = rng.uniform(-0.995, 0.995, 8)
        lam = family.precession_rate(cs, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"])
        ok = np.isfinite(lam)
        if ok.any():
            yield t, cs[ok], lam[ok]


def test_tilted_verdicts_energy_criterion_equals_reduced_jacobian():
    """The sign of U_J'' (closed form, S8) decides stable/unstable exactly as the reduced
    Jacobian does, away from |U''| < 1e-9 of its terms (where the Jacobian's 1e3 u ||A||
    tolerance calls a mode neutral); and no complex mode of an energetically stable state has a
    positive real part (no Hopf bifurcation; measured max Re / ||A|| = -3.6e-11)."""
    agree = total = 0
    max_complex = -np.inf
    for t, cs, lam in _tilted_samples(500, 4):
        p = pack(q=t["q"], fr_inv=t["fr_inv"], sigma=t["sigma"], mu=t["mu"], alpha_v=t["alpha_v"])
        y = family.state_vector(np.arccos(cs), lam, t["q"])
        ev, scale = reduced_spectrum(y, lam, np.zeros(len(cs), bool), p, q=t["q"], sigma=t["sigma"], mu=t["mu"])
        _, _, verdict = modes_verdict(ev, scale)
        for i, c in enumerate(cs):
            J = lam[i] * family.d_of_c(c, t["q"], t["sigma"], t["mu"])
            test, size = family.energy_test("tilted", c, J, q=t["q"], sigma=t["sigma"], fr_inv=t["fr_inv"], mu=t["mu"])
            if abs(test) < 1e-9 * size:
                continue
            total += 1
            agree += (verdict[i] == 0) == (test > 0) and (verdict[i] == 2) == (test < 0)
            if test > 0:
                cplx = ev[i][np.abs(ev[i].imag) > 1e-9]
                if cplx.size:
                    max_complex = max(max_complex, cplx.real.max() / scale[i])
    assert total > 1500
    assert agree == total
    assert max_complex < 0


def test_the_three_structural_neutral_directions():
    """At tilted states of random tops: (0, k, 0) and grad J are left null vectors of A (the
    second on ker l1), and the orbit direction G y* is a right null vector; the 8 x 8 A has a
    simple zero and a 2 x 2 Jordan block (a pair split to ~sqrt(u)). Tolerances relative to
    ||A||: 1e-13 for the null vectors (complex-step A, exact to rounding), 1e-6 for the
    Jordan pair (sqrt(u) ~ 1.5e-8, measured 1.3e-8)."""
    worst = 0.0
    for t, cs, lam in _tilted_samples(40, 5):
        p = pack(q=t["q"], fr_inv=t["fr_inv"], sigma=t["sigma"], mu=t["mu"], alpha_v=t["alpha_v"])
        y = family.state_vector(np.arccos(cs), lam, t["q"])
        A = precessing_jacobians(y, lam, p)
        l1, l2 = neutral_covectors(y, q=t["q"], sigma=t["sigma"], mu=t["mu"])
        for i in range(len(cs)):
            a = np.linalg.norm(A[i])
            T = np.linalg.svd(l1[i][None])[2][1:].T  # basis of ker l1
            worst = max(
                worst,
                np.abs(l1[i] @ A[i]).max() / a,
                np.abs(l2[i] @ A[i] @ T).max() / a,
                np.abs(A[i] @ (ROTATION @ y[i])).max() / a,
            )
            small = np.sort(np.abs(np.linalg.eigvals(A[i])))[:3] / a
            assert small[0] < 1e-13 and small[2] < 1e-6
    assert worst < 1e-13


@pytest.mark.parametrize("q,fr_inv", [(-0.1, 0.0), (0.0, 0.3)])
def test_structural_zeros_are_marginal(q, fr_inv):
    """fr_inv = 0 or q = 0: eq. (11) has an exact zero root at the vertical states (a continuum
    of rolling motions beside them), flagged marginal as the linear atlases flag it; at q = 0 the
    tilted state (c = 0) too. Reference: stability.spectrum's flag at the equivalent point. (At
    fr_inv = 0, q != 0 the tilted state c0 is no continuum: its flag is the energy criterion's.)"""
    ds = stability.steady_states(q=q, sigma=1.2 if q else 0.8, fr_inv=fr_inv, alpha_v=0.5, jellett=1.1)
    for i in range(ds.sizes["state"]):
        s = ds.isel(state=i)
        if str(s.kind.values) == "tilted":
            if q == 0.0:
                assert int(s.stability) == 1 and float(s.tilt) == pytest.approx(90.0, abs=1e-12)
            else:
                c0 = family.c0(q, 1.2, MU)
                assert float(s.tilt) == pytest.approx(math.degrees(math.acos(c0)), abs=1e-12)
                assert int(s.stability) == (0 if float(s.energy_test) > 0 else 2)
            continue
        ref = stability.spectrum(
            "sliding",
            q=float(s.equivalent_q),
            fr_inv=float(s.equivalent_fr_inv),
            sigma=float(ds.attrs["sigma"]),
            alpha_v=float(s.equivalent_alpha_v),
        )
        assert int(s.stability) == int(ref.stability)
        assert int(s.stability) in (1, 2)


def test_paper_run_level_has_the_hanging_state_at_166_degrees():
    """The Jellett level of the paper's Fr^-1 = 0.3 run (Sec. 3(ii), printed initial state):
    three states, only the tilted one stable; its tilt is the root of the quartic (S6) and the
    run settles there (tests/test_steady_final.py). The inverted spin is unstable on this level:
    |J0| = 0.90012 < J_inv = 0.90306 (closed form)."""
    from stability.nonlinear.scene import INITIAL_CONDITIONS

    end = stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3])
    ds = stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, jellett=end.jellett)
    assert list(ds.stability.values) == [2, 0, 2]
    assert float(ds.tilt[1]) == pytest.approx(166.018431, abs=1e-6)
    assert abs(end.jellett) < family.branch_point_jellett("inverted", q=-0.1, sigma=1.0, fr_inv=0.3, mu=MU)


def test_without_friction_no_state_is_asymptotically_stable():
    """alpha_v = 0: the energy is conserved (and horizontal momentum: two more zero modes), so the
    flag is the Jacobian's with 'stable' demoted to 'marginal'; an energy maximum may still be
    gyroscopically stable, so unstable states are those whose Jacobian says so."""
    ds = stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.0)
    assert 0 not in ds.stability.values
    assert np.array_equal(ds.stability.values == 2, ds.stability_jacobian.values == 2)
    assert np.all(ds.n_neutral.values >= 1)


@pytest.mark.parametrize(
    "kw,exc,fragment",
    [
        (dict(jellett=float("nan")), ValueError, "jellett = nan is not finite"),
        (dict(jellett="1"), TypeError, "jellett = '1' is a str"),
        (dict(jellett=[1.0, 2.0]), TypeError, "jellett must be a single number here"),
        (dict(sigma=2.5), ValueError, "sigma = 2.5 is outside the physical domain"),
        (dict(fr_inv=-0.1), ValueError, "fr_inv = -0.1 is outside the physical domain: fr_inv >= 0"),
        (dict(alpha_v=None), TypeError, "alpha_v is required"),
        (dict(model="fixed_pivot"), ValueError, "model = 'fixed_pivot' is not known; choose one of sliding"),
    ],
)
def test_bad_input(kw, exc, fragment):
    args = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    args.update(kw)
    with pytest.raises(exc, match=fragment):
        stability.steady_states(**args)
