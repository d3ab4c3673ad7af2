"""Atlases as Zarr stores (stability.grids.store): written by region, by the workers, resumed.

Reference: the in-memory atlas (``stability.atlas`` without ``chunks``, checked against mpmath in
test_spectra_reference and test_kernel). A store computes the same per-point arithmetic on
slices of the grid, so what :func:`stability.open_atlas` reads back must equal it bit for bit
(``assert_same_atlas``, plus the bytes of the floating-point variables, NaN included), whether the
chunks were written in this process, by the two workers of a LocalCluster, or resumed.
"""

from __future__ import annotations

import errno
import os
import tracemalloc

import numpy as np
import pytest
import xarray as xr
from conftest import assert_same_atlas, interrupt_resumable_run

import stability
import stability.grids.chunked as dist
from stability.cli import main
from stability.errors import AtlasFileError, InputError, OutputWriteError, ResumeError
from stability.files import TEMPORARY_PREFIX
from stability.grids.chunked import write_atlas
from stability.grids.cluster import dask_client
from stability.grids.store import parts_directory

GRID = dict(
    q=np.linspace(-0.6, 0.6, 13), fr_inv=[0.0, 0.3], sigma=np.linspace(0.2, 1.2, 4), alpha_v=0.5, mask_unphysical=True
)
CHUNKS = {"q": 4, "sigma": 2}  # 4 x 1 x 2 = 8 chunks, ragged in q


@pytest.fixture(scope="module")
def reference() -> xr.Dataset:
    return stability.atlas("sliding", **GRID)


def _bitwise(read: xr.Dataset, reference: xr.Dataset) -> None:
    assert_same_atlas(read, reference)
    for v in ("growth_rate", "frequency", "eigenvalue_error_bound", "max_growth_rate", "leading_growth_rate"):
        assert read[v].values.tobytes() == reference[v].values.tobytes(), v


def _interrupted(out, monkeypatch, kept: int) -> None:
    interrupt_resumable_run(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, monkeypatch, kept)


def test_store_in_this_process_equals_in_memory(tmp_path, reference):
    out = write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), tmp_path / "a.zarr")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.zarr"]  # no temporary store left
    _bitwise(stability.open_atlas(out), reference)
    # an in-memory atlas is written as one chunk; an existing store is replaced only if asked
    with pytest.raises(FileExistsError, match="exists"):
        write_atlas(reference, out)
    _bitwise(stability.open_atlas(write_atlas(reference, out, overwrite=True)), reference)


def test_store_written_by_two_workers_equals_in_memory(tmp_path, reference):
    """A LocalCluster of two worker processes: the workers write the regions, the client gets
    back two flags per chunk (recorded here), never a chunk."""
    seen = []
    real = dist._run_on_cluster

    def spy(client, spec, todo, put, *args, **kwargs):
        return real(client, spec, todo, lambda *a: seen.append(a[2]) or put(*a), *args, **kwargs)

    with pytest.MonkeyPatch.context() as mp, dask_client(workers=2) as client:
        mp.setattr(dist, "_run_on_cluster", spy)
        out = write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), tmp_path / "a.zarr", client=client)
    assert len(seen) == 8 and all(isinstance(s, tuple) and len(s) == 2 and set(s) <= {True, False} for s in seen)
    _bitwise(stability.open_atlas(out), reference)


def test_client_memory_stays_flat_as_the_atlas_grows(tmp_path):
    """The client's peak of traced allocations (tracemalloc: numpy's arrays included, every
    thread of the client process) while two workers write a store of 4 and then 16 chunks of
    2.4 MB each: below one chunk both times (the chunks never reach the client), and growing by
    less than a twentieth of a chunk's bytes per chunk added (what does grow is bookkeeping of a
    few tens of kB per chunk, whatever the chunk's size: the layout's task graph, the futures;
    measured 43 kB). Reference: the netCDF writer in the same run, whose client receives every
    chunk, peaks above one chunk."""
    chunk_bytes = 16 * 40 * 50 * (3 * 3 * 8 + 2)

    def peak(nq: int, name: str) -> int:
        grid = dict(q=np.linspace(-0.6, 0.6, nq), fr_inv=np.linspace(0, 1, 40), sigma=np.linspace(0.2, 1.2, 50))
        ds = stability.atlas("sliding", chunks={"q": 16}, alpha_v=0.5, mask_unphysical=True, **grid)
        tracemalloc.start()
        try:
            write_atlas(ds, tmp_path / name, client=client)
            return tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()

    with dask_client(workers=2) as client:
        peak(16, "warm.zarr")  # imports and first calls
        small, large = peak(64, "small.zarr"), peak(256, "large.zarr")
        netcdf = peak(64, "small.nc")
    assert small < chunk_bytes and large < chunk_bytes, (small, large, chunk_bytes)
    assert (large - small) / (16 - 4) < chunk_bytes / 20, (small, large)
    assert netcdf > chunk_bytes, netcdf


