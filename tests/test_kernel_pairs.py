"""The kernel's model loops solve their points in blocks (``stability.linear.kernel.BLOCK``
points, structure of arrays, ``_block_solve``), and a point that leaves the generic cubic is
solved again point by point: every point must still get its own roots, whatever its neighbours
in the block are (outside the domain, a structural zero, widely separated scales, the partial
block at the end), and the same bits as the point-by-point path.

Reference: the eigenvalues of ``M^-1 A`` of eq. (11) by mpmath at 50 digits
(``conftest.mp_sliding_eigenvalues``, the matrices typed from the paper). Tolerance: 1e-13
relative to the root, as tests/test_kernel.py asks of well-conditioned roots (these random
points are), or the kernel's own stated error bound where that is larger; a structural zero
(``fr_inv = 0``) must be exactly 0 with bound 0; a point outside the domain NaN with flag -1.
The bits: the interpreted execution, which solves every point by the point-by-point path
(``kernel._solve``, with its branches), against the compiled blocks, serial and parallel.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from conftest import mp_sliding_eigenvalues, random_domain_points

import stability
from stability.linear import kernel
from stability.parameters import sigma_max

NAMES = ("q", "fr_inv", "sigma", "alpha_v", "mu")
RTOL = 1e-13


def _mixed(n: int) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """``n`` random domain points; every third one moved outside the domain (``q`` with
    ``mu q^2 > 1``), every fourth given ``fr_inv = 0`` (a structural zero root)."""
    p = random_domain_points(n, seed=40 + n)
    inside = np.ones(n, dtype=bool)
    inside[1::3] = False
    p["q"][~inside] = 2.0 / np.sqrt(p["mu"][~inside])
    p["fr_inv"][::4] = 0.0
    return p, inside


def _check(p: dict[str, np.ndarray], inside: np.ndarray, ev: np.ndarray, bd: np.ndarray, st: np.ndarray) -> None:
    for j in range(inside.size):
        if not inside[j]:
            assert st[j] == -1 and np.isnan(ev[j]).all(), j
            continue
        left = list(range(ev.shape[1]))
        for r in mp_sliding_eigenvalues(*(p[k][j] for k in NAMES)):
            d = [float(abs(mp.mpc(complex(ev[j, k])) - r)) for k in left]
            k = left.pop(int(np.argmin(d)))
            if abs(r) < mp.mpf(10) ** -40:  # the structural zero (mpmath: ~1e-50)
                assert ev[j, k] == 0 and bd[j, k] == 0, (j, ev[j])
                continue
            err = float(abs(mp.mpc(complex(ev[j, k])) - r))
            assert err <= max(RTOL * float(abs(r)), bd[j, k]), (j, k, err, bd[j, k])


@pytest.mark.parametrize("engine", ["python", "compiled"])
@pytest.mark.parametrize("n", [1, 2, 3, 7])
def test_pairs_with_outside_and_structural_neighbours(n, engine):
    """The fused path (domain test in the loop) and the masked path, odd and even counts."""
    p, inside = _mixed(n)
    checked = kernel.checked_model_spectrum("sliding", p, engine=engine, parallel=False)
    np.testing.assert_array_equal(checked.inside, inside)
    _check(p, inside, *checked.spectrum[:2], checked.spectrum.stability)
    masked = kernel.model_spectrum("sliding", p, inside, engine=engine, parallel=False)
    _check(p, inside, masked.eigenvalues, masked.error_bound, masked.stability)


def test_parallel_pairs_odd_count():
    """The parallel loop on an odd count above the serial threshold (pairs split among the
    threads, the last point paired with itself): the public path, against mpmath on a subset
    that includes the last point."""
    n = kernel.SERIAL_BELOW + 13
    p, inside = _mixed(n)
    sp = stability.spectrum("sliding", mask_unphysical=True, **p)
    pick = np.r_[0:9, n - 9 : n]
    sub = {k: p[k][pick] for k in NAMES}
    _check(sub, inside[pick], sp.eigenvalues[pick], sp.error_bound[pick], sp.stability[pick])


def _blocks_sample() -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Two blocks and a partial third of random domain points, with every kind of point that
    leaves the blocks' generic cubic scattered among them: structural zeros (``fr_inv = 0``,
    ``q = 0``), widely separated scales (``fr_inv``, ``alpha_v`` tiny: a root ~1e-9 of the
    others), points outside the domain; and the ``sigma`` bound itself."""
    n = 2 * kernel.BLOCK + 37
    p, inside = _mixed(n)
    p["fr_inv"][5::11] = 1e-9
    p["alpha_v"][7::13] = 1e-10
    p["q"][9::17] = 0.0
    inside[9::17] = True  # q = 0 is inside
    bound = np.arange(3, n, 19)
    bound = bound[inside[bound]]
    p["sigma"][bound] = sigma_max(p["q"][bound], p["mu"][bound])
    return p, inside


@pytest.mark.parametrize("polish", [0, 1, 3])
def test_blocks_give_the_point_by_point_bits(polish):
    """Compiled blocks (serial and parallel) against the interpreted point-by-point path, bit for
    bit, on both model loops (fused domain test, and masked); no sweep, one sweep with no second
    allowed, and the default."""
    p, inside = _blocks_sample()
    ref = kernel.checked_model_spectrum("sliding", p, engine="python", polish=polish)
    np.testing.assert_array_equal(ref.inside, inside)
    for parallel in (False, True):
        got = kernel.checked_model_spectrum("sliding", p, engine="compiled", parallel=parallel, polish=polish)
        masked = kernel.model_spectrum("sliding", p, inside, engine="compiled", parallel=parallel, polish=polish)
        for out in (got.spectrum, masked):
            for a, b in zip(ref.spectrum, out):
                assert a.shape == b.shape and a.tobytes() == b.tobytes()


def test_blocks_rare_points_against_mpmath():
    """The points that leave the generic cubic, and their neighbours, against mpmath."""
    p, inside = _blocks_sample()
    sp = kernel.checked_model_spectrum("sliding", p, engine="compiled", parallel=False).spectrum
    pick = np.unique(np.r_[0:12, 3:200:19, 5:200:11, 7:200:13, 9:200:17, len(inside) - 5 : len(inside)])
    sub = {k: p[k][pick] for k in NAMES}
    _check(sub, inside[pick], sp.eigenvalues[pick], sp.error_bound[pick], sp.stability[pick])
