"""Where the nonlinear runs are hard: long runs, Coulomb friction at zero slip, stiff friction.

References, all independent of the run under test:

* integrals of the exact equations (docs/nonlinear.md): |k| = 1 (k' = omega x k is a
  rotation), the energy and h_cg of eq. (10) for the rolling sphere, the energy and the
  horizontal momentum for frictionless sliding;
* the rolling model (a different right-hand side, V_c = 0 imposed, the traction an unknown) as
  the limit of the sliding model when the contact becomes stiff: alpha_v -> infinity, or the
  regularised Coulomb law at sticking (viscous with coefficient alpha_k / slip_scale).

Tolerances are tied to the integrator's: the compiled Dormand-Prince keeps the local error per
step below rtol |y| + atol, so over T time units a non-chaotic motion drifts by at most
C T rtol with C of order one (measured below); the singular-perturbation limits are first
order in 1/alpha_v and in slip_scale, which the tests check by the scaling between two values.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from stability import simulate

TILTED = dict(omega=[0.05, -0.02, 1.0], k=[np.sin(0.5), 0.0, np.cos(0.5)])  # 28.6 degrees
W = np.array(TILTED["omega"])
ROLLING_START = dict(velocity=[W[1], -W[0]])  # V0 = -K x omega: slip V_c = 0 exactly
PAR = dict(q=-0.1, fr_inv=0.5, sigma=1.0)
T_LONG = 1e4


def _drift(x: np.ndarray) -> float:
    return float(np.max(np.abs(x - x[0])))


@pytest.fixture(scope="module")
def rolling_reference():
    """The rolling sphere over 20 time units at rtol 1e-11 (error ~1e-10, below every
    tolerance that uses it)."""
    return simulate("rolling", t_end=20.0, dt=0.05, **TILTED, **PAR, rtol=1e-11, atol=1e-14)


@pytest.mark.parametrize("model", ["rolling", "sliding"])
def test_long_run_drift_is_the_integrators(model):
    """10^4 time units (1600 spin periods). Measured drifts (rtol 1e-8 / 1e-10):
    rolling: |k| 3.4e-6 / 3.3e-8, energy 2.9e-8 / 2.8e-10, h_cg 4.9e-8 / 4.7e-10;
    frictionless sliding: |k| 2.9e-6 / 2.8e-8, energy 3.1e-8 / 2.9e-10, horizontal momentum
    8e-11 / 1e-12, h_cg 4.6e-8 / 4.4e-10. So drift ~ 0.03 T rtol at most (|k|): the tests
    allow 0.1 T rtol and require the drift to fall by more than 30 when rtol falls by 100
    (it falls by 100: the global error of a fifth-order method with error-per-step control).
    No projection onto |k| = 1 is applied: the drift stays at the tolerance's level."""
    kw = dict(velocity=[0.03, -0.01], alpha_v=0.0) if model == "sliding" else {}
    drifts = {}
    for rtol in (1e-8, 1e-10):
        ds = simulate(model, t_end=T_LONG, dt=1.0, **TILTED, **PAR, **kw, rtol=rtol, atol=rtol * 1e-3, method="dopri5")
        assert ds.attrs["status"] == 0
        d = {
            "|k|": _drift(np.linalg.norm(ds.k.values, axis=1)),
            "energy": _drift(ds.energy.values),
            "h_cg": _drift(ds.h_cg.values),
        }
        if model == "sliding":
            d["momentum"] = max(_drift(ds.momentum.values[:, 0]), _drift(ds.momentum.values[:, 1]))
        for name, v in d.items():
            assert v <= 0.1 * T_LONG * rtol, (rtol, name, v)
        drifts[rtol] = d
        assert float(np.ptp(ds.polar_angle.values)) > 1.0  # a nutating motion, not a rest state
    for name in drifts[1e-8]:
        if name != "momentum":  # momentum sits near round-off already (1e-12)
            assert drifts[1e-10][name] * 30 < drifts[1e-8][name], name