def test_interrupted_store_resumes_bitwise(tmp_path, monkeypatch, reference):
    out = tmp_path / "a.zarr"
    _interrupted(out, monkeypatch, kept=3)
    calls = []
    real = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or real(spec, sl))
    write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    assert len(calls) == 5  # only the chunks not kept
    assert not parts_directory(out).exists()
    _bitwise(stability.open_atlas(out), reference)


def test_resume_after_a_kill_between_data_and_digest(tmp_path, monkeypatch, reference):
    """A chunk whose data was written but not its digest (killed in between) counts as not
    written: computed again."""
    out = tmp_path / "a.zarr"
    _interrupted(out, monkeypatch, kept=3)
    store = parts_directory(out)
    with xr.open_dataset(store, engine="zarr", consolidated=False, chunks=None) as z:
        digests = z["chunk_digest"].values
    first = tuple(np.argwhere(digests != 0)[0])
    xr.Dataset({"chunk_digest": (("q_chunk", "fr_inv_chunk", "sigma_chunk"), np.zeros((1, 1, 1), np.uint64))}).to_zarr(
        store,
        region={d: slice(i, i + 1) for d, i in zip(("q_chunk", "fr_inv_chunk", "sigma_chunk"), first)},
        mode="r+",
        consolidated=False,
    )
    calls = []
    real = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or real(spec, sl))
    write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    assert len(calls) == 6
    _bitwise(stability.open_atlas(out), reference)


def test_resume_refuses_an_edited_chunk_and_another_atlas(tmp_path, monkeypatch):
    out = tmp_path / "a.zarr"
    _interrupted(out, monkeypatch, kept=3)
    store = parts_directory(out)
    with xr.open_dataset(store, engine="zarr", consolidated=False, chunks=None) as z:
        g = z["growth_rate"].isel(q=slice(0, 4), fr_inv=slice(0, 2), sigma=slice(0, 2)).values.copy()
    i = tuple(np.argwhere(np.isfinite(g))[0])
    g[i] = np.nextafter(g[i], np.inf)  # one ulp
    xr.Dataset({"growth_rate": (("q", "fr_inv", "sigma", "mode"), g)}).to_zarr(
        store, region={"q": slice(0, 4), "fr_inv": slice(0, 2), "sigma": slice(0, 2)}, mode="r+", consolidated=False
    )
    with pytest.raises(ResumeError, match=r"chunk chunk-0-0-0 of .* does not match its digest"):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    other = stability.atlas("sliding", chunks=CHUNKS, **{**GRID, "alpha_v": 0.7})
    with pytest.raises(ResumeError, match=r"different atlas \(alpha_v differ\)"):
        write_atlas(other, out, resume=True)
    assert not out.exists() and store.is_dir()


def test_cli_zarr_and_refusals(tmp_path, capsys, reference):
    args = ["atlas", "--q", "-0.6:0.6:13", "--fr-inv", "0,0.3", "--sigma", "0.2:1.2:4", "--alpha-v", "0.5"]
    args += ["--mask-unphysical", "--no-progress"]
    assert main([*args, "--chunks", "q=4,sigma=2", "--resume", "-o", str(tmp_path / "a.zarr")]) == 0
    assert "wrote" in capsys.readouterr().out
    _bitwise(stability.open_atlas(tmp_path / "a.zarr"), reference)
    assert main([*args, "--variables", "map", "-o", str(tmp_path / "b.zarr")]) == 2
    assert "apply to netCDF files only" in capsys.readouterr().err
    with pytest.raises(InputError, match="apply to netCDF files only"):
        write_atlas(reference, tmp_path / "c.zarr", float32=True)
    (tmp_path / "d.zarr").mkdir()
    with pytest.raises(AtlasFileError, match="not a readable Zarr store"):
        stability.open_atlas(tmp_path / "d.zarr")


def test_an_unreadable_store_without_zarr_is_refused_naming_it(tmp_path, monkeypatch):
    """Without zarr (the optional cluster extra) a directory named like a store is still an
    AtlasFileError naming it (the search for its damaged chunk needs zarr and is skipped), not
    the ImportError of the search."""
    import sys

    (tmp_path / "e.zarr").mkdir()
    (tmp_path / "e.zarr" / "zarr.json").write_text("junk")
    monkeypatch.setitem(sys.modules, "zarr", None)
    with pytest.raises(AtlasFileError, match=r"atlas store .*e\.zarr' is not a readable Zarr store: it cannot be read"):
        stability.open_atlas(tmp_path / "e.zarr")


def _hidden(directory) -> list[str]:
    return sorted(p.name for p in directory.iterdir() if p.name.startswith(TEMPORARY_PREFIX))


def _on_commit(monkeypatch, target, action) -> None:
    """Call ``action(error)`` in place of nothing just before the rename that commits a store to
    ``target`` (the rename of a hidden temporary store onto it, not the one moving an old store
    aside); ``action`` may raise, or act as another process."""
    real = os.rename

    def rename(src, dst, *args, **kwargs):
        src_name = os.path.basename(os.fspath(src))
        if os.fspath(dst) == os.fspath(target) and src_name.startswith(TEMPORARY_PREFIX) and "-old-" not in src_name:
            action()
        return real(src, dst, *args, **kwargs)

    monkeypatch.setattr(os, "rename", rename)


