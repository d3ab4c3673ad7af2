"""Marginal is a decision, not round-off.

References: exact structure derived in stability/models/sliding.py and second_order.py:

* sliding: ``c0 = -mu alpha_v q fr_inv`` is exactly zero at fr_inv = 0, so s = 0 is an exact
  eigenvalue (a spin about a tilted axis is an equilibrium without gravity);
* fixed_pivot / rolling: ``p(i nu) = -nu^2 + sigma_hat nu - kappa`` is real, so a gyroscopically
  stable top has Re s = 0 exactly (eq. 8 with real lambda).
"""

from __future__ import annotations

import numpy as np

import stability
from stability.linear.spectra import MARGINAL, STABLE, UNSTABLE


def test_zero_eigenvalue_at_zero_gravity_is_exact_and_marginal():
    q = np.linspace(0.01, 0.45, 45)  # q > 0: the other modes decay at sigma = 1, alpha_v = 0.5
    sp = stability.spectrum("sliding", q=q, fr_inv=0.0, sigma=1.0, alpha_v=0.5)
    assert (sp.eigenvalues == 0).any(axis=-1).all()
    assert (sp.stability == MARGINAL).all()


def test_zero_gravity_unstable_where_a_mode_grows():
    # q = -0.1, sigma = 1 < (1 - mu q^2)/(1 + q) = 1.0858: the gyroscopic mode grows
    sp = stability.spectrum("sliding", q=-0.1, fr_inv=0.0, sigma=1.0, alpha_v=0.5)
    assert sp.stability == UNSTABLE
    assert sp.max_growth_rate > 1e-3


def test_stable_point():
    # q = 0.1, fr_inv = 0.3: every mode decays (checked against the lapack path's signs)
    sp = stability.spectrum("sliding", q=0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    ref = np.linalg.eigvals(
        np.linalg.solve(*stability.get_model("sliding").matrices(q=0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5, mu=2.28))
    )
    assert (ref.real < -1e-4).all()
    assert sp.stability == STABLE


def test_conservative_models_neutral_exactly():
    # rolling (eq. 8 as printed) with q < 0 is always gyroscopically stable (paper, after eq. 9): Re s == 0 exactly
    q = np.linspace(-0.6, -0.01, 60)
    sp = stability.spectrum("rolling_eq8", q=q, fr_inv=np.array([[0.0], [0.3], [3.0]]), sigma=0.3)
    assert (sp.eigenvalues.real == 0).all()
    assert (sp.stability == MARGINAL).all()


def test_fixed_pivot_threshold_sign():
    """Eq. (8): unstable iff 4 kappa > sigma_hat^2, i.e. fr_inv > sigma^2 / (4 mu (1+q) A_C)."""
    q, sg, mu = -0.1, 1.0, 2.28
    a_c = 1 + mu * (1 + 2 * q)
    f_c = sg**2 / (4 * mu * (1 + q) * a_c)
    sp = stability.spectrum("fixed_pivot", q=q, fr_inv=np.array([0.9, 0.999, 1.001, 1.1]) * f_c, sigma=sg)
    assert list(sp.stability) == [MARGINAL, MARGINAL, UNSTABLE, UNSTABLE]


def test_neutral_line_at_zero_gravity_right_or_flagged():
    """On the sliding top's neutral line at fr_inv = 0, sigma = (1 - mu q^2)/(1 + q) (README),
    the gyroscopic mode is neutral in exact arithmetic; with sigma rounded its true growth rate
    is O(u). Every method must give that mode's sign as the mpmath reference (60 digits, on
    the polynomial typed in test_hard_spectra) or flag it neutral, and the point must not be
    called unstable unless the reference grows. Measured: all three methods flag it (|Re s| <=
    1.4e-16 kernel/polynomial, 8.9e-16 LAPACK; bounds >= 1.5e-15 and 4.2e-15)."""
    from test_hard_spectra import _poly_reference, assert_right_or_flagged

    mu = 2.28
    for q in np.linspace(-0.4, 0.4, 9):
        sg = (1 - mu * q * q) / (1 + q)
        ref = _poly_reference(q, 0.0, sg, 0.5, mu)
        for method in ("kernel", "polynomial", "lapack"):
            sp = stability.spectrum("sliding", q=q, fr_inv=0.0, sigma=sg, alpha_v=0.5, mu=mu, method=method)
            assert_right_or_flagged(sp, ref)
            near = np.argsort(np.abs(sp.eigenvalues.real))[1]  # [0] is the structural zero
            assert sp.neutral[near] or abs(sp.eigenvalues[near].real) > sp.error_bound[near]
