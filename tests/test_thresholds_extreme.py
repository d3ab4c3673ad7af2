"""Thresholds and critical spins over alpha_v in [1e-12, 1e12] (issue 13, item 1).

The references are closed forms of the sliding model's neutral surface (eq. 11), evaluated with
mpmath at 40 digits, and mpmath's roots of eq. 11's characteristic polynomial (60 digits).

Derivation of the closed forms. Eq. 11 gives ``mu det(s M - A) = c3 s^3 + c2 s^2 + c1 s + c0``
with ``c3 = mu A_G``, ``c2 = alpha_v A_C - i mu sigma``, ``c1 = -mu^2 q fr_inv - i alpha_v
(sigma + mu (1 + q))``, ``c0 = -mu alpha_v q fr_inv`` (``A_G = 1 - mu q^2``, ``A_C = 1 + mu (1 +
2 q)``). At ``s = i w``::

    p(i w) = alpha_v [-A_C w^2 + (sigma + mu (1 + q)) w - mu q fr_inv]
             + i mu w [-A_G w^2 + sigma w - mu q fr_inv]

so for ``alpha_v > 0`` both brackets vanish. Their difference ``(A_C - A_G) w^2 - mu (1 + q) w
= mu (1 + q) w ((1 + q) w - 1)`` vanishes for ``w = 1/(1 + q)`` (the slip-free frequency; ``w =
0`` would need ``q fr_inv = 0``), and the second bracket at that ``w`` gives the neutral surface

    sigma_n = (1 - mu q^2)/(1 + q) + mu q (1 + q) fr_inv,

independent of ``alpha_v``: the sigma threshold is ``sigma_n``, the fr_inv threshold
``(sigma - (1 - mu q^2)/(1 + q)) / (mu q (1 + q))``, and the q thresholds are the roots in the
domain of the cubic ``sigma (1 + q) - (1 - mu q^2) - mu q (1 + q)^2 fr_inv`` (at ``sigma = 1``:
``q = 0`` and the roots of ``mu fr_inv (1 + q)^2 - mu q - 1``). The neutral frequency is
``1/(1 + q)`` in every case.

Why these tests: near a crossing at small or large ``alpha_v`` the crossing mode's growth rate
is tiny beside the spectrum's scale (``~0.3 alpha_v (sigma - sigma_n)`` at small alpha_v,
``O(1/alpha_v)`` beside a slip mode ``-1.3 alpha_v`` at large alpha_v), and the stability flag's
marginal floor made the old bisection return the floor's edge (sigma = 1.01202 instead of
1.0242178 at alpha_v = 1e-12; 393 rpm instead of 363.7 for the Table 1 top).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

import stability
from stability import critical_spin, threshold, threshold_crossings
from stability.linear.growth import growth
from stability.linear.spectra import STABLE, UNSTABLE

mp = mpmath.mp
MU = mpmath.mpf("2.28")
U = 2.0**-53

ALPHA_V = [float(a) for a in np.logspace(-12, 12, 9)]


def _sigma_n(q, fr_inv):
    mp.dps = 40
    q, f = mpmath.mpf(q), mpmath.mpf(fr_inv)
    return (1 - MU * q * q) / (1 + q) + MU * q * (1 + q) * f


def _max_growth(q, fr_inv, sigma, alpha_v):
    """Largest Re s of eq. 11 (mpmath.polyroots at 60 digits of the exact coefficients of the
    doubles given)."""
    mp.dps = 60
    q, f, s, a = (mpmath.mpf(v) for v in (q, fr_inv, sigma, alpha_v))
    a_g, a_c = 1 - MU * q * q, 1 + MU * (1 + 2 * q)
    c = [MU * a_g, a * a_c - 1j * MU * s, -MU * MU * q * f - 1j * a * (s + MU * (1 + q)), -MU * a * q * f]
    roots = mpmath.polyroots(c[::-1], maxsteps=400, extraprec=400, asc=True)
    return max(mpmath.re(r) for r in roots)


@pytest.mark.parametrize("alpha_v", ALPHA_V)
def test_sigma_threshold_is_the_neutral_surface_at_every_alpha_v(alpha_v):
    """sigma threshold at q = -0.1, fr_inv = 0.3 is sigma_n = 1.0242177777... for every
    alpha_v. Tolerance 8 ulp: the root of the neutral condition to a backward error ~u, with a
    condition number O(1) here (sigma enters only the coefficient mu sigma and alpha_v sigma)."""
    ref = _sigma_n(-0.1, 0.3)
    (t,) = threshold_crossings("sigma", q=-0.1, fr_inv=0.3, alpha_v=alpha_v)
    assert t.exact and t.lower == t.upper == t.value
    assert abs(t.value - float(ref)) <= 8 * U * float(ref)
    assert abs(t.frequency - 1 / 0.9) <= 8 * U / 0.9
    assert t.unstable_side == "below"
    assert threshold("sigma", q=-0.1, fr_inv=0.3, alpha_v=alpha_v) == t.value


@pytest.mark.parametrize("alpha_v", ALPHA_V)
def test_fr_inv_threshold_at_every_alpha_v(alpha_v):
    """fr_inv threshold at q = -0.1, sigma = 1 (closed form of the module docstring). The
    numerator sigma - (1 - mu q^2)/(1 + q) cancels: the condition number of the root for a
    normwise relative backward error of the coefficients is
    kappa = ||c||_1 max(1, w)^3 / (|dp/dfr_inv| fr_inv) (~27 at small alpha_v); 8 u kappa."""
    mp.dps = 40
    q, s, a = mpmath.mpf("-0.1"), mpmath.mpf(1), mpmath.mpf(alpha_v)
    ref = (s - (1 - MU * q * q) / (1 + q)) / (MU * q * (1 + q))
    w = 1 / (1 + q)
    c = [
        MU * (1 - MU * q * q),
        a * (1 + MU * (1 + 2 * q)) - 1j * MU * s,
        -MU * MU * q * ref - 1j * a * (s + MU * (1 + q)),
        -MU * a * q * ref,
    ]
    kappa = sum(abs(x) for x in c) * w**3 / (abs(-(MU**2) * q * 1j * w - MU * a * q) * ref)
    (t,) = threshold_crossings("fr_inv", q=-0.1, sigma=1.0, alpha_v=alpha_v)
    assert t.exact
    assert abs(t.value - float(ref)) <= 8 * U * float(kappa) * float(ref)
    assert abs(t.frequency - float(w)) <= 8 * U * float(w)


@pytest.mark.parametrize("alpha_v", ALPHA_V)
def test_q_thresholds_at_every_alpha_v(alpha_v):
    """q thresholds at fr_inv = 0.3, sigma = 1: q = 0 and the root in the domain of
    mu fr_inv (1 + q)^2 - mu q - 1 (the other root, q = 2.19, is outside |q| < 1/sqrt(mu)).
    Absolute 8 u: both roots are simple, O(1) conditioned."""
    mp.dps = 40
    f = mpmath.mpf("0.3")
    # mu f q^2 + (2 mu f - mu) q + (mu f - 1) = 0
    a2, a1, a0 = MU * f, 2 * MU * f - MU, MU * f - 1
    disc = mp.sqrt(a1 * a1 - 4 * a2 * a0)
    roots = sorted(r for r in ((-a1 - disc) / (2 * a2), (-a1 + disc) / (2 * a2)) if abs(r) < 1 / mp.sqrt(MU))
    refs = sorted(roots + [mpmath.mpf(0)])
    found = threshold_crossings("q", fr_inv=0.3, sigma=1.0, alpha_v=alpha_v)
    assert len(found) == 2 and all(t.exact for t in found)
    for t, r in zip(found, refs):
        assert abs(t.value - float(r)) <= 8 * U
        assert abs(t.frequency - 1 / (1 + t.value)) <= 8 * U * 2  # w = 1/(1 + q) at the q found


@pytest.mark.parametrize("alpha_v", [1e-12, 1e-6, 1e6, 1e12])
def test_signs_on_either_side_agree_with_mpmath(alpha_v):
    """A relative step of 1e-9 either side of the threshold: the largest growth rate from mpmath's
    roots (60 digits) is positive below and negative above, and the structured signs that the
    threshold search bisects on (stability.linear.growth) say the same. At alpha_v = 1e-12 the
    growth rate there is ~3e-22, far inside the atlas flag's marginal floor."""
    t = threshold("sigma", q=-0.1, fr_inv=0.3, alpha_v=alpha_v)
    below, above = t * (1 - 1e-9), t * (1 + 1e-9)
    assert _max_growth(-0.1, 0.3, below, alpha_v) > 0
    assert _max_growth(-0.1, 0.3, above, alpha_v) < 0
    gr = growth("sliding", q=-0.1, fr_inv=0.3, alpha_v=alpha_v, sigma=np.array([below, above]))
    assert list(gr.state) == [UNSTABLE, STABLE]


