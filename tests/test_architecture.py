"""The import layers of the package (docs/architecture.md), checked on the installed code.

Why: the folder tree is meant to show the architecture, models -> linear -> grids / nonlinear ->
recipes -> plotting -> benchmarks -> command line, and the continuation engine is meant to be
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
3. an import of ``stability`` from a module of ``continuation`` other than its ``__init__``
   (the engine knows nothing about tops; ``continuation/__init__.py`` re-exports the neutral
   curves lazily, the one documented exception);
4. a module that is in no layer (a new module must be placed in the table below, and in the
   table of docs/architecture.md, which mirrors it).
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import pkgutil

import pytest

PACKAGES = ("stability", "continuation")

#: (module or package prefix, layer); the longest matching prefix decides. Mirrors the table in
#: docs/architecture.md. Imports may go to the same or a lower layer only.
LAYERS: tuple[tuple[str, int], ...] = (
    ("continuation", 0),                 # the generic engine (its __init__ is a facade, below)
    ("stability._version", 0),
    ("stability.errors", 0),
    ("stability.products", 0),
    ("stability.execution", 0),
    ("stability.interrupts", 0),         # signals as flags, checkpoints, temporary files
    ("stability.resources", 0),          # memory estimates and limits
    ("stability.parameters", 1),
    ("stability.models", 1),
    ("stability.top", 1),
    ("stability.linear", 2),
    ("stability.nonlinear", 3),
    ("stability.grids", 3),
    ("stability.steady", 4),             # steady states, branch, final state, classes
    ("stability.recipes", 5),
    ("stability.launches", 5),             # launch, flip_time: a real top launched (issue 23)
    ("stability.plotting", 6),
    ("stability.bench", 7),
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
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


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
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(
            node, ast.AnnAssign) else []
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
                base = ".".join(parts[:len(parts) - node.level + 1])
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
    for name in ("stability", "continuation", "stability.errors", "stability.linear.kernel",
                 "stability.grids.atlases", "stability.nonlinear.runs", "stability.bench.records",
                 "stability.commands.atlas", "continuation.engine"):
        assert name in MODULES
    assert "stability.linear.neutral_curves" in GRAPH["continuation"]  # lazy, in _EXPORTS
    assert "stability.linear.spectra" in GRAPH["stability"]  # lazy, in _EXPORTS
    assert "stability.linear.kernel" in GRAPH["stability.linear.spectra"]  # inside a function
    assert "stability.bench.records" not in GRAPH["stability.plotting.work_precision"]  # TYPE_CHECKING


def test_every_module_has_a_layer():
    missing = sorted(name for name in MODULES if layer(name) is None)
    assert not missing, f"modules in no layer (add them to LAYERS and docs/architecture.md): {missing}"


def test_no_import_goes_up_a_layer():
    upward = sorted(f"{a} (layer {layer(a)}) imports {b} (layer {layer(b)})"
                    for a, targets in GRAPH.items() for b in targets
                    if layer(a) is not None and layer(b) is not None and layer(b) > layer(a))
    assert not upward, "imports of a higher layer:\n" + "\n".join(upward)


def test_the_engine_does_not_import_stability():
    bad = sorted(f"{a} imports {b}" for a, targets in GRAPH.items() if a.startswith("continuation.")
                 for b in targets if b.split(".")[0] == "stability")
    assert not bad, "continuation (except its __init__ facade) must not import stability:\n" + "\n".join(bad)


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
