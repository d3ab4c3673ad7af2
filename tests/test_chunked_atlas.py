"""Chunked, dask-backed atlases: lazy datasets, chunk-wise netCDF writing, resuming, clusters.

Reference: the in-memory atlas (``stability.atlas`` without ``chunks``), whose values are checked
against mpmath in test_spectra_reference and test_kernel; a chunked computation runs the same
per-point arithmetic on slices of the grid, so the values must be identical (atol = rtol = 0), and
the file written chunk by chunk must read back identical to the in-memory dataset, attributes
included (except the creation time in ``history``).
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from conftest import assert_resume_completes, assert_same_atlas, kept_chunks

import stability
from stability.cli import main
from stability.errors import DomainError, ResumeError
from stability.grids.chunked import parts_directory, write_atlas
from stability.grids.cluster import dask_client

GRID = dict(
    q=np.linspace(-0.6, 0.6, 31),
    fr_inv=[0.0, 0.1, 0.3, 1.0],
    sigma=np.linspace(0.2, 1.2, 5),
    alpha_v=0.5,
    mask_unphysical=True,
)
CHUNKS = {"q": 8, "sigma": 2}  # 4 x 1 x 3 = 12 chunks, ragged at the ends


@pytest.fixture(scope="module")
def reference() -> xr.Dataset:
    return stability.atlas("sliding", **GRID)


def test_lazy_atlas_is_dask_backed_and_equal(reference):
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    assert ds.growth_rate.chunks is not None
    assert ds.growth_rate.data.numblocks == (4, 1, 3, 1)
    assert_same_atlas(ds.compute(), reference)


def test_lazy_atlas_refuses_unphysical_grid_at_once():
    with pytest.raises(DomainError, match="sigma"):
        stability.atlas("sliding", chunks=4, **{**GRID, "mask_unphysical": False})


def test_chunk_wise_file_equals_in_memory(tmp_path, reference):
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    seen = []
    write_atlas(ds, tmp_path / "a.nc", progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (12, 12)
    assert_same_atlas(stability.open_atlas(tmp_path / "a.nc"), reference)
    # xarray's own streaming writer (dask, in this process) gives the same file contents
    stability.write_dataset(ds, tmp_path / "b.nc")
    assert_same_atlas(stability.open_atlas(tmp_path / "b.nc"), reference)


def test_interrupted_run_leaves_no_file_and_resumes(tmp_path, reference, monkeypatch):
    import stability.grids.chunked as dist

    out = tmp_path / "a.nc"
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    real = dist._compute_block
    calls = []

    def interrupted(spec, sl):
        if len(calls) == 5:
            raise KeyboardInterrupt
        calls.append(sl)
        return real(spec, sl)

    monkeypatch.setattr(dist, "_compute_block", interrupted)
    with pytest.raises(KeyboardInterrupt):
        write_atlas(ds, out, resume=True)
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == [parts_directory(out).name]  # no temporary file either
    assert kept_chunks(out) == 5

    assert_resume_completes(ds, out, reference, monkeypatch, missing=7)


def test_resume_refuses_a_store_of_another_atlas(tmp_path, monkeypatch):
    import stability.grids.chunked as dist

    out = tmp_path / "a.nc"
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: (_ for _ in ()).throw(KeyboardInterrupt))
    with pytest.raises(KeyboardInterrupt):
        write_atlas(stability.atlas("sliding", chunks=CHUNKS, **GRID), out, resume=True)
    other = stability.atlas("sliding", chunks=CHUNKS, **{**GRID, "alpha_v": 0.7})
    with pytest.raises(ResumeError, match="different atlas"):
        write_atlas(other, out, resume=True)


def test_cli_chunks_and_errors(tmp_path, capsys, reference):
    out = tmp_path / "a.nc"
    rc = main(
        [
            "atlas",
            "--q",
            "-0.6:0.6:31",
            "--fr-inv",
            "0,0.1,0.3,1",
            "--sigma",
            "0.2:1.2:5",
            "--alpha-v",
            "0.5",
            "--mask-unphysical",
            "--chunks",
            "q=8,sigma=2",
            "--resume",
            "-o",
            str(out),
        ]
    )
    assert rc == 0 and "in chunks" in capsys.readouterr().out
    assert_same_atlas(stability.open_atlas(out), reference)
    rc = main(
        [
            "atlas",
            "--q",
            "0.1",
            "--fr-inv",
            "0.1",
            "--sigma",
            "1",
            "--alpha-v",
            "0.5",
            "--workers",
            "2",
            "-o",
            str(tmp_path / "b.nc"),
        ]
    )
    assert rc == 2 and "give --chunks too" in capsys.readouterr().err
    rc = main(
        [
            "atlas",
            "--q",
            "0.1",
            "--fr-inv",
            "0.1",
            "--sigma",
            "1",
            "--alpha-v",
            "0.5",
            "--chunks",
            "x=3",
            "-o",
            str(tmp_path / "b.nc"),
        ]
    )
    assert rc == 2 and "not grid dimensions" in capsys.readouterr().err


def _write_scheduler_file(path: str, dask_scheduler=None) -> None:
    """Runs on the scheduler: write its scheduler file as ``dask scheduler --scheduler-file``
    does when it starts (``json.dump(scheduler.identity())``, before any worker has joined)."""
    import json

    with open(path, "w") as f:
        json.dump(dask_scheduler.identity(n_workers=0), f, indent=2)


def test_two_worker_local_cluster(tmp_path, reference):
    """A real LocalCluster: two worker processes on 127.0.0.1; the file written from their
    chunks (through the cluster's client, through a second client connected by address, and
    through ``tippe atlas --scheduler FILE`` connected by a scheduler file), and the lazy dataset
    computed on them, equal the in-process atlas."""
    ds = stability.atlas("sliding", chunks=CHUNKS, **GRID)
    with dask_client(workers=2) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        assert all(w.startswith("tcp://127.0.0.1:") for w in client.scheduler_info()["workers"])
        write_atlas(ds, tmp_path / "a.nc", client=client)
        on_cluster = ds.compute()
        # the same cluster reached as an existing one, by its address (--scheduler tcp://...)
        with dask_client(scheduler=client.scheduler.address) as other:
            write_atlas(ds, tmp_path / "b.nc", client=other, window=1)
        # ... and by a scheduler file, as dask writes it (`dask scheduler --scheduler-file`),
        # through the command line (--scheduler path/to/scheduler.json)
        sched = tmp_path / "scheduler.json"
        client.run_on_scheduler(_write_scheduler_file, path=str(sched))
        with dask_client(scheduler=str(sched)) as other:
            assert other.scheduler.address == client.scheduler.address
        assert (
            main(
                [
                    "atlas",
                    "--q",
                    "-0.6:0.6:31",
                    "--fr-inv",
                    "0,0.1,0.3,1",
                    "--sigma",
                    "0.2:1.2:5",
                    "--alpha-v",
                    "0.5",
                    "--mask-unphysical",
                    "--chunks",
                    "q=8,sigma=2",
                    "--no-progress",
                    "--scheduler",
                    str(sched),
                    "-o",
                    str(tmp_path / "c.nc"),
                ]
            )
            == 0
        )
    assert_same_atlas(stability.open_atlas(tmp_path / "a.nc"), reference)
    assert_same_atlas(stability.open_atlas(tmp_path / "b.nc"), reference)
    assert_same_atlas(stability.open_atlas(tmp_path / "c.nc"), reference)
    assert_same_atlas(on_cluster, reference)


def test_scheduler_errors(tmp_path, capsys):
    """A scheduler file that is missing or not JSON, and --workers 0, are refused before computing."""
    base = ["atlas", "--q", "0.1,0.2", "--fr-inv", "0.1", "--sigma", "1", "--alpha-v", "0.5", "--chunks", "1"]
    rc = main([*base, "--scheduler", str(tmp_path / "nope.json"), "-o", str(tmp_path / "a.nc")])
    err = capsys.readouterr().err
    assert rc == 2 and "nope.json' is neither an address (tcp://host:port) nor an existing scheduler file" in err
    bad = tmp_path / "bad.json"
    bad.write_text("not json")
    rc = main([*base, "--scheduler", str(bad), "-o", str(tmp_path / "a.nc")])
    err = capsys.readouterr().err
    assert rc == 2 and "bad.json' is not a dask scheduler file" in err
    rc = main([*base, "--workers", "0", "-o", str(tmp_path / "a.nc")])
    err = capsys.readouterr().err
    assert rc == 2 and "--workers = 0 is outside the allowed range: --workers >= 1" in err
    assert not (tmp_path / "a.nc").exists()
