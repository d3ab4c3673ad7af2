"""The first call in a fresh process: one source, two executions, and what is imported.

Two kinds of check, said for each test:

* *engine agreement* (not an independent reference): the kernel's loops and the batched loops
  (stability.execution; stability.jit.cached) run interpreted (Python lists) and compiled
  (numba) on the same points must give the same bits, signed zeros included (a NaN must be a
  NaN in both; its sign bit, which IEEE 754 leaves unspecified, is not compared). The
  independent references of the numbers themselves stay where they are (mpmath in
  tests/test_kernel.py, tests/test_spectra_reference.py, tests/test_one_home.py; closed forms in
  tests/test_neutral.py and tests/test_thresholds.py); what these tests add is that a user gets
  the same answer whichever execution the size of the request picked.
* *import hygiene*, in fresh interpreters (this test process has imported and compiled
  everything): ``import stability`` imports nothing heavy, and a first eigenvalue, threshold,
  critical spin or neutral curve imports no numba (it runs interpreted: no compilation).

Speed is measured in benchmarks/cold_start.py, never here.
"""

from __future__ import annotations

import ast
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import stability
from stability import execution
from stability.errors import InputError
from stability.jit import cached
from stability.linear import kernel
from stability.linear.roots import axis_growth_many, cbrt, quadratic_roots_many

HEAVY = ("numba", "scipy", "xarray", "matplotlib", "dask", "pandas")


def _bits(a: np.ndarray) -> np.ndarray:
    """The bit patterns of a float or complex array, every NaN replaced by one quiet NaN (signed
    zeros compared; a NaN's sign is not specified by IEEE 754 and differs between code paths)."""
    a = np.array(a, dtype=np.complex128 if a.dtype.kind == "c" else np.float64)
    r = a.view(np.float64)
    r[np.isnan(r)] = np.nan
    return r.view(np.uint64)


def _assert_same(python, compiled) -> None:
    for x, y in zip(python, compiled):
        x, y = np.asarray(x), np.asarray(y)
        assert x.dtype == y.dtype and x.shape == y.shape
        if x.dtype.kind in "fc":
            np.testing.assert_array_equal(_bits(x), _bits(y))
        else:
            np.testing.assert_array_equal(x, y)


def _hard_points(n: int, seed: int) -> dict[str, np.ndarray]:
    """``n`` points of eq. (11)'s parameters that reach every branch of the kernel: spread over
    the physical domain with mu from 1e-3 to 1e3, alpha_v from 1e-6 to 1e6 and fr_inv from 1e-4
    to 1e3 (widely separated root scales: the deflation branch of the cubic); exact structural
    zeros (fr_inv = 0, alpha_v = 0, q = 0); sigma on its bound 2 A_G; points within 1e-9 of the
    neutral curve sigma = (1 - mu q^2)/(1 + q) at fr_inv = 0 (neutral decisions); points
    outside the domain; NaN, inf and values beyond the computable range."""
    rng = np.random.default_rng(seed)
    mu = 10.0 ** rng.uniform(-3, 3, n)
    q = rng.uniform(-0.999, 0.999, n) / np.sqrt(mu)
    a_g = 1.0 - mu * q * q
    sigma = rng.uniform(0.0, 1.0, n) * 2.0 * a_g
    fr_inv = 10.0 ** rng.uniform(-4, 3, n)
    alpha_v = 10.0 ** rng.uniform(-6, 6, n)
    k = np.arange(n)
    fr_inv[k % 7 == 0] = 0.0
    alpha_v[k % 11 == 0] = 0.0
    q[k % 13 == 0] = 0.0
    sigma[k % 17 == 0] = 2.0 * (1.0 - mu[k % 17 == 0] * q[k % 17 == 0] ** 2)
    near = k % 19 == 0  # the neutral curve of the paper's mu at fr_inv = 0, within 1e-9
    mu[near] = 2.28
    q[near] = rng.uniform(-0.6, 0.6, near.sum())
    sigma[near] = (1 - 2.28 * q[near] ** 2) / (1 + q[near]) * (1 + 1e-9 * rng.uniform(-1, 1, near.sum()))
    fr_inv[near] = 0.0
    out = k % 23 == 0  # outside: beyond |q| < 1/sqrt(mu), sigma > 2 A_G, fr_inv < 0
    q[out & (k % 3 == 0)] = 1.5 / np.sqrt(mu[out & (k % 3 == 0)])
    sigma[out & (k % 3 == 1)] = 3.0
    fr_inv[out & (k % 3 == 2)] = -0.1
    for j, bad in enumerate((np.nan, np.inf, -np.inf, 1e40)):
        (q, fr_inv, sigma, alpha_v, mu)[j % 5][29 * (j + 1)] = bad
    return dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu)


