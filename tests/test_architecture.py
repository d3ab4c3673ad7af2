"""The import layers of the package (docs/architecture.md), checked on the installed code.

Why: the folder tree is meant to show the architecture, models -> linear -> grids / nonlinear ->
recipes -> plotting -> command line, and the continuation engine is meant to be
generic. Nothing but a test keeps it so. This one walks every module of the installed
``stability`` and ``continuation`` packages (found with ``pkgutil`` from the imported packages,
not from a source path), parses each with ``ast`` and collects every import: at module level and
inside functions (a lazy import is still a dependency), relative imports resolved. Imports
under ``if TYPE_CHECKING:`` are left out (annotations only, never executed). ``from pkg import
name`` counts as an import of the submodule ``pkg.name`` when there is one, else of ``pkg``.
Importing a submodule also runs its parent packages' ``__init__``; that implicit step is not
counted (otherwise every module would depend on the ``stability`` facade). A facade imports its
names lazily through a module-level table ``_EXPORTS`` (name -> module, ``.relative`` or
absolute): the modules named there count as its imports.

It fails on

1. an import of a higher layer (a lower layer must not know what is built on it);
2. an import cycle among modules (a strongly connected component of more than one module, lazy
   imports included: a cycle hidden in a function is still a cycle);
3. an import of ``stability`` from any module of ``continuation``, its ``__init__`` included
   (the engine knows nothing about tops; its clients, ``stability.neutral_curve`` and
   ``stability.steady_branch``, live in the application);
4. a module that is in no layer (a new module must be placed in the table below, and in the
   table of docs/architecture.md, which mirrors it).
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import pathlib
import pkgutil

import pytest

PACKAGES = ("stability", "continuation")

#: (module or package prefix, layer); the longest matching prefix decides. Mirrors the table in
#: docs/architecture.md. Imports may go to the same or a lower layer only.
LAYERS: tuple[tuple[str, int], ...] = (
    ("continuation", 0),  # the generic engine (its __init__ is a facade, below)
    ("stability._version", 0),
    ("stability.errors", 0),
    ("stability.products", 0),
    ("stability.execution", 0),
    ("stability.jit", 0),  # one source, two executions (numba on demand)
    ("stability.interrupts", 0),  # signals as flags, checkpoints, temporary files
    ("stability.resources", 0),  # memory estimates and limits
    ("stability.files", 0),  # output files and their atomic commit (grids, plotting, benchmarks)
    ("stability.parameters", 1),
    ("stability.models", 1),
    ("stability.top", 1),
    ("stability.stick", 1),
    ("stability.linear", 2),
    ("stability.nonlinear", 3),
    ("stability.grids", 3),
    ("stability.steady", 4),  # steady states, branch, final state, classes
    ("stability.recipes", 5),
    ("stability.launches", 5),  # launch, flip_time: a real top launched (issue 23)
    ("stability.plotting", 6),
    ("stability.commands", 8),
    ("stability.cli", 8),
    ("stability.__main__", 8),
)

#: package __init__ modules that only re-export the public API (the top layer)
FACADES: dict[str, int] = {"stability": 8, "continuation": 8}


def _modules() -> dict[str, tuple[str, bool]]:
    """Every module of the installed packages: name -> (source file, is a package)."""
    out = {}
    for pkg in PACKAGES:
        mod = importlib.import_module(pkg)
        out[pkg] = (mod.__file__, True)
        for info in pkgutil.walk_packages(mod.__path__, pkg + "."):
            spec = importlib.util.find_spec(info.name)
            out[info.name] = (spec.origin, info.ispkg)
    return out


MODULES = _modules()


def layer(name: str) -> int | None:
    if name in FACADES:
        return FACADES[name]
    best = None
    for prefix, lay in LAYERS:
        if (name == prefix or name.startswith(prefix + ".")) and (best is None or len(prefix) > len(best[0])):
            best = (prefix, lay)
    return None if best is None else best[1]


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _import_nodes(tree: ast.AST):
    """Import and ImportFrom nodes anywhere in the tree, except in ``if TYPE_CHECKING:`` bodies."""
    stack = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            stack.extend(node.orelse)
            continue
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        stack.extend(ast.iter_child_nodes(node))


def _lazy_exports(tree: ast.Module, package: str) -> set[str]:
    """The modules named in a module-level ``_EXPORTS`` table (a facade's lazy imports): its
    string values that start with "." (relative to ``package``) or with a package's name."""
    out = set()
    for node in tree.body:
        targets = (
            node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        )
        if not any(isinstance(t, ast.Name) and t.id == "_EXPORTS" for t in targets) or node.value is None:
            continue
        values = node.value.values if isinstance(node.value, ast.Dict) else [node.value]
        for v in values:
            for c in ast.walk(v):
                if isinstance(c, ast.Constant) and isinstance(c.value, str):
                    if c.value.startswith("."):
                        out.add(package + c.value)
                    elif c.value.split(".")[0] in PACKAGES:
                        out.add(c.value)
    return out


def imports_of(name: str) -> set[str]:
    """The package modules ``name`` imports (module level and in functions)."""
    path, is_pkg = MODULES[name]
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    package = name if is_pkg else name.rpartition(".")[0]
    found = {t for t in _lazy_exports(tree, package) if t in MODULES and t != name}
    for node in _import_nodes(tree):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        else:
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1])
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base for a in node.names]
        for t in targets:
            # "import stability.grids.chunked" is an import of that module (or the nearest
            # enclosing module that exists, for an attribute path)
            while t not in MODULES and "." in t:
                t = t.rpartition(".")[0]
            if t in MODULES and t != name:
                found.add(t)
    return found


