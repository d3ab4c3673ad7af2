"""python-control forms of the operators against the complex operator.

Reference: the eigenvalues of the complex operator computed by mpmath (50 digits) from the
matrices of eq. (11) typed in the test module test_spectra_reference; the real form must have
exactly those and their conjugates (a real 6-dim system packs two real components per complex
state). Tolerance 1e-10 relative to the largest root: python-control computes poles with
LAPACK on the 6x6 real matrix, accurate to ~u ||A|| in absolute terms.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import mp_sliding_eigenvalues

import stability


def _same_set(a, b, tol):
    a, b = list(a), list(b)
    assert len(a) == len(b)
    for x in a:
        k = int(np.argmin([abs(x - y) for y in b]))
        assert abs(x - b[k]) <= tol, (x, b[k])
        b.pop(k)


POINTS = [
    (-0.1, 0.3, 1.0, 0.5, 2.28),
    (0.2, 1.0, 0.8, 2.0, 2.28),
    (-0.3, 0.0, 1.1, 0.05, 3.0),
    (0.35, 2.5, 0.3, 5.0, 1.5),
]


@pytest.mark.parametrize("q,fr_inv,sigma,alpha_v,mu", POINTS)
def test_real_state_space_and_friction_loop(q, fr_inv, sigma, alpha_v, mu):
    ref = [complex(r) for r in mp_sliding_eigenvalues(q, fr_inv, sigma, alpha_v, mu)]
    expected = ref + [np.conj(r) for r in ref]
    tol = 1e-10 * max(1.0, max(abs(r) for r in ref))
    sys = stability.state_space("sliding", q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu)
    assert sys.nstates == 6
    _same_set(sys.poles(), expected, tol)
    plant, gain, closed = stability.friction_loop(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu)
    assert plant.ninputs == 2 and plant.noutputs == 2
    assert np.array_equal(gain, alpha_v * np.eye(2))
    _same_set(closed.poles(), expected, tol)


def test_plant_is_the_frictionless_top():
    """Open loop = alpha_v = 0: poles 0 (twice, with its conjugate) and the free-top quadratic
    ``A_G s^2 - i sigma s - mu q fr_inv`` and conjugates (derivation in test_spectra_reference)."""
    q, F, sg, mu = -0.1, 0.3, 1.0, 2.28
    plant, _, _ = stability.friction_loop(q=q, fr_inv=F, sigma=sg, alpha_v=0.7, mu=mu)
    a_g = 1 - mu * q * q
    quad = list(np.roots([a_g, -1j * sg, -mu * q * F]))
    expected = [0, 0] + quad + [np.conj(r) for r in quad]
    _same_set(plant.poles(), expected, 1e-7)  # the double zero is defective-free but LAPACK-limited


@pytest.mark.parametrize("model", ["fixed_pivot", "rolling_eq8"])
def test_second_order_state_space(model):
    q, F, sg, mu = 0.2, 0.7, 0.9, 2.28
    a_c = 1 + mu * (1 + 2 * q)
    h = 1 + q if model == "fixed_pivot" else q
    quad = list(np.roots([a_c, -1j * sg, -mu * F * h]))  # eq. (8) times A_C, in s = i (lambda + 1)
    sys = stability.state_space(model, q=q, fr_inv=F, sigma=sg, mu=mu)
    _same_set(sys.poles(), quad + [np.conj(r) for r in quad], 1e-12)


def test_state_space_refuses_arrays():
    with pytest.raises(TypeError, match=r"^q must be a single number here, got an array of shape \(2,\)"):
        stability.state_space("rolling_eq8", q=[0.1, 0.2], fr_inv=0.3, sigma=1.0)
