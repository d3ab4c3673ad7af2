"""One home per fact, several engines; and models reached through the registry only.

Each formula of the linear layer is written once, in plain arithmetic registered with
``numba.extending.register_jitable`` (eq. (11)'s coefficients and their derivatives in
stability/models/sliding.py, ``A_G`` in stability/models/inertia.py, the domain table in
stability/parameters.py, Horner's scheme, the quadratic formula and synthetic division in
stability/linear/roots.py), and runs in up to three engines: Python floats, numpy arrays and
numba-compiled code.

Most tests below are *engine-agreement checks*, and say so: they compare the engines of one
source with each other, bit for bit, on random points and at the hard places (around every
bound of the domain, near ``A_G = 0``). They catch an engine that does not do the written
floating-point operations (a compiler contracting ``a * b + c`` into a fused multiply-add, a
numpy function standing in for the arithmetic, a stale numba disk cache of an edited formula),
not a wrong formula: the independent references of the formulas remain the mpmath tests
(tests/test_spectra_reference.py, tests/test_kernel.py, tests/test_neutral.py,
tests/test_hard_*.py). Where a test here does compare with an independent reference (mpmath,
a closed form, the inequalities of docs/conventions.md) it says which.

The last tests register two toy models at test time (one with no optional capability, one that
offers its coefficients as formulas) and get spectra, thresholds and neutral curves for them
through the registry only, checked against their closed forms.
"""

from __future__ import annotations

import math
import re
import subprocess
import sys

import mpmath as mp
import numpy as np
import pytest
from conftest import mp_polyroots, random_domain_points
from numba import njit
from numba.extending import register_jitable
from test_kernel import NAMES, _bound_points

import stability
import stability.jit
from stability.jit import cached
from stability.linear import kernel
from stability.linear.neutral_curves import neutral_curve
from stability.linear.neutrality import NeutralCondition, _other_roots_list, _other_roots_many
from stability.linear.roots import divide_root, horner, horner_scheme, quadratic_roots, quadratic_roots_many
from stability.models import LinearModel
from stability.models.inertia import inertia_g, transverse_inertia_g, two_product
from stability.models.sliding import coefficient_parts, derivative_parts
from stability.parameters import DOMAIN, check_domain, domain_applies, domain_sides, inside_domain

# numba code of one's own that calls the package's formulas: register them first (the package
# installs no hook into numba; stability/jit.py)
stability.jit.activate()

U = 2.0**-53


def _finite_bound_points() -> dict[str, np.ndarray]:
    """tests/test_kernel.py's points on and within 12 ulps of every bound of the domain, without
    the NaN/inf rows and the magnitudes beyond the computable range (refused before any formula
    runs)."""
    p = _bound_points()
    keep = np.ones(p["q"].size, dtype=bool)
    for v in p.values():
        keep &= np.isfinite(v) & (np.abs(v) <= 1e30)
    keep &= p["mu"] >= 1e-30
    return {k: v[keep] for k, v in p.items()}


def _sample() -> dict[str, np.ndarray]:
    """500 random points of the domain and the finite bound points (a few hundred)."""
    rand = random_domain_points(500, seed=41)
    edge = _finite_bound_points()
    return {k: np.concatenate([rand[k], edge[k]]) for k in NAMES}


# --- eq. (11): coefficients and derivatives ----------------------------------------------------


@njit(cache=False)
def _compiled_derivative_parts(q, fr_inv, sigma, alpha_v, mu, k):
    return derivative_parts(q, fr_inv, sigma, alpha_v, mu, k)