def test_checked_kernel_same_bits_interpreted_and_compiled():
    """Engine agreement of the default path (the domain test fused with the spectrum,
    kernel.checked_model_spectrum): 20,000 points of :func:`_hard_points`, every output
    (eigenvalues, error bounds, neutral flags, stability, inside, counts) bit for bit, serial
    and parallel compiled loops alike."""
    p = _hard_points(20_000, seed=151)
    py = kernel.checked_model_spectrum("sliding", p, engine="python")
    for parallel in (False, True):
        c = kernel.checked_model_spectrum("sliding", p, engine="compiled", parallel=parallel)
        _assert_same(py.spectrum, c.spectrum)
        _assert_same((py.inside,), (c.inside,))
        assert (py.n_outside, py.n_not_finite) == (c.n_outside, c.n_not_finite)
    assert py.n_outside > 0 and py.n_not_finite > 0 and np.any(py.spectrum.stability == 1)


def test_masked_kernel_and_domain_same_bits_interpreted_and_compiled():
    """Engine agreement of the kernel without the domain test (model_spectrum, with a mask) and
    of the domain test alone (model_domain), on the points of :func:`_hard_points` that are
    finite (the masked loop assumes checked input)."""
    p = _hard_points(5_000, seed=152)
    code = kernel.model_domain("sliding", p, engine="python")
    _assert_same((code,), (kernel.model_domain("sliding", p, engine="compiled"),))
    inside = code == 0
    py = kernel.model_spectrum("sliding", p, inside, engine="python")
    _assert_same(py, kernel.model_spectrum("sliding", p, inside, engine="compiled"))


def _polynomials(n: int, degree: int, seed: int) -> np.ndarray:
    """Random complex polynomials (leading coefficient nonzero): root scales from 1e-300 to 1e300
    (``c_k`` times ``s^(k/degree)``; Cardano overflows beyond ~1e100: the cubic's start on a
    circle), exactly zero trailing coefficients (structural roots), conservative quadratics
    (``p(i nu)`` real: real arithmetic in ``nu``)."""
    rng = np.random.default_rng(seed)
    c = rng.normal(size=(n, degree + 1)) + 1j * rng.normal(size=(n, degree + 1))
    c *= (10.0 ** rng.uniform(-300, 300, (n, 1))) ** (np.arange(degree + 1) / degree)
    k = np.arange(n)
    c[k % 5 == 0, -1] = 0.0
    if degree >= 2:
        c[k % 9 == 0, -2:] = 0.0
        cons = k % 4 == 1
        c[cons, 0] = c[cons, 0].real
        c[cons, 1] = 1j * c[cons, 1].imag
        c[cons, 2] = c[cons, 2].real
        if degree == 3:
            c[cons, 3] = 0.0
    return c


@pytest.mark.parametrize("degree", [1, 2, 3])
def test_coefficient_kernel_same_bits_interpreted_and_compiled(degree):
    """Engine agreement of the kernel on given coefficients (coefficient_spectrum: the models
    without a formula, eq. 8), degrees 1 to 3, on :func:`_polynomials`, with a mask."""
    c = _polynomials(3_000, degree, seed=153 + degree)
    inside = np.arange(len(c)) % 31 != 0
    py = kernel.coefficient_spectrum(c, inside, engine="python")
    _assert_same(py, kernel.coefficient_spectrum(c, inside, engine="compiled"))


