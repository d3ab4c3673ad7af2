"""What an atlas is: open_atlas, require_atlas and the plots refuse files and datasets that break it.

Issue 13, item 6 (and E11: an atlas larger than memory is not loaded whole to be checked).
References: a small atlas written by the package reads back equal to the in-memory one, bit for
bit (the layout the validator encodes is the one ``stability.atlas`` produces); a table of
single-defect copies, each built with xarray or netCDF4 directly, each refused with the
variable's name and the rule in the message.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr
from conftest import assert_same_atlas

import stability
import stability.grids.schema as schema
from stability.errors import AtlasFileError, ResourceError
from stability.grids.schema import require_atlas


@pytest.fixture(scope="module")
def good() -> xr.Dataset:
    return stability.atlas(
        "sliding",
        q=np.linspace(-0.8, 0.6, 15),
        fr_inv=[0.0, 0.3],
        sigma=[0.5, 1.0, 1.9],
        alpha_v=0.5,
        mask_unphysical=True,
    )


def _set(ds, name, values):
    out = ds.copy(deep=True)
    out[name] = (ds[name].dims, values, ds[name].attrs)
    return out


def _mutants(good: xr.Dataset) -> list[tuple[str, xr.Dataset, str]]:
    stab = good["stability"].values
    inside = np.argwhere(stab != -1)[0]
    outside = np.argwhere(stab == -1)[0]
    g = good["growth_rate"].values
    out = []

    def add(label, ds, fragment):
        out.append((label, ds, fragment))

    add(
        "stability as floats",
        _set(good, "stability", stab.astype(np.float64) + 0.5),
        "variable 'stability' has dtype float64; an atlas stores it as integer flags",
    )
    s = stab.copy()
    s[tuple(inside)] = 7
    add("stability flag 7", _set(good, "stability", s), "variable 'stability' holds 7, outside its flags")
    add(
        "stability on a foreign dimension",
        good.assign(stability=(("foo", "fr_inv", "sigma"), stab)).drop_vars("physical"),
        "variable 'growth_rate' has dimensions",
    )
    add("growth_rate of strings", _set(good, "growth_rate", g.astype(str)), "variable 'growth_rate' has dtype <U")
    m = good["max_growth_rate"].values.copy()
    m[tuple(inside)] += 1e-3
    add(
        "max_growth_rate not mode 0",
        _set(good, "max_growth_rate", m),
        "variable 'max_growth_rate' differs from growth_rate of mode 0",
    )
    gg = g.copy()
    gg[tuple(inside)] = np.nan
    add("NaN inside the domain", _set(good, "growth_rate", gg), "variable 'growth_rate' has NaN where")
    p = good["physical"].values.copy()
    p[tuple(outside)] = 1
    add("physical disagrees", _set(good, "physical", p), "variables 'physical' and 'stability' disagree")
    p = good["physical"].values.copy()
    p[tuple(inside)] = 3
    add("physical flag 3", _set(good, "physical", p), "variable 'physical' holds 3")
    b = good["eigenvalue_error_bound"].values.copy()
    b[tuple(inside)] = -1.0
    add("negative bound", _set(good, "eigenvalue_error_bound", b), "'eigenvalue_error_bound' has negative values")
    add(
        "frequency without mode",
        good.assign(frequency=good["frequency"].isel(mode=0)),
        "variable 'frequency' has dimensions",
    )
    add(
        "integer growth_rate",
        _set(good, "growth_rate", np.zeros(g.shape, dtype=np.int32)),
        "variable 'growth_rate' has dtype int32",
    )
    bad = good.copy()
    bad["stability"].attrs["flag_values"] = np.array([0, 1, 2, 3], dtype=np.int8)
    add("other flag_values", bad, "variable 'stability' has flag_values [0, 1, 2, 3]")
    add("unknown model", good.assign_attrs(model="spinning"), "its attribute model = 'spinning' is not a linear model")
    add("modes of another model", good.isel(mode=[0, 1]), "it has 2 modes; the sliding model has 3")
    q = good["q"].values.copy()
    q[3] = np.inf
    add("coordinate not finite", good.assign_coords(q=q), "coordinate 'q' has values that are not finite")
    return out


def test_written_atlas_reads_back_identical(tmp_path, good):
    stability.write_dataset(good, tmp_path / "a.nc")
    back = stability.open_atlas(tmp_path / "a.nc")
    assert_same_atlas(back, good)
    for v in ("growth_rate", "frequency", "eigenvalue_error_bound", "max_growth_rate", "stability", "physical"):
        assert back[v].values.tobytes() == good[v].values.tobytes()


@pytest.mark.parametrize("index", range(15))
def test_single_defect_files_are_refused(tmp_path, good, index):
    label, ds, fragment = _mutants(good)[index]
    path = tmp_path / "bad.nc"
    ds.to_netcdf(path)
    with pytest.raises(AtlasFileError) as err:
        stability.open_atlas(path)
    msg = str(err.value)
    assert msg.startswith(f"atlas file '{path}' is not a valid atlas: ") and fragment in msg, (label, msg)


@pytest.mark.parametrize("index", range(15))
def test_single_defect_datasets_are_refused_by_the_plots(good, index):
    label, ds, fragment = _mutants(good)[index]
    with pytest.raises(ValueError) as err:
        require_atlas(ds)
    assert fragment in str(err.value), label
    with pytest.raises(ValueError, match="is not a valid atlas"):
        stability.grids.atlases.leading_growth_rate(ds)


def test_a_defect_in_a_later_slab_is_found(tmp_path, good, monkeypatch):
    """The values are checked slab by slab: a defect in the last slab is found too."""
    monkeypatch.setattr(schema, "SLAB_POINTS", 6)  # one q row (2 x 3 points) per slab
    s = good["stability"].values.copy()
    s[-1, -1, -1] = 9
    path = tmp_path / "bad.nc"
    _set(good, "stability", s).to_netcdf(path)
    with pytest.raises(AtlasFileError, match="holds 9"):
        stability.open_atlas(path)


def test_open_atlas_does_not_load_what_does_not_fit(tmp_path, good, monkeypatch):
    """E11: a file larger than the memory available is refused with the way out; opened with
    chunks= it is lazy (dask) and still checked."""
    path = tmp_path / "a.nc"
    stability.write_dataset(good, path)
    monkeypatch.setenv("TIPPE_MEMORY_LIMIT", "1000")
    with pytest.raises(ResourceError, match=r"would need about .* of memory .*pass chunks="):
        stability.open_atlas(path)
    lazy = stability.open_atlas(path, chunks=5)
    try:
        assert lazy["growth_rate"].chunks is not None
        assert_same_atlas(lazy.compute(), good)
    finally:
        lazy.close()
