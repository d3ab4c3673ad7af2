"""The one commit primitive (stability.files): exactly one winner, regular files only.

Issue 13, items 4 and 7. References:

* the race: a barrier of N real processes writing different datasets to the same new name at
  once; the reference for the file's content is the winner's own in-memory dataset (each
  dataset is tagged), and the invariant is the contract: exactly one returns, the others get
  ``FileExistsError``, no temporary file remains;
* the no-replace commit (``os.link``): called directly, the same contract is checked (target
  unchanged, the temporary left to its owner);
* non-regular targets: a FIFO, a UNIX socket, a symbolic link, and a character device when
  ``mknod`` is permitted (created in the test's directory, never /dev/null), with and without
  ``overwrite``, through every writer and the command line; the reference is the path's own
  ``lstat`` before and after (``os.path.samestat``, mode).
"""

from __future__ import annotations

import multiprocessing
import os
import socket
import stat
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stability
from stability.cli import main
from stability.files import TEMPORARY_PREFIX, atomic_output, temporary_name
from stability.grids.chunked import write_atlas

pytestmark = pytest.mark.skipif(os.name != "posix", reason="POSIX file semantics")


def _leftovers(d: Path) -> list[str]:
    return sorted(p.name for p in d.iterdir() if p.name.startswith(TEMPORARY_PREFIX))


def _tagged(i: int, n: int = 50) -> xr.Dataset:
    return xr.Dataset({"x": ("t", np.arange(float(n + i)))}, attrs={"writer": i})


# --- the race ------------------------------------------------------------------------------------


def _race_writer(path: str, i: int, barrier, results) -> None:
    """Runs in a spawned process: wait for every writer, then write dataset i to ``path``."""
    from stability.grids.netcdf import write_dataset

    barrier.wait(timeout=120)
    try:
        write_dataset(_tagged(i), path)
        results.put((i, "wrote"))
    except FileExistsError as exc:
        results.put((i, f"FileExistsError: {exc}"))
    except BaseException as exc:  # pragma: no cover - reported by the assertion
        results.put((i, f"{type(exc).__name__}: {exc}"))


def test_concurrent_writers_exactly_one_wins(tmp_path):
    """N processes released together by a barrier write to one new name without overwrite:
    exactly one succeeds, every other gets FileExistsError, the file is the winner's."""
    n = 6
    ctx = multiprocessing.get_context("spawn")
    barrier, results = ctx.Barrier(n), ctx.Queue()
    path = tmp_path / "same.nc"
    procs = [ctx.Process(target=_race_writer, args=(str(path), i, barrier, results)) for i in range(n)]
    # spawn hands the parent's sys.path to the children, which must import this module by its
    # importlib-mode name ("tests.test_commit"): a folder holding only a link to tests/ (not
    # the repository, so the installed package stays the one imported)
    only_tests = tmp_path / "only_tests"
    only_tests.mkdir()
    (only_tests / "tests").symlink_to(Path(__file__).resolve().parent)
    sys.path.append(str(only_tests))
    try:
        for p in procs:
            p.start()
    finally:
        sys.path.remove(str(only_tests))
    for p in procs:
        p.join(timeout=300)
        assert p.exitcode == 0
    outcome = dict(results.get(timeout=10) for _ in range(n))
    winners = [i for i, r in outcome.items() if r == "wrote"]
    assert len(winners) == 1, outcome
    losers = [r for i, r in outcome.items() if i not in winners]
    assert all(r.startswith("FileExistsError") for r in losers), outcome
    with xr.open_dataset(path) as f:
        xr.testing.assert_identical(f.load(), _tagged(winners[0]))
    assert _leftovers(tmp_path) == []


def test_file_created_during_the_run_is_not_replaced(tmp_path):
    """Deterministic: another process creates the target between the start and the commit."""
    path = tmp_path / "a.nc"
    with pytest.raises(
        FileExistsError,
        match=r"was created by another process while this run was computing; "
        r"nothing was written \(pass overwrite=True",
    ):
        with atomic_output(path) as tmp:
            Path(tmp).write_text("mine")
            path.write_text("theirs")
    assert path.read_text() == "theirs"
    assert _leftovers(tmp_path) == []


def test_the_commit_links_and_refuses_an_existing_target(tmp_path):
    """The one no-replace commit, ``os.link`` then ``unlink``: a complete temporary is committed
    to a new name (and counted as committed); with the target created meanwhile the commit
    refuses, leaves the target as it was, counts nothing as committed and leaves no temporary."""
    from stability import interrupts

    target = tmp_path / "d"
    with atomic_output(target) as tmp:
        Path(tmp).write_text("x")
    assert target.read_text() == "x" and interrupts.run.committed[-1] == str(target)
    assert _leftovers(tmp_path) == []
    committed = list(interrupts.run.committed)
    with pytest.raises(FileExistsError, match="created by another process"):
        with atomic_output(tmp_path / "e") as tmp:
            Path(tmp).write_text("y")
            (tmp_path / "e").write_text("theirs")
    assert (tmp_path / "e").read_text() == "theirs" and interrupts.run.committed == committed
    assert target.read_text() == "x" and _leftovers(tmp_path) == []


