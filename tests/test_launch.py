"""stability.launch (issue 23): its launch spins against closed forms, its end against long runs.

Closed forms (derivation in stability/launches/result.py and docs/launch.md). Vertical states
of a top with G on the axis at ``q R`` from O (``q = -alpha``: G below O upright), spinning at
``n`` about the vertical: Jellett's integral ``J = -L . a`` (``a`` from G to the contact point)
is ``C n R (1 - alpha)`` upright and ``C n R (1 + alpha)`` inverted. Eq. (11)'s neutral curve
of the sliding model, ``sigma (1 + q) = 1 - mu q^2 + mu q (1 + q)^2 fr_inv``, in SI
(``sigma = C/A0``, ``mu = M R^2/A0``, ``fr_inv = g/(n^2 R)``, ``A0 = A_G + M q^2 R^2``):

* upright (``q = -alpha``): ``n_up^2 = M g R alpha (1 - alpha)^2 / (A_G - C (1 - alpha))``;
* inverted (``q = +alpha``): ``n_inv^2 = M g R alpha (1 + alpha)^2 / (C (1 + alpha) - A_G)``;
* a top launched upright at ``n`` reaches the inverted branch point when its ``J`` is the
  inverted state's there: ``n_launch = n_inv (1 + alpha)/(1 - alpha)``.

Rauch-Wojciechowski and Rutstam (2014): the inverted state is stable for
``lambda > lambda_thres = sqrt(m g R^3 I3 alpha) (1 + alpha)^2 / sqrt(1 + alpha - gamma)``, with
``lambda`` Jellett's integral ``I3 n R (1 + alpha)`` of the inverted state (kg m^2 s^-1: I3 n
times a length), I1 = A_G, I3 = C and ``gamma = I1 / I3`` (the form that makes it the
closed form above: ``I3 (1 + alpha - gamma) = C (1 + alpha) - A_G``; with ``I3/I1`` it would
not be). So the inverted critical spin is ``lambda_thres / (I3 R (1 + alpha))`` and the
launch spin that inverts is ``lambda_thres / (I3 R (1 - alpha))``.
"""

import math

import numpy as np
import pytest

import stability
from stability.errors import DomainError
from stability.launches.result import inverts_above
from stability.products import PRODUCT_ATTR
from stability.top import Top


def rutstam_top():
    m, r = 0.020, 0.020
    return Top(
        mass=m, radius=r, com_offset=-0.3 * r, inertia_transverse=0.376 * m * r * r, inertia_axial=0.4 * m * r * r
    )


def test_rutstam_threshold():
    # reference: the published threshold (module docstring); 1e-10: both spins are roots found
    # to rounding (the neutral condition, and Newton on the nonlinear rhs at the branch point)
    top = rutstam_top()
    m, g, r, alpha = top.mass, top.g, top.radius, 0.3
    i1, i3 = top.inertia_transverse, top.inertia_axial
    gamma = i1 / i3
    lam = math.sqrt(m * g * r**3 * i3 * alpha) * (1 + alpha) ** 2 / math.sqrt(1 + alpha - gamma)
    n_inv = lam / (i3 * r * (1 + alpha))
    assert stability.critical_spin(top, orientation="inverted").spin == pytest.approx(n_inv, rel=1e-10)
    assert inverts_above(top, 40.0, 0.5) == pytest.approx(lam / (i3 * r * (1 - alpha)), rel=1e-10)


@pytest.mark.parametrize("q,sigma", [(-0.1, 1.0), (-0.3, 1.05), (-0.2, 0.95), (-0.05, 1.0)])
def test_inverts_above_closed_form(q, sigma):
    # reference: n_launch = n_inv (1 + alpha)/(1 - alpha) with n_inv from its own closed form
    top = Top.from_nondimensional(mass=0.015, radius=0.015, q=q, mu=2.28, sigma=sigma)
    alpha = -q
    a_g, c = top.inertia_transverse, top.inertia_axial
    n_inv = math.sqrt(top.mass * top.g * top.radius * alpha * (1 + alpha) ** 2 / (c * (1 + alpha) - a_g))
    ref = n_inv * (1 + alpha) / (1 - alpha)
    # the answer does not depend on the reference spin that makes it nondimensional
    for reference in (10.0, 50.0, 300.0):
        assert inverts_above(top, reference, 0.5) == pytest.approx(ref, rel=1e-10)
    if a_g > c * (1 - alpha):
        n_up = math.sqrt(top.mass * top.g * top.radius * alpha * (1 - alpha) ** 2 / (a_g - c * (1 - alpha)))
        assert stability.critical_spin(top).spin == pytest.approx(n_up, rel=1e-10)


