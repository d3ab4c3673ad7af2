"""Neutral curves of the linear models against independent references.

References (derived here, not by the code under test):

* Sliding model, eq. (11). With ``c3..c0`` of ``mu det(sM - A)`` (stability/models/sliding.py),
  ``p(i w) = alpha_v P_r(w) + i mu w P_f(w)`` where
  ``P_f(w) = -A_G w^2 + sigma w - mu q fr_inv`` (free top, the ``alpha_v -> 0`` limit) and
  ``P_r(w) = -A_C w^2 + (sigma + mu (1 + q)) w - mu q fr_inv`` (rolling top, the
  ``alpha_v -> infinity`` limit of ``p / alpha_v``), both real. For ``alpha_v > 0`` a nonzero
  neutral frequency is a common root; ``P_r - P_f = mu (1 + q) w (1 - (1 + q) w)`` gives
  ``w = 1/(1 + q)`` and then ``sigma = (1 - mu q^2)/(1 + q) + mu q (1 + q) fr_inv``, for every
  ``alpha_v > 0``. At ``fr_inv = 0`` its maximum over q (the fold) is at
  ``q* = -1 + sqrt(1 - 1/mu)``, ``sigma* = 2 (mu - sqrt(mu (mu - 1)))`` = 1.14331 at mu = 2.28
  (the paper's "sigma ~ 1.14").
* Fixed-pivot and rolling models, eq. (8): the boundary is the discriminant
  ``sigma_hat^2 = 4 kappa``, i.e. ``sigma^2 = 4 A_C mu fr_inv h`` (h = 1 + q or q), with the
  double root at ``w = sigma / (2 A_C)``.
* Brute force: bisection in sigma on the sign of the leading growth rate from mpmath's
  polynomial roots at 30 digits.

Tolerances: points are accepted at a relative backward error <= 1e-13 and polished to the
rounding floor (~1e-16); the closed forms are O(1) functions with O(1) derivatives, so 1e-13
bounds coordinate errors with a margin; folds are located to 1e-14 of a step in arclength
(coordinates of a fold: the issue asks 1e-10, we test 1e-12).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import xarray as xr
from conftest import mp_polyroots

from continuation import dense
from stability import fold_curve, neutral_curve
from stability.models import get_model
from stability.models.base import LinearModel
from stability.models.sliding import coefficient_parts, derivative_parts
from stability.parameters import PARAMETERS

MU = 2.28


def sliding_coefficients(**p):
    """Eq. (11)'s coefficients ``[c3, c2, c1, c0]`` at one point as Python complex numbers
    (coefficient_parts on floats), and their derivatives by each parameter (derivative_parts)."""
    point = tuple(float(p[k]) for k in PARAMETERS)

    def pairs(parts):
        return [complex(parts[i], parts[i + 1]) for i in range(0, len(parts), 2)]

    return pairs(coefficient_parts(*point)), {k: pairs(derivative_parts(*point, i)) for i, k in enumerate(PARAMETERS)}


def sigma_closed(q, f, mu=MU):
    """Neutral sigma of the sliding model (module docstring)."""
    return (1 - mu * q * q) / (1 + q) + mu * q * (1 + q) * f


@pytest.fixture(scope="module")
def curve_fr0():
    return neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))


def test_sliding_fr_inv_0_against_closed_form(curve_fr0):
    ds = curve_fr0
    q = ds.q.values
    assert ds.attrs["form"] == "crossing" and ds.attrs["deflated_zero_roots"] == 1
    assert np.max(np.abs(ds.sigma.values - sigma_closed(q, 0.0))) <= 1e-13
    assert np.max(np.abs(ds.frequency.values - 1 / (1 + q))) <= 1e-13
    assert float(ds.residual.max()) <= 1e-14
    # independent check with LAPACK eigenvalues of M^-1 A, away from the corner where
    # det M = 1 - mu q^2 -> 0 (cond(M) ~ 1e9 there)
    inner = (1 - MU * q * q) > 1e-6
    assert np.max(np.abs(ds.check_growth_rate.values[inner])) <= 1e-12
    # the whole curve across the domain: from the triangle edge at q = -1/2 to sigma -> 0
    ends = ds.where(ds.kind == "domain_edge", drop=True)
    assert sorted(ends.detail.values.tolist()) == ["sigma <= 2 (1 - mu q^2)", "sigma > 0"]
    edge = ends.where(ends.detail == "sigma <= 2 (1 - mu q^2)", drop=True)
    assert abs(float(edge.q[0]) + 0.5) <= 1e-13


def test_fold_is_the_papers_sigma_114(curve_fr0):
    fold = curve_fr0.where(curve_fr0.kind == "fold", drop=True)
    assert fold.detail.values.tolist() == ["fold in sigma"]
    mp = mpmath.mp
    mp.dps = 30
    q_star = float(-1 + mp.sqrt(1 - 1 / mp.mpf("2.28")))
    s_star = float(2 * (mp.mpf("2.28") - mp.sqrt(mp.mpf("2.28") * (mp.mpf("2.28") - 1))))
    assert abs(float(fold.q[0]) - q_star) <= 1e-12
    assert abs(float(fold.sigma[0]) - s_star) <= 1e-14
    assert round(s_star, 2) == 1.14


def test_dense_output_against_the_closed_form(curve_fr0):
    """``continuation.dense`` (cubic Hermite with the stored tangents) between the traced points
    of the fr_inv = 0 curve, against ``sigma = (1 - mu q^2)/(1 + q)`` and ``w = 1/(1 + q)``.

    Tolerance: the Hermite error is ``O(h^4)``; at the default steps (``max_step = 0.05``,
    ``max_angle = 0.1``) it was measured at 5.6e-7 in sigma (largest near q = -1/2, where the
    fourth derivative ``24 (1 - mu)/(1 + q)^5`` of the closed form is largest), so 2e-6 leaves a
    margin of ~3.5; the polyline's chord error there is ~5e-4. Doubling both step limits must
    multiply the error by about 2^4 = 16 (we accept 8 to 32).
    """
    d = dense(curve_fr0, 32)
    q, s, w = d.q.values, d.sigma.values, d.frequency.values
    assert d.sizes["sample"] == 32 * (curve_fr0.sizes["point"] - 1) + 1
    assert np.array_equal(q[::32], curve_fr0.q.values)  # through the traced points
    e_fine = np.max(np.abs(s - sigma_closed(q, 0.0)))
    assert e_fine <= 2e-6
    assert np.max(np.abs(w - 1 / (1 + q))) <= 2e-6
    coarse = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5), max_step=0.1, max_angle=0.2)
    dc = dense(coarse, 32)
    e_coarse = np.max(np.abs(dc.sigma.values - sigma_closed(dc.q.values, 0.0)))
    assert 8 <= e_coarse / e_fine <= 32


def test_sliding_analytic_coefficients_match_the_model():
    """The scalar path of the neutral condition (coefficient_parts and derivative_parts on floats)
    against the model's batched coefficients (the same operations: bit for bit) and its
    derivatives against the 4th-order central stencil on the model (the coefficients are
    polynomials of degree <= 2 in each parameter, so the stencil is exact up to rounding,
    ~1e-13 relative at h = 1e-3; 1e-10 leaves a wide margin)."""
    model = get_model("sliding")
    rng = np.random.default_rng(7)
    for _ in range(20):
        p = dict(
            q=rng.uniform(-0.6, 0.6),
            fr_inv=rng.uniform(0, 3),
            sigma=rng.uniform(0, 2),
            alpha_v=rng.uniform(0, 3),
            mu=MU,
        )
        c, dc = sliding_coefficients(**p)
        assert np.array_equal(np.array(c), model.coefficients(**p))
        for name in p:
            h = 1e-3
            f = [model.coefficients(**{**p, name: p[name] + k * h}) for k in (-2, -1, 1, 2)]
            num = (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h)
            assert np.allclose(dc[name], num, rtol=1e-10, atol=1e-10)


@pytest.mark.parametrize("alpha_v", [1e-3, 0.5, 1e3])
def test_sliding_alpha_v_limits(alpha_v):
    """The neutral curve is the common root of the alpha_v -> 0 (free top) and alpha_v -> inf
    (rolling top) polynomials, for every alpha_v."""
    f = 0.3
    ds = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=f, alpha_v=alpha_v))
    q, s, w = ds.q.values, ds.sigma.values, ds.frequency.values
    a_g, a_c = 1 - MU * q * q, 1 + MU * (1 + 2 * q)
    p_free = -a_g * w * w + s * w - MU * q * f
    p_roll = -a_c * w * w + (s + MU * (1 + q)) * w - MU * q * f
    assert np.max(np.abs(p_free)) <= 1e-13 and np.max(np.abs(p_roll)) <= 1e-13
    assert np.max(np.abs(s - sigma_closed(q, f))) <= 1e-13


def test_sliding_against_mpmath_bisection():
    """Brute force: at the q of some traced points, bisect in sigma on the leading growth rate
    of the mpmath roots (30 digits)."""
    f, a = 0.3, 0.5
    ds = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=f, alpha_v=a))
    mp = mpmath.mp
    mp.dps = 30

    def leading(q, s):
        q, s, mu = mp.mpf(q), mp.mpf(s), mp.mpf(MU)
        c = [
            mu * (1 - mu * q * q),
            a * (1 + mu * (1 + 2 * q)) - 1j * mu * s,
            -mu * mu * q * f - 1j * a * (s + mu * (1 + q)),
            -mu * a * q * f,
        ]
        return max(mp.re(r) for r in mp_polyroots(c, maxsteps=200, extraprec=60))

    idx = np.linspace(3, ds.sizes["point"] - 4, 4).astype(int)
    for k in idx:
        q, s = float(ds.q[k]), float(ds.sigma[k])
        lo, hi = s - 1e-3, s + 1e-3
        sign_lo = leading(q, lo) > 0
        assert sign_lo != (leading(q, hi) > 0)
        for _ in range(45):  # bracket 2e-3 -> 6e-17
            mid = (lo + hi) / 2
            if (leading(q, mid) > 0) == sign_lo:
                lo = mid
            else:
                hi = mid
        assert abs(s - (lo + hi) / 2) <= 1e-13


@pytest.mark.parametrize("model, h", [("rolling_eq8", lambda q: q), ("fixed_pivot", lambda q: 1 + q)])
def test_second_order_models_follow_the_discriminant(model, h):
    f = 0.05 if model == "fixed_pivot" else 0.3
    ds = neutral_curve(model, "q", "sigma", fixed=dict(fr_inv=f))
    assert ds.attrs["form"] == "collision" and ds.sizes["point"] > 10
    q, s, w = ds.q.values, ds.sigma.values, ds.frequency.values
    a_c = 1 + MU * (1 + 2 * q)
    # eq. (8): sigma_hat^2 = 4 kappa, double root at w = sigma_hat / 2
    disc = s * s - 4 * a_c * MU * f * h(q)
    assert np.max(np.abs(disc)) <= 1e-13
    assert np.max(np.abs(w - s / (2 * a_c))) <= 1e-13


def test_curve_that_turns_back():
    """In (q, fr_inv) at sigma = 1 the curve fr_inv = (1 + mu q)/(mu (1 + q)^2) has a maximum
    at q = (mu - 2)/mu: a column at fixed fr_inv just below it crosses the curve twice."""
    ds = neutral_curve("sliding", "q", "fr_inv", fixed=dict(sigma=1.0, alpha_v=0.5))
    main = ds.where((ds.q != 0) | (ds.kind != "regular"), drop=True)
    q, f = main.q.values, main.fr_inv.values
    ok = np.abs(q) > 1e-6  # the second branch is the line q = 0 (w = 1 at sigma = 1)
    assert np.max(np.abs(f[ok] - (1 + MU * q[ok]) / (MU * (1 + q[ok]) ** 2))) <= 1e-13
    fold = ds.where(ds.detail == "fold in fr_inv", drop=True)
    q_star = (MU - 2) / MU
    assert abs(float(fold.q[0]) - q_star) <= 1e-12
    assert abs(float(fold.fr_inv[0]) - (1 + MU * q_star) / (MU * (1 + q_star) ** 2)) <= 1e-14
    # points on both sides of the fold at fr_inv > 0.44 (two crossings per fr_inv column)
    sel = f > 0.44
    assert (q[sel] < q_star).any() and (q[sel] > q_star).any()
    # the two branches cross at (0, 1/mu): a branch point
    bp = ds.where(ds.kind == "branch_point", drop=True)
    assert bp.sizes["point"] >= 1
    assert np.min(np.abs(bp.fr_inv.values - 1 / MU)) <= 1e-10
    # On the line q = 0 (sigma = 1, A_G = 1): p(i w) = (w - w^2)(alpha_v (1 + mu) + i mu w), so
    # the modes are the traced s = i, a structurally neutral s = 0 and s = -alpha_v (1+mu)/mu.
    # No other mode grows: the line is a stability boundary and must be marked leading, even
    # though the computed zero root comes out as +-1e-17.
    line = ds.where((np.abs(ds.q) < 1e-12) & (ds.kind == "regular"), drop=True)
    assert line.sizes["point"] > 3
    assert bool(line.leading.all())


class TwoModes(LinearModel):
    """Test model with modes s1 = q + i (sigma - 1) and s2 = (sigma - 0.5) + 2 i.

    Neutral curves: q = 0 with w = sigma - 1 (w changes sign at sigma = 1: zero frequency), and
    sigma = 0.5 with w = 2; on q = 0 mode 2 is neutral too at sigma = 0.5 (double crossing,
    where the leading mode changes).
    """

    name = "two_modes"
    equations = "test"
    parameters = ("q", "fr_inv", "sigma", "mu")
    state = ("a", "b")
    n_modes = 2
    description = "two decoupled modes"

    def _modes(self, q, sigma):
        return q + 1j * (sigma - 1), (sigma - 0.5) + 2j

    def matrices(self, *, q, fr_inv, sigma, mu):
        q, sigma = np.broadcast_arrays(np.asarray(q, float), np.asarray(sigma, float))
        s1, s2 = self._modes(q, sigma)
        A = np.zeros(q.shape + (2, 2), complex)
        A[..., 0, 0], A[..., 1, 1] = s1, s2
        return np.broadcast_to(np.eye(2, dtype=complex), A.shape).copy(), A

    def coefficients(self, *, q, fr_inv, sigma, mu):
        q, sigma = np.broadcast_arrays(np.asarray(q, float), np.asarray(sigma, float))
        s1, s2 = self._modes(q, sigma)
        return np.stack([np.ones_like(s1), -(s1 + s2), s1 * s2], axis=-1)


def test_special_points_zero_frequency_and_double_crossing():
    ds = neutral_curve(
        TwoModes(), "q", "sigma", fixed=dict(fr_inv=0.0, mu=1.0), x_range=(-0.5, 0.5), y_range=(0.1, 1.5)
    )
    zf = ds.where(ds.kind == "zero_frequency", drop=True)
    dc = ds.where(ds.kind == "double_crossing", drop=True)
    # each branch sees the double crossing at (0, 0.5): mode 1 (w = -0.5) and mode 2 (w = 2)
    assert zf.sizes["point"] == 1 and dc.sizes["point"] == 2
    assert abs(float(zf.q[0])) <= 1e-14 and abs(float(zf.sigma[0]) - 1) <= 1e-12
    assert np.max(np.abs(dc.q.values)) <= 1e-14 and np.max(np.abs(dc.sigma.values - 0.5)) <= 1e-12
    assert sorted(dc.frequency.values.round(12).tolist()) == [-0.5, 2.0]
    assert all("leading mode changes" in str(d) for d in dc.detail.values)
    line = ds.where((np.abs(ds.q) < 1e-12) & (ds.kind == "regular"), drop=True)
    # on q = 0 mode 1 leads where mode 2 decays (sigma < 0.5)
    lead = line.leading.values.astype(bool)
    assert np.array_equal(lead, line.sigma.values < 0.5)
    other = ds.where((np.abs(ds.sigma - 0.5) < 1e-12) & (np.abs(ds.q) > 1e-12), drop=True)
    assert other.sizes["point"] > 5 and np.allclose(other.frequency.values, 2.0, atol=1e-13)


def test_dataset_format_and_netcdf_round_trip(curve_fr0, tmp_path):
    ds = curve_fr0
    assert {"q", "sigma", "frequency", "branch", "kind", "residual", "leading"} <= set(ds.data_vars)
    assert ds.q.dims == ("point",)
    for v in ("q", "sigma", "frequency", "residual"):
        assert ds[v].attrs["units"] in ("1", "R", "Omega") and ds[v].attrs["long_name"]
    assert ds.attrs["Conventions"].startswith("CF") and ds.attrs["fr_inv"] == 0.0
    path = tmp_path / "curve.nc"
    ds.to_netcdf(path)
    with xr.open_dataset(path) as back:
        back = back.load()
    for v in ("q", "sigma", "frequency", "residual"):
        np.testing.assert_array_equal(back[v].values, ds[v].values)
    assert back.kind.values.tolist() == ds.kind.values.tolist()
    assert back.leading.values.astype(bool).tolist() == ds.leading.values.tolist()


def test_fold_continued_in_fr_inv():
    """The largest unstable sigma as fr_inv varies: at the fold d sigma/dq = 0, i.e.
    mu f (1 + 2q) (1 + q)^2 = mu q^2 + 2 mu q + 1 (from the closed form of sigma)."""
    ds = fold_curve(
        "sliding",
        "q",
        "sigma",
        "fr_inv",
        fold_in="sigma",
        fixed=dict(fr_inv=0.0, alpha_v=0.5),
        z_range=(0.0, 0.3),
        max_step=0.1,
    )
    q, s, f = ds.q.values, ds.sigma.values, ds.fr_inv.values
    assert f.min() == 0.0 and f.max() == pytest.approx(0.3, abs=1e-15)
    g = MU * f * (1 + 2 * q) * (1 + q) ** 2 - (MU * q * q + 2 * MU * q + 1)
    assert np.max(np.abs(g)) <= 1e-10
    assert np.max(np.abs(s - sigma_closed(q, f))) <= 1e-12


def test_errors():
    with pytest.raises(ValueError, match="two different"):
        neutral_curve("sliding", "q", "q", fixed=dict(fr_inv=0, alpha_v=0.5, sigma=1))
    with pytest.raises(ValueError, match="alpha_k"):
        neutral_curve("sliding", "q", "alpha_k", fixed=dict(fr_inv=0, alpha_v=0.5))
    with pytest.raises(ValueError, match="not a known model"):
        neutral_curve("spinning", "q", "sigma", fixed={})
    with pytest.raises(TypeError, match="alpha_v"):
        neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0))
    with pytest.raises(TypeError, match="no parameter alpha_v"):
        neutral_curve("rolling", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=1.0))
    with pytest.raises(ValueError, match=r"fr_inv = -1 .*fr_inv >= 0"):
        neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=-1.0, alpha_v=0.5))
    with pytest.raises(ValueError, match="lo < hi"):
        neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5), x_range=(0.5, 0.1))


def test_compiled_twins_of_the_sliding_condition_are_bit_identical():
    """The compiled neutral condition (stability.linear.neutrality.crossing_kernels, used by
    the compiled corrector) and the second test function against the scalar Python path: the
    same floating-point operations, so the same bits, at random points (both derivatives'
    parameters, structural zero root deflated or not, |w| below and above 1)."""
    from stability.linear.neutrality import NeutralCondition, _other_roots_list

    rng = np.random.default_rng(5)
    planes = [("q", "sigma"), ("q", "fr_inv"), ("sigma", "alpha_v"), ("q", "mu"), ("fr_inv", "sigma")]
    for k in range(200):
        free = planes[k % 5]
        p = dict(
            q=rng.uniform(-0.6, 0.6),
            fr_inv=rng.uniform(0, 3) if k % 3 else 0.0,
            sigma=rng.uniform(0, 2),
            alpha_v=rng.uniform(0.1, 3),
            mu=rng.uniform(1, 3),
        )
        cond = NeutralCondition("sliding", free, {n: v for n, v in p.items() if n not in free}, compiled=True)
        assert cond._compiled is not None
        sliding_crossing_residual = cond.kernels.residual_and_jacobian
        sliding_crossing_other_growth = cond.kernels.other_growth
        vals, w = np.array([p[n] for n in free]), rng.uniform(-3, 3)
        F, J = cond.residual_and_jacobian(vals, w)
        Fc, Jc = sliding_crossing_residual(*cond._compiled, np.array([*vals, w]), True)
        np.testing.assert_array_equal(Fc, F)
        np.testing.assert_array_equal(Jc, J)
        r = _other_roots_list(cond._scalar(vals, False)[0], w, 1)
        assert sliding_crossing_other_growth(*cond._compiled, np.array([*vals, w])) == max(z.real for z in r)


@pytest.mark.parametrize(
    "x, y, fixed",
    [
        ("q", "sigma", dict(fr_inv=0.0, alpha_v=0.5)),
        ("q", "sigma", dict(fr_inv=0.3, alpha_v=0.5)),
        ("q", "sigma", dict(fr_inv=0.3, alpha_v=1e3)),
        ("sigma", "alpha_v", dict(q=-0.1, fr_inv=0.3)),
    ],
)
def test_compiled_path_gives_the_python_curve(x, y, fixed):
    """The compiled corrector (stability.linear.neutral_compiled) against the engine's Python path
    on the same problem: a second implementation of the same equations, so the same points,
    special points and flags, coordinates and tangents to rounding (observed <= 3e-15; both
    at the rounding floor of a problem whose points have condition ~1). The closed forms above
    remain the reference. (At a branch point, where the Jacobian loses rank, the two agree
    only to the conditioning of the point, ~1e-7: not compared here.)"""
    from stability.linear.neutral_curves import NeutralProblem

    fast = neutral_curve("sliding", x, y, fixed=fixed, compiled=True)
    slow = neutral_curve("sliding", x, y, fixed=fixed, compiled=False)
    assert fast.sizes == slow.sizes and fast.sizes["point"] > 10
    for v in ("kind", "detail", "branch", "leading"):
        assert fast[v].values.tolist() == slow[v].values.tolist()
    for v in (x, y, "frequency", f"tangent_{x}", f"tangent_{y}", "tangent_frequency"):
        np.testing.assert_allclose(fast[v].values, slow[v].values, rtol=0, atol=2e-14)
    assert float(fast.residual.max()) <= 1e-14
    # the compiled path exists for the sliding model's crossing form only
    rng = {x: (0.0, 1.0), y: (0.0, 1.0)}
    assert NeutralProblem("sliding", x, y, fixed | {"mu": MU}, rng, compiled=True).compiled_step is not None
    assert NeutralProblem("sliding", x, y, fixed | {"mu": MU}, rng, compiled=False).compiled_step is None
    assert (
        NeutralProblem(
            "rolling", "q", "sigma", dict(fr_inv=0.3, mu=MU), {"q": (0, 1), "sigma": (0, 1)}, compiled=True
        ).compiled_step
        is None
    )


def test_compiled_step_returns_the_problems_constraints_and_test_functions():
    """The compiled step also returns the constraints and test functions at the corrected
    point (continuation.problem: the optional two trailing values), which the engine then does
    not ask for: they must be the numbers the problem's own methods give there, exactly."""
    from stability.linear.neutral_curves import NeutralProblem

    fixed = dict(fr_inv=0.0, alpha_v=0.5, mu=MU)
    rng = {"q": (-1 / np.sqrt(MU), 1 / np.sqrt(MU)), "sigma": (0.0, 2.0)}
    prob = NeutralProblem("sliding", "q", "sigma", fixed, rng, compiled=True)
    scale = np.array([2 / np.sqrt(MU), 2.0, 1.0])
    for q in (-0.3, 0.0, 0.2, 0.6):
        u = np.array([q, (1 - MU * q * q) / (1 + q), 1 / (1 + q)])
        t = np.array([1.0, 0.0, 0.0])
        res = prob.compiled_step(u / scale, t, u / scale, 0.0, scale, 1e-13, 8, 1.0)
        assert len(res) == 11 and res[0]
        v = res[4]
        np.testing.assert_array_equal(res[9], prob.constraints(v * scale))
        np.testing.assert_array_equal(res[10], prob.test_functions(v * scale, res[7]))