def test_sliding_formulas_same_bits_in_every_engine():
    """Engine agreement (not accuracy: see test_spectra_reference, test_neutral's stencil test):
    eq. (11)'s coefficients from Python floats, from numpy arrays (Sliding.coefficients) and
    compiled (the formula as the spectral kernel compiles it, stability.jit.cached), and their derivatives by
    each parameter from Python floats, numpy arrays and a compiled call, on random points and
    the points around every domain bound: identical bits (every value, both signs of zero
    compared as equal)."""
    p = _sample()
    n = p["q"].size
    arrays = stability.get_model("sliding").coefficients(**p)
    parts_np = coefficient_parts(*(p[k] for k in NAMES))
    for j in range(n):
        point = tuple(float(p[k][j]) for k in NAMES)
        py = coefficient_parts(*point)
        py_c = [complex(py[2 * i], py[2 * i + 1]) for i in range(4)]
        assert py == cached(coefficient_parts)(*point) and py_c == arrays[j].tolist(), point
        assert all(float(np.broadcast_to(a, (n,))[j]) == b for a, b in zip(parts_np, py))
        for k in range(5):
            d = derivative_parts(*point, k)
            assert d == _compiled_derivative_parts(*point, k), (point, k)
    for k in range(5):
        d_np = derivative_parts(*(p[name] for name in NAMES), k)
        for j in range(0, n, 7):
            point = tuple(float(p[name][j]) for name in NAMES)
            assert tuple(float(np.broadcast_to(a, (n,))[j]) for a in d_np) == derivative_parts(*point, k)


@njit(cache=False)
def _compiled_inertia_g(q, mu):
    return inertia_g(q, mu)


def test_inertia_g_same_bits_in_every_engine_near_the_edge():
    """Engine agreement: the compensated A_G = 1 - mu q^2 from Python floats, numpy arrays and
    compiled code at q = +-1/sqrt(mu) and 12 ulps around it, for mu from 1e-3 to 1e3, where
    A_G loses all its digits if evaluated naively. (Its accuracy: test_hard_spectra, mpmath.)"""
    qs, mus = [], []
    for mu in np.geomspace(1e-3, 1e3, 13):
        q = 1.0 / math.sqrt(mu)
        for k in range(-12, 13):
            qk = q
            for _ in range(abs(k)):
                qk = math.nextafter(qk, math.inf if k > 0 else -math.inf)
            qs += [qk, -qk]
            mus += [mu, mu]
    qs, mus = np.array(qs), np.array(mus)
    arr = transverse_inertia_g(qs, mus)
    for j in range(qs.size):
        py = inertia_g(float(qs[j]), float(mus[j]))
        assert py == float(arr[j]) == _compiled_inertia_g(qs[j], mus[j])


@njit(cache=False)
def _compiled_two_product(a, b):
    return two_product(a, b)


def test_two_product_exact_in_every_engine():
    """Reference: exact rational arithmetic (fractions.Fraction). Dekker's product with
    Veltkamp's splits, the one home of the split that A_G and the exact domain margins use, gives
    a b = p + e with no error at all (tolerance zero), for factors over 60 decades and of both
    signs, from Python floats, numpy arrays and compiled code alike."""
    from fractions import Fraction

    rng = np.random.default_rng(7)
    a = rng.uniform(-1, 1, 400) * 10.0 ** rng.uniform(-30, 30, 400)
    b = rng.uniform(-1, 1, 400) * 10.0 ** rng.uniform(-30, 30, 400)
    p_arr, e_arr = two_product(a, b)
    for j in range(a.size):
        x, y = float(a[j]), float(b[j])
        p, e = two_product(x, y)
        assert Fraction(x) * Fraction(y) == Fraction(p) + Fraction(e)
        assert (p, e) == (float(p_arr[j]), float(e_arr[j])) == _compiled_two_product(x, y)


# --- the domain table --------------------------------------------------------------------------


def test_domain_table_same_decision_in_every_engine():
    """Engine agreement: the domain table's test of a point from Python floats
    (domain_sides/inside_domain, what a pure-Python kernel would run), numpy arrays
    (check_domain's path, mask=True) and the compiled kernel (its fused test,
    kernel.model_domain) on and within 12 ulps of every bound, the slack of sigma <= 2 A_G
    included. (check_domain against the kernel on 20,000 random points and NaN/inf:
    test_kernel.)"""
    p = _finite_bound_points()
    code = kernel.model_domain("sliding", p)
    mask = check_domain(mask=True, **p)[1]
    applies = domain_applies(NAMES)
    assert (code == 0).any() and (code == 1).any() and not (code == 2).any()
    for j in range(p["q"].size):
        sides = domain_sides(*(float(p[k][j]) for k in NAMES), 0.0)
        assert inside_domain(sides, applies) == bool(mask[j]) == (code[j] == 0), {k: p[k][j] for k in NAMES}