@pytest.mark.parametrize("law", ["isotropic", "componentwise"])
def test_coulomb_at_zero_slip_is_the_regularised_stick(law, rolling_reference):
    """Start exactly at zero slip (V_c = 0, where sgn is discontinuous), Coulomb friction
    alone (alpha_k = 0.5, alpha_v = 0). The regularised law (stability/nonlinear/friction.py)
    is then viscous with coefficient alpha_k / eps, far above the traction rolling needs
    (|f| <= 0.012 here, from the rolling model): the sphere rolls, with the slip that makes the
    regularised law deliver the rolling traction,

        isotropic:      |V_c| = eps |f| / sqrt(alpha_k^2 - |f|^2),
        componentwise:  V_ci  = eps f_i / sqrt(alpha_k^2 - f_i^2),

    f the rolling model's traction (an independent code). The slip matches that to 1 % (measured
    to 3 digits; the correction is relative O(eps) from the slip's own dynamics), and the axis
    follows the rolling one to O(eps): measured 1.3e-4, 1.3e-5, 1.3e-6 for eps = 1e-3, 1e-4,
    1e-5. No NaN at V_c = 0, status 0; the automatic method is LSODA (stiff)."""
    f_roll = rolling_reference.friction.values[:, :2]
    a_k = 0.5
    devs = []
    for eps in (1e-3, 1e-4):
        ds = simulate(
            "sliding",
            t_end=20.0,
            dt=0.05,
            **TILTED,
            **ROLLING_START,
            **PAR,
            alpha_v=0.0,
            alpha_k=a_k,
            slip_scale=eps,
            friction=law,
            rtol=1e-10,
            atol=1e-13,
        )
        assert ds.attrs["status"] == 0 and ds.attrs["method"] == "LSODA"
        assert np.isfinite(ds.k.values).all() and np.isfinite(ds.friction.values).all()
        assert float(ds.slip_speed[0]) < 1e-15
        if law == "isotropic":
            fm = np.hypot(*f_roll.T)
            pred = eps * fm / np.sqrt(a_k**2 - fm**2)
        else:
            pred = np.hypot(*(eps * f_roll / np.sqrt(a_k**2 - f_roll**2)).T)
        ratio = ds.slip_speed.values[1:] / pred[1:]
        assert np.all(np.abs(ratio - 1) < 1e-2), (ratio.min(), ratio.max())
        devs.append(float(np.max(np.abs(ds.k.values - rolling_reference.k.values))))
        assert devs[-1] <= 0.5 * eps
    assert devs[0] / devs[1] == pytest.approx(10.0, rel=0.2)


def test_stiff_viscous_friction_default_copes(rolling_reference):
    """alpha_v = 1e3, 1e4, 1e6: the slip mode decays at alpha_v A_C / (mu A_G) (1.3e3 to
    1.3e6, above STIFF_RATE = 400), the automatic method switches to LSODA and each run takes
    ~3e3 evaluations. Sliding follows rolling to first order in 1/alpha_v (docs/nonlinear.md):
    measured |k - k_rolling| = 6.48e-5, 6.48e-6 (so 0.0648 / alpha_v) and 7.2e-8 at 1e6, where
    the integrator's own error (~T rtol = 2e-9 .. 1e-8) and the 1/alpha_v term are comparable."""
    for a in (1e3, 1e4, 1e6):
        ds = simulate(
            "sliding", t_end=20.0, dt=0.05, **TILTED, **ROLLING_START, **PAR, alpha_v=a, rtol=1e-10, atol=1e-13
        )
        assert ds.attrs["status"] == 0 and ds.attrs["method"] == "LSODA"
        assert ds.attrs["nfev"] < 20_000
        dev = float(np.max(np.abs(ds.k.values - rolling_reference.k.values)))
        assert dev * a == pytest.approx(0.0648, rel=0.1) if a < 1e6 else dev < 2e-7


def test_moderately_stiff_run_keeps_the_explicit_method_and_its_accuracy():
    """alpha_v = 100 (slip-mode rate 127, below STIFF_RATE = 400): "auto" keeps the compiled
    dopri5, whose step is then partly held by stability, because there it is both cheaper and
    more accurate than LSODA (stability.nonlinear.runs.STIFF_RATE has the measurements). Reference:
    DOP853 at rtol 1e-13 (a different method; it agrees with Radau at rtol 1e-12 to 8e-15).
    Linear regime, tilt 1e-3, 50 time units: measured relative error of the final tilt 3e-10
    for "auto" at the default rtol 1e-9 (LSODA at the same rtol: 8.5e-7); the bound 1e-8
    leaves 30x for platform differences and fails for LSODA."""
    run = dict(
        t_end=50.0, dt=1.0, omega=[0.0, 0.0, 1.0], k=[1e-3, 0.0, 1.0], q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=100.0
    )
    ref = simulate("sliding", **run, method="DOP853", rtol=1e-13, atol=1e-17)
    ds = simulate("sliding", **run)
    assert ds.attrs["method"] == "dopri5" and ds.attrs["status"] == 0
    tilt = np.hypot(*ds.k.values[-1, :2]) / np.hypot(*ref.k.values[-1, :2])
    assert abs(tilt - 1) < 1e-8


@pytest.mark.parametrize("method", ["dopri5", "RK45"])
def test_explicit_method_on_stiff_run_is_reported_not_hung(method):
    """An explicit method at alpha_v = 1e4 is step-limited by stability (h ~ 2.8 / 1.3e4):
    200 time units would take ~10^6 steps. With max_steps it stops, warns, returns the states
    computed so far (finite) and NaN after, and says so in attrs (status -1). Before this the
    scipy methods ignored max_steps (solve_ivp has no such limit)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ds = simulate(
            "sliding", t_end=200.0, **TILTED, velocity=[-0.02, -0.05], **PAR, alpha_v=1e4, method=method, max_steps=3000
        )
    assert ds.attrs["status"] == -1
    assert "maximum number of steps" in ds.attrs["message"]
    assert any(issubclass(w.category, RuntimeWarning) for w in caught)
    ok = np.isfinite(ds.k.values).all(axis=1)
    assert ok[0] and not ok[-1]
    assert np.all(ok[: int(ok.sum())])  # finite up to the stop, NaN after
