"""Sphinx configuration of the tippe-stability documentation site.

Build: ``nox -s docs``, or ``sphinx-build -W --keep-going -b html docs docs/_build/html`` and
``sphinx-build -W --keep-going -b doctest docs docs/_build/doctest`` (the tutorial's examples
run and their output is compared).

Two parts of the site are generated here at every build, into ``docs/generated/`` (ignored by
git), so that they cannot fall behind the code:

* the API reference: one autosummary table per import package, listing every name of
  ``stability.__all__`` and ``continuation.__all__`` (a name added to ``__all__`` appears
  without an edit here), each with its own page (``autosummary_generate``);
* the gallery: every ``atlases/*.png`` with the recipe (``atlases/*.toml``) that draws it,
  included literally, and the work-precision charts with the data file beside them.
"""

from __future__ import annotations

import doctest
import importlib
import importlib.util
import inspect
import os
from pathlib import Path

os.environ.setdefault("MPLBACKEND", "Agg")

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
GENERATED = DOCS / "generated"

project = "tippe-stability"
author = "tippe-stability developers"
copyright = "2026, tippe-stability developers"
release = importlib.import_module("stability._version").package_version()
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.doctest",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "generated/api/*.rst.tmp"]
root_doc = "index"

# --- MyST: the existing Markdown pages -------------------------------------------------------
myst_enable_extensions = ["colon_fence", "dollarmath", "amsmath", "deflist"]
myst_heading_anchors = 3
# links such as (../stability/top.py) or (README.md) point into the repository, not the site:
# they stay plain links (the pages are also read on GitHub, where they resolve)
suppress_warnings = ["myst.xref_missing"]

# --- autodoc / autosummary / numpydoc ---------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": False}
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# numpydoc's validation, enforced by the -W build: every check that the public API passes today
# ("all" minus the listed ones). Left out, with their counts over the 47 public callables and
# classes: SA01 no "See Also" (47), ES01 no extended summary (39), EX01 no "Examples" (35),
# PR07 a parameter without description (11), PR01 a parameter not documented (7), RT01 no
# "Returns" (5), RT03 a return value without description (5), PR04 a parameter without type
# (5), SS05 summary not in the infinitive (2), PR03 parameters out of order (2), RT05 return
# description without a period (1), SS06 a summary over two lines (2, on members), GL02 closing
# quotes on the last line of text (1, on a member). Remove a code once the API passes it.
numpydoc_validation_checks = {
    "all",
    "SA01",
    "ES01",
    "EX01",
    "PR07",
    "PR01",
    "RT01",
    "RT03",
    "PR04",
    "SS05",
    "PR03",
    "RT05",
    "SS06",
    "GL02",
}
# Not validated: the constants and class attributes documented by a ``#:`` comment (a comment
# is not a docstring: no closing quotes, a phrase rather than a sentence); and (GL08, no
# docstring) the capability slots of LinearModel, class attributes holding a model's compiled
# functions (documented in stability.models.base's module docstring)
numpydoc_validation_exclude = {
    r"\.__init__$",
    r"\.__getattr__$",
    r"\.__dir__$",
    r"^stability\.models\.MODELS$",
    r"^stability\.parameters\.(PARAMETERS|DEFAULT_MU)$",
    r"^stability\.LinearModel\.(name|equations|parameters|state|n_modes|description)$",
    r"LinearModel\.point_(coefficients|derivatives)$",
}

# no intersphinx: the build must not depend on the network (CI and offline machines alike)

# --- doctest ---------------------------------------------------------------------------------
doctest_global_setup = """
import numpy as np
import stability
import continuation
np.set_printoptions(precision=4, suppress=True)
"""
doctest_default_flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE | doctest.DONT_ACCEPT_TRUE_FOR_1

# --- HTML ------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = "tippe-stability"
html_theme_options = {
    "show_toc_level": 2,
    "navigation_with_keys": False,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path: list[str] = []
html_show_sourcelink = False


# --- generated pages -------------------------------------------------------------------------
def _write(path: Path, text: str) -> None:
    """Write ``text`` unless the file already holds it (no rebuild of unchanged pages)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def _entry(module: object, package: str, name: str) -> str:
    """The autosummary entry of one public name. Functions and classes are documented under
    the package's name; a constant (a dict, a tuple, a float) is documented where it is
    defined, where autodoc finds its ``#:`` comment (under the package's name it would only
    show the docstring of its type)."""
    obj = getattr(module, name)
    if inspect.isclass(obj) or inspect.ismodule(obj) or callable(obj):
        return name
    home = importlib.util.resolve_name(module._EXPORTS[name], package)  # type: ignore[attr-defined]
    return f"~{home.removeprefix(package + '.')}.{name}"


def _api_page(package: str, title: str, intro: str) -> str:
    module = importlib.import_module(package)
    names = sorted(module.__all__, key=lambda n: (n.lower(), n))
    rows = "\n".join(f"   {_entry(module, package, n)}" for n in names)
    underline = "=" * len(title)
    return (
        f"{title}\n{underline}\n\n{intro}\n\n.. currentmodule:: {package}\n\n"
        f".. autosummary::\n   :toctree: {package}\n   :nosignatures:\n\n{rows}\n"
    )


def _gallery_page() -> str:
    atlases = ROOT / "atlases"
    out = [
        "# Gallery\n",
        "Every figure in `atlases/` with the recipe that draws it, included literally. Draw one "
        "with `tippe figures atlases/<name>.toml` (the recipe format is described in the "
        "module docstring of `stability.recipes`; the datasets behind the figures in "
        "[Datasets](../datasets.md)); the charts of the last section are drawn by the "
        "benchmark suites (`python benchmarks/run.py`) from the measurements stored beside them.\n",
    ]
    for png in sorted(atlases.glob("*.png")):
        recipe = png.with_suffix(".toml")
        data = png.with_suffix(".json")
        if not recipe.exists():
            continue
        out.append(
            f"## {png.stem}\n\n```{{image}} ../../atlases/{png.name}\n:alt: {png.stem}\n:width: 100%\n```\n\n"
            f"```{{literalinclude}} ../../atlases/{recipe.name}\n:language: toml\n:caption: atlases/{recipe.name}\n```\n"
        )
    without_recipe = [p for p in sorted(atlases.glob("*.png")) if not p.with_suffix(".toml").exists()]
    charts = [p for p in without_recipe if p.stem.startswith("work_precision")]
    others = [p for p in without_recipe if p not in charts]
    if others:
        out.append(
            "## Figures drawn by a script or a docs example\n\nEach is described, with the command or "
            "the code that draws it, in the README's gallery and in the docs page it illustrates "
            "(docs/contact.md, docs/launch.md).\n"
        )
        for png in others:
            out.append(
                f"### {png.stem}\n\n```{{image}} ../../atlases/{png.name}\n:alt: {png.stem}\n:width: 100%\n```\n"
            )
    if charts:
        out.append(
            "## Work-precision charts\n\nDrawn by the benchmark suites (docs/performance.md) "
            "from the JSON file of the same name in `atlases/`.\n"
        )
        for png in charts:
            data = png.with_suffix(".json")
            src = f"`atlases/{data.name}`" if data.exists() else "no data file"
            out.append(
                f"### {png.stem}\n\n```{{image}} ../../atlases/{png.name}\n:alt: {png.stem}\n"
                f":width: 100%\n```\n\nData: {src}.\n"
            )
    return "\n".join(out)


# the stubs autosummary wrote for names no longer public would stay as orphan pages: remove them
for _package in ("stability", "continuation"):
    _public = set(importlib.import_module(_package).__all__)
    for _stub in (GENERATED / "api" / _package).glob("*.rst"):
        if _stub.stem.removeprefix(_package + ".") not in _public:
            _stub.unlink()

_write(
    GENERATED / "api" / "stability.rst",
    _api_page(
        "stability",
        "stability",
        "Every public name of the import package ``stability`` (``stability.__all__``; "
        "each is imported lazily from the module that defines it).",
    ),
)
_write(
    GENERATED / "api" / "continuation.rst",
    _api_page(
        "continuation",
        "continuation",
        "Every public name of the continuation engine ``continuation`` "
        "(``continuation.__all__``): the generic pseudo-arclength engine, and the "
        "facade to its clients in ``stability``.",
    ),
)
_write(GENERATED / "gallery.md", _gallery_page())