def test_spectrum_same_bits_in_every_execution(monkeypatch):
    """Engine agreement through the public path, stability.spectrum, chosen by TIPPE_KERNEL:
    every model (the sliding model's fused kernel, the others' coefficient kernel)."""
    rng = np.random.default_rng(157)
    q = rng.uniform(-0.5, 0.5, 300)
    for model, extra in (("sliding", dict(alpha_v=0.5)), ("rolling_eq8", {}), ("fixed_pivot", {}), ("rolling", {})):
        out = {}
        for mode in ("python", "compiled"):
            monkeypatch.setenv(execution.ENVIRONMENT, mode)
            sp = stability.spectrum(model, q=q, fr_inv=0.3, sigma=0.8, mask_unphysical=True, **extra)
            out[mode] = (sp.eigenvalues, sp.error_bound, sp.neutral, sp.stability, sp.inside)
        _assert_same(out["python"], out["compiled"])


def test_batched_loops_same_bits_interpreted_and_compiled(monkeypatch):
    """Engine agreement of the other loops that run either way: the batched stable quadratic
    formula (roots.quadratic_roots_many, behind polynomial_roots) and the batched other modes
    of the neutral condition (neutrality._other_roots_many)."""
    from stability.linear.neutrality import NeutralCondition

    c = _polynomials(4_000, 2, seed=158)
    a, b, k = (np.ascontiguousarray(c[:, j]) for j in range(3))
    roots, exact = np.empty((len(c), 2), complex), np.empty((len(c), 2), bool)
    cached(quadratic_roots_many)(a, b, k, roots, exact)
    r_py, e_py = [[0j, 0j] for _ in c], [[False, False] for _ in c]
    quadratic_roots_many(a.tolist(), b.tolist(), k.tolist(), r_py, e_py)
    _assert_same((np.array(r_py), np.array(e_py)), (roots, exact))

    cond = NeutralCondition("rolling", ("q", "sigma"), dict(fr_inv=0.3, mu=2.28), form="crossing", compiled=False)
    rng = np.random.default_rng(159)
    values = np.column_stack([rng.uniform(-0.5, 0.5, 500), rng.uniform(0.1, 1.5, 500)])
    w = rng.uniform(-2, 2, 500)
    out = {}
    for mode in ("python", "compiled"):
        monkeypatch.setenv(execution.ENVIRONMENT, mode)
        out[mode] = cond.other_modes_many(values, w)
    _assert_same((out["python"],), (out["compiled"],))


def _cbrt_loop(x, out):
    for i in range(len(x)):
        out[i] = cbrt(x[i])


def test_cube_root_same_bits_in_both_executions():
    """Engine agreement of the one building block whose executions call different functions:
    roots.cbrt is math.cbrt (the C library's cbrt) interpreted and numba's numpy.cbrt compiled;
    200,000 values from 1e-300 to 1e300 of both signs, zeros, inf and NaN."""
    rng = np.random.default_rng(160)
    x = 10.0 ** rng.uniform(-300, 300, 200_000) * np.where(rng.random(200_000) < 0.5, -1.0, 1.0)
    x[:6] = (0.0, -0.0, np.inf, -np.inf, np.nan, 5e-324)
    compiled = np.empty_like(x)
    cached(_cbrt_loop)(x, compiled)
    _assert_same((np.array([math.cbrt(v) for v in x.tolist()]),), (compiled,))


