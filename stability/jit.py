"""One source, two executions: plain Python functions that numba compiles only on demand.

The numerical building blocks of the package are written once, as plain arithmetic that runs
on Python numbers, on numpy arrays and inside numba-compiled loops (the "one home per formula"
rule, docs/architecture.md). Layer 0 (it imports nothing of the package); the continuation
engine does not use it (its compiled face, :mod:`continuation.compiled`, registers its own
building blocks with numba's public API when imported). numba makes such a function callable from compiled code with
:func:`numba.extending.register_jitable` (or :func:`numba.extending.overload`), which registers
it at decoration time and so needs numba imported, ~0.45 s, before any compiled code is wanted.
This module defers that: its :func:`register_jitable` and :func:`overload` take the same
arguments as numba's, return the function unchanged, and register it with numba when compiled
code is first wanted (:func:`activate`), or at once if that has already happened. A process
that only ever runs the Python execution never imports numba.

:func:`activate` runs (it is idempotent)

* when a compiled function is made through this module (:func:`njit`, :func:`cached`);
* when called: an ``@numba.njit`` function of a user's own that calls, say,
  ``stability.models.inertia.inertia_g`` needs ``stability.jit.activate()`` called once before
  it compiles (the package installs no hook into numba: no ``numba_extensions`` entry point,
  which would run in every numba program of the environment).

:func:`cached` compiles a plain Python function of the package (a loop over points, say) with
``cache=True``, once per process and only when asked (the function itself stays the
interpreted execution); :func:`in_memory` tells whether calling that compilation would compile
(or load from numba's disk cache) first. A compilation may be *parallel*: the source loops over
``prange`` (bound to the builtin ``range`` in its module, so the Python execution and a serial
compilation run an ordinary loop), and the parallel compilation sees numba's ``prange``.

The interpreted execution of a compiled function is its plain source: the function given to
:func:`cached`, or the public ``py_func`` of an :func:`njit` dispatcher, whose callees are plain
:func:`register_jitable` functions (so that nothing compiles when it runs in Python): what a
single query runs (the steady states, a final state, a short run's first steps);
:func:`stability.execution.pick` chooses between the two by size.

Disk cache. Functions compiled with ``cache=True`` use numba's own disk cache, through its
public options only. numba revalidates a cached function against its own source file: after
editing a ``register_jitable`` formula of another file in a source checkout, clear the cache
(delete the ``*.nbi``/``*.nbc`` files under ``__pycache__``, or set ``NUMBA_CACHE_DIR`` to a new
directory); an installed release never changes its files.

The numba options used across the package are :data:`OPTIONS` (IEEE arithmetic: no fastmath,
so no reassociation or contraction into fused multiply-adds, and the same bits as the Python
execution; numpy's error model, so a division by zero gives inf or NaN as in numpy).
"""

from __future__ import annotations

import types
from collections.abc import Callable
from typing import Any

__all__ = ["OPTIONS", "activate", "active", "cached", "in_memory", "njit", "overload", "register_jitable"]

#: numba options of the compiled code of the package (module docstring)
OPTIONS: dict[str, Any] = dict(fastmath=False, nogil=True, error_model="numpy")

_PENDING: list[Callable[[Any], Any]] = []  # registrations waiting for numba (each takes the numba module)
_NUMBA: Any = None  # the numba module once activated


def _defer(register: Callable[[Any], Any]) -> None:
    _PENDING.append(register) if _NUMBA is None else register(_NUMBA)


def register_jitable(fn: Callable | None = None, **options: Any) -> Callable:
    """:func:`numba.extending.register_jitable`, deferred until compiled code is wanted.

    Used as numba's (``@register_jitable`` or ``@register_jitable(**options)``); returns the
    function itself, so that it runs as plain Python when called from Python.
    """

    def mark(f: Callable) -> Callable:
        _defer(lambda nb: nb.extending.register_jitable(**options)(f) if options else nb.extending.register_jitable(f))
        return f

    return mark if fn is None else mark(fn)


def overload(python_fn: Callable, jit_options: dict[str, Any] | None = None) -> Callable:
    """:func:`numba.extending.overload`, deferred until compiled code is wanted: ``impl``
    (the decorated typing function) stands for ``python_fn`` in compiled code."""

    def mark(impl: Callable) -> Callable:
        _defer(lambda nb: nb.extending.overload(python_fn, jit_options=dict(jit_options or {}))(impl))
        return impl

    return mark


def activate() -> Any:
    """Import numba and register every function marked so far; return the numba module.

    Call it before compiling code of your own that calls the package's formulas (module
    docstring).
    """
    global _NUMBA
    if _NUMBA is None:
        _NUMBA = __import__("numba")  # numba.extending with it
        while _PENDING:
            _PENDING.pop(0)(_NUMBA)
    return _NUMBA


def active() -> bool:
    """Whether numba has been activated in this process (:func:`activate`)."""
    return _NUMBA is not None


def njit(fn: Callable | None = None, **options: Any) -> Any:
    """:func:`numba.njit` after :func:`activate`; for modules whose only purpose is compiled code."""

    return activate().njit(**options) if fn is None else activate().njit(fn, **options)


_CACHED: dict[tuple[Callable, bool], Any] = {}


def cached(fn: Callable, parallel: bool = False) -> Any:
    """``fn`` (a plain function of the package) compiled with :data:`OPTIONS` and ``cache=True``:
    one numba dispatcher per process (made, not compiled, on the first request; imports numba).

    ``parallel=True`` compiles with ``parallel=True``, the name ``prange`` in the source then
    meaning numba's ``prange`` (module docstring); that copy is named ``<name>_parallel``, so
    that numba's disk cache keeps it apart from the serial compilation of the same source.
    """
    if (fn, parallel) not in _CACHED:
        f, scope, suffix = fn, {**fn.__globals__, "prange": activate().prange}, "_parallel"
        if parallel:  # a copy of fn reading its globals from scope
            f = types.FunctionType(fn.__code__, scope, fn.__name__ + suffix, fn.__defaults__, fn.__closure__)
            f.__kwdefaults__, f.__module__, f.__qualname__ = fn.__kwdefaults__, fn.__module__, fn.__qualname__ + suffix
        _CACHED[fn, parallel] = activate().njit(f, parallel=parallel, cache=True, **OPTIONS)
    return _CACHED[fn, parallel]


def in_memory(fn: Any, parallel: bool = False) -> bool:
    """Whether this process holds compiled code of ``fn`` (a numba dispatcher, or a function
    given to :func:`cached`): calling it compiles and loads nothing. Never imports numba."""
    return bool(getattr(_CACHED.get((fn, parallel), fn), "signatures", None))
