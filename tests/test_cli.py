"""The ``tippe`` command line: atlas writing, errors as one line with exit status 2.

Reference for the values: the library call with the same arguments (the CLI is a thin layer;
the numbers themselves are checked against mpmath in test_spectra_reference).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import stability
from stability.cli import main
from stability.grids.ranges import parse_values


def test_parse_values():
    assert np.array_equal(parse_values("-0.6:0.6:241"), np.linspace(-0.6, 0.6, 241))
    assert np.array_equal(parse_values("0,0.1,0.3"), [0, 0.1, 0.3])
    assert parse_values("1") == 1.0
    with pytest.raises(ValueError, match="--q = 'a:b'"):
        parse_values("a:b", name="--q")


def test_atlas_command(tmp_path, capsys):
    out = tmp_path / "atlas.nc"
    png = tmp_path / "atlas.png"
    rc = main(["atlas", "--model", "sliding", "--q", "-0.6:0.6:25", "--fr-inv", "0,0.1,0.3", "--sigma", "1",
               "--alpha-v", "0.5", "--mask-unphysical", "-o", str(out), "--plot", str(png)])
    assert rc == 0
    assert "wrote" in capsys.readouterr().out
    ds = stability.open_atlas(out)
    ref = stability.atlas("sliding", q=np.linspace(-0.6, 0.6, 25), fr_inv=[0, 0.1, 0.3], sigma=1.0,
                          alpha_v=0.5, mask_unphysical=True)
    xr.testing.assert_allclose(ds.drop_attrs(), ref.drop_attrs(), rtol=0, atol=0)
    assert png.stat().st_size > 10_000


def test_refused_grid_leaves_no_file(tmp_path, capsys):
    out = tmp_path / "atlas.nc"
    rc = main(["atlas", "--q", "-0.6:0.6:25", "--fr-inv", "0.1", "--sigma", "1", "--alpha-v", "0.5",
               "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.count("\n") == 1 and "sigma = 1 is outside the physical domain" in err
    assert not out.exists()


def test_unwritable_output_fails_before_computing(tmp_path, capsys):
    rc = main(["atlas", "--q", "0.1", "--fr-inv", "0.1", "--sigma", "1", "--alpha-v", "0.5",
               "-o", str(tmp_path / "no" / "such" / "dir.nc")])
    assert rc == 2 and "does not exist" in capsys.readouterr().err


def test_python_m_stability_no_traceback(tmp_path):
    r = subprocess.run([sys.executable, "-m", "stability", "atlas", "--q", "0.1", "--fr-inv", "nan",
                        "--sigma", "1", "--alpha-v", "0.5", "-o", str(tmp_path / "a.nc")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and "fr_inv = nan is not finite" in r.stderr