def test_no_float_power_in_the_shared_source():
    """CPython's ``x ** 2`` on a float calls the C library's ``pow``, which is not always
    ``x * x`` (numba's lowering): 10 in 20,000 random values differ by an ulp. The source that
    runs in both executions (every ``register_jitable`` function, and the kernel's loops) must
    write squares as products; a power of a constant (``2.0**-53``) is fine."""
    roots = [Path(stability.__file__).parent, Path(stability.__file__).parent.parent / "continuation"]
    found = []
    for root in roots:
        for path in sorted(root.rglob("*.py")):
            tree = ast.parse(path.read_text(), str(path))
            shared = [
                f
                for f in ast.walk(tree)
                if isinstance(f, ast.FunctionDef)
                and (
                    (path.name == "kernel.py" and path.parent.name == "linear")
                    or any("register_jitable" in ast.unparse(d) for d in f.decorator_list)
                )
            ]
            for f in shared:
                for node in ast.walk(f):
                    if (
                        isinstance(node, ast.BinOp)
                        and isinstance(node.op, ast.Pow)
                        and not isinstance(node.left, ast.Constant)
                    ):
                        found.append(f"{path.name}:{node.lineno} {ast.unparse(node)}")
    assert not found, found


# --- the rule and its message ---------------------------------------------------------------


def test_engine_rule_and_its_errors(monkeypatch):
    """The execution asked for (stability.execution.engine and use_compiled): the argument wins,
    then TIPPE_KERNEL, then auto; auto runs interpreted below PYTHON_BELOW points unless the
    compiled loop is in memory (a numba dispatcher's public ``signatures``). A value that is not
    known is refused with its name and the allowed ones."""

    class Stub:  # a numba dispatcher as the rule sees it
        def __init__(self, in_memory):
            self.signatures = [()] if in_memory else []

    monkeypatch.delenv(execution.ENVIRONMENT, raising=False)
    small, large = execution.PYTHON_BELOW - 1, execution.PYTHON_BELOW
    with execution.quiet():  # no compile notice from these stubs
        assert not execution.use_compiled(Stub(False), small) and execution.use_compiled(Stub(False), large)
        assert execution.use_compiled(Stub(True), 1)
        assert execution.use_compiled(Stub(False), 1, "compiled") and not execution.use_compiled(
            Stub(True), large, "python"
        )
        monkeypatch.setenv(execution.ENVIRONMENT, "Python")
        assert not execution.use_compiled(Stub(True), large)
        assert execution.use_compiled(Stub(False), 1, "compiled")
    monkeypatch.setenv(execution.ENVIRONMENT, "numba")
    with pytest.raises(
        InputError, match=r"TIPPE_KERNEL = 'numba' is not known; set it to one of auto, python, compiled"
    ):
        execution.engine()
    with pytest.raises(InputError, match=r"engine = 'fast' is not known; choose one of auto, python, compiled"):
        stability.linear.kernel.coefficient_spectrum(np.ones((2, 3)), engine="fast")


def _run(code: str, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, **(env or {})},
    )


def test_compile_notice_once_per_process_and_only_if_not_cached(tmp_path):
    """The stderr line of a compilation: printed when the loop is not in memory and the call is
    still running NOTICE_AFTER seconds later (a compilation; a load from numba's disk cache is
    shorter), once per process, never inside execution.quiet() (tippe warmup). Checked in a
    fresh interpreter, without compiling (the call "runs" for 0.3 s, NOTICE_AFTER is 0.05 s)."""
    code = """
        import sys, time
        from stability import execution, jit
        from stability.linear import kernel
        execution.NOTICE_AFTER = 0.05
        execution.COMPILE_SECONDS = 7.0
        loop = kernel._coefficient_loop
        with execution.quiet():
            assert execution.use_compiled(loop, 1, "compiled", parallel=True)
        time.sleep(0.3)
        print("after quiet", file=sys.stderr, flush=True)
        assert execution.use_compiled(loop, 1, "compiled", parallel=True)
        assert execution.use_compiled(loop, 1, "compiled")
        time.sleep(0.3)
        assert not jit.in_memory(loop) and "numba" not in sys.modules
    """
    out = _run(code, {"NUMBA_CACHE_DIR": str(tmp_path)})
    assert out.returncode == 0, out.stderr
    assert out.stderr.splitlines() == ["after quiet", execution.NOTICE.format(seconds=7.0)]
    assert "tippe warmup" in out.stderr and "~7 s" in out.stderr


