"""Flight and landing after the contact is lost (``on_contact_loss="continue"``).

References, each independent of :mod:`stability.nonlinear.flight`'s closed form:

* the free flight integrated by scipy's DOP853 on a right-hand side written here (Newton for G
  under gravity; Euler's law about G in the fixed frame with ``omega = I_G(k)^-1 L`` solved
  numerically at every evaluation, ``k' = omega x k``) with a terminal event on the height of
  the sphere's lowest point: the landing time to 1e-11 relative (what DOP853 at rtol 1e-12
  justifies; the closed form's Brent search is at round-off), the state along the flight to 1e-9;
* conserved quantities of the flight (energy, angular momentum about G) along the run's
  flight samples, to 1e-12 (round-off of the closed form);
* the impact's conservation laws (horizontal momentum, angular momentum about the contact
  point, Jellett's integral) and the plastic law ``v_C+ . K = 0``, from the states before and
  after, to 1e-12.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from stability import simulate
from stability.errors import InputError
from stability.nonlinear.flight import body_state, flight_motion, impact, landing_height, landing_time

MU, Q, FR, SG = 2.28, -0.1, 0.05, 1.0
K = np.array([0.0, 0.0, 1.0])


def _unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


def _run(omega=(4.0, 0.0, 1.0), t_end=30.0, **kw):
    return simulate(
        "sliding",
        t_end=t_end,
        q=Q,
        fr_inv=FR,
        sigma=SG,
        alpha_v=0.5,
        omega=list(omega),
        k=_unit([0.3, 0, 1]),
        velocity=[0, 0],
        normal="actual",
        on_contact_loss="continue",
        **kw,
    )


def _inertia(k):
    a_g = 1.0 - MU * Q * Q
    return a_g * np.eye(3) + (SG - a_g) * np.outer(k, k)


def _takeoff():
    ds = _run()
    t0 = ds.attrs["takeoff_times"][0]
    i = int(np.nonzero(ds.time.values == t0)[0][0])
    y = np.concatenate([ds.omega[i].values, ds.k[i].values, ds.velocity[i].values[:2], ds.position[i].values[:2]])
    return ds, y


def _free_fall_reference(y, t_max):
    """DOP853 on Newton + Euler about G (fixed frame), event: lowest point at the floor."""
    w, k = y[0:3], y[3:6]
    x_o = np.array([y[8], y[9], 1.0])
    v_o = np.array([y[6], y[7], 0.0])
    l_g = _inertia(k) @ w

    def f(t, s):
        kk = s[0:3]
        om = np.linalg.solve(_inertia(kk), l_g)
        return np.concatenate([np.cross(om, kk), s[6:9], [0.0, 0.0, -FR]])

    def height(t, s):
        return s[5] - Q * s[2] - 1.0

    height.terminal = True
    height.direction = -1
    s0 = np.concatenate([k, x_o + Q * k, v_o + Q * np.cross(w, k)])
    sol = solve_ivp(f, (0.0, t_max), s0, method="DOP853", rtol=1e-12, atol=1e-14, events=height, dense_output=True)
    return sol, l_g


def test_landing_time_against_independent_dop853():
    """Tolerance 1e-11 relative: DOP853 at rtol 1e-12 (atol 1e-14) carries a state error of
    order 1e-12, which moves the zero of the height by ~1e-12 / |h'| with |h'| = 0.16 at this
    landing, ~6e-12 in time or ~2e-12 of tau = 3.83; the closed form's time is Brent's to 4
    machine epsilons. Measured: 6e-14."""
    ds, y = _takeoff()
    f = body_state("sliding", y, q=Q, fr_inv=FR, sigma=SG, mu=MU)
    tau = landing_time(f)
    ref, l_g = _free_fall_reference(y, 50.0)
    t_ref = ref.t_events[0][0]
    assert abs(tau - t_ref) <= 1e-11 * t_ref
    # the run's own landing is the same flight
    assert abs(ds.attrs["landing_times"][0] - ds.attrs["takeoff_times"][0] - t_ref) <= 1e-11 * t_ref
    # the closed form along the flight against the integrated one: k and G
    taus = np.linspace(0.0, tau, 37)
    w, k, x_o, v_o = flight_motion(f, taus)
    s = ref.sol(taus).T
    np.testing.assert_allclose(k, s[:, 0:3], atol=1e-9)
    np.testing.assert_allclose(x_o + Q * k, s[:, 3:6], atol=1e-9)
    np.testing.assert_allclose(np.array([_inertia(kk) @ ww for kk, ww in zip(k, w)]), np.tile(l_g, (37, 1)), atol=1e-12)
    assert landing_height(f, np.array([tau]))[0] == pytest.approx(0.0, abs=1e-14)


def test_flight_conserves_energy_and_angular_momentum():
    ds = _run()
    fly = ds.contact.values == 0
    assert fly.sum() > 20
    # no friction, gravity only: the energy is constant within each flight
    for t0, t1 in zip(ds.attrs["takeoff_times"], np.append(ds.attrs["landing_times"], np.inf)):
        seg = fly & (ds.time.values > t0) & (ds.time.values < t1)
        if seg.sum() > 1:
            e = ds.energy.values[seg]
            assert np.ptp(e) <= 1e-12 * abs(e[0])
            l_g = np.array([_inertia(k) @ w for k, w in zip(ds.k.values[seg], ds.omega.values[seg])])
            assert np.max(np.ptp(l_g, axis=0)) <= 1e-12
    assert np.all(ds.normal_force.values[fly] == 0.0)
    assert np.all(ds.height.values[fly] >= -1e-15)  # 0 at a landing that leaves the floor at once


def test_impact_is_plastic_and_conserves_what_it_should():
    _, y = _takeoff()
    f = body_state("sliding", y, q=Q, fr_inv=FR, sigma=SG, mu=MU)
    tau = landing_time(f)
    w0, k, x_o, v_o0 = (a[0] for a in flight_motion(f, np.array([tau])))
    w1, k1, v_o1, landing = impact(f, tau)
    r = -K - Q * k  # from G to the contact point
    vg0, vg1 = v_o0 + Q * np.cross(w0, k), v_o1 + Q * np.cross(w1, k)
    lg0, lg1 = _inertia(k) @ w0, _inertia(k) @ w1
    assert landing.contact_velocity_before[2] < 0  # it lands
    assert abs(v_o1[2]) < 1e-14 and abs((vg1 + np.cross(w1, r))[2]) < 1e-14  # e = 0
    np.testing.assert_allclose(MU * vg1[:2], MU * vg0[:2], atol=1e-14)  # frictionless: horizontal momentum
    # angular momentum about the contact point C: L_G + (G - C) x mu v_G
    np.testing.assert_allclose(lg1 - np.cross(r, MU * vg1), lg0 - np.cross(r, MU * vg0), atol=1e-13)
    assert -r @ lg1 == pytest.approx(-r @ lg0, abs=1e-13)  # Jellett's integral (K + q k) . L_G
    # energy dissipated, as stated: Lambda^2 / (2 (1/mu + (r x K) . I_G^-1 (r x K)))
    rk = np.cross(r, K)
    m_eff = 1.0 / (1.0 / MU + rk @ np.linalg.solve(_inertia(k), rk))
    assert landing.energy_loss == pytest.approx(0.5 * landing.impulse[2] ** 2 / m_eff, rel=1e-12)
    assert landing.impulse[2] == pytest.approx(-m_eff * landing.contact_velocity_before[2], rel=1e-12)


def test_continued_run_records_its_phases():
    ds = _run()
    a = ds.attrs
    assert a["event"] == "contact_lost" and a["event_time"] == a["takeoff_times"][0]
    assert a["flights"] == len(a["takeoff_times"]) >= 2 and a["status"] == 0
    assert np.all(np.diff(ds.time.values) > 0)
    assert float(ds.time[-1]) == 30.0
    assert float(ds.normal_force.min()) > -1e-9  # never through a negative normal force
    assert np.all(a["impact_energy_loss"] > 0) and np.all(a["impact_contact_velocity_before"] < 0)
    # the energy falls at each landing by the impact's loss (the friction works in between)
    t_land = a["landing_times"][0]
    i = int(np.nonzero(ds.time.values == t_land)[0][0])
    before = ds.energy.values[i - 1]  # the last flight sample before the landing: energy of the flight
    assert ds.energy.values[i] == pytest.approx(before - a["impact_energy_loss"][0], abs=1e-9)


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(model="sliding", alpha_v=0.5), "normal = 'equilibrium'"),
        (dict(model="rolling"), "rolling"),
        (dict(model="fixed_pivot"), "no floor"),
    ],
)
def test_continue_refused_where_the_take_off_is_not_smooth(kw, match):
    with pytest.raises(InputError, match=match):
        simulate(
            t_end=1, q=Q, fr_inv=FR, sigma=SG, omega=[2, 0, 1], k=_unit([0.3, 0, 1]), on_contact_loss="continue", **kw
        )


def test_flight_figure_marks_the_phases():
    """The figure draws N(t) and the height as the run has them, a line at every take-off and
    landing time of the run's attributes."""
    from stability.plotting import plot_flight_run

    ds = _run()
    fig, axes = plot_flight_run(ds)
    assert len(axes) == 2
    np.testing.assert_array_equal(axes[0].lines[0].get_ydata(), ds.normal_force.values)
    np.testing.assert_array_equal(axes[1].lines[0].get_ydata(), ds.height.values)
    marked = sorted(ln.get_xdata()[0] for ln in axes[1].lines[2:])
    expected = sorted(np.concatenate([ds.attrs["takeoff_times"], ds.attrs["landing_times"]]))
    np.testing.assert_array_equal(marked, expected)


