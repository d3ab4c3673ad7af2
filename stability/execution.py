"""Which execution runs a loop that is written once: interpreted (Python) or compiled (numba).

The spectral kernel's loops, the batched root finders and the neutral curves' corrector are
each one plain Python source (:class:`stability.jit.Twin`) with two executions that give the
same bits: the interpreter, which needs no compilation but costs ~50-100 us per point, and numba,
~0.3 us per point once compiled but several seconds to compile on a machine whose numba disk
cache does not hold it yet (a fresh install), and ~0.5 s to import numba and load it when it
does. The rule (docs/performance.md, "The first call"):

* fewer than :data:`PYTHON_BELOW` points run interpreted, unless the compiled loop is already in
  memory in this process (then it runs, compiling and loading nothing); a first eigenvalue,
  threshold or neutral curve in a fresh process then takes a fraction of a second and imports
  no numba;
* larger requests run compiled; if that call is still compiling after :data:`NOTICE_AFTER`
  seconds, one line on stderr says so, once per process (:data:`NOTICE`); ``tippe warmup``
  compiles every loop ahead of time;
* the environment variable :data:`ENVIRONMENT` (``TIPPE_KERNEL``) forces a path: ``python``,
  ``compiled`` or ``auto`` (the default, the rule above); so does :func:`using` inside a block
  (the benchmarks of ``python benchmarks/run.py`` measure the compiled paths), and functions that take an
  ``engine`` argument take the same three values (None: :func:`using`'s, else the
  environment's).

The two executions run the same source on the same points: the tests compare them bit for bit
(an engine-agreement check; the independent references remain mpmath and the closed forms).
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Iterator
from typing import Any

from .errors import InputError

__all__ = [
    "ENGINES",
    "ENVIRONMENT",
    "NOTICE",
    "NOTICE_AFTER",
    "PYTHON_BELOW",
    "announce",
    "before_compiled_call",
    "engine",
    "pick",
    "quiet",
    "use_compiled",
    "using",
]

#: the environment variable that forces an execution
ENVIRONMENT = "TIPPE_KERNEL"

#: its values: the rule of the module docstring, the interpreter, numba
ENGINES = ("auto", "python", "compiled")

#: requests of fewer points run interpreted unless the compiled loop is in memory (~0.2-0.4 s of
#: interpreted work at this size, less than importing numba and loading a cached loop)
PYTHON_BELOW = 4096

#: the line printed on stderr, once per process, before a compilation (``{seconds}``: an estimate)
NOTICE = (
    "tippe-stability: compiling kernels, once, ~{seconds:.0f} s "
    "(cached for later runs; `tippe warmup` compiles them all)"
)

#: seconds a first compiled call runs before :data:`NOTICE` is printed (loading a cached loop
#: takes ~0.1-0.5 s, compiling one several seconds)
NOTICE_AFTER = 1.5

_STATE: dict[str, Any] = {"noticed": False, "quiet": 0, "using": None}


def engine(value: str | None = None) -> str:
    """The execution asked for: ``value`` if given, else :func:`using`'s, else
    :data:`ENVIRONMENT`'s, else ``"auto"``.

    Raises
    ------
    InputError
        A value that is not one of :data:`ENGINES` (the message names where it came from).
    """
    using: str | None = _STATE["using"]
    if value is None and using is not None:
        return using
    if value is None:
        raw = os.environ.get(ENVIRONMENT, "").strip().lower()
        if raw in ("", "auto"):
            return "auto"
        if raw not in ENGINES:
            raise InputError(
                f"the environment variable {ENVIRONMENT} = {raw!r} is not known; "
                f"set it to one of {', '.join(ENGINES)} (or unset it)"
            )
        return raw
    if value not in ENGINES:
        raise InputError(
            f"engine = {value!r} is not known; choose one of {', '.join(ENGINES)} "
            f"or None (the environment variable {ENVIRONMENT}, default auto)"
        )
    return value


def use_compiled(twin: Any, npts: int, value: str | None = None) -> bool:
    """Whether ``twin`` (a :class:`stability.jit.Twin`) runs compiled on ``npts`` points
    (module docstring); ``value`` as in :func:`engine`."""
    chosen = engine(value)
    if chosen != "auto":
        return chosen == "compiled"
    return npts >= PYTHON_BELOW or twin.in_memory()


def pick(fn: Any, npts: int, value: str | None = None, *, below: int = PYTHON_BELOW) -> Any:
    """``fn`` (a function compiled by numba) or its interpreted execution
    (:func:`stability.jit.python`), by the rule of the module docstring for a request of
    ``npts`` points (``below``: the size from which it runs compiled, where the interpreted
    cost per point is larger than the kernel's); ``value`` as in :func:`engine`."""
    chosen = engine(value)
    if chosen == "compiled" or (chosen == "auto" and (npts >= below or _in_memory(fn))):
        return fn
    from .jit import python

    return python(fn)


def _in_memory(fn: Any) -> bool:
    """Whether this process holds the compiled code of ``fn`` (a :class:`stability.jit.Twin` or
    a numba dispatcher: its public ``signatures``)."""
    return fn.in_memory() if hasattr(fn, "in_memory") else bool(fn.signatures)


def before_compiled_call(twin: Any, seconds: float) -> None:
    """Say on stderr, once per process, that ``twin`` (a :class:`stability.jit.Twin` or a numba
    dispatcher) is being compiled (``seconds``: the
    estimate printed), if the call that follows is still compiling :data:`NOTICE_AFTER` seconds
    later (numba's public API cannot tell a cached function from one it must compile, but a
    load from the cache takes a fraction of that); nothing if ``twin`` is in memory already
    or while :func:`quiet` is active."""
    if _STATE["noticed"] or _STATE["quiet"] or _in_memory(twin):
        return
    _STATE["noticed"] = True

    def notice() -> None:
        if not _in_memory(twin):
            print(NOTICE.format(seconds=seconds), file=sys.stderr, flush=True)  # noqa: T201 (the compile notice)

    timer = threading.Timer(NOTICE_AFTER, notice)
    timer.daemon = True
    timer.start()


def announce(text: str) -> None:
    """Say on stderr, before a long computation starts, what it will cost (one line; nothing
    while :func:`quiet` is active): the same channel as :data:`NOTICE`."""
    if not _STATE["quiet"]:
        print(f"tippe-stability: {text}", file=sys.stderr, flush=True)  # noqa: T201 (the notice channel)


@contextlib.contextmanager
def quiet() -> Iterator[None]:
    """No :data:`NOTICE` inside (``tippe warmup`` reports its own progress)."""
    _STATE["quiet"] += 1
    try:
        yield
    finally:
        _STATE["quiet"] -= 1


@contextlib.contextmanager
def using(value: str) -> Iterator[None]:
    """Every loop inside runs in the execution ``value`` (one of :data:`ENGINES`) unless a call
    asks for another; also a decorator. The suites of ``python benchmarks/run.py`` measure the compiled
    paths under ``using("compiled")``: their baselines and the package's default both get
    compiled code, as a long-running process has."""
    chosen = engine(value)
    previous = _STATE["using"]
    _STATE["using"] = chosen
    try:
        yield
    finally:
        _STATE["using"] = previous
