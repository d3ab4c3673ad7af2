"""Faults in chunked atlas runs: an exception in one chunk, a killed worker, an interruption.

Reference: the uninterrupted in-memory atlas (``stability.atlas`` without ``chunks``, itself
checked against mpmath in test_spectra_reference); a run that failed and was resumed must give a
file identical to it (atol = rtol = 0), and nothing computed before the failure may be lost.
"""

from __future__ import annotations

import functools
import os
import sys

import numpy as np
import pytest
import xarray as xr
from conftest import assert_resume_completes, assert_same_atlas, kept_chunks

import stability
import stability.grids.chunked as dist
from stability.cli import main
from stability.errors import ChunkError
from stability.grids.chunked import parts_directory, write_atlas
from stability.grids.cluster import dask_client

GRID = dict(
    q=np.linspace(-0.5, 0.5, 12), fr_inv=[0.0, 0.3], sigma=np.linspace(0.4, 1.2, 4), alpha_v=0.5, mask_unphysical=True
)
CHUNKS = {"q": 4, "sigma": 2}  # 3 x 1 x 2 = 6 chunks
ARGS = [
    "atlas",
    "--q",
    "-0.5:0.5:12",
    "--fr-inv",
    "0,0.3",
    "--sigma",
    "0.4:1.2:4",
    "--alpha-v",
    "0.5",
    "--mask-unphysical",
    "--chunks",
    "q=4,sigma=2",
    "--no-progress",
]


@pytest.fixture(scope="module")
def reference() -> xr.Dataset:
    return stability.atlas("sliding", **GRID)


def _failing_at(k: int, exc: BaseException):
    """A chunk function that raises ``exc`` on its k-th call (0-based) and computes otherwise."""
    real = dist._compute_block
    calls = []

    def compute(spec, sl):
        calls.append(sl)
        if len(calls) == k + 1:
            raise exc
        return real(spec, sl)

    return compute, calls


def _without_compile_notice(err: str) -> str:
    """stderr without the one-line notice a cold numba cache prints before its first compile.

    A fresh install (CI's clean clone) has no cache, so the first compiled call of a process
    announces itself; that line is not the interruption's one line under test."""
    return "".join(ln for ln in err.splitlines(True) if not ln.startswith("tippe-stability: compiling"))


def test_exception_in_one_chunk_names_it_keeps_the_others_and_resume_completes(tmp_path, monkeypatch, reference):
    out = tmp_path / "a.nc"
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    compute, _ = _failing_at(3, RuntimeError("injected fault"))
    monkeypatch.setattr(dist, "_compute_block", compute)
    with pytest.raises(ChunkError) as err:
        write_atlas(ds, out, resume=True)
    msg = str(err.value)
    # the fourth chunk in order is chunk (q block 1, fr_inv block 0, sigma block 1)
    assert "chunk chunk-1-0-1 (q[4:8], fr_inv[0:2], sigma[2:4]) failed: RuntimeError: injected fault" in msg
    assert f"3 of 6 chunks are kept in {parts_directory(out)}" in msg
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == [parts_directory(out).name]  # no temporary file
    assert kept_chunks(out) == 3

    assert_resume_completes(ds, out, reference, monkeypatch, missing=3)


def test_exception_without_resume_says_nothing_was_kept(tmp_path, monkeypatch):
    out = tmp_path / "a.nc"
    compute, _ = _failing_at(0, ValueError("bad block"))
    monkeypatch.setattr(dist, "_compute_block", compute)
    with pytest.raises(
        ChunkError,
        match=r"chunk chunk-0-0-0 \(q\[0:4\], fr_inv\[0:2\], sigma\[0:2\]\) failed: "
        r"ValueError: bad block; .*no chunks were kept .*resume=True \(--resume\)",
    ):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out)
    assert list(tmp_path.iterdir()) == []


