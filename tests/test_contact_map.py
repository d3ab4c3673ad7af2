"""Where a launch loses its contact (stability.contact_loss_boundary): the smallest normal force
of a run and the traced boundary N_min = 0, each against an independent reference.

Reference: the sliding sphere of tests/test_contact_loss.py (Newton's law for G and Euler's law
about G, written independently of the package, N from the vertical momentum equation),
integrated by scipy's DOP853 at rtol 1e-12 with dense output; its smallest N over the run is
found by sampling the dense output every 0.02 time units and Brent's bounded minimisation of
N(dense(t)) around the smallest sample. Tolerances: both runs are held to rtol ~1e-10 or better
and N is O(1) in units of M g, so the two minima agree to ~1e-8; 1e-7 M g leaves room for the
error growth over a few hundred time units.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar
from test_contact_loss import MU, _accelerations

import stability
from stability.errors import InputError
from stability.launches.contact_map import launch_min_normal_force

TOP = stability.Top.table1()
ALPHA_V = 0.5  # the launch default (stability.launches.flip.DEFAULT_ALPHA_V)


def _reference_min(spin, tilt, rate, duration):
    """Smallest N / (M g) of the launch over duration seconds, independently (module docstring)."""
    nd = TOP.nondimensional(spin, alpha_v=ALPHA_V)
    q, fr, sg, mu = nd["q"], nd["fr_inv"], nd["sigma"], nd["mu"]
    assert mu == pytest.approx(MU)
    th = math.radians(tilt)
    k = np.array([math.sin(th), 0.0, math.cos(th)])
    y0 = np.concatenate([k + rate / spin * np.array([0.0, 1.0, 0.0]), k, [0.0, 0.0]])

    def f(t, y):
        x = _accelerations(y, q, fr, sg, ALPHA_V, MU)
        return np.concatenate([x[0:3], np.cross(y[0:3], y[3:6]), x[3:5]])

    t_end = duration * spin
    sol = solve_ivp(f, (0.0, t_end), y0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)

    def n(t):
        return _accelerations(sol.sol(t), q, fr, sg, ALPHA_V, MU)[5] / (mu * fr)

    ts = np.arange(0.0, t_end, 0.02)
    vals = np.array([n(t) for t in ts])
    i = int(np.argmin(vals))
    res = minimize_scalar(
        n, bounds=(ts[max(i - 1, 0)], ts[min(i + 1, ts.size - 1)]), method="bounded", options={"xatol": 1e-10}
    )
    return min(float(res.fun), float(vals[i]))


@pytest.mark.parametrize("spin, tilt, rate", [(150.0, 5.0, 60.0), (250.0, 5.0, 120.0)])
def test_min_normal_force_against_independent_dop853(spin, tilt, rate):
    n_min, _ = launch_min_normal_force(TOP, spin, tilt, rate, duration=0.5)
    assert n_min == pytest.approx(_reference_min(spin, tilt, rate, 0.5), abs=1e-7)


def test_traced_boundary_against_bisection_and_reference():
    """The traced line is the grid's zero contour: at two of its points the zero of N_min found
    by Brent's method along the spin at the traced tilt rate (to 1e-10 rad/s) matches the traced
    spin to 1e-6 relative (the engine accepts |N_min| <= 1e-8 M g, and dN_min/dspin is ~1e-2 per
    rad/s, so the traced spin is within ~1e-6 rad/s); and the independent run's N_min there is
    0 to 1e-7 M g (module docstring)."""
    ds = stability.contact_loss_boundary(
        TOP,
        x="tilt_rate",
        y="spin",
        x_range=(90.0, 110.0),
        y_range=(38.0, 46.0),
        unit="rev/s",
        tilt=5.0,
        grid=(3, 3),
        duration=0.5,
        max_points=8,
    )
    assert ds.attrs[stability.products.PRODUCT_ATTR] == "contact_loss_map"
    z = ds.min_normal_force.values
    assert z.min() < 0 < z.max()
    n = ds.sizes["point"]
    assert n >= 3
    for j in (0, n // 2):
        rate = float(ds.boundary_x[j])
        spin = float(ds.boundary_y[j]) * 2 * math.pi
        zero = brentq(
            lambda s: launch_min_normal_force(TOP, s, 5.0, rate, duration=0.5)[0],
            38.0 * 2 * math.pi,
            46.0 * 2 * math.pi,
            xtol=1e-10,
        )
        assert spin == pytest.approx(zero, rel=1e-6)
        assert abs(_reference_min(spin, 5.0, rate, 0.5)) < 1e-7


def test_contact_map_figure():
    import matplotlib as mpl

    mpl.use("Agg")
    from stability.plotting.contact_plots import plot_contact_loss_map

    ds = stability.contact_loss_boundary(
        TOP,
        x="tilt",
        y="tilt_rate",
        x_range=(2.0, 10.0),
        y_range=(60.0, 140.0),
        spin=40.0,
        unit="rev/s",
        grid=(2, 2),
        duration=0.3,
        max_points=4,
    )
    fig, ax = plot_contact_loss_map(ds)
    assert ax.get_xlabel().startswith("tilt")
    from matplotlib.collections import QuadMesh

    meshes = [c for c in ax.collections if isinstance(c, QuadMesh)]
    assert len(meshes) == 1  # the N_min colour mesh: it draws the dataset's values, in its (y, x) order
    drawn = np.asarray(meshes[0].get_array()).reshape(ds.min_normal_force.shape)
    np.testing.assert_array_equal(drawn, ds.min_normal_force.values)
    assert meshes[0].norm.vcenter == 0.0  # diverging about N = 0 (the boundary)


@pytest.mark.parametrize(
    "kw, name",
    [
        ({"x": "spin", "y": "spin"}, "x = y"),
        ({"x": "wobble"}, "x"),
        ({"x_range": (5.0, 1.0)}, "x_range"),
        ({"grid": (1, 4)}, "grid"),
        ({"x": "tilt", "x_range": (0.0, 10.0)}, "tilt range"),
        ({"grid": (2.7, 4)}, "grid"),  # was int(2.7) = 2
        ({"grid": 3}, "grid"),
        ({"tilt": 200.0}, "tilt"),  # the held tilt (default axes tilt_rate, spin) was not checked
        ({"tilt": "abc"}, "tilt"),  # float("abc"): a bare ValueError
        (
            {"x": "spin", "y": "tilt", "x_range": (20.0, 50.0), "y_range": (2.0, 10.0), "tilt_rate": float("nan")},
            "tilt_rate",
        ),
        ({"max_points": 0}, "max_points"),
    ],
)
def test_bad_input_is_refused_naming_the_parameter(kw, name):
    from stability.errors import ParameterTypeError

    with pytest.raises((InputError, ParameterTypeError), match=name):
        stability.contact_loss_boundary(TOP, **kw)


def _stick_event(omega, k, q, fr, sg, stick_tilt, velocity=(0.0, 0.0)):
    """Time and state where the independent sliding sphere (module docstring), run by DOP853 at
    rtol 1e-11, first reaches the tilt ``stick_tilt`` (a terminal event on ``k_3 - cos``)."""
    c = math.cos(math.radians(stick_tilt))

    def f(t, y):
        x = _accelerations(y, q, fr, sg, ALPHA_V, MU)
        return np.concatenate([x[0:3], np.cross(y[0:3], y[3:6]), x[3:5]])

    def gap(t, y):
        return y[5] / np.linalg.norm(y[3:6]) - c

    gap.terminal = True
    y0 = np.concatenate([omega, np.asarray(k, float) / np.linalg.norm(k), velocity])
    sol = solve_ivp(f, (0.0, 5000.0), y0, method="DOP853", rtol=1e-11, atol=1e-13, events=gap)
    return float(sol.t_events[0][0]), sol.y_events[0][0]


def test_final_state_says_when_the_motion_reaches_the_stick():
    """The paper's Fr^-1 = 0.3 run with the toy's stick: J and E decide 166.0 degrees, beyond the
    stick's 131.18, so a run says when the stick is reached: its time against the independent
    DOP853 tilt event to 1e-6 relative (both at rtol <= 1e-10 over ~700 time units); an end below
    the stick is kept as J and E decide it."""
    from stability.nonlinear.scene import INITIAL_CONDITIONS

    ic = INITIAL_CONDITIONS[0.3]
    st = stability.Top.table1(stick=stability.Stick(0.02, 0.003, 0.012)).stick_contact()[0]
    end = stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=ALPHA_V, stick_tilt=st, **ic)
    assert end.kind == "stick_contact" and end.tilt == pytest.approx(st, abs=1e-6)
    t_ref, _ = _stick_event(np.asarray(ic["omega"], float), ic["k"], -0.1, 0.3, 1.0, st, ic["velocity"])
    assert end.event_time == pytest.approx(t_ref, rel=1e-6)
    assert "reaches its stick at 131.2 degrees" in end.reason
    kept = stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=ALPHA_V, stick_tilt=170.0, **ic)
    assert kept.kind == "tilted" and kept.method == "jellett"


def test_bifurcation_diagram_of_a_top_with_a_stick():
    """The diagram of the toy with its stick: the branch's states beyond the stick marked, a run
    launched upright at 40 rev/s (1 degree off) stopped at the stick, its time against the
    independent DOP853 tilt event to 1e-6 relative; the figure draws the stick's tilt."""
    import matplotlib as mpl

    mpl.use("Agg")
    from stability.plotting.steady_plots import plot_bifurcation

    top = stability.Top.table1(stick=stability.Stick(0.02, 0.003, 0.012))
    st = top.stick_contact()[0]
    d = stability.bifurcation_diagram(top, unit="rev/s", runs=[40.0])
    b = d["branch"]
    assert b.attrs["stick_tilt"] == st
    assert np.array_equal(b.beyond_stick.values == 1, b.tilt.values >= st) and b.beyond_stick.sum() > 0
    r = d["runs"]
    assert int(r.reaches_stick[0]) == 1 and float(r.end_tilt[0]) == pytest.approx(st, abs=1e-6)
    nd = top.nondimensional(40.0, "rev/s", alpha_v=ALPHA_V)
    th = math.radians(1.0)
    t_ref, _ = _stick_event(
        np.array([0.0, 0.0, 1.0]), [math.sin(th), 0.0, math.cos(th)], nd["q"], nd["fr_inv"], nd["sigma"], st
    )
    assert float(r.stick_time[0]) == pytest.approx(t_ref, rel=1e-6)
    fig, ax = plot_bifurcation(b, vertical=d["vertical"], runs=r)
    assert any("stick touches" in str(line.get_label()) for line in ax.get_lines())