def test_domain_table_states_the_documented_domain():
    """Independent reference: the inequalities of docs/conventions.md typed in here
    (1 - mu q^2 > 0, 0 < sigma <= 2 (1 - mu q^2), mu > 0, fr_inv >= 0, alpha_v >= 0), evaluated
    in exact rational arithmetic (fractions) on 2,000 random points of a box four times wider
    than the domain, against the table's test (check_domain, mask=True). Points within 1e-12 of a bound
    are left out (the table has an 8-ulp slack on sigma <= 2 A_G). Also: every row names the
    parameter its message reports, and check_domain's message for a point violating only that
    row quotes the row's text."""
    from fractions import Fraction

    from stability.errors import DomainError
    from stability.parameters import check_domain

    rng = np.random.default_rng(42)
    n = 2000
    p = {
        "q": rng.uniform(-1.5, 1.5, n),
        "fr_inv": rng.uniform(-0.5, 3.0, n),
        "sigma": rng.uniform(-0.5, 2.5, n),
        "alpha_v": rng.uniform(-0.5, 5.0, n),
        "mu": rng.uniform(-1.0, 6.0, n),
    }
    mask = check_domain(mask=True, **p)[1]
    checked = 0
    for j in range(n):
        q, f, s, a, m = (Fraction(float(p[k][j])) for k in NAMES)
        a_g = 1 - m * q * q
        margins = [m, f, a, a_g, s, 2 * a_g - s]
        if min(abs(x) for x in margins) < Fraction(1, 10**12):
            continue
        ref = m > 0 and f >= 0 and a >= 0 and a_g > 0 and 0 < s <= 2 * a_g
        assert bool(mask[j]) == ref
        checked += 1
    assert checked > 1900 and 0.05 < mask.mean() < 0.5
    inside = dict(q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5, mu=2.28)
    violate = {
        "mu > 0": dict(mu=-1.0),
        "fr_inv >= 0": dict(fr_inv=-1.0),
        "alpha_v >= 0": dict(alpha_v=-1.0),
        "1 - mu q^2 > 0": dict(q=0.9),
        "sigma > 0": dict(sigma=-1.0),
        "sigma <= 2 (1 - mu q^2)": dict(sigma=1.99),
    }
    for b in DOMAIN:
        if b.parameter == "alpha_k":
            continue
        with pytest.raises(DomainError, match=rf"^{b.parameter} = .* outside the physical domain: {re.escape(b.text)}"):
            check_domain(**{**inside, **violate[b.text]})


def test_margins_same_bits_python_and_compiled():
    """Engine agreement: the constraints of a neutral-curve problem (the table's margins and
    the ranges) from Python floats (neutral_constraints.constraint_values, interpreted) and compiled
    (the compiled step's own, neutral_compiled.constraint_values), on points near the domain's
    edges in three planes."""
    from stability.linear.neutral_curves import NeutralProblem

    rng = np.random.default_rng(43)
    for x, y, fixed in (
        ("q", "sigma", dict(fr_inv=0.0, alpha_v=0.5, mu=2.28)),
        ("q", "mu", dict(fr_inv=0.3, sigma=0.5, alpha_v=0.5)),
        ("sigma", "fr_inv", dict(q=-0.1, alpha_v=0.5, mu=2.28)),
    ):
        prob = NeutralProblem("sliding", x, y, fixed, {x: (-1.0, 1.0), y: (0.0, 2.0)}, compiled=True)
        python = NeutralProblem("sliding", x, y, fixed, {x: (-1.0, 1.0), y: (0.0, 2.0)}, compiled=False)
        assert prob._compiled is not None and python._compiled is None
        for _ in range(200):
            u = np.array(
                [
                    rng.uniform(-0.7, 0.7) if x == "q" else rng.uniform(0, 2.2),
                    rng.uniform(-0.01, 2.5),
                    rng.uniform(-2, 2),
                ]
            )
            ours = python.constraints(u)
            np.testing.assert_array_equal(prob.constraints(u), ours)


# --- polynomial building blocks (stability/linear/roots.py) ------------------------------------


