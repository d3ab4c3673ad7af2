"""Contact lost: the runs' event against an independent integrator, and their N against eq. (1).

Reference: the sliding sphere written here again, independently of the package, from Newton's
law for G and Euler's law about G (the paper's eqs. 1, 2 taken about G instead of O; eq. 4;
friction 7 with alpha_k = 0) with the constraint that O stays at height R; N from the vertical
component of Newton's law. scipy's DOP853 with a terminal event on N locates the first zero.
Tolerance 1e-6 relative on the time (the issue's): both integrators run at rtol 1e-10, so the
event times agree to ~1e-8; 1e-6 leaves room for the error growth over the run.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from stability import simulate
from stability.errors import InputError

MU = 2.28  # stability.parameters.DEFAULT_MU, checked below


def _unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


def _skew(a):
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _accelerations(y, q, fr, sg, av, mu):
    """(omega', V0'_h, N) from Newton for G and Euler about G (independent of the package)."""
    w, k, v = y[0:3], y[3:6], y[6:8]
    K = np.array([0.0, 0.0, 1.0])
    a_g = 1.0 - mu * q * q
    i_g = a_g * np.eye(3) + (sg - a_g) * np.outer(k, k)
    vc = np.array([v[0] - w[1], v[1] + w[0], 0.0])
    f = -av * vc
    r = -K - q * k  # from G to the contact point
    wk = np.dot(w, k)
    # unknowns x = (omega' (3), b1, b2, N)
    a = np.zeros((6, 6))
    rhs = np.zeros(6)
    # Euler about G: I_G omega' - N (r x K) = r x f - (sigma - A_G)(k.omega)(omega x k)
    a[0:3, 0:3] = i_g
    a[0:3, 5] = -np.cross(r, K)
    rhs[0:3] = np.cross(r, f) - (sg - a_g) * wk * np.cross(w, k)
    # Newton for G: mu (V0' - q k x omega') - N K = f - mu fr K - mu q omega x (omega x k)
    a[3:6, 0:3] = -mu * q * _skew(k)
    a[3, 3] = mu
    a[4, 4] = mu
    a[3:6, 5] = -K
    rhs[3:6] = f - mu * fr * K - mu * q * np.cross(w, np.cross(w, k))
    return np.linalg.solve(a, rhs)


def _reference(omega, k, q, fr, sg, av, t_end):
    k = np.asarray(k, float) / np.linalg.norm(k)
    y0 = np.concatenate([omega, k, [0.0, 0.0]])

    def f(t, y):
        x = _accelerations(y, q, fr, sg, av, MU)
        return np.concatenate([x[0:3], np.cross(y[0:3], y[3:6]), x[3:5]])

    def n(t, y):
        return _accelerations(y, q, fr, sg, av, MU)[5]

    n.terminal = True
    n.direction = -1
    return solve_ivp(f, (0.0, t_end), y0, method="DOP853", rtol=1e-11, atol=1e-13, events=n, dense_output=True)


def test_default_mu_is_the_reference_mu():
    from stability.parameters import DEFAULT_MU

    assert DEFAULT_MU == MU


@pytest.mark.parametrize(
    "omega, k, fr, lost",
    [
        ([2.0, 0.0, 1.0], [0.3, 0.0, 1.0], 0.05, True),  # the reproducer
        ([4.0, 0.0, 1.0], [0.3, 0.0, 1.0], 0.05, True),
        ([0.5, 0.0, 1.0], [0.2, 0.0, 1.0], 0.3, False),  # a gentle launch: contact holds
    ],
)
def test_contact_loss_time_against_independent_dop853(omega, k, fr, lost):
    t_end = 20.0
    ref = _reference(omega, k, -0.1, fr, 1.0, 0.5, t_end)
    ds = simulate(
        "sliding",
        t_end=t_end,
        q=-0.1,
        fr_inv=fr,
        sigma=1.0,
        alpha_v=0.5,
        omega=omega,
        k=_unit(k),
        velocity=[0, 0],
        rtol=1e-11,
        atol=1e-13,
    )
    if lost:
        assert ref.t_events[0].size == 1
        t_ref = ref.t_events[0][0]
        assert ds.attrs["event"] == "contact_lost"
        assert ds.attrs["status"] == 0
        assert abs(ds.attrs["event_time"] - t_ref) <= 1e-6 * t_ref
        assert float(ds.time[-1]) == ds.attrs["event_time"]  # the last sample is the event
        assert abs(float(ds.normal_force[-1])) < 1e-9  # N = 0 there (to the event's root)
    else:
        assert ref.t_events[0].size == 0
        assert ds.attrs["event"] == "none" and np.isnan(ds.attrs["event_time"])
        assert float(ds.time[-1]) == t_end
    # never through a negative normal force
    assert float(ds.normal_force.min()) > -1e-9
    # N of the run against the reference's vertical equation at the run's own states
    y = np.column_stack([ds.omega.values, ds.k.values, ds.velocity.values[:, :2]])
    n_ref = np.array([_accelerations(s, -0.1, fr, 1.0, 0.5, MU)[5] for s in y])
    np.testing.assert_allclose(ds.normal_force.values, n_ref, rtol=0, atol=1e-12)


def test_rolling_run_stops_at_contact_loss():
    ds = simulate("rolling", t_end=20, q=-0.1, fr_inv=0.05, sigma=1, omega=[2, 0, 1], k=_unit([0.3, 0, 1]))
    assert ds.attrs["event"] == "contact_lost"
    assert float(ds.time[-1]) == ds.attrs["event_time"] < 20
    assert float(ds.normal_force.min()) > -1e-9


def test_continue_is_refused_with_the_papers_friction_law():
    with pytest.raises(InputError, match="on_contact_loss = .continue. is not available for normal = .equilibrium."):
        simulate(
            "sliding",
            t_end=1,
            q=-0.1,
            fr_inv=0.05,
            sigma=1,
            alpha_v=0.5,
            omega=[2, 0, 1],
            k=_unit([0.3, 0, 1]),
            on_contact_loss="continue",
        )
    with pytest.raises(InputError, match="on_contact_loss = 'fly'"):
        simulate(
            "sliding",
            t_end=1,
            q=-0.1,
            fr_inv=0.05,
            sigma=1,
            alpha_v=0.5,
            omega=[2, 0, 1],
            k=_unit([0.3, 0, 1]),
            on_contact_loss="fly",
        )


def test_final_state_run_reports_the_contact_loss():
    """The deciding run of final_state (steady.final.settle) stops at the event; reference: the
    independent DOP853 event time (1e-6 relative, as above)."""
    from stability.nonlinear.runs import initial_state, model_parameter_vector
    from stability.steady.final import settle

    params, _ = model_parameter_vector("sliding", dict(q=-0.1, fr_inv=0.05, sigma=1.0, alpha_v=0.5))
    params.pop("alpha_k")
    y0 = initial_state("sliding", [2.0, 0.0, 1.0], _unit([0.3, 0, 1]), [0.0, 0.0])
    tilt, _, run = settle(y0, params, chunk=50.0, t_max=200.0, settle_tolerance=1e-4, rtol=1e-10)
    t_ref = _reference([2.0, 0.0, 1.0], [0.3, 0, 1], -0.1, 0.05, 1.0, 0.5, 20.0).t_events[0][0]
    assert run.event == "contact_lost" and not run.settled
    assert abs(run.event_time - t_ref) <= 1e-6 * t_ref
    assert run.t_end == run.event_time


@pytest.mark.parametrize("method, extra", [("rk4", {"step": 2e-3}), ("DOP853", {}), ("LSODA", {}), ("Radau", {})])
def test_every_integrator_locates_the_event(method, extra):
    """Each integrator's own location (rk4: Hermite cubic; scipy: dense output and Brent) against
    the independent DOP853 event. Tolerance: 1e-6 relative (rk4 at step 2e-3 has a global error
    ~1e-10 here; LSODA's and Radau's global errors are ~100-1000 rtol, with rtol 1e-11)."""
    t_ref = _reference([2.0, 0.0, 1.0], [0.3, 0, 1], -0.1, 0.05, 1.0, 0.5, 20.0).t_events[0][0]
    ds = simulate(
        "sliding",
        t_end=5,
        q=-0.1,
        fr_inv=0.05,
        sigma=1,
        alpha_v=0.5,
        omega=[2, 0, 1],
        k=_unit([0.3, 0, 1]),
        method=method,
        rtol=1e-11,
        atol=1e-13,
        **extra,
    )
    assert ds.attrs["event"] == "contact_lost" and ds.attrs["status"] == 0
    assert abs(ds.attrs["event_time"] - t_ref) <= 1e-6 * t_ref
    assert float(ds.time[-1]) == ds.attrs["event_time"]
    assert float(ds.normal_force.min()) > -1e-8


def test_a_launch_without_normal_force_stops_at_once():
    """N at the start <= 0 (a spin so fast about a tilted axis that the floor would have to
    pull): the event is the initial state, t = 0 (the reference's N there is negative)."""
    k = _unit([1.0, 0.0, 1.0])
    assert _accelerations(np.concatenate([[0, 0, 30.0], k, [0, 0]]), -0.1, 0.05, 1.0, 0.5, MU)[5] < 0
    ds = simulate("sliding", t_end=5, q=-0.1, fr_inv=0.05, sigma=1, alpha_v=0.5, omega=[0, 0, 30], k=k)
    assert ds.attrs["event"] == "contact_lost" and ds.attrs["event_time"] == 0.0
    assert ds.time.size == 1


def test_run_stops_at_the_stick_against_independent_dop853():
    """The paper's Fr^-1 = 0.3 run with a stick touching at 131.2 degrees: the stop time against
    the independent DOP853 with a tilt event (1e-6 relative; both at rtol 1e-10, the inversion
    over ~700 time units amplifies the error to ~1e-8), the stop tilt at the stick to round-off."""
    from stability.nonlinear.scene import INITIAL_CONDITIONS

    ic = INITIAL_CONDITIONS[0.3]
    c = np.cos(np.radians(131.2))
    k0 = _unit(ic["k"])
    y0 = np.concatenate([ic["omega"], k0, ic["velocity"]])

    def f(t, y):
        x = _accelerations(y, -0.1, 0.3, 1.0, 0.5, MU)
        return np.concatenate([x[0:3], np.cross(y[0:3], y[3:6]), x[3:5]])

    def tilt(t, y):
        return y[5] - c * np.linalg.norm(y[3:6])

    tilt.terminal = True
    ref = solve_ivp(f, (0.0, 1000.0), y0, method="DOP853", rtol=1e-10, atol=1e-12, events=tilt)
    t_ref = ref.t_events[0][0]
    ds = simulate(
        "sliding",
        t_end=1000,
        q=-0.1,
        fr_inv=0.3,
        sigma=1,
        alpha_v=0.5,
        stick_tilt=131.2,
        rtol=1e-10,
        atol=1e-12,
        omega=ic["omega"],
        k=k0,
        velocity=ic["velocity"],
    )
    assert ds.attrs["event"] == "stick_contact" and ds.attrs["status"] == 0
    assert abs(ds.attrs["event_time"] - t_ref) <= 1e-6 * t_ref
    assert abs(float(ds.polar_angle[-1]) - 131.2) < 1e-9
    assert float(ds.time[-1]) == ds.attrs["event_time"]


def test_stick_tilt_is_checked():
    with pytest.raises(ValueError, match="stick_tilt"):
        simulate(
            "sliding", t_end=1, q=-0.1, fr_inv=0.3, sigma=1, alpha_v=0.5, omega=[0, 0, 1], k=[0, 0, 1], stick_tilt=190.0
        )


def test_contact_figure_marks_the_event():
    """The figure draws N(t) as the run has it and marks the event at the run's event time."""
    from stability.plotting import plot_contact_run

    ds = simulate("sliding", t_end=5, q=-0.1, fr_inv=0.05, sigma=1, alpha_v=0.5, omega=[2, 0, 1], k=_unit([0.3, 0, 1]))
    fig, axes = plot_contact_run(ds)
    assert len(axes) == 2
    line = axes[0].lines[0]
    np.testing.assert_array_equal(line.get_ydata(), ds.normal_force.values)
    marks = [ln for ln in axes[0].lines if ln.get_marker() == "o"]
    assert marks and marks[0].get_xdata()[0] == ds.attrs["event_time"]


@pytest.mark.parametrize("batch", [1, 7, 64, 100000])
def test_scipy_batched_check_locates_the_event(batch, monkeypatch):
    """scipy's path checks N in batches of WATCH_BATCH steps and integrates the step of the zero
    again from its start (integrators._relocate) unless it is the solver's last: every batch size
    (1: every step; 7, 64: the zero inside a batch; 100000: found at the run's end) gives the
    independent DOP853 event time to 1e-6 relative (LSODA's global error is ~100-1000 rtol)."""
    from stability.nonlinear import integrators

    monkeypatch.setattr(integrators, "WATCH_BATCH", batch)
    ref = _reference([2.0, 0.0, 1.0], [0.3, 0.0, 1.0], -0.1, 0.05, 1.0, 0.5, 20.0).t_events[0][0]
    ds = simulate(
        "sliding",
        t_end=20.0,
        q=-0.1,
        fr_inv=0.05,
        sigma=1.0,
        alpha_v=0.5,
        omega=[2.0, 0.0, 1.0],
        k=_unit([0.3, 0, 1]),
        velocity=[0, 0],
        method="LSODA",
        rtol=1e-11,
        atol=1e-13,
    )
    assert ds.attrs["event"] == "contact_lost"
    assert abs(ds.attrs["event_time"] - ref) <= 1e-6 * ref
    assert float(ds.time[-1]) == ds.attrs["event_time"] and np.all(np.diff(ds.time.values) > 0)
    assert np.isfinite(ds.omega.values).all() and float(ds.normal_force.min()) > -1e-9


def test_rolling_contact_loss_time_against_independent_dop853():
    """The rolling model's constraint force can point down too: its run stops at the first zero
    of N with event contact_lost. Reference: the rolling sphere of
    suites.reference.rolling_rhs (plain numpy, the centre's acceleration eliminated
    first and a 3 x 3 system for omega', not the kernels' 6 x 6 one), integrated by scipy's
    DOP853 with a terminal event on N = mu fr_inv + mu q (k'')_3, k'' = omega' x k + omega x
    (omega x k) (the vertical component of eq. 1 with O at height R). Tolerance 1e-6 relative on
    the time (the issue's; both runs at rtol 1e-11 agree to ~1e-9); N of the run against the
    same vertical equation at the run's own states to 1e-10 (round-off of two eliminations of
    an O(1) system)."""
    from suites.reference import rolling_rhs

    q, fr, sg = -0.1, 0.05, 1.0
    k0 = _unit([0.3, 0, 1])
    y0 = np.concatenate([[2.0, 0.0, 1.0], k0, [0.0, 0.0]])

    def n_ref(t, y, *_):
        wd = rolling_rhs(t, y, q, fr, sg, MU)[0:3]
        w, k = y[0:3], y[3:6]
        return MU * fr + MU * q * (np.cross(wd, k) + np.cross(w, np.cross(w, k)))[2]

    n_ref.terminal = True
    n_ref.direction = -1
    ref = solve_ivp(
        rolling_rhs, (0.0, 20.0), y0, method="DOP853", rtol=1e-11, atol=1e-13, events=n_ref, args=(q, fr, sg, MU)
    )
    assert ref.t_events[0].size == 1
    t_ref = ref.t_events[0][0]
    ds = simulate("rolling", t_end=20, q=q, fr_inv=fr, sigma=sg, omega=[2, 0, 1], k=k0, rtol=1e-11, atol=1e-13)
    assert ds.attrs["event"] == "contact_lost" and ds.attrs["status"] == 0
    assert abs(ds.attrs["event_time"] - t_ref) <= 1e-6 * t_ref
    assert float(ds.time[-1]) == ds.attrs["event_time"]
    states = np.column_stack([ds.omega.values, ds.k.values, ds.position.values])
    n_run = np.array([n_ref(0.0, s) for s in states])
    np.testing.assert_allclose(ds.normal_force.values, n_run, rtol=0, atol=1e-10)
    assert abs(n_run[-1]) < 1e-8 and n_run.min() > -1e-8


def test_closed_form_normal_force_against_independent_equations():
    """stability.nonlinear.sliding.normal_force (closed form, the eigenvector u = k x K of the
    reduced 3 x 3 system) against N of the independent Newton/Euler-about-G system of this file
    (numpy's LU), at random unit-k states with viscous friction; tolerance 1e-12 of its scale
    (round-off of two eliminations). With Coulomb friction proportional to N (normal="actual")
    and a k off the unit sphere (as an integrated k drifts), against the kernel's own 6 x 6
    solve (contact_forces: a different elimination of the same equations), 1e-12 of the scale."""
    from stability.nonlinear.parameters import pack
    from stability.nonlinear.sliding import contact_forces, normal_force

    rng = np.random.default_rng(7)
    for _ in range(200):
        q, fr, sg, av = rng.uniform(-0.5, 0.5), rng.uniform(0.01, 1.0), rng.uniform(0.3, 2.0), rng.uniform(0, 1)
        y = rng.normal(size=10)
        y[3:6] = _unit(y[3:6])
        n, scale = normal_force(y, pack(q=q, fr_inv=fr, sigma=sg, mu=MU, alpha_v=av))
        assert abs(n - _accelerations(y, q, fr, sg, av, MU)[5]) <= 1e-12 * scale
        p = pack(q=q, fr_inv=fr, sigma=sg, mu=MU, alpha_v=av, alpha_k=rng.uniform(0, 0.5), normal=1)
        y[3:6] *= rng.uniform(0.95, 1.05)
        n, scale = normal_force(y, p)
        if np.isfinite(n):
            assert abs(n - contact_forces(y[None, :], p)[0, 2]) <= 1e-12 * scale


def test_screened_batch_check_finds_the_first_nonpositive_n():
    """integrators.first_event skips the solve where the closed-form lower bound is positive: on
    the states of the issue's reproducer run past its contact loss (unwatched), the first row it
    reports is the first row where the independent N of this file is <= 0 (and -1 before it)."""
    from stability.nonlinear.integrators import first_event, integrate
    from stability.nonlinear.parameters import pack

    q, fr, sg, av = -0.1, 0.05, 1.0, 0.5
    p = pack(q=q, fr_inv=fr, sigma=sg, mu=MU, alpha_v=av)
    y0 = np.concatenate([[2.0, 0.0, 1.0], _unit([0.3, 0, 1]), [0.0, 0.0, 0.0, 0.0]])
    t = np.linspace(0.0, 2.0, 2001)
    ys = integrate("sliding", y0, t, p, method="DOP853").y
    n_ref = np.array([_accelerations(y, q, fr, sg, av, MU)[5] for y in ys])
    first = int(np.argmax(n_ref <= 0.0))
    assert first > 0 and n_ref[first - 1] > 0.0
    assert first_event(0, t, ys, p, 1, -2.0) == first
    assert first_event(0, t[:first], ys[:first], p, 1, -2.0) == -1


def test_rolling_closed_form_normal_force_against_reference():
    """stability.nonlinear.rolling.normal_force (closed form) against N from the plain-numpy
    rolling sphere of suites.reference (its 3 x 3 solve for omega', then the
    vertical equation N = mu fr_inv + mu q (k'')_3), at random states with k off the unit
    sphere too; tolerance 1e-12 of the closed form's scale (round-off of two eliminations)."""
    from suites.reference import rolling_rhs

    from stability.nonlinear.parameters import pack
    from stability.nonlinear.rolling import normal_force

    rng = np.random.default_rng(11)
    for _ in range(200):
        q, fr, sg = rng.uniform(-0.5, 0.5), rng.uniform(0.01, 1.0), rng.uniform(0.3, 2.0)
        y = rng.normal(size=8)
        y[3:6] = _unit(y[3:6]) * rng.uniform(0.95, 1.05)
        w, k = y[0:3], y[3:6]
        wd = rolling_rhs(0.0, y, q, fr, sg, MU)[0:3]
        n_ref = MU * fr + MU * q * (np.cross(wd, k) + np.cross(w, np.cross(w, k)))[2]
        n, scale = normal_force(y, pack(q=q, fr_inv=fr, sigma=sg, mu=MU))
        assert abs(n - n_ref) <= 1e-12 * scale
