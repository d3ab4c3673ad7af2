"""Every array of a representative set of traced curves, to compare two versions bit for bit.

A refactoring of the continuation engine must not move a single traced point. Run this script
with each version (e.g. a ``git archive`` of the old commit on ``PYTHONPATH``) and compare::

    PYTHONPATH=/tmp/old python benchmarks/trace_snapshot.py /tmp/old.npz
    python benchmarks/trace_snapshot.py /tmp/new.npz
    python benchmarks/trace_snapshot.py --compare /tmp/old.npz /tmp/new.npz

The set: neutral curves of the sliding model in (q, sigma) at fr_inv 0 and 0.3 (also at
alpha_v = 1e3 and with coarse steps), in (sigma, fr_inv), (q, fr_inv) (a fold and a branch
point), (sigma, alpha_v); a start at the fold and a start on a mode that touches the axis; the
fixed_pivot and rolling curves (collision form); a fold curve; each sliding curve also with
``compiled=False``; and engine problems with closed forms: a closed circle, a closed Hopf
neutral curve (with and without a ``compiled_step`` hook), a cubic whose branch ends at two
constraints (finite-difference Jacobian), crossing lines (a branch point), a test function and
a callback that stops. Compared: every data variable, coordinate and attribute of the datasets,
and every field of the branches (points, tangents, arclength, kinds, details, closed, end
reasons, work counters). Listed apart ("derived"): the dense output of two curves and short
nonlinear runs, which use the shared building blocks too.
"""

from __future__ import annotations

import functools
import json
import sys

import numpy as np


class Circle:
    def residual(self, u):
        return np.array([u[0] ** 2 + u[1] ** 2 - 1.0])

    def jacobian(self, u):
        return np.array([[2 * u[0], 2 * u[1]]])


class Cubic:
    constraint_names = ("y >= -2", "y <= 2")

    def residual(self, u):
        return np.array([u[0] - (u[1] ** 3 - u[1])])

    def constraints(self, u):
        return np.array([u[1] + 2.0, 2.0 - u[1]])


class Hopf:
    def residual(self, u):
        x, y, w = u
        a = (x * x + y * y - 1) / 2
        return np.array([-w * w + a * a + 2 + x, -2 * a * w])

    def jacobian(self, u):
        x, y, w = u
        a = (x * x + y * y - 1) / 2
        return np.array([[2 * a * x + 1, 2 * a * y, -2 * w], [-2 * x * w, -2 * y * w, -2 * a]])


class HopfWithHook(Hopf):
    def compiled_step(self, *corrector):
        return _hopf_step()(*corrector)


@functools.cache
def _hopf_step():
    """The Hopf problem's compiled step: its residual compiled, the engine's corrector and tangent
    (``continuation.compiled.step``)."""
    from numba import njit
    from numba.extending import register_jitable

    from continuation.compiled import step

    @register_jitable
    def residual(u, jacobian, F, J):
        x, y, w = u[0], u[1], u[2]
        a = (x * x + y * y - 1) / 2
        F[0], F[1] = -w * w + a * a + 2 + x, -2 * a * w
        if jacobian:
            J[0, 0], J[0, 1], J[0, 2] = 2 * a * x + 1, 2 * a * y, -2 * w
            J[1, 0], J[1, 1], J[1, 2] = -2 * x * w, -2 * y * w, -2 * a

    @njit
    def hook(guess, t_plane, anchor, h, scale, tol, max_iter, max_move):
        return step(residual, (), guess, t_plane, anchor, h, scale, tol, max_iter, max_move)

    return hook


class Lines:
    def residual(self, u):
        return np.array([u[0] ** 2 - u[1] ** 2])

    def jacobian(self, u):
        return np.array([[2 * u[0], -2 * u[1]]])


