"""Property-based tests (hypothesis) over the physical domain.

Each property is an identity derived independently of the package's root finder:

* trace and determinant: sum and product of the eigenvalues equal ``tr(M^-1 A)`` and
  ``det(A)/det(M)`` computed from the matrices of eq. (11) (LAPACK-free closed forms for 3x3);
* frictionless symmetry: with alpha_v = 0 the sliding operator is Hamiltonian-gyroscopic, so the
  spectrum is closed under ``s -> -conj(s)`` (p(i nu) has real coefficients, docs/models.md);
* real form: the python-control StateSpace has the complex spectrum and its conjugate.

Tolerances: round-off scaled by the size of the terms involved (``1e-12`` relative to the
largest of |s|^k products), since these identities hold exactly in exact arithmetic.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import stability


@st.composite
def sliding_points(draw, alpha_v=True):
    mu = draw(st.floats(0.3, 8.0))
    q = draw(st.floats(-0.97, 0.97)) / np.sqrt(mu)
    sigma = draw(st.floats(0.01, 1.0)) * 2 * (1 - mu * q * q)
    fr_inv = draw(st.floats(0.0, 5.0))
    a = 10 ** draw(st.floats(-3.0, 2.0)) if alpha_v else 0.0
    return dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=a, mu=mu)


def _det3(m):
    return (m[0, 0] * (m[1, 1] * m[2, 2] - m[1, 2] * m[2, 1])
            - m[0, 1] * (m[1, 0] * m[2, 2] - m[1, 2] * m[2, 0])
            + m[0, 2] * (m[1, 0] * m[2, 1] - m[1, 1] * m[2, 0]))


def _perm3(m):
    return (m[0, 0] * (m[1, 1] * m[2, 2] + m[1, 2] * m[2, 1])
            + m[0, 1] * (m[1, 0] * m[2, 2] + m[1, 2] * m[2, 0])
            + m[0, 2] * (m[1, 0] * m[2, 1] + m[1, 1] * m[2, 0]))


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
