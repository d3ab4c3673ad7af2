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

from stability.linear.kernel import checked_model_spectrum, model_domain
from stability.parameters import (
    COMPUTABLE_MAX,
    domain_applies,
    domain_clearly_inside,
    domain_sides,
    domain_sides_quick,
    inside_domain,
    sigma_max,
)

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
    code = model_domain(
        "sliding", dict(q=q, fr_inv=np.full(n, 0.1), sigma=sigma, alpha_v=np.full(n, 0.5), mu=mu), engine="compiled"
    )
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
    code = model_domain(
        "sliding", dict(q=q, fr_inv=np.full(n, 0.1), sigma=sigma, alpha_v=np.full(n, 0.5), mu=mu), engine="compiled"
    )
    np.testing.assert_array_equal(code == 0, [exact_inside(*c) for c in pts])


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_quick_decision_refuses_what_the_exact_one_refuses(bad):
    """NaN and inf in q, sigma or mu fail the quick test as they fail the exact one."""
    for args in ((bad, 0.5, 2.28), (0.1, bad, 2.28), (0.1, 0.5, bad)):
        q, sigma, mu = args
        quick = inside_domain(domain_sides_quick(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES)
        slow = inside_domain(domain_sides(q, 0.1, sigma, 0.5, mu, 0.0), APPLIES)
        assert quick == slow is False


# --- the packed first pass of the fused loop (domain_clearly_inside) ----------------------------


def exact_code(q: float, fr_inv: float, sigma: float, alpha_v: float, mu: float) -> int:
    """The fused loop's code in rationals: 2 outside the computable range (NaN, inf,
    ``|x| > 1e30``, ``0 < mu < 1e-30``), 1 outside the physical domain, 0 inside."""
    values = (q, fr_inv, sigma, alpha_v, mu)
    if not all(math.isfinite(x) and abs(x) <= COMPUTABLE_MAX for x in values) or 0 < mu < 1e-30:
        return 2
    return 0 if fr_inv >= 0 and alpha_v >= 0 and exact_inside(q, sigma, mu) else 1


def near_every_bound() -> list[tuple[float, float, float, float, float]]:
    """The A_G cases above, each also with fr_inv, alpha_v, mu and sigma moved to within a few
    ulp of their sign bounds (0, the smallest subnormals either side, -0.0), and points in the
    band ``(1 - 8u, 1 + 8u)`` of the plain ``mu q^2`` and ``sigma/2 + mu q^2`` where the first
    pass must leave the decision to the exact test."""
    tiny = 5e-324
    signs = (-2 * tiny, -tiny, -0.0, 0.0, tiny, 2 * tiny, 2.2250738585072014e-308)
    pts = [(q, 0.1, sigma, 0.5, mu) for q, sigma, mu in CASES]
    for x in signs:
        pts += [(0.3, x, 0.5, 0.5, 2.28), (0.3, 0.1, 0.5, x, 2.28), (0.3, 0.1, x, 0.5, 2.28), (0.3, 0.1, 0.5, 0.5, x)]
    pts += [(0.3, 0.1, 0.5, 0.5, m) for m in (down(1e-30), 1e-30, up(1e-30), down(1e30), 1e30, up(1e30))]
    rng = np.random.default_rng(17)
    for _ in range(200):
        mu = float(rng.uniform(0.1, 10.0))
        q = math.sqrt((1.0 + float(rng.integers(-12, 13)) * 2.0**-53) / mu)  # mu q^2 within ~12u of 1
        pts.append((q, 0.1, 1e-3, 0.5, mu))
        q = float(rng.uniform(-0.9, 0.9)) / math.sqrt(mu)
        a_g = 1.0 - mu * q * q
        pts.append((q, 0.1, 2.0 * a_g * (1.0 + float(rng.integers(-12, 13)) * 2.0**-53), 0.5, mu))
    return pts


NEAR = near_every_bound()


def test_first_pass_calls_inside_only_what_is_inside():
    """:func:`domain_clearly_inside` (interpreted, the same operations as compiled) is true only
    where the rational rule is inside; it decides the far points and leaves the band to the exact
    test. Reference: :mod:`fractions` on the doubles given, no rounding at all, so independent of
    both the plain comparisons with their 4u margin and the two_product expansions of the exact
    test; a decision is a yes or no, so there is no tolerance. (The computable range is the
    kernel's own refusal, tested with the fused loop below.)"""
    clear_count = 0
    for q, fr_inv, sigma, alpha_v, mu in NEAR:
        clear = domain_clearly_inside(q, fr_inv, sigma, alpha_v, mu, 0.0, APPLIES)
        if clear:
            assert exact_inside(q, sigma, mu) and fr_inv >= 0 and alpha_v >= 0, (q, fr_inv, sigma, alpha_v, mu)
        clear_count += bool(clear)
    assert 0 < clear_count < len(NEAR)  # both answers occur near the bounds
    rng = np.random.default_rng(19)
    mu = rng.uniform(0.5, 6.0, 500)
    q = rng.uniform(-0.9, 0.9, 500) / np.sqrt(mu)
    sigma = (1.0 - mu * q * q) * rng.uniform(0.1, 1.9, 500)
    far = [
        bool(domain_clearly_inside(*p, 0.0, APPLIES)) for p in zip(q, np.full(500, 0.1), sigma, np.full(500, 0.5), mu)
    ]
    assert all(far)  # far from every bound the first pass decides alone


@pytest.mark.parametrize("parallel", [False, True])
def test_fused_loop_codes_are_exact_near_every_bound(parallel):
    """The compiled fused loop (first pass packed over blocks of 256 points, the exact test for
    the points it leaves) gives the rational rule's inside mask and count of refused points on
    the points near every bound, shuffled among far points so that every block mixes both.
    Reference: :func:`exact_code` in :mod:`fractions`, independent as above."""
    rng = np.random.default_rng(23)
    mu = rng.uniform(0.5, 6.0, 3000)
    q = rng.uniform(-0.9, 0.9, 3000) / np.sqrt(mu)
    far = list(zip(q, np.full(3000, 0.1), (1.0 - mu * q * q) * rng.uniform(0.1, 1.9, 3000), np.full(3000, 0.5), mu))
    pts = [tuple(float(x) for x in p) for p in far] + NEAR
    pts = [pts[k] for k in rng.permutation(len(pts))]
    want = np.array([exact_code(*p) for p in pts])
    arrays = [np.array(c) for c in zip(*pts)]
    got = checked_model_spectrum(
        "sliding", dict(zip(("q", "fr_inv", "sigma", "alpha_v", "mu"), arrays)), engine="compiled", parallel=parallel
    )
    np.testing.assert_array_equal(got.inside, want == 0)
    assert got.n_not_finite == int(np.sum(want == 2))
    assert got.n_outside == int(np.sum(want != 0))
