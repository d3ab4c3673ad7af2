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
disk cache) first, ``twin.cached()`` whether numba's disk cache holds it for this machine. A
twin may be *parallel*: its source loops over ``prange`` (bound to the builtin ``range`` in the
module's namespace, so the Python execution and a serial compilation run an ordinary loop), and
its compilation sees numba's ``prange`` instead.

Disk cache. numba stamps the cache of a compiled function with a hash of its own source file
only: a compiled loop that calls a ``register_jitable`` function of another file would be loaded
stale after that file changed (the helpers are compiled into the loop). Every function compiled
through this module with ``cache=True`` is stamped instead with a hash of its own file, of
every source file of its package that registers functions for compiled code, and of every
source file of :mod:`continuation` (whose compiled building blocks are compiled into the
callers) (:func:`source_stamp`): editing any single-sourced formula invalidates the caches
that may contain it.

The numba options used across the package are :data:`OPTIONS` (IEEE arithmetic: no fastmath,
so no reassociation or contraction into fused multiply-adds, and the same bits as the Python
execution; numpy's error model, so a division by zero gives inf or NaN as in numpy).
"""

from __future__ import annotations

import functools
import hashlib
import os
import types
from collections.abc import Callable
from typing import Any

__all__ = [
    "OPTIONS",
    "Twin",
    "activate",
    "active",
    "in_disk_cache",
    "njit",
    "overload",
    "register_jitable",
    "source_stamp",
]

#: numba options of the compiled code of the package (module docstring)
OPTIONS: dict[str, Any] = dict(fastmath=False, nogil=True, error_model="numpy")

#: registrations waiting for numba: ("jitable", function, options) or ("overload", function, impl, options)
_PENDING: list[tuple] = []
_NUMBA: Any = None  # the numba module once activated

#: the text that marks a source file as holding functions for compiled code (source_stamp)
_MARKERS = (b"register_jitable", b"overload(")


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
    """:func:`numba.njit` after :func:`activate`, with the disk cache stamped by
    :func:`source_stamp` when ``cache=True``; for modules whose only purpose is compiled code."""

    def make(f: Callable) -> Any:
        disp = activate().njit(**options)(f)
        if options.get("cache"):
            _stamp(disp)
        return disp

    return make if fn is None else make(fn)


# ------------------------------------------------------------------------------------------
# the disk cache
# ------------------------------------------------------------------------------------------
@functools.cache
def _all_sources(root: str) -> tuple[tuple[str, bytes], ...]:
    """``(path, contents)`` of every ``.py`` file under ``root``, sorted by path."""
    out = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith((".", "__")))
        for name in sorted(files):
            if name.endswith(".py"):
                path = os.path.join(folder, name)
                with open(path, "rb") as f:
                    out.append((os.path.relpath(path, root), f.read()))
    return tuple(out)


def _package_sources(root: str) -> tuple[tuple[str, bytes], ...]:
    """The files of :func:`_all_sources` that register functions for compiled code (they
    contain one of :data:`_MARKERS`)."""
    return tuple((path, data) for path, data in _all_sources(root) if any(m in data for m in _MARKERS))


def _continuation_root() -> str:
    """The directory of the installed :mod:`continuation` package (found, not imported)."""
    import importlib.util

    spec = importlib.util.find_spec("continuation")
    return os.path.dirname(spec.origin) if spec is not None and spec.origin else ""


def _package_root(filename: str) -> str:
    """The top-level package directory of a source file (the highest folder with an
    ``__init__.py`` above it)."""
    folder = os.path.dirname(os.path.abspath(filename))
    while os.path.exists(os.path.join(os.path.dirname(folder), "__init__.py")):
        folder = os.path.dirname(folder)
    return folder


@functools.cache
def source_stamp(filename: str) -> bytes:
    """The stamp of numba's disk cache for a function defined in ``filename``: a SHA-256 of that
    file, of every source file of its top-level package and of this one that registers
    functions for compiled code, and of every source file of :mod:`continuation` (module
    docstring)."""
    h = hashlib.sha256()
    with open(filename, "rb") as f:
        h.update(f.read())
    for root in sorted({_package_root(filename), _package_root(__file__)}):
        for path, data in _package_sources(root):
            h.update(path.encode())
            h.update(hashlib.sha256(data).digest())
    engine = _continuation_root()
    for path, data in _all_sources(engine) if engine else ():
        h.update(b"continuation/" + path.encode())
        h.update(hashlib.sha256(data).digest())
    return h.digest()


def _stamp(disp: Any) -> None:
    """Stamp ``disp``'s disk cache with :func:`source_stamp` (numba's private cache API; left
    as numba made it if that is not there)."""
    try:
        cache_file = disp._cache._cache_file
        cache_file._source_stamp = source_stamp(disp.py_func.__code__.co_filename)
    except (AttributeError, OSError):
        pass


def in_disk_cache(disp: Any) -> bool | None:
    """Whether numba's disk cache holds compiled code of ``disp`` valid on this machine (same
    stamp, numba, Python, CPU and bytecode), read from its small index file without loading
    anything; None if that cannot be told (numba's private cache API changed)."""
    try:
        cache = disp._cache
        if not getattr(cache, "_enabled", False):
            return False
        index = cache._cache_file._load_index()
        if not index:
            return False
        codegen = disp.targetctx.codegen()
        magic = codegen.magic_tuple()
        return any(key[1] == magic and key[2] == cache._index_key(key[0], codegen)[2] for key in index)
    except Exception:  # private API: any change means "unknown", never a failure
        return None


class Compiled:
    """One or more numba dispatchers, asked as a whole whether calling them compiles: whether
    their code is in memory (:meth:`in_memory`) or in numba's disk cache (:meth:`cached`); what a
    caller needs to say "compiling, once" before a first call (the same two questions as
    :class:`Twin`'s). List the dispatchers that a call always runs (callees compiled into them
    have disk caches of their own and follow)."""

    def __init__(self, *dispatchers: Any) -> None:
        self.dispatchers = dispatchers

    def in_memory(self) -> bool:
        """Whether this process holds the compiled code of every one of them."""
        return all(bool(d.overloads) for d in self.dispatchers)

    def cached(self) -> bool | None:
        """Whether numba's disk cache holds every one of them (:func:`in_disk_cache`; None if
        that cannot be told for one)."""
        states = [in_disk_cache(d) for d in self.dispatchers]
        return None if None in states else all(states)


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
        return self._dispatcher is not None and bool(self._dispatcher.overloads)

    def cached(self) -> bool | None:
        """Whether numba's disk cache holds the compiled code for this machine
        (:func:`in_disk_cache`; imports numba)."""
        return in_disk_cache(self.dispatcher)

    def __call__(self, *args: Any) -> Any:
        """The compiled execution (compiled, or loaded from the disk cache, on first call)."""
        return self.dispatcher(*args)