GRAPH = {name: imports_of(name) for name in MODULES}


def test_the_walk_finds_the_packages():
    """A sanity check of the walk itself: the facades, a few modules of each layer, the lazy
    facade import of continuation/__init__ and a function-level import are seen."""
    for name in (
        "stability",
        "continuation",
        "stability.errors",
        "stability.linear.kernel",
        "stability.grids.atlases",
        "stability.nonlinear.runs",
        "stability.steady.final",
        "stability.commands.atlas",
        "continuation.engine",
    ):
        assert name in MODULES
    assert "continuation.engine" in GRAPH["continuation"]  # lazy, in _EXPORTS
    assert "stability.linear.spectra" in GRAPH["stability"]  # lazy, in _EXPORTS
    assert "stability.linear.kernel" in GRAPH["stability.linear.spectra"]  # inside a function
    hidden = ast.parse("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import a\nelse:\n    import b\n")
    assert [n.names[0].name for n in _import_nodes(hidden) if isinstance(n, ast.Import)] == ["b"]  # TYPE_CHECKING


def test_every_module_has_a_layer():
    missing = sorted(name for name in MODULES if layer(name) is None)
    assert not missing, f"modules in no layer (add them to LAYERS and docs/architecture.md): {missing}"


def test_no_import_goes_up_a_layer():
    upward = sorted(
        f"{a} (layer {layer(a)}) imports {b} (layer {layer(b)})"
        for a, targets in GRAPH.items()
        for b in targets
        if layer(a) is not None and layer(b) is not None and layer(b) > layer(a)
    )
    assert not upward, "imports of a higher layer:\n" + "\n".join(upward)


def test_the_engine_does_not_import_stability():
    bad = sorted(
        f"{a} imports {b}"
        for a, targets in GRAPH.items()
        if a.split(".")[0] == "continuation"
        for b in targets
        if b.split(".")[0] == "stability"
    )
    assert not bad, "continuation (its __init__ included) must not import stability:\n" + "\n".join(bad)