@pytest.mark.parametrize("alpha_v", ALPHA_V)
def test_critical_spin_of_table1_top_at_every_alpha_v(alpha_v):
    """The Table 1 top's critical spin, 38.0900414 rad/s (363.7 rpm), for every fixed alpha_v
    (the neutral surface does not depend on it). Reference: the fr_inv closed form at the top's
    (q, sigma) to 40 digits, Omega = sqrt(g / (R fr_inv)); the top's q and mu are the floats of
    -0.1 and 2.28 up to the SI round trip (~1e-15), so 1e-13 relative."""
    top = stability.Top.table1()
    mp.dps = 40
    q, s = mpmath.mpf(top.q), mpmath.mpf(top.sigma)
    mu = mpmath.mpf(top.mu)
    f = (s - (1 - mu * q * q) / (1 + q)) / (mu * q * (1 + q))
    omega = float(mp.sqrt(mpmath.mpf(top.g) / (mpmath.mpf(top.radius) * f)))
    c = critical_spin(top, alpha_v=alpha_v)
    assert c.exact and c.unstable_above
    assert math.isclose(c.spin, omega, rel_tol=1e-13)
    assert abs(c.spin - 38.0900414) <= 5e-8  # the printed digits
    assert c.spin_interval[0] == pytest.approx(c.spin, rel=1e-15)


