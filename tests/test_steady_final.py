"""Where the top goes: final_state by Jellett's integral against long nonlinear runs, and the
stability flags against perturbed runs.

References: the nonlinear runs of stability.simulate (compiled DOPRI5 on the sliding sphere's
full equations), independent of the closed forms and the energy argument behind final_state.

Long runs. Thirteen tops and initial states over the three high-spin classes, q of both signs,
fr_inv from 0 to 1, alpha_v 0.5 and 1: tops that stay upright (4), invert completely (2) and
stop at a tilt (7), one of them the paper's Fr^-1 = 0.3 run of Sec. 3(ii). Each is one
simulate call at the default rtol 1e-9 of length t_end = 1.15 x the time after which a long
run (rtol 1e-10, until settled; measured once, when the feature was derived) stays within 0.01
degree of the prediction: measured error <= 6.1e-3 degree here; required 0.05 degree (the
issue's), so the test has an 8-fold margin for other platforms' rounding. About 3 s in all.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import stability
from stability.nonlinear.scene import INITIAL_CONDITIONS
from stability.steady import family


def tilted_start(theta_deg, spin=1.0, transverse=0.0, velocity=(0.0, 0.0)):
    """Axis at ``theta_deg`` from the vertical (azimuth 0), ``omega = spin k + transverse e_theta``."""
    t = math.radians(theta_deg)
    k = np.array([math.sin(t), 0.0, math.cos(t)])
    e = np.array([math.cos(t), 0.0, -math.sin(t)])
    return dict(omega=list(spin * k + transverse * e), k=list(k), velocity=list(velocity))


PAPER = dict(q=-0.1, sigma=1.0, alpha_v=0.5)
#: (name, parameters, initial state, expected kind, t_end)
LONG_RUNS = [
    ("paper Fr^-1 = 0.3, printed state: hangs", dict(PAPER, fr_inv=0.3), INITIAL_CONDITIONS[0.3], "tilted", 15600),
    ("paper Fr^-1 = 0.1, printed state: inverts", dict(PAPER, fr_inv=0.1), INITIAL_CONDITIONS[0.1], "inverted", 22000),
    ("paper top, slow spin: stays upright", dict(PAPER, fr_inv=0.6), tilted_start(8.0, 1.0, 0.02), "upright", 1300),
    ("hangs class q=-0.3 s=0.5", dict(q=-0.3, sigma=0.5, fr_inv=0.1, alpha_v=0.5), tilted_start(3.0), "tilted", 15000),
    (
        "hangs class, alpha_v = 1",
        dict(q=-0.2, sigma=0.6, fr_inv=0.3, alpha_v=1.0),
        tilted_start(10.0, 1.2, -0.03),
        "tilted",
        5600,
    ),
    (
        "inverts class at finite spin: hangs",
        dict(q=-0.3, sigma=0.7, fr_inv=0.2, alpha_v=0.5),
        tilted_start(5.0),
        "tilted",
        6200,
    ),
    (
        "never_inverts, G above O: stays upright",
        dict(q=0.2, sigma=1.0, fr_inv=0.3, alpha_v=0.5),
        tilted_start(15.0, 1.0, 0.03),
        "upright",
        1400,
    ),
    ("hangs, G above O", dict(q=0.3, sigma=0.9, fr_inv=0.5, alpha_v=0.5), tilted_start(5.0), "tilted", 400),
    (
        "inverts class, spin 1.5: hangs at 37.5 deg",
        dict(q=-0.25, sigma=0.9, fr_inv=1.0, alpha_v=0.5),
        tilted_start(5.0, 1.5),
        "tilted",
        800,
    ),
    (
        "paper top clockwise from 60 deg: back upright",
        dict(PAPER, fr_inv=0.3),
        tilted_start(60.0, -1.0, 0.1, (0.0, 0.05)),
        "upright",
        2200,
    ),
    ("paper top started inverted, slow: falls upright", dict(PAPER, fr_inv=1.0), tilted_start(175.0), "upright", 900),
    (
        "inverts class, fast: inverts",
        dict(q=-0.3, sigma=0.7, fr_inv=0.02, alpha_v=0.5),
        tilted_start(5.0),
        "inverted",
        34800,
    ),
    ("fr_inv = 0, hangs at c0", dict(q=-0.3, sigma=0.5, fr_inv=0.0, alpha_v=0.5), tilted_start(5.0), "tilted", 18800),
]


def test_the_cases_cover_the_three_classes():
    classes = {stability.top_class(q=p["q"], sigma=p["sigma"]) for _, p, *_ in LONG_RUNS}
    assert classes == {"never_inverts", "inverts", "hangs"}
    kinds = [k for *_, k, _ in LONG_RUNS]
    assert kinds.count("upright") >= 3 and kinds.count("tilted") >= 5 and kinds.count("inverted") >= 2


@pytest.mark.parametrize("name,params,start,kind,t_end", LONG_RUNS, ids=[c[0] for c in LONG_RUNS])
def test_long_run_ends_at_the_predicted_tilt(name, params, start, kind, t_end):
    pred = stability.final_state(**params, **start)
    assert pred.method == "jellett" and pred.kind == kind
    run = stability.simulate("sliding", t_end=t_end, t_eval=np.array([0.0, t_end]), **params, **start)
    assert abs(float(run.polar_angle[-1]) - pred.tilt) < 0.05
    # J kept by the run: |dJ/J| grows like rtol per 1000 time units (tests/test_nonlinear_conservation.py);
    # up to 35000 units at rtol 1e-9, measured <= 2e-7
    assert float(run.h_cg[-1]) == pytest.approx(pred.jellett, rel=1e-6)
    if kind == "tilted":  # the end spin is the steady state's omega . k (S1)
        assert float(run.spin[-1]) == pytest.approx(pred.axial_spin, abs=1e-3)


def test_the_paper_run_hangs_at_166_degrees_with_spin_0801():
    """Sec. 3(ii), Fr^-1 = 0.3: not a complete inversion. J0 = -0.90012 is below the inverted
    branch point |J_inv| = 0.90306, so the top ends on the tilted state at 166.0184 degrees with
    axial spin 0.8011 (the energy of the inverted state of the level, 1.0871990, is above the
    tilted one's, 1.0871924). docs/nonlinear.md's 0.754 at t = 1200 was not yet settled."""
    end = stability.final_state(fr_inv=0.3, **PAPER, **INITIAL_CONDITIONS[0.3])
    assert (end.method, end.kind) == ("jellett", "tilted")
    assert end.tilt == pytest.approx(166.018431, abs=1e-6)
    assert end.axial_spin == pytest.approx(0.80105, abs=1e-5)
    inverted = next(c for c in end.candidates if c.kind == "inverted")
    assert inverted.stability == 2 and inverted.energy > end.energy
    at_01 = stability.final_state(fr_inv=0.1, **PAPER, **INITIAL_CONDITIONS[0.1])
    assert (at_01.kind, at_01.tilt) == ("inverted", 180.0)
    assert at_01.energy == pytest.approx(0.5855, abs=1e-4)  # docs/nonlinear.md's end energy at Fr^-1 = 0.1


@pytest.mark.parametrize(
    "params,start,why",
    [
        (dict(q=-0.1, sigma=1.2, fr_inv=0.3, alpha_v=0.5), tilted_start(20.0, 1.0, 0.05, (0.05, 0.0)), "bistable"),
        (dict(q=0.0, sigma=0.8, fr_inv=0.3, alpha_v=0.5), tilted_start(10.0), "fr_inv = 0 or q = 0"),
        (dict(q=-0.1, sigma=1.2, fr_inv=0.0, alpha_v=0.5), tilted_start(10.0), "fr_inv = 0 or q = 0"),
    ],
)
def test_levels_jellett_cannot_decide_go_to_simulation(params, start, why):
    """Two stable candidates (a never_inverts top with q < 0: upright and inverted both stable),
    or marginal ones next to continua of rolling motions (q = 0, fr_inv = 0): method "simulation"."""
    end = stability.final_state(**params, **start, simulation=False)
    assert end.method == "simulation" and end.kind == "undecided" and math.isnan(end.tilt)
    assert why in end.reason


def test_the_deciding_run_says_how_far_it_got():
    """The fallback integrates in chunks and reports whether it settled; with a short time
    limit it does not (the q = 0 top still swings), and says so."""
    end = stability.final_state(q=0.0, sigma=0.8, fr_inv=0.3, alpha_v=0.5, **tilted_start(10.0), t_max=600.0)
    assert end.method == "simulation" and end.kind == "unsettled"
    assert end.run is not None and not end.run.settled and end.run.t_end == pytest.approx(600.0)
    assert end.run.jellett_drift < 1e-8 and "not settled at t_max = 600" in end.reason
    ds = end.to_dataset()
    assert ds.attrs["method"] == "simulation" and ds.attrs["run_settled"] == 0


def test_final_state_dataset():
    end = stability.final_state(fr_inv=0.3, **PAPER, **INITIAL_CONDITIONS[0.3])
    ds = end.to_dataset()
    assert ds.attrs["tippe_stability_product"] == "final_state" and ds.attrs["kind"] == "tilted"
    assert float(ds.tilt) == end.tilt and ds.tilt.attrs["units"] == "degree"
    assert list(ds.candidate_kind.values) == ["upright", "tilted", "inverted"]
    assert list(ds.candidate_is_final.values) == [0, 1, 0]
    # the candidates are the steady states of the level (stability.steady_states)
    states = stability.steady_states(fr_inv=0.3, **PAPER, jellett=end.jellett)
    assert np.allclose(ds.candidate_tilt.values, states.tilt.values, rtol=0, atol=1e-12)
    assert np.allclose(ds.candidate_energy.values, states.energy.values, rtol=1e-13)
    assert list(ds.candidate_stability.values) == list(states.stability.values)


# --- the stability flag against perturbed runs -------------------------------------------
PERTURBED = [  # (q, sigma, fr_inv, kind, J or the cosine of the tilted state)
    (-0.2, 1.3, 0.5, "tilted", -0.6),  # stable, beyond the fold
    (-0.2, 1.3, 0.5, "tilted", 0.3),  # unstable, before the fold
    (-0.15, 1.12, 0.3, "tilted", 0.0),  # unstable
    (-0.25, 0.9, 1.0, "tilted", 0.79),  # stable
    (-0.1, 1.0, 0.3, "upright", 0.9),  # the paper's top at spin 1: unstable
    (-0.1, 1.0, 0.3, "upright", 0.6),  # spun slowly: stable
    (0.2, 1.0, 0.3, "upright", 1.2),  # G above O, fast: stable
]


@pytest.mark.parametrize("q,sigma,fr,kind,where", PERTURBED)
def test_perturbed_runs_return_or_leave_as_flagged(q, sigma, fr, kind, where):
    """A state perturbed by 1e-5 (random, seeded) and run for 12 / |growth rate| (rtol 1e-11):
    the deviation from the steady state of the same kind on the perturbed level shrinks by more
    than 100 if flagged stable and grows by more than 100 if flagged unstable (measured 1e-5 to
    1e-6 and 1e4 to 6e4)."""
    J = family.jellett_of_c(where, q=q, sigma=sigma, fr_inv=fr, mu=2.28) if kind == "tilted" else where
    ds = stability.steady_states(q=q, sigma=sigma, fr_inv=fr, alpha_v=0.5, jellett=J)
    if kind == "tilted":
        i = int(np.argmin(np.abs(np.cos(np.radians(ds.tilt.values)) - where)))
        s = ds.isel(state=i)
        y = family.state_vector(math.radians(float(s.tilt)), float(s.precession_rate), q)
    else:
        s = ds.isel(state=int(np.nonzero(ds.kind.values == kind)[0][0]))
        y = family.vertical_state(kind, float(s.omega_vertical))
    assert str(s.kind.values) == kind
    flag, g = int(s.stability), float(s.growth_rate)
    assert flag in (0, 2)
    y1 = y + 1e-5 * np.random.default_rng(0).normal(size=8)
    T = 12.0 / abs(g)
    run = stability.simulate(
        "sliding",
        t_end=T,
        t_eval=np.linspace(0, T, 401),
        omega=y1[0:3],
        k=y1[3:6],
        velocity=y1[6:8],
        q=q,
        fr_inv=fr,
        sigma=sigma,
        alpha_v=0.5,
        rtol=1e-11,
        atol=1e-14,
    )
    ref = stability.steady_states(q=q, sigma=sigma, fr_inv=fr, alpha_v=0.5, jellett=float(run.h_cg[0]))
    same = ref.kind.values == kind
    ref_tilt = float(ref.tilt.values[same][np.argmin(np.abs(ref.tilt.values[same] - float(s.tilt)))])
    dev = np.abs(np.radians(run.polar_angle.values - ref_tilt)) + run.slip_speed.values
    ratio = dev[-40:].max() / dev[:5].max()
    assert (ratio < 1e-2) if flag == 0 else (ratio > 1e2)


# --- bad input ---------------------------------------------------------------------------
GOOD = dict(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, omega=[0.0, 0.0, 1.0], k=[0.01, 0.0, 1.0])


@pytest.mark.parametrize(
    "kw,exc,fragment",
    [
        (dict(alpha_v=0.0), ValueError, r"alpha_v = 0 is outside the allowed range of final_state: alpha_v > 0"),
        (dict(k=[0.0, 0.0, 1.05]), ValueError, r"k = \[0.0, 0.0, 1.05\] has length 1.05; k is the unit symmetry axis"),
        (dict(k=[0.0, 1.0]), ValueError, r"k = \[0.0, 1.0\] has shape \(2,\); k must be a vector of 3 components"),
        (dict(k=[[0.0, 0.0, 1.0]]), ValueError, r"has shape \(1, 3\); k must be a vector of 3 components"),
        (dict(omega=[0.0, float("nan"), 1.0]), ValueError, "omega = nan is not finite"),
        (dict(omega="up"), TypeError, "omega = 'up' is a str"),
        (dict(velocity=[0.0, 0.0, 0.1]), ValueError, "the vertical component must be 0"),
        (dict(q=0.8), ValueError, "q = 0.8 is outside the physical domain"),
        (dict(sigma=[1.0, 1.1]), TypeError, "sigma must be a single number here"),
        (dict(model="rolling"), ValueError, "model = 'rolling' is not known; choose one of sliding"),
        (dict(t_max=-1.0), ValueError, "t_max = -1 is outside the allowed range: t_max > 0"),
        (dict(simulation="no"), TypeError, "simulation = 'no' is a str"),
    ],
)
def test_bad_input(kw, exc, fragment):
    args = dict(GOOD, q=0.0, sigma=0.8) if "t_max" in kw else dict(GOOD)  # t_max is checked when a run is needed
    args.update(kw)
    with pytest.raises(exc, match=fragment):
        stability.final_state(**args)
