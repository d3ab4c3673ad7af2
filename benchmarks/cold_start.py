"""Benchmark: the first call in a fresh process, on a cold and on a warm numba cache.

Each measurement is its own fresh interpreter (``python -c``), so that nothing is imported or
compiled beforehand. *Cold*: numba's disk cache is an empty directory (``NUMBA_CACHE_DIR``, the
state right after ``pip install``); *warm*: the same directory after that cold run (the state
of every later run of the same call), measured right after it: the baseline of the cold time,
cold / warm printed. Two executions of each call, measured in the same run:

* ``auto``: the package as shipped (stability.execution: single queries, short runs and small
  batches interpreted unless compiled code is in memory, large ones compiled);
* ``compiled``: ``TIPPE_KERNEL=compiled``, every loop compiled (or loaded) before its first
  use: the behaviour before the interpreted execution existed, the baseline.

Per call: the wall time of the whole process (interpreter start, imports, the call), the
call's own time inside the process, and the process's CPU time (user + sys; the machines are
shared, and CPU time is less disturbed by other load than wall time). The minimum over
``--repeat`` runs is reported. With ``--fresh-venv`` the package is first installed
(``pip install``, not editable, no extras) into a new temporary virtual environment and
measured there: what a user gets from a fresh install.

Run: ``python benchmarks/cold_start.py [--repeat 3] [--calls NAME ...] [--fresh-venv]
[--json out.json]`` (about 10 minutes, most of it the compiled baseline compiling; 10 more with
``--fresh-venv``, most of it pip).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
import venv
from pathlib import Path

#: the README's "Where the top goes" block, as a user pastes it
README_BLOCK = """\
from stability.nonlinear.scene import INITIAL_CONDITIONS
stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
branch = stability.steady_branch(q=-0.2, sigma=1.3, fr_inv=0.5, alpha_v=0.5)
branch.where(branch.kind != "", drop=True)
end = stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3])
end.tilt, end.kind, end.method, end.axial_spin
stability.top_class(q=-0.1, sigma=1.0)
stability.class_atlas(q=np.linspace(-0.6, 0.6, 121), sigma=np.linspace(0.01, 2, 200))"""

#: name -> (code run after ``import numpy as np, stability, continuation``, modes measured)
CALLS: dict[str, tuple[str, tuple[str, ...]]] = {
    "import stability": ("pass", ("auto",)),
    "tippe --help": ("", ("auto",)),
    "first eigenvalue": (
        'stability.eigenvalues("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)',
        ("auto", "compiled"),
    ),
    "first threshold": ('stability.threshold("sigma", q=-0.2, fr_inv=0.0, alpha_v=0.5)', ("auto", "compiled")),
    "first critical spin": (
        'stability.critical_spin(stability.Top.table1(), orientation="upright")',
        ("auto", "compiled"),
    ),
    "first neutral curve": (
        'stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))',
        ("auto", "compiled"),
    ),
    "README atlas (181 x 3)": (
        'stability.atlas("sliding", q=np.linspace(-0.45, 0.45, 181), fr_inv=[0, 0.1, 0.3], sigma=1.0, alpha_v=0.5)',
        ("auto", "compiled"),
    ),
    "spectrum of 10^5 points": (
        'stability.spectrum("sliding", q=np.linspace(-0.45, 0.45, 100_000), fr_inv=0.3, sigma=1.0, alpha_v=0.5)',
        ("auto",),
    ),
    "first simulate (t_end = 50)": (
        'stability.simulate("sliding", t_end=50.0, omega=[0, 0, 1], k=[1e-3, 0, 1], '
        "q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)",
        ("auto", "compiled"),
    ),
    "first final_state (Jellett)": (
        "from stability.nonlinear.scene import INITIAL_CONDITIONS\n"
        "stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3])",
        ("auto", "compiled"),
    ),
    "first steady_branch": (
        "stability.steady_branch(q=-0.2, sigma=1.3, fr_inv=0.5, alpha_v=0.5)",
        ("auto", "compiled"),
    ),
    "README 'Where the top goes'": (README_BLOCK, ("auto", "compiled")),
    "first launch": (
        "top = stability.Top(mass=0.015, radius=0.015, com_offset=-0.003, inertia_transverse=1.3e-6, "
        "inertia_axial=1.5e-6)\n"
        'stability.launch(top, 15, unit="rev/s")',
        ("auto", "compiled"),
    ),
}

_TEMPLATE = """
import time
t0 = time.perf_counter()
import numpy as np, stability, continuation
t1 = time.perf_counter()
{code}
t2 = time.perf_counter()
import json, sys
print(json.dumps({{"imports": t1 - t0, "call": t2 - t1, "numba": "numba" in sys.modules}}))
"""


def measure(python: str, name: str, mode: str, cache: str, cwd: str) -> dict:
    """One fresh process: wall and CPU time of the process, the call's time inside it, whether
    it imported numba, and whether it printed the compile notice."""
    code, _ = CALLS[name]
    argv = (
        [python, "-m", "stability", "--help"] if name == "tippe --help" else [python, "-c", _TEMPLATE.format(code=code)]
    )
    env = {**os.environ, "NUMBA_CACHE_DIR": cache, "TIPPE_KERNEL": mode}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    out = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=cwd, timeout=900)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        raise RuntimeError(f"{name} ({mode}) failed:\n{out.stderr}")
    row = {
        "wall": wall,
        "cpu": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
        "notice": "compiling kernels" in out.stderr,
    }
    if name != "tippe --help":
        row.update(json.loads(out.stdout.strip().splitlines()[-1]))
    return row


def run_table(python: str, repeat: int, names: list[str]) -> dict:
    """Every call in each of its modes, cold and then warm: each repeat runs the call in a fresh
    process on a new empty cache directory (cold), then again in a fresh process on the cache
    that run filled (warm: what every later process of the user gets); the minimum over
    ``repeat`` runs, and the ratio cold / warm."""
    results: dict = {}
    with tempfile.TemporaryDirectory(prefix="tippe-cold-") as tmp:
        for name in names:
            for mode in CALLS[name][1]:
                rows: dict[str, list] = {"cold": [], "warm": []}
                for k in range(repeat):
                    cache = os.path.join(tmp, f"cache-{k}")
                    for state in ("cold", "warm"):
                        rows[state].append(measure(python, name, mode, cache, tmp))
                    shutil.rmtree(cache, ignore_errors=True)
                for state in ("cold", "warm"):
                    best = {
                        key: min(r[key] for r in rows[state])
                        for key in ("wall", "cpu", *(("call",) if "call" in rows[state][0] else ()))
                    }
                    best["notice"] = any(r["notice"] for r in rows[state])
                    best["numba"] = any(r.get("numba", False) for r in rows[state])
                    results.setdefault(name, {}).setdefault(mode, {})[state] = best
                cold, warm = results[name][mode]["cold"], results[name][mode]["warm"]
                print(
                    f"{name:30s} {mode:9s} cold {cold['wall']:6.2f} s wall ({cold['cpu']:6.2f} s CPU"
                    + (f", call {cold['call']:6.3f} s" if "call" in cold else "")
                    + f"), warm {warm['wall']:6.2f} s wall"
                    + (f" (call {warm['call']:6.3f} s)" if "call" in warm else "")
                    + f": cold / warm {cold['wall'] / warm['wall']:5.2f}"
                    + ("; numba imported" if cold["numba"] else "")
                    + ("; compile notice" if cold["notice"] else ""),
                    flush=True,
                )
    return results


_CROSSOVER = """
import json, os, time
import stability
from stability import execution
from stability.nonlinear import integrators

