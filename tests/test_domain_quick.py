"""The kernel's cheap domain decision is still exact (:func:`stability.parameters.domain_sides_quick`).

Reference: :mod:`fractions`. The bounds ``1 - mu q^2 > 0`` and ``sigma <= 2 (1 - mu q^2)`` are
evaluated in exact rational arithmetic on the doubles given; the quick decision (plain floats
with a proven margin, exact expansions only between its thresholds), the exact one
(:func:`stability.parameters.domain_sides`) and the compiled kernel's domain test must all say
the same, with no tolerance: a decision is a yes or no. Cases: points exactly on each bound,
and one ulp either side of it (in q, in mu and in sigma), points in the band where the plain
comparison cannot decide, and random points far from the bounds.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from stability.linear.kernel import sliding_domain
from stability.parameters import domain_applies, domain_sides, domain_sides_quick, inside_domain, sigma_max

APPLIES = domain_applies(("q", "fr_inv", "sigma", "alpha_v", "mu"))


def exact_inside(q: float, sigma: float, mu: float) -> bool:
    """Both A_G bounds and the sign bounds, in rationals (the doubles given, exactly)."""
    a_g = 1 - Fraction(mu) * Fraction(q) ** 2
    return mu > 0 and sigma > 0 and a_g > 0 and Fraction(sigma) <= 2 * a_g


def up(x: float) -> float:
    return math.nextafter(x, math.inf)


def down(x: float) -> float:
    return math.nextafter(x, -math.inf)


def boundary_cases() -> list[tuple[float, float, float]]:
    cases = []
    # mu q^2 = 1 exactly representable, and one ulp either side in q and in mu
    for q, mu in ((0.5, 4.0), (2.0, 0.25), (0.25, 16.0), (-0.5, 4.0)):
        for qq in (down(q), q, up(q)):
            for mm in (down(mu), mu, up(mu)):
                cases.append((qq, 1e-3, mm))
    # the largest |q| of the domain at a mu where 1/sqrt(mu) is not a double
    rng = np.random.default_rng(5)
    for mu in (2.28, 3.0, 0.7, *rng.uniform(0.5, 6.0, 20)):
        b = 1.0 / math.sqrt(mu)
        for qq in (down(down(b)), down(b), b, up(b), up(up(b))):
            cases.append((qq, 1e-3, float(mu)))
    # sigma = 2 (1 - mu q^2) exactly (2 A_G a double), and one ulp either side
    for q, mu in ((0.5, 2.0), (0.25, 4.0), (0.0, 2.28), (0.5, 1.0)):
        s = 2.0 * float(1 - Fraction(mu) * Fraction(q) ** 2)
        assert Fraction(s) == 2 * (1 - Fraction(mu) * Fraction(q) ** 2)
        for ss in (down(s), s, up(s)):
            cases.append((q, ss, mu))
    # sigma at the exact bound rounded down (sigma_max) and the next doubles, random q, mu
    mus = rng.uniform(0.5, 6.0, 40)
    qs = rng.uniform(-0.99, 0.99, 40) / np.sqrt(mus)
    for q, mu in zip(qs, mus):
        s = float(sigma_max(float(q), float(mu)))
        for ss in (down(s), s, up(s), up(up(s))):
            cases.append((float(q), ss, float(mu)))
    return cases


CASES = boundary_cases()


def test_quick_decision_is_exact_on_the_bounds():
    """Quick == exact == fractions on every boundary case, and both verdicts occur."""
    verdicts = set()
    for q, sigma, mu in CASES:
        want = exact_inside(q, sigma, mu)
        quick = inside_domain(domain_sides_quick(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES)
        slow = inside_domain(domain_sides(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES)
        assert quick == slow == want, (q, sigma, mu)
        verdicts.add(want)
    assert verdicts == {True, False}


def test_compiled_kernel_domain_test_is_exact_on_the_bounds():
    """The compiled loop (the quick decision compiled into it) agrees with fractions."""
    q, sigma, mu = (np.array(c) for c in zip(*CASES))
    n = len(q)
    code = sliding_domain(q, np.full(n, 0.1), sigma, np.full(n, 0.5), mu, engine="compiled")
    want = np.array([exact_inside(*c) for c in CASES])
    np.testing.assert_array_equal(code == 0, want)


def test_plain_comparison_band_and_far_points():
    """Points whose plain margins fall inside and outside the thresholds (both branches of the
    quick decision), and random points over a wide range, against fractions."""
    rng = np.random.default_rng(11)
    pts = []
    for _ in range(300):
        mu = float(rng.uniform(0.1, 10.0))
        b = 1.0 / math.sqrt(mu)
        q = b * (1.0 + float(rng.integers(-8, 9)) * 2.0**-52)  # within a few ulp of the q bound
        pts.append((q, 1e-3, mu))
        q = float(rng.uniform(-1.2, 1.2)) * b
        a_g = float(1 - Fraction(mu) * Fraction(q) ** 2)
        s = 2.0 * a_g * (1.0 + float(rng.integers(-8, 9)) * 2.0**-52) if a_g > 0 else float(rng.uniform(0, 2))
        pts.append((q, s, mu))  # within a few ulp of the sigma bound
        pts.append((q, float(rng.uniform(-0.5, 2.5)), mu))
    for q, sigma, mu in pts:
        want = exact_inside(q, sigma, mu)
        assert inside_domain(domain_sides_quick(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES) == want, (q, sigma, mu)
    q, sigma, mu = (np.array(c) for c in zip(*pts))
    n = len(q)
    code = sliding_domain(q, np.full(n, 0.1), sigma, np.full(n, 0.5), mu, engine="compiled")
    np.testing.assert_array_equal(code == 0, [exact_inside(*c) for c in pts])


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_quick_decision_refuses_what_the_exact_one_refuses(bad):
    """NaN and inf in q, sigma or mu fail the quick test as they fail the exact one."""
    for args in ((bad, 0.5, 2.28), (0.1, bad, 2.28), (0.1, 0.5, bad)):
        q, sigma, mu = args
        quick = inside_domain(domain_sides_quick(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES)
        slow = inside_domain(domain_sides(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES)
        assert quick == slow is False
