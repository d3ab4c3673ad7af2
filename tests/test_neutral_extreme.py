"""Neutral curves at large alpha_v (issue 13, item 2): found from the start grid, on the
closed-form curve, and an empty result only with a warning and a note.

Reference: the sliding model's neutral surface (derived in tests/test_thresholds_extreme.py)
``sigma = (1 - mu q^2)/(1 + q) + mu q (1 + q) fr_inv`` with frequency ``w = 1/(1 + q)``, for
every alpha_v > 0. At alpha_v >= 1e8 the slow modes' growth rates (O(1/alpha_v)) sat below the
atlas flag's floor 16 u max|s| (max|s| ~ 1.3 alpha_v): every start-grid point was "marginal",
no edge changed and an empty curve came back, exit 0, no warning. With start points supplied,
the old residual (one scale for both rows) let Newton converge onto points of the dominant row
alone (32,717 spurious points of the rolling limit at alpha_v = 1e12, and the curve 7e-12 off
at alpha_v = 1e-12): every traced point is checked against the closed form here.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from stability.linear.neutral_curves import neutral_curve

MU = 2.28
U = 2.0**-53


@pytest.mark.parametrize("alpha_v", [1e-12, 1e8, 1e9, 1e12])
def test_curve_at_large_alpha_v_is_the_closed_form(alpha_v):
    """Tolerance: each point solves both row-scaled equations to a backward error <= 1e-15
    (the residual column); sigma and w enter the rows with O(1) condition numbers on this
    curve, so the closed form holds to 32 u absolute (values O(1)). The traced q-extent is the
    same as at alpha_v = 0.5 (the curve does not depend on alpha_v). The check column (LAPACK
    on M^-1 A) is good only to ~u of the slip mode (1.3 alpha_v): it is within its own bound
    check_bound, which says how little it checks at large alpha_v."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        ds = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=alpha_v))
    ref = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=0.5))
    q, s, w = ds.q.values, ds.sigma.values, ds.frequency.values
    assert ds.sizes["point"] > 20 and "note" not in ds.attrs
    assert np.max(ds.residual.values) <= 1e-15
    assert np.max(np.abs(s - ((1 - MU * q**2) / (1 + q) + MU * q * (1 + q) * 0.3))) <= 32 * U
    assert np.max(np.abs(w - 1 / (1 + q))) <= 32 * U
    assert abs(q.min() - ref.q.values.min()) <= 1e-12 and abs(q.max() - ref.q.values.max()) <= 1e-12
    assert np.all(np.abs(ds.check_growth_rate.values) <= ds.check_bound.values)
    # the curve is the stability boundary throughout (as at alpha_v = 0.5): the third mode decays,
    # Re s < 0 (the slip mode -1.3 alpha_v; ~-alpha_v at small alpha_v), signed against its own
    # bound rather than a tolerance relative to the slip mode (which made every O(1) mode "not
    # growing" at 1e12 whatever its sign)
    assert bool(ds.leading.all()) and bool(ref.leading.all())
    if alpha_v > 1:
        assert np.min(ds.check_bound.values) >= 2.0**-52 * alpha_v  # absolute, ~u |slip mode|


def test_genuinely_empty_curve_warns_and_says_why():
    """At fr_inv = 0.3 the curve lies above sigma = 0.6 for q in [0.3, 0.5] (closed form: sigma
    = 0.61 at q = 0.3, 0.79 at 0.5): the window sigma in [0.1, 0.5] holds no neutral point, the
    signs are decided everywhere (unstable throughout): an empty dataset with a UserWarning and
    the attribute note."""
    with pytest.warns(UserWarning, match="no neutral curve crosses the ranges"):
        ds = neutral_curve(
            "sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=1e12), x_range=(0.3, 0.5), y_range=(0.1, 0.5)
        )
    assert ds.sizes["point"] == 0
    assert "number of growing modes is the same" in ds.attrs["note"]