def test_fold_selected_along_the_point_index():
    """The dataset's ``point`` index selects: the one fold of the sliding model's (q, sigma)
    curve at fr_inv = 0 (the paper's sigma ~ 1.14; tests above check its value)."""
    ds = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5, mu=MU))
    assert ds.where(ds.kind == "fold", drop=True).sizes["point"] == 1


def test_start_from_a_threshold_query_without_frequency():
    """A threshold answer as a start point (x, y) at fr_inv = 0: the frequency guess must come
    from the gyroscopic mode, not the structural zero root (s = 0 exactly, neutral everywhere:
    it used to send Newton to another curve and raise). Reference: the closed forms
    sigma = (1 - mu q^2)/(1 + q) at q = -0.2 (1.136) and the fold sigma* = 2 (mu - sqrt(mu (mu - 1)))."""
    import stability

    v = stability.threshold("sigma", q=-0.2, fr_inv=0.0, alpha_v=0.5)
    assert v == pytest.approx((1 - MU * 0.04) / 0.8, rel=1e-14)
    ds = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5), start=[(-0.2, v)])
    fold = ds.where(ds.kind == "fold", drop=True)
    assert fold.sizes["point"] == 1
    assert float(fold.sigma[0]) == pytest.approx(2 * (MU - np.sqrt(MU * (MU - 1))), rel=1e-14)