@pytest.mark.parametrize("alpha_v", [1e-12, 1e12])
@pytest.mark.parametrize("delta", [1e-6, 1e-9])
def test_fold_pair_at_extreme_alpha_v(alpha_v, delta):
    """Two q thresholds closer than the sampling step near the fold of the fr_inv = 0 neutral
    curve sigma (1 + q) = 1 - mu q^2 (tests/test_hard_continuation.py does alpha_v = 0.5): the
    fold is at the double root, discriminant sigma^2 - 4 mu (sigma - 1) = 0, i.e.
    sigma* = 2 (mu - sqrt(mu (mu - 1))); at sigma* - delta the pair is ~2 sqrt(delta / 3) apart.
    At alpha_v = 1e-12 and 1e12 the growth rates between them are ~1e-12 delta and ~delta/1e12,
    hidden by the atlas flag's floor: the structured estimate must see them. Reference: the
    roots of mu q^2 + sigma q + sigma - 1 (mpmath, 40 digits); tolerance 16 u / d + 4 u, d the
    discriminant's square root (a backward error u in sigma moves a root by ~u (1 + q) / d)."""
    mp.dps = 40
    star = 2 * (MU - mp.sqrt(MU * (MU - 1)))
    s = float(star) - delta
    sm = mpmath.mpf(s)
    d = mp.sqrt(sm * sm - 4 * MU * (sm - 1))
    refs = sorted([(-sm - d) / (2 * MU), (-sm + d) / (2 * MU)])
    got = threshold_crossings("q", fr_inv=0.0, sigma=s, alpha_v=alpha_v)
    assert len(got) == 2 and all(g.exact for g in got)
    tol = 16 * U / float(d) + 4 * U
    for g, r in zip(got, refs):
        assert abs(g.value - float(r)) <= tol
    assert [g.unstable_side for g in got] == ["above", "below"]


@pytest.mark.parametrize("model, q, f", [("rolling_eq8", 0.1, 0.3), ("fixed_pivot", -0.1, 0.05)])
def test_collision_models_keep_their_form(model, q, f):
    """The conservative models (eq. 8) cross by a collision of two neutral modes; the
    threshold is the discriminant's root sigma_c^2 = 4 A_C mu fr_inv h (h = q rolling, 1 + q
    fixed pivot) at 40 digits, exact, to 8 ulp (the collision form P = P' = 0 has no
    dissipative row to scale: the row-scaled crossing form is for dissipative models only)."""
    mp.dps = 40
    qm, fm = mpmath.mpf(q), mpmath.mpf(f)
    h = qm if model == "rolling_eq8" else 1 + qm
    ref = mp.sqrt(4 * (1 + MU * (1 + 2 * qm)) * MU * fm * h)
    (t,) = threshold_crossings("sigma", model=model, q=q, fr_inv=f)
    assert t.exact and abs(t.value - float(ref)) <= 8 * U * float(ref)
    assert math.isfinite(t.frequency)


def test_cli_prints_an_interval_and_says_it_is_one(capsys):
    """The threshold in alpha_v at (q, fr_inv, sigma) = (-0.1, 0.3, 1) is the domain's edge
    alpha_v = 0 (every viscous friction destabilises; tests/test_thresholds.py): the sign of the
    growth rate ~1.7e-2 alpha_v is decided only down to alpha_v ~ 1e-40, so the answer is an
    interval [0, upper], and the CLI prints both ends and says so. An exact threshold (sigma at
    alpha_v = 1e-12, the closed form 1.0242177777...) prints no interval."""
    from stability.cli import main

    assert main(["threshold", "alpha_v", "--q", "-0.1", "--fr-inv", "0.3", "--sigma", "1.0"]) == 0
    out = capsys.readouterr().out
    assert "alpha_v = 0\n" in out and "an interval, not a value" in out and "[0.0, " in out
    assert main(["threshold", "sigma", "--q", "-0.1", "--fr-inv", "0.3", "--alpha-v", "1e-12"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("sigma = 1.02421777777777") and "interval" not in out