@pytest.mark.parametrize("rev_s, answer", [(7.15, "falls_back"), (40.0, "spins")])
def test_launch_says_whether_the_top_spins_on_its_stick(rev_s, answer):
    """The launch's stick answer: the spin about the axis at the stick (omega . k at the event)
    against the independent sliding sphere (module docstring) run by DOP853 to the same stick
    tilt (a terminal event on the tilt), to 1e-6 relative (both at rtol <= 1e-10 over ~1e3 time
    units); the verdict against the stick's critical spin (131.2 rad/s for this stick, itself
    checked against runs on the stick in tests/test_stick.py): 7.15 rev/s arrives at ~27 rad/s
    and falls back, 40 rev/s at ~143 rad/s and spins on."""
    top = stability.Top.table1(stick=stability.Stick(0.02, 0.003, 0.012))
    ans = stability.launch(top, rev_s, unit="rev/s")
    assert ans.event == "stick_contact" and ans.on_stick == answer
    w = ans.spin
    nd = top.nondimensional(w, alpha_v=ALPHA_V)
    q, fr, sg = nd["q"], nd["fr_inv"], nd["sigma"]
    k0 = np.array([math.sin(math.radians(1.0)), 0.0, math.cos(math.radians(1.0))])
    _, y = _stick_event(k0, k0, q, fr, sg, top.stick_contact()[0])
    assert ans.stick_spin == pytest.approx(abs(np.dot(y[0:3], y[3:6])) * w, rel=1e-6)
    assert ans.stick_critical_spin == pytest.approx(
        stability.critical_spin(top.on_stick(), "sliding", "upright").spin, rel=1e-12
    )
    assert ("spins on its stick" if answer == "spins" else "falls back") in str(ans)
    assert ans.to_dataset().attrs["on_stick"] == answer