@pytest.mark.parametrize("ranges", [dict(x_range=(5.0, 6.0)), dict(y_range=(-5.0, -1.0))])
def test_ranges_outside_the_domain_are_an_error_not_an_empty_curve(ranges):
    """q in (5, 6) has mu q^2 > 1 everywhere; sigma in (-5, -1) is negative: no point of either
    rectangle is physical (the domain's inequalities, docs/conventions.md). Before, the call
    returned an empty dataset (and `tippe neutral` wrote it), indistinguishable from "no curve"."""
    from stability.errors import DomainError

    with pytest.raises(DomainError, match=r"lie outside the physical domain at fr_inv = 0, alpha_v = 0.5"):
        neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5), **ranges)


def test_no_false_double_crossing_as_fr_inv_goes_to_zero():
    """(sigma, fr_inv) plane at q = -0.1, alpha_v = 0.5: as fr_inv -> 0 a small root
    s ~ -i 0.073 fr_inv has real part -1.57e-2 fr_inv^2 (< 0: mpmath at 50 digits below), so no
    second mode crosses. Forward synthetic division gave the quotient's last coefficient an
    absolute error ~u, which decided that root's sign (+3.8e-15 for a true -3e-34 next to the
    edge) and produced a "double_crossing" at fr_inv = 5e-7; with composite deflation (the last
    coefficient -c0/r) the small root is right to relative rounding."""
    from stability.linear.neutrality import _other_roots_list

    ds = neutral_curve("sliding", "sigma", "fr_inv", fixed=dict(q=-0.1, alpha_v=0.5))
    assert "double_crossing" not in set(ds.kind.values)
    for compiled in (True, False):
        ds2 = neutral_curve("sliding", "sigma", "mu", fixed=dict(q=-0.1, fr_inv=0.3, alpha_v=0.5), compiled=compiled)
        assert "double_crossing" not in set(ds2.kind.values)
        # the corner q = 0, fr_inv = 0 of the (q, fr_inv) plane: on q ~ 0 the small root's real
        # part is ~(q fr_inv)^2, below rounding; at fr_inv = 0 it is an exact zero (Re s = 0, no
        # sign). Removing exact zeros there made the test jump to the next mode and report one.
        ds3 = neutral_curve(
            "sliding",
            "q",
            "fr_inv",
            fixed=dict(sigma=1.0, alpha_v=0.5),
            x_range=(-0.468, 0.468),
            y_range=(0.0, 2.0),
            compiled=compiled,
        )
        assert "double_crossing" not in set(ds3.kind.values)
        assert list(ds3.kind.values).count("branch_point") >= 1 and "fold" in set(ds3.kind.values)
    # the small root at the regular point nearest fr_inv = 0 on the curve: _other_roots_list vs mpmath
    regular = np.flatnonzero(ds.kind.values == "regular")
    k = regular[np.argmin(ds.fr_inv.values[regular])]
    f, sigma, w = float(ds.fr_inv[k]), float(ds.sigma[k]), float(ds.frequency[k])
    mp = mpmath.mp
    mp.dps = 50
    c = [
        MU * (1 - MU * 0.01),
        0.5 * (1 + MU * 0.8) - 1j * MU * sigma,
        -MU * MU * (-0.1) * f - 0.5j * (sigma + MU * 0.9),
        -MU * 0.5 * (-0.1) * f,
    ]
    ref = [r for r in mp_polyroots([mp.mpc(z) for z in c], maxsteps=200, extraprec=200) if abs(r - 1j * w) > 1e-3]
    assert all(mp.re(r) < 0 for r in ref)
    coeffs, _ = sliding_coefficients(q=-0.1, fr_inv=f, sigma=sigma, alpha_v=0.5, mu=MU)
    ours = np.array(_other_roots_list(np.asarray(coeffs).ravel(), w))
    small = ours[np.argmin(np.abs(ours))]
    # relative 1e-8: the root has modulus ~3e-3 and real part ~3.6e-5 here, so its real part
    # carries ~u |s| / |Re s| ~ 1e-14 relative error from the quotient, times the point's own
    # residual (the curve point is a root of p to ~1e-16)
    assert abs(small.real / float(mp.re(min(ref, key=abs))) - 1) < 1e-8
