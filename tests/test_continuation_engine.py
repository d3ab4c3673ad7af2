"""The continuation engine on problems with exact answers (it knows nothing about tops).

References are closed forms: a circle, the cubic x = y^3 - y with folds at y = +-1/sqrt(3), a
2x2 Hopf normal form whose neutral curve is the unit circle with frequency sqrt(2 + x), and two
crossing lines (a branch point at the origin). Tolerances: points are accepted at
||F|| <= 1e-13, and F is O(1) with O(1) derivatives here, so coordinates are right to about
1e-13; folds and branch points are located by Brent's method to 1e-14 of a step, with a tangent
from an exact Jacobian, so 1e-12 leaves a margin of ten.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest
from trace_snapshot import _hopf_step  # the Hopf problem's compiled step (benchmarks/, on sys.path)

from continuation import ConvergenceError, TraceOptions, project, trace, trace_both


class Circle:
    """x^2 + y^2 = 1 (analytic Jacobian)."""

    def residual(self, u):
        return np.array([u[0] ** 2 + u[1] ** 2 - 1.0])

    def jacobian(self, u):
        return np.array([[2 * u[0], 2 * u[1]]])


class Cubic:
    """x = y^3 - y on |y| <= 2 (no Jacobian: the engine's finite differences)."""

    constraint_names = ("y >= -2", "y <= 2")

    def residual(self, u):
        return np.array([u[0] - (u[1] ** 3 - u[1])])

    def constraints(self, u):
        return np.array([u[1] + 2.0, 2.0 - u[1]])


class HopfNormalForm:
    """Neutral curve of A(x, y) = [[a, -(2 + x)], [1, a]], a = (x^2 + y^2 - 1)/2.

    ``det(s - A) = s^2 - 2 a s + a^2 + 2 + x``; at ``s = i w``: ``Re = -w^2 + a^2 + 2 + x``,
    ``Im = -2 a w``. With ``w > 0``, the neutral curve is ``a = 0`` (the unit circle) with
    ``w = sqrt(2 + x)``.
    """

    def residual(self, u):
        x, y, w = u
        a = (x * x + y * y - 1) / 2
        return np.array([-w * w + a * a + 2 + x, -2 * a * w])

    def jacobian(self, u):
        x, y, w = u
        a = (x * x + y * y - 1) / 2
        return np.array([[2 * a * x + 1, 2 * a * y, -2 * w], [-2 * x * w, -2 * y * w, -2 * a]])


class CrossingLines:
    """x^2 - y^2 = 0: the lines y = x and y = -x cross at the origin (a branch point)."""

    def residual(self, u):
        return np.array([u[0] ** 2 - u[1] ** 2])

    def jacobian(self, u):
        return np.array([[2 * u[0], -2 * u[1]]])


def test_circle_closes_with_four_exact_folds():
    u0 = [np.cos(0.3), np.sin(0.3)]
    br = trace(Circle(), u0, TraceOptions(fold_components=(0, 1), max_angle=0.15, max_step=0.3))
    assert br.closed and br.end_reasons == ["closed"]
    assert np.allclose(br.points[-1], br.points[0], atol=1e-15)
    r = np.hypot(br.points[:, 0], br.points[:, 1])
    assert np.max(np.abs(r - 1)) <= 1e-13
    folds = br.points[[k == "fold" for k in br.kinds]]
    comps = [int(d) for k, d in zip(br.kinds, br.details) if k == "fold"]
    assert sorted(comps) == [0, 0, 1, 1]
    # folds in x at (+-1, 0), in y at (0, +-1)
    for p, c in zip(folds, comps):
        assert abs(p[1 - c]) <= 1e-12 and abs(abs(p[c]) - 1) <= 1e-13
    # angle control: consecutive tangents turn by <= 0.15 rad, so a full turn needs >= 2 pi / 0.15
    n_regular = sum(k in ("regular", "start") for k in br.kinds)
    assert 2 * np.pi / 0.15 <= n_regular <= 3 * 2 * np.pi / 0.15
    assert br.n_residual > 0 and br.n_jacobian > 0


def test_cubic_folds_and_bounds_with_finite_difference_jacobian():
    br = trace_both(Cubic(), [0.0, 0.0], TraceOptions(fold_components=(0,), max_step=0.1))
    ys = br.points[:, 1]
    assert br.end_reasons == ["boundary", "boundary"]
    ends = sorted([ys[0], ys[-1]])
    assert abs(ends[0] + 2) <= 1e-13 and abs(ends[1] - 2) <= 1e-13
    folds = br.points[[k == "fold" for k in br.kinds]]
    assert len(folds) == 2
    y_fold = np.sort(folds[:, 1])
    # closed form: dx/dy = 3 y^2 - 1 = 0 -> y = -+1/sqrt(3), x = +-2/(3 sqrt 3);
    # the tangent comes from a central-difference Jacobian (relative error ~1e-10), so y is
    # located to ~1e-10 and x (extremal there, error quadratic in dy) far better
    assert np.allclose(y_fold, [-1 / np.sqrt(3), 1 / np.sqrt(3)], atol=1e-9)
    x_ref = -(y_fold**3 - y_fold)
    assert np.allclose(-folds[np.argsort(folds[:, 1]), 0], x_ref, atol=1e-13)
    assert np.max(np.abs(br.points[:, 0] - (ys**3 - ys))) <= 1e-13


def test_hopf_normal_form_neutral_curve_is_the_unit_circle():
    prob = HopfNormalForm()
    u0 = project(prob, [1.1, 0.1, 1.6])
    br = trace(prob, u0, TraceOptions(fold_components=(0, 1)))
    assert br.closed
    x, y, w = br.points.T
    assert np.max(np.abs(x * x + y * y - 1)) <= 1e-13
    assert np.max(np.abs(w - np.sqrt(2 + x))) <= 1e-13
    assert sum(k == "fold" for k in br.kinds) == 4


def test_branch_point_of_two_crossing_lines():
    br = trace(CrossingLines(), [-1.0, -1.0], TraceOptions(max_points=200, max_arclength=2.5))
    bp = br.points[[k == "branch_point" for k in br.kinds]]
    assert len(bp) == 1
    # det [J; t] = 2 (x t_2 + y t_1) is linear in arclength through the origin
    assert np.max(np.abs(bp)) <= 1e-12
    # the engine continued on the same line beyond the branch point
    assert np.allclose(br.points[:, 0], br.points[:, 1], atol=1e-12) and br.points[-1, 0] > 0.5


def test_callback_sees_every_point_and_can_stop():
    seen = []

    def cb(u, t, kind):
        seen.append(kind)
        return len(seen) < 5

    br = trace(Circle(), [1.0, 0.0], callback=cb)
    assert br.end_reasons == ["callback"] and len(seen) == 5 and len(br.points) == 5


def test_errors():
    with pytest.raises(ValueError, match="direction"):
        trace(Circle(), [1.0, 0.0], direction=2)
    with pytest.raises(ValueError, match="min_step"):
        trace(Circle(), [1.0, 0.0], TraceOptions(step=1.0, max_step=0.1))
    with pytest.raises(ValueError, match="equations"):
        trace(Circle(), [1.0, 0.0, 0.0])
    with pytest.raises(ConvergenceError):
        project(Circle(), [0.0, 0.0], max_iter=5)
    with pytest.raises(ValueError, match="violates constraint 'y <= 2'"):
        trace(Cubic(), [24.0, 3.0])  # on the curve, outside |y| <= 2


def test_dense_output_of_a_circle_is_fourth_order():
    """Cubic Hermite between points of the unit circle, against the exact circle.

    Reference (derived here): for an arc of angle theta = 2a between points with exact unit
    tangents, the chord-length Hermite curve's midpoint is ``(p0 + p1)/2 + d (t0 - t1)/8`` with
    ``d = 2 sin a``, at radius ``cos a + sin(a)^2 / 2 = 1 - a^4/8 + O(a^6)``: a radial error
    ``theta^4 / 128``. The traced arcs turn by at most ``max_angle``, so the error is bounded by
    ``max_angle^4 / 128`` (plus rounding), and halving ``max_angle`` divides it by about 16.
    """
    from continuation import dense, hermite_samples

    errs = []
    for max_angle in (0.4, 0.2):
        br = trace(Circle(), [1.0, 0.0], TraceOptions(max_angle=max_angle, max_step=1.0, step=0.1))
        assert br.closed
        d = dense(br, 64)
        # the samples include the traced points themselves
        assert np.array_equal(d[::64], br.points)
        r = np.hypot(d[:, 0], d[:, 1])
        err = float(np.max(np.abs(r - 1)))
        assert err <= max_angle**4 / 128 * 1.05 + 1e-15
        errs.append(err)
    assert 12 <= errs[0] / errs[1] <= 20
    # one arc, exact tangents: the midpoint radius is cos a + sin(a)^2 / 2 exactly
    a = 0.3
    p0, p1 = np.array([np.cos(a), -np.sin(a)]), np.array([np.cos(a), np.sin(a)])
    t0, t1 = np.array([np.sin(a), np.cos(a)]), np.array([-np.sin(a), np.cos(a)])
    mid = hermite_samples(np.array([p0, p1]), np.array([t0, t1]), 2)[1]
    assert abs(mid[0] - (np.cos(a) + np.sin(a) ** 2 / 2)) <= 1e-15 and mid[1] == 0


def test_dense_errors():
    from continuation import dense, hermite_samples

    with pytest.raises(ValueError, match="same shape"):
        hermite_samples(np.zeros((3, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="n >= 1"):
        hermite_samples(np.zeros((3, 2)), np.ones((3, 2)), 0)
    with pytest.raises(TypeError, match="Branch"):
        dense([1, 2, 3])


def _bits(x):
    """The bit patterns of a float array (so that NaN and -0.0 compare too)."""
    return np.asarray(x, dtype=float).view(np.uint64)


def _random_systems(rng, m, count):
    """Random m x m systems, with ties in the pivot column, exact zeros of either sign and
    singular matrices among them."""
    for _ in range(count):
        G, b = rng.normal(size=(m, m)), rng.normal(size=m)
        r = rng.random()
        if r < 0.2:
            G[rng.integers(m), rng.integers(m)] = 0.0
        elif r < 0.3:
            G[:, 0] = np.round(G[:, 0])  # ties for the first pivot
        elif r < 0.35:
            G[rng.integers(m)] = 0.0  # singular
        elif r < 0.4:
            G[rng.integers(m), rng.integers(m)] = -0.0
        yield G, b


def _lu_solve_loop(A, x):
    """The elimination of ``continuation.linalg.lu_solve`` coded on nested lists (rows ``A[k]``):
    the tests' second coding of it, the reference of the unrolled and the array codings."""
    m = len(x)
    det = 1.0
    for k in range(m):
        # pivot: the first largest |a_ik|, i >= k
        p = k
        big = abs(A[k][k])
        for i in range(k + 1, m):
            if abs(A[i][k]) > big:
                p = i
                big = abs(A[i][k])
        if big == 0.0 or big != big:
            return False, big
        Ak = A[k]
        if p != k:  # exchange rows k and p (columns < k are no longer read)
            Ap = A[p]
            for j in range(k, m):
                tmp = Ak[j]
                Ak[j] = Ap[j]
                Ap[j] = tmp
            tmp = x[k]
            x[k] = x[p]
            x[p] = tmp
            det = -det
        piv = Ak[k]
        det *= piv
        for i in range(k + 1, m):
            Ai = A[i]
            f = Ai[k] / piv
            if f != 0.0:
                for j in range(k + 1, m):
                    Ai[j] -= f * Ak[j]
                x[i] -= f * x[k]
    for k in range(m - 1, -1, -1):
        Ak = A[k]
        acc = x[k]
        for j in range(k + 1, m):
            acc -= Ak[j] * x[j]
        x[k] = acc / Ak[k]
    return True, det


@functools.cache
def _compiled_bordered_solve():
    from numba import njit

    from continuation import compiled, linalg  # noqa: F401  (compiled registers linalg with numba)

    return njit(lambda J, c, f, r: linalg.bordered_solve(J, c, f, r))


def _solve_det(G, b, compiled=False):
    """``G x = b`` and ``det G`` by ``continuation.linalg.bordered_solve`` with the last row of
    ``G`` as the border (the engine's systems), from Python or compiled: ``(ok, x, det)``."""
    from continuation import linalg

    return (_compiled_bordered_solve() if compiled else linalg.bordered_solve)(G[:-1], G[-1], b[:-1], float(b[-1]))


def test_unrolled_3x3_elimination_is_the_loop():
    """continuation.linalg solves 3 x 3 systems (the engine's most frequent) unrolled, for the
    Python path's speed. Reference: the loop version of the same elimination on nested lists
    (``_lu_solve_loop``, in this file), a second coding of it. They must agree bit for bit (the same
    operations in the same order), on ties in the pivot column, zero multipliers, zeros of
    either sign and singular matrices too; in Python and compiled."""
    from numba import njit

    import continuation.compiled  # noqa: F401  (registers the building blocks with numba)
    from continuation.linalg import _lu_solve3

    loop_compiled = njit(_lu_solve_loop)

    @njit
    def both(G, b):
        A1, x1, A2, x2 = G.copy(), b.copy(), G.copy(), b.copy()
        ok1, d1 = _lu_solve3(A1, x1)
        ok2, d2 = loop_compiled(A2, x2)
        return ok1, d1, x1, ok2, d2, x2

    rng = np.random.default_rng(5)
    n_singular = 0
    for G, b in _random_systems(rng, 3, 2000):
        x1, x2 = b.tolist(), b.tolist()
        ok1, d1 = _lu_solve3(G.tolist(), x1)
        ok2, d2 = _lu_solve_loop(G.tolist(), x2)
        assert ok1 == ok2 and _bits(d1) == _bits(d2)
        n_singular += not ok1
        if ok1:
            assert np.array_equal(_bits(x1), _bits(x2))
        c1, e1, y1, c2, e2, y2 = both(G, b)
        assert (c1, _bits(e1)) == (ok1, _bits(d1)) and (c2, _bits(e2)) == (ok1, _bits(d1))
        if ok1:
            assert np.array_equal(_bits(y1), _bits(x1)) and np.array_equal(_bits(y2), _bits(x1))
    assert n_singular > 50  # the singular cases were exercised


@pytest.mark.parametrize("m", [2, 4, 6])
def test_array_elimination_is_the_loop(m):
    """Compiled code solves on 2-D arrays indexed ``A[i, j]`` (``_lu_solve_array``: numba makes
    a reference-counted view for every row ``A[i]`` the nested-list coding would take). Reference:
    the nested-list loop ``_lu_solve_loop`` (in this file), a second coding of the same elimination. They must
    agree bit for bit (the same operations in the same order), on ties, zero multipliers, zeros
    of either sign and singular matrices: the float loop in Python on lists against the array
    coding in Python and compiled (``solve_dense``, the nonlinear runs' 6 x 6 solve, and the
    compiled ``lu_solve`` inside ``bordered_solve``), and the Python ``bordered_solve`` up to
    PYTHON_LU_MAX (a 2 x 2 system bordered by the identity and solved unrolled); complex systems (a complex-step Jacobian) both
    codings compiled, where the same complex arithmetic runs in both."""
    from numba import njit

    from continuation import linalg
    from continuation.compiled import solve_dense
    from continuation.linalg import _lu_solve_array

    loop_compiled = njit(_lu_solve_loop)

    @njit
    def loop(G, b):
        x = b.copy()
        ok, d = loop_compiled(G.copy(), x)
        return ok, d, x

    rng = np.random.default_rng(11)
    n_singular = 0
    for G, b in _random_systems(rng, m, 1000):
        x1 = b.tolist()
        ok1, d1 = _lu_solve_loop(G.tolist(), x1)
        x2 = b.copy()
        ok2, d2 = _lu_solve_array(G.copy(), x2)
        ok3, x3, d3 = _solve_det(G, b, compiled=True)
        x4 = solve_dense(G.copy(), b.copy())
        assert (ok2, _bits(d2)) == (ok1, _bits(d1)) and (ok3, _bits(d3)) == (ok1, _bits(d1))
        python = [_solve_det(G, b)] if m <= linalg.PYTHON_LU_MAX else []  # m = 2: bordered by the identity
        for ok5, _, d5 in python:
            assert (ok5, _bits(d5)) == (ok1, _bits(d1))
        n_singular += not ok1
        if ok1:
            for x in (x2, x3, x4, *(x5 for _, x5, _ in python)):
                assert np.array_equal(_bits(x), _bits(x1))
        else:
            assert np.isnan(x4).all()
        Gc, bc = G + 1j * rng.standard_normal(G.shape), b - 1j * rng.standard_normal(b.shape)
        okc, dc, xc = loop(Gc, bc)
        yc = solve_dense(Gc.copy(), bc.copy())
        if okc:
            assert np.array_equal(_bits(yc.real), _bits(xc.real)) and np.array_equal(_bits(yc.imag), _bits(xc.imag))
    assert n_singular > 20  # the singular cases were exercised


@pytest.mark.parametrize("m", [2, 3, 4, 5])
def test_small_solves_against_lapack(m):
    """continuation.linalg's solves and determinants, from Python (lists; LAPACK itself above
    PYTHON_LU_MAX = 4) and compiled (continuation.compiled), against LAPACK
    (numpy.linalg.solve and det, another implementation of LU with partial pivoting).
    Tolerances: Gaussian elimination with partial pivoting is backward stable, residual
    ``||G x - b|| <= c m eps ||G|| ||x||`` with a small growth factor (c = 8 is generous at
    these sizes); determinants to 1e-13 relative, a few roundings per pivot over m <= 5 pivots
    of well-conditioned matrices (condition < 1e4, checked). The Python and compiled faces do
    the same operations (up to LAPACK above PYTHON_LU_MAX), so below it they agree bit for
    bit: that is what lets the engine's two paths give the same points."""
    from continuation import linalg

    rng = np.random.default_rng(100 + m)
    eps = np.finfo(float).eps
    for _ in range(200):
        G, b = rng.normal(size=(m, m)), rng.normal(size=m)
        if np.linalg.cond(G) > 1e4:
            continue
        det_ref = np.linalg.det(G)
        for ok, x, d in (_solve_det(G, b), _solve_det(G, b, compiled=True)):
            assert ok
            assert np.linalg.norm(G @ x - b) <= 8 * m * eps * np.linalg.norm(G, 2) * np.linalg.norm(x)
            assert abs(d - det_ref) <= 1e-13 * abs(det_ref)
        J, c, f, r = G[:-1], G[-1], b[:-1], float(b[-1])
        ok, x, d = linalg.bordered_solve(J, c, f, r)
        assert ok and np.linalg.norm(G @ x - b) <= 8 * m * eps * np.linalg.norm(G, 2) * np.linalg.norm(x)
        assert abs(linalg.bordered_det(J, c) - det_ref) <= 1e-13 * abs(det_ref)
        if m <= linalg.PYTHON_LU_MAX:
            okc, xc, dc = _solve_det(G, b, compiled=True)
            assert np.array_equal(_bits(xc), _bits(_solve_det(G, b)[1]))
            assert _bits(dc) == _bits(_solve_det(G, b)[2]) == _bits(d)
            assert np.array_equal(_bits(x), _bits(xc))
    # an exactly singular matrix: no solution, determinant 0.0
    S = np.ones((m, m))
    assert not _solve_det(S, np.ones(m))[0] and not _solve_det(S, np.ones(m), compiled=True)[0]
    assert linalg.bordered_det(S[:-1], S[-1]) == 0.0


@pytest.mark.parametrize("m", [1, 2, 3, 4])
def test_bordered_solve_of_integer_and_extreme_input(m):
    """The Python face of bordered_solve at every size it eliminates itself: an integer or
    float32 system is solved in float64 (reference: numpy.linalg.solve of the float64 system,
    to the backward-error bound of test_small_solves_against_lapack), a 1 x 1 one too, and
    entries near the overflow threshold give the numbers of the tests' own coding on Python
    floats (_lu_solve_loop: IEEE's inf, silently), with no RuntimeWarning (one would become an
    error under -W error)."""
    import warnings

    from continuation import linalg

    G = np.array([[2, 1, 0, 0], [1, 3, 1, 0], [0, 1, 4, 1], [0, 0, 1, 5]])[:m, :m] + np.eye(m, dtype=int)
    b = np.arange(1, m + 1)
    ref = np.linalg.solve(G.astype(float), b.astype(float))
    eps = np.finfo(float).eps
    for dtype in (int, np.float32):
        ok, x, d = linalg.bordered_solve(G[:-1].astype(dtype), G[-1].astype(dtype), b[:-1].astype(dtype), float(b[-1]))
        assert ok and x.dtype == np.float64
        assert np.linalg.norm(G @ x - b) <= 8 * m * eps * np.linalg.norm(G, 2) * np.linalg.norm(ref)
        assert abs(d - np.linalg.det(G.astype(float))) <= 1e-13 * abs(np.linalg.det(G.astype(float)))
    if m >= 2:
        H = 1e200 * np.eye(m)  # the product of the pivots, det = 1e200^m, overflows
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            ok, x, d = linalg.bordered_solve(H[:-1], H[-1], np.ones(m - 1), 1.0)
        y = [1.0] * m
        ok_ref, d_ref = _lu_solve_loop(H.tolist(), y)
        assert ok and ok_ref and _bits(d) == _bits(d_ref) and np.isinf(d)
        assert np.array_equal(_bits(x), _bits(y)) and (x == 1e-200).all()


def test_bordered_tangent_and_branch_point_test():
    """continuation.linalg.tangent_det against its definition: ``J t = 0`` (to rounding, ``m
    eps ||J||``), ``|t| = 1``, ``t . t_ref > 0``, and ``det [J; t^T]`` against LAPACK's
    determinant of the bordered matrix (1e-12 relative: the test comes from the pivots of the
    solve with ``t_ref`` and the norm of the solution, a few more roundings than a plain
    determinant). Compiled and Python agree to rounding (1e-14: the norm is a BLAS dot product
    in Python, a loop compiled). With ``t_ref`` orthogonal to the null space the bordered
    matrix is singular: ``ok`` is False, and the engine takes the tangent from the SVD."""
    from continuation import compiled, linalg
    from continuation.engine import _tangent_det

    rng = np.random.default_rng(11)
    eps = np.finfo(float).eps
    for m in (2, 3, 4, 5):
        for _ in range(50):
            J, t_ref = rng.normal(size=(m - 1, m)), rng.normal(size=m)
            ok, t, d = linalg.tangent_det(J, t_ref)
            assert ok
            assert np.linalg.norm(J @ t) <= 4 * m * eps * np.linalg.norm(J, 2)
            assert abs(np.linalg.norm(t) - 1) <= 4 * eps and t @ t_ref > 0
            ref = np.linalg.det(np.vstack([J, t]))
            assert abs(d - ref) <= 1e-12 * abs(ref)
            okc, tc, dc = compiled.tangent_det(J, t_ref)
            assert okc and np.max(np.abs(tc - t)) <= 1e-14 and abs(dc - d) <= 1e-13 * abs(d)
    J = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])  # null vector e_3
    ok, _, _ = linalg.tangent_det(J, np.array([1.0, 0.0, 0.0]))
    assert not ok and not compiled.tangent_det(J, np.array([1.0, 0.0, 0.0]))[0]
    t, d = _tangent_det(J, np.array([1.0, 0.0, 0.0]))  # the SVD fallback
    assert np.allclose(np.abs(t), [0, 0, 1], atol=0) and abs(d) == 1.0


def test_hermite_predictor_on_a_line_and_a_circle():
    """The cubic Hermite curve (continuation.interpolation), Python and compiled. References:
    on a straight line with its own direction as tangents the chord-length Hermite curve is the
    line, ``H(tau) = p0 + tau (p1 - p0)`` (``h01 + h10 + h11 = tau``), so the predictor
    extrapolates exactly, to ``v + h e`` (to rounding, 4 eps of the coordinates); on the unit
    circle (arc 2a, exact tangents) the midpoint lies at radius ``cos a + sin(a)^2 / 2``
    (tests above). Without the last step, or after a rejected one, the predictor is the
    tangent ``v + h t`` exactly. Compiled and Python agree to rounding (their norms are
    summed differently)."""
    from continuation import compiled
    from continuation.interpolation import hermite, predict

    rng = np.random.default_rng(2)
    eps = np.finfo(float).eps
    for _ in range(20):
        p0, e = rng.normal(size=3), rng.normal(size=3)
        e /= np.linalg.norm(e)
        d, h = rng.uniform(0.1, 1.0), rng.uniform(0.01, 0.5)
        p1 = p0 + d * e
        for P in (predict, compiled.predict):
            guess = P(p1, e, p0, e, True, h)
            assert np.max(np.abs(guess - (p1 + h * e))) <= 8 * eps * (1 + np.max(np.abs(p1)))
            assert np.array_equal(P(p1, e, p0, e, False, h), p1 + h * e)
        taus = np.array([0.0, 0.25, 0.5, 1.0, 1.5])
        line = hermite(p0, e, p1, e, taus)
        assert np.max(np.abs(line - (p0 + np.outer(taus, p1 - p0)))) <= 8 * eps * (1 + np.max(np.abs(p1)))
        t0, t1 = rng.normal(size=3), rng.normal(size=3)
        assert np.max(np.abs(compiled.predict(p1, t1, p0, t0, True, h) - predict(p1, t1, p0, t0, True, h))) <= 1e-14
    a = 0.3
    p0, p1 = np.array([np.cos(a), -np.sin(a)]), np.array([np.cos(a), np.sin(a)])
    t0, t1 = np.array([np.sin(a), np.cos(a)]), np.array([-np.sin(a), np.cos(a)])
    mid = hermite(p0, t0, p1, t1, 0.5)
    assert abs(mid[0] - (np.cos(a) + np.sin(a) ** 2 / 2)) <= 1e-15 and abs(mid[1]) <= 1e-16


def test_solve_dense_complex_step_and_singular():
    """continuation.compiled.solve_dense, the nonlinear models' compiled 6 x 6 solve, in float
    and complex. References: LAPACK (backward error as above); the complex-step derivative of
    ``x(s) = G(s)^-1 b`` through it against the closed form ``x' = -G^-1 G' x`` (the pivot
    choice uses ``abs`` and an imaginary part of 1e-30 does not change it, so the step is exact
    to rounding: 1e-12 relative for these condition numbers < 1e4). A singular matrix gives
    NaN (an integrator then rejects the step) rather than an exception or a silent number."""
    from continuation.compiled import solve_dense

    rng = np.random.default_rng(3)
    eps = np.finfo(float).eps
    for _ in range(50):
        G, dG, b = rng.normal(size=(6, 6)), rng.normal(size=(6, 6)), rng.normal(size=6)
        if np.linalg.cond(G) > 1e4:
            continue
        x = solve_dense(G.copy(), b.copy())
        assert np.linalg.norm(G @ x - b) <= 48 * eps * np.linalg.norm(G, 2) * np.linalg.norm(x)
        xc = solve_dense(G + 1e-30j * dG, b.astype(complex))
        deriv = -np.linalg.solve(G, dG @ np.linalg.solve(G, b))
        assert np.max(np.abs(xc.imag / 1e-30 - deriv)) <= 1e-12 * np.max(np.abs(deriv))
        assert np.max(np.abs(xc.real - x)) <= 4 * eps * np.max(np.abs(x))  # the real solve, to rounding
    assert np.isnan(solve_dense(np.ones((6, 6)), np.ones(6))).all()
    assert np.isnan(solve_dense(np.ones((6, 6), complex), np.ones(6, complex))).all()


class HopfWithHook(HopfNormalForm):
    """The Hopf normal form with a ``compiled_step`` hook (continuation.problem): its residual
    compiled (a ``register_jitable`` function) and the engine's corrector and tangent compiled
    (``continuation.compiled.step``): the engine must give the branch of its Python path, and
    count the work the hook reports."""

    calls = 0

    def compiled_step(self, *corrector):
        type(self).calls += 1
        return _hopf_step()(*corrector)


def test_compiled_step_hook_gives_the_python_branch():
    prob = HopfWithHook()
    u0 = project(prob, [1.1, 0.1, 1.6])
    HopfWithHook.calls = 0
    hooked = trace(prob, u0, TraceOptions(fold_components=(0, 1)))
    assert HopfWithHook.calls > len(hooked.points)  # every step, and the fold searches
    python = trace(prob, u0, TraceOptions(fold_components=(0, 1), compiled=False))
    assert hooked.closed and python.closed
    assert hooked.kinds == python.kinds and hooked.points.shape == python.points.shape
    assert np.max(np.abs(hooked.points - python.points)) <= 1e-14
    assert np.max(np.abs(hooked.tangents - python.tangents)) <= 1e-13
    # the work the hook reports is counted as the Python path counts its own
    assert (hooked.n_residual, hooked.n_jacobian) == (python.n_residual, python.n_jacobian)


class LineWithTest:
    """The line y = x / 2 on x <= 2 with the test function x - x_event."""

    test_function_names = ("x - x_event",)
    constraint_names = ("x <= 2",)

    def __init__(self, x_event: float):
        self.x_event = x_event

    def residual(self, u):
        return np.array([u[1] - 0.5 * u[0]])

    def jacobian(self, u):
        return np.array([[-0.5, 1.0]])

    def constraints(self, u):
        return np.array([2.0 - u[0]])

    def test_functions(self, u, t):
        return np.array([u[0] - self.x_event])


def test_special_point_exactly_on_an_accepted_point_is_reported_once():
    """A test function that is exactly 0.0 at an accepted point (no sign change to bracket on
    either step: the product of its values is 0) is reported at that point, once. Reference: a
    first run without the event (its point 3, where the second run's test is x_3 - x_3 = 0.0
    exactly: the engine is deterministic and the test does not steer the steps); before this
    was handled, the event went unreported."""
    first = trace(LineWithTest(10.0), [0.0, 0.0], TraceOptions(max_step=0.3))
    assert "test" not in first.kinds
    x3 = float(first.points[3, 0])
    seen = []
    br = trace(LineWithTest(x3), [0.0, 0.0], TraceOptions(max_step=0.3), callback=lambda u, t, kind: seen.append(kind))
    np.testing.assert_array_equal(br.points, first.points)  # the same steps
    assert br.kinds.count("test") == 1 and br.kinds[3] == "test" and br.details[3] == "x - x_event"
    assert seen.count("test") == 1


def test_the_docs_example_problem():
    """docs/continuation.md's "How to write a problem" example, run as written (the code block
    and its printed output). References, closed forms of ``x^3 - x - lam = 0``: folds in lam at
    ``x = -+1/sqrt(3)``, ``lam = +-2/(3 sqrt 3)``; the test function x changes sign at the
    origin; the branch ends at ``x = -+1.5``, ``lam = -+1.875``. Tolerances: as the other tests
    of this module (1e-13 for coordinates; a fold's x, off by about the tangent's rounding over
    the curvature, 1e-12); the printed output matches to its 12 decimals."""
    import contextlib
    import io

    text = (Path(__file__).resolve().parents[1] / "docs" / "continuation.md").read_text()
    section = text.split("## How to write a problem", 1)[1].split("\n## ", 1)[0]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    printed = section.split("```python\n", 1)[1].split("```\n", 2)[2].split("```", 1)[0]
    ns: dict = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "docs/continuation.md", "exec"), ns)
    assert out.getvalue().split() == printed.split()
    br = ns["branch"]
    lam, x = br.points.T
    assert np.max(np.abs(x**3 - x - lam)) <= 1e-13 and br.end_reasons == ["boundary", "boundary"]
    fold = br.points[[k == "fold" for k in br.kinds]]
    assert len(fold) == 2
    fold = fold[np.argsort(fold[:, 1])]
    r = 1 / np.sqrt(3)
    assert np.allclose(fold[:, 1], [-r, r], rtol=0, atol=1e-12)
    assert np.allclose(fold[:, 0], [2 * r / 3, -2 * r / 3], rtol=0, atol=1e-13)
    (test,) = br.points[[k == "test" for k in br.kinds]]
    assert np.max(np.abs(test)) <= 1e-13
    assert np.allclose(br.points[[0, -1]], [[-1.875, -1.5], [1.875, 1.5]], rtol=0, atol=1e-13)


def test_python_path_compiles_nothing():
    """The engine's Python path (a problem without ``compiled_step``, or ``compiled=False``)
    runs the building blocks as plain Python: it imports no compiled module and compiles no
    numba function, so a cold start pays no compilation. Checked in a fresh interpreter (this
    test process has compiled them already): the dispatchers of continuation.linalg and
    continuation.compiled are not even made after a traced circle (numba is not imported)."""
    import subprocess
    import sys

    code = (
        "import sys, numpy as np, continuation\n"
        "from continuation import linalg\n"
        "class Circle:\n"
        "    def residual(self, u): return np.array([u[0]**2 + u[1]**2 - 1.0])\n"
        "br = continuation.trace(Circle(), [1.0, 0.0], continuation.TraceOptions(fold_components=(0, 1)))\n"
        "assert br.closed\n"
        "assert 'continuation.compiled' not in sys.modules\n"
        "assert 'numba' not in sys.modules\n"
        "print('ok')\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
