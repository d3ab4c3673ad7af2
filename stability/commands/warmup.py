"""``tippe warmup``: compile every compiled path once, ahead of time, and say what and how long.

A fresh install has an empty numba disk cache. Small requests run interpreted and compile
nothing (stability.execution); a large one compiles its loop first (a few seconds, said once
on stderr). This command compiles them all now, or loads them from numba's disk cache where it
already holds them, so that later processes only load: the spectral kernel's loops (the sliding
model's, with and without the domain test, serial and parallel; the coefficient loop of the
other models), the batched root finders and growth-rate signs, the neutral curves' compiled
corrector, the steady states' closed forms and the compiled step of their branch, and the
integrators of the nonlinear runs. Each line names a step and its time.
"""

from __future__ import annotations

import argparse
import functools
import os
import time
from collections.abc import Callable

HELP = "compile every compiled kernel now (numba's disk cache) and report the times"
DESCRIPTION = (
    "Compile (or load from numba's disk cache) every compiled path: the spectral kernel's loops, the batched root "
    "finders and growth-rate signs, the neutral curves' corrector, the steady states and their branch, the "
    "integrators. Later processes then load them instead of compiling (a first call with a large grid, or a "
    "first simulate, would otherwise compile for seconds)."
)


def arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``tippe warmup``."""
    p.add_argument("--list", action="store_true", help="list the steps without running them")


def steps() -> list[tuple[str, Callable[[], object], list]]:
    """``(what, call, loops)``: each step's name, a call that runs it compiled, and the
    ``(function, parallel)`` pairs it compiles by :func:`stability.jit.cached` (the test that
    every loop is covered)."""
    import numpy as np

    from ..jit import cached
    from ..linear import kernel, neutrality, roots
    from ..linear.growth import growth
    from ..linear.neutral_curves import neutral_curve
    from ..models import get_model
    from ..nonlinear import NONLINEAR_MODELS
    from ..nonlinear.runs import simulate
    from ..steady import branch, final, states

    sliding = kernel._model_kernels(get_model("sliding"))
    p = dict(q=np.linspace(-0.4, 0.4, 64), fr_inv=np.full(64, 0.3), sigma=np.ones(64), alpha_v=np.full(64, 0.5))
    p["mu"] = np.full(64, 2.28)
    c = get_model("rolling", warn=False).coefficients(q=p["q"], fr_inv=p["fr_inv"], sigma=p["sigma"], mu=p["mu"])
    quad = [np.ascontiguousarray(c[:, j]) for j in range(3)]
    top = dict(q=-0.1, sigma=1.0, fr_inv=0.3)  # the paper's top (Sec. 3(ii)) for the one-point steps
    kernels = (  # (what, the loop compiled, the call that compiles it)
        ("eigenvalue kernel, sliding model, domain test fused", sliding.checked, kernel.checked_model_spectrum),
        ("eigenvalue kernel, sliding model, masked", sliding.masked, kernel.model_spectrum),
        ("eigenvalue kernel on coefficients, other models", kernel._coefficient_loop, kernel.coefficient_spectrum),
    )
    out = [
        (
            f"{what} ({'parallel' if par else 'serial'})",
            functools.partial(call, *inputs, engine="compiled", parallel=par),
            [(loop, par)],
        )
        for par in (False, True)
        for (what, loop, call), inputs in zip(kernels, (("sliding", p), ("sliding", p), (c,)))
    ]
    quadratic, others = roots.quadratic_roots_many, neutrality._other_roots_many
    sliding_top = dict(top, alpha_v=0.5)
    out += [
        (
            "batched quadratic formula (method='polynomial')",
            lambda: cached(quadratic)(*quad, np.empty((64, 2), complex), np.empty((64, 2), bool)),
            [(quadratic, False)],
        ),
        (
            "batched other modes of the neutral condition",
            lambda: cached(others)(c, 3, p["sigma"], 1, np.empty((64, 1), complex)),
            [(others, False)],
        ),
        (
            "neutral curves: compiled corrector (sliding model)",
            lambda: neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5), compiled=True),
            [],
        ),
        (
            "growth-rate signs of every mode (batched; the atlases' leading growth rate)",
            lambda: growth("sliding", **p),
            [(roots.axis_growth_many, False)],
        ),
        (
            "steady states and the final state (sliding model)",
            lambda: (
                states.steady_states("sliding", **sliding_top),
                final.final_state(
                    "sliding", omega=[0.0, 0.0, 1.0], k=[0.05, 0.0, 1.0], velocity=[0.0, 0.0], **sliding_top
                ),
            ),
            [],
        ),
        (
            "branch of tilted states: compiled step (sliding model)",
            lambda: branch.steady_branch("sliding", **sliding_top, compiled=True),
            [],
        ),
    ]
    for name in NONLINEAR_MODELS:
        run = dict(top, alpha_v=0.5) if name == "sliding" else top
        out.append(
            (
                f"integrator, {name} model",
                lambda n=name, r=run: simulate(n, t_end=0.5, omega=[0, 0, 1], k=[1e-3, 0, 1], **r),
                [],
            )
        )
    return out


def run(args: argparse.Namespace) -> int:
    """Run ``tippe warmup``."""
    from .. import execution

    todo = steps()
    if args.list:
        print(*(what for what, _, _ in todo), sep="\n")
        return 0
    start = time.perf_counter()
    os.environ[execution.ENVIRONMENT] = "compiled"  # this process only: every step runs compiled
    with execution.quiet():
        for what, call, _loops in todo:
            t0 = time.perf_counter()
            call()
            print(f"{what}: {time.perf_counter() - t0:.1f} s (compiled, or loaded from the disk cache)", flush=True)
    print(
        f"warmup: {time.perf_counter() - start:.1f} s; numba's cache: "
        f"{os.environ.get('NUMBA_CACHE_DIR') or 'the __pycache__ folders of the installed package'}"
    )
    return 0
