"""The compiled spectral kernel (stability/linear/kernel.py) against independent references.

Reference: the eigenvalues of ``M^-1 A`` computed by mpmath at 50 digits, with ``M`` and ``A``
typed in from eq. (11) of the paper in tests/conftest.py (not taken from the package), at the same
floating-point parameters.

Sample: 1,000 points, 700 spread over the physical domain (tests/conftest.py) and 300 at the
hard places: the edge of the domain ``A_G = 1 - mu q^2 -> 0`` (one root runs off to
``-alpha_v A_C / (mu A_G)``), ``alpha_v`` from 1e-6 to 1e6 and ``fr_inv`` from 1e-8 to 1e3
(widely separated scales), tiny ``q``, the structural zeros (``fr_inv = 0``, ``q = 0``,
``alpha_v = 0``), the neutral curve at ``fr_inv = 0`` and nearly colliding roots (the free
top's double root, ``sigma^2 = 4 A_G mu q fr_inv`` at ``alpha_v = 0``, approached with
``alpha_v`` down to 1e-12).

Tolerance: relative error per eigenvalue ``<= 1e-13`` (the issue's target) wherever the root
is well conditioned, i.e. wherever its own error bound ``e`` (stability/linear/roots.py: coefficient
errors of ``(deg + 4) u`` relative, first order ``dp/|p'|`` or second order
``sqrt(2 dp/|p''|)`` near a collision) is below ``1e-13 |s|``; where the problem itself is ill
conditioned (a near collision: two roots ``d`` apart move by ``~u |s|^2 / d``), the error must
stay below ``e``, the documented bound. The random part of the sample must be entirely of the
first kind (no hidden loosening), and a structural zero root must be exactly zero.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from conftest import mp_sliding_eigenvalues, random_domain_points

import stability
from stability.jit import cached
from stability.linear import kernel
from stability.linear.spectra import MARGINAL, STABLE, UNSTABLE

mp.mp.dps = 50
RTOL = 1e-13
NAMES = ("q", "fr_inv", "sigma", "alpha_v", "mu")
N_COLLISION = 66  # the last rows of the sample: near collisions


def _hard_points() -> dict[str, np.ndarray]:
    """300 points at the hard places listed in the module docstring."""
    rows = []
    rng = np.random.default_rng(5)
    mu = 2.28
    for eps in np.geomspace(1e-12, 1e-2, 20):  # domain edge, sigma at the triangle bound
        q = -np.sqrt((1 - eps) / mu)
        a_g = float(1 - mp.mpf(mu) * mp.mpf(q) ** 2)  # exact for the rounded q, then rounded
        rows.append((q, 0.3, 2 * a_g * (1 - 1e-15), 0.5, mu))
        rows.append((-q, 1.0, a_g, 2.0, mu))
    for a in np.geomspace(1e-6, 1e6, 30):  # separated scales
        rows.append((-0.1, 0.3, 1.0, a, mu))
        rows.append((0.2, 2.0, 0.5, a, 4.0))
    for f in np.geomspace(1e-8, 1e3, 25):
        rows.append((-0.1, f, 1.0, 0.5, mu))
        rows.append((0.3, f, 0.3, 5.0, mu))
    for qq in (1e-9, -1e-9, -1e-15):  # tiny q: tiny c0
        rows.append((qq, 0.3, 1.0, 0.5, mu))
    for _ in range(20):  # structural zeros
        q, a, f = rng.uniform(-0.6, 0.6), 10 ** rng.uniform(-2, 1), rng.uniform(0, 3)
        s = rng.uniform(0.05, 1.0) * 2 * (1 - mu * q * q)
        rows += [(q, 0.0, s, a, mu), (0.0, f, s, a, mu), (q, f, s, 0.0, mu)]
    for q in np.linspace(-0.45, 0.45, 21):  # neutral curve at fr_inv = 0: sigma = A_G / (1 + q)
        if q != 0:
            rows.append((q, 0.0, (1 - mu * q * q) / (1 + q), rng.uniform(0.1, 5.0), mu))
    # last N_COLLISION rows: the free top's double root, approached by alpha_v -> 0
    for q in (0.05, 0.2, 0.4):
        a_g = 1 - mu * q * q
        f = 1.0 / (4 * a_g * mu * q)  # sigma = 1
        for a in np.geomspace(1e-12, 1e-3, 10):
            rows.append((q, f, 1.0, a, mu))
            rows.append((q, f * (1 + 1e-9), 1.0, a, mu))
        rows.append((q, f, 1.0, 0.0, mu))
        rows.append((q, f * (1 - 1e-9), 1.0, 1e-8, mu))
    assert len(rows) == 300
    arr = np.array(rows, dtype=float)
    return {k: arr[:, j] for j, k in enumerate(NAMES)}


def _sample() -> tuple[dict[str, np.ndarray], int]:
    rand = random_domain_points(700, seed=21)
    hard = _hard_points()
    return {k: np.concatenate([rand[k], hard[k]]) for k in NAMES}, 700


@pytest.fixture(scope="module")
def reference():
    p, n_random = _sample()
    assert p["q"].size == 1000
    ref = [mp_sliding_eigenvalues(*(p[k][j] for k in NAMES)) for j in range(p["q"].size)]
    return p, n_random, ref


def _pair(ours: np.ndarray, ref: list) -> list[tuple[int, object]]:
    """Pair each reference root with the nearest remaining computed one."""
    left = list(range(len(ours)))
    out = []
    for r in ref:
        d = [abs(mp.mpc(complex(ours[k])) - r) for k in left]
        k = left.pop(int(np.argmin([float(x) for x in d])))
        out.append((k, r))
    return out


def test_kernel_against_mpmath(reference):
    p, n_random, ref = reference
    sp = stability.spectrum("sliding", method="kernel", **p)
    worst_random = worst_conditioned = 0.0
    n_ill = 0
    for j, rj in enumerate(ref):
        for k, r in _pair(sp.eigenvalues[j], rj):
            s, e = sp.eigenvalues[j, k], sp.error_bound[j, k]
            if abs(r) < mp.mpf(10) ** -40:  # a structural zero root (mpmath: ~1e-50)
                assert s == 0 and e == 0, (j, s)
                continue
            err = float(abs(mp.mpc(complex(s)) - r))
            scale = float(abs(r))
            if e <= RTOL * scale:
                worst_conditioned = max(worst_conditioned, err / scale)
                if j < n_random:
                    worst_random = max(worst_random, err / scale)
            else:  # ill conditioned: the documented bound holds
                assert j >= len(ref) - N_COLLISION, (j, s, e)
                n_ill += 1
                assert err <= e, (j, s, err, e)
    assert worst_conditioned <= RTOL, worst_conditioned
    assert worst_random <= RTOL, worst_random
    assert n_ill >= N_COLLISION  # the near collisions are there (and, above, only there)


def test_growth_rate_signs_and_flags(reference):
    """Where ``|Re s|`` exceeds the mode's tolerance the sign is the reference's; where it does
    not, the mode is neutral and the point marginal unless another mode grows."""
    p, _, ref = reference
    sp = stability.spectrum("sliding", method="kernel", **p)
    tol = 4 * sp.error_bound + 16 * 2.0**-53 * np.abs(sp.eigenvalues).max(axis=-1, keepdims=True)
    for j, rj in enumerate(ref):
        for k, r in _pair(sp.eigenvalues[j], rj):
            re = sp.eigenvalues[j, k].real
            if sp.neutral[j, k]:
                assert abs(float(mp.re(r))) <= 2 * tol[j, k] + 1e-40
            else:
                assert np.sign(re) == np.sign(float(mp.re(r))), (j, k, re, r)
        ref_max = max(float(mp.re(r)) for r in rj)
        if sp.stability[j] == UNSTABLE:
            assert ref_max > 0
        elif sp.stability[j] == STABLE:
            assert ref_max < 0
        else:
            assert sp.stability[j] == MARGINAL and sp.neutral[j].any()


def test_neutral_curve_is_flagged_not_guessed():
    """fr_inv = 0, sigma = A_G / (1 + q): a mode on the imaginary axis (test_spectra_reference,
    closed form); rounding of sigma leaves |Re s| ~ 1e-16, below the tolerance: marginal, and
    the structural zero root is exactly zero."""
    mu = 2.28
    q = np.linspace(-0.4, 0.4, 40)
    sp = stability.spectrum(
        "sliding", method="kernel", q=q, fr_inv=0.0, sigma=(1 - mu * q * q) / (1 + q), alpha_v=0.7, mu=mu
    )
    assert (sp.eigenvalues == 0).any(axis=-1).all()
    assert (sp.stability == MARGINAL).all()


def test_second_order_models_against_eq8(domain_points):
    """fixed_pivot and rolling_eq8 through the coefficient kernel: eq. (8) in mpmath (the paper's
    lambda, s = i (lambda + 1)); a gyroscopically stable top keeps Re s = 0 exactly."""
    p = domain_points(200, seed=23, alpha_v=False)
    for model, h in (("fixed_pivot", lambda q: 1 + q), ("rolling_eq8", lambda q: q)):
        sp = stability.spectrum(model, method="kernel", **p)
        for j in range(200):
            q, F, sg, m = (mp.mpf(float(p[k][j])) for k in ("q", "fr_inv", "sigma", "mu"))
            a_c = 1 + m * (1 + 2 * q)
            sh = sg / a_c
            root = mp.sqrt(mp.mpc(sh**2 / 4 - m * F * h(q) / a_c))
            ref = [mp.mpc(0, 1) * (sh / 2 - 1 + x + 1) for x in (root, -root)]
            for k, r in _pair(sp.eigenvalues[j], ref):
                err = float(abs(mp.mpc(complex(sp.eigenvalues[j, k])) - r))
                assert err <= max(RTOL * float(abs(r)), sp.error_bound[j, k]), (model, j)
            if sh**2 / 4 - m * F * h(q) / a_c > 0:
                assert (sp.eigenvalues[j].real == 0).all()


def test_sliding_coefficients_bitwise():
    """The kernel forms eq. (11)'s coefficients itself: they must be the model's, bit for bit."""
    p = random_domain_points(500, seed=24)
    ref = stability.get_model("sliding").coefficients(**p)
    formula = cached(stability.get_model("sliding").point_coefficients)  # compiled as in the kernel
    ours = np.array([formula(*(p[k][j] for k in NAMES)) for j in range(500)]).view(np.complex128)
    assert np.array_equal(ours, ref)


def test_lapack_cross_check_of_flags():
    """An independent method: the LAPACK path (absolute accuracy ~u ||M^-1 A||) agrees on the
    stability flag wherever its own tolerance decides the point."""
    p = random_domain_points(20000, seed=25)
    k = stability.spectrum("sliding", method="kernel", **p)
    la = stability.spectrum("sliding", method="lapack", **p)
    decided = la.stability != MARGINAL
    assert decided.mean() > 0.99
    assert np.array_equal(k.stability[decided], la.stability[decided])


def test_masked_points_and_polish_none():
    """Points outside the domain get NaN and flag -1; without polishing (Cardano only) the
    roots are still roots, to the accuracy the work-precision chart reports."""
    sp = stability.spectrum("sliding", q=np.array([0.1, 0.9]), fr_inv=0.3, sigma=1.0, alpha_v=0.5, mask_unphysical=True)
    assert sp.stability[1] == -1 and np.isnan(sp.eigenvalues[1]).all()
    p = random_domain_points(200, seed=26)
    raw = kernel.model_spectrum("sliding", p, polish=0)
    fine = kernel.model_spectrum("sliding", p)
    rel = np.abs(raw[0] - fine[0]) / np.abs(fine[0]).max(axis=-1, keepdims=True)
    assert rel.max() < 1e-6


def _ulps(x: float, k: int) -> list[float]:
    """``x`` and its neighbours up to ``k`` ulps away on each side."""
    out = [x]
    up = down = x
    for _ in range(k):
        up, down = np.nextafter(up, np.inf), np.nextafter(down, -np.inf)
        out += [up, down]
    return out


def _bound_points() -> dict[str, np.ndarray]:
    """Points exactly on and within 12 ulps of every bound of the domain: mu = 0, fr_inv = 0,
    alpha_v = 0, sigma = 0, A_G = 1 - mu q^2 = 0 (q = +-1/sqrt(mu) and its neighbours, in
    several mu) and sigma = 2 A_G (1 + 8 u) (the bound and its neighbours: the exact bound of
    check_domain is crossed both ways), then NaN and +-inf in each parameter."""
    base = dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5, mu=2.28)
    rows = []
    for name in ("mu", "fr_inv", "alpha_v", "sigma"):
        for x in _ulps(0.0, 12) + [-0.0, 5e-324, -5e-324]:
            rows.append({**base, name: x})
    for mu in (0.5, 1.0, 2.28, 3.0, 6.0, 1e-300, 1e300):
        for q in _ulps(1.0 / np.sqrt(mu), 12):
            for sign in (1.0, -1.0):
                rows.append({**base, "mu": mu, "q": sign * q, "sigma": 1e-3})
    for mu, q in ((2.28, -0.1), (2.28, 0.6), (0.5, 1.3), (6.0, 0.4), (4.0, 0.5 - 1e-9), (1.0, 0.0)):
        a_g = float(stability.models.inertia.transverse_inertia_g(q, mu))
        for bound in (2 * a_g, 2 * a_g * (1.0 + 8 * 2.0**-53), 2 * (1 - mu * q * q)):
            for s in _ulps(bound, 12):
                rows.append({**base, "mu": mu, "q": q, "sigma": s})
    for name in NAMES:
        for x in (np.nan, np.inf, -np.inf):
            rows.append({**base, name: x})
    # the computable range of check_domain (stability.parameters.COMPUTABLE_RANGE, if defined:
    # magnitudes above 1e30, positive mu below 1e-30, refused even when masked)
    for name in NAMES:
        for x in _ulps(1e30, 3) + [-1e30, -np.nextafter(1e30, np.inf), 1e300, -1e300]:
            rows.append({**base, name: x})
    for x in _ulps(1e-30, 3) + [1e-300, 5e-324]:
        rows.append({**base, "mu": x})
    return {k: np.array([r[k] for r in rows]) for k in NAMES}


def test_fused_domain_test_agrees_with_check_domain():
    """The kernel's domain test (fused into the default path) against the package's canonical
    one, stability.parameters.check_domain, point by point: exact agreement is required (no
    tolerance: both must evaluate the same A_G bit for bit and the same comparisons, including
    the exact sign of 2 (1 - mu q^2) - sigma and of 1 - mu q^2). Points: on and a few
    ulps around every bound (and the computable range's), NaN and inf in each parameter, and
    20,000 random points of a box four times wider than the domain. Code 2 (refused even
    masked) must be exactly where check_domain(mask=True) raises."""
    from stability.errors import DomainError
    from stability.parameters import check_domain

    rng = np.random.default_rng(30)
    n = 20000
    mu = rng.uniform(-1.0, 6.0, n)
    box = {
        "q": rng.uniform(-1.5, 1.5, n),
        "fr_inv": rng.uniform(-0.5, 3.0, n),
        "sigma": rng.uniform(-0.5, 2.5, n),
        "alpha_v": rng.uniform(-0.5, 10.0, n),
        "mu": mu,
    }
    edge = _bound_points()
    m = edge["q"].size
    p = {k: np.concatenate([edge[k], box[k]]) for k in NAMES}
    code = kernel.model_domain("sliding", p)
    refused = np.zeros(code.size, dtype=bool)
    for j in range(m):  # the random box holds no refused values: check the edge points one by one
        try:
            check_domain(mask=True, **{k: v[j] for k, v in p.items()})
        except DomainError:
            refused[j] = True
    assert np.array_equal(code == 2, refused)
    assert refused[:m].sum() >= 15  # NaN, inf in each parameter (and the computable range if defined)
    ok = ~refused
    _, inside = check_domain(mask=True, **{k: v[ok] for k, v in p.items()})
    assert np.array_equal(code[ok] == 0, inside)
    k = int(ok[:m].sum())
    assert 0.1 < inside[:k].mean() < 0.9 and 0.1 < inside[k:].mean() < 0.9  # both kinds well represented
    # through the public path: the same mask, and the canonical errors
    sp = stability.spectrum("sliding", mask_unphysical=True, **{k: v[ok] for k, v in p.items()})
    assert np.array_equal(sp.inside, inside)
    assert np.array_equal(sp.stability == -1, ~inside)
    outside = np.nonzero(~inside)[0][0]
    point = {k: v[ok][outside] for k, v in p.items()}
    with pytest.raises(DomainError) as fused:
        stability.spectrum("sliding", **point)
    with pytest.raises(DomainError) as canonical:
        check_domain(**point)
    assert str(fused.value) == str(canonical.value)
    with pytest.raises(DomainError, match="q = nan is not finite"):
        stability.spectrum("sliding", mask_unphysical=True, **{**point, "q": np.array([0.1, np.nan])})


def test_fused_path_equals_general_path():
    """The fused default path (scalars read in place, no broadcast copies) returns what the
    kernel returns on explicitly broadcast, checked parameters: identical arrays (same
    arithmetic, so no tolerance), on a broadcast grid with a masked region."""
    from stability.parameters import check_domain

    q = np.linspace(-0.8, 0.8, 41).reshape(-1, 1, 1)
    fr_inv = np.array([0.0, 0.1, 0.3]).reshape(1, -1, 1)
    sigma = np.linspace(0.1, 2.0, 7).reshape(1, 1, -1)
    sp = stability.spectrum("sliding", q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=0.5, mu=2.28, mask_unphysical=True)
    p, inside = check_domain(mask=True, q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=0.5, mu=2.28)
    ref = kernel.model_spectrum("sliding", p, inside)
    assert sp.eigenvalues.shape == (41, 3, 7, 3) and not inside.all() and inside.any()
    assert np.array_equal(sp.inside, inside)
    for ours, theirs in zip((sp.eigenvalues, sp.error_bound, sp.neutral, sp.stability), ref):
        assert np.array_equal(ours, theirs, equal_nan=ours.dtype.kind in "fc")
    assert all(v.shape == inside.shape for v in sp.params.values())


@pytest.mark.parametrize("engine", ["python", "compiled"])
def test_flag_from_modes_of_known_polynomials(engine):
    """The stability flag from the modes' decisions (the decision's arithmetic form): polynomials
    written from chosen roots, ``prod_k (s - r_k)`` expanded by hand (closed form, exact in
    binary for these small integers and halves), degrees 1 to 3: all roots in the left half
    plane -> stable; a root exactly at 0 (``c0 = 0``, a structural zero) and none to the right
    -> marginal; one to the right -> unstable, also when another mode is neutral (growth
    outranks neutrality)."""
    cases = [
        ([1, 2], STABLE),  # s + 2
        ([1, -0.5], UNSTABLE),  # s - 1/2
        ([1, 3, 2], STABLE),  # (s + 1)(s + 2)
        ([1, 1, 0], MARGINAL),  # s (s + 1)
        ([1, -1, 0], UNSTABLE),  # s (s - 1)
        ([1, 6, 11, 6], STABLE),  # (s + 1)(s + 2)(s + 3)
        ([1, 3, 2, 0], MARGINAL),  # s (s + 1)(s + 2)
        ([1, 0, -1, 0], UNSTABLE),  # s (s - 1)(s + 1): neutral and growing modes together
    ]
    for coefficients, flag in cases:
        sp = kernel.coefficient_spectrum(np.array([coefficients], dtype=complex), engine=engine)
        assert sp.stability[0] == flag, (coefficients, sp)
        n_zero = int(coefficients[-1] == 0)
        assert sp.neutral[0].sum() == n_zero
        assert (sp.eigenvalues[0] == 0).sum() == n_zero
