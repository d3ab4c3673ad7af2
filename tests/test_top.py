"""The dimensional description of a real top against numbers printed in the paper.

References: Table 1's 1/Froude rows (5.53, 1.38, 0.62 at 100, 200, 300 rpm) and Sec. 3(ii)'s
conversions (fr_inv = 0.3 <-> 7.15 rev/s, 0.1 <-> 12.4 rev/s), which hold with R = 0.6366 in
(NOTES.md). Tolerances: half a unit in the last printed digit of the paper's numbers, except
where the paper's own rows disagree with each other (see the tests).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import stability
from stability import Top
from stability.top import INCH, OUNCE


def test_table1_preset_nondimensional():
    t = Top.table1()
    assert t.q == pytest.approx(-0.1, abs=1e-15)
    assert t.mu == pytest.approx(2.28, rel=1e-14)
    assert t.sigma == pytest.approx(1.0, rel=1e-14)


@pytest.mark.parametrize("rpm,printed", [(100, 5.53), (200, 1.38)])
def test_table1_froude_rows(rpm, printed):
    assert Top.table1().fr_inv(rpm, unit="rpm") == pytest.approx(printed, abs=0.005)


def test_table1_300_rpm_row():
    """The printed 0.62 is not 5.53 / 9 = 0.614 (fr_inv ~ 1/Omega^2): the table rounds it up.

    Reference: the printed 100-rpm row scaled by (100/300)^2, to half a unit of its last digit
    scaled likewise (0.005 / 9); the printed 0.62 is within 0.01 (one unit) only.
    """
    f = Top.table1().fr_inv(300, unit="rpm")
    assert f == pytest.approx(5.53 / 9, abs=0.005 / 9 + 1e-12)
    assert abs(f - 0.62) < 0.01


@pytest.mark.parametrize("fr_inv,rev_s", [(0.3, 7.15), (0.1, 12.4)])
def test_sec3_spin_rates(fr_inv, rev_s):
    t = Top.table1()
    # one unit of the last printed digit: 7.156 is printed as 7.15 (truncated), 12.38 as 12.4
    assert t.spin_rate(fr_inv, unit="rev/s") == pytest.approx(rev_s, abs=0.1 if rev_s > 10 else 0.01)


def test_units_round_trip_and_consistency():
    t = Top.table1()
    w = np.array([10.0, 50.0, 200.0])
    assert np.allclose(t.spin_rate(t.fr_inv(w)), w, rtol=1e-14)
    assert t.fr_inv(60.0, "rpm") == pytest.approx(t.fr_inv(1.0, "rev/s"), rel=1e-15)
    assert t.fr_inv(1.0, "rev/s") == pytest.approx(t.fr_inv(2 * math.pi), rel=1e-15)


def test_measured_preset_reproduces_the_inconsistency():
    """mu from the measured mass, radius and moment about O: M R^2 / (A_G + M d^2), by hand."""
    m = Top.table1_measured()
    a0 = 0.066 + 0.64 * (0.094 * 0.63) ** 2  # oz in^2
    assert m.mu == pytest.approx(0.64 * 0.63**2 / a0, rel=1e-12)
    assert m.mu > 3.5  # not the 2.28 listed in Table 1


def test_friction_parameters_eq7():
    t = Top.table1(mu_k=0.2, mu_v=0.01)
    w = 44.92
    f = t.fr_inv(w)
    assert t.alpha_k(w) == pytest.approx(t.mu * f * 0.2, rel=1e-15)
    # alpha_v = mu Omega R Fr^-1 mu_v (eq. 7)
    assert t.alpha_v(w) == pytest.approx(t.mu * w * t.radius * f * 0.01, rel=1e-13)
    nd = t.nondimensional(w)
    assert set(nd) == {"q", "fr_inv", "sigma", "mu", "alpha_v", "alpha_k"}


def test_inverted():
    t = Top.table1()
    assert t.inverted().q == pytest.approx(0.1)
    assert t.inverted().mu == t.mu  # A0 = A_G + M d^2 does not depend on the sign of d
    assert t.inverted().sigma == t.sigma


@pytest.mark.parametrize(
    "field,value,msg",
    [
        ("mass", -1.0, "mass = -1 is outside the allowed range: mass > 0"),
        ("radius", 0.0, "radius = 0 is outside"),
        ("inertia_axial", float("nan"), "inertia_axial = nan is not finite"),
    ],
)
def test_bad_top(field, value, msg):
    kw = dict(
        mass=0.64 * OUNCE, radius=0.6366 * INCH, com_offset=-0.06 * INCH, inertia_transverse=1e-6, inertia_axial=1e-6
    )
    kw[field] = value
    with pytest.raises(ValueError, match=msg):
        Top(**kw)


def test_top_outside_domain():
    # C > 2 A_G violates the triangle inequality of the principal moments
    with pytest.raises(ValueError, match="sigma = .* sigma <= 2"):
        Top(mass=0.01, radius=0.01, com_offset=0.0, inertia_transverse=1e-7, inertia_axial=3e-7)


def test_bad_unit():
    # "Hz" is a spin unit (rev/s) since issue 23; an unknown unit is still refused
    with pytest.raises(ValueError, match="unit = 'kHz'"):
        Top.table1().fr_inv(10, unit="kHz")


def test_nondimensional_takes_alpha_v_when_the_top_has_no_mu_v():
    """Issue 15 item 6: ``eigenvalues("sliding", **top.nondimensional(w))`` needs alpha_v; a Top
    without mu_v takes it as an argument. Reference: the parameters written by hand from eq. (3)
    (fr_inv = g / (Omega^2 R)), whose spectrum must be the same array (same inputs, same code)."""
    t = Top.table1()
    w = 44.92
    nd = t.nondimensional(w, alpha_v=0.5)
    by_hand = dict(q=t.q, fr_inv=t.g / (w**2 * t.radius), sigma=t.sigma, mu=t.mu, alpha_v=0.5)
    assert nd.keys() == by_hand.keys()
    for k in nd:
        assert nd[k] == pytest.approx(by_hand[k], rel=1e-15)
    s = stability.eigenvalues("sliding", **nd)
    assert np.array_equal(s, stability.eigenvalues("sliding", **by_hand))
    # without alpha_v (and no mu_v), asking for a model that needs it names both ways
    with pytest.raises(TypeError, match=r"pass alpha_v=\.\.\. or build the Top with mu_v="):
        t.nondimensional(w, model="sliding")
    # model= returns exactly that model's parameters (no foreign alpha_v for the rolling top)
    assert "alpha_v" not in t.nondimensional(w, alpha_v=0.5, model="fixed_pivot")
    # with mu_v, alpha_v follows from the spin (eq. 7); giving it too is refused
    with pytest.raises(TypeError, match="conflicts with this Top's mu_v"):
        Top.table1(mu_v=0.01).nondimensional(w, alpha_v=0.5)
    with pytest.raises(ValueError, match="alpha_v = -1 is outside the physical domain"):
        t.nondimensional(w, alpha_v=-1)
