"""Property-based tests (hypothesis) over the physical domain.

Each property is an identity derived independently of the package's root finder:

* trace and determinant: sum and product of the eigenvalues equal ``tr(M^-1 A)`` and
  ``det(A)/det(M)`` computed from the matrices of eq. (11) (LAPACK-free closed forms for 3x3);
* frictionless symmetry: with alpha_v = 0 the sliding operator is Hamiltonian-gyroscopic, so the
  spectrum is closed under ``s -> -conj(s)`` (p(i nu) has real coefficients, docs/models.md);
* real form: the python-control StateSpace has the complex spectrum and its conjugate.

* right or flagged over the hard regions (near-singular M, alpha_v 1e-6 .. 1e6, fr_inv up to
  1e3) against mpmath;
* continuity along a parameter: Elsner's perturbation theorem for eigenvalues;
* mirror symmetry: the reflection y -> -y reverses the spin and maps runs of the nonlinear
  sliding model onto runs.

Tolerances: round-off scaled by the size of the terms involved (``1e-12`` relative to the
largest of |s|^k products), since these identities hold exactly in exact arithmetic; each
new test states its own.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import stability
from stability.parameters import sigma_max


@st.composite
def sliding_points(draw, alpha_v=True):
    mu = draw(st.floats(0.3, 8.0))
    q = draw(st.floats(-0.97, 0.97)) / np.sqrt(mu)
    # 2 A_G without cancellation (a naive 1 - mu q^2 is off by ~u / A_G, which can put
    # sigma = 2 A_G an ulp outside the domain check's 8 u allowance)
    sigma = draw(st.floats(0.01, 1.0)) * float(sigma_max(q, mu))  # up to the largest sigma allowed
    fr_inv = draw(st.floats(0.0, 5.0))
    a = 10 ** draw(st.floats(-3.0, 2.0)) if alpha_v else 0.0
    return dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=a, mu=mu)


def _det3(m):
    return (
        m[0, 0] * (m[1, 1] * m[2, 2] - m[1, 2] * m[2, 1])
        - m[0, 1] * (m[1, 0] * m[2, 2] - m[1, 2] * m[2, 0])
        + m[0, 2] * (m[1, 0] * m[2, 1] - m[1, 1] * m[2, 0])
    )


def _perm3(m):
    return (
        m[0, 0] * (m[1, 1] * m[2, 2] + m[1, 2] * m[2, 1])
        + m[0, 1] * (m[1, 0] * m[2, 2] + m[1, 2] * m[2, 0])
        + m[0, 2] * (m[1, 0] * m[2, 1] + m[1, 1] * m[2, 0])
    )


@settings(max_examples=200, deadline=None)
@given(sliding_points())
def test_trace_and_determinant(p):
    s = stability.eigenvalues("sliding", **p)
    M, A = stability.get_model("sliding").matrices(**p)
    # M = [[1,0,a],[0,1,0],[b,0,1]] has the explicit inverse [[1,0,-a],[0,1,0],[-b,0,1]] / (1 - ab)
    a, b = M[0, 2], M[2, 0]
    minv = np.array([[1, 0, -a], [0, (1 - a * b), 0], [-b, 0, 1]]) / (1 - a * b)
    trace = np.trace(minv @ A)
    scale = np.abs(s).sum()
    assert abs(s.sum() - trace) <= 1e-12 * max(scale, 1e-300) + 1e-300
    det = _det3(A) / _det3(M)
    # the reference's own round-off: u times the sum of |terms| of the cofactor expansion
    terms = _perm3(np.abs(A)) / abs(_det3(M))
    assert abs(np.prod(s) - det) <= 1e-12 * abs(det) + 32 * 2.0**-53 * terms


@settings(max_examples=200, deadline=None)
@given(sliding_points(alpha_v=False))
def test_frictionless_spectrum_symmetric(p):
    s = stability.eigenvalues("sliding", **p)
    mirrored = -np.conj(s)
    scale = np.abs(s).max()
    for x in mirrored:
        assert np.min(np.abs(s - x)) <= 1e-9 * scale + 1e-300


@settings(max_examples=50, deadline=None)
@given(sliding_points())
def test_real_form_has_spectrum_and_conjugate(p):
    s = stability.eigenvalues("sliding", **p)
    poles = list(stability.state_space("sliding", **p).poles())
    scale = max(np.abs(s).max(), 1.0)
    for x in list(s) + list(np.conj(s)):
        k = int(np.argmin([abs(x - y) for y in poles]))
        assert abs(poles[k] - x) <= 1e-9 * scale
        poles.pop(k)


# --- hard regions, mirror symmetry, continuity (issue 7) ----------------------------------------


@st.composite
def hard_points(draw):
    """The physical domain with its hard corners weighted in: A_G down to 1e-12, alpha_v from
    1e-6 to 1e6, fr_inv from 1e-6 to 1e3, sigma down to 1e-6 of its range."""
    mu = draw(st.floats(0.3, 8.0))
    edge = draw(st.floats(-12.0, 0.0))
    q = draw(st.sampled_from([-1.0, 1.0])) * np.sqrt((1 - 10**edge * 0.999) / mu)
    # up to the largest sigma allowed, sigma_max (the exact bound 2 A_G rounded down)
    sigma = 10 ** draw(st.floats(-6.0, 0.0)) * float(sigma_max(q, mu))
    fr_inv = 10 ** draw(st.floats(-6.0, 3.0))
    a = 10 ** draw(st.floats(-6.0, 6.0))
    return dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=a, mu=mu)


@settings(max_examples=40, deadline=None)
@given(hard_points(), st.sampled_from(["kernel", "polynomial"]))
def test_right_or_flagged_over_hard_regions(p, method):
    """Against mpmath (60 digits, test_hard_spectra._poly_reference): each eigenvalue within
    its error bound, each sign right unless flagged neutral, the verdict right unless
    marginal. (LAPACK is not held to this: docs/hard_cases.md.)"""
    from test_hard_spectra import _poly_reference, assert_right_or_flagged

    sp = stability.spectrum("sliding", method=method, **p)
    assert_right_or_flagged(sp, _poly_reference(**p))


@settings(max_examples=60, deadline=None)
@given(sliding_points(), st.sampled_from(["q", "fr_inv", "sigma", "alpha_v", "mu"]), st.floats(-9.0, -3.0))
def test_spectrum_continuous_along_a_parameter(p, name, log_h):
    """Elsner's theorem (Bhatia, Matrix Analysis, VIII.1): the optimal matching distance of
    the spectra of n x n matrices B and B' is at most
    ``4 * 2^(-1/n) (||B|| + ||B'||)^(1 - 1/n) ||B - B'||^(1/n)``, whatever their defectiveness.
    B = M^-1 A of eq. (11) (explicit 3x3 inverse, as above) at p and at p with one parameter
    moved by a relative 10^log_h (inside the domain). A jump between branches, or a root lost
    by the root finder, would break it."""
    from itertools import permutations

    p2 = dict(p)
    p2[name] = p[name] * (1 + 10**log_h) if p[name] != 0 else 10**log_h
    if name in ("q", "mu", "sigma") and not (
        p2["mu"] * p2["q"] ** 2 < 1 and p2["sigma"] <= 2 * (1 - p2["mu"] * p2["q"] ** 2)
    ):
        p2[name] = p[name] * (1 - 10**log_h)
    mats = []
    for pp in (p, p2):
        M, A = stability.get_model("sliding").matrices(**pp)
        a, b = M[0, 2], M[2, 0]
        minv = np.array([[1, 0, -a], [0, (1 - a * b), 0], [-b, 0, 1]]) / (1 - a * b)
        mats.append(minv @ A)
    s1 = stability.eigenvalues("sliding", **p)
    s2 = stability.eigenvalues("sliding", **p2)
    n1, n2 = np.linalg.norm(mats[0], 2), np.linalg.norm(mats[1], 2)
    elsner = 4 * 2 ** (-1 / 3) * (n1 + n2) ** (2 / 3) * np.linalg.norm(mats[0] - mats[1], 2) ** (1 / 3)
    slack = 1e-12 * (n1 + n2)  # the two spectra's own round-off
    best = min(np.max(np.abs(s1 - s2[list(perm)])) for perm in permutations(range(3)))
    assert best <= elsner + slack


@st.composite
def nonlinear_points(draw):
    mu = draw(st.floats(0.5, 6.0))
    q = draw(st.floats(-0.9, 0.9)) / np.sqrt(mu)
    sigma = draw(st.floats(0.1, 1.0)) * float(sigma_max(q, mu))  # up to the largest sigma allowed
    tilt = draw(st.floats(0.05, 1.2))
    az = draw(st.floats(0.0, 2 * np.pi))
    w = [draw(st.floats(-0.2, 0.2)), draw(st.floats(-0.2, 0.2)), draw(st.floats(0.5, 1.5))]
    v = [draw(st.floats(-0.2, 0.2)), draw(st.floats(-0.2, 0.2))]
    return dict(
        q=q,
        sigma=sigma,
        mu=mu,
        fr_inv=draw(st.floats(0.05, 2.0)),
        alpha_v=draw(st.floats(0.0, 2.0)),
        alpha_k=draw(st.sampled_from([0.0, 0.3])),
        friction=draw(st.sampled_from(["isotropic", "componentwise"])),
        omega=w,
        k=[np.sin(tilt) * np.cos(az), np.sin(tilt) * np.sin(az), np.cos(tilt)],
        velocity=v,
    )


@settings(max_examples=15, deadline=None)
@given(nonlinear_points())
def test_mirror_symmetry_spin_reversed(p):
    """Reflection in the vertical plane y = 0 maps solutions to solutions (eqs. 1, 2, 4, 5 and
    both friction laws 7 and 16 are invariant: the component-wise law's axes are x and y).
    Polar vectors (k, V0) map to (x, -y, z), the axial omega to (-x, y, -z): the spin
    omega . k is reversed (the paper's omega3 ~ -1 runs are the mirror images of +1 ones).
    Both runs at rtol 1e-10 over 10 time units: they agree to ~T rtol; allowed 1e-7."""
    kw = {k: p[k] for k in ("q", "sigma", "mu", "fr_inv", "alpha_v", "alpha_k", "friction")}
    w, k, v = (np.array(p[x], float) for x in ("omega", "k", "velocity"))
    pol = np.array([1.0, -1.0, 1.0])
    ax = np.array([-1.0, 1.0, -1.0])
    run = dict(t_end=10.0, dt=0.5, rtol=1e-10, atol=1e-13, method="LSODA" if p["alpha_k"] else "dopri5")
    a = stability.simulate("sliding", omega=w, k=k, velocity=v, **kw, **run)
    b = stability.simulate("sliding", omega=ax * w, k=pol * k, velocity=pol[:2] * v, **kw, **run)
    assert np.max(np.abs(b.k.values - pol * a.k.values)) < 1e-7
    assert np.max(np.abs(b.omega.values - ax * a.omega.values)) < 1e-7
    assert np.max(np.abs(b.spin.values + a.spin.values)) < 1e-7