class LineWithTest:
    test_function_names = ("x - 0.7",)
    constraint_names = ("x <= 2",)

    def residual(self, u):
        return np.array([u[1] - 0.5 * u[0]])

    def jacobian(self, u):
        return np.array([[-0.5, 1.0]])

    def constraints(self, u):
        return np.array([2.0 - u[0]])

    def test_functions(self, u, t):
        return np.array([u[0] - 0.7])


def _dataset(out: dict, name: str, ds) -> None:
    for k in list(ds.data_vars) + list(ds.coords):
        v = ds[k].values
        out[f"{name}/{k}"] = v.astype(str) if v.dtype.kind in "OU" else v
    out[f"{name}/attrs"] = np.array(
        json.dumps({k: str(v) for k, v in ds.attrs.items() if k not in ("history", "date_created")}, sort_keys=True)
    )


def _branch(out: dict, name: str, br) -> None:
    for k in ("points", "tangents", "arclength"):
        out[f"{name}/{k}"] = getattr(br, k)
    out[f"{name}/kinds"] = np.array(br.kinds)
    out[f"{name}/details"] = np.array(br.details)
    out[f"{name}/meta"] = np.array(
        [str(br.closed), *br.end_reasons, str(br.n_newton), str(br.n_residual), str(br.n_jacobian)]
    )