def _quadratics(n: int, seed: int) -> np.ndarray:
    """Random quadratics (n, 3): general complex, conservative with real and with complex nu
    (a real, b imaginary, k real), b = 0, k = 0, and scales from 1e-8 to 1e8."""
    rng = np.random.default_rng(seed)
    z = lambda: complex(rng.normal(), rng.normal())  # noqa: E731
    rows = []
    for j in range(n):
        kind = j % 5
        scale = 10.0 ** rng.uniform(-8, 8)
        if kind == 0:
            a, b, k = z(), z() * scale, z() * scale**2
        elif kind == 1:  # conservative: p(i nu) = -a nu^2 - Im(b) nu + k real
            a = complex(rng.normal(), 0)
            b, k = complex(0, rng.normal() * scale), complex(rng.normal() * scale**2, 0)
        elif kind == 2:
            a, b, k = z(), 0j, z() * scale**2
        elif kind == 3:
            a, b, k = z(), z() * scale, 0j
        else:
            a, b, k = complex(1.0, 0), complex(0, 2 * scale), complex(-(scale**2) * (1 + 1e-6 * rng.normal()), 0)
        rows.append((a, b, k))
    return np.array(rows, dtype=complex)


def test_quadratic_formula_engines_and_mpmath():
    """The stable quadratic formula (roots.quadratic_roots). Engine agreement: Python complex
    numbers against the compiled batch loop (quadratic_roots_many, what polynomial_roots and
    the neutral condition's batches run), identical bits and flags. Independent reference:
    mpmath's roots at 40 digits; each root within 8 u of the larger root's modulus plus 8 u of its
    own times the conditioning |r| / |r1 - r2| (the formula is backward stable and its two roots
    are computed without cancellation), and a conservative quadratic with real nu gives
    Re s = 0 exactly, flagged."""
    c = _quadratics(1000, 44)
    roots = np.empty((c.shape[0], 2), dtype=complex)
    exact = np.empty((c.shape[0], 2), dtype=bool)
    cached(quadratic_roots_many)(c[:, 0].copy(), c[:, 1].copy(), c[:, 2].copy(), roots, exact)
    mp.mp.dps = 40
    n_exact = 0
    for j, (a, b, k) in enumerate(c):
        r1, r2, ex = quadratic_roots(complex(a), complex(b), complex(k))
        assert (r1, r2) == (roots[j, 0], roots[j, 1]) and ex == exact[j, 0] == exact[j, 1]
        ref = mp_polyroots([mp.mpc(complex(a)), mp.mpc(complex(b)), mp.mpc(complex(k))], maxsteps=200, extraprec=200)
        big = max(abs(complex(x)) for x in ref)
        sep = abs(complex(ref[0] - ref[1]))
        for r in (r1, r2):
            err = min(float(abs(mp.mpc(r) - x)) for x in ref)
            cond = abs(r) * big / sep if sep > 0 else math.inf
            assert err <= 8 * U * (big + cond), (j, r, ref)
        if ex:
            assert r1.real == 0 and r2.real == 0
            n_exact += 1
    assert n_exact > 100


def test_composite_division_engines_and_mpmath():
    """Synthetic division by (s - i w) (roots.divide_root, composite: the last coefficient
    from the bottom). Independent reference: for p(s) = (s - i w)(a s^2 + b s + k) built in
    mpmath and rounded (k down to 1e-12), the quotient against (a, b, k) in mpmath: the forward
    coefficients within 4 u of |c_j| + |w| |q_(j-1)|, and the last within 4 u of itself,
    relative however small (the point of the composite division, which keeps a tiny root's
    sign; forward, its error would be ~u |c_2|). Engine
    agreement: the other modes from Python numbers (_other_roots_list) and from the compiled
    batch (_other_roots_many), identical bits."""
    rng = np.random.default_rng(45)
    mp.mp.dps = 40
    cs, ws = [], []
    for _ in range(300):
        w = rng.uniform(-3, 3)
        a = mp.mpc(rng.uniform(1, 3), 0)
        b = mp.mpc(rng.normal(), rng.normal())
        k = mp.mpc(rng.normal(), rng.normal()) * mp.mpf(10) ** rng.uniform(-12, 0)
        iw = mp.mpc(0, w)
        c = [a, b - iw * a, k - iw * b, -iw * k]
        cf = [complex(x) for x in c]
        out = [0j, 0j, 0j]
        divide_root(cf, 3, complex(0.0, w), out)
        # forward: q_j = c_j + i w q_(j-1), error <= ~4 u (|c_j| + |w| |q_(j-1)|) with the
        # rounding of the inputs; from the bottom: q_2 = -c_3 / (i w), error <= ~4 u |q_2|
        assert abs(mp.mpc(out[0]) - a) <= 4 * U * abs(a)
        assert abs(mp.mpc(out[1]) - b) <= 4 * U * (abs(cf[1]) + abs(w) * abs(cf[0]))
        assert abs(mp.mpc(out[2]) - k) <= 4 * U * abs(k)
        cs.append(cf)
        ws.append(w)
    cs, ws = np.array(cs), np.array(ws)
    many = np.empty((len(ws), 2), dtype=complex)
    cached(_other_roots_many)(cs, 4, ws, 1, many)
    for j in range(len(ws)):
        assert _other_roots_list(cs[j], ws[j], 1) == many[j].tolist()


