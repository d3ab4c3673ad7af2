"""A resumed atlas equals the one computed in one go, or the run refuses naming the chunk file.

Issue 13, item 5 (and E5: the store under concurrency). Reference: the one-shot in-memory atlas
(``stability.atlas`` without ``chunks``, checked against mpmath in test_spectra_reference),
compared bit for bit (``assert_same_atlas``: values, coordinates and attributes). Each case
damages the store of an interrupted run in one way; the resumed run must either refuse with a
``ResumeError`` naming the damaged file (no output file written, the store kept), or compute the
damaged chunk again, say so, and give the reference.
"""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from conftest import assert_same_atlas

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
    real = dist._compute_block
    calls = []

    def compute(spec, sl):
        if len(calls) == kept:
            raise KeyboardInterrupt
        calls.append(sl)
        return real(spec, sl)

    monkeypatch.setattr(dist, "_compute_block", compute)
    with pytest.raises(KeyboardInterrupt):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    monkeypatch.undo()
    assert len(list(parts_directory(out).glob("chunk-*.npz"))) == kept


def _rewrite(path, **changes) -> None:
    """Rewrite a chunk file with some arrays changed (keeping its stored digest)."""
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files}
    arrays.update(changes)
    with open(path, "wb") as f:
        np.savez(f, **arrays)


def _array(path, key):
    with np.load(path) as z:
        return z[key]


def _damage(kind: str, store, tmp_path, monkeypatch):
    """Damage the store; return the file the refusal must name (or None: recomputed)."""
    first = store / "chunk-0-0-0.npz"
    if kind == "wrong shape (broadcastable)":
        with np.load(first) as z:
            small = {k: z[k].reshape(-1)[:1].reshape((1,) * z[k].ndim) for k in z.files if k != "_digest"}
        _rewrite(first, **small)
        return first
    if kind == "wrong dtype":
        _rewrite(first, stability=_array(first, "stability").astype(np.float64) + 0.5)
        return first
    if kind == "flag out of range":
        s = _array(first, "stability").copy()
        s[0, 0, 0] = 7
        _rewrite(first, stability=s)
        return first
    if kind == "NaN inconsistent":
        g = _array(first, "growth_rate").copy()
        inside = np.argwhere(_array(first, "physical") == 1)[0]
        g[tuple(inside)] = np.nan
        _rewrite(first, growth_rate=g)
        return first
    if kind == "edited by one ulp":
        g = _array(first, "growth_rate").copy()
        i = tuple(np.argwhere(np.isfinite(g))[0])
        g[i] = np.nextafter(g[i], np.inf)
        _rewrite(first, growth_rate=g)
        return first
    if kind == "two files swapped":
        a, b = store / "chunk-0-0-0.npz", store / "chunk-0-0-1.npz"
        tmp = store / "swap"
        a.rename(tmp)
        b.rename(a)
        tmp.rename(b)
        return a
    if kind == "copied from another store":
        other = tmp_path / "other" / "a.nc"
        other.parent.mkdir()
        _interrupted_store(other, monkeypatch, kept=2)
        shutil.copy(parts_directory(other) / "chunk-0-0-0.npz", first)
        return first
    if kind == "journal line missing":
        journal = store / "chunks.jsonl"
        lines = journal.read_text().splitlines()
        journal.write_text("\n".join(line for line in lines if "chunk-0-0-0" not in line) + "\n")
        return None
    if kind == "truncated file":
        data = first.read_bytes()
        first.write_bytes(data[: len(data) // 2])
        return None
    raise AssertionError(kind)


REFUSED = [
    "wrong shape (broadcastable)",
    "wrong dtype",
    "flag out of range",
    "NaN inconsistent",
    "edited by one ulp",
    "two files swapped",
    "copied from another store",
]
RECOMPUTED = ["journal line missing", "truncated file"]


@pytest.mark.parametrize("kind", REFUSED + RECOMPUTED)
def test_damaged_store(tmp_path, monkeypatch, reference, kind):
    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch)
    store = parts_directory(out)
    named = _damage(kind, store, tmp_path, monkeypatch)
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    notes = []
    if named is not None:
        with pytest.raises(ResumeError) as err:
            write_atlas(ds, out, resume=True, notes=notes.append)
        assert f"chunk file '{named}'" in str(err.value)
        assert not out.exists() and store.is_dir()
        return
    calls = []
    real = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or real(spec, sl))
    write_atlas(ds, out, resume=True, notes=notes.append)
    assert len(calls) == 8 - 5 + 1  # the three never computed, and the damaged one again
    assert len(notes) == 1 and "chunk-0-0-0.npz" in notes[0] and "computed again" in notes[0]
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


def test_store_of_an_older_version_is_refused(tmp_path, monkeypatch):
    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch)
    manifest = parts_directory(out) / "manifest.json"
    old = json.loads(manifest.read_text())
    manifest.write_text(json.dumps(old["identity"]))  # the format of the first version: no journal
    with pytest.raises(ResumeError, match="written by an older version of the package"):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)


def test_a_second_run_on_the_same_store_fails_at_once(tmp_path, monkeypatch):
    """The store's lock: a run holding it (here opened by the test, as another process would)
    makes a second run fail at once naming the holder's pid; when it is released the run goes on."""
    import os

    out = tmp_path / "a.nc"
    _interrupted_store(out, monkeypatch)
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    holder = dist._Store(
        parts_directory(out), dist._identity(ds, CHUNKS | {"fr_inv": 2}), ["q", "fr_inv", "sigma"], print
    )
    holder.open()
    try:
        with pytest.raises(ResumeError, match=rf"another run \(pid {os.getpid()}\) is using this chunk store"):
            write_atlas(ds, out, resume=True)
    finally:
        holder.close()
    write_atlas(ds, out, resume=True)
    assert out.exists()


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