def test_a_file_system_without_hard_links_is_named(tmp_path, monkeypatch):
    """``link`` refused as on vfat (EPERM): the commit without overwrite cannot keep its promise
    there and says so (an OutputWriteError naming the file and the way out); nothing is left
    behind. With overwrite=True (``os.replace``) the write goes through."""
    import errno

    from stability.errors import OutputWriteError

    def no_links(src, dst):
        raise OSError(errno.EPERM, "Operation not permitted", src)

    monkeypatch.setattr(os, "link", no_links)
    with pytest.raises(OutputWriteError, match=r"cannot write .*a\.txt.*no hard links.*overwrite=True"):
        with atomic_output(tmp_path / "a.txt") as tmp:
            Path(tmp).write_text("x")
    assert list(tmp_path.iterdir()) == []
    with atomic_output(tmp_path / "a.txt", overwrite=True) as tmp:
        Path(tmp).write_text("y")
    assert (tmp_path / "a.txt").read_text() == "y" and _leftovers(tmp_path) == []


def test_temporary_names_are_unique_hidden_and_keep_the_suffix(tmp_path):
    names = {temporary_name(tmp_path / "fig.png") for _ in range(50)}
    assert len(names) == 50
    for n in names:
        assert Path(n).name.startswith(TEMPORARY_PREFIX) and Path(n).suffix == ".png"
    assert Path(temporary_name(tmp_path / "noext")).suffix == ""  # a figure's format is read off it


# --- non-regular targets -------------------------------------------------------------------------


def _make(kind: str, path: Path) -> str:
    """Create a non-regular file of ``kind`` at ``path``; return the kind's words."""
    if kind == "fifo":
        os.mkfifo(path)
        return "a FIFO (named pipe)"
    if kind == "socket":
        s = socket.socket(socket.AF_UNIX)
        s.bind(str(path))
        s.close()
        return "a socket"
    if kind == "symlink":
        target = path.with_name(path.name + ".target")
        target.write_text("the link's target")
        path.symlink_to(target)
        return "a symbolic link"
    try:
        os.mknod(path, stat.S_IFCHR | 0o600, os.makedev(1, 3))
    except (PermissionError, OSError):
        pytest.skip("mknod not permitted here")
    return "a character device"


def _writers():
    ds = stability.atlas("fixed_pivot", q=[0.1, 0.2], fr_inv=0.1, sigma=1.0)

    def save_figure(path, overwrite):
        import matplotlib as mpl

        mpl.use("Agg")
        import matplotlib.pyplot as plt

        from stability.plotting import save_figure as save

        fig = plt.figure()
        try:
            save(fig, path, overwrite=overwrite)
        finally:
            plt.close(fig)

    return {
        "write_dataset": lambda p, o: stability.write_dataset(ds, p, overwrite=o),
        "write_atlas": lambda p, o: write_atlas(ds, p, overwrite=o),
        "save_figure": save_figure,
    }


@pytest.mark.parametrize("kind", ["fifo", "socket", "symlink", "chardev"])
@pytest.mark.parametrize("writer", ["write_dataset", "write_atlas", "save_figure"])
@pytest.mark.parametrize("overwrite", [False, True])
def test_only_a_regular_file_is_replaced(tmp_path, kind, writer, overwrite):
    path = tmp_path / ("out.png" if writer == "save_figure" else "out.nc")
    words = _make(kind, path)
    before = os.lstat(path)
    with pytest.raises(FileExistsError) as err:
        _writers()[writer](path, overwrite)
    assert f"output path '{path}' is {words}; only a regular file can be replaced" in str(err.value)
    after = os.lstat(path)
    assert os.path.samestat(before, after) and before.st_mode == after.st_mode
    assert _leftovers(tmp_path) == []


def test_overwrite_is_checked_again_at_commit(tmp_path):
    """The path becomes a FIFO while the run computes: the commit refuses it (lstat again)."""
    path = tmp_path / "a.nc"
    path.write_text("regular at the start")
    with pytest.raises(FileExistsError, match="is a FIFO"):
        with atomic_output(path, overwrite=True) as tmp:
            Path(tmp).write_text("new")
            path.unlink()
            os.mkfifo(path)
    assert stat.S_ISFIFO(os.lstat(path).st_mode)
    assert _leftovers(tmp_path) == []


@pytest.mark.parametrize("kind", ["fifo", "symlink"])
def test_cli_refuses_non_regular_output_before_computing(tmp_path, capsys, kind):
    path = tmp_path / "out.nc"
    words = _make(kind, path)
    rc = main(
        [
            "atlas",
            "--q",
            "0.1,0.2",
            "--fr-inv",
            "0.1",
            "--sigma",
            "1",
            "--alpha-v",
            "0.5",
            "-o",
            str(path),
            "--overwrite",
        ]
    )
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and f"is {words}; only a regular file can be replaced" in err


def test_open_atlas_says_what_a_non_regular_path_is(tmp_path):
    """E12: a FIFO is not 'missing' (and opening it for reading would block)."""
    path = tmp_path / "pipe.nc"
    os.mkfifo(path)
    with pytest.raises(stability.AtlasFileError, match=r"pipe.nc' is a FIFO \(named pipe\), not a netCDF file"):
        stability.open_atlas(path)