@njit(cache=False)
def _compiled_horner(c, s):
    return horner_scheme(c, s)


def test_horner_engines_and_mpmath():
    """Horner's scheme with two derivatives (roots.horner_scheme). Engine agreement: a Python
    list and a numba array give identical bits. A numpy batch (roots.horner) runs the same
    source but not the same operations: numpy's complex multiply loops use fused multiply-adds
    on machines that have them (AVX2/FMA3), so complex arithmetic on arrays agrees with scalar
    code only to rounding (why the formulas that must agree bit for bit, eq. (11)'s
    coefficients, A_G and the domain, are written in real arithmetic). Independent reference,
    for all three: p, p', p'' in mpmath, within 10 u of sum_k |c_k| |s|^k (and of the
    derivatives' own such sums)."""
    rng = np.random.default_rng(46)
    c = rng.normal(size=(200, 4)) + 1j * rng.normal(size=(200, 4))
    s = rng.normal(size=200) * 3 + 1j * rng.normal(size=200)
    batch = horner(c, s)
    mp.mp.dps = 30
    for j in range(200):
        py = horner_scheme(c[j].tolist(), complex(s[j]))
        assert py == _compiled_horner(c[j], s[j])
        x = mp.mpc(complex(s[j]))
        coeffs = [mp.mpc(complex(v)) for v in c[j]]
        ref = [
            sum(coeffs[k] * x ** (3 - k) for k in range(4)),
            sum((3 - k) * coeffs[k] * x ** (2 - k) for k in range(3)),
            sum((3 - k) * (2 - k) * coeffs[k] * x ** (1 - k) for k in range(2)),
        ]
        a = abs(complex(s[j]))
        scales = [
            sum(abs(c[j, k]) * a ** (3 - k) for k in range(4)),
            sum((3 - k) * abs(c[j, k]) * a ** (2 - k) for k in range(3)),
            sum((3 - k) * (2 - k) * abs(c[j, k]) * a ** (1 - k) for k in range(2)),
        ]
        for engine in (py, tuple(complex(x[j]) for x in batch)):
            for got, want, sc in zip(engine, ref, scales):
                assert abs(mp.mpc(got) - want) <= 10 * U * sc


