"""Which execution runs a loop that is written once: interpreted (Python) or compiled (numba).

The spectral kernel's loops, the batched root finders, the neutral curves' corrector, the
steady layer's closed forms and the integrators are each one plain Python source with two
executions that give the same bits (:func:`stability.jit.python` or the source itself, and
:func:`stability.jit.cached` or an ``njit`` function): the interpreter, which needs no
compilation but costs ~50-100 us per point, and numba, ~0.3 us per point once compiled but
several seconds to compile on a machine whose numba disk cache does not hold it yet (a fresh
install), and ~0.5 s to import numba and load it when it does. The rule (docs/performance.md, "The first call"):

* fewer than :data:`PYTHON_BELOW` points run interpreted, unless the compiled loop is already in
  memory in this process (then it runs, compiling and loading nothing); a first eigenvalue,
  threshold or neutral curve in a fresh process then takes a fraction of a second and imports
  no numba;
* larger requests run compiled; if that call is still compiling after :data:`NOTICE_AFTER`
  seconds, one line on stderr says so, once per process (:data:`NOTICE`, with the one estimate
  :data:`COMPILE_SECONDS`); ``tippe warmup`` compiles every loop ahead of time;
* the environment variable :data:`ENVIRONMENT` (``TIPPE_KERNEL``) forces a path: ``python``,
  ``compiled`` or ``auto`` (the default, the rule above); so does :func:`using` inside a block
  (the benchmarks of ``python benchmarks/run.py`` measure the compiled paths), and functions that take an
  ``engine`` argument take the same three values (None: :func:`using`'s, else the
  environment's).

:func:`use_compiled` is the rule, :func:`pick` the code it chooses: the entry point of each
path asks one of them, once per request.

The two executions run the same source on the same points: the tests compare them bit for bit
(an engine-agreement check; the independent references remain mpmath and the closed forms).
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time
from collections.abc import Iterator
from typing import Any

from . import jit
from .errors import InputError

__all__ = ["COMPILE_SECONDS", "ENGINES", "ENVIRONMENT", "NOTICE", "NOTICE_AFTER", "PYTHON_BELOW", "announce"]
__all__ += ["engine", "pick", "quiet", "use_compiled", "using"]

#: the environment variable that forces an execution
ENVIRONMENT = "TIPPE_KERNEL"

#: its values: the rule of the module docstring, the interpreter, numba
ENGINES = ("auto", "python", "compiled")

#: requests of fewer points run interpreted unless the compiled loop is in memory (~0.2-0.4 s of
#: interpreted work at this size, less than importing numba and loading a cached loop)
PYTHON_BELOW = 4096

#: what a first compilation on a cold cache takes, at most (s; the estimate of :data:`NOTICE`:
#: a model's kernel loop ~10 s, a first compiled run's integrator and right-hand sides ~18 s of
#: CPU on a 2-core machine with numba 0.68, docs/performance.md)
COMPILE_SECONDS = 20.0

#: the line printed on stderr, once per process, before a compilation (``{seconds}``: an estimate)
NOTICE = "tippe-stability: compiling kernels, once, ~{seconds:.0f} s (then cached; `tippe warmup` compiles them all)"

#: seconds a first compiled call runs before :data:`NOTICE` is printed (loading a cached loop
#: takes ~0.1-0.5 s, compiling one several seconds)
NOTICE_AFTER = 1.5

_STATE: dict[str, Any] = {"noticed": False, "quiet": False, "using": None}


def engine(value: str | None = None) -> str:
    """The execution asked for: ``value`` if given, else :func:`using`'s, else
    :data:`ENVIRONMENT`'s, else ``"auto"``.

    Raises
    ------
    InputError
        A value that is not one of :data:`ENGINES` (the message names where it came from).
    """
    chosen = value or _STATE["using"] or os.environ.get(ENVIRONMENT, "").strip().lower() or "auto"
    if chosen not in ENGINES:
        ok = ", ".join(ENGINES)
        where = f"the environment variable {ENVIRONMENT}" if value is None else "engine"
        ask = f"set it to one of {ok} (or unset it)" if value is None else f"choose one of {ok} or None ({ENVIRONMENT})"
        raise InputError(f"{where} = {chosen!r} is not known; {ask}")
    return chosen


def use_compiled(
    fn: Any, npts: float, value: str | None = None, *, below: int = PYTHON_BELOW, parallel: bool = False
) -> bool:
    """Whether a request of ``npts`` points runs ``fn`` compiled (module docstring): ``fn`` a
    numba dispatcher or a function given to :func:`stability.jit.cached` (with ``parallel``);
    None: no compiled code exists yet. ``below``: the size from which it runs compiled, where
    the interpreted cost per point is larger than the kernel's; ``value`` as in :func:`engine`.
    When it says yes, the compile notice is armed (:data:`NOTICE`)."""
    chosen = engine(value)
    if chosen == "python" or (chosen == "auto" and npts < below and not jit.in_memory(fn, parallel)):
        return False
    if not (_STATE["noticed"] or _STATE["quiet"] or jit.in_memory(fn, parallel)):
        _STATE["noticed"] = True
        threading.Thread(target=_notice, args=(fn, parallel), daemon=True).start()
    return True


def _notice(fn: Any, parallel: bool) -> None:
    """:data:`NOTICE` after :data:`NOTICE_AFTER` seconds, unless ``fn`` got into memory meanwhile
    (numba's public API cannot tell a cached function from one it must compile, but a load from
    the disk cache is quicker)."""
    time.sleep(NOTICE_AFTER)
    if not jit.in_memory(fn, parallel):
        print(NOTICE.format(seconds=COMPILE_SECONDS), file=sys.stderr, flush=True)  # noqa: T201 (the compile notice)


def pick(fn: Any, npts: float, value: str | None = None, **rule: Any) -> Any:
    """The code :func:`use_compiled` chooses for ``fn`` (``rule``: its ``below`` and
    ``parallel``): compiled (``fn`` itself if a numba dispatcher, else
    :func:`stability.jit.cached`), or its interpreted execution (:func:`stability.jit.python`)."""
    if use_compiled(fn, npts, value, **rule):
        return fn if hasattr(fn, "signatures") else jit.cached(fn, rule.get("parallel", False))
    return jit.python(fn)


def announce(text: str) -> None:
    """Say on stderr, before a long computation starts, what it will cost (one line; nothing
    while :func:`quiet` is active): the same channel as :data:`NOTICE`."""
    if not _STATE["quiet"]:
        print(f"tippe-stability: {text}", file=sys.stderr, flush=True)  # noqa: T201 (the notice channel)


@contextlib.contextmanager
def _setting(key: str, value: Any) -> Iterator[None]:
    previous, _STATE[key] = _STATE[key], value
    try:
        yield
    finally:
        _STATE[key] = previous


def quiet() -> contextlib.AbstractContextManager[None]:
    """No :data:`NOTICE` inside (``tippe warmup`` reports its own progress)."""
    return _setting("quiet", True)


def using(value: str) -> contextlib.AbstractContextManager[None]:
    """Every loop inside runs in the execution ``value`` (one of :data:`ENGINES`) unless a call
    asks for another; also a decorator. The suites of ``python benchmarks/run.py`` measure the compiled
    paths under ``using("compiled")``: their baselines and the package's default both get
    compiled code, as a long-running process has."""
    return _setting("using", engine(value))
