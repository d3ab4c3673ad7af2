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

* when a compiled function is made through this module (:func:`njit`, :class:`Twin`);
* when called: an ``@numba.njit`` function of a user's own that calls, say,
  ``stability.models.inertia.inertia_g`` needs ``stability.jit.activate()`` called once before
  it compiles (the package installs no hook into numba: no ``numba_extensions`` entry point,
  which would run in every numba program of the environment).

:class:`Twin` pairs a plain Python function (a loop over points, say) with its numba
compilation, made on first use: ``twin.python`` runs interpreted, ``twin(...)`` compiled,
``twin.in_memory()`` tells whether calling the compiled one would compile (or load from numba's
disk cache) first. A twin may be *parallel*: its source loops over ``prange`` (bound to the
builtin ``range`` in the module's namespace, so the Python execution and a serial compilation
run an ordinary loop), and its compilation sees numba's ``prange`` instead.

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

__all__ = [
    "OPTIONS",
    "Twin",
    "activate",
    "active",
    "njit",
    "overload",
    "python",
    "register_jitable",
]

#: numba options of the compiled code of the package (module docstring)
OPTIONS: dict[str, Any] = dict(fastmath=False, nogil=True, error_model="numpy")

#: registrations waiting for numba: ("jitable", function, options) or ("overload", function, impl, options)
_PENDING: list[tuple] = []
_NUMBA: Any = None  # the numba module once activated


def _register(entry: tuple) -> None:
    import numba.extending

    if entry[0] == "jitable":
        if entry[2]:
            numba.extending.register_jitable(**entry[2])(entry[1])
        else:
            numba.extending.register_jitable(entry[1])
    else:
        numba.extending.overload(entry[1], jit_options=entry[3])(entry[2])


def register_jitable(fn: Callable | None = None, **options: Any) -> Callable:
    """:func:`numba.extending.register_jitable`, deferred until compiled code is wanted.

    Used as numba's (``@register_jitable`` or ``@register_jitable(**options)``); returns the
    function itself, so that it runs as plain Python when called from Python.
    """

    def mark(f: Callable) -> Callable:
        entry = ("jitable", f, options)
        if _NUMBA is not None:
            _register(entry)
        else:
            _PENDING.append(entry)
        return f

    return mark if fn is None else mark(fn)


def overload(python_fn: Callable, jit_options: dict[str, Any] | None = None) -> Callable:
    """:func:`numba.extending.overload`, deferred until compiled code is wanted: ``impl``
    (the decorated typing function) stands for ``python_fn`` in compiled code."""

    def mark(impl: Callable) -> Callable:
        entry = ("overload", python_fn, impl, dict(jit_options or {}))
        if _NUMBA is not None:
            _register(entry)
        else:
            _PENDING.append(entry)
        return impl

    return mark


def activate() -> Any:
    """Import numba and register every function marked so far; return the numba module.

    Call it before compiling code of your own that calls the package's formulas (module
    docstring).
    """
    global _NUMBA
    if _NUMBA is None:
        import numba

        _NUMBA = numba
        while _PENDING:
            _register(_PENDING.pop(0))
    return _NUMBA


def active() -> bool:
    """Whether numba has been activated in this process (:func:`activate`)."""
    return _NUMBA is not None


def njit(fn: Callable | None = None, **options: Any) -> Any:
    """:func:`numba.njit` after :func:`activate`; for modules whose only purpose is compiled code."""

    def make(f: Callable) -> Any:
        return activate().njit(**options)(f)

    return make if fn is None else make(fn)


# ------------------------------------------------------------------------------------------
# the interpreted execution of compiled functions
# ------------------------------------------------------------------------------------------
#: the packages whose functions :func:`python` re-binds (the rest of the world is left as it is)
_PACKAGES = ("stability", "continuation")


def _is_dispatcher(value: Any) -> bool:
    """Whether ``value`` is a numba dispatcher (its public ``py_func`` and ``signatures``)."""
    return callable(value) and hasattr(value, "py_func") and hasattr(value, "signatures")


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
    if _is_dispatcher(value) or (isinstance(value, types.FunctionType) and _ours(value)):
        return python(value)
    if isinstance(value, types.ModuleType) and _ours(value):
        return _Interpreted(value)
    return value


