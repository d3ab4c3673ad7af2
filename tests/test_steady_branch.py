"""The branch of tilted steady states traced by continuation (stability.steady_branch).

References (independent of the traced branch, which solves the nonlinear model's right-hand
side with the continuation engine):

* the closed form of the family (S3)-(S6), stability.steady.family (1e-12);
* the full 8-component precessing-frame residual of the compiled rhs at the traced states
  (only one component is traced);
* eq. (11)'s thresholds and the Table 1 top's critical spin (stability.threshold(s),
  stability.critical_spin: the linear model and its own root finder) for the branch points
  (1e-10);
* the closed-form folds and the energy criterion for the events and the stability flags.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import stability
from stability.nonlinear import sliding
from stability.nonlinear.parameters import pack
from stability.steady import family
from stability.steady.branch import branch_points
from stability.steady.linearisation import ROTATION

MU = 2.28
#: (q, sigma, fr_inv): upright -> inverted (the paper's top); upright -> J_max (hangs);
#: inverted -> J_max with no fold (q > 0); inverted -> fold -> J_max (two never_inverts tops);
#: upright -> fold -> inverted (hysteresis type)
CASES = [
    (-0.1, 1.0, 0.3),
    (-0.3, 0.5, 0.1),
    (0.2, 0.7, 0.3),
    (-0.2, 1.3, 0.5),
    (-0.15, 1.12, 0.3),
    (-0.295, 1.107, 1.0 / MU),
]


@pytest.fixture(scope="module")
def branches():
    return {c: stability.steady_branch(q=c[0], sigma=c[1], fr_inv=c[2], alpha_v=0.5) for c in CASES}


@pytest.mark.parametrize("case", CASES)
def test_traced_branch_equals_the_closed_form(branches, case):
    """lam, J, E and the axial spin of every traced point against (S3)-(S5) at c = cos(tilt):
    1e-12 relative (measured <= 6e-14: the closed form itself loses ~u |sigma q / P| near c0,
    where the branch is cut)."""
    q, sigma, fr = case
    ds = branches[case]
    assert ds.sizes["point"] > 50
    c = np.cos(np.radians(ds.tilt.values))
    inner = ds.kind.values != "branch_point"
    lam = family.precession_rate(c, q=q, sigma=sigma, fr_inv=fr, mu=MU)
    J = lam * family.d_of_c(c, q, sigma, MU)
    E = family.effective_potential(c, J, q=q, sigma=sigma, fr_inv=fr, mu=MU)
    for got, ref in (
        (ds.precession_rate.values, lam),
        (ds.jellett.values, J),
        (ds.energy.values, E),
        (ds.axial_spin.values, lam * (c + q)),
    ):
        assert np.max(np.abs(got[inner] - ref[inner]) / np.abs(ref[inner])) < 1e-12


@pytest.mark.parametrize("case", CASES[:3])
def test_traced_states_solve_all_eight_equations(branches, case):
    """Only one component of F = f(y) - lam G y is traced; the other seven must vanish by the
    no-slip parametrisation: all eight at rounding, <= 1e-13 max(1, lam^2)."""
    q, sigma, fr = case
    ds = branches[case]
    p = pack(q=q, fr_inv=fr, sigma=sigma, mu=MU, alpha_v=0.5)
    y = family.state_vector(np.radians(ds.tilt.values), ds.precession_rate.values, q)
    for yi, lam in zip(y, ds.precession_rate.values):
        f = sliding.rhs(0.0, np.concatenate([yi, [0.0, 0.0]]), p)[:8] - lam * (ROTATION @ yi)
        assert np.max(np.abs(f)) <= 1e-13 * max(1.0, lam * lam)


def test_branch_points_are_eq11_thresholds():
    """The branch points located on the nonlinear rhs are where eq. (11) changes stability:
    with n = J / (sigma (1 +- q)), fr_inv / n^2 is the threshold in fr_inv of the upright
    (q) or inverted (-q) top (stability.thresholds: sampling, bisection and Newton on the
    neutral condition of the linear model). 1e-10 relative (measured ~1e-15)."""
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(12):
        q = rng.uniform(-0.4, 0.4)
        sigma = rng.uniform(0.1, 1.9 * (1 - MU * q * q))
        fr = rng.uniform(0.05, 1.5)
        bp = branch_points(q=q, sigma=sigma, fr_inv=fr, alpha_v=0.5)
        for orient, sgn in (("upright", 1.0), ("inverted", -1.0)):
            if not math.isfinite(bp[orient]):
                continue
            n = bp[orient] / (sigma * (1 + sgn * q))
            ths = stability.thresholds("fr_inv", q=sgn * q, sigma=sigma, alpha_v=0.5)
            assert len(ths) >= 1
            th = min(ths, key=lambda v: abs(v - fr / n**2))
            assert abs(th - fr / n**2) <= 1e-10 * th
            checked += 1
    assert checked >= 12


def test_branch_points_of_the_table1_top_are_its_critical_spins():
    """At the Table 1 top's critical spin (stability.critical_spin: fr_inv = 0.418 upright, 0.445
    inverted), the upright launch at spin 1 sits on the branch point: J_up = sigma (1 + q), and
    the inverted one J_inv = sigma (1 - q); 1e-10."""
    top = stability.Top.table1()
    for orient, sgn in (("upright", 1.0), ("inverted", -1.0)):
        cs = stability.critical_spin(top, orientation=orient)
        ds = stability.steady_branch(q=top.q, sigma=top.sigma, fr_inv=cs.fr_inv, alpha_v=0.5, mu=top.mu)
        bps = ds.where(ds.kind == "branch_point", drop=True)
        j = float(bps.jellett[np.argmin(np.abs(bps.tilt.values - (0.0 if sgn > 0 else 180.0)))])
        assert j == pytest.approx(top.sigma * (1 + sgn * top.q), rel=1e-10)


def test_ends_and_events(branches):
    """Ends: the paper's top joins the two branch points; a hanging top runs to |J| = jellett_max
    (10 x J_b by default), cut exactly. Folds where dJ/dc = 0 in closed form (c0 -+ sqrt(D(c0) /
    (3 a))) to 1e-10 in the cosine; there the flag is marginal and the energy test changes sign
    (S8); no other change of the flag (no "stability_change")."""
    paper = branches[CASES[0]]
    assert list(paper.kind.values[[0, -1]]) == ["branch_point", "branch_point"]
    assert float(paper.tilt[0]) == 0.0 and float(paper.tilt[-1]) == 180.0
    hang = branches[CASES[1]]
    assert str(hang.kind.values[-1]) == "end"
    assert float(hang.jellett[-1]) == pytest.approx(hang.attrs["jellett_max"], rel=1e-12)
    assert hang.attrs["jellett_max"] == pytest.approx(10 * float(hang.jellett[0]), rel=1e-12)
    for case in CASES:
        ds = branches[case]
        assert "stability_change" not in ds.kind.values
        folds = ds.where(ds.kind == "fold", drop=True)
        ref = [c for c in family.fold_cosines(case[0], case[1], MU) if -1 < c < 1]
        ref = [
            c for c in ref if float(np.cos(np.radians(ds.tilt.min()))) >= c >= float(np.cos(np.radians(ds.tilt.max())))
        ]
        assert folds.sizes["point"] == len(ref), case
        for c, f in zip(sorted(ref), sorted(np.cos(np.radians(folds.tilt.values)))):
            assert f == pytest.approx(c, abs=1e-10)
        assert np.all(folds.stability.values == 1)
        flags = ds.stability.values
        changes = np.nonzero(np.diff(flags))[0]
        for i in changes:  # every change of flag touches a marginal point (a fold or a branch point)
            assert 1 in (flags[i], flags[i + 1])
        decided = flags != 1
        assert np.array_equal(ds.stability_jacobian.values[decided], flags[decided])


def test_compiled_step_and_python_path_agree():
    """The engine's Python path and the problem's compiled step trace the same points (the same
    equations, the same operations): 1e-12."""
    a = stability.steady_branch(q=-0.15, sigma=1.12, fr_inv=0.3, alpha_v=0.5)
    b = stability.steady_branch(q=-0.15, sigma=1.12, fr_inv=0.3, alpha_v=0.5, compiled=False)
    assert a.sizes == b.sizes and list(a.kind.values) == list(b.kind.values)
    for name in ("tilt", "precession_rate", "jellett"):
        assert np.allclose(a[name].values, b[name].values, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("q,sigma,fr", [(-0.3, 0.5, 0.0), (0.0, 0.8, 0.3)])
def test_degenerate_family_is_a_vertical_line(q, sigma, fr):
    """fr_inv = 0 or q = 0: one tilt at every J (arccos c0; 90 degrees for q = 0), traced from
    jellett_max / 1000 to jellett_max; the tilt is constant to 1e-12 deg."""
    ds = stability.steady_branch(q=q, sigma=sigma, fr_inv=fr, alpha_v=0.5)
    ref = math.degrees(math.acos(family.c0(q, sigma, MU)))
    assert np.max(np.abs(ds.tilt.values - ref)) < 1e-12
    assert list(ds.kind.values[[0, -1]]) == ["end", "end"]
    assert float(ds.jellett[-1]) / float(ds.jellett[0]) == pytest.approx(1000.0, rel=1e-9)


def test_no_family_gives_an_empty_branch_with_a_note():
    """q = 0 and sigma = A_G = 1: every tilt is steady (a dynamically spherical ball); no line."""
    ds = stability.steady_branch(q=0.0, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    assert ds.sizes["point"] == 0 and "note" in ds.attrs


def test_branch_dataset_attributes(branches):
    ds = branches[CASES[0]]
    assert ds.attrs["tippe_stability_product"] == "steady_branch"
    assert ds.attrs["start"] == "upright" and ds.tilt.attrs["units"] == "degree"
    assert set(np.unique(ds.kind.values)) <= {"regular", "branch_point", "fold", "stability_change", "end"}
    assert ds.stability.attrs["flag_meanings"] == "stable marginal unstable"


@pytest.mark.parametrize(
    "kw,exc,fragment",
    [
        (dict(max_step=0.0), ValueError, "max_step = 0 is outside the allowed range: 0.0001 <= max_step"),
        (dict(jellett_max=-1.0), ValueError, "jellett_max = -1 is outside the allowed range"),
        (dict(jellett_max=0.5), ValueError, "jellett_max = 0.5 is outside the allowed range: jellett_max > 0.762438"),
        (dict(model="rolling"), ValueError, "model = 'rolling' is not known; choose one of sliding"),
        (dict(q=0.9), ValueError, "q = 0.9 is outside the physical domain"),
        (dict(alpha_v=None), TypeError, "alpha_v is required"),
        (dict(compiled="yes"), TypeError, "compiled = 'yes' is a str"),
    ],
)
def test_bad_input(kw, exc, fragment):
    args = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    args.update(kw)
    with pytest.raises(exc, match=fragment):
        stability.steady_branch(**args)