def test_table1_readme_numbers():
    # reference: README bifurcation_toy row: upright unstable above 363.73 rpm, inverts
    # completely above 430.82 rpm
    res = stability.launch(Top.table1(), 330.0, unit="rpm")
    assert res.unstable_above * 60 / (2 * math.pi) == pytest.approx(363.73, abs=0.005)
    assert res.inverts_above * 60 / (2 * math.pi) == pytest.approx(430.82, abs=0.005)
    assert res.end_kind == "upright" and res.flip_time is None and "never reaches 90" in res.reasons["flip_time"]
    text = str(res)
    assert "the upright top becomes unstable above:" in text and "363.733 rpm = 6.06222 rev/s" in text
    assert "launched upright, it inverts completely above: 430.817 rpm" in text
    ds = res.to_dataset()
    assert ds.attrs[PRODUCT_ATTR] == "launch" and ds.inverts_above.attrs["units"] == "rad s-1"
    assert np.isnan(float(ds.flip_time)) and "never reaches 90" in ds.flip_time.attrs["comment"]
    assert res.event == "none" and res.parameters["alpha_v"] == 0.5 and "default 0.5" in res.alpha_v_source


def test_alpha_v_from_mu_v_is_eq7():
    # reference: eq. (7), alpha_v = mu mu_v g / Omega at the launch spin
    top = Top.table1(mu_v=0.01)
    res = stability.launch(top, 5.0, unit="rev/s")
    assert res.parameters["alpha_v"] == pytest.approx(top.mu * 0.01 * top.g / (2 * math.pi * 5.0), rel=1e-15)
    assert "eq. (7)" in res.alpha_v_source
    with pytest.raises(TypeError, match="conflicts with this Top's mu_v"):
        stability.launch(top, 5.0, unit="rev/s", alpha_v=0.5)


def test_min_normal_force_si():
    # reference: the equilibrium normal force is M g (N = mu fr_inv in units A0 Omega^2 / R);
    # below the critical spin the run stays near equilibrium (tilt <= 1 degree): within 1e-3
    top = Top.table1()
    res = stability.launch(top, 5.0, unit="rev/s")
    assert res.min_normal_force == pytest.approx(top.mass * top.g, rel=1e-3)
    assert res.min_normal_force_nd == pytest.approx(res.parameters["mu"] * res.parameters["fr_inv"], rel=1e-3)


@pytest.mark.parametrize("spin,unit", [(0.01, "rev/s"), (1e6, "rpm")])
def test_bad_launch(spin, unit):
    with pytest.raises(DomainError, match="spin = .* is outside the allowed range: 0.1 to 10000 rev/s"):
        stability.launch(Top.table1(), spin, unit=unit)
    with pytest.raises(DomainError, match="tilt = 0 degrees is outside the allowed range: 0 < tilt < 180"):
        stability.launch(Top.table1(), 7.0, unit="rev/s", tilt=0.0)
    with pytest.raises(ValueError, match="model = 'rolling'"):
        stability.launch(Top.table1(), 7.0, unit="rev/s", model="rolling")


# three tops, one per high-spin class (stability.top_class), each at spins around its thresholds
CASES = [
    ((-0.1, 1.0), 5.0),
    ((-0.1, 1.0), 6.6),
    ((-0.1, 1.0), 8.0),
    ((-0.1, 1.0), 12.0),
    ((-0.15, 1.4), 5.0),
    ((-0.15, 1.4), 9.0),
    ((-0.15, 1.4), 15.0),
    ((-0.15, 1.4), 25.0),
    ((-0.1, 0.8), 3.0),
    ((-0.1, 0.8), 6.0),
    ((-0.1, 0.8), 10.0),
    ((-0.1, 0.8), 20.0),
]


@pytest.mark.parametrize("nd,spin", CASES)
def test_launch_agrees_with_a_long_simulate(nd, spin):
    # reference: stability.simulate from the same launch state, run to twice the settle time
    # (at least 4000 time units); the end tilt within 0.5 degree (the run's tilt at the end of
    # the settle band is within 1 degree by definition; the final approach is exponential);
    # the flip time against the crossing on the run's 0.05-unit output within 0.1 time unit
    q, sigma = nd
    top = Top.from_nondimensional(mass=0.015, radius=0.015, q=q, mu=2.28, sigma=sigma)
    res = stability.launch(top, spin, unit="rev/s")
    w = 2 * math.pi * spin
    t_end = max(4000.0, 2 * w * (res.settle_time or 0.0))
    th = math.radians(1.0)
    k = [math.sin(th), 0.0, math.cos(th)]
    ds = stability.simulate(
        "sliding", t_end=t_end, dt=0.05, omega=k, k=k, velocity=[0.0, 0.0], rtol=1e-10, atol=1e-13, **res.parameters
    )
    pol = ds.polar_angle.values
    assert pol[-1] == pytest.approx(res.end_tilt, abs=0.5)
    hit = np.nonzero(pol >= 90.0)[0]
    if res.flip_time is None:
        assert hit.size == 0
    else:
        assert float(ds.time[hit[0]]) == pytest.approx(res.flip_time * w, abs=0.1)
    assert res.top_class == stability.top_class(q=q, sigma=sigma)