_PYTHON: dict[Any, Callable] = {}


def _names(code: types.CodeType) -> set[str]:
    """The global names a code object and the code nested in it refer to."""
    out = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            out |= _names(const)
    return out


def python(fn: Any) -> Callable:
    """The interpreted execution of ``fn`` (a numba dispatcher, a plain function of the
    package, or a module of the package: its functions so executed): its Python source (the dispatcher's public ``py_func``), with every compiled
    function it reaches (through its globals, or attributes of the package's modules) run the
    same way. Nothing is compiled and numba's caches are not touched: what a single query runs
    (:mod:`stability.execution`). The same source as the compiled execution; the floating-point
    results agree to rounding (numba and numpy may round the library functions differently)."""
    if isinstance(fn, types.ModuleType):
        return _Interpreted(fn)
    key = getattr(fn, "py_func", fn)
    if key in _PYTHON:
        return _PYTHON[key]
    names: dict[str, Any] = {}
    f = types.FunctionType(key.__code__, names, key.__name__, key.__defaults__, key.__closure__)
    f.__kwdefaults__ = key.__kwdefaults__
    f.__doc__, f.__module__, f.__qualname__ = key.__doc__, key.__module__, key.__qualname__
    _PYTHON[key] = f  # before the globals: recursive functions find themselves
    used = _names(key.__code__)
    names.update({k: _rebound(v) for k, v in key.__globals__.items() if k in used})
    names.setdefault("__builtins__", key.__globals__.get("__builtins__", __builtins__))
    for k, v in key.__globals__.items():
        names.setdefault(k, v)
    return f


# ------------------------------------------------------------------------------------------
# a Python function and its compilation
# ------------------------------------------------------------------------------------------
class Twin:
    """A plain Python function (:attr:`python`) and its numba compilation, made on demand.

    Parameters
    ----------
    python : callable
        The source, run as it is by the interpreter.
    parallel : bool, default False
        Compile with ``parallel=True``, the name ``prange`` in the source then meaning numba's
        ``prange`` (module docstring); the compiled copy is named ``<qualname>_parallel``, so that
        numba's disk cache keeps it apart from a serial compilation of the same source.
    **options
        Further numba options (``cache``, ``fastmath``, ...): :data:`OPTIONS` by default.
    """

    def __init__(self, python: Callable, *, parallel: bool = False, **options: Any):
        self.python = python
        self.parallel = bool(parallel)
        self.options = {**OPTIONS, **options}
        self._dispatcher: Any = None

    @property
    def __name__(self) -> str:
        return self.python.__name__ + ("_parallel" if self.parallel else "")

    def __repr__(self) -> str:
        return f"<Twin {self.python.__qualname__}{' (parallel)' if self.parallel else ''}>"

    @property
    def dispatcher(self) -> Any:
        """The numba dispatcher (made, not compiled, on first access; imports numba)."""
        if self._dispatcher is None:
            numba = activate()
            f = self.python
            if self.parallel:
                f = types.FunctionType(
                    f.__code__,
                    {**f.__globals__, "prange": numba.prange},
                    f.__name__ + "_parallel",
                    f.__defaults__,
                    f.__closure__,
                )
                f.__qualname__ = self.python.__qualname__ + "_parallel"
                f.__doc__ = self.python.__doc__
                f.__module__ = self.python.__module__
            self._dispatcher = njit(f, parallel=self.parallel, **self.options)
        return self._dispatcher

    @property
    def py_func(self) -> Callable:
        """The function numba compiles (:attr:`python`, or its parallel copy)."""
        return self.dispatcher.py_func

    def in_memory(self) -> bool:
        """Whether this process holds the compiled code (calling it compiles nothing, loads nothing)."""
        return self._dispatcher is not None and bool(self._dispatcher.signatures)

    def __call__(self, *args: Any) -> Any:
        """The compiled execution (compiled, or loaded from the disk cache, on first call)."""
        return self.dispatcher(*args)