def test_a_failed_commit_puts_the_replaced_store_back(tmp_path, monkeypatch, reference):
    """overwrite=True moves the existing store aside before the rename that commits: when that
    rename fails (here EIO), the existing store is put back under its name, intact, and the
    error names the cause (not "another process")."""
    out = write_atlas(reference, tmp_path / "a.zarr")

    def fail():
        raise OSError(errno.EIO, os.strerror(errno.EIO))

    _on_commit(monkeypatch, out, fail)
    other = stability.atlas("sliding", **{**GRID, "alpha_v": 0.7})
    with pytest.raises(OutputWriteError, match=r"renaming the complete store to it failed .*nothing was replaced"):
        write_atlas(other, out, overwrite=True)
    monkeypatch.undo()
    assert _hidden(tmp_path) == []
    _bitwise(stability.open_atlas(out), reference)


@pytest.mark.parametrize("existing", [False, True])
def test_another_process_creating_the_name_wins(tmp_path, monkeypatch, reference, existing):
    """Another process creates the output while this run computes (just before its commit): this
    run gets FileExistsError and removes its own store; the other's output is left as it is. With
    overwrite=True the store being replaced cannot be put back then (its name is taken): the
    error says where it is."""
    out = tmp_path / "a.zarr"
    if existing:
        write_atlas(reference, out)

    def other_process():
        (tmp_path / "elsewhere").mkdir()
        (tmp_path / "elsewhere" / "theirs").write_text("theirs")
        os.replace(tmp_path / "elsewhere", out) if not out.exists() else None

    _on_commit(monkeypatch, out, other_process)
    with pytest.raises(FileExistsError, match="created by another process") as info:
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, overwrite=existing)
    monkeypatch.undo()
    assert sorted(p.name for p in out.iterdir()) == ["theirs"]
    hidden = _hidden(tmp_path)
    if existing:  # the store replaced: moved aside, named in the error, intact
        assert len(hidden) == 1 and hidden[0] in str(info.value) and "could not be put back" in str(info.value)
        _bitwise(stability.open_atlas(tmp_path / hidden[0]), reference)
    else:
        assert hidden == []


def test_two_writers_in_one_process_have_their_own_stores(tmp_path, monkeypatch, reference):
    """A second write_atlas to the same name, in the same process, while the first computes its
    first chunk: each builds its own hidden store (unique names, not one per process id); the
    second commits, the first then finds the name taken (and says so: the check at the commit)."""
    out = tmp_path / "a.zarr"
    real = dist._compute_block
    nested = []

    def compute(spec, sl):
        if not nested:
            nested.append(_hidden(tmp_path))  # the first writer's store, and only it
            write_atlas(reference, out)
        return real(spec, sl)

    monkeypatch.setattr(dist, "_compute_block", compute)
    with pytest.raises(FileExistsError, match=r"a\.zarr' exists; pass overwrite=True"):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out)
    assert len(nested[0]) == 1 and _hidden(tmp_path) == []
    _bitwise(stability.open_atlas(out), reference)


@pytest.mark.parametrize("variable", ["growth_rate", "q"])
def test_a_damaged_store_is_refused_naming_the_chunk(tmp_path, reference, variable):
    """One chunk file of a complete store overwritten with other bytes (a data variable's, read
    when the atlas loads; a coordinate's, read when the store opens): open_atlas refuses it
    with an AtlasFileError naming the store and that chunk file, not a bare OSError."""
    out = write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), tmp_path / "a.zarr")
    key = "c/0/0/0/0" if variable == "growth_rate" else "c/0"
    chunk = out / variable / key
    assert chunk.is_file()
    chunk.write_bytes(b"not a zstd frame" * 4)
    with pytest.raises(AtlasFileError, match=rf"atlas store .*a\.zarr' .*chunk file '{variable}/{key}' is damaged"):
        stability.open_atlas(out)


def test_a_store_in_a_missing_or_unwritable_directory_is_refused_before_computing(tmp_path, monkeypatch):
    """As for a netCDF file: the store's directory must exist and be writable, checked before
    any chunk is computed (nothing created: not no/such/, not a store)."""
    computed = []
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: computed.append(sl))
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    with pytest.raises(FileNotFoundError, match=r"output directory .*no/such' of .*a\.zarr' does not exist"):
        write_atlas(ds, tmp_path / "no" / "such" / "a.zarr")
    (tmp_path / "file").write_text("")
    with pytest.raises(NotADirectoryError, match=r"output directory .*file' of .* is not a directory"):
        write_atlas(ds, tmp_path / "file" / "a.zarr")
    if os.geteuid() != 0:  # root writes anywhere: the probe is what tells
        locked = tmp_path / "locked"
        locked.mkdir(mode=0o500)
        with pytest.raises(PermissionError, match=r"output directory .*locked' of .* is not writable"):
            write_atlas(ds, locked / "a.zarr")
    assert computed == [] and sorted(p.name for p in tmp_path.iterdir()) == ["file"] + (
        ["locked"] if os.geteuid() else []
    )
