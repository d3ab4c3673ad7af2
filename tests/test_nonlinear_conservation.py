"""Conserved quantities of the nonlinear models as accuracy checks.

References (independent of the code): energy, horizontal momentum and h_cg (eq. 10) are
integrals of the exact equations (derivations in docs/nonlinear.md and the docstring of
stability.nonlinear.quantities), and the energy balance dE/dt = f . V_c (the power of the
contact force at the contact point) integrated by Simpson's rule.

Tolerances. The compiled Dormand-Prince integrator keeps the local error per step below
rtol |y| + atol; over a run of T time units with O(1) states, the global drift of an
integral is at most of order T * rtol * (a small constant) for these non-chaotic motions.
With rtol = 1e-10 and T = 200 that is ~2e-8; the tests allow 1e-7 and check that the drift
shrinks with the tolerance (so it is the integrator's, not a modelling error).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import simpson

from stability import simulate

TILTED = dict(omega=[0.05, -0.02, 1.0], k=[np.sin(0.5), 0.0, np.cos(0.5)])  # 28.6 degrees


def _drift(x: np.ndarray) -> float:
    return float(np.max(np.abs(x - x[0])))


def test_frictionless_sliding_conserves_energy_and_horizontal_momentum():
    runs = {}
    for rtol in (1e-7, 1e-10):
        runs[rtol] = simulate(
            "sliding",
            t_end=200.0,
            **TILTED,
            velocity=[0.03, -0.01],
            q=-0.1,
            fr_inv=0.5,
            sigma=1.0,
            alpha_v=0.0,
            rtol=rtol,
            atol=rtol * 1e-3,
        )
    ds = runs[1e-10]
    assert float(np.ptp(ds.polar_angle.values)) > 5.0  # a real nutating motion, not a rest state
    assert _drift(ds.energy.values) < 1e-7
    assert _drift(ds.momentum.values[:, 0]) < 1e-7
    assert _drift(ds.momentum.values[:, 1]) < 1e-7
    assert _drift(ds.h_cg.values) < 1e-7
    assert _drift(ds.energy.values) < _drift(runs[1e-7].energy.values)


FRICTION_CASES = [
    ("isotropic", "equilibrium", 0.0),
    ("isotropic", "equilibrium", 0.2),
    ("componentwise", "equilibrium", 0.2),
    ("isotropic", "actual", 0.2),
]


def _run(friction, normal, alpha_k, t_end, dt):
    return simulate(
        "sliding",
        t_end=t_end,
        dt=dt,
        **TILTED,
        velocity=[0.2, 0.05],
        q=-0.1,
        fr_inv=0.3,
        sigma=1.0,
        alpha_v=0.5,
        alpha_k=alpha_k,
        friction=friction,
        normal=normal,
        method="dopri5",
        rtol=1e-10,
        atol=1e-13,
    )


@pytest.mark.parametrize("friction,normal,alpha_k", FRICTION_CASES)
def test_sliding_with_friction_keeps_h_cg(friction, normal, alpha_k):
    """h_cg is conserved for any force acting at the contact point (Jellett), sticking included."""
    ds = _run(friction, normal, alpha_k, 60.0, 0.1)
    assert _drift(ds.h_cg.values) < 1e-8


@pytest.mark.parametrize("friction,normal,alpha_k", FRICTION_CASES)
def test_sliding_with_friction_balances_energy(friction, normal, alpha_k):
    """E(t) - E(0) = int f . V_c dt, and f . V_c <= 0.

    With Coulomb friction the slip is extinguished after about 0.7 time units here (the sphere
    then rolls and the regularised law has a fast transient), so those runs stop at 0.6, before
    sticking; the viscous run lasts 60. Simpson's rule with these sample spacings has a
    relative error below 1e-9 (the power varies on the O(1) spin time and the O(0.1) slip time).
    """
    t_end, dt = (60.0, 0.01) if alpha_k == 0.0 else (0.6, 1e-4)
    ds = _run(friction, normal, alpha_k, t_end, dt)
    v = ds.velocity.values
    w = ds.omega.values
    slip = np.column_stack([v[:, 0] - w[:, 1], v[:, 1] + w[:, 0]])
    assert float(ds.slip_speed.min()) > 1e-2 or alpha_k == 0.0  # before sticking
    power = np.einsum("ij,ij->i", ds.friction.values[:, :2], slip)
    assert np.all(power <= 1e-15)  # friction never feeds energy in
    dissipated = simpson(power, x=ds.time.values)
    change = float(ds.energy[-1] - ds.energy[0])
    assert change < -1e-3  # the run does dissipate
    assert abs(change - dissipated) < 1e-6 * abs(change)


def test_rolling_conserves_energy_and_h_cg():
    ds = simulate("rolling", t_end=200.0, **TILTED, q=-0.1, fr_inv=0.5, sigma=1.0, rtol=1e-10, atol=1e-13)
    assert float(np.ptp(ds.polar_angle.values)) > 1.0
    assert _drift(ds.energy.values) < 1e-7
    assert _drift(ds.h_cg.values) < 1e-7
    assert float(np.max(ds.slip_speed)) < 1e-12  # V_c = 0 holds by construction


def test_fixed_pivot_conserves_energy_spin_and_vertical_momentum():
    ds = simulate("fixed_pivot", t_end=200.0, **TILTED, q=-0.1, fr_inv=0.5, sigma=1.0, rtol=1e-10, atol=1e-13)
    assert _drift(ds.energy.values) < 1e-7
    assert _drift(ds.spin.values) < 1e-7
    assert _drift(ds.angular_momentum_vertical.values) < 1e-7


def test_rolling_is_the_large_friction_limit_of_sliding():
    """With alpha_v large the slip is damped on a time ~ mu A_G / (alpha_v A_C) and sliding
    follows rolling; starting from a rolling state the difference after T scales as 1/alpha_v
    (first-order singular perturbation), which the test checks by halving 1/alpha_v."""
    kw = dict(t_end=20.0, q=-0.1, fr_inv=0.5, sigma=1.0, **TILTED)
    w = np.array(TILTED["omega"])
    roll = simulate("rolling", **kw, rtol=1e-11, atol=1e-14)
    diffs = []
    for alpha_v in (200.0, 400.0):
        sl = simulate("sliding", **kw, velocity=[w[1], -w[0]], alpha_v=alpha_v, method="Radau", rtol=1e-10, atol=1e-13)
        diffs.append(float(np.max(np.abs(sl.k.values - roll.k.values))))
    assert diffs[1] < diffs[0]
    assert diffs[0] / diffs[1] == pytest.approx(2.0, rel=0.1)


def test_sliding_keeps_jellett_to_integrator_tolerance_over_long_runs():
    """Jellett's integral h_cg (eq. 10) over the paper's Fr^-1 = 0.3 run of Sec. 3(ii) continued
    to 4000 time units (past the rise, onto its final tilted state), at rtol 1e-7 and 1e-9
    (atol 1e-3 rtol). Reference: J is an exact integral of the sliding sphere with any friction
    (docs/steady_states.md, sec. 1), so its drift is the integrator's. Measured max |dJ/J|:
    0.5-0.75 rtol per 1000 time units at both tolerances (1.9e-7 and 1.9e-9 at 4000 units);
    the final-state prediction relies on it (near a branch point the end tilt moves by
    2.2e3 degrees per unit of dJ/J at the paper's end state). Bound: 2 rtol per 1000 units, and
    the drift must scale with rtol (a ratio within a factor 3 of 100)."""
    from stability.nonlinear.scene import INITIAL_CONDITIONS

    drift = {}
    for rtol in (1e-7, 1e-9):
        ds = simulate(
            "sliding",
            t_end=4000.0,
            dt=10.0,
            q=-0.1,
            fr_inv=0.3,
            sigma=1.0,
            alpha_v=0.5,
            rtol=rtol,
            atol=1e-3 * rtol,
            **INITIAL_CONDITIONS[0.3],
        )
        assert float(ds.polar_angle[-1]) > 160.0  # the top has risen
        j = ds.h_cg.values
        drift[rtol] = float(np.max(np.abs(j - j[0]))) / abs(float(j[0]))
        assert drift[rtol] < 2.0 * rtol * 4.0
    assert 100 / 3 < drift[1e-7] / drift[1e-9] < 300