def test_using_the_engine_imports_nothing_of_stability():
    """At run time too: a fresh interpreter imports continuation, traces a circle with the
    engine (Python path) and its dense output, and has not imported any module of stability."""
    import subprocess
    import sys

    code = (
        "import sys, numpy as np, continuation\n"
        "class Circle:\n"
        "    def residual(self, u): return np.array([u[0] ** 2 + u[1] ** 2 - 1.0])\n"
        "    def jacobian(self, u): return np.array([[2 * u[0], 2 * u[1]]])\n"
        "br = continuation.trace(Circle(), [1.0, 0.0])\n"
        "continuation.dense(br, 4)\n"
        "assert br.closed, br.end_reasons\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] == 'stability'))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"
    assert not {"neutral_curve", "steady_branch", "fold_curve"} & set(importlib.import_module("continuation").__all__)


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    out: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, it = work[-1]
            for nxt in it:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(graph[nxt]))))
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = []
                    while True:
                        m = stack.pop()
                        on_stack.discard(m)
                        comp.append(m)
                        if m == node:
                            break
                    if len(comp) > 1:
                        out.append(sorted(comp))
    return out


def test_the_cycle_finder_finds_cycles():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_no_import_cycles():
    cycles = _cycles(GRAPH)
    assert not cycles, "import cycles:\n" + "\n".join(" <-> ".join(c) for c in cycles)


@pytest.mark.parametrize("facade", sorted(FACADES))
def test_nothing_imports_a_facade(facade):
    """The facades are the top layer: no module of the packages imports them (a test of rule 1
    for the package names themselves, whose layer is not their subpackages')."""
    users = sorted(a for a, targets in GRAPH.items() if facade in targets and a not in FACADES)
    assert not users, f"modules importing the facade {facade!r}: {users}"


def test_no_bench_code_in_the_installed_package():
    """Measurement lives beside the package (benchmarks/suites/, benchmarks/run.py), as scipy
    keeps its benchmarks: no installed module is a benchmark, draws a work-precision chart or
    imports the suites, and ``tippe`` has no ``bench`` command (issue 22, move 5)."""
    from stability.cli import COMMANDS

    named = sorted(m for m in MODULES if any(w in m for w in ("bench", "work_precision", "timing")))
    assert not named, f"benchmark modules in the installed package: {named}"
    users = sorted(
        m
        for m in MODULES
        for node in _import_nodes(ast.parse(pathlib.Path(MODULES[m][0]).read_text()))
        for a in (node.names if isinstance(node, ast.Import) else [ast.alias(node.module or "")])
        if a.name.split(".")[0] in ("suites", "run", "benchmarks")
    )
    assert not users, f"installed modules importing the benchmark suites: {users}"
    assert "bench" not in COMMANDS


def test_trace_takes_one_options_object():
    """Issue 22, move 4: the engine's settings are one frozen options object
    (continuation.TraceOptions, like BifurcationKit's ContinuationPar), so that ``trace`` takes
    at most 8 parameters and its clients cannot re-list its keywords with other defaults; the
    compiled step's result is a named tuple."""
    import dataclasses
    import inspect

    import continuation

    assert len(inspect.signature(continuation.trace).parameters) <= 8
    assert len(inspect.signature(continuation.trace_both).parameters) <= 8
    opts = continuation.TraceOptions()
    assert dataclasses.is_dataclass(opts)
    with pytest.raises(dataclasses.FrozenInstanceError):
        opts.max_angle = 0.1  # type: ignore[misc]
    with pytest.raises(ValueError, match="min_step <= step <= max_step"):
        continuation.TraceOptions(step=1.0, max_step=0.1)
    assert continuation.StepResult._fields[:4] == ("ok", "iterations", "n_residual_and_jacobian", "n_residual")
    assert len(continuation.StepResult._fields) == 11


#: the built-in exceptions the package raises only through its own hierarchy (stability/errors.py)
BUILTIN_ERRORS = frozenset(
    {
        "ValueError",
        "TypeError",
        "RuntimeError",
        "OSError",
        "KeyError",
        "IndexError",
        "FileExistsError",
        "FileNotFoundError",
        "ArithmeticError",
        "OverflowError",
        "ZeroDivisionError",
        "NotImplementedError",
        "AttributeError",
        "LookupError",
    }
)


