"""The stick: where it touches the floor (closed form against mpmath roots of the height
functions), bad sticks refused, and the top on its stick (critical spin against runs)."""

import itertools
import math

import mpmath
import numpy as np
import pytest

from stability import Stick, Top, critical_spin, simulate
from stability.errors import DomainError, InputError

R = Top.table1().radius  # 0.6366 in


def _mp_contact(r, s, rho, t):
    """Independent: the tilts where the lowest heights of the tip and of the rim reach 0 (mpmath,
    40 digits): the tip's height crosses 0 (bisection from a bracket found on a grid); the rim's
    touches 0 at its minimum (a double zero: its stationary point, by findroot of the derivative,
    where the height is checked to vanish)."""
    mpmath.mp.dps = 40
    r, s, rho, t = (mpmath.mpf(x) for x in (r, s, rho, t))

    def tip(th):
        return r + s * mpmath.cos(th) - rho

    def rim(th):
        return r + t * mpmath.cos(th) - mpmath.sqrt(r * r - t * t) * mpmath.sin(th)

    out = {}
    lo = mpmath.acos(-t / r) * mpmath.mpf("0.9")  # a start near, not at, the closed form
    out["rim"] = mpmath.findroot(lambda th: mpmath.diff(rim, th), lo, tol=mpmath.mpf(10) ** -35)
    assert abs(rim(out["rim"])) < mpmath.mpf(10) ** -30 * r
    for name, h in (("tip", tip),):
        grid = [mpmath.pi * i / 2000 for i in range(2001)]
        lo = next((a for a, b in itertools.pairwise(grid) if h(a) > 0 >= h(b)), None)
        if lo is None:
            out[name] = mpmath.inf
            continue
        out[name] = mpmath.findroot(h, (lo, lo + mpmath.pi / 2000), solver="bisect", tol=mpmath.mpf(10) ** -35)
    part = "tip" if out["tip"] <= out["rim"] else "rim"
    return float(mpmath.degrees(out[part])), part


@pytest.mark.parametrize(
    "s, rho, t",
    [
        (1.25 * R, 0.2 * R, 0.75 * R),  # a toy's proportions: the tip first
        (1.6 * R, 0.1 * R, 0.2 * R),  # a long stick, deep cut: the rim first
        (1.0 * R, 0.15 * R, 0.8 * R),  # a tip that never reaches the floor (s < R - rho): the rim
        (1.1 * R, 0.05 * R, -0.3 * R),  # a cut past the centre
    ],
)
def test_stick_contact_against_mpmath(s, rho, t):
    """Exact to 1e-12 degrees-relative: the closed form (one arccos) against a 35-digit root."""
    top = Top.table1(stick=Stick(s, rho, t))
    tilt, part = top.stick_contact()
    ref, ref_part = _mp_contact(R, s, rho, t)
    assert part == ref_part
    assert abs(tilt - ref) <= 1e-12 * ref


def test_the_paper_toy_touches_with_its_tip():
    top = Top.table1(stick=Stick(0.02, 0.003, 0.012))
    tilt, part = top.stick_contact()
    assert part == "tip" and 90 < tilt < 180


@pytest.mark.parametrize(
    "stick, name",
    [
        (Stick(0.02, R, 0.012), "tip_radius"),  # a tip as large as the sphere
        (Stick(0.03, 0.002, R), "truncation"),  # a plane outside the sphere
        (Stick(0.03, 0.002, -1.2 * R), "truncation"),
        (Stick(0.013, 0.002, 0.012), "tip_center"),  # the tip inside the body: the stick does not fit
    ],
)
def test_bad_sticks_are_refused_naming_the_parameter(stick, name):
    with pytest.raises(DomainError, match=f"^{name} = "):
        Top.table1(stick=stick)


@pytest.mark.parametrize(
    "args, name",
    [
        ((0.0, 0.003, 0.01), "tip_center"),
        ((0.02, -1.0, 0.01), "tip_radius"),
        ((0.02, 0.003, float("nan")), "truncation"),
    ],
)
def test_bad_stick_numbers_are_refused(args, name):
    with pytest.raises(ValueError, match=name):
        Stick(*args)


def test_a_top_without_a_stick_says_so():
    with pytest.raises(InputError, match="no stick"):
        Top.table1().stick_contact()


def test_on_stick_is_the_tip_sphere():
    """q' = (s - d) / rho and A_G, C kept: the closed forms of stability.stick, by hand."""
    top = Top.table1(stick=Stick(0.02, 0.003, 0.012))
    on = top.on_stick()
    assert on.q == pytest.approx((0.02 - top.com_offset) / 0.003, rel=1e-15)
    assert on.q > 1
    assert on.inertia_transverse == top.inertia_transverse and on.inertia_axial == top.inertia_axial
    a0 = top.inertia_transverse + top.mass * (0.02 - top.com_offset) ** 2
    assert 1 - on.mu * on.q**2 == pytest.approx(top.inertia_transverse / a0, rel=1e-12)


@pytest.mark.parametrize("factor, grows", [(1.05, False), (0.95, True)])
def test_critical_spin_on_the_stick_against_runs(factor, grows):
    """The linear threshold of the top on its stick (stability.critical_spin) against the
    nonlinear sliding model started 0.01 degree off the vertical spin on the stick: 5 % above,
    the tilt decays (slowly: rate ~8e-5, so the late maximum is below the early one); 5 % below,
    it grows by orders of magnitude (rate ~0.04)."""
    on = Top.table1(stick=Stick(0.02, 0.003, 0.012)).on_stick()
    c = critical_spin(on, orientation="upright", alpha_v=0.5)
    assert not c.unstable_above
    nd = on.nondimensional(c.spin * factor, alpha_v=0.5)
    th = math.radians(0.01)
    k = np.array([math.sin(th), 0.0, math.cos(th)])
    ds = simulate("sliding", t_end=2000, omega=k, k=k, dt=1, **nd)
    assert ds.attrs["event"] == "none"
    p = ds.polar_angle.values
    if grows:
        assert p.max() > 100 * 0.01
    else:
        assert p[-500:].max() < 0.9 * p[:500].max()
