"""validate() at the extremes of alpha_v (issue 13, item 3): the leading mode is the one with
the largest growth rate, and a measurement is resolved only when it holds.

References: mpmath's roots (60 digits) of eq. 11's characteristic polynomial
``mu det(s M - A) = c3 s^3 + c2 s^2 + c1 s + c0`` (``c3 = mu A_G``, ``c2 = alpha_v A_C - i mu
sigma``, ``c1 = -mu^2 q fr_inv - i alpha_v (sigma + mu (1 + q))``, ``c0 = -mu alpha_v q fr_inv``)
and its closed-form limits. For ``alpha_v -> inf`` the terms in alpha_v dominate: besides the slip
mode ``s ~ -alpha_v A_C / (mu A_G)`` the two slow modes tend to ``s = i w`` with
``A_C w^2 - (sigma + mu (1 + q)) w + mu q fr_inv = 0`` (the rolling limit); for ``alpha_v -> 0``
they tend to ``s = 0`` and ``s = i w`` with ``A_G w^2 - sigma w + mu q fr_inv = 0`` (the
frictionless top). The leading mode is the larger-``w`` root in both limits here.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

import stability
from stability import validate
from stability.errors import DomainError

mp = mpmath.mp
MU = mpmath.mpf("2.28")
P = dict(q=-0.1, fr_inv=0.3, sigma=1.0)


def _roots(alpha_v):
    mp.dps = 60
    q, f, s, a = (mpmath.mpf(v) for v in (P["q"], P["fr_inv"], P["sigma"], alpha_v))
    a_g, a_c = 1 - MU * q * q, 1 + MU * (1 + 2 * q)
    c = [MU * a_g, a * a_c - 1j * MU * s, -MU * MU * q * f - 1j * a * (s + MU * (1 + q)), -MU * a * q * f]
    return mpmath.polyroots(c[::-1], maxsteps=400, extraprec=600, asc=True)


def _limit_w(alpha_v):
    mp.dps = 40
    q, f, s = (mpmath.mpf(v) for v in (P["q"], P["fr_inv"], P["sigma"]))
    a2 = 1 + MU * (1 + 2 * q) if alpha_v > 1 else 1 - MU * q * q
    a1 = s + MU * (1 + q) if alpha_v > 1 else s
    return (a1 + mp.sqrt(a1 * a1 - 4 * a2 * MU * q * f)) / (2 * a2)


@pytest.mark.parametrize("alpha_v", [1e12, 1e-12])
def test_leading_mode_is_the_largest_growth_rate(alpha_v):
    """At alpha_v = 1e12 the slip mode (-1.3e12) used to be taken as leading (the O(1) modes
    dropped as "zero" beside it). The predicted mode must be mpmath's root of largest real part:
    its frequency to 1e-13 relative (a simple root), its growth rate (~1e-14, beside |s| = 1.1)
    within the kernel's error bound plus u |s|; and its frequency the closed-form limit to
    1e-10 (the next terms are O(1/alpha_v), O(alpha_v)). The growth rate is far below
    1e-3 |s|, so the measurement is not resolved and status says why; the measured values
    are finite and the run's growth rate agrees with neutral to 1e-3 |s|."""
    roots = _roots(alpha_v)
    lead = max(roots, key=lambda r: mpmath.re(r))
    ds = validate("sliding", alpha_v=alpha_v, **P)
    sp = stability.spectrum("sliding", alpha_v=alpha_v, **P)
    bound = float(sp.error_bound[np.argmin(np.abs(sp.eigenvalues - complex(lead)))])
    assert abs(float(ds.predicted_frequency[0]) - float(mpmath.im(lead))) <= 1e-13 * abs(float(mpmath.im(lead)))
    assert abs(float(ds.predicted_growth_rate[0]) - float(mpmath.re(lead))) <= bound + 2**-52 * abs(complex(lead))
    assert abs(float(ds.predicted_frequency[0]) - float(_limit_w(alpha_v))) <= 1e-10
    assert np.isfinite(float(ds.measured_growth_rate[0])) and np.isfinite(float(ds.measured_frequency[0]))
    assert abs(float(ds.measured_frequency[0]) - float(mpmath.im(lead))) <= 1e-6
    assert not bool(ds.resolved[0]) and str(ds.status.values[0]).startswith("growth rate not resolved")
    assert bool(ds.sign_agrees[0])
    # the Jacobian's eigenvalue (LAPACK, absolute error ~u of the largest mode) carries a bound
    # that covers the exact growth rate, and says when it does not resolve it
    assert abs(float(ds.jacobian_growth_rate[0]) - float(mpmath.re(lead))) <= float(ds.jacobian_bound[0])
    assert not bool(ds.jacobian_resolved[0])


def test_a_measurement_that_is_nan_is_never_resolved(monkeypatch):
    """A run whose samples are not finite (here: the integrator's output replaced by NaN after
    the first half) is not resolved, its status says so, sign_agrees is False and a
    RuntimeWarning names the point. Reference: the same point unmodified is resolved (an
    unstable mode, growth rate 0.17 of |s|: tests/test_validate.py's spread)."""
    import stability.nonlinear.validation as v

    kw = dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    assert bool(validate("sliding", **kw).resolved[0])
    real = v.simulate

    def broken(*a, **k):
        ds = real(*a, **k)
        vals = ds.k.values.copy()
        vals[len(vals) // 2 :] = np.nan
        return ds.assign(k=(ds.k.dims, vals))

    monkeypatch.setattr(v, "simulate", broken)
    with pytest.warns(RuntimeWarning, match="not all finite"):
        ds = validate("sliding", **kw)
    assert not bool(ds.resolved[0]) and not bool(ds.sign_agrees[0])
    assert "not all finite" in str(ds.status.values[0])


def test_out_of_domain_hint_is_not_mask_unphysical():
    """validate has no mask_unphysical: its domain error must not suggest it."""
    with pytest.raises(DomainError, match="sigma") as err:
        validate("sliding", q=-0.1, fr_inv=0.3, sigma=[1.0, 3.0], alpha_v=0.5)
    assert "mask_unphysical" not in str(err.value)
