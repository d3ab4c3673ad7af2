"""Threshold queries and the critical spin against closed forms evaluated with mpmath.

References (derived in tests/test_neutral.py's docstring and stability/linear/critical.py):
sliding model, ``sigma_n = (1 - mu q^2)/(1 + q) + mu q (1 + q) fr_inv`` for any alpha_v > 0;
eq. (8), ``sigma_c^2 = 4 A_C mu fr_inv h``. Each is evaluated at 40 digits. Tolerance: the
threshold is the root of the neutral condition at a relative backward error ~1e-16; with O(1)
condition numbers here, 8 ulp (relative 2e-15) bounds it, absolute 1e-15 near zero.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

import stability
from stability import critical_spin, threshold, threshold_crossings, thresholds
from stability.cli import main
from stability.errors import DomainError

mp = mpmath.mp
MU = mpmath.mpf("2.28")


def close(value, ref, rel=2e-15, abs_=1e-15):
    return abs(value - float(ref)) <= max(rel * abs(float(ref)), abs_)


@pytest.mark.parametrize("q", [-0.3, -0.1, 0.2])
def test_sigma_threshold_at_fr_inv_0(q):
    mp.dps = 40
    qm = mpmath.mpf(q)
    ref = (1 - MU * qm * qm) / (1 + qm)
    assert close(threshold("sigma", q=q, fr_inv=0.0, alpha_v=0.5), ref)


@pytest.mark.parametrize("q, sigma", [(-0.1, 1.0), (0.1, 1.0), (-0.2, 0.95)])
def test_fr_inv_threshold(q, sigma):
    mp.dps = 40
    qm, sm = mpmath.mpf(q), mpmath.mpf(sigma)
    ref = (sm - (1 - MU * qm * qm) / (1 + qm)) / (MU * qm * (1 + qm))
    found = threshold_crossings("fr_inv", q=q, sigma=sigma, alpha_v=0.5)
    # the root's condition number for a normwise backward error of the coefficients:
    # kappa = ||c||_1 max(1, |w|)^3 / (|dp/dfr_inv| |fr_inv|), dp/dfr_inv = -mu^2 q (i w) - mu alpha_v q
    # (the numerator sigma - (1 - mu q^2)/(1 + q) cancels, so kappa ~ 10-50 here); allow 8 u kappa
    w, a = 1 / (1 + qm), mpmath.mpf("0.5")
    c = [
        MU * (1 - MU * qm * qm),
        a * (1 + MU * (1 + 2 * qm)) - 1j * MU * sm,
        -MU * MU * qm * ref - 1j * a * (sm + MU * (1 + qm)),
        -MU * a * qm * ref,
    ]
    kappa = sum(abs(x) for x in c) * max(1, w) ** 3 / (abs(-(MU**2) * qm * 1j * w - MU * a * qm) * ref)
    assert len(found) == 1
    assert abs(found[0].value - float(ref)) <= 8 * 2.0**-53 * float(kappa) * float(ref)
    assert close(found[0].frequency, 1 / (1 + qm))  # the slip-free frequency 1/(1+q)


def test_return_details_is_deprecated_and_still_works():
    """``thresholds(return_details=...)`` warns (DeprecationWarning, naming threshold_crossings)
    and returns what it returned before: with True the records (the threshold at fr_inv = 0 is
    sigma = (1 - mu q^2)/(1 + q), closed form at 40 digits; its neutral frequency the slip-free
    1/(1 + q)), with False the values. Without the keyword: no warning."""
    import warnings

    mp.dps = 40
    qm = mpmath.mpf("-0.1")
    ref = (1 - MU * qm * qm) / (1 + qm)
    kw = dict(q=-0.1, fr_inv=0.0, alpha_v=0.5)
    with pytest.warns(DeprecationWarning, match="threshold_crossings"):
        (t,) = thresholds("sigma", return_details=True, **kw)
    assert close(t.value, ref) and close(t.frequency, 1 / (1 + qm)) and t.unstable_side == "below"
    with pytest.warns(DeprecationWarning, match="return_details"):
        (v,) = thresholds("sigma", return_details=False, **kw)
    assert close(v, ref)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert close(thresholds("sigma", **kw)[0], ref)


def test_all_q_thresholds_sorted():
    """At fr_inv = 0, sigma (1 + q) = 1 - mu q^2: two roots in the domain for sigma = 1.1."""
    mp.dps = 40
    s = mpmath.mpf("1.1")
    disc = mp.sqrt(s * s - 4 * MU * (s - 1))
    refs = sorted([(-s - disc) / (2 * MU), (-s + disc) / (2 * MU)])
    got = thresholds("q", fr_inv=0.0, sigma=1.1, alpha_v=0.5)
    assert len(got) == 2 and all(close(g, r) for g, r in zip(got, refs))
    assert np.all(np.diff(got) > 0)


@pytest.mark.parametrize("model, q, f", [("rolling_eq8", 0.1, 0.3), ("fixed_pivot", -0.1, 0.05)])
def test_second_order_models_discriminant(model, q, f):
    mp.dps = 40
    qm, fm = mpmath.mpf(q), mpmath.mpf(f)
    h = qm if model == "rolling_eq8" else 1 + qm
    ref = mp.sqrt(4 * (1 + MU * (1 + 2 * qm)) * MU * fm * h)
    found = threshold_crossings("sigma", model=model, q=q, fr_inv=f)
    assert len(found) == 1 and close(found[0].value, ref)
    assert found[0].unstable_side == "below"


def test_threshold_errors():
    with pytest.raises(ValueError, match=r"marginal \(neutrally stable\) throughout sigma in \[1\.2, 1\.5\]"):
        threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5, bracket=(1.2, 1.5))
    with pytest.raises(ValueError, match=r"2 thresholds in q .*-0\.2854.*stability\.thresholds"):
        threshold("q", fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    with pytest.raises(ValueError, match="not a parameter"):
        threshold("alpha_k", q=0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    with pytest.raises(TypeError, match="sigma"):
        threshold("q", fr_inv=0.3, alpha_v=0.5)
    with pytest.raises(TypeError, match="cannot also be given"):
        threshold("q", q=0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    with pytest.raises(ValueError, match="lo < hi"):
        threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5, bracket=(1.5, 1.2))
    with pytest.raises(ValueError, match=r"sigma = 1\.99 is outside the physical domain"):
        threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5, bracket=(1.0, 1.99))
    with pytest.raises(ValueError, match=r"alpha_v = -1 .*alpha_v >= 0"):
        threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=-1.0)


def _fr_inv_closed(q, sigma):
    mp.dps = 40
    q, s, mu = mpmath.mpf(q), mpmath.mpf(sigma), mpmath.mpf(2.28)
    return (s - (1 - mu * q * q) / (1 + q)) / (mu * q * (1 + q))


def test_critical_spin_of_the_papers_top():
    top = stability.Top.table1()
    up = critical_spin(top)
    f = _fr_inv_closed(top.q, top.sigma)
    omega = mp.sqrt(mpmath.mpf(top.g) / (mpmath.mpf(top.radius) * f))
    # top.q, top.mu are the floats of -0.1, 2.28 up to rounding in the SI round trip (~1e-15)
    assert math.isclose(up.spin, float(omega), rel_tol=1e-13)
    assert up.unstable_above and math.isclose(up.rpm, up.spin * 60 / (2 * math.pi), rel_tol=1e-15)
    inv = critical_spin(top, orientation="inverted")
    f_inv = _fr_inv_closed(-top.q, top.sigma)
    assert math.isclose(inv.fr_inv, float(f_inv), rel_tol=1e-13) and not inv.unstable_above
    # the paper's runs: unstable at 7.15 rev/s (fr_inv 0.3) and 12.4 rev/s (fr_inv 0.1)
    assert up.spin < 7.15 * 2 * math.pi


def test_critical_spin_does_not_depend_on_viscous_friction():
    """alpha_v = mu mu_v g / Omega varies with the spin; the neutral set does not depend on it."""
    a = critical_spin(stability.Top.table1())
    b = critical_spin(stability.Top.table1(mu_v=0.3))
    assert math.isclose(a.spin, b.spin, rel_tol=1e-13)
    assert b.alpha_v == pytest.approx(2.28 * 0.3 * 9.80665 / b.spin, rel=1e-12)


def test_critical_spin_errors():
    with pytest.raises(ValueError, match="orientation"):
        critical_spin(stability.Top.table1(), orientation="sideways")
    with pytest.raises(TypeError, match="stability.Top"):
        critical_spin({"q": -0.1})
    # sigma above the fr_inv = 0 fold (1.1433) with q < 0: stable at every spin
    top = stability.Top.from_nondimensional(mass=0.02, radius=0.016, q=-0.1, mu=2.28, sigma=1.5)
    with pytest.raises(ValueError, match="upright sliding top is not unstable .* at every spin"):
        critical_spin(top)


def test_cli(capsys):
    assert main(["threshold", "spin", "--preset", "table1"]) == 0
    out = capsys.readouterr().out
    assert "upright: unstable above 38.09" in out and "inverted: stable above" in out and "rpm" in out
    assert main(["threshold", "sigma", "--q", "-0.1", "--fr-inv", "0", "--alpha-v", "0.5"]) == 0
    assert capsys.readouterr().out.startswith("sigma = 1.08577777777777")
    assert main(["threshold", "spin", "--mass", "1"]) == 2
    assert "--mass given without --radius" in capsys.readouterr().err


def test_cli_neutral(tmp_path, capsys):
    out = tmp_path / "c.nc"
    assert (
        main(
            [
                "neutral",
                "--model",
                "sliding",
                "--x",
                "q",
                "--y",
                "sigma",
                "--fr-inv",
                "0",
                "--alpha-v",
                "0.5",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "fold" in text and "1.1433349593" in text and out.exists()
    assert main(["neutral", "--x", "q", "--y", "sigma", "--fr-inv", "0"]) == 2
    assert "give --alpha-v" in capsys.readouterr().err


def test_threshold_at_the_domain_edge_is_the_edge():
    """q = -0.1, fr_inv = 0.3, sigma = 1: the frictionless top (alpha_v = 0) is marginal (its
    spectrum lies on the imaginary axis: eq. 11 without friction is conservative) and any
    viscous friction destabilises it (growth rate ~1.7e-2 alpha_v for small alpha_v, docs/
    hard_cases.md: 1.686e-8 at 1e-6). The stability change is at the edge alpha_v = 0 itself;
    Newton used to land a rounding error outside it (alpha_v = -2.2e-27). The answer must be
    exactly 0, inside the domain.

    There is no neutral point at alpha_v > 0 for Newton to find (the neutral surface does not
    pass through this (q, fr_inv, sigma)), and the growth rate's sign is decided (structured
    estimate) only down to alpha_v ~ 1e-45, not to 0: the record is the honest interval
    [0, upper] with exact = False, the value its end on the domain's edge, and threshold()
    says so with a warning."""
    sp0 = stability.spectrum("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.0)
    assert int(sp0.stability) == 1
    for a in (1e-12, 1e-6, 1e-2):
        assert int(stability.spectrum("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=a).stability) == 2
    with pytest.warns(UserWarning, match=r"known only to an interval.*\[0.0, "):
        assert stability.threshold("alpha_v", q=-0.1, fr_inv=0.3, sigma=1.0) == 0.0
    (t,) = threshold_crossings("alpha_v", q=-0.1, fr_inv=0.3, sigma=1.0)
    assert (t.value, t.lower, t.exact, t.unstable_side) == (0.0, 0.0, False, "above")
    assert 0.0 < t.upper < 1e-30


def test_bracket_outside_the_domain_names_the_end_not_a_grid_option():
    with pytest.raises(DomainError, match=r"bracket = \(0.5, 2.5\) leaves the physical domain: sigma = 2.5") as exc:
        stability.threshold("sigma", q=-0.1, fr_inv=0.0, alpha_v=0.5, bracket=(0.5, 2.5))
    assert "mask_unphysical" not in str(exc.value)


@pytest.mark.parametrize(
    "argv, names",
    [
        (
            ["spin", "--preset", "table1", "--mass", "5", "--radius", "1"],
            "--preset table1 and --mass, --radius conflict",
        ),
        (
            ["spin", "--preset", "table1", "--q", "0.3", "--sigma", "1.5"],
            "--q, --sigma: not used by 'tippe threshold spin'",
        ),
        (["spin", "--preset", "table1", "--bracket", "0:1"], "--bracket: not used"),
        (
            ["sigma", "--q", "-0.1", "--fr-inv", "0", "--alpha-v", "0.5", "--mass", "3"],
            "--mass: only used with PARAM = spin",
        ),
        (
            ["sigma", "--q", "-0.1", "--fr-inv", "0", "--alpha-v", "0.5", "--orientation", "upright"],
            "--orientation: only used with PARAM = spin",
        ),
    ],
)
def test_threshold_cli_refuses_options_it_would_ignore(argv, names, capsys):
    """An option the chosen PARAM does not use is an error (exit 2, one line naming it): before,
    `--preset table1 --mass 5` printed the preset's critical spin as if --mass were not there."""
    assert main(["threshold", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and names in err


def test_critical_spin_both_orientations():
    """orientation="both" (the CLI's default) answers for the two orientations at once.
    Reference: the closed form of the neutral curve at the no-slip frequency (see
    _fr_inv_closed), for q and -q."""
    top = stability.Top.table1()
    both = critical_spin(top, orientation="both")
    assert both.reasons == {}
    assert both.upright.orientation == "upright" and both.inverted.orientation == "inverted"
    assert math.isclose(both.upright.fr_inv, float(_fr_inv_closed(top.q, top.sigma)), rel_tol=1e-13)
    assert math.isclose(both.inverted.fr_inv, float(_fr_inv_closed(-top.q, top.sigma)), rel_tol=1e-13)
    assert both.upright.unstable_above and not both.inverted.unstable_above
    # sigma = 1.5: the upright top is stable at every spin (test_critical_spin_errors); the
    # inverted one (q = +0.1) changes at fr_inv = 2.4387 by the same closed form
    t2 = stability.Top.from_nondimensional(mass=0.02, radius=0.016, q=-0.1, mu=2.28, sigma=1.5)
    r = critical_spin(t2, orientation="both")
    assert r.upright is None and "upright sliding top is not unstable" in r.reasons["upright"]
    assert math.isclose(r.inverted.fr_inv, float(_fr_inv_closed(0.1, 1.5)), rel_tol=1e-13)