def test_other_modes_batched_path_divides_composite():
    """The batched other modes of a model without compiled twins (compiled=False: the numpy
    path) used forward division only, while the one-point and compiled paths divided
    composite. Engine agreement: the three now give identical bits at random points.
    Independent reference (mpmath at 60 digits): on the sliding model's neutral curve at
    q = -0.1, alpha_v = 0.5 near fr_inv = 0 (closed form, from the common root of the free-top
    and rolling-top polynomials as in tests/test_neutral.py: w = 1/(1 + q),
    sigma = A_G/(1 + q) + mu q (1 + q) fr_inv), the small other root s ~ -0.073 i fr_inv has
    Re s ~ -1.6e-2 fr_inv^2; at fr_inv = 1e-6 and 1e-7 the batched path gets it within
    20 u |s| / |Re s| relative (composite division: relative rounding of the quotient's last
    coefficient; measured 2e-9 and 5e-9). Forward division was off by 3e-2 and 0.8 there."""
    rng = np.random.default_rng(47)
    vals = np.stack([rng.uniform(-0.4, 0.4, 300), rng.uniform(0.2, 1.0, 300)], axis=-1)
    w = rng.uniform(-2, 2, 300)
    fixed = dict(fr_inv=0.3, alpha_v=0.5, mu=2.28)
    fast = NeutralCondition("sliding", ("q", "sigma"), fixed).other_modes_many(vals, w)
    slow_cond = NeutralCondition("sliding", ("q", "sigma"), fixed, compiled=False)
    slow = slow_cond.other_modes_many(vals, w)
    np.testing.assert_array_equal(fast, slow)
    for j in range(0, 300, 10):
        assert slow[j].tolist() == slow_cond.other_modes_list(vals[j], w[j])

    mu, q, alpha_v = 2.28, -0.1, 0.5
    cond = NeutralCondition("sliding", ("sigma", "fr_inv"), dict(q=q, alpha_v=alpha_v, mu=mu), compiled=False)
    mp.mp.dps = 60
    for f in (1e-6, 1e-7):
        sigma = (1 - mu * q * q) / (1 + q) + mu * q * (1 + q) * f
        wk = 1 / (1 + q)
        ours = cond.other_modes_many(np.array([[sigma, f]]), np.array([wk]))[0]
        small = ours[np.argmin(np.abs(ours))]
        c = stability.get_model("sliding").coefficients(q=q, fr_inv=f, sigma=sigma, alpha_v=alpha_v, mu=mu)
        ref = [
            r
            for r in mp_polyroots([mp.mpc(complex(z)) for z in c], maxsteps=400, extraprec=400)
            if abs(r - 1j * wk) > 1e-3
        ]
        small_ref = min(ref, key=abs)
        re_ref = float(mp.re(small_ref))
        assert re_ref < 0
        assert abs(small.real / re_ref - 1) <= 20 * U * abs(small) / abs(re_ref), (f, small, re_ref)


# --- the numba disk cache of the per-model closures ---------------------------------------------

_CACHE_KEYS = """
import hashlib
from numba.core.serialize import dumps
import stability
from stability.jit import cached
from stability.linear import kernel, neutral_compiled
from stability.linear.neutrality import NeutralCondition
ks = kernel._model_kernels(stability.get_model("sliding"))
cond = NeutralCondition("sliding", ("q", "sigma"), dict(fr_inv=0.0, alpha_v=0.5, mu=2.28), compiled=True)
funcs = [*(cached(f, p) for f in (ks.checked, ks.masked) for p in (False, True)),
         *cond.kernels[2:], neutral_compiled.step_kernel(cond.kernels)]
for d in funcs:
    f = d.py_func
    cells = tuple(c.cell_contents for c in f.__closure__ or ())
    print(f.__qualname__, hashlib.sha256(dumps(cells)).hexdigest())
"""


def test_compiled_closures_have_the_same_cache_key_in_every_process():
    """The per-model compiled loops are closures over the model's formulas; numba keys their
    disk cache by a hash of the pickled captured values (numba.core.caching.Cache._index_key).
    If a closure captured an ``njit`` dispatcher (directly, or through a local helper function
    that refers to one), that pickle would differ in every process: each process would compile
    the kernel again (seconds) and the cache index would grow. Reference: the same hashes
    computed in two fresh processes (no compilation happens here)."""
    runs = [
        subprocess.run([sys.executable, "-c", _CACHE_KEYS], capture_output=True, text=True, check=True).stdout
        for _ in range(2)
    ]
    assert runs[0] == runs[1] and len(runs[0].splitlines()) == 8


# --- models added through the registry only ----------------------------------------------------


