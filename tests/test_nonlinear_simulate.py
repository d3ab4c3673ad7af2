"""simulate(): output format, input checking, integrator accuracy and speed.

References: scipy's DOP853 at a tight tolerance (a different method) for the compiled
Dormand-Prince; the order-4 error law of classical RK4 (halving the step divides the error
by 2^4 = 16); the closed-form free rotation of a uniform ball on a fixed pivot.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from stability import simulate
from stability.errors import DomainError

BASE = dict(q=-0.1, fr_inv=0.3, sigma=1.0)
IC = dict(omega=[0.0219, 0.0047, -0.9997], k=[0.0676, 0.0676, 0.9954], velocity=[0.0935, 0.0384])


def test_dataset_has_cf_attributes_and_the_documented_variables():
    ds = simulate("sliding", t_end=5.0, **IC, **BASE, alpha_v=0.5)
    for name in (
        "omega",
        "k",
        "velocity",
        "position",
        "polar_angle",
        "spin",
        "transverse_rate",
        "energy",
        "kinetic_translational",
        "kinetic_spin",
        "kinetic_transverse",
        "potential",
        "slip_speed",
        "friction",
        "normal_force",
        "h_cg",
    ):
        assert name in ds, name
        assert ds[name].attrs["long_name"]
        assert ds[name].attrs["units"] in ("1", "degree", "Omega", "Omega R", "R", "A0 Omega", "A0 Omega^2")
    assert ds.omega.dims == ("time", "axis")
    assert ds.attrs["Conventions"].startswith("CF")
    assert ds.attrs["status"] == 0
    # the paper's k has |k| = 0.99998: normalised, polar angle from the normalised axis
    assert np.allclose(np.linalg.norm(ds.k.values, axis=1), 1.0, atol=1e-9)
    # normal force near its equilibrium mu fr_inv for a small tilt (relative change O(tilt))
    assert float(ds.normal_force[0]) == pytest.approx(2.28 * 0.3, rel=0.05)


def test_dopri5_agrees_with_scipy_dop853():
    kw = dict(t_end=100.0, dt=1.0, **IC, **BASE, alpha_v=0.5)
    a = simulate("sliding", **kw, method="dopri5", rtol=1e-11, atol=1e-14)
    b = simulate("sliding", **kw, method="DOP853", rtol=1e-12, atol=1e-15)
    # both globally accurate to ~1e-9 over 100 time units
    np.testing.assert_allclose(a.omega.values, b.omega.values, rtol=0, atol=1e-8)
    np.testing.assert_allclose(a.k.values, b.k.values, rtol=0, atol=1e-8)


def test_fixed_step_rk4_is_fourth_order():
    kw = dict(t_end=20.0, dt=1.0, **IC, **BASE, alpha_v=0.5)
    ref = simulate("sliding", **kw, method="dopri5", rtol=1e-12, atol=1e-15)
    err = [
        float(np.max(np.abs(simulate("sliding", **kw, method="rk4", step=h).k.values - ref.k.values)))
        for h in (0.1, 0.05)
    ]
    assert err[0] / err[1] == pytest.approx(16.0, rel=0.15)


def test_uniform_ball_on_pivot_spins_freely():
    """q = -1 puts G at the pivot: no torque; sigma = A_C = 1 + mu (1 - 2) gives a spherical
    inertia about the pivot, so omega is constant and k turns rigidly about omega:
    k(t) = rotation of k(0) by angle |omega| t about omega (closed form)."""
    mu = 0.5
    sigma = 1 + mu * (1 - 2)  # = A_C at q = -1, and sigma <= 2 (1 - mu) holds
    w = np.array([0.3, -0.2, 1.0])
    k0 = np.array([np.sin(0.4), 0.0, np.cos(0.4)])
    ds = simulate(
        "fixed_pivot",
        t_end=10.0,
        dt=0.5,
        omega=w,
        k=k0,
        q=-1.0 * 0.999999,
        fr_inv=0.0,
        sigma=sigma,
        mu=mu,
        rtol=1e-12,
        atol=1e-14,
    )
    n = w / np.linalg.norm(w)
    th = np.linalg.norm(w) * ds.time.values[:, None]
    exact = k0 * np.cos(th) + np.cross(n, k0) * np.sin(th) + n * (n @ k0) * (1 - np.cos(th))
    np.testing.assert_allclose(ds.k.values, exact, atol=1e-5)  # q is 1e-6 off -1: O(1e-6) torque


def test_a_thousand_time_units_run_well_under_a_second(monkeypatch):
    kw = dict(t_end=1000.0, **IC, **BASE, alpha_v=0.5)
    with monkeypatch.context() as m:  # a short run is interpreted unless asked for compiled
        m.setenv("TIPPE_KERNEL", "compiled")
        simulate("sliding", t_end=1.0, **IC, **BASE, alpha_v=0.5)  # compile / load the cache
    t0 = time.perf_counter()
    ds = simulate("sliding", **kw)
    elapsed = time.perf_counter() - t0
    assert ds.attrs["method"] == "dopri5"
    assert elapsed < 0.5


@pytest.mark.parametrize(
    "kwargs,exc,match",
    [
        (dict(k=[0.0, 1.0]), ValueError, "k ="),
        (dict(k=[0.0, 0.0, 2.0]), ValueError, "length"),
        (dict(q=0.9), DomainError, "q = 0.9"),
        (dict(alpha_v=None), TypeError, "alpha_v is required"),
        (dict(alpha_v=-1.0), DomainError, "alpha_v = -1"),
        (dict(velocity=[0.1, 0.0, 0.2]), ValueError, "vertical"),
        (dict(fr_inv=0.0, normal="actual"), ValueError, "fr_inv > 0"),
        (dict(friction="viscous"), ValueError, "friction = 'viscous'"),
        (dict(method="euler"), ValueError, "method = 'euler'"),
        (dict(t_end=-1.0), ValueError, "t_end = -1"),
        (dict(slip_scale=0.0), ValueError, "slip_scale"),
        (dict(omega="fast"), TypeError, "omega"),
    ],
)
def test_bad_input_is_refused_with_a_clear_message(kwargs, exc, match):
    args = dict(t_end=1.0, **IC, **BASE, alpha_v=0.5)
    args.update(kwargs)
    with pytest.raises(exc, match=match):
        simulate("sliding", **args)


def test_models_refuse_foreign_parameters():
    with pytest.raises(TypeError, match="alpha_v"):
        simulate("rolling", t_end=1.0, omega=[0, 0, 1], k=[0, 0, 1], **BASE, alpha_v=0.5)
    with pytest.raises(ValueError, match="velocity"):
        simulate("rolling", t_end=1.0, omega=[0, 0, 1], k=[0, 0, 1], **BASE, velocity=[0, 0])
    with pytest.raises(ValueError, match="not a nonlinear model"):
        simulate("hovering", t_end=1.0, omega=[0, 0, 1], k=[0, 0, 1], **BASE)


def test_cli_simulate_writes_netcdf_and_reports_bad_input(tmp_path, capsys):
    import xarray as xr

    from stability.cli import main

    out = tmp_path / "run.nc"
    args = [
        "simulate",
        "--t-end",
        "2",
        "--omega",
        "0.02,0,1",
        "--k",
        "0.05,0,1",
        "--q",
        "-0.1",
        "--fr-inv",
        "0.3",
        "--sigma",
        "1",
        "--alpha-v",
        "0.5",
        "-o",
        str(out),
    ]
    assert main(args) == 0
    ds = xr.open_dataset(out)
    ref = simulate("sliding", t_end=2.0, omega=[0.02, 0, 1], k=[0.05, 0, 1], **BASE, alpha_v=0.5)
    np.testing.assert_array_equal(ds.k.values, ref.k.values)
    bad = args[:-1] + [str(tmp_path / "bad.nc")]
    bad[bad.index("--q") + 1] = "0.9"
    assert main(bad) == 2
    assert "q = 0.9" in capsys.readouterr().err
