"""Issue 20, consistency a newcomer trips over: the accessor after ``import stability``,
one convention for regular points, the README's tables, deterministic figures, CLI names."""

import subprocess
import sys


def _run(code: str, cwd) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=cwd).stdout


def test_accessor_registered_whatever_the_import_order(tmp_path):
    """Item 12: docs/datasets.md says importing the package registers ds.tippe. Reference: a
    file written by xarray alone, opened by xarray alone, in a fresh interpreter, with
    ``import stability`` before or after ``import xarray``."""
    path = tmp_path / "run.nc"
    _run("import numpy as np, xarray as xr; xr.Dataset({'a': ('x', np.zeros(2))}, "
         f"attrs={{'tippe_stability_product': 'simulate'}}).to_netcdf({str(path)!r})", tmp_path)
    for first, second in (("stability", "xarray as xr"), ("xarray as xr", "stability")):
        out = _run(f"import {first}; import {second}; import xarray as xr; "
                   f"print(xr.open_dataset({str(path)!r}).tippe.product)", tmp_path)
        assert out.strip() == "simulate"
