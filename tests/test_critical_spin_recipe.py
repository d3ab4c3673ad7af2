"""The critical-spin recipe against the closed-form neutral surface of the sliding model.

Reference (docs/continuation.md, derived independently there and re-derived here): for
alpha_v > 0 a mode of eq. (11) is neutral only where the free-top and rolling-top polynomials
share the root w = 1/(1 + q), i.e. on sigma = (1 - mu q^2)/(1 + q) + mu q (1 + q) fr_inv. So the
critical fr_inv is (sigma - A_G/(1 + q)) / (mu q (1 + q)) and the spin is sqrt(g / (fr_inv R)).
Tolerance 1e-9 relative: the thresholds are polished to near machine precision
(tests/test_thresholds.py), and the rpm conversion adds a few roundings.
"""

from __future__ import annotations

import numpy as np

from stability import Top
from stability.recipes import compute, load_recipe


def _closed_form_rpm(q: float, top: Top) -> float:
    mu, sigma = top.mu, top.sigma
    a_g = 1 - mu * q * q
    f_c = (sigma - a_g / (1 + q)) / (mu * q * (1 + q))
    return np.sqrt(top.g / (f_c * top.radius)) * 60 / (2 * np.pi)


def test_critical_spin_recipe(tmp_path):
    p = tmp_path / "spin.toml"
    p.write_text('title = "x"\nkind = "critical_spin"\npreset = "table1"\nx = "q"\n[grid]\nq = [-0.3, -0.1, -0.02]\n')
    ds = compute(load_recipe(p))["sliding"]
    top = Top.table1()
    for q, up, inv in zip(ds.q.values, ds.critical_spin_upright.values, ds.critical_spin_inverted.values):
        assert abs(up / _closed_form_rpm(q, top) - 1) < 1e-9
        assert abs(inv / _closed_form_rpm(-q, top) - 1) < 1e-9
    assert ds.critical_spin_upright.attrs["units"] == "min-1"