# -- the steady states' contact margin (stability.steady.margin) ---------------------------------
MARGIN = dict(q=-0.5, sigma=0.5, fr_inv=0.01, alpha_v=0.5)


@pytest.mark.parametrize("tilt", [0.0, 180.0])
def test_vertical_states_have_no_first_order_change_of_n(tilt):
    """Closed form (stability.steady.margin): at k = +-K with f(y*) = 0 every term of N - mu fr_inv
    is of second order in the tilt, so grad N . d = 0 and the linear estimate is infinite."""
    from stability.steady.margin import contact_margin

    m = contact_margin(tilt=tilt, duration=20.0, max_size=5.0, **MARGIN)
    assert m.linear_size == math.inf and m.size is None


def _tilted_state(tilt):
    from stability.steady import family

    th = math.radians(tilt)
    lam = float(
        family.precession_rate(math.cos(th), q=MARGIN["q"], sigma=MARGIN["sigma"], fr_inv=MARGIN["fr_inv"], mu=MU)
    )
    return family.state_vector(th, lam, MARGIN["q"])


def _perturbed(y, d, size):
    z = y + math.radians(size) * d
    z[3:6] /= np.linalg.norm(z[3:6])
    return z


def test_linearised_change_of_n_against_runs():
    """The first-order closed form delta N = eps Re(c e^{st}) (stability.steady.margin) against
    runs from y* + eps d: the run's dip (mu fr_inv - N_min) / eps tends to the linear dip
    mu fr_inv / linear_size as eps -> 0, with an error of first order in eps (halving eps halves
    it, to 10 %), below 2 % at eps = 0.25 degree."""
    from stability.nonlinear.min_force import min_normal_force
    from stability.nonlinear.runs import model_parameter_vector
    from stability.steady.margin import contact_margin

    m = contact_margin(tilt=90.0, duration=50.0, max_size=5.0, **MARGIN)
    y = _tilted_state(90.0)
    _, p = model_parameter_vector("sliding", dict(mu=MU, **MARGIN))
    linear = m.normal_force / m.linear_size
    errs = []
    for eps in (0.5, 0.25):
        z = np.concatenate([_perturbed(y, m.direction, eps), [0.0, 0.0]])
        dip = (m.normal_force - min_normal_force("sliding", z, p, 50.0)[0]) / eps
        errs.append(dip / linear - 1.0)
    assert abs(errs[1]) < 0.02
    assert errs[1] / errs[0] == pytest.approx(0.5, abs=0.1)