def test_compile_notice_before_a_first_compiled_run(tmp_path):
    """simulate's compiled integrators say so too before compiling on an empty cache (issue 15:
    a first simulate compiled ~18 s of CPU silently). Checked without compiling: the slices
    are not in memory and the "call" lasts longer than NOTICE_AFTER, so the line is printed, once."""
    code = """
        import sys, time
        from stability import execution
        from stability.nonlinear import integrators as I
        execution.NOTICE_AFTER = 0.05
        for slice_ in (I.dopri5_slice, I.rk4_slice):
            assert not slice_.signatures
            assert execution.pick(slice_, 1, "compiled") is slice_
        time.sleep(0.3)
    """
    out = _run(code, {"NUMBA_CACHE_DIR": str(tmp_path)})
    assert out.returncode == 0, out.stderr
    assert out.stderr.splitlines() == [execution.NOTICE.format(seconds=execution.COMPILE_SECONDS)]


# --- what a fresh process imports -----------------------------------------------------------


def test_import_stability_imports_nothing_heavy():
    """``import stability`` and ``import continuation`` (the lazy facades) import none of numba,
    scipy, xarray, matplotlib, dask, pandas; the command line's parser neither numba nor xarray."""
    out = _run(f"""
        import sys
        import stability, continuation
        heavy = [m for m in {HEAVY!r} if m in sys.modules]
        assert not heavy, heavy
        from stability.cli import build_parser
        build_parser()
        assert "numba" not in sys.modules and "xarray" not in sys.modules, sorted(sys.modules)
        print("ok")
    """)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


@pytest.mark.parametrize(
    "call, absent",
    [
        ('stability.eigenvalues("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)', ("numba", "scipy", "xarray")),
        ('stability.threshold("sigma", q=-0.2, fr_inv=0.0, alpha_v=0.5)', ("numba", "scipy", "xarray")),
        ('stability.critical_spin(stability.Top.table1(), orientation="upright")', ("numba", "scipy", "xarray")),
        ('stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))', ("numba",)),
        (
            'stability.spectrum("sliding", q=np.linspace(-0.4, 0.4, 5000), fr_inv=0.3, sigma=1.0, alpha_v=0.5)',
            ("numba",),
        ),
    ],
)
def test_a_first_call_compiles_nothing(call, absent):
    """A first eigenvalue, threshold, critical spin and neutral curve in a fresh process run
    interpreted: numba is not imported (nor scipy or xarray where the call needs none). The
    last case is a large request with TIPPE_KERNEL=python, which forces the interpreter."""
    env = {execution.ENVIRONMENT: "python"} if "5000" in call else {execution.ENVIRONMENT: "auto"}
    out = _run(
        f"""
        import sys
        import numpy as np
        import continuation, stability
        {call}
        loaded = [m for m in {absent!r} if m in sys.modules]
        assert not loaded, loaded
        print("ok")
    """,
        env,
    )
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr
    assert out.stderr == ""


def test_warmup_covers_every_loop_and_lists_its_steps(capsys):
    """``tippe warmup`` compiles every loop a request can choose to compile: its steps name the
    twins of the sliding model's kernel (fused and masked, serial and parallel), of the
    coefficient kernel, of the batched quadratic formula, of the other modes of the neutral
    condition and of the batched growth-rate signs. A structural check (nothing is compiled here:
    ``--list`` prints the steps)."""
    from stability.cli import main
    from stability.commands.warmup import steps
    from stability.linear import neutrality

    todo = steps()
    twins = {loop for _, _, loops in todo for loop in loops}
    sliding = kernel._model_kernels(stability.get_model("sliding"))
    expected = [
        *((f, p) for f in (sliding.checked, sliding.masked, kernel._coefficient_loop) for p in (False, True)),
        (quadratic_roots_many, False),
        (neutrality._other_roots_many, False),
        (axis_growth_many, False),
    ]
    assert all(t in twins for t in expected)
    assert main(["warmup", "--list"]) == 0
    assert capsys.readouterr().out.splitlines() == [what for what, _, _ in todo]