def test_inverts_above_only_for_the_inverting_class():
    # a never_inverts top has an inverted branch point, but launched upright it stays up; a
    # hanging top's family does not reach the inverted state (stability.top_class)
    never = Top.from_nondimensional(mass=0.015, radius=0.015, q=-0.15, mu=2.28, sigma=1.4)
    hangs = Top.from_nondimensional(mass=0.015, radius=0.015, q=-0.1, mu=2.28, sigma=0.8)
    assert inverts_above(never, 50.0, 0.5) is None and inverts_above(hangs, 50.0, 0.5) is None


def test_cli_launch_and_threshold(capsys):
    # the top in SI: 15 g, 15 mm, G 3 mm below O, A_G = 1.3e-6, C = 1.5e-6 kg m^2;
    # reference: the 8.51 rev/s, and the closed form n_inv (1 + alpha)/(1 - alpha)
    from stability.cli import main

    si = [
        "--mass",
        "0.015",
        "--radius",
        "0.015",
        "--com-offset",
        "-0.003",
        "--inertia-transverse",
        "1.3e-6",
        "--inertia-axial",
        "1.5e-6",
    ]
    assert main(["threshold", "spin", *si, "--unit", "rev/s"]) == 0
    out = capsys.readouterr().out.splitlines()
    inv = [ln for ln in out if ln.startswith("launched upright, it inverts completely above ")]
    up = [ln for ln in out if ln.startswith("the upright top becomes unstable above ")]
    assert len(inv) == 1 and len(up) == 1
    top = Top(mass=0.015, radius=0.015, com_offset=-0.003, inertia_transverse=1.3e-6, inertia_axial=1.5e-6)
    n_inv = stability.critical_spin(top, orientation="inverted").spin
    assert float(inv[0].split()[-2]) == pytest.approx(n_inv * 1.2 / 0.8 / (2 * math.pi), rel=1e-9)
    assert float(inv[0].split()[-2]) == pytest.approx(8.51, abs=0.005)
    assert main(["launch", *si, "--spin", "15", "--unit", "rev/s"]) == 0
    text = capsys.readouterr().out
    assert "launch at 15 rev/s" in text and "inverts completely above: 8.51088 rev/s" in text
    assert (
        main(
            [
                "launch",
                "--mass",
                "15",
                "--radius",
                "15",
                "--com-offset",
                "-3",
                "--inertia-transverse",
                "1.3e-6",
                "--inertia-axial",
                "1.5e-6",
                "--spin",
                "15",
            ]
        )
        == 2
    )
    assert "radius looks like millimetres" in capsys.readouterr().err


def test_launch_of_a_top_with_a_stick_stops_where_the_stick_touches():
    """A launch of the toy with a stick reports the stick's contact and stops there.

    Reference: the closed-form tilt at which the stick's tip touches the floor
    (``Top.stick_contact``, tested against mpmath in tests/test_stick.py); the run's stop is
    located on the integrator's interpolant, so its tilt agrees to the integrator's tolerance
    (1e-6 degree is far above rtol 1e-10 on angles of order 1 rad, far below any physical
    meaning). The answer must not report the sphere model's 163.7 degrees as where the toy ends.
    """
    top = stability.Top.table1(stick=stability.Stick(0.02, 0.003, 0.012))
    tilt, part = top.stick_contact()
    ans = stability.launch(top, 7.15, unit="rev/s")
    assert ans.event == "stick_contact" and part == "tip"
    assert abs(ans.event_tilt - tilt) < 1e-6
    assert ans.flip_time is not None and ans.flip_time < ans.event_time
    assert ans.settle_time is None
    assert "reaches its stick" in str(ans)


def test_cli_launch_plot_draws_the_diagram_with_the_launch(tmp_path, capsys):
    """``tippe launch --plot``: the top's bifurcation diagram with the launch marked. The drawing
    itself (the launch at its equivalent spin, the critical spin where the upright line changes
    style) is tested by its artists in tests/test_si_inputs.py; here: the command writes a PNG
    and says where."""
    from stability.cli import main

    out = tmp_path / "launch.png"
    assert main(["launch", "--preset", "table1", "--spin", "7.15", "--unit", "rev/s", "--plot", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"drawn: {out}" in capsys.readouterr().out
