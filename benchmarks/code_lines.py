"""Lines of code of the installed packages: blank lines, comments and docstrings not counted.

A line counts if it holds at least one token that is neither a comment nor part of a docstring
(the string that opens a module, a class or a function, read with ``ast``). Usage::

    python benchmarks/code_lines.py            # stability/ and continuation/ of this tree
    python benchmarks/code_lines.py PATH ...   # other folders or files

Prints the code lines per top-level folder and the total.
"""

from __future__ import annotations

import ast
import io
import sys
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def docstring_lines(source: str) -> set[int]:
    """Line numbers (1-based) covered by the docstrings of a module, its classes and functions."""
    lines: set[int] = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                lines.update(range(first.lineno, first.end_lineno + 1))
    return lines


def code_lines(source: str) -> int:
    """Number of lines of ``source`` holding code (not blank, not only a comment or docstring)."""
    skip = docstring_lines(source)
    ignored = (
        tokenize.COMMENT,
        tokenize.NL,
        tokenize.NEWLINE,
        tokenize.INDENT,
        tokenize.DEDENT,
        tokenize.ENCODING,
        tokenize.ENDMARKER,
    )
    seen: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type in ignored:
            continue
        for line in range(tok.start[0], tok.end[0] + 1):
            if line not in skip:
                seen.add(line)
    return len(seen)


def count(paths: list[Path]) -> dict[str, int]:
    """Code lines per given path (a folder: all its ``*.py`` files)."""
    out = {}
    for p in paths:
        files = sorted(p.rglob("*.py")) if p.is_dir() else [p]
        out[str(p.relative_to(ROOT) if p.is_relative_to(ROOT) else p)] = sum(code_lines(f.read_text()) for f in files)
    return out


if __name__ == "__main__":
    paths = [Path(a).resolve() for a in sys.argv[1:]] or [ROOT / "stability", ROOT / "continuation"]
    counts = count(paths)
    for name, n in counts.items():
        print(f"{name:40s} {n:7d}")
    print(f"{'total':40s} {sum(counts.values()):7d}")
