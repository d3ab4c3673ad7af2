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


def test_one_name_for_an_ordinary_point():
    """Item 13: neutral_curve and steady_branch both call an ordinary point "regular" (the
    engine's name), never ""."""
    import continuation

    nc = continuation.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=0.5))
    br = continuation.steady_branch(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    for ds in (nc, br):
        kinds = set(ds.kind.values.astype(str))
        assert "regular" in kinds and "" not in kinds
