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

:func:`python` gives the interpreted execution of any function compiled with :func:`njit` (its
public ``py_func``, with the compiled functions it calls re-bound to their own interpreted
executions): what a single query runs (the steady states, a final state, a short run's first
steps), compiling nothing; :func:`stability.execution.pick` chooses between the two by size.

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

__all__ = ["OPTIONS", "activate", "active", "cached", "in_memory", "njit", "overload", "python", "register_jitable"]

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
        f = _copy(fn, {**fn.__globals__, "prange": activate().prange}, "_parallel") if parallel else fn
        _CACHED[fn, parallel] = activate().njit(f, parallel=parallel, cache=True, **OPTIONS)
    return _CACHED[fn, parallel]


def in_memory(fn: Any, parallel: bool = False) -> bool:
    """Whether this process holds compiled code of ``fn`` (a numba dispatcher, or a function
    given to :func:`cached`): calling it compiles and loads nothing. Never imports numba."""
    return bool(getattr(_CACHED.get((fn, parallel), fn), "signatures", None))


# ------------------------------------------------------------------------------------------
# the interpreted execution of compiled functions
# ------------------------------------------------------------------------------------------
#: the packages whose functions :func:`python` re-binds (the rest of the world is left as it is)
_PACKAGES = ("stability", "continuation")
_PYTHON: dict[Any, Callable] = {}


def _ours(value: Any) -> bool:
    module = getattr(value, "__module__", None) or getattr(value, "__name__", "")
    return isinstance(module, str) and module.split(".")[0] in _PACKAGES


class _Interpreted(types.ModuleType):
    """A module of the package seen from interpreted code: its compiled functions are their
    :func:`python` executions (``sliding.rhs(...)`` inside a function run by :func:`python`)."""

    def __init__(self, module: types.ModuleType) -> None:
        super().__init__(module.__name__)
        self._module = module

    def __getattr__(self, name: str) -> Any:
        value = _rebound(getattr(self._module, name))
        setattr(self, name, value)  # found once
        return value


def _rebound(value: Any) -> Any:
    """``value`` as interpreted code sees it: a numba dispatcher (its public ``py_func``) or a
    function of the package by :func:`python`, a module of the package by :class:`_Interpreted`."""
    if (callable(value) and hasattr(value, "py_func")) or (isinstance(value, types.FunctionType) and _ours(value)):
        return python(value)
    return _Interpreted(value) if isinstance(value, types.ModuleType) and _ours(value) else value


def _names(code: types.CodeType) -> set[str]:
    """The global names a code object and the code nested in it refer to."""
    return set(code.co_names).union(*(_names(c) for c in code.co_consts if isinstance(c, types.CodeType)))


def _copy(fn: Callable, scope: dict[str, Any], suffix: str = "") -> Callable:
    """A copy of the function ``fn`` that reads its globals from ``scope``."""
    f = types.FunctionType(fn.__code__, scope, fn.__name__ + suffix, fn.__defaults__, fn.__closure__)
    f.__kwdefaults__, f.__module__, f.__qualname__ = fn.__kwdefaults__, fn.__module__, fn.__qualname__ + suffix
    return f


def python(fn: Any) -> Callable:
    """The interpreted execution of ``fn`` (a numba dispatcher, a plain function of the
    package, or a module of the package: its functions so executed): its Python source (the
    dispatcher's public ``py_func``), with every compiled function it reaches (through its
    globals, or attributes of the package's modules) run the same way. Nothing is compiled and
    numba's caches are not touched: what a single query runs (:mod:`stability.execution`). The
    same source as the compiled execution; the floating-point results agree to rounding (numba
    and numpy may round the library functions differently)."""
    if isinstance(fn, types.ModuleType):
        return _Interpreted(fn)
    key = getattr(fn, "py_func", fn)
    if key not in _PYTHON:
        names = dict(key.__globals__)
        _PYTHON[key] = _copy(key, names)  # before the globals: recursive functions find themselves
        names.update({k: _rebound(names[k]) for k in _names(key.__code__) if k in names})
    return _PYTHON[key]