kw = dict(omega=[0, 0, 1], k=[1e-3, 0, 1], q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
out = {}
for mode in ("python", "compiled"):
    os.environ[execution.ENVIRONMENT] = mode
    t = time.perf_counter()
    stability.simulate("sliding", t_end=1.0, **kw)  # the compiled run: compile or load here
    out[mode + "_first"] = time.perf_counter() - t
    for t_end in (50.0, 200.0):
        t = time.perf_counter()
        ds = stability.simulate("sliding", t_end=t_end, **kw)
        out[f"{mode}_{t_end:g}"] = (time.perf_counter() - t, int(ds.attrs["naccept"]) + int(ds.attrs["nreject"]))
print(json.dumps(out))
"""


def crossover(python: str, cwd: str, cache: str) -> dict:
    """The interpreted integrator's cost per step against the compiled one's, in one process on
    ``cache`` (run it twice: the first fills the cache), and the step count from which compiling
    pays (:data:`stability.nonlinear.integrators.INTERPRETED_STEPS`)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache}
    out = subprocess.run([python, "-c", _CROSSOVER], capture_output=True, text=True, env=env, cwd=cwd, check=True)
    r = json.loads(out.stdout.strip().splitlines()[-1])
    (tp, n), (tc, _) = r["python_200"], r["compiled_200"]
    r["python_ms_per_step"] = 1e3 * tp / n
    r["compiled_ms_per_step"] = 1e3 * tc / n
    return r


