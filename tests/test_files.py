"""Files: atlases that are missing, truncated, foreign or not netCDF; output paths checked before
any computation; no partial files; existing files kept unless asked; recipes regenerate their own.

Reference: docs/input_checks.md (file behaviour) and stability.grids.netcdf's contract.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stability
from stability.cli import main
from stability.errors import AtlasFileError

ATLAS = ["atlas", "--q", "0.1,0.2", "--fr-inv", "0.1", "--sigma", "1", "--alpha-v", "0.5"]


@pytest.fixture(scope="module")
def atlas_file(tmp_path_factory) -> Path:
    ds = stability.atlas("sliding", q=np.linspace(-0.3, 0.3, 40), fr_inv=[0.0, 0.1], sigma=1.0, alpha_v=0.5)
    return stability.write_dataset(ds, tmp_path_factory.mktemp("a") / "atlas.nc")


@pytest.mark.parametrize(
    "make,fragment",
    [
        (lambda p, good: None, "does not exist"),
        (
            lambda p, good: p.write_bytes(good.read_bytes()[: good.stat().st_size // 2]),
            "is not a readable netCDF file: it cannot be read to the end (truncated or damaged",
        ),
        (
            lambda p, good: xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(p),
            "is not an atlas of tippe-stability: it has no global attribute 'tippe_stability_product' (written by "
            "another program",
        ),
        (
            lambda p, good: stability.write_dataset(
                stability.open_atlas(good).assign_attrs(tippe_stability_product="neutral_curve"), p
            ),
            "is not an atlas: it is a 'neutral_curve' file of tippe-stability (open it with xarray.open_dataset)",
        ),
        (lambda p, good: p.write_text("plain text"), "is not a readable netCDF file (it does not start with a netCDF"),
        (lambda p, good: p.write_bytes(b""), "is empty (0 bytes)"),
        (
            lambda p, good: stability.write_dataset(stability.open_atlas(good).drop_vars("frequency"), p),
            "is not a complete atlas: missing variables frequency",
        ),
    ],
)
def test_open_atlas_bad_files(tmp_path, atlas_file, make, fragment):
    p = tmp_path / "x.nc"
    make(p, atlas_file)
    with pytest.raises(AtlasFileError) as err:
        stability.open_atlas(p)
    assert f"atlas file '{p}'" in str(err.value) and fragment in str(err.value)


def test_open_atlas_wrong_path_type():
    with pytest.raises(TypeError, match="atlas path = None must be a file name"):
        stability.open_atlas(None)


def _never(*args, **kwargs):
    raise AssertionError("the computation must not start")


def _unwritable_directory(tmp_path):
    """A directory this process cannot create files in: a read-only one, or, as root (who
    ignores permission bits), the kernel's /sys, where creating a file fails."""
    if os.geteuid() != 0:
        d = tmp_path / "ro"
        d.mkdir()
        d.chmod(0o500)
        return d
    import tempfile

    try:
        fd, probe = tempfile.mkstemp(dir="/sys")
    except OSError:
        return Path("/sys")
    os.close(fd)
    os.unlink(probe)
    pytest.skip("no unwritable directory available to root on this machine")