def _skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _normal_force_actual(y, av=0.5):
    """N from Newton for G and Euler about G with friction proportional to N,
    f = N (-alpha_v V_c) / (mu fr_inv) (independent of the package; the law normal="actual")."""
    w, k, v = y[0:3], y[3:6], y[6:8]
    a_g = 1.0 - MU * Q * Q
    i_g = a_g * np.eye(3) + (SG - a_g) * np.outer(k, k)
    g = -av * np.array([v[0] - w[1], v[1] + w[0], 0.0]) / (MU * FR)  # friction per unit N
    r = -K - Q * k
    a = np.zeros((6, 6))
    b = np.zeros(6)
    a[0:3, 0:3] = i_g
    a[0:3, 5] = -(np.cross(r, K) + np.cross(r, g))
    b[0:3] = -(SG - a_g) * (w @ k) * np.cross(w, k)
    a[3:6, 0:3] = -MU * Q * _skew(k)
    a[3, 3] = a[4, 4] = MU
    a[3:6, 5] = -(K + g)
    b[3:6] = -MU * FR * K - MU * Q * np.cross(w, np.cross(w, k))
    return np.linalg.solve(a, b)[5]


def test_normal_force_of_the_continued_run_against_the_vertical_equation():
    """On the floor (before, between and after the flights) N of the run equals the independent
    vertical equation at the run's own states, to 1e-12 (two 6 x 6 solves' round-off); in flight 0."""
    ds = _run()
    on = ds.contact.values == 1
    y = np.column_stack([ds.omega.values, ds.k.values, ds.velocity.values[:, :2]])[on]
    n_ref = np.array([_normal_force_actual(s) for s in y])
    np.testing.assert_allclose(ds.normal_force.values[on], n_ref, rtol=0, atol=1e-12)
    assert np.all(ds.normal_force.values[~on] == 0.0)


