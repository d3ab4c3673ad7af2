"""Atlases: shape, coordinates, CF attributes, netCDF round trip, atomic writing, reading back.

References: the eigenvalues of each grid point computed one point at a time by the LAPACK path
(a different method: batched numpy.linalg.eigvals of solve(M, A)), to 1e-11 relative to the
largest root (the LAPACK path's absolute accuracy, see test_spectra_reference); the stability
flag at fr_inv = 0 from the exact structure (c0 = 0).
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import stability
from stability.errors import AtlasFileError


@pytest.fixture
def ds():
    return stability.atlas("sliding", q=np.linspace(-0.4, 0.4, 41), fr_inv=[0.0, 0.1, 0.3], sigma=1.0, alpha_v=0.5)


def test_shape_coordinates_and_values(ds):
    assert ds.growth_rate.dims == ("q", "fr_inv", "mode")
    assert ds.sizes == {"q": 41, "fr_inv": 3, "mode": 3}
    assert ds.sigma.ndim == 0 and float(ds.sigma) == 1.0
    assert float(ds.mu) == 2.28
    for j, f in enumerate([0.0, 0.1, 0.3]):
        ref = stability.eigenvalues("sliding", q=ds.q.values, fr_inv=f, sigma=1.0, alpha_v=0.5, method="lapack")
        scale = np.abs(ref).max(axis=-1, keepdims=True)
        assert np.all(np.abs(ds.growth_rate.values[:, j] - ref.real) <= 1e-11 * scale)
        assert np.all(np.abs(ds.frequency.values[:, j] - ref.imag) <= 1e-11 * scale)
    assert np.array_equal(ds.max_growth_rate.values, ds.growth_rate.values[..., 0])
    assert (np.diff(ds.growth_rate.values, axis=-1) <= 0).all()  # sorted by decreasing Re s


def test_cf_attributes(ds):
    assert ds.attrs["Conventions"].startswith("CF-")
    assert ds.attrs["model"] == "sliding" and ds.attrs["model_equations"] == "(11)"
    assert "exp(s t)" in ds.attrs["time_convention"]
    assert ds.attrs["source"].startswith("tippe-stability ")
    assert ds.attrs["sigma"] == 1.0 and ds.attrs["alpha_v"] == 0.5
    for name in list(ds.data_vars) + ["q", "fr_inv", "sigma", "alpha_v", "mu", "mode"]:
        assert "long_name" in ds[name].attrs, name
    for name in ("growth_rate", "frequency", "max_growth_rate", "leading_growth_rate"):
        assert ds[name].attrs["units"] == "Omega"  # rates in units of the spin rate
    assert ds.q.attrs["units"] == "R"
    for name in ("fr_inv", "sigma"):
        assert ds[name].attrs["units"] == "1"
    st = ds.stability.attrs
    assert list(st["flag_values"]) == [-1, 0, 1, 2]
    assert st["flag_meanings"].split() == ["outside_domain", "stable", "marginal", "unstable"]


def test_stability_flag_at_zero_gravity(ds):
    """fr_inv = 0: exactly zero eigenvalue. q > 0 (others decay): marginal; q < 0 with sigma = 1
    below (1 - mu q^2)/(1 + q): a mode grows, unstable (closed form in test_spectra_reference)."""
    st = ds.stability.sel(fr_inv=0.0)
    q = ds.q.values
    grows = (1 - 2.28 * q**2) / (1 + q) > 1.0
    assert (st.values[(q > 1e-12) & ~grows] == 1).all()
    assert (st.values[grows & (q < -1e-12)] == 2).all()
    assert (st.values != 2)[~grows].all()


def test_netcdf_round_trip(ds, tmp_path):
    path = stability.write_dataset(ds, tmp_path / "atlas.nc")
    back = stability.open_atlas(path)
    xr.testing.assert_identical(ds, back)


def test_existing_file_not_overwritten(ds, tmp_path):
    p = tmp_path / "atlas.nc"
    stability.write_dataset(ds, p)
    with pytest.raises(FileExistsError, match="exists"):
        stability.write_dataset(ds, p)
    stability.write_dataset(ds, p, overwrite=True)


def test_failed_write_leaves_no_file(ds, tmp_path, monkeypatch):
    import stability.grids.netcdf as netcdf

    def boom(ds, path):
        open(path, "wb").write(b"CDF\x01 partial")
        raise RuntimeError("disk full")

    monkeypatch.setattr(netcdf, "_to_netcdf", boom)
    with pytest.raises(RuntimeError, match="disk full"):
        stability.write_dataset(ds, tmp_path / "atlas.nc")
    assert list(tmp_path.iterdir()) == []


def test_open_atlas_refuses_non_atlases(ds, tmp_path):
    with pytest.raises(AtlasFileError, match="missing.nc' does not exist"):
        stability.open_atlas(tmp_path / "missing.nc")
    junk = tmp_path / "junk.nc"
    junk.write_bytes(b"this is not netCDF")
    with pytest.raises(AtlasFileError, match="junk.nc' is not a readable netCDF file"):
        stability.open_atlas(junk)
    good = stability.write_dataset(ds, tmp_path / "good.nc")
    trunc = tmp_path / "trunc.nc"
    trunc.write_bytes(good.read_bytes()[:2000])
    with pytest.raises(AtlasFileError, match="trunc.nc"):
        stability.open_atlas(trunc)
    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(foreign)
    with pytest.raises(AtlasFileError, match="foreign.nc' is not an atlas of tippe-stability"):
        stability.open_atlas(foreign)


def test_second_order_model_atlas():
    ds = stability.atlas("fixed_pivot", q=[-0.2, 0.0, 0.2], fr_inv=np.linspace(0, 2, 5), sigma=1.0)
    assert ds.sizes == {"q": 3, "fr_inv": 5, "mode": 2}
    assert "alpha_v" not in ds.coords
    with pytest.raises(TypeError, match="scalar or a 1-D array"):
        stability.atlas("fixed_pivot", q=np.zeros((2, 2)), fr_inv=0.1, sigma=1.0)