class PivotAtCentre(LinearModel):
    """Toy: a heavy symmetric top on a pivot at the sphere's centre O (h = q, eq. 9's form with
    the moments about O): ``Phi'' - i sigma Phi' - mu fr_inv q Phi = 0`` (A0 = 1). No optional
    capability. Closed form: ``s = i (sigma/2 +- sqrt(sigma^2/4 - mu fr_inv q))``, unstable
    where ``fr_inv > sigma^2 / (4 mu q)`` (q > 0)."""

    name = "toy_pivot_at_centre"
    equations = "toy (eq. 8 with the moments about O)"
    parameters = ("q", "fr_inv", "sigma", "mu")
    state = ("Phi", "dPhi_dt")
    n_modes = 2
    description = "toy: heavy top on a pivot at the sphere's centre"

    def matrices(self, *, q, fr_inv, sigma, mu):
        q, fr_inv, sigma, mu = np.broadcast_arrays(*(np.asarray(v, float) for v in (q, fr_inv, sigma, mu)))
        A = np.zeros(q.shape + (2, 2), dtype=complex)
        A[..., 0, 1] = 1.0
        A[..., 1, 0] = mu * fr_inv * q
        A[..., 1, 1] = 1j * sigma
        return np.broadcast_to(np.eye(2, dtype=complex), A.shape).copy(), A

    def coefficients(self, *, q, fr_inv, sigma, mu):
        q, fr_inv, sigma, mu = np.broadcast_arrays(*(np.asarray(v, float) for v in (q, fr_inv, sigma, mu)))
        c = np.zeros(q.shape + (3,), dtype=complex)
        c[..., 0] = 1.0
        c[..., 1] = -1j * sigma
        c[..., 2] = -mu * fr_inv * q
        return c


@register_jitable
def _free_top_parts(q, fr_inv, sigma, alpha_v, mu):
    """``A_G s^2 - i sigma s - mu q fr_inv`` (eq. 11 at alpha_v = 0 without its zero root, the
    free top of stability/models/sliding.py's docstring), as reals."""
    return (inertia_g(q, mu), 0.0, 0.0, -sigma, -mu * q * fr_inv, 0.0)


@register_jitable
def _free_top_derivatives(q, fr_inv, sigma, alpha_v, mu, k):
    if k == 0:
        return (-2.0 * mu * q, 0.0, 0.0, 0.0, -mu * fr_inv, 0.0)
    if k == 1:
        return (0.0, 0.0, 0.0, 0.0, -mu * q, 0.0)
    if k == 2:
        return (0.0, 0.0, 0.0, -1.0, 0.0, 0.0)
    if k == 4:
        return (-q * q, 0.0, 0.0, 0.0, -q * fr_inv, 0.0)
    return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


class FreeTop(LinearModel):
    """Toy: the frictionless top on its sphere, ``A_G s^2 - i sigma s - mu q fr_inv``; offers
    both optional capabilities. Closed form: ``s = i nu``, ``A_G nu^2 - sigma nu + mu q fr_inv
    = 0``; unstable where ``fr_inv > sigma^2 / (4 A_G mu q)`` (q > 0)."""

    name = "toy_free_top"
    equations = "toy (eq. 11 at alpha_v = 0)"
    parameters = ("q", "fr_inv", "sigma", "mu")
    state = ("Phi", "dPhi_dt")
    n_modes = 2
    description = "toy: frictionless top on its sphere"
    point_coefficients = staticmethod(_free_top_parts)
    point_derivatives = staticmethod(_free_top_derivatives)

    def matrices(self, *, q, fr_inv, sigma, mu):
        q, fr_inv, sigma, mu = np.broadcast_arrays(*(np.asarray(v, float) for v in (q, fr_inv, sigma, mu)))
        M = np.zeros(q.shape + (2, 2), dtype=complex)
        M[..., 0, 0] = 1.0
        M[..., 1, 1] = transverse_inertia_g(q, mu)
        A = np.zeros(q.shape + (2, 2), dtype=complex)
        A[..., 0, 1] = 1.0
        A[..., 1, 0] = mu * q * fr_inv
        A[..., 1, 1] = 1j * sigma
        return M, A

    def coefficients(self, *, q, fr_inv, sigma, mu):
        q, fr_inv, sigma, mu = np.broadcast_arrays(*(np.asarray(v, float) for v in (q, fr_inv, sigma, mu)))
        parts = _free_top_parts(q, fr_inv, sigma, 0.0, mu)
        c = np.empty(q.shape + (3,), dtype=complex)
        for j in range(3):
            c.real[..., j] = parts[2 * j]
            c.imag[..., j] = parts[2 * j + 1]
        return c


