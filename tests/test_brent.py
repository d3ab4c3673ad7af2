"""continuation.brent.brentq against scipy.optimize.brentq (the independent reference: scipy's
C implementation, of which brent.py is a port). The port must return the very same float as
scipy for the same function, bracket and tolerances (the same iterates, so exact equality is the
right tolerance), and refuse what scipy refuses."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq as scipy_brentq

from continuation.brent import RTOL_MIN, brentq

EPS = float(np.finfo(float).eps)


def _functions(rng: np.random.Generator, n: int):
    """``n`` random bracketed problems of several shapes: smooth cubics with a wiggle (several
    roots in the bracket), steep exponentials and tanh steps (ill-scaled), a flat double-root-like
    ``(x - r)^3`` (slow convergence, bisection steps), a discontinuous sign step (no root: Brent
    converges to the jump) and roots near 0 (absolute tolerance dominates)."""
    out = []
    while len(out) < n:
        kind = len(out) % 6
        a3, a2, a1, a0 = rng.normal(size=4)
        r = rng.uniform(-2.5, 2.5)
        s = 10.0 ** rng.uniform(-3, 3)
        if kind == 0:
            f = lambda x, a3=a3, a2=a2, a1=a1, a0=a0: ((a3 * x + a2) * x + a1) * x + a0 + 0.3 * math.sin(3 * x)
        elif kind == 1:
            f = lambda x, r=r, s=s: math.expm1(min(s * (x - r), 700.0))
        elif kind == 2:
            f = lambda x, r=r, s=s: math.tanh(s * (x - r)) + 1e-3 * (x - r)
        elif kind == 3:
            f = lambda x, r=r: (x - r) * (x - r) * (x - r)
        elif kind == 4:
            f = lambda x, r=r: -1.0 if x < r else 2.0
        else:
            f = lambda x, s=s: s * x * (1.0 + x * x) - 1e-12 * s
        lo, hi = -3.0, 3.0 + rng.uniform(0, 1)
        if np.sign(f(lo)) == np.sign(f(hi)) or f(lo) == 0 or f(hi) == 0:
            continue
        out.append((f, lo, hi))
    return out


def test_same_root_as_scipy_on_random_functions():
    """3,000 problems (:func:`_functions`), xtol from 1e-300 to 1e-3 and rtol from 4 eps to
    1e-6 (the engine's setting is xtol ~ 1e-14 width, rtol 4.5 eps): the same float as scipy,
    and the same failure after maxiter iterations when it is too small."""
    rng = np.random.default_rng(2026)
    for f, lo, hi in _functions(rng, 3000):
        xtol = 10.0 ** rng.uniform(-300, -3)
        rtol = max(RTOL_MIN, 10.0 ** rng.uniform(-16, -6))
        maxiter = int(rng.choice([5, 50, 100, 200]))
        try:
            expected = scipy_brentq(f, lo, hi, xtol=xtol, rtol=rtol, maxiter=maxiter)
        except RuntimeError as exc:
            with pytest.raises(RuntimeError, match="Failed to converge after"):
                brentq(f, lo, hi, xtol=xtol, rtol=rtol, maxiter=maxiter)
            assert "Failed to converge" in str(exc)
            continue
        got = brentq(f, lo, hi, xtol=xtol, rtol=rtol, maxiter=maxiter)
        assert got == expected, (lo, hi, xtol, rtol, got, expected)


def test_roots_at_the_ends_and_refusals():
    """A zero at an end is returned as is; the refusals of scipy (same-sign ends, xtol <= 0,
    rtol < 4 eps) are refused too, with the value in the message."""
    assert brentq(lambda x: x, 0.0, 1.0) == scipy_brentq(lambda x: x, 0.0, 1.0) == 0.0
    assert brentq(lambda x: x - 1.0, 0.0, 1.0) == 1.0
    with pytest.raises(ValueError, match="different signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(ValueError, match=r"xtol too small \(0 <= 0\)"):
        brentq(lambda x: x, -1.0, 1.0, xtol=0.0)
    with pytest.raises(ValueError, match="rtol too small"):
        brentq(lambda x: x, -1.0, 1.0, rtol=EPS)
    with pytest.raises(ValueError):
        scipy_brentq(lambda x: x, -1.0, 1.0, rtol=EPS)
