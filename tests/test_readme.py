"""The README's examples run, in order and twice, in a clean directory (issue 15 item 3).

Every fenced ```python and ```bash block of README.md is run against the installed package
(``python`` and ``tippe`` of this interpreter's environment) in one temporary directory, in the
order of the README, and then all of them a second time: the examples must not collide (one
writing a file that another, or a second run, refuses to overwrite). A block preceded by
``<!-- readme-test: skip (reason) -->`` is left out (the set-up commands that create a venv, install,
and run every recipe or the test suite), the reason written in the marker. (The numbers the README quotes
are checked against their references by the tests of each function, not here.)
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

README = Path(__file__).resolve().parent.parent / "README.md"
_SKIP = re.compile(r"<!--\s*readme-test:\s*skip\s*(?:\((?P<why>[^)]*)\))?\s*-->")


def readme_blocks(text: str) -> list[tuple[str, int, str, str | None]]:
    """(language, line of the fence, body, skip reason or None) of every python/bash block."""
    lines = text.splitlines()
    out, i = [], 0
    while i < len(lines):
        m = re.match(r"^```(python|bash)\s*$", lines[i])
        if m:
            j = i + 1
            while not lines[j].startswith("```"):
                j += 1
            marker = _SKIP.search(lines[i - 1]) if i > 0 else None
            out.append(
                (m.group(1), i + 1, "\n".join(lines[i + 1 : j]), (marker.group("why") or "marked") if marker else None)
            )
            i = j
        i += 1
    return out


def test_every_block_is_run_or_skipped_with_a_reason():
    blocks = readme_blocks(README.read_text())
    assert len(blocks) >= 5
    for _lang, line, body, skip in blocks:
        if "pip install" in body or "python3 -m venv" in body:
            assert skip, f"README line {line}: a set-up block must carry <!-- readme-test: skip (...) -->"
    assert sum(skip is not None for *_, skip in blocks) == 2  # the set-up blocks only


def test_readme_examples_run_in_sequence_twice(tmp_path):
    bindir = Path(sys.executable).parent
    env = dict(os.environ, PATH=str(bindir) + os.pathsep + os.environ.get("PATH", ""), MPLBACKEND="Agg")
    env.pop("PYTHONPATH", None)
    blocks = [b for b in readme_blocks(README.read_text()) if b[3] is None]
    for rnd in (1, 2):
        for lang, line, body, _ in blocks:
            if lang == "python":
                cmd = [sys.executable, "-P", "-c", body]  # -P: the temporary directory is not on sys.path
            else:
                cmd = ["bash", "-e", "-c", body]
            done = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=900)
            assert done.returncode == 0, f"round {rnd}: README line {line} ({lang}) failed:\n{done.stderr[-2000:]}"
    assert {"atlas.nc", "atlas_cli.nc", "atlas_cli.png", "map.png"} <= {p.name for p in tmp_path.iterdir()}