def test_cli_chunk_fault_one_line_exit_1_then_resume(tmp_path, monkeypatch, capsys, reference):
    out = tmp_path / "a.nc"
    compute, _ = _failing_at(2, RuntimeError("injected fault"))
    monkeypatch.setattr(dist, "_compute_block", compute)
    rc = main([*ARGS, "--resume", "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 1
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("tippe atlas: error: chunk chunk-1-0-0 (q[4:8], fr_inv[0:2], sigma[0:2]) failed")
    assert f"2 of 6 chunks are kept in {parts_directory(out)}" in err
    monkeypatch.undo()
    assert main([*ARGS, "--resume", "-o", str(out)]) == 0
    assert_same_atlas(stability.open_atlas(out), reference)


def test_cli_interrupt_exit_130_one_line_no_partial_file(tmp_path, monkeypatch, capsys):
    out = tmp_path / "a.nc"
    compute, _ = _failing_at(1, KeyboardInterrupt())
    monkeypatch.setattr(dist, "_compute_block", compute)
    rc = main([*ARGS, "--resume", "-o", str(out)])
    err = capsys.readouterr().err
    err = _without_compile_notice(err)
    assert rc == 130 and err.count("\n") == 1
    assert err.startswith("tippe atlas: interrupted; no output file was written; the finished chunks are kept in")
    assert not out.exists() and kept_chunks(out) == 1
    # without --resume nothing is kept, and the message says so
    compute, _ = _failing_at(1, KeyboardInterrupt())
    monkeypatch.setattr(dist, "_compute_block", compute)
    rc = main([*ARGS, "-o", str(tmp_path / "b.nc")])
    err = capsys.readouterr().err
    assert rc == 130 and "no chunks were kept (run with --resume" in err
    assert not (tmp_path / "b.nc").exists() and not parts_directory(tmp_path / "b.nc").exists()


# --- on a real two-worker LocalCluster ----------------------------------------------------------


def _raise_on_chunk(spec, sl):
    """Runs on a worker: fail the chunk starting at q = 4, sigma = 2."""
    if sl["q"].start == 4 and sl["sigma"].start == 2:
        raise RuntimeError("fault on a worker")
    return dist._compute_block(spec, sl)


def _kill_worker_once(spec, sl, *, marker: str):
    """Runs on a worker: the first attempt at the chunk (q 4:8, sigma 0:2) kills its worker process
    (os._exit, as a crash or the OOM killer would); dask reschedules the chunk on another worker."""
    if sl["q"].start == 4 and sl["sigma"].start == 0 and not os.path.exists(marker):
        open(marker, "w").close()
        os._exit(1)
    return dist._compute_block(spec, sl)


@pytest.fixture(scope="module")
def cluster_client():
    import cloudpickle

    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    # pytest's importlib mode names this module "tests.test_faults", which the workers must
    # import to unpickle its functions: they get a folder holding only a link to tests/ on
    # their path (not the repository: they keep importing the installed package)
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as only_tests:
        (Path(only_tests) / "tests").symlink_to(Path(__file__).resolve().parent)
        sys.path.append(only_tests)  # multiprocessing's spawn hands the parent's path to the workers
        try:
            with dask_client(workers=2) as client:
                yield client
        finally:
            sys.path.remove(only_tests)
    cloudpickle.unregister_pickle_by_value(sys.modules[__name__])


def test_cluster_exception_in_one_chunk(tmp_path, monkeypatch, cluster_client, reference):
    out = tmp_path / "a.nc"
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    monkeypatch.setattr(dist, "_compute_block", _raise_on_chunk)
    with pytest.raises(ChunkError) as err:
        write_atlas(ds, out, client=cluster_client, resume=True, window=1)
    msg = str(err.value)
    assert "chunk chunk-1-0-1 (q[4:8], fr_inv[0:2], sigma[2:4]) failed: RuntimeError: fault on a worker" in msg
    assert "3 of 6 chunks are kept" in msg  # window=1: the chunks before it, in order
    assert not out.exists() and kept_chunks(out) == 3
    monkeypatch.undo()
    write_atlas(ds, out, client=cluster_client, resume=True)
    assert_same_atlas(stability.open_atlas(out), reference)


def test_cluster_killed_worker_is_retried_and_nothing_is_lost(tmp_path, monkeypatch, cluster_client, reference):
    marker = tmp_path / "killed"
    monkeypatch.setattr(dist, "_compute_block", functools.partial(_kill_worker_once, marker=str(marker)))
    out = tmp_path / "a.nc"
    write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, client=cluster_client, resume=True)
    assert marker.exists()  # a worker did die
    assert_same_atlas(stability.open_atlas(out), reference)
    assert not parts_directory(out).exists()


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_sigterm_mid_run_leaves_no_partial_file_and_keeps_chunks(tmp_path):
    """``kill`` (SIGTERM, as sent by timeout or a batch scheduler) in the middle of a chunked
    ``tippe atlas --resume`` run: Python's default would end the process at once and leave the
    hidden temporary netCDF (measured: 2.2 GB for 4e7 points); the CLI turns it into an
    interrupt, so: exit 130, one line, no output and no temporary file, the finished chunks kept,
    and a rerun completes from them."""
    import signal
    import subprocess
    import time

    out = tmp_path / "r.nc"
    cmd = [
        sys.executable,
        "-m",
        "stability",
        "atlas",
        "--q",
        "-0.6:0.6:400",
        "--fr-inv",
        "0:3:100",
        "--sigma",
        "0.1:1.2:50",
        "--alpha-v",
        "0.1,1",
        "--mask-unphysical",
        "--chunks",
        "q=10",
        "--resume",
        "--no-progress",
        "-o",
        str(out),
    ]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    parts = parts_directory(out)
    deadline = time.monotonic() + 120

    def some_kept() -> bool:
        try:  # the store is being laid out, or a chunk written, by the run
            return kept_chunks(out) >= 1
        except (OSError, ValueError, KeyError):
            return False

    while not (parts.exists() and some_kept()):
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "no chunk written in 120 s"
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    err = _without_compile_notice(err)
    assert err.count("\n") == 1 and "interrupted" in err and "Traceback" not in err
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == [parts.name]  # no temporary file
    kept = kept_chunks(out)
    assert 1 <= kept < 40
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert out.exists() and not parts.exists()
