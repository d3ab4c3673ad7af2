"""The tumbling runs of Sec. 3(ii) (Figs. 5-9) and the numbers read off them.

Parameters: ``alpha_v = 0.5``, ``mu = 2.28``, ``q = -0.1``, ``sigma = 1``, ``alpha_k = 0``;
initial conditions as printed for ``fr_inv = 0.3`` and ``0.1`` (a clockwise spin,
``omega_3 ~ -1``: the mirror image of the linear analysis' spin +1). One spin period is
``2 pi`` time units. ``k`` as printed has ``|k| = 0.99998`` and is normalised.

Numbers (``python benchmarks/scene_numbers.py``): the time of the 90-degree crossing of the axis (in spin
periods, linear interpolation between output samples, 0.05 time units apart), the spin
``omega . k`` at the start and the end, the peak transverse angular rate and its value at the
crossing, the energy parts at start and end, the excursion of the centre, the sliding speed
and the friction of the sliding run against the traction a rolling run needs (Fig. 9a).
:func:`friction_cases` runs the four cases of Fig. 9(b).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..errors import InputError
from ..products import PRODUCT_ATTR
from .runs import simulate

__all__ = ["FRICTION_CASES", "INITIAL_CONDITIONS", "PAPER", "crossing_time", "friction_cases", "run"]

#: the paper's parameters of Sec. 3(ii)
PAPER = dict(q=-0.1, sigma=1.0, mu=2.28)

#: initial conditions of Sec. 3(ii), by fr_inv
INITIAL_CONDITIONS: dict[float, dict[str, list[float]]] = {
    0.3: dict(omega=[0.0219, 0.0047, -0.9997], k=[0.0676, 0.0676, 0.9954], velocity=[0.0935, 0.0384]),
    0.1: dict(omega=[0.00219, 0.0047, -0.9999], k=[0.0080, 0.0150, 0.9998], velocity=[0.0110, 0.0038]),
}

#: (alpha_k, alpha_v) of the four cases of Fig. 9(b), at fr_inv = 0.3
FRICTION_CASES: tuple[tuple[float, float], ...] = ((0.0, 0.5), (0.5, 0.5), (0.5, 0.1), (0.5, 0.0))


def run(
    fr_inv: float = 0.3,
    *,
    model: str = "sliding",
    alpha_v: float = 0.5,
    alpha_k: float = 0.0,
    t_end: float = 1200.0,
    dt: float = 0.05,
    **kw,
) -> xr.Dataset:
    """A run of Sec. 3(ii) from the printed initial conditions (``fr_inv`` 0.3 or 0.1).

    ``model="rolling"`` starts the rolling sphere from the same ``omega`` and ``k`` (its
    velocity follows from the constraint). Extra keywords go to :func:`stability.simulate`.
    """
    if fr_inv not in INITIAL_CONDITIONS:
        raise InputError(
            f"fr_inv = {fr_inv!r}: the paper gives initial conditions for "
            f"{', '.join(map(str, INITIAL_CONDITIONS))} only"
        )
    ic = dict(INITIAL_CONDITIONS[fr_inv])
    friction = {}
    if model == "sliding":
        friction = dict(alpha_v=alpha_v, alpha_k=alpha_k)
    else:
        ic.pop("velocity")
    return simulate(model, t_end=t_end, dt=dt, fr_inv=fr_inv, **PAPER, **ic, **friction, **kw)


def crossing_time(ds: xr.Dataset, angle: float = 90.0) -> float:
    """First time the polar angle reaches ``angle`` degrees (linear interpolation); NaN if never."""
    pol = ds.polar_angle.values
    t = ds.time.values
    above = np.nonzero(pol >= angle)[0]
    if above.size == 0 or above[0] == 0:
        return float("nan")
    i = above[0]
    return float(t[i - 1] + (angle - pol[i - 1]) * (t[i] - t[i - 1]) / (pol[i] - pol[i - 1]))


def friction_cases(
    fr_inv: float = 0.3, *, t_end: float = 1500.0, scheme: str = "adaptive", step: float = 0.1
) -> xr.Dataset:
    """The four friction cases of Fig. 9(b): crossing time, largest polar angle, slip.

    ``scheme="adaptive"`` integrates the regularised law to tolerance (``method="auto"``);
    ``scheme="fixed_step"`` uses the paper's fixed-step RK4 with the unregularised
    component-wise sign law of eq. (16) and step ``step``.
    """
    rows = []
    for alpha_k, alpha_v in FRICTION_CASES:
        kw = {}
        if scheme == "fixed_step":
            kw = dict(method="rk4", step=step, friction="componentwise", slip_scale=1e-12)
        ds = run(fr_inv, alpha_v=alpha_v, alpha_k=alpha_k, t_end=t_end, dt=0.5, **kw)
        slip = ds.slip_speed.values
        rows.append((crossing_time(ds) / (2 * np.pi), float(ds.polar_angle.max()), float(np.median(slip)), slip.min()))
    crossing = {"long_name": "time of the 90-degree crossing", "units": "1"}
    crossing["comment"] = "in spin periods 2 pi / Omega; NaN if none"
    variables = {  # name: attributes, in the order of the rows
        "crossing_periods": crossing,
        "max_polar_angle": {"long_name": "largest polar angle of k", "units": "degree"},
        "median_slip_speed": {"long_name": "median sliding speed", "units": "1"},
        "min_slip_speed": {"long_name": "smallest sliding speed", "units": "1"},
    }
    r = np.array(rows)
    case = {"long_name": "friction case of Fig. 9(b)", "units": "1"}
    coords = {
        "case": ("case", np.arange(1, len(FRICTION_CASES) + 1), case),
        "alpha_k": ("case", [c[0] for c in FRICTION_CASES], {"long_name": "Coulomb friction", "units": "1"}),
        "alpha_v": ("case", [c[1] for c in FRICTION_CASES], {"long_name": "viscous friction", "units": "1"}),
    }
    attrs = {"Conventions": "CF-1.10", "title": "friction cases of Fig. 9(b)", PRODUCT_ATTR: "friction_cases"}
    attrs.update(fr_inv=fr_inv, scheme=scheme, step=step if scheme == "fixed_step" else 0.0, **PAPER)
    data = {name: ("case", r[:, i], a) for i, (name, a) in enumerate(variables.items())}
    return xr.Dataset(data, coords=coords, attrs=attrs)
