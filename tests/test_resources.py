"""Memory estimates before allocating (stability.resources), issue 13 item 10 and issue 15 item 4.

References:

* the refusals: a request sized at 10x the limit set by ``TIPPE_MEMORY_LIMIT`` is refused before
  anything is allocated (the process's peak stays under the limit), and the message names the
  estimate, the parameter and a way out;
* the limit: ``MemAvailable`` read from /proc/meminfo by the test itself;
* the estimates: the bytes of the datasets the calls return (``nbytes``).

The peak estimates (bytes per point times points) are not pinned to a measured peak: they only
have to refuse a request far above the memory (docs/hard_cases.md, "Memory").
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import stability
from stability import resources
from stability.cli import main
from stability.errors import ResourceError
from stability.grids.ranges import parse_values
from stability.linear.neutral_curves import neutral_curve

# --- the limit and the refusals ------------------------------------------------------------------


@pytest.mark.skipif(not os.path.exists("/proc/meminfo"), reason="Linux /proc/meminfo")
def test_limit_is_a_fraction_of_mem_available(monkeypatch):
    monkeypatch.delenv(resources.ENV_LIMIT, raising=False)
    with open("/proc/meminfo") as f:
        avail = next(float(ln.split()[1]) * 1024 for ln in f if ln.startswith("MemAvailable:"))
    limit, source = resources.memory_limit()
    # 80 % of MemAvailable (which moves by a few % between the two reads on a shared machine)
    assert limit <= resources.HEADROOM * avail * 1.05
    assert "80%" in source


@pytest.mark.parametrize("text,value", [("2e9", 2e9), ("500M", 500e6), ("8G", 8e9), ("1GiB", 2.0**30), ("123", 123.0)])
def test_env_limit_syntax(monkeypatch, text, value):
    monkeypatch.setenv(resources.ENV_LIMIT, text)
    assert resources.memory_limit() == (value, f"the limit {resources.ENV_LIMIT}")


def test_env_limit_garbage_is_named(monkeypatch):
    monkeypatch.setenv(resources.ENV_LIMIT, "lots")
    with pytest.raises(ValueError, match="TIPPE_MEMORY_LIMIT"):
        resources.memory_limit()


# --- the estimates against the datasets the calls return ----------------------------------------


SIMULATE_START = dict(t_end=20, dt=0.1, omega=[0.02, 0, 1], k=[0.05, 0, 1], q=-0.1, fr_inv=0.3, sigma=1.5)


@pytest.mark.parametrize("model", sorted(resources.SIMULATE_FILE_BYTES_PER_TIME))
def test_simulate_estimates_against_the_returned_dataset(model):
    """Reference: the dataset simulate returns, its bytes counted by numpy (``nbytes``). The
    stored bytes per output time are exact (every variable along ``time`` counted once: a count
    of float64 values, no tolerance); the peak estimate holds at least the whole dataset (the
    ``axis`` coordinate too) and is the 1.6 x the stored values its comment states (the
    integrator's output array and the derived quantities' temporaries, not measurable
    deterministically: the removed VmHWM test)."""
    extra = {"alpha_v": 0.5} if model == "sliding" else {}
    ds = stability.simulate(model, **SIMULATE_START, **extra)
    n = ds.sizes["time"]
    along_time = sum(v.nbytes for v in ds.variables.values() if "time" in v.dims)
    assert resources.simulate_file_bytes(model, n) == along_time
    assert ds.nbytes <= resources.simulate_bytes(model, n) <= 1.6 * ds.nbytes


@pytest.mark.parametrize("model,extra", [("sliding", {"alpha_v": 0.5}), ("rolling", {}), ("fixed_pivot", {})])
def test_atlas_estimates_against_the_returned_dataset(model, extra):
    """Reference: the atlas returned (``nbytes`` of its variables over the grid, by numpy). The
    stored bytes per point and mode are exact (a count of float64 and int8 values, no
    tolerance); the peak estimate holds at least the whole dataset, coordinates included. Its
    excess (one block's temporaries) is not pinned: only measurable, not derivable."""
    ds = stability.atlas(
        model,
        q=np.linspace(-0.3, 0.3, 7),
        fr_inv=[0.0, 0.3],
        sigma=np.linspace(1.0, 1.6, 5),
        mask_unphysical=True,
        **extra,
    )
    dims = set(ds["stability"].dims)
    n_points, n_modes = 7 * 2 * 5, ds.sizes["mode"]
    over_grid = sum(v.nbytes for v in ds.variables.values() if dims <= set(v.dims))
    assert resources.atlas_file_bytes(n_modes, n_points) == over_grid
    assert ds.nbytes <= resources.atlas_bytes(n_modes, n_points, 2**16)


LIMIT = 50e6


@pytest.mark.parametrize(
    "call,fragments",
    [
        (
            lambda: stability.simulate(
                "sliding",
                t_end=2e5,
                dt=0.1,
                omega=[0.02, 0, 1],
                k=[0.05, 0, 1],
                q=-0.1,
                fr_inv=0.3,
                sigma=1.5,
                alpha_v=0.5,
            ),
            ["2000001 output times", "t_end", "dt"],
        ),
        (
            lambda: stability.atlas(
                "sliding", q=np.linspace(-0.3, 0.3, 3000), sigma=np.linspace(1.0, 1.6, 3000), fr_inv=0.3, alpha_v=0.5
            ),
            ["9000000", "chunk"],
        ),
        (
            lambda: stability.thresholds("sigma", q=-0.1, fr_inv=0.3, alpha_v=0.5, samples=10**6),
            ["1000000 samples", "samples"],
        ),
        (
            lambda: neutral_curve("sliding", "q", "sigma", fixed={"fr_inv": 0.3, "alpha_v": 0.5}, grid=(2000, 2000)),
            ["2000 x 2000", "grid"],
        ),
        (
            lambda: stability.class_atlas(q=np.linspace(-0.3, 0.3, 2000), sigma=np.linspace(1.0, 1.6, 2000)),
            ["4000000 grid points"],
        ),
        (lambda: parse_values("0:1:100000000", name="q"), ["q = '0:1:100000000' (100000000 values)", "fewer points"]),
    ],
    ids=["simulate", "atlas", "thresholds", "neutral_curve", "class_atlas", "parse_values"],
)
def test_requests_above_the_limit_are_refused_with_estimate_and_way_out(monkeypatch, call, fragments):
    """Each entry point refuses at once (before allocating: measured below for simulate) with the
    estimate, the limit's source and the parameter."""
    monkeypatch.setenv(resources.ENV_LIMIT, str(LIMIT))
    with pytest.raises(ResourceError) as info:
        call()
    text = str(info.value)
    assert "would need about" in text and "TIPPE_MEMORY_LIMIT" in text
    for f in fragments:
        assert f in text, text
    assert isinstance(info.value, ValueError)


@pytest.mark.skipif(not os.path.exists("/proc/self/clear_refs"), reason="Linux peak-RSS reset")
def test_refusal_happens_before_allocating():
    """A simulate request of ~20 GB under a 200 MB limit: the peak resident memory grows by less
    than 50 MB during the refused call (the peak reset after the imports, as above)."""
    code = textwrap.dedent("""
        import stability
        from stability.errors import ResourceError
        from stability.nonlinear import get_nonlinear_model

        simulate = stability.simulate  # the lazy facade imports the run's modules here, before the reset
        get_nonlinear_model("sliding")

        def status(key):
            with open("/proc/self/status") as f:
                return float(next(ln for ln in f if ln.startswith(key)).split()[1]) * 1024.0

        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        base = status("VmRSS")
        try:
            simulate("sliding", t_end=1e7, dt=0.2, omega=[0.02, 0, 1], k=[0.05, 0, 1], q=-0.1,
                               fr_inv=0.3, sigma=1.5, alpha_v=0.5)
        except ResourceError:
            print(status("VmHWM") - base)
    """)
    env = dict(os.environ, TIPPE_MEMORY_LIMIT="200M")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert float(r.stdout.split()[-1]) < 50e6  # no 20 GB array, not even a part of it


def test_cli_refusal_exit_2_one_line(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv(resources.ENV_LIMIT, "100M")
    status = main(
        [
            "simulate",
            "--t-end",
            "1e6",
            "--omega",
            "0.02,0,1",
            "--k",
            "0.05,0,1",
            "--q",
            "-0.1",
            "--fr-inv",
            "0.3",
            "--sigma",
            "1.5",
            "--alpha-v",
            "0.5",
            "-o",
            str(tmp_path / "s.nc"),
        ]
    )
    err = capsys.readouterr().err
    assert status == 2
    assert len(err.strip().splitlines()) == 1 and "would need about" in err and "dt" in err, err
    assert list(tmp_path.iterdir()) == []


# --- issue 15 item 4: tippe simulate says what it wrote and warns before a large output -----------


def test_simulate_says_what_it_wrote(tmp_path, capsys):
    """The report against the file itself: its size on disk, its first and last time, its
    number of output times."""
    import xarray as xr

    out = tmp_path / "s.nc"
    status = main(
        [
            "simulate",
            "--t-end",
            "5",
            "--omega",
            "0.02,0,1",
            "--k",
            "0.05,0,1",
            "--q",
            "-0.1",
            "--fr-inv",
            "0.3",
            "--sigma",
            "1.5",
            "--alpha-v",
            "0.5",
            "-o",
            str(out),
        ]
    )
    assert status == 0
    text = capsys.readouterr()
    assert text.err == ""
    with xr.open_dataset(out) as ds:
        n = ds.sizes["time"]
        t0, t1 = float(ds.time[0]), float(ds.time[-1])
    assert text.out.startswith(f"wrote {out} (")
    assert resources.format_bytes(out.stat().st_size) in text.out
    assert f"t = {t0:g} ... {t1:g} ({n} output times" in text.out
    assert "steps" in text.out


def test_simulate_warns_before_a_large_output(tmp_path, monkeypatch, capsys):
    """Above WARN_BYTES the warning comes before the run (checked: the run is stopped at once by
    a failing simulate, and the warning is already on stderr)."""
    import stability.commands.simulate as cmd
    import stability.nonlinear.runs as runs

    monkeypatch.setattr(cmd, "WARN_BYTES", 1e5)

    def boom(*a, **k):
        raise RuntimeError("not run")

    monkeypatch.setattr(runs, "simulate", boom)
    status = main(
        [
            "simulate",
            "--t-end",
            "100",
            "--dt",
            "0.1",
            "--omega",
            "0.02,0,1",
            "--k",
            "0.05,0,1",
            "--q",
            "-0.1",
            "--fr-inv",
            "0.3",
            "--sigma",
            "1.5",
            "--alpha-v",
            "0.5",
            "-o",
            str(tmp_path / "s.nc"),
        ]
    )
    err = capsys.readouterr().err
    assert status == 1
    assert "warning: the output will be about" in err and "1001 output times" in err
    assert err.index("warning") < err.index("not run")