def fresh_venv(source: Path, where: str) -> str:
    """A new virtual environment with the package installed from ``source`` (not editable, no
    extras): its python."""
    venv.EnvBuilder(with_pip=True).create(where)
    python = os.path.join(where, "bin", "python")
    t = time.perf_counter()
    subprocess.run([python, "-m", "pip", "install", "-q", str(source)], check=True)
    print(f"pip install into a fresh venv: {time.perf_counter() - t:.0f} s", flush=True)
    return python


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per measurement (the minimum is kept)")
    parser.add_argument("--python", default=sys.executable, help="the interpreter to measure (default: this one)")
    parser.add_argument(
        "--fresh-venv",
        action="store_true",
        help="install the package into a new temporary venv and measure that (no dask)",
    )
    parser.add_argument("--calls", nargs="*", default=list(CALLS), help="which calls (default: all)")
    parser.add_argument("--json", help="also write the results as JSON")
    parser.add_argument(
        "--crossover", action="store_true", help="also measure the integrator's interpreted and compiled cost per step"
    )
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="tippe-venv-") as tmp:
        python = fresh_venv(Path(__file__).resolve().parent.parent, tmp) if args.fresh_venv else args.python
        extras = subprocess.run(
            [python, "-c", "import importlib.util as u; print(u.find_spec('dask') is not None)"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        print(
            f"interpreter {python}; dask installed: {extras}; {os.cpu_count()} cores; "
            f"load average {os.getloadavg()[0]:.2f}",
            flush=True,
        )
        results = run_table(python, args.repeat, args.calls)
        if args.crossover:
            with tempfile.TemporaryDirectory(prefix="tippe-cross-") as cache:
                cold = crossover(python, cache, cache)
                warm = crossover(python, cache, cache)
            results["crossover"] = {"cold": cold, "warm": warm}
            print(
                f"integrator: interpreted {warm['python_ms_per_step']:.2f} ms per step, compiled "
                f"{warm['compiled_ms_per_step']:.4f} ms; first compiled run {cold['compiled_first']:.1f} s cold, "
                f"{warm['compiled_first']:.2f} s warm: compiling pays from "
                f"~{cold['compiled_first'] / warm['python_ms_per_step'] * 1e3:.0f} steps cold, "
                f"~{warm['compiled_first'] / warm['python_ms_per_step'] * 1e3:.0f} warm",
                flush=True,
            )
        results["dask_installed"] = extras == "True"
        results["load_average_after"] = os.getloadavg()[0]
        print(f"load average now {results['load_average_after']:.2f}")
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