def snapshot() -> dict:
    import continuation
    from continuation import project

    try:  # the engine's options object and the curves' home in stability (issue 22)
        from continuation import TraceOptions
        from stability import fold_curve, neutral_curve

        def trace(problem, u0, callback=None, **options):
            return continuation.trace(problem, u0, TraceOptions(**options), callback=callback)

        def trace_both(problem, u0, **options):
            return continuation.trace_both(problem, u0, TraceOptions(**options))
    except ImportError:  # before: keywords, and the curves re-exported by continuation
        from continuation import fold_curve, neutral_curve, trace, trace_both

    out: dict = {}
    sliding = [
        ("q_sigma_fr0", "q", "sigma", dict(fr_inv=0.0, alpha_v=0.5), {}),
        ("q_sigma_fr03", "q", "sigma", dict(fr_inv=0.3, alpha_v=0.5), {}),
        ("q_sigma_fr03_av1e3", "q", "sigma", dict(fr_inv=0.3, alpha_v=1e3), {}),
        ("q_sigma_fr0_coarse", "q", "sigma", dict(fr_inv=0.0, alpha_v=0.5), dict(max_step=0.5, max_angle=1.0)),
        ("sigma_frinv", "sigma", "fr_inv", dict(q=-0.1, alpha_v=0.5), {}),
        ("q_frinv", "q", "fr_inv", dict(sigma=1.0, alpha_v=0.5), {}),
        ("sigma_alphav", "sigma", "alpha_v", dict(q=-0.1, fr_inv=0.3), {}),
        (
            "start_at_fold",
            "q",
            "sigma",
            dict(fr_inv=0.0, alpha_v=0.5),
            dict(start=[(-1 + np.sqrt(1 - 1 / 2.28), 2 * (2.28 - np.sqrt(2.28 * 1.28)), 1 / np.sqrt(1 - 1 / 2.28))]),
        ),
        ("start_zero_mode", "q", "sigma", dict(fr_inv=0.3, alpha_v=0.5), dict(start=[(0.0, 0.5, 0.0)])),
    ]
    for name, x, y, fixed, kw in sliding:
        for compiled in (True, False):
            ds = neutral_curve("sliding", x, y, fixed=fixed, compiled=compiled, **kw)
            _dataset(out, f"neutral/{name}/{'compiled' if compiled else 'python'}", ds)
    _dataset(out, "neutral/fixed_pivot", neutral_curve("fixed_pivot", "q", "sigma", fixed=dict(fr_inv=0.05)))
    _dataset(out, "neutral/rolling", neutral_curve("rolling", "q", "sigma", fixed=dict(fr_inv=0.3)))
    _dataset(
        out, "neutral/sliding_alpha_v_0", neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=0.0))
    )
    _dataset(
        out,
        "fold/q_sigma_frinv",
        fold_curve(
            "sliding",
            "q",
            "sigma",
            "fr_inv",
            fold_in="sigma",
            fixed=dict(fr_inv=0.0, alpha_v=0.5),
            z_range=(0.0, 0.3),
            max_step=0.1,
        ),
    )
    _dataset(
        out,
        "fold/q_sigma_alphav",
        fold_curve("sliding", "q", "sigma", "fr_inv", fold_in="sigma", fixed=dict(fr_inv=0.1, alpha_v=0.5)),
    )

    _branch(
        out,
        "engine/circle",
        trace(Circle(), [np.cos(0.3), np.sin(0.3)], fold_components=(0, 1), max_angle=0.15, max_step=0.3),
    )
    _branch(out, "engine/circle_coarse", trace(Circle(), [1.0, 0.0], max_angle=0.4, max_step=1.0, step=0.1))
    _branch(out, "engine/cubic", trace_both(Cubic(), [0.0, 0.0], fold_components=(0,), max_step=0.1))
    u0 = project(Hopf(), [1.1, 0.1, 1.6])
    _branch(out, "engine/hopf", trace(Hopf(), u0, fold_components=(0, 1)))
    _branch(out, "engine/hopf_hook", trace(HopfWithHook(), u0, fold_components=(0, 1)))
    _branch(out, "engine/lines", trace(Lines(), [-1.0, -1.0], max_points=200, max_arclength=2.5))
    _branch(out, "engine/line_test", trace_both(LineWithTest(), [0.0, 0.0], max_step=0.3))
    seen: list = []
    _branch(
        out, "engine/callback", trace(Circle(), [1.0, 0.0], callback=lambda u, t, k: seen.append(k) or len(seen) < 5)
    )

    # derived: dense output and nonlinear runs (listed apart)
    ds = neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))
    out["derived/dense_q_sigma_fr0"] = continuation.dense(ds, 16).sigma.values
    out["derived/dense_circle"] = continuation.dense(trace(Circle(), [1.0, 0.0]), 8)
    from stability import simulate

    for model, kw in (("sliding", dict(alpha_v=0.5)), ("rolling", {}), ("fixed_pivot", {})):
        r = simulate(model, t_end=60.0, omega=[0.05, 0.0, 1.0], k=[0.05, 0.0, 1.0], q=-0.1, fr_inv=0.3, sigma=1.0, **kw)
        for k in r.data_vars:
            if r[k].dtype.kind == "f":
                out[f"derived/simulate_{model}/{k}"] = r[k].values
    return out


def compare(a_path: str, b_path: str) -> int:
    a, b = np.load(a_path), np.load(b_path)
    keys = sorted(set(a.files) | set(b.files))
    bad = []
    n_main = 0
    for k in keys:
        if k not in a.files or k not in b.files:
            bad.append((k, "missing in one"))
            continue
        x, y = a[k], b[k]
        same = (
            x.shape == y.shape
            and x.dtype == y.dtype
            and (np.array_equal(x, y) if x.dtype.kind in "OUSb" else np.array_equal(x.view(np.uint8), y.view(np.uint8)))
        )  # bit for bit, NaN and -0.0 too
        if not k.startswith("derived/"):
            n_main += 1
            if not same:
                bad.append((k, "differs"))
        elif not same:
            d = np.nanmax(np.abs(x - y)) if x.shape == y.shape else np.inf
            print(f"derived {k}: differs, max |difference| {d:.2e} (max |value| {np.nanmax(np.abs(x)):.2e})")
        else:
            print(f"derived {k}: identical")
    print(f"{n_main} arrays of traced curves compared bit for bit: {n_main - len(bad)} identical")
    for k, why in bad:
        print(f"  {k}: {why}")
    return 1 if bad else 0


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    np.savez(sys.argv[1], **snapshot())
