"""A resumed atlas equals the one computed in one go, or the run refuses naming the chunk file.

Issue 13, item 5; the store is a Zarr store (stability.grids.store, issue 22 move 2).
Reference: the one-shot in-memory atlas (``stability.atlas`` without ``chunks``, checked against mpmath in test_spectra_reference),
compared bit for bit (``assert_same_atlas``: values, coordinates and attributes). Each case
damages the store of an interrupted run in one way; the resumed run must either refuse with a
``ResumeError`` naming the damaged chunk (no output file written, the store kept), or compute the
damaged chunk again, say so, and give the reference.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from conftest import assert_same_atlas, interrupt_resumable_run

import stability
import stability.grids.chunked as dist
from stability.errors import ChunkError, ResumeError
from stability.grids.chunked import parts_directory, write_atlas

GRID = dict(
    q=np.linspace(-0.6, 0.6, 13), fr_inv=[0.0, 0.3], sigma=np.linspace(0.2, 1.2, 4), alpha_v=0.5, mask_unphysical=True
)
CHUNKS = {"q": 4, "sigma": 2}  # 4 x 1 x 2 = 8 chunks


@pytest.fixture(scope="module")
def reference():
    return stability.atlas("sliding", **GRID)


def _interrupted_store(out, monkeypatch, kept: int = 5) -> None:
    """A store of an interrupted run: ``kept`` chunks finished, then Ctrl-C."""
    interrupt_resumable_run(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, monkeypatch, kept)


def _chunk_file(store, variable: str, key: str) -> Path:
    """A Zarr chunk file of ``variable`` (key ``"0/0/0/0"``: the grid chunk (0, 0, 0))."""
    return store / variable / "c" / key


def _damage(kind: str, store, tmp_path, monkeypatch) -> bool | None:
    """Damage the store in one way; True if the resumed run must refuse it naming chunk-0-0-0,
    False if it must compute that chunk again, None if the store is still right (a chunk file
    copied from another store of the same atlas holds the same bytes: the digest binds the
    content to the atlas and the slice, not to one store)."""
    first = _chunk_file(store, "growth_rate", "0/0/0/0")
    if kind == "edited by one ulp":
        region = {"q": slice(0, 4), "fr_inv": slice(0, 2), "sigma": slice(0, 2)}
        with xr.open_dataset(store, engine="zarr", consolidated=False, chunks=None) as z:
            g = z["growth_rate"].isel(region).values.copy()
        i = tuple(np.argwhere(np.isfinite(g))[0])
        g[i] = np.nextafter(g[i], np.inf)
        xr.Dataset({"growth_rate": (("q", "fr_inv", "sigma", "mode"), g)}).to_zarr(
            store, region=region, mode="r+", consolidated=False
        )
        return True
    if kind == "two chunk files swapped":
        other = _chunk_file(store, "growth_rate", "0/0/1/0")
        tmp = store / "swap"
        first.rename(tmp)
        other.rename(first)
        tmp.rename(other)
        return True
    if kind == "copied from another store":
        elsewhere = tmp_path / "other" / "a.nc"
        elsewhere.parent.mkdir()
        _interrupted_store(elsewhere, monkeypatch, kept=2)
        shutil.copy(_chunk_file(parts_directory(elsewhere), "growth_rate", "0/0/0/0"), first)
        return None
    if kind == "truncated chunk file":
        data = first.read_bytes()
        first.write_bytes(data[: len(data) // 2])
        return False
    raise AssertionError(kind)


REFUSED = ["edited by one ulp", "two chunk files swapped"]
RECOMPUTED = ["truncated chunk file"]
UNCHANGED = ["copied from another store"]


@pytest.mark.parametrize("kind", REFUSED + RECOMPUTED + UNCHANGED)
def test_damaged_store(tmp_path, monkeypatch, reference, kind):
    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch)
    store = parts_directory(out)
    refused = _damage(kind, store, tmp_path, monkeypatch)
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    if refused:
        with pytest.raises(ResumeError, match=r"chunk chunk-0-0-0 of .* does not match its digest"):
            write_atlas(ds, out, resume=True)
        assert not out.exists() and store.is_dir()
        return
    calls = []
    real = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or real(spec, sl))
    if refused is None:
        write_atlas(ds, out, resume=True)
        assert len(calls) == 8 - 5  # the three never computed
    else:
        with pytest.warns(UserWarning, match=r"chunk chunk-0-0-0 of .* cannot be read .*: computed again"):
            write_atlas(ds, out, resume=True)
        assert len(calls) == 8 - 5 + 1  # the three never computed, and the damaged one again
    assert_same_atlas(stability.open_atlas(out), reference)
    assert not store.exists()


def test_resumed_equals_one_shot_bitwise(tmp_path, monkeypatch, reference):
    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch, kept=3)
    write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    resumed = stability.open_atlas(out)
    assert_same_atlas(resumed, reference)
    for v in ("growth_rate", "frequency", "eigenvalue_error_bound"):  # bit for bit, NaN included
        assert resumed[v].values.tobytes() == reference[v].values.tobytes()


def test_a_wrongly_computed_block_is_never_broadcast(tmp_path, monkeypatch):
    """A block of the wrong shape from the computation itself (a bug) is a ChunkError, not
    broadcast into the file (netCDF4 would broadcast it silently)."""
    real = dist._compute_block

    def small(spec, sl):
        block = real(spec, sl)
        return {k: v[(slice(0, 1),) * v.ndim] for k, v in block.items()}

    monkeypatch.setattr(dist, "_compute_block", small)
    with pytest.raises(
        ChunkError, match=r"has growth_rate of shape \(1, 1, 1, 1\); this chunk of the grid has shape \(4, 2, 2, 3\)"
    ):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), tmp_path / "a.nc")
    assert list(tmp_path.iterdir()) == []


HOLD = """
import fcntl, os, sys
fd = os.open(sys.argv[1], os.O_RDONLY)
fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
print("held", flush=True)
sys.stdin.read()
"""


@pytest.mark.skipif(sys.platform == "win32", reason="fcntl.flock")
def test_a_second_run_on_the_same_store_fails_at_once(tmp_path, monkeypatch, reference):
    """Another process holds the store of an interrupted run (the lock taken by the test's own
    flock on the store's directory, in a subprocess: a run in progress): a resumed run is
    refused at once, computing nothing and leaving the store as it was; once the other process
    has ended (its lock released by the kernel), the same run resumes to the reference."""
    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch, kept=3)
    store = parts_directory(out)
    before = sorted((p.relative_to(store), p.stat().st_mtime_ns) for p in store.rglob("*"))
    calls = []
    real = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or real(spec, sl))
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    holder = subprocess.Popen([sys.executable, "-c", HOLD, str(store)], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    try:
        assert holder.stdout.readline().strip() == b"held"
        with pytest.raises(ResumeError, match=r"another run is writing .*a\.nc\.parts' now"):
            write_atlas(ds, out, resume=True)
    finally:
        holder.communicate(b"", timeout=60)
    assert calls == [] and not out.exists()
    assert sorted((p.relative_to(store), p.stat().st_mtime_ns) for p in store.rglob("*")) == before
    write_atlas(ds, out, resume=True)
    assert len(calls) == 8 - 3 and not store.exists()
    assert_same_atlas(stability.open_atlas(out), reference)


@pytest.mark.parametrize("kind", ["a file", "a directory of other files"])
def test_a_foreign_parts_path_is_refused_and_left_alone(tmp_path, kind):
    """``<output>.parts`` that is not a store of this package (a file; a directory holding other
    files): refused before computing, naming it, and left exactly as it was (never written
    into, never removed)."""
    out = tmp_path / "a.nc"
    parts = parts_directory(out)
    if kind == "a file":
        parts.write_text("mine")
        mine = parts
    else:
        parts.mkdir()
        mine = parts / "notes.txt"
        mine.write_text("mine")
    with pytest.raises(ResumeError, match=r"a\.nc\.parts' exists .*not a .*Zarr store"):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    assert mine.read_text() == "mine" and not out.exists()
    assert sorted(p.name for p in tmp_path.rglob("*")) == sorted(
        ["a.nc.parts"] + (["notes.txt"] if kind != "a file" else [])
    )


def test_a_resumed_run_replaces_an_existing_file_when_asked(tmp_path, monkeypatch, reference):
    """``resume=True, overwrite=True`` onto an existing netCDF file: the store is committed as
    netCDF over it (the store is checked as a target only when it is itself the output; before,
    the existing file was refused as "not a Zarr store"). Without ``overwrite`` it is kept.
    Reference: the in-memory atlas, bit for bit; the foreign file's bytes."""
    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch, kept=3)
    out.write_bytes(b"an older atlas")
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    with pytest.raises(FileExistsError, match="pass overwrite=True"):
        write_atlas(ds, out, resume=True)
    assert out.read_bytes() == b"an older atlas"
    write_atlas(ds, out, resume=True, overwrite=True)
    assert_same_atlas(stability.open_atlas(out), reference)
    assert not parts_directory(out).exists()