def bare_builtin_raises(source: str) -> list[tuple[int, str]]:
    """``(line, exception)`` of every ``raise`` of a built-in exception class (called or not) in
    ``source``: what issue 22 (move 3) converts to the package's hierarchy. A re-raise
    (``raise``, ``raise exc``) and a raise of a package class are not counted."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Raise) and node.exc is not None:
            exc = node.exc.func if isinstance(node.exc, ast.Call) else node.exc
            if isinstance(exc, ast.Name) and exc.id in BUILTIN_ERRORS:
                out.append((node.lineno, exc.id))
    return out


def bare_raises_in_stability() -> dict[str, list[tuple[int, str]]]:
    """Module -> its bare built-in raises, over the installed ``stability``."""
    found = {}
    for name, (path, _) in MODULES.items():
        if name.split(".")[0] == "stability":
            hits = bare_builtin_raises(pathlib.Path(path).read_text())
            if hits:
                found[name] = hits
    return found


#: bare built-in raises that stay, with their reason: a module ``__getattr__`` (PEP 562) must raise
#: AttributeError; an abstract method NotImplementedError; a refusal of the file system (an
#: output that exists, a directory that does not, a recipe or scheduler file not found) keeps the
#: OSError subclass that os itself raises for it (check_output_path's "Raises" section, and the
#: CLI's exit status 2 for OSError)
ALLOWED_BARE_RAISES = {
    (kind, "*")
    for kind in (
        "AttributeError",
        "NotImplementedError",
        "OSError",
        "FileExistsError",
        "FileNotFoundError",
        "IsADirectoryError",
        "NotADirectoryError",
        "PermissionError",
    )
}


def test_no_bare_builtin_raise_in_stability():
    """Issue 22: every raise of the package goes through its hierarchy (stability/errors.py:
    InputError is a ValueError, ParameterTypeError a TypeError, so callers catching the built-ins
    still do), except the documented :data:`ALLOWED_BARE_RAISES`."""
    left = {
        name: [
            (line, kind)
            for line, kind in hits
            if (kind, "*") not in ALLOWED_BARE_RAISES and (kind, name) not in ALLOWED_BARE_RAISES
        ]
        for name, hits in bare_raises_in_stability().items()
    }
    assert not {k: v for k, v in left.items() if v}


def test_the_bare_raise_checker():
    """The checker on a small source of known content."""
    src = (
        "def f(x):\n    raise ValueError('a')\n\ndef g():\n    raise TypeError\n\n"
        "def h(e):\n    try:\n        pass\n    except Exception as exc:\n        raise\n"
        "    raise DomainError('b')\n"
    )
    assert bare_builtin_raises(src) == [(2, "ValueError"), (5, "TypeError")]
    assert isinstance(bare_raises_in_stability(), dict)


def test_no_hook_into_numba():
    """Issue 22, move 1: the installed distribution declares no ``numba_extensions`` entry point
    (numba runs every such hook in every numba program of the environment); the package's
    deferred registrations run when it compiles, or when ``stability.jit.activate()`` is called."""
    from importlib import metadata

    hooks = [ep for ep in metadata.entry_points(group="numba_extensions") if ep.value.split(".")[0] in PACKAGES]
    assert not hooks, hooks


def test_no_ctypes_and_no_private_xarray():
    """Issue 22, move 2: no module imports ``ctypes`` (a system call by hand) or xarray's
    internals (``xarray.backends``, ``xarray.core``: its private ``ArrayWriter``,
    ``dump_to_store``); files are written through ``Dataset.to_netcdf`` and ``os``."""
    bad = []
    for name, (path, _) in MODULES.items():
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        for node in _import_nodes(tree):
            mods = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
            bad += [
                (name, m)
                for m in mods
                if m.split(".")[0] == "ctypes" or m.startswith(("xarray.backends", "xarray.core"))
            ]
    assert not bad, bad
