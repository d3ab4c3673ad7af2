"""Where a launch loses its contact: the boundary ``N_min = 0`` in the plane of two launch
quantities, traced by continuation (issue 19, "Where contact is lost").

The launch (nondimensional as :func:`stability.simulate`, ``Omega`` the launch spin): the axis
tilted by ``tilt`` in the x-z plane, ``k = (sin tilt, 0, cos tilt)``, spun about it and tipped
at the rate ``tilt_rate`` about the horizontal ``J``,

    omega = k + (tilt_rate / Omega) J,      d(tilt)/dt = tilt_rate at t = 0

(``J x k = (cos tilt, 0, -sin tilt)`` is the direction of increasing tilt), the sphere's centre
at rest. ``tilt_rate = 0`` is the launch state of :func:`stability.launch`.

The smallest normal force of a run over ``duration`` seconds,

    N_min = min over 0 <= t <= T of N(t),  N = mu fr_inv + mu q (k'')_3  (eq. 1, vertical),

is found on a run that is *not* stopped at ``N = 0``, so that ``N_min`` keeps its sign beyond
the boundary, at its interior minimum ``dN/dt = 0``
(:func:`stability.nonlinear.min_force.min_normal_force`). ``N_min`` is a minimum over time: a
smooth function of the launch where one interior minimum is the smallest (envelope theorem:
``d N_min / d p = dN/dp`` at ``t*``), with kinks where two minima exchange.

The residual of the continuation is ``N_min / (M g)`` (the equilibrium normal force is
``mu fr_inv`` in the units of the run, so this is ``N_min / (mu fr_inv)``: 1 at rest, O(1),
continuous in the spin); the engine (:func:`continuation.trace`, generic) follows its zero
through the box of the two quantities (the box's edges its constraints), from a zero found by
Brent's method on a grid edge where the grid's ``N_min`` changes sign; then from every other
such edge that no traced piece crosses (the line stops at a kink of ``N_min``, where the
minimum of ``N(t)`` that is the smallest changes: the piece beyond it starts from its own edge). The grid itself (coarse,
for the figure's colour) and the traced line are returned in one Dataset (product
``contact_loss_map``, docs/datasets.md).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
import xarray as xr

from continuation.engine import TraceOptions, trace

from ..errors import InputError
from ..nonlinear.min_force import min_normal_force
from ..nonlinear.runs import initial_state, model_parameter_vector
from ..parameters import as_scalar, check_choice, check_integer, check_interval, check_positive
from ..top import Top, check_launch_spin, from_rad_per_s, to_rad_per_s
from .flip import launch_parameters, product_header

__all__ = ["QUANTITIES", "ContactLossProblem", "contact_loss_boundary", "launch_min_normal_force"]

#: the product attribute of :func:`contact_loss_boundary` (docs/datasets.md)
PRODUCT = "contact_loss_map"
#: the launch quantities a map can be drawn over, and their units (spin: the caller's unit)
QUANTITIES = {"spin": None, "tilt": "degree", "tilt_rate": "rad s-1"}
#: integrator tolerance of the runs (the boundary is located to about this, relative)
RUN_RTOL = 1e-10


def launch_min_normal_force(
    top: Top, spin: float, tilt: float, tilt_rate: float, *, duration: float = 1.0, alpha_v: Any = None
) -> tuple[float, float]:
    """The smallest normal force of a launch over ``duration`` seconds, in units of ``M g``,
    and its time (s) (module docstring), by runs at :data:`RUN_RTOL`. ``spin`` and ``tilt_rate``
    in rad/s, ``tilt`` in degrees."""
    w, params, _ = launch_parameters(top, spin, "rad/s", alpha_v, "sliding")
    nd = {k: params[k] for k in ("q", "fr_inv", "sigma", "alpha_v", "mu")}
    _, p = model_parameter_vector("sliding", nd)
    th = math.radians(tilt)
    k = np.array([math.sin(th), 0.0, math.cos(th)])
    y0 = initial_state("sliding", k + (tilt_rate / w) * np.array([0.0, 1.0, 0.0]), k, [0.0, 0.0])
    n_min, t_min = min_normal_force("sliding", y0, p, duration * w, rtol=RUN_RTOL)
    return n_min / (nd["mu"] * nd["fr_inv"]), t_min / w


class ContactLossProblem:
    """Continuation problem ``N_min(x, y) / (M g) = 0`` (module docstring): ``u = (x, y)``, the
    two launch quantities in SI (spin and tilt rate rad/s, tilt degrees), one equation; the
    box ``lower <= u <= upper`` as the constraints."""

    constraint_names = ("x_min", "x_max", "y_min", "y_max")

    def __init__(self, top: Top, names: tuple[str, str], launch: dict[str, float], box: np.ndarray, **run: Any):
        self.top, self.names, self.launch, self.box, self.run = top, names, launch, box, run

    def min_force(self, u: np.ndarray) -> tuple[float, float]:
        """``(N_min / (M g), its time in s)`` at the launch ``u``."""
        q = dict(self.launch)
        q[self.names[0]], q[self.names[1]] = float(u[0]), float(u[1])
        return launch_min_normal_force(self.top, q["spin"], q["tilt"], q["tilt_rate"], **self.run)

    def residual(self, u: np.ndarray) -> np.ndarray:
        return np.array([self.min_force(u)[0]])

    def constraints(self, u: np.ndarray) -> np.ndarray:
        b = self.box
        return np.array([u[0] - b[0, 0], b[0, 1] - u[0], u[1] - b[1, 0], b[1, 1] - u[1]])


def _crosses(p0: np.ndarray, p1: np.ndarray, pts: np.ndarray, widths: np.ndarray) -> bool:
    """Whether the segment ``p0 p1`` meets the polyline ``pts`` (in coordinates scaled by
    ``widths``; the orientation test of two segments, touching counted)."""
    a, b, q = p0 / widths, p1 / widths, pts / widths

    def side(u: np.ndarray, v: np.ndarray, w: np.ndarray) -> np.ndarray:
        return (v[..., 0] - u[..., 0]) * (w[..., 1] - u[..., 1]) - (v[..., 1] - u[..., 1]) * (w[..., 0] - u[..., 0])

    c, d = q[:-1], q[1:]
    s1, s2 = side(a, b, c), side(a, b, d)
    s3, s4 = side(c, d, a), side(c, d, b)
    return bool(np.any((s1 * s2 <= 0) & (s3 * s4 <= 0)))


def contact_loss_boundary(
    top: Top,
    *,
    x: str = "tilt_rate",
    y: str = "spin",
    x_range: tuple[float, float] = (0.0, 100.0),
    y_range: tuple[float, float] = (20.0, 50.0),
    spin: float = 25.0,
    tilt: float = 5.0,
    tilt_rate: float = 0.0,
    unit: str = "rev/s",
    grid: tuple[int, int] = (11, 11),
    duration: float = 1.0,
    alpha_v: Any = None,
    max_points: int = 200,
) -> xr.Dataset:
    """Where a launch of ``top`` loses its contact, in the plane of two launch quantities.

    Parameters
    ----------
    top : stability.Top
        The top in SI units.
    x, y : {"spin", "tilt", "tilt_rate"}
        The two quantities of the plane (different); the third is held at its given value.
    x_range, y_range : (float, float)
        Their ranges (spin in ``unit``, tilt in degrees, tilt rate in rad/s).
    spin, tilt, tilt_rate : float
        The launch (module docstring); those not on an axis are held.
    unit : {"rad/s", "rev/s", "rpm", "Hz"}
        Unit of the spin.
    grid : (int, int)
        Points of the coarse grid along x and y (at least 2 each).
    duration : float, default 1.0
        Seconds of each run over which the smallest normal force is taken.
    alpha_v : float, optional
        As :func:`stability.launch` (default the top's ``mu_v``, else 0.5).
    max_points : int
        Points of the traced line, at most, per direction.

    Returns
    -------
    xarray.Dataset
        ``min_normal_force`` (units of ``M g``) and ``min_time`` (s) over ``(y, x)``; the traced
        boundary ``boundary_x``, ``boundary_y`` along ``point`` (empty where the grid has no
        sign change), why its two ends stopped (``boundary_end_reasons``: the engine's
        ``"boundary"`` at the box, ``"step_failure"`` at a kink of ``N_min``); attributes: the held launch, ``unit``, ``duration``, the wall time
        ``seconds``, the number of runs; product ``contact_loss_map``.

    Raises
    ------
    stability.errors.InputError
        Unknown or equal quantities, an empty range, a grid smaller than 2 x 2 or not of two
        integers, ``max_points < 2``, a held ``tilt`` outside ``(0, 180)``, a ``tilt_rate`` not
        finite.
    stability.errors.ParameterTypeError
        A held ``tilt`` or ``tilt_rate``, a ``grid`` entry or ``max_points`` of the wrong type.
    """
    from scipy.optimize import brentq

    x = check_choice("x", x, tuple(QUANTITIES))
    y = check_choice("y", y, tuple(QUANTITIES))
    if x == y:
        raise InputError(f"x = y = {x!r}: the map needs two different launch quantities")
    for name, rng in (("x_range", x_range), ("y_range", y_range)):
        if len(rng) != 2 or not float(rng[0]) < float(rng[1]):
            raise InputError(f"{name} = {rng!r} must be (low, high) with low < high")
    if not isinstance(grid, (tuple, list)) or len(grid) != 2:
        raise InputError(f"grid = {grid!r} must be two integers (nx, ny), at least 2 points along each axis")
    nx, ny = (check_integer("grid", v, minimum=2) for v in grid)
    max_points = check_integer("max_points", max_points, minimum=2)
    duration = check_positive("duration", duration)
    launch = {
        "spin": check_launch_spin(spin, unit),
        "tilt": check_interval("tilt", tilt, 0.0, 180.0),
        "tilt_rate": as_scalar("tilt_rate", tilt_rate),
    }
    ranges = [np.asarray(r, dtype=float) for r in (x_range, y_range)]
    box = np.array([to_rad_per_s(r, unit) if n == "spin" else r for n, r in zip((x, y), ranges)], dtype=float)
    for name, (lo, hi) in zip((x, y), box):
        for v in (lo, hi) if name == "spin" else ():
            check_launch_spin(v, "rad/s")
        if name == "tilt" and not (lo > 0.0 and hi < 180.0):
            raise InputError(f"the tilt range {lo:g} to {hi:g} degrees is outside the allowed range: 0 < tilt < 180")
    problem = ContactLossProblem(top, (x, y), launch, box, duration=duration, alpha_v=alpha_v)
    t0 = time.perf_counter()
    xs, ys = np.linspace(*box[0], nx), np.linspace(*box[1], ny)
    n_min, t_min = np.empty((ny, nx)), np.empty((ny, nx))
    for j, yv in enumerate(ys):
        for i, xv in enumerate(xs):
            n_min[j, i], t_min[j, i] = problem.min_force(np.array([xv, yv]))
    # every grid edge where N_min changes sign, as (fixed axis, index along it, cell index)
    edges = [(0, i, int(j)) for i in range(nx) for j in np.nonzero(n_min[:-1, i] * n_min[1:, i] < 0)[0]]
    edges += [(1, j, int(i)) for j in range(ny) for i in np.nonzero(n_min[j, :-1] * n_min[j, 1:] < 0)[0]]
    widths = box[:, 1] - box[:, 0]
    quiet, scale = dict(detect_branch_points=False, detect_closed=False), (float(widths[0]), float(widths[1]))
    options = TraceOptions(
        step=0.02, max_step=0.05, tol=1e-8, scale=scale, max_points=max_points, max_angle=0.3, **quiet
    )
    pieces: list[tuple[np.ndarray, list[str], list[str]]] = []
    for axis, a_i, c_j in edges:
        if axis == 0:  # along y at x = xs[a_i], between ys[c_j] and ys[c_j + 1]
            p0, p1 = np.array([xs[a_i], ys[c_j]]), np.array([xs[a_i], ys[c_j + 1]])
        else:
            p0, p1 = np.array([xs[c_j], ys[a_i]]), np.array([xs[c_j + 1], ys[a_i]])
        if any(_crosses(p0, p1, pts, widths) for pts, _, _ in pieces):
            continue  # a traced piece already passes through this edge
        s0 = brentq(  # a start on the boundary (Brent along the edge)
            lambda f, p0=p0, p1=p1: problem.residual(p0 + f * (p1 - p0))[0], 0.0, 1.0, xtol=1e-12
        )
        start = p0 + s0 * (p1 - p0)
        ahead, back = (trace(problem, start, options, direction=d, project_start=False) for d in (1, -1))
        points = np.concatenate([back.points[::-1], ahead.points[1:]])
        pieces.append((points, back.kinds[::-1] + ahead.kinds[1:], [back.end_reasons[0], ahead.end_reasons[0]]))
    bxy = np.concatenate([pts for pts, _, _ in pieces]) if pieces else np.zeros((0, 2))
    piece = np.concatenate([np.full(len(k), n) for n, (_, k, _) in enumerate(pieces)]) if pieces else np.zeros(0, int)
    kinds = [k for _, ks, _ in pieces for k in ks]
    ends = "; ".join(f"piece {n}: {' and '.join(e)}" for n, (_, _, e) in enumerate(pieces))
    seconds = time.perf_counter() - t0

    def axis(dim: Any, name: str, v: np.ndarray, long_name: str) -> tuple:
        si = name == "spin"
        attrs = {"long_name": long_name, "units": unit if si else QUANTITIES[name]}
        return dim, (from_rad_per_s(v, unit) if si else v), attrs

    held = {k: (from_rad_per_s(v, unit) if k == "spin" else v) for k, v in launch.items() if k not in (x, y)}
    attrs = product_header(PRODUCT, "where a launch loses its contact: the smallest normal force of the run")
    attrs.update(x_quantity=x, y_quantity=y, unit=unit, **{f"launch_{k}": float(v) for k, v in held.items()})
    attrs.update(duration=duration, boundary_end_reasons=ends or "no sign change on the grid", runs=nx * ny)
    attrs.update(seconds=seconds, q=top.q, mu=top.mu, sigma=top.sigma)
    force = {"long_name": "smallest normal force of the run", "units": "M g", "comment": "below 0: contact lost"}
    pieces_text = "traced piece (a smooth piece of N_min = 0; pieces meet at kinks of N_min)"
    data = {
        "min_normal_force": (("y", "x"), n_min, force),
        "min_time": (("y", "x"), t_min, {"long_name": "time of the smallest normal force", "units": "s"}),
        "boundary_x": axis("point", x, bxy[:, 0], f"{x} on the boundary N_min = 0"),
        "boundary_y": axis("point", y, bxy[:, 1], f"{y} on the boundary N_min = 0"),
        "boundary_kind": ("point", np.array(kinds, dtype=str), {"long_name": "kind of the traced point"}),
        "boundary_piece": ("point", piece.astype(np.int32), {"long_name": pieces_text}),
    }
    coords = {"x": axis("x", x, xs, x.replace("_", " ")), "y": axis("y", y, ys, y.replace("_", " "))}
    return xr.Dataset(data, coords=coords, attrs=attrs)
