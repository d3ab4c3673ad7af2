"""Spectra where naive methods fail, against mpmath at 50 digits.

* Near-singular mass matrix, 1 - mu q^2 -> 0 (det M = A_G): a naive ``1 - mu*q*q`` loses
  ``log10(1/A_G)`` digits to cancellation; the package evaluates A_G with error-free
  transformations (stability/inertia.py).
* Widely separated scales: alpha_v from 1e-6 to 1e6 (a fast slip mode ~ -alpha_v A_C/(mu A_G)
  beside slow modes whose growth rates are ~1e-8 but whose signs matter), fr_inv up to 1e3.
* Tiny structural-looking roots: q = 1e-9 makes c0 tiny (not zero).

Reference: eigenvalues of M^-1 A from eq. (11) typed in test_spectra_reference, 50 digits.
Tolerance: 1e-14 relative per eigenvalue — the polynomial method is backward stable in the
coefficients and these roots are simple and well separated (condition numbers < 10), so
anything above a few units of round-off would be a defect, not noise. The sign of every
growth rate must agree with the reference.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import stability
from stability.inertia import transverse_inertia_g
from test_spectra_reference import _match, _sliding_reference

MU = 2.28
CASES = []
for eps in (1e-3, 1e-6, 1e-9, 1e-12):
    q = -np.sqrt((1 - eps) / MU)
    CASES.append(dict(q=q, fr_inv=0.3, sigma=float(2 * transverse_inertia_g(q, MU)), alpha_v=0.5))
for a in (1e-6, 1e-3, 1e3, 1e6):
    CASES.append(dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=a))
for f in (1e-8, 1e2, 1e3):
    CASES.append(dict(q=-0.1, fr_inv=f, sigma=1.0, alpha_v=0.5))
CASES.append(dict(q=1e-9, fr_inv=0.3, sigma=1.0, alpha_v=0.5))


@pytest.mark.parametrize("case", CASES, ids=lambda c: ",".join(f"{k}={v:.3g}" for k, v in c.items()))
def test_hard_case_against_mpmath(case):
    sp = stability.spectrum("sliding", mu=MU, **case)
    ref = _sliding_reference(case["q"], case["fr_inv"], case["sigma"], case["alpha_v"], MU)
    assert _match(sp.eigenvalues, ref) <= 1e-14
    ref_max = max(float(mp.re(r)) for r in ref)
    assert np.sign(sp.max_growth_rate) == np.sign(ref_max)


def test_transverse_inertia_g_against_mpmath():
    """A_G for the floating-point q at the domain edge, relative to A_G itself."""
    mp.mp.dps = 50
    for eps in (1e-4, 1e-8, 1e-12, 1e-15):
        q = np.sqrt((1 - eps) / MU)
        exact = 1 - mp.mpf(MU) * mp.mpf(q) ** 2
        assert abs(float((transverse_inertia_g(q, MU) - exact) / exact)) <= 4 * 2.0**-53


def test_fast_slip_mode_runs_to_infinity_at_singular_mass_matrix():
    """As A_G -> 0 one root runs off like ``s = -c2/c3 + c1/c2 + O(c3)``.

    Derivation: for large s, ``c3 s^3 + c2 s^2 + c1 s + c0 = 0`` gives
    ``s = -c2/c3 - c1/(c3 s) - ...`` with ``1/s = -(c3/c2)(1 + rho + ...)``,
    ``rho = c3 c1 / c2^2``; the first neglected term is ``(c1/c2) rho``, i.e. ``rho^2``
    relative to ``|s| ~ |c2/c3|``. The test allows ``4 |rho|^2`` plus 8 units of round-off
    (which dominate at A_G = 1e-12). Coefficients typed from the
    docstring of stability/models/sliding.py with alpha_v = 0.5, fr_inv = 0.3.
    """
    a, f = 0.5, 0.3
    for eps in (1e-4, 1e-8, 1e-12):
        q = -np.sqrt((1 - eps) / MU)
        a_g = float(transverse_inertia_g(q, MU))
        s = stability.eigenvalues("sliding", q=q, fr_inv=f, sigma=a_g, alpha_v=a, mu=MU)
        a_c = a_g + MU * (1 + q) ** 2
        c3, c2 = MU * a_g, a * a_c - 1j * MU * a_g
        c1 = -MU * MU * q * f - 1j * a * (a_g + MU * (1 + q))
        expansion = -c2 / c3 + c1 / c2
        fast = s[np.argmax(np.abs(s))]
        rho = c3 * c1 / c2**2
        assert abs(fast - expansion) / abs(expansion) < 4 * abs(rho) ** 2 + 8 * 2.0**-53
