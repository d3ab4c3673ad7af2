"""Stick and slip with Coulomb friction (stability.stick_slip) and a Coulomb top's end.

References: an independent hybrid built here on the plain-numpy right-hand sides of
suites.reference (benchmarks/) (a different elimination of the same equations) with the needed
rolling friction and N from Newton's law for G written here, integrated by scipy's DOP853 with
its own events; a closed form of the slip's extinction for the uniform ball (q = 0, sigma = 1);
the integrals of pure rolling (energy, Jellett's h_cg); the Coulomb bound |f| <= alpha_s.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from suites.reference import rolling_rhs, sliding_rhs

import stability
from stability.errors import InputError
from stability.nonlinear.friction import traction
from stability.steady.coulomb import rolling_band

TOP = dict(q=-0.1, sigma=1.0, mu=2.28, fr_inv=0.3)
TH = math.radians(30.0)
#: a wobbling launch with weak Coulomb friction that sticks and slips again and again
LAUNCH = dict(omega=[1.0, 0.0, 0.5], k=[math.sin(TH), 0.0, math.cos(TH)], velocity=[0.3, 0.0])
ALPHA_K = 0.02
#: static limit above the kinetic one (mu_S > mu_K, as Kane and Levinson take it): the slip
#: then restarts decisively (with alpha_s = alpha_k it grows from the seed at second order only,
#: which costs the plain-numpy reference ~1e5 right-hand sides)
ALPHA_S = 0.022
THRESHOLD = 1e-10
_K = np.array([0.0, 0.0, 1.0])


@pytest.fixture(scope="module")
def run():
    return stability.stick_slip(
        t_end=62.0, **TOP, **LAUNCH, alpha_k=ALPHA_K, alpha_s=ALPHA_S, rtol=1e-11, atol=1e-14, slip_threshold=THRESHOLD
    )


def _need(y8):
    """Friction and N that keep the contact at rest: Newton's law for G, mu a_G = f + (N - mu fr_inv) K,
    a_G = V0' + q k'' with V0' = -K x omega' (reference.rolling_rhs gives omega')."""
    q, fr, mu = TOP["q"], TOP["fr_inv"], TOP["mu"]
    w, k = y8[0:3], y8[3:6]
    wd = rolling_rhs(0.0, y8, q, fr, TOP["sigma"], mu)[0:3]
    a_g = -np.cross(_K, wd) + q * (np.cross(wd, k) + np.cross(w, np.cross(w, k)))
    return mu * a_g[:2], mu * a_g[2] + mu * fr


def _reference_switches(t_end):
    """The Kane-Levinson hybrid with the reference right-hand sides and the same switch rules."""
    q, fr, sg, mu = TOP["q"], TOP["fr_inv"], TOP["sigma"], TOP["mu"]
    k = np.array(LAUNCH["k"]) / np.linalg.norm(LAUNCH["k"])
    y = np.concatenate([LAUNCH["omega"], k, LAUNCH["velocity"], [0.0, 0.0]])

    def slip(t, y):
        return sliding_rhs(t, y, q, fr, sg, mu, 0.0, ALPHA_K, 0.0, 0)

    def roll(t, y):
        return rolling_rhs(t, y, q, fr, sg, mu)

    def stop(t, y):
        return math.hypot(y[6] - y[1], y[7] + y[0]) - THRESHOLD

    def brk(t, y):
        return ALPHA_S - float(np.hypot(*_need(y)[0]))

    stop.terminal = brk.terminal = True
    stop.direction = brk.direction = -1
    t, sticking, out = 0.0, False, []
    while t < t_end:
        sol = solve_ivp(
            roll if sticking else slip,
            (t, t_end),
            y,
            method="DOP853",
            rtol=1e-11,
            atol=1e-14,
            events=brk if sticking else stop,
        )
        if sol.t_events[0].size == 0:
            break
        t, ye = float(sol.t_events[0][0]), sol.y_events[0][0]
        if sticking:
            f = _need(ye)[0]
            e = -f / np.hypot(*f)
            y = np.concatenate([ye[0:6], [ye[1], -ye[0]] + 2 * THRESHOLD * e, ye[6:8]])
            out.append((t, "slip"))
        else:
            y = np.concatenate([ye[0:6], ye[8:10]])
            out.append((t, "stick"))
        sticking = not sticking
    return out


def test_switch_times_match_an_independent_hybrid(run):
    """Reference: the hybrid of _reference_switches (DOP853 with events on reference.py's
    right-hand sides and the needed friction from Newton's law for G). Tolerance 1e-6 relative
    (the issue's): both integrate to rtol 1e-11, the events are located on the dense output to
    round-off, the threshold 1e-10 moves a stick by ~1e-10 / rate; 1e-6 is far above."""
    ref = _reference_switches(62.0)
    assert [k for _, k in ref] == ["stick", "slip", "stick"]  # it sticks, slips and sticks again
    assert [k for _, k in ref] == list(run.switch_kind.values)
    np.testing.assert_allclose(run.switch_time.values, [t for t, _ in ref], rtol=1e-6)


def test_rolling_keeps_energy_and_jellett(run):
    """Reference: the integrals of the rolling top (paper, Sec. 3(i)). Energy constant within
    each stick phase, to 1e-9 relative (rtol 1e-11 over < 10 time units per phase); Jellett's
    h_cg constant throughout (every contact force acts at C), 1e-8 over the run."""
    ph = run.phase.values
    e = run.energy.values
    starts = np.flatnonzero(np.diff(ph) == 1) + 1
    ends = np.flatnonzero(np.diff(ph) == -1)
    assert starts.size >= 1 and ends.size >= 1
    for a in starts:
        b = ends[ends > a][0] if (ends > a).any() else ph.size - 1
        seg = e[a : b + 1]
        assert np.ptp(seg) < 1e-9 * abs(seg[0])
    assert np.ptp(run.h_cg.values) < 1e-8 * abs(float(run.h_cg[0]))
    # and slipping dissipates: the energy falls over each slip phase
    assert float(run.energy[-1]) < float(run.energy[0])


def test_friction_within_the_coulomb_bound(run):
    """Reference: the Coulomb law itself. Sticking: |f| <= alpha_s, to 1e-9
    (the event's location in round-off); at each stick -> slip switch the needed friction equals
    the limit to 1e-8; slipping (alpha_v = 0): |f| = alpha_k exactly (eq. 7 without
    regularisation), to 1e-12."""
    st = run.phase.values == 1
    ratio = run.friction_magnitude.values / run.friction_limit.values
    assert ratio[st].max() <= 1.0 + 1e-9
    slips = run.switch_kind.values == "slip"
    np.testing.assert_allclose(run.switch_friction_ratio.values[slips], 1.0, atol=1e-8)
    assert np.all(run.switch_friction_ratio.values[~slips] <= 1.0)
    np.testing.assert_allclose(run.friction_magnitude.values[~st], ALPHA_K, rtol=1e-12)
    assert np.all(run.normal_force.values > 0)


def test_uniform_ball_stops_slipping_at_the_closed_form_time():
    """Closed form: for q = 0, sigma = 1 (I0 = 1 whatever k) eqs. (1)-(2) give V0' = f / mu and
    omega' = -K x f, so V_c' = V0' + K x omega' = (1 + 1/mu) f = -alpha_k (1 + 1/mu) e_v (alpha_v
    = 0): the slip falls linearly, |V_c(t)| = |V_c0| - alpha_k (1 + 1/mu) t, and the ball then
    rolls needing no friction (it sticks for good). Tolerance 1e-9 relative: the threshold 1e-10
    over the rate ~0.1, and the integrator's error."""
    mu, ak = 2.28, 0.1
    ds = stability.stick_slip(
        t_end=10.0,
        q=0.0,
        sigma=1.0,
        mu=mu,
        fr_inv=0.3,
        alpha_k=ak,
        omega=[0.2, -0.1, 3.0],
        k=[0.1, 0.0, 1.0],
        velocity=[0.05, 0.3],
    )
    vc0 = math.hypot(0.05 - (-0.1), 0.3 + 0.2)
    assert list(ds.switch_kind.values) == ["stick"]
    assert float(ds.switch_time[0]) == pytest.approx(vc0 / (ak * (1 + 1 / mu)), rel=1e-9)
    assert float(ds.switch_friction_ratio[0]) < 1e-12
    assert ds.attrs["final_phase"] == "stick"


def _effective_potential_by_minimising(c, jellett):
    """U_J(c) from its definition: the least energy of a state with axis height c and Jellett's
    integral J, E = mu |v_G|^2 / 2 + omega . I_G omega / 2 + mu fr_inv z_G, minimised over the
    horizontal velocity of O (which zeroes v_G's horizontal part, leaving v_G . K = q omega .
    (k x K) since O stays at height 1) and over omega on the plane (K + q k) . I_G omega = J (eq.
    10), by scipy's BFGS on the plane's two coordinates; I_G = A_G 1 + (sigma - A_G) k k^T,
    A_G = 1 - mu q^2, z_G = 1 + q c (G = O + q k)."""
    from scipy.optimize import minimize

    q, sg, fr, mu = TOP["q"], TOP["sigma"], TOP["fr_inv"], TOP["mu"]
    k = np.array([math.sqrt(max(0.0, 1.0 - c * c)), 0.0, c])
    a_g = 1.0 - mu * q * q
    i_g = a_g * np.eye(3) + (sg - a_g) * np.outer(k, k)
    a = i_g @ (_K + q * k)
    base = jellett * a / (a @ a)  # on the plane
    plane = np.linalg.svd(a[None, :])[2][1:]  # two unit vectors normal to a

    def energy(s):
        w = base + s @ plane
        return 0.5 * mu * (q * w @ np.cross(k, _K)) ** 2 + 0.5 * w @ i_g @ w + mu * fr * (1.0 + q * c)

    return minimize(energy, np.zeros(2), method="BFGS", options={"gtol": 1e-13}).fun


def test_final_state_of_a_coulomb_top_is_rolling_in_its_band():
    """Reference: the energy principle E >= U_J(c), U_J written here from its definition
    (_effective_potential_by_minimising): the band's ends solve U_J(c) = E, to 1e-9 of E (the
    ends are bisected to round-off; BFGS on a convex quadratic stops at a gradient 1e-13, an
    energy error ~1e-26; measured agreement 2e-16; 1e-9 leaves room for the minimiser's line
    search, and an end off by 0.001 degree already moves U_J by 8e-7 of E); an end at the
    vertical must have U_J <= E there; and the tilts the hybrid run shows after its
    last stick lie inside the band; E and J of the answer are the run's (conserved while rolling)."""
    end = stability.final_state(**TOP, **LAUNCH, alpha_v=0.0, alpha_k=0.03, t_max=200.0)
    assert end.kind == "rolling" and end.method == "simulation"
    assert end.contact == "held"  # the hybrid run watched N to its end
    assert "rolls without slipping" in end.reason
    lo, hi = rolling_band(end.tilt, end.energy, end.jellett, q=-0.1, sigma=1.0, fr_inv=0.3, mu=2.28)
    assert lo <= end.tilt < hi < 180.0
    for tilt in (lo, hi):
        u = _effective_potential_by_minimising(math.cos(math.radians(tilt)), end.jellett)
        if 0.0 < tilt < 180.0:  # an inner end is a zero of U_J - E
            assert u == pytest.approx(end.energy, rel=1e-9)
        else:  # an end at the vertical: U_J <= E all the way there
            assert u <= end.energy
    ds = stability.stick_slip(t_end=200.0, **TOP, **LAUNCH, alpha_k=0.03)
    t_stick = float(ds.switch_time[-1])
    seen = ds.polar_angle.where(ds.time > t_stick, drop=True).values
    assert lo <= seen.min() and seen.max() <= hi
    assert end.to_dataset().attrs["kind"] == "rolling"


@pytest.mark.parametrize(
    "change, name",
    [
        (dict(alpha_k=0.0), "alpha_k"),
        (dict(alpha_s=0.01), "alpha_s"),
        (dict(fr_inv=0.0), "fr_inv"),
        (dict(slip_threshold=-1.0), "slip_threshold"),
    ],
)
def test_bad_input_names_the_parameter(change, name):
    args = dict(t_end=1.0, **TOP, **LAUNCH, alpha_k=ALPHA_K)
    args.update(change)
    with pytest.raises(InputError, match=name):
        stability.stick_slip(**args)


def test_slip_law_is_the_package_traction():
    """The slip phase uses eq. (7) unregularised: traction with epsilon = 0 is alpha_k e_v."""
    f1, f2 = traction(0.3, -0.4, 0.0, 0.7, 0.0, 0.0)
    assert (f1, f2) == pytest.approx((-0.7 * 0.6, 0.7 * 0.8), rel=1e-15)


def test_plot_marks_every_switch(run):
    """The figure draws the run's switches: one marker per switch, at the run's switch times."""
    from stability.plotting import plot_stick_slip

    fig, axes = plot_stick_slip(run)
    marked = np.concatenate([ln.get_xdata() for ln in axes[0].get_lines() if ln.get_marker() in ("v", "^", "x")])
    np.testing.assert_array_equal(np.sort(marked), np.sort(run.switch_time.values))


def test_a_rolling_start_sticks_from_the_start():
    """A start without slip (V0 = -K x omega) whose rolling needs less than the limit sticks at
    once: phase 1 from t = 0, no switch, and the energy of the rolling top is constant (its
    integral; 1e-9 relative at rtol 1e-10 over 20 time units)."""
    ds = stability.stick_slip(
        t_end=20.0, **TOP, alpha_k=0.2, omega=[0.3, 0.0, 1.5], k=[0.5, 0.0, 0.866], velocity=[0.0, -0.3]
    )
    assert np.all(ds.phase.values == 1) and ds.sizes["switch"] == 0
    assert np.ptp(ds.energy.values) < 1e-9 * abs(float(ds.energy[0]))
    assert float(ds.slip_speed.max()) < 1e-15


#: a launch tilted 60 degrees spinning about a tipped axis: the floor would have to pull
#: (N < 0 at t = 0, by the reference's Newton's law for G: about -0.12 rolling, -0.085 slipping)
_PULLED = dict(omega=[3.0, 0.0, 3.0], k=[math.sin(math.radians(60.0)), 0.0, math.cos(math.radians(60.0))])


def _reference_normal_force(y, slipping):
    """N from Newton's law for G, N = mu fr_inv + mu q (omega' x k + omega x (omega x k)) . K,
    with omega' of reference.py's right-hand sides (alpha_k = 0.03, alpha_v = 0, law (7))."""
    q, fr, sg, mu = TOP["q"], TOP["fr_inv"], TOP["sigma"], TOP["mu"]
    w, k = y[0:3], y[3:6]
    rhs = sliding_rhs(0.0, y, q, fr, sg, mu, 0.0, 0.03, 0.0, 0) if slipping else rolling_rhs(0.0, y, q, fr, sg, mu)
    wd = rhs[0:3]
    return mu * fr + mu * q * (np.cross(wd, k) + np.cross(w, np.cross(w, k)))[2]


@pytest.mark.parametrize(
    "velocity, slipping, normal",
    [
        ([0.0, -3.0], False, "equilibrium"),  # V0 = -K x omega: a rolling start
        ([0.0, -3.0], False, "actual"),  # its static limit alpha_s N / (mu fr_inv) < 0 (was NaN)
        ([0.5, 0.0], True, "equilibrium"),  # a slipping start
    ],
)
def test_a_start_without_contact_force_is_reported_at_once(velocity, slipping, normal):
    """Reference: N at the start from Newton's law for G (_reference_normal_force) is negative
    (checked here: a sign, no tolerance needed, |N| > 0.08). The events fire on a downward
    crossing only, so such a start must be its own event: contact_lost at t = 0, one sample, no
    NaN; final_state's Coulomb path says the contact was lost (issue: it said "not checked")."""
    y = np.concatenate([_PULLED["omega"], _PULLED["k"], velocity, [0.0, 0.0]])
    if not slipping:
        y = np.concatenate([y[0:6], y[8:10]])
    assert _reference_normal_force(y, slipping) < -0.08
    ds = stability.stick_slip(t_end=5.0, **TOP, **_PULLED, velocity=velocity, alpha_k=0.03, normal=normal)
    assert ds.attrs["event"] == "contact_lost" and ds.attrs["event_time"] == 0.0
    assert ds.sizes["time"] == 1 and ds.sizes["switch"] == 0
    assert all(np.isfinite(ds[v].values).all() for v in ("omega", "polar_angle", "friction", "normal_force"))
    assert float(ds.normal_force[0]) <= 0.0
    end = stability.final_state(**TOP, **_PULLED, velocity=velocity, alpha_v=0.0, alpha_k=0.03, t_max=5.0)
    assert (end.kind, end.event, end.event_time, end.contact) == ("contact_lost", "contact_lost", 0.0, "lost")


@pytest.mark.parametrize("change, name", [(dict(stick_tilt=5.0), "stick_tilt"), (dict(simulation=False), "simulation")])
def test_coulomb_final_state_refuses_options_it_cannot_honour(change, name):
    """With alpha_k > 0 the end is the hybrid run's: a stick tilt (no stick event there) or no
    run cannot be honoured, and were silently ignored (the answer was 'rolling' at 17 degrees with
    stick_tilt = 5): now an InputError naming the option."""
    with pytest.raises(InputError, match=name):
        stability.final_state(**TOP, **LAUNCH, alpha_v=0.0, alpha_k=0.03, t_max=200.0, **change)


def test_chattering_has_its_named_status():
    """max_switches = 1 on the launch that sticks, slips and sticks again (the reference hybrid
    above): the run stops after its first switch with the named status CHATTERING (not -1,
    which is MAX_STEPS of the integrators) and a warning."""
    from stability.nonlinear.integrators import CHATTERING, MAX_STEPS, STATUS_MESSAGES

    with pytest.warns(RuntimeWarning, match="chattering"):
        ds = stability.stick_slip(t_end=62.0, **TOP, **LAUNCH, alpha_k=ALPHA_K, alpha_s=ALPHA_S, max_switches=1)
    assert ds.attrs["status"] == CHATTERING != MAX_STEPS and "chattering" in STATUS_MESSAGES[CHATTERING]
    assert ds.attrs["n_switches"] == 1


def test_rolling_band_refuses_an_energy_below_the_potential():
    """Reference: U_J minimised from its definition (_effective_potential_by_minimising). Below it
    (by 1e-3 of U_J, far beyond the accepted slack 1e-8 and the minimiser's error) no state has
    this tilt: a DomainError naming the energy and U_J (it returned (tilt, tilt) before: E = -100
    gave (30, 30)); just above it (1e-3) the band is a small interval around the tilt."""
    from stability.errors import DomainError

    jel = 1.2
    u = _effective_potential_by_minimising(math.cos(math.radians(30.0)), jel)
    for energy in (u - 1e-3 * abs(u), -100.0):
        with pytest.raises(DomainError, match=r"energy = .* U_J"):
            rolling_band(30.0, energy, jel, q=-0.1, sigma=1.0, fr_inv=0.3, mu=2.28)
    lo, hi = rolling_band(30.0, u + 1e-3 * abs(u), jel, q=-0.1, sigma=1.0, fr_inv=0.3, mu=2.28)
    assert lo < 30.0 < hi
