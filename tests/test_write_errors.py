"""A failed write names the file and the cause, exits 2, and leaves nothing behind.

Issue 13, item 12 (and E6: a clean-up error never replaces the first error). References:

* a real file size limit: ``RLIMIT_FSIZE`` set in a subprocess (unprivileged and deterministic;
  Python ignores SIGXFSZ, so the write fails with EFBIG inside HDF5, which reports only
  "NetCDF: HDF error"). The limit is chosen above the package's estimate of the output's size
  (so the up-front check lets it through) and below the real file (the HDF5 header adds a few
  kB): the failure happens during the write;
* the up-front check: a limit below the estimate refuses before computing;
* ENOSPC: ``np.savez`` of a chunk file made to raise ``OSError(ENOSPC)``, and a netCDF failure
  without an errno while ``statvfs`` reports a full file system.
"""

from __future__ import annotations

import errno
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import stability
import stability.files as outputs
from stability.errors import OutputWriteError
from stability.files import TEMPORARY_PREFIX, check_free_space, close_quietly

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX resource limits")

TIPPE = [sys.executable, "-m", "stability"]
SIM = [
    "simulate",
    "--t-end",
    "10",
    "--omega",
    "0.02,0,1",
    "--k",
    "0.05,0,1",
    "--q",
    "-0.1",
    "--fr-inv",
    "0.3",
    "--sigma",
    "1",
    "--alpha-v",
    "0.5",
]
ATLAS = ["atlas", "--q=-0.6:0.6:31", "--fr-inv", "0:1:4", "--sigma", "1", "--alpha-v", "0.5", "--mask-unphysical"]


def _leftovers(d: Path) -> list[str]:
    return sorted(str(p.relative_to(d)) for p in d.rglob(f"{TEMPORARY_PREFIX}*"))


def _run_limited(argv: list[str], limit: int, cwd: Path) -> subprocess.CompletedProcess:
    def limited() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, resource.getrlimit(resource.RLIMIT_FSIZE)[1]))

    return subprocess.run([*TIPPE, *argv], cwd=cwd, preexec_fn=limited, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize(
    "name,argv,limit",
    [
        ("simulate", SIM, 40_000),  # estimate 2.7 kB; the file ~ 50 kB
        ("atlas", ATLAS, 12_000),  # estimate 10 kB; the file ~ 35 kB
        ("atlas --chunks --resume", [*ATLAS, "--chunks", "4", "--resume", "--no-progress"], 12_000),
        ("neutral", ["neutral", "--x", "q", "--y", "sigma", "--fr-inv", "0.3", "--alpha-v", "0.5"], 10_000),
    ],
)
def test_file_size_limit_names_file_and_cause(tmp_path, name, argv, limit):
    r = _run_limited([*argv, "-o", "out.nc"], limit, tmp_path)
    assert r.returncode == 2, r.stderr
    assert r.stderr.count("\n") == 1, r.stderr
    assert (
        f"error: cannot write 'out.nc': file size limit (ulimit -f) of {limit} bytes reached" in r.stderr
        and "nothing was written" in r.stderr
    ), r.stderr
    assert not (tmp_path / "out.nc").exists()
    assert _leftovers(tmp_path) == []


def test_output_above_the_limit_is_refused_before_computing(tmp_path):
    r = _run_limited([*SIM[:2], "1000", *SIM[3:], "-o", "out.nc"], 200_000, tmp_path)
    assert r.returncode == 2 and r.stderr.count("\n") == 1
    assert (
        "cannot write 'out.nc': the output needs about 2.48 MB, above the file size limit (ulimit -f) of "
        "200000 bytes; nothing was written"
    ) in r.stderr
    assert list(tmp_path.iterdir()) == []


def test_library_error_without_errno_is_diagnosed(tmp_path, monkeypatch):
    """HDF5 reports a full disk as RuntimeError('NetCDF: HDF error'); the diagnosis made at that
    moment (statvfs: 3 kB free) names the cause."""
    import stability.grids.netcdf as netcdf

    class Full:
        f_bavail, f_frsize, f_flag = 3, 1024, 0

    def failing(ds, path):
        Path(path).write_bytes(b"\x89HDF partial")
        monkeypatch.setattr(outputs.os, "statvfs", lambda d: Full())
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(netcdf, "_to_netcdf", failing)
    with pytest.raises(OutputWriteError) as err:
        stability.write_dataset(xr.Dataset({"x": ("t", np.arange(3.0))}), tmp_path / "a.nc")
    assert err.value.errno == errno.ENOSPC
    assert str(err.value) == (
        f"cannot write '{tmp_path / 'a.nc'}': no space left on the file system holding "
        f"'{tmp_path}' (3.07 kB free) (NetCDF: HDF error); nothing was written"
    )
    monkeypatch.undo()
    assert list(tmp_path.iterdir()) == []


def test_free_space_checked_before_computing(tmp_path, monkeypatch):
    class Small:
        f_bavail, f_frsize, f_flag = 3, 1024, 0

    monkeypatch.setattr(outputs.os, "statvfs", lambda d: Small())
    with pytest.raises(
        OutputWriteError,
        match=r"the output needs about 80 MB and the file system holding .* has "
        r"3.07 kB free; nothing was written",
    ):
        check_free_space(tmp_path / "a.nc", 80e6)
    check_free_space(tmp_path / "a.nc", 3000)


def test_a_close_error_never_replaces_the_first_error():
    class Handle:
        def close(self):
            raise RuntimeError("NetCDF: HDF error (while closing)")

    with pytest.raises(OSError, match="the first error"):
        with close_quietly(Handle()):
            raise OSError(errno.ENOSPC, "the first error")
    with pytest.raises(RuntimeError, match="while closing"):  # on success a failed close is a failed write
        with close_quietly(Handle()):
            pass


def test_failures_that_are_not_write_errors_pass_unchanged(tmp_path, monkeypatch):
    """Bad input and interruptions raised while writing are not turned into write errors."""
    import stability.grids.netcdf as netcdf

    for exc in (ValueError("bad value"), KeyboardInterrupt()):
        monkeypatch.setattr(netcdf, "_to_netcdf", lambda ds, path, exc=exc: (_ for _ in ()).throw(exc))
        with pytest.raises(type(exc)):
            stability.write_dataset(xr.Dataset({"x": ("t", np.arange(3.0))}), tmp_path / "a.nc")
    assert list(tmp_path.iterdir()) == []


def test_a_closed_stdout_after_the_write_is_not_an_error(tmp_path):
    """E10: ``tippe atlas ... | <reader that exits at once>``: the file is complete, so the
    command says so on stderr and exits 0 (it used to say "[Errno 32] Broken pipe", exit 2).
    Reference for "complete": the file read back equals the atlas computed in this process."""
    proc = subprocess.Popen(
        [*TIPPE, *ATLAS, "-o", "p.nc"], cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    proc.stdout.close()  # the reader goes away before the report is printed
    err = proc.stderr.read()
    proc.wait(timeout=300)
    assert proc.returncode == 0, err
    assert "wrote 'p.nc'" in err and "could not be printed" in err and len(err.strip().splitlines()) == 1
    with xr.open_dataset(tmp_path / "p.nc") as ds:
        got = ds.load()
    ref = stability.atlas(
        "sliding",
        q=np.linspace(-0.6, 0.6, 31),
        fr_inv=np.linspace(0, 1, 4),
        sigma=1.0,
        alpha_v=0.5,
        mask_unphysical=True,
    )
    xr.testing.assert_identical(got.drop_attrs(), ref.drop_attrs())
    assert _leftovers(tmp_path) == []