def test_contact_margin_size_against_independent_dop853():
    """At the size found by Brent's method, the independent sliding sphere (module docstring)
    started from y* + size d has its smallest N over the run at 0, to 1e-7 of mu fr_inv (both
    runs at rtol <= 1e-10 over 50 time units); the first-order estimate is within 20 % (the
    size, ~32 degrees, is not small)."""
    from stability.steady.margin import contact_margin

    m = contact_margin(tilt=90.0, duration=50.0, max_size=80.0, **MARGIN)
    assert m.size is not None and m.size == pytest.approx(m.linear_size, rel=0.2)
    z = _perturbed(_tilted_state(90.0), m.direction, m.size)
    q, fr, sg, av = MARGIN["q"], MARGIN["fr_inv"], MARGIN["sigma"], MARGIN["alpha_v"]

    def f(t, y):
        x = _accelerations(y, q, fr, sg, av, MU)
        return np.concatenate([x[0:3], np.cross(y[0:3], y[3:6]), x[3:5]])

    sol = solve_ivp(f, (0.0, 50.0), z, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)

    def n(t):
        return _accelerations(sol.sol(t), q, fr, sg, av, MU)[5] / (MU * fr)

    ts = np.arange(0.0, 50.0, 0.02)
    vals = np.array([n(t) for t in ts])
    i = int(np.argmin(vals))
    res = minimize_scalar(
        n, bounds=(ts[max(i - 1, 0)], ts[min(i + 1, ts.size - 1)]), method="bounded", options={"xatol": 1e-10}
    )
    assert abs(min(float(res.fun), vals[i])) < 1e-7


def test_contact_margin_finds_the_smallest_size_of_a_non_monotone_n_min(monkeypatch):
    """N_min(eps) need not fall monotonically: a stand-in for the run's smallest N, a cubic in
    the angle phi between the perturbed axis and the steady one with zeros at phi = 0.3, 0.5, 0.9
    rad (N > 0 below 0.3, < 0 on (0.3, 0.5), > 0 on (0.5, 0.9), < 0 above), must give the
    size of the first zero, phi = 0.3, solved here from the geometry alone (brentq on the angle
    of normalise(k* + eps d_k)). Tolerance 1e-7 relative: the margin's Brent xtol 1e-9 degree on
    a size ~18 degrees. Before, Brent on [0, max_size] returned any of the zeros."""
    import stability.steady.margin as margin

    k_star = _tilted_state(90.0)[3:6]

    def phi_of(z):
        return math.acos(min(1.0, float(z[3:6] @ k_star / np.linalg.norm(z[3:6]))))

    def stand_in(model, z, p, duration, rtol=1e-10):
        phi = phi_of(z)
        return -(phi - 0.3) * (phi - 0.5) * (phi - 0.9), None

    monkeypatch.setattr(margin, "min_normal_force", stand_in)
    m = margin.contact_margin(tilt=90.0, duration=5.0, max_size=80.0, **MARGIN)
    d = m.direction
    expected = brentq(lambda e: phi_of(_perturbed(_tilted_state(90.0), d, e)) - 0.3, 1e-3, 80.0, xtol=1e-12)
    assert m.size == pytest.approx(expected, rel=1e-7)


@pytest.mark.parametrize(
    "kw, name",
    [(dict(tilt="abc"), "tilt"), (dict(tilt=200.0), "tilt"), (dict(spin="x"), "spin"), (dict(rtol=2.0), "rtol")],
)
def test_contact_margin_bad_input_names_the_parameter(kw, name):
    """The package's errors (TypeError / DomainError subclasses), naming the parameter; before,
    tilt = 'abc' gave float()'s bare ValueError."""
    from stability.errors import ParameterTypeError
    from stability.steady.margin import contact_margin

    args = dict(tilt=90.0, **MARGIN)
    args.update(kw)
    with pytest.raises((InputError, ParameterTypeError), match=name):
        contact_margin(**args)
