"""High-spin classes of tops (stability.top_class, stability.class_atlas).

References:

* Hugenholtz's condition for complete inversion, 1 - alpha < I1/I3 < 1 + alpha (alpha = -q the
  eccentricity of G, I1 = A_G, I3 = C; as cited by Rutstam and by Rauch-Wojciechowski & Rutstam,
  SIGMA 10 (2014) 017), typed in from the literature;
* Rauch-Wojciechowski & Rutstam's threshold of the Jellett integral for inversion,
  lambda_thres = sqrt(m g R^3 I3 alpha) (1 + alpha)^2 / sqrt(1 + alpha - gamma) (abstract of the
  same paper), in the package's units;
* the energy principle of final_state (the steady states of the level below the initial energy)
  at a large finite spin, an independent route to the same classes;
* the closed-form boundaries sigma = A_G / (1 +- q).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import stability
from stability.errors import DomainError
from stability.steady import family
from stability.steady.branch import branch_points
from stability.steady.classes import class_boundaries, class_codes

MU = 2.28


def _random_tops(n, seed):
    rng = np.random.default_rng(seed)
    q = rng.uniform(-0.66, 0.66, n)
    sigma = rng.uniform(0.0, 2.0, n)
    return q, sigma


def test_inverts_is_hugenholtz_band():
    """On 1e5 random tops of the physical domain, 'inverts' holds exactly where
    1 - alpha < gamma < 1 + alpha, alpha = -q > 0, gamma = A_G / sigma: 0 mismatches."""
    q, sigma = _random_tops(100_000, 1)
    names = stability.top_class(q=q, sigma=sigma, mask_unphysical=True)
    inside = names != "outside_domain"
    alpha = -q
    gamma = (1 - MU * q * q) / sigma
    hug = (alpha > 0) & (1 - alpha < gamma) & (gamma < 1 + alpha)
    assert inside.sum() > 50_000
    assert np.array_equal((names == "inverts")[inside], hug[inside])
    assert not np.any((names == "inverts") & (q > 0))


def test_boundaries_are_the_closed_forms():
    """Just above sigma = A_G / (1 + q) a top never inverts, just below it inverts (q < 0, above
    A_G / (1 - q)) or hangs; the hanging tilt is arccos(sigma q / (A_G - sigma)), beyond 90
    degrees for q < 0 and short of it for q > 0."""
    for q in (-0.4, -0.25, -0.1, 0.1, 0.3):
        b = class_boundaries(q)
        up = float(b["never_inverts"])
        if up * 1.001 <= 2 * (1 - MU * q * q):
            assert stability.top_class(q=q, sigma=up * 1.001) == "never_inverts"
        below = stability.top_class(q=q, sigma=up * 0.999)
        if q < 0:
            assert below == "inverts"
            assert stability.top_class(q=q, sigma=float(b["hangs"]) * 0.999) == "hangs"
            assert stability.top_class(q=q, sigma=float(b["hangs"]) * 1.001) == "inverts"
        else:
            assert below == "hangs" and math.isnan(float(b["hangs"]))
    code, tilt = class_codes(np.array([-0.2, 0.2]), np.array([0.5, 0.5]), np.array([MU, MU]))
    assert list(code) == [2, 2] and tilt[0] > 90 > tilt[1]
    c0 = family.c0(-0.2, 0.5, MU)
    assert tilt[0] == pytest.approx(math.degrees(math.acos(c0)), abs=1e-12)


def test_ties_and_the_spherical_top():
    """q = 0, sigma = 1 (every tilt is steady) is never_inverts by convention; sigma* = 1.1433
    (the top of sigma = A_G / (1 + q), at q* = -0.2507) is the paper's 'sigma ~ 1.14': above it
    no top inverts."""
    assert stability.top_class(q=0.0, sigma=1.0) == "never_inverts"
    q_star = -1 + math.sqrt(1 - 1 / MU)
    s_star = 2 * (MU - math.sqrt(MU * (MU - 1)))
    assert float(class_boundaries(q_star)["never_inverts"]) == pytest.approx(s_star, rel=1e-14)
    q = np.linspace(-0.6, 0.6, 2001)
    assert np.nanmax(class_boundaries(q)["never_inverts"][1 - MU * q * q > 0]) == pytest.approx(s_star, rel=1e-6)
    assert stability.top_class(q=q_star, sigma=s_star * 1.0001) == "never_inverts"


def test_inversion_threshold_of_rauch_wojciechowski_and_rutstam_is_the_inverted_branch_point():
    """Their lambda_thres^2 = m g R^3 I3 alpha (1 + alpha)^4 / (1 + alpha - gamma), in the
    package's units (m R^2 / A0 = mu, g / (R Omega^2) = fr_inv, I3 / A0 = sigma): mu fr_inv sigma
    alpha (1 + alpha)^4 / (1 + alpha - gamma). It equals the closed-form J_inv and the inverted
    branch point located on the nonlinear rhs (stability.steady.branch.branch_points), 1e-12."""
    rng = np.random.default_rng(2)
    checked = 0
    while checked < 10:
        q = rng.uniform(-0.4, -0.02)
        sigma = rng.uniform(0.1, 2 * (1 - MU * q * q))
        fr = rng.uniform(0.05, 1.0)
        alpha, gamma = -q, (1 - MU * q * q) / sigma
        if not 1 + alpha - gamma > 0:
            continue
        rr = math.sqrt(MU * fr * sigma * alpha * (1 + alpha) ** 4 / (1 + alpha - gamma))
        assert family.branch_point_jellett("inverted", q=q, sigma=sigma, fr_inv=fr, mu=MU) == pytest.approx(
            rr, rel=1e-12
        )
        assert branch_points(q=q, sigma=sigma, fr_inv=fr)["inverted"] == pytest.approx(rr, rel=1e-12)
        checked += 1


def test_ueda_group_three_angle_is_c0():
    """Ueda, Sasaki and Watanabe's group III end angle, cos(theta_f) = -alpha / (A/C - 1) (as
    recalled in docs/steady_states.md, not checked against their text), with A/C = gamma, is
    c0 = sigma q / (A_G - sigma)."""
    for q, sigma in ((-0.3, 0.5), (-0.2, 0.6), (-0.1, 0.8)):
        gamma = (1 - MU * q * q) / sigma
        assert family.c0(q, sigma, MU) == pytest.approx(q / (gamma - 1), rel=1e-14)


def test_classes_agree_with_the_energy_principle_at_high_finite_spin():
    """For tops launched upright (tilt 1e-6 rad, spin 1) with mu fr_inv / J^2 = 1e-8, final_state
    (steady states of the level below the initial energy, closed forms) ends upright for
    never_inverts (or is bistable, upright and inverted both stable, for q < 0), inverted for
    inverts, and at arccos(c0) for hangs (within 1e-4 degree: the finite-spin shift is
    O(mu fr_inv / J^2)). Tops within 1e-3 of a boundary are skipped (the limit is not reached).
    The start tilt is 1e-6: the nutation of a tilted start changes the normal force by
    O(tilt^2) (up to ~0.2 tilt^2 for these tops), against mu fr_inv ~ 1e-9..1e-8 here; at 1e-3
    the sphere leaves the floor at once and final_state rightly answers "contact_lost"."""
    q, sigma = _random_tops(600, 3)
    checked = bistable = 0
    for qi, si in zip(q, sigma):
        ag = 1 - MU * qi * qi
        if not (ag > 0 and 0 < si <= 2 * ag) or qi == 0:
            continue
        if min(abs(si * (1 + qi) - ag), abs(si * (1 - qi) - ag)) < 1e-3:
            continue
        fr = 1e-8 * (si * (1 + qi)) ** 2 / MU
        th = 1e-6
        end = stability.final_state(
            q=qi, sigma=si, fr_inv=fr, alpha_v=0.5, omega=[0, 0, 1], k=[math.sin(th), 0, math.cos(th)], simulation=False
        )
        cls = stability.top_class(q=qi, sigma=si)
        if cls == "never_inverts" and qi < 0 and end.method == "simulation":
            assert "bistable" in end.reason
            bistable += 1
        elif cls == "never_inverts":
            assert end.kind == "upright"
        elif cls == "inverts":
            assert end.kind == "inverted"
        else:
            assert end.kind == "tilted"
            assert end.tilt == pytest.approx(math.degrees(math.acos(family.c0(qi, si, MU))), abs=1e-4)
        checked += 1
    assert checked > 200 and bistable > 10


def test_class_atlas():
    q = np.linspace(-0.6, 0.6, 61)
    sigma = np.linspace(0.02, 2.0, 50)
    ds = stability.class_atlas(q=q, sigma=sigma)
    assert ds.attrs["tippe_stability_product"] == "top_classes"
    assert ds.top_class.dims == ("q", "sigma") and ds.top_class.dtype == np.int8
    assert list(ds.top_class.attrs["flag_values"]) == [-1, 0, 1, 2]
    assert ds.top_class.attrs["flag_meanings"] == "outside_domain never_inverts inverts hangs"
    names = stability.top_class(q=q[:, None], sigma=sigma[None, :], mask_unphysical=True)
    codes = {"outside_domain": -1, "never_inverts": 0, "inverts": 1, "hangs": 2}
    assert np.array_equal(ds.top_class.values, np.vectorize(codes.get)(names))
    ag = 1 - MU * q * q
    assert np.allclose(ds.sigma_never_inverts.values, ag / (1 + q), rtol=1e-14)
    assert np.isnan(ds.sigma_hangs.values[q >= 0]).all()
    assert np.array_equal(np.isnan(ds.high_spin_tilt.values), ds.top_class.values == -1)


def test_a_million_tops():
    """Shape and dtype only (the timing is in the bench, tippe bench --suite steady)."""
    q, sigma = _random_tops(1_000_000, 4)
    names = stability.top_class(q=q, sigma=sigma, mask_unphysical=True)
    assert names.shape == (1_000_000,) and names.dtype.kind == "U"


@pytest.mark.parametrize(
    "call,exc,fragment",
    [
        (lambda: stability.top_class(q=0.9, sigma=1.0), DomainError, "q = 0.9 is outside the physical domain"),
        (lambda: stability.top_class(q=-0.1, sigma=3.0), DomainError, "sigma = 3 is outside the physical domain"),
        (lambda: stability.top_class(q="a", sigma=1.0), TypeError, "q = 'a' is a str"),
        (lambda: stability.top_class(q=[0.1, 0.2], sigma=[1.0, 1.0, 1.0]), DomainError, "do not broadcast"),
        (lambda: stability.top_class(q=-0.1, sigma=1.0, mask_unphysical=1), TypeError, "mask_unphysical = 1"),
        (lambda: stability.class_atlas(q=[[0.1]], sigma=1.0), TypeError, "q must be a number or a 1-D array"),
        (
            lambda: stability.class_atlas(q=-0.1, sigma=[1.0, 3.0], mask_unphysical=False),
            DomainError,
            "sigma = 3 is outside the physical domain",
        ),
    ],
)
def test_bad_input(call, exc, fragment):
    with pytest.raises(exc, match=fragment):
        call()


def test_outside_points_are_named_when_masked():
    assert stability.top_class(q=0.9, sigma=1.0, mask_unphysical=True) == "outside_domain"


def test_class_atlas_over_mu():
    """mu as a dimension: the boundaries over (q, mu) are A_G / (1 +- q) with A_G = 1 - mu q^2."""
    q = np.linspace(-0.4, 0.4, 9)
    mu = np.array([1.5, 2.28, 3.0])
    ds = stability.class_atlas(q=q, sigma=0.9, mu=mu)
    assert ds.top_class.dims == ("q", "mu") and ds.sigma_never_inverts.dims == ("q", "mu")
    ag = 1 - mu[None, :] * q[:, None] ** 2
    assert np.allclose(ds.sigma_never_inverts.values, ag / (1 + q[:, None]), rtol=1e-14)
