"""What an atlas file stores (``write_atlas(variables=, compression=, float32=)``, ``tippe atlas
--variables/--compression/--float32``), read back by ``open_atlas``.

Reference: the in-memory atlas of :func:`stability.atlas` (the whole grid in one call, the
leading growth rate decided on the whole grid by :func:`stability.grids.atlases.leading_growth_rate`,
a different code path from the writer's chunk-by-chunk one). Float64 variables and the flags
must come back bit for bit (compression is lossless); a float32 variable within its stated
bound, the relative error ``2**-24`` of rounding to nearest with a 24-bit significand (derived:
``|fl32(x) - x| <= 2**-24 |x|`` for ``x`` in float32's normal range), read from the file's own
attribute.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import stability
from stability.cli import main
from stability.errors import InputError
from stability.grids.chunked import write_atlas

GRID = dict(
    q=np.linspace(-0.6, 0.6, 31), fr_inv=np.linspace(0.0, 3.0, 7), sigma=np.linspace(0.05, 1.95, 9), alpha_v=[0.1, 1.0]
)


@pytest.fixture(scope="module")
def reference():
    return stability.atlas("sliding", mask_unphysical=True, **GRID)


def _aligned(read, ref, v):
    return read[v].values, ref[v].transpose(*read[v].dims).values


@pytest.mark.parametrize("variables", ["all", "map"])
@pytest.mark.parametrize("compression", [None, "zlib", "zstd"])
@pytest.mark.parametrize("lazy", [False, True])
def test_float64_file_equals_in_memory_atlas(tmp_path, reference, variables, compression, lazy):
    src = stability.atlas("sliding", mask_unphysical=True, chunks={"q": 7}, **GRID) if lazy else reference
    path = write_atlas(src, tmp_path / "a.nc", variables=variables, compression=compression)
    read = stability.open_atlas(path)
    want = set(reference.data_vars) if variables == "all" else {"leading_growth_rate", "stability"}
    assert set(read.data_vars) == want
    for v in read.data_vars:
        a, b = _aligned(read, reference, v)
        assert a.dtype == b.dtype and np.array_equal(a, b, equal_nan=True), v
    assert read.attrs.get("atlas_variables", "all") == variables
    if compression is not None:
        assert read.attrs["compression"].startswith(compression)


@pytest.mark.parametrize("variables", ["all", "map"])
def test_float32_file_within_its_stated_bound(tmp_path, reference, variables):
    path = write_atlas(reference, tmp_path / "a.nc", variables=variables, compression="zstd", float32=True)
    read = stability.open_atlas(path)
    floats = [v for v in read.data_vars if read[v].dtype.kind == "f"]
    assert floats and all(read[v].dtype == np.float32 for v in floats)
    for v in read.data_vars:
        a, b = _aligned(read, reference, v)
        if v in floats:
            bound = float(read[v].attrs["storage_relative_error"])
            assert bound == 2.0**-24
            assert "eigenvalue error bound" in read[v].attrs["storage_comment"]
            assert np.array_equal(np.isnan(a), np.isnan(b)), v
            ok = ~np.isnan(b)
            assert np.all(np.abs(a[ok].astype(np.float64) - b[ok]) <= bound * np.abs(b[ok])), v
            assert np.array_equal(np.sign(a[ok]), np.sign(b[ok])), v  # no sign changed by the rounding
        else:  # flags: decided in float64, stored exactly
            assert a.dtype == b.dtype and np.array_equal(a, b), v


def test_leading_growth_rate_decided_on_the_whole_grid(tmp_path):
    """Chunks along fr_inv with the fr_inv = 0 plane first: the writer first leaves the zero mode
    out, then meets a chunk that has none and rewrites the first ones (recomputed in a map)."""
    grid = dict(GRID, fr_inv=[0.0, 0.0, 0.5])
    ref = stability.atlas("sliding", mask_unphysical=True, **grid)
    plane = stability.atlas("sliding", mask_unphysical=True, **dict(GRID, fr_inv=0.0))
    # the plane alone leaves the zero mode out (so the rewrite above is exercised)
    assert not np.array_equal(plane.leading_growth_rate.values, plane.max_growth_rate.values, equal_nan=True)
    for variables in ("all", "map"):
        lazy = stability.atlas("sliding", mask_unphysical=True, chunks={"fr_inv": 1}, **grid)
        read = stability.open_atlas(write_atlas(lazy, tmp_path / f"{variables}.nc", variables=variables))
        a, b = _aligned(read, ref, "leading_growth_rate")
        assert np.array_equal(a, b, equal_nan=True)
    read = stability.open_atlas(write_atlas(plane, tmp_path / "plane.nc", variables="map"))
    a, b = _aligned(read, plane, "leading_growth_rate")
    assert np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("value", [-1e-300, 1e-40, 1e39])  # -> -0.0, a subnormal, inf in float32
def test_float32_refuses_a_value_it_would_change(tmp_path, reference, value):
    ds = reference.copy(deep=True)
    inside = np.argwhere(ds.stability.values >= 0)[0]
    ds["frequency"].values[tuple(inside) + (2,)] = value
    with pytest.raises(InputError, match=re.escape(f"frequency = {value!r} is outside the normal range of float32")):
        write_atlas(ds, tmp_path / "a.nc", float32=True)
    assert not (tmp_path / "a.nc").exists()


def test_bad_choices_are_named(tmp_path, reference):
    with pytest.raises(InputError, match="variables = 'modes' is not a choice"):
        write_atlas(reference, tmp_path / "a.nc", variables="modes")
    with pytest.raises(InputError, match="compression = 'gzip' is not a choice"):
        write_atlas(reference, tmp_path / "a.nc", compression="gzip")


@pytest.mark.parametrize("chunks", [[], ["--chunks", "q=5"]])
def test_cli_map_file(tmp_path, reference, chunks):
    out = tmp_path / "m.nc"
    rc = main(
        [
            "atlas",
            "--model",
            "sliding",
            "--q",
            "-0.6:0.6:31",
            "--fr-inv",
            "0:3:7",
            "--sigma",
            "0.05:1.95:9",
            "--alpha-v",
            "0.1,1.0",
            "--mask-unphysical",
            "--variables",
            "map",
            "--compression",
            "zstd",
            "--float32",
            "--no-progress",
            *chunks,
            "-o",
            str(out),
        ]
    )
    assert rc == 0
    read = stability.open_atlas(out)
    assert set(read.data_vars) == {"leading_growth_rate", "stability"}
    a, b = _aligned(read, reference, "stability")
    assert np.array_equal(a, b)


def test_map_file_draws_the_same_stability_map(tmp_path, reference):
    """The map file draws the stability map of the full atlas: the same colour array (the leading
    growth rate, bit for bit in float64) over the same plane."""
    import matplotlib as mpl

    mpl.use("Agg")
    import matplotlib.pyplot as plt

    from stability.plotting.figures import plot_atlas

    plane = dict(fr_inv=0.5, alpha_v=0.1)
    read = stability.open_atlas(write_atlas(reference, tmp_path / "m.nc", variables="map"))
    fig_a, ax_a = plot_atlas(reference.sel(plane), "q", "sigma")
    fig_b, ax_b = plot_atlas(read.sel(plane), "q", "sigma")
    a = np.ma.filled(ax_a.collections[0].get_array(), np.nan)
    b = np.ma.filled(ax_b.collections[0].get_array(), np.nan)
    assert np.array_equal(a, b, equal_nan=True)
    plt.close(fig_a)
    plt.close(fig_b)
    with pytest.raises(ValueError, match="map atlas"):
        from stability.plotting.atlas_plots import plot_growth_rate

        plot_growth_rate(read.sel(fr_inv=0.5, alpha_v=0.1, sigma=1.0, method="nearest"), "q")


def test_small_file_chunks_read_back_bit_for_bit(tmp_path, reference, monkeypatch):
    """Grid chunks written as several file (HDF5) chunks: each file chunk divides the grid chunk
    (every write covers whole file chunks) and is at most ``FILE_CHUNK_BYTES``; the file, read
    back, equals the in-memory atlas bit for bit (reference: the whole grid in one call), the
    grid chunks q=8 of 31 leaving a partial last one. The limit is made small (2 kB) so that this
    small grid is cut along two dimensions."""
    import netCDF4

    from stability.grids import chunked

    monkeypatch.setattr(chunked, "FILE_CHUNK_BYTES", 2048)
    lazy = stability.atlas("sliding", mask_unphysical=True, chunks={"q": 8}, **GRID)
    calls = []
    path = write_atlas(lazy, tmp_path / "a.nc", compression="zstd", progress=lambda d, t: calls.append((d, t)))
    # the progress callback runs in the caller's thread, once per chunk, in order
    assert calls == [(i, 4) for i in range(1, 5)]
    with netCDF4.Dataset(path) as nc:
        for k in ("growth_rate", "leading_growth_rate", "stability"):
            var = nc.variables[k]
            grid_chunk = [8 if d == "q" else len(nc.dimensions[d]) for d in var.dimensions]
            file_chunk = var.chunking()
            assert all(g % f == 0 for g, f in zip(grid_chunk, file_chunk)), (k, file_chunk)
            assert np.prod(file_chunk) * var.dtype.itemsize <= 2048, (k, file_chunk)
            if np.prod(grid_chunk) * var.dtype.itemsize > 2048:
                assert file_chunk != grid_chunk, k
    read = stability.open_atlas(path)
    for v in reference.data_vars:
        a, b = _aligned(read, reference, v)
        assert np.array_equal(a, b, equal_nan=True), v