@pytest.mark.parametrize(
    "command,module,func,argv",
    [
        ("atlas", "stability.grids.atlases", "atlas", ATLAS),  # commands import it in run()
        ("atlas --chunks", "stability.grids.atlases", "atlas", [*ATLAS, "--chunks", "1"]),
        (
            "simulate",
            "stability.nonlinear.runs",
            "simulate",
            [
                "simulate",
                "--t-end",
                "1",
                "--omega",
                "0,0,1",
                "--k",
                "0,0,1",
                "--q",
                "-0.1",
                "--fr-inv",
                "0.3",
                "--sigma",
                "1",
                "--alpha-v",
                "0.5",
            ],
        ),
        (
            "validate",
            "stability.nonlinear.validation",
            "validate",
            ["validate", "--q", "-0.1", "--fr-inv", "0.3", "--sigma", "1", "--alpha-v", "0.5"],
        ),
        (
            "neutral",
            "stability.linear.neutral_curves",
            "neutral_curve",
            ["neutral", "--x", "q", "--y", "sigma", "--fr-inv", "0", "--alpha-v", "0.5"],
        ),
    ],
)
@pytest.mark.parametrize("problem", ["missing directory", "unwritable directory", "existing file"])
def test_outputs_checked_before_computing(tmp_path, monkeypatch, capsys, command, module, func, argv, problem):
    import importlib

    monkeypatch.setattr(importlib.import_module(module), func, _never)
    if problem == "missing directory":
        out, fragment = tmp_path / "no" / "such" / "a.nc", "does not exist"
    elif problem == "unwritable directory":
        out, fragment = _unwritable_directory(tmp_path) / "a.nc", "is not writable"
    else:
        out = tmp_path / "a.nc"
        out.write_text("keep me")
        fragment = "exists; pass overwrite=True (--overwrite) to replace it"
    rc = main([*argv, "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and fragment in err and str(out) in err
    if problem == "existing file":
        assert out.read_text() == "keep me"


def test_unwritable_directory_api(tmp_path):
    d = tmp_path / "file-not-dir"
    d.write_text("")
    ds = stability.atlas("fixed_pivot", q=0.1, fr_inv=0.1, sigma=1.0)
    with pytest.raises(NotADirectoryError, match="is not a directory"):
        stability.write_dataset(ds, d / "a.nc")
    with pytest.raises(IsADirectoryError, match="is a directory; give a file name"):
        stability.write_dataset(ds, tmp_path)


def test_overwrite_only_when_asked(tmp_path, capsys):
    out = tmp_path / "a.nc"
    assert main([*ATLAS, "-o", str(out)]) == 0
    first = out.read_bytes()
    assert main([*ATLAS[:2], "0.3,0.4", *ATLAS[3:], "-o", str(out)]) == 2
    assert "exists; pass overwrite=True (--overwrite)" in capsys.readouterr().err
    assert out.read_bytes() == first
    assert main([*ATLAS[:2], "0.3,0.4", *ATLAS[3:], "-o", str(out), "--overwrite"]) == 0
    assert list(stability.open_atlas(out).q.values) == [0.3, 0.4]
    ds = stability.atlas("fixed_pivot", q=0.1, fr_inv=0.1, sigma=1.0)
    with pytest.raises(FileExistsError, match="exists; pass overwrite=True"):
        stability.write_dataset(ds, out)
    stability.write_dataset(ds, out, overwrite=True)
    assert stability.open_atlas(out).attrs["model"] == "fixed_pivot"


def test_failed_write_leaves_no_partial_file(tmp_path, monkeypatch):
    ds = stability.atlas("fixed_pivot", q=[0.1, 0.2], fr_inv=0.1, sigma=1.0)

    def broken(ds, path):
        Path(path).write_bytes(b"CDF\x01 half written")
        raise OSError("disk full")

    import stability.grids.netcdf as netcdf

    monkeypatch.setattr(netcdf, "_to_netcdf", broken)
    with pytest.raises(OSError, match="disk full"):
        stability.write_dataset(ds, tmp_path / "a.nc")
    assert list(tmp_path.iterdir()) == []


def test_recipes_regenerate_their_own_outputs_and_refuse_foreign_files(tmp_path, capsys):
    recipe = tmp_path / "tiny.toml"
    recipe.write_text(
        'title = "tiny"\nkind = "lines"\nmodel = "fixed_pivot"\nx = "q"\n\n'
        '[grid]\nq = "-0.2:0.2:5"\nfr_inv = 0.1\nsigma = 1.0\n'
    )
    capsys.readouterr()
    assert main(["figures", str(recipe)]) == 0  # fresh
    png, nc = tmp_path / "tiny.png", tmp_path / "tiny.nc"
    assert png.is_file() and nc.is_file()
    out = capsys.readouterr().out  # what it did with the dataset is said (issue 15 item 8)
    assert re.search(rf"tiny: computed {re.escape(str(nc))} \(\d+\.\d s\)", out) and "reused" not in out
    assert f"tiny: wrote {png}" in out
    assert main(["figures", str(recipe)]) == 0  # second run: reuses the dataset, redraws the PNG
    out = capsys.readouterr().out
    assert f"tiny: reused {nc}" in out and "computed" not in out and f"tiny: wrote {png}" in out
    recipe.write_text(recipe.read_text().replace("0.2:5", "0.2:7"))
    assert main(["figures", str(recipe)]) == 0  # stale dataset: replaced (it is the recipe's own)
    assert f"tiny: computed {nc}" in capsys.readouterr().out
    assert stability.open_atlas(nc).sizes["q"] == 7
    capsys.readouterr()
    nc.unlink()
    xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(nc)  # a file no recipe wrote
    assert main(["figures", str(recipe)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "was not written by a recipe" in err and "--force" in err
    assert "x" in xr.open_dataset(nc).load()
    assert main(["figures", "--force", str(recipe)]) == 0
    assert stability.open_atlas(nc).sizes["q"] == 7


def test_figures_output_directory_checked_before_computing(tmp_path, monkeypatch, capsys):
    import stability.recipes as recipes  # tippe figures imports compute from here in its run()

    recipe = tmp_path / "tiny.toml"
    recipe.write_text(
        'title = "tiny"\nkind = "lines"\nmodel = "fixed_pivot"\nx = "q"\n\n'
        '[grid]\nq = "-0.2:0.2:5"\nfr_inv = 0.1\nsigma = 1.0\n'
    )
    (tmp_path / "tiny.png").mkdir()  # the output path is taken by a directory
    monkeypatch.setattr(recipes, "compute", _never)
    assert main(["figures", str(recipe)]) == 2
    assert "tiny.png' is a directory" in capsys.readouterr().err


def test_write_dataset_in_slabs_is_the_dataset(tmp_path, monkeypatch):
    """Reference: the dataset itself (xarray.testing.assert_identical after reading back), and
    xarray's own ``to_netcdf`` of it. With slabs of 1 kB every variable goes through the slab
    path (numpy and dask-backed, float64 with NaN, int8 flags, attributes), with an interruption
    point per slab (counted): the file holds exactly the dataset."""
    import dask.array as da

    import stability.grids.netcdf as netcdf

    monkeypatch.setattr(netcdf, "SLAB_BYTES", 1024)
    calls = []
    real = netcdf.checkpoint
    monkeypatch.setattr(netcdf, "checkpoint", lambda: calls.append(1) or real())
    rng = np.random.default_rng(1)
    g = rng.random((300, 7))
    g[5, 3] = np.nan
    ds = xr.Dataset(
        {
            "g": (("a", "b"), g, {"units": "Omega"}),
            "s": (("a", "b"), rng.integers(-1, 3, (300, 7)).astype(np.int8)),
            "lazy": (("a", "b"), da.from_array(g * 2, chunks=(50, 7))),
        },
        coords={"a": np.arange(300.0), "b": np.arange(7.0)},
        attrs={"product": "test"},
    )
    netcdf.write_dataset(ds, tmp_path / "w.nc")
    ds.to_netcdf(tmp_path / "x.nc")
    with xr.open_dataset(tmp_path / "w.nc") as w, xr.open_dataset(tmp_path / "x.nc") as x:
        xr.testing.assert_identical(w.load(), ds.compute())
        xr.testing.assert_identical(w.load(), x.load())
    assert len(calls) >= 300 * 7 * 8 // 1024 + 6  # one per slab of g, of lazy's 6 chunks, and more


@pytest.mark.skipif(os.name != "posix", reason="POSIX permissions")
def test_outputs_get_the_umask_without_setting_it(tmp_path, monkeypatch):
    """A committed file (and a Zarr store's directory) has the mode the process's umask gives a
    new file (directory). Reference: a file and a directory created by ``open`` and
    ``os.mkdir`` in the same directory, to which the kernel applies the umask itself; under an
    unusual umask (0o027), so that 0o644 would not pass by chance. The umask is read, never
    set: ``os.umask`` (process-wide, a race with every other thread creating a file) fails
    the test if called."""
    import stat

    from stability.files import atomic_output
    from stability.grids.chunked import write_atlas

    previous = os.umask(0o027)
    try:
        (tmp_path / "reference").write_text("")
        os.mkdir(tmp_path / "reference-dir")

        def forbidden(mask):
            raise AssertionError(f"os.umask({mask:#o}) called while writing")

        monkeypatch.setattr(os, "umask", forbidden)
        with atomic_output(tmp_path / "a.txt") as tmp:
            Path(tmp).write_text("x")
        ds = stability.atlas("fixed_pivot", q=[0.1, 0.2], fr_inv=0.1, sigma=1.0)
        store = write_atlas(ds, tmp_path / "a.zarr")
        monkeypatch.undo()
    finally:
        os.umask(previous)
    mode = lambda p: stat.S_IMODE(os.stat(p).st_mode)  # noqa: E731
    assert mode(tmp_path / "a.txt") == mode(tmp_path / "reference") == 0o640
    assert mode(store) == mode(tmp_path / "reference-dir") == 0o750


def test_a_long_output_name_fits_its_temporary(tmp_path):
    """The temporary file of a write is the output's name plus 20 characters (the hidden prefix
    and 8 random hex digits: stability.files.temporary_name); an output name that leaves room
    for them under the file system's limit on a name (os.pathconf NAME_MAX, 255 on Linux) is
    written, and no temporary is left."""
    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    name = "a" * (limit - 20 - 3) + ".nc"
    path = stability.write_dataset(xr.Dataset({"x": ("i", np.arange(3.0))}), tmp_path / name)
    assert path.name == name and sorted(p.name for p in tmp_path.iterdir()) == [name]
