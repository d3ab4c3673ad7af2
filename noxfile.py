#!/usr/bin/env -S uv run --script
# /// script
# dependencies = ["nox>=2025.2.9"]
# ///
"""Developer tasks: ``nox -s tests``, ``nox -s lint``, ``nox -s typecheck``, ``nox -s docs``,
``nox -s bench-quick`` (``nox -l`` lists them). Each session builds its own virtualenv from the
``dev``/``docs`` dependency groups of pyproject.toml (PEP 735)."""

from __future__ import annotations

import shutil
from pathlib import Path

import nox

nox.needs_version = ">=2025.2.9"
nox.options.default_venv_backend = "uv|virtualenv"

ROOT = Path(__file__).parent
PYPROJECT = nox.project.load_toml("pyproject.toml")
PYTHONS = ["3.11", "3.12", "3.13"]


@nox.session(python=PYTHONS, default=True)
def tests(session: nox.Session) -> None:
    """The README's test command: the installed (not editable) package, the whole suite."""
    session.install(".[test]")
    session.run("pytest", *session.posargs)


@nox.session(reuse_venv=True, default=True)
def lint(session: nox.Session) -> None:
    """Ruff: the lint rules, then the formatter's check (the versions of the ``dev`` group).

    The other pre-commit hooks run with ``pre-commit run --all-files`` (it needs the network
    once, to fetch them).
    """
    session.install(*(r for r in nox.project.dependency_groups(PYPROJECT, "dev") if r.startswith("ruff")))
    session.run("ruff", "check", "--no-fix", ".", *session.posargs)
    session.run("ruff", "format", "--check", ".")


@nox.session(reuse_venv=True, default=True)
def typecheck(session: nox.Session) -> None:
    """Mypy over the scope configured in pyproject.toml ([tool.mypy] files)."""
    session.install("-e", ".", *nox.project.dependency_groups(PYPROJECT, "dev"))
    session.run("mypy", *session.posargs)


@nox.session(reuse_venv=True, default=False)
def docs(session: nox.Session) -> None:
    """The documentation site, warnings as errors, then every example in it run (doctest).

    ``nox -s docs -- --serve`` is not offered: open docs/_build/html/index.html.
    """
    session.install("-e", ".", *nox.project.dependency_groups(PYPROJECT, "docs"))
    shutil.rmtree(ROOT / "docs" / "_build", ignore_errors=True)
    shutil.rmtree(ROOT / "docs" / "generated", ignore_errors=True)
    common = ["-W", "--keep-going", "-T"]
    session.run("sphinx-build", *common, "-b", "html", "docs", "docs/_build/html", *session.posargs)
    session.run("sphinx-build", *common, "-b", "doctest", "docs", "docs/_build/doctest", *session.posargs)


@nox.session(name="bench-quick", reuse_venv=True, default=False)
def bench_quick(session: nox.Session) -> None:
    """The quick work-precision run (benchmarks/run.py --quick): charts and summaries written to
    the session's temporary directory, never over the committed charts in atlases/."""
    session.install(".")
    session.run(
        "python", str(ROOT / "benchmarks" / "run.py"), "--quick", "--out-dir", session.create_tmp(), *session.posargs
    )


if __name__ == "__main__":
    nox.main()