def test_continue_refuses_a_stick():
    with pytest.raises(InputError, match="stick_tilt.*not watched in flight"):
        _run(stick_tilt=120.0)


def test_a_graze_stops_the_run_with_its_status():
    """A take-off after which the sphere does not rise: at rest upright on the floor, off it the
    closed form gives h(tau) = -fr_inv tau^2 / 2 < 0 (G falls, nothing turns), so landing_time is
    0. The run must stop at once with status GRAZE, not take off 1000 times at the same instant
    (it did: duplicate samples, status -4). The floor integrator is a stand-in that reports the
    contact lost at its first time, as the real one does for a start with N <= 0."""
    from stability.nonlinear.flight import MAX_FLIGHTS, run_with_flights
    from stability.nonlinear.integrators import GRAZE, STATUS_MESSAGES, Solution

    y = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    f = body_state("sliding", y, q=Q, fr_inv=FR, sigma=SG, mu=MU)
    assert landing_height(f, np.array([1e-3, 1.0]))[1] == pytest.approx(-FR / 2, rel=1e-12)  # the closed fall
    assert landing_time(f) == 0.0
    calls = []

    def lost_at_once(model, y0, t_eval, p, **kw):
        calls.append(t_eval[0])
        y1 = np.asarray(y0, float)[None, :]
        return Solution(t_eval[:1], y1, 1, 0, 0, 0, "stand-in", float(t_eval[0]), "contact_lost")

    params = dict(q=Q, fr_inv=FR, sigma=SG, mu=MU)
    run = run_with_flights(lost_at_once, "sliding", y, np.linspace(0.0, 5.0, 11), np.zeros(9), params)
    assert run.status == GRAZE and "graze" in run.message and "graze" in STATUS_MESSAGES[GRAZE]
    assert run.message.startswith("at t = 0 the normal force reached zero")  # the stand-in's take-off time
    assert len(calls) == 1 < MAX_FLIGHTS and run.takeoffs == [0.0] and run.landings == []


def test_no_gravity_refuses_continue():
    """fr_inv = 0: the contact is not watched and a flight never lands (T_max divides by
    fr_inv). simulate cannot reach a flight there: "continue" needs normal = 'actual', which
    refuses fr_inv = 0 (naming it); landing_time itself refuses the flight."""
    with pytest.raises(InputError, match=r"fr_inv = 0"):
        simulate(
            "sliding",
            t_end=1.0,
            q=Q,
            fr_inv=0.0,
            sigma=SG,
            alpha_v=0.5,
            omega=[1, 0, 1],
            k=[0, 0, 1],
            velocity=[0, 0],
            normal="actual",
            on_contact_loss="continue",
        )
    y = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
    with pytest.raises(InputError, match="fr_inv"):
        landing_time(body_state("sliding", y, q=Q, fr_inv=0.0, sigma=SG, mu=MU))