def _inertia(name: str, q, mu):
    """The moment ``I`` of the toy's closed form (``1``, or ``A_G = 1 - mu q^2``), in the type of
    its arguments (floats or mpmath numbers)."""
    return 1 - mu * q * q if name == FreeTop.name else 1 + 0 * q


TOYS = {PivotAtCentre.name: PivotAtCentre(), FreeTop.name: FreeTop()}


@pytest.fixture(params=sorted(TOYS))
def toy(request, monkeypatch):
    """The name of a toy model registered in stability.models.MODELS for the test only."""
    model = TOYS[request.param]
    monkeypatch.setitem(stability.models.MODELS, model.name, model)
    return model.name


def test_toy_model_spectra_through_the_registry(toy):
    """Spectra of a model registered at test time, by name, every method. Independent
    reference: the closed form ``s = i nu``, ``I nu^2 - sigma nu + mu q fr_inv = 0`` (``I = 1``
    or ``A_G``), in mpmath; within 1e-13 relative (the well-conditioned roots). A model that
    offers point_coefficients takes the fused compiled path, and that path gives the same bits
    as the kernel on the coefficients the model returns (engine agreement)."""
    name = toy
    p = random_domain_points(200, seed=48, alpha_v=False)
    model = stability.get_model(name)
    mp.mp.dps = 30
    for method in ("kernel", "polynomial", "lapack"):
        sp = stability.spectrum(name, method=method, **p)
        tol = 1e-13 if method != "lapack" else 1e-10
        for j in range(0, 200, 5):
            q, f, s, m = (mp.mpf(float(p[k][j])) for k in ("q", "fr_inv", "sigma", "mu"))
            i_ = _inertia(name, q, m)
            disc = mp.sqrt(mp.mpc(s**2 - 4 * i_ * m * q * f))
            ref = [1j * (s + sg * disc) / (2 * i_) for sg in (1, -1)]
            big = max(abs(r) for r in ref)
            for r in ref:
                err = min(float(abs(mp.mpc(complex(e)) - r)) for e in sp.eigenvalues[j])
                assert err <= tol * float(big) + 4 * sp.error_bound[j].max(), (name, method, j)
    assert kernel.accepts(model) == (model.point_coefficients is not None)
    if kernel.accepts(model):
        fused = stability.spectrum(name, **p)
        plain = kernel.coefficient_spectrum(model.coefficients(**p))
        for a, b in zip((fused.eigenvalues, fused.error_bound, fused.neutral, fused.stability), plain):
            np.testing.assert_array_equal(a, b)


def test_toy_model_thresholds_and_neutral_curves_through_the_registry(toy):
    """Thresholds and neutral curves of a model registered at test time. Independent reference:
    the closed-form collision ``sigma^2 = 4 I mu q fr_inv`` (``I = 1`` or ``A_G``): the threshold
    in fr_inv at q = 0.2, sigma = 1 to 1e-12 relative, and every point of the traced curve in
    the (q, fr_inv) plane on fr_inv = sigma^2 / (4 I mu q) to 1e-12 relative. A model with
    both formulas has its neutral condition's derivatives exact (no stencil)."""
    name = toy
    mu = 2.28
    thr = stability.threshold("fr_inv", model=name, q=0.2, sigma=1.0, bracket=(0.1, 5.0))
    assert thr == pytest.approx(1.0 / (4 * _inertia(name, 0.2, mu) * mu * 0.2), rel=1e-12)
    ds = neutral_curve(name, "q", "fr_inv", fixed=dict(sigma=1.0), x_range=(0.05, 0.6), y_range=(0.0, 3.0))
    assert ds.attrs["form"] == "collision" and ds.sizes["point"] > 10
    q, f = ds.q.values, ds.fr_inv.values
    ref = 1.0 / (4 * _inertia(name, q, mu) * mu * q)
    assert np.max(np.abs(f / ref - 1)) <= 1e-12
    cond = NeutralCondition(name, ("q", "fr_inv"), dict(sigma=1.0, mu=mu))
    assert cond._analytic == (stability.get_model(name).point_derivatives is not None)
