"""First-principles linearisations (complex-step Jacobians of the nonlinear models) against
the linear operators, and the compiled right-hand sides against the plain-numpy reference.

The two sides are computed independently: the Jacobian differentiates the nonlinear kernels
(stability.nonlinear) at the upright spin; the operators are eq. (11) / eq. (8) as written in
stability.models. Tolerance: both are eigenvalues of well-conditioned 2x2 / 3x3 problems
computed in double precision (the complex step is exact to rounding); for simple roots the
difference is a few ulps times the condition number, so 1e-9 (1 + |s|) leaves a wide margin
except near colliding roots, which the random points avoid (asserted).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from conftest import random_domain_points
from suites import reference

import stability
from stability import jacobian_eigenvalues
from stability.nonlinear import rolling, sliding
from stability.nonlinear.jacobian import transverse_jacobian
from stability.nonlinear.parameters import pack


def _match(a: np.ndarray, b: np.ndarray) -> float:
    """Smallest max-distance over pairings of two small sets of roots."""
    return min(float(np.max(np.abs(a - b[list(p)]))) for p in itertools.permutations(range(b.size)))


def _separation(a: np.ndarray) -> float:
    return min(abs(x - y) for x, y in itertools.combinations(a, 2))


@pytest.mark.parametrize(
    "nonlinear,linear,with_alpha",
    [
        ("sliding", "sliding", True),
        ("fixed_pivot", "fixed_pivot", False),
        ("rolling", "rolling", False),
    ],
)
def test_jacobian_matches_linear_operator(nonlinear, linear, with_alpha):
    pts = random_domain_points(25, seed=4, alpha_v=with_alpha)
    for j in range(25):
        p = {k: float(v[j]) for k, v in pts.items()}
        s_jac = jacobian_eigenvalues(nonlinear, **p)
        s_lin = stability.eigenvalues(linear, **p)
        assert _separation(s_lin) > 1e-4
        assert _match(s_jac, s_lin) < 1e-9 * (1 + np.max(np.abs(s_lin)))


def test_transverse_jacobian_is_complex_linear():
    """Rotational symmetry about K: the real block has the form [[Re A, -Im A], [Im A, Re A]]."""
    for model, extra in (("sliding", {"alpha_v": 0.7}), ("rolling", {}), ("fixed_pivot", {})):
        _, asym = transverse_jacobian(model, dict(q=0.17, fr_inv=1.3, sigma=0.8, **extra))
        assert asym < 1e-14


def test_rolling_jacobian_disagrees_with_eq8_as_printed():
    """Closed form (docs/nonlinear.md): a uniform ball (q = 0, sigma = 1) rolling has the
    first-principles modes s = 0 and s = i (A_C s^2 - i (1 + mu) s = 0 with A_C = 1 + mu),
    whereas eq. (8) as printed gives s = 0 and s = i / (1 + mu)."""
    mu = 2.28
    s_jac = jacobian_eigenvalues("rolling", q=0.0, fr_inv=0.4, sigma=1.0, mu=mu)
    assert _match(s_jac, np.array([1j, 0.0])) < 1e-14
    s_paper = stability.eigenvalues("rolling_eq8", q=0.0, fr_inv=0.4, sigma=1.0, mu=mu)
    assert _match(s_paper, np.array([1j / (1 + mu), 0.0])) < 1e-14


def test_sliding_polynomial_tends_to_first_principles_rolling():
    """det of eq. (11) divided by alpha_v -> A_C (s^2 - i gamma s - kappa) as alpha_v -> inf;
    the remainder is the alpha_v-free part mu A_G s^3 - i mu sigma s^2 - mu^2 q fr_inv s,
    i.e. exactly O(1/alpha_v)."""
    q, fr_inv, sigma, mu = -0.13, 0.8, 1.1, 2.28
    a_c = 1 + mu * (1 + 2 * q)
    target = np.concatenate(
        [[0.0], a_c * stability.MODELS["rolling"].coefficients(q=q, fr_inv=fr_inv, sigma=sigma, mu=mu)]
    )
    for alpha_v in (1e3, 1e6):
        c = stability.MODELS["sliding"].coefficients(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu) / alpha_v
        rest = np.array([mu * (1 - mu * q * q), -1j * mu * sigma, -mu * mu * q * fr_inv, 0.0])
        np.testing.assert_allclose(c - rest / alpha_v, target, rtol=0, atol=1e-14)


def test_structural_zero_of_sliding_at_zero_fr_inv():
    s = jacobian_eigenvalues("sliding", q=-0.2, fr_inv=0.0, sigma=1.0, alpha_v=0.5)
    assert np.min(np.abs(s)) < 1e-15


def test_first_principles_rolling_contract():
    """matrices and coefficients describe the same polynomial: det(s M - A) at random s."""
    m = stability.MODELS["rolling"]
    pts = random_domain_points(10, seed=9, alpha_v=False)
    M, A = m.matrices(**pts)
    c = m.coefficients(**pts)
    s = np.exp(1j * np.linspace(0, 6, 10)) * 1.7
    det = np.linalg.det(s[:, None, None] * M - A)
    np.testing.assert_allclose(det, c[:, 0] * s**2 + c[:, 1] * s + c[:, 2], rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_compiled_rhs_matches_numpy_reference(seed):
    """The reference eliminates the centre's acceleration first (a 3x3 system) instead of the
    kernels' 6x6 system; agreement to rounding (1e-12 on O(1) states)."""
    rng = np.random.default_rng(seed)
    y = rng.normal(size=10)
    y[3:6] /= np.linalg.norm(y[3:6])
    pr = dict(q=-0.2, fr_inv=0.7, sigma=0.9, mu=2.0, alpha_v=0.3, alpha_k=0.2)
    for law in (0, 1):
        a = sliding.rhs(0.0, y, pack(**pr, law=law))
        b = reference.sliding_rhs(0.0, y, **pr, law=law)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)
    rp = dict(q=0.15, fr_inv=0.7, sigma=0.9, mu=2.0)
    np.testing.assert_allclose(
        rolling.rhs(0.0, y[:8], pack(**rp)), reference.rolling_rhs(0.0, y[:8], **rp), rtol=0, atol=1e-12
    )


def test_jacobian_refuses_bad_input():
    with pytest.raises(TypeError, match="alpha_v"):
        jacobian_eigenvalues("sliding", q=0.0, fr_inv=0.1, sigma=1.0)
    with pytest.raises(TypeError, match="alpha_v"):
        jacobian_eigenvalues("rolling", q=0.0, fr_inv=0.1, sigma=1.0, alpha_v=0.2)
    with pytest.raises(ValueError, match="q = 0.9"):
        jacobian_eigenvalues("fixed_pivot", q=0.9, fr_inv=0.1, sigma=1.0)
    with pytest.raises(ValueError, match="not a nonlinear model"):
        jacobian_eigenvalues("spinning", q=0.0, fr_inv=0.1, sigma=1.0)
