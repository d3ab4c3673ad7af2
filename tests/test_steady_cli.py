"""``tippe steady`` and ``tippe final``: output, files, one-line errors.

Reference: the library calls with the same arguments (the commands are thin layers; the numbers
are checked in tests/test_steady_*.py)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import stability
from stability.cli import main

TOP = ["--q", "-0.1", "--sigma", "1", "--fr-inv", "0.3", "--alpha-v", "0.5"]
PAPER_STATE = ["--omega", "0.0219,0.0047,-0.9997", "--k", "0.0676,0.0676,0.9954", "--velocity", "0.0935,0.0384"]


def test_steady_prints_the_states_and_writes_them(tmp_path, capsys):
    out = tmp_path / "states.nc"
    assert main(["steady", *TOP, "--jellett", "-0.900118587313518", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "166.018431" in text and text.count("unstable") == 2
    with xr.open_dataset(out) as ds:
        ref = stability.steady_states(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, jellett=-0.900118587313518)
        assert ds.attrs["tippe_stability_product"] == "steady_states"
        assert np.array_equal(ds.tilt.values, ref.tilt.values)


def test_steady_branch(tmp_path, capsys):
    out = tmp_path / "branch.nc"
    assert (
        main(
            [
                "steady",
                "--q",
                "-0.2",
                "--sigma",
                "1.3",
                "--fr-inv",
                "0.5",
                "--alpha-v",
                "0.5",
                "--branch",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    text = capsys.readouterr().out
    assert "fold" in text and "98.904667" in text and "inverted spin" in text
    with xr.open_dataset(out) as ds:
        assert ds.attrs["tippe_stability_product"] == "steady_branch"


def test_final_prints_the_prediction(tmp_path, capsys):
    out = tmp_path / "final.nc"
    assert main(["final", *PAPER_STATE, *TOP, "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "final state: tilted, tilt 166.018431 deg (method: jellett)" in text
    with xr.open_dataset(out) as ds:
        assert ds.attrs["method"] == "jellett" and float(ds.tilt) == pytest.approx(166.018431, abs=1e-6)


def test_final_without_simulation(capsys):
    assert (
        main(
            [
                "final",
                "--omega",
                "0,0,1",
                "--k",
                "0.17,0,0.985",
                "--q",
                "0",
                "--sigma",
                "0.8",
                "--fr-inv",
                "0.3",
                "--alpha-v",
                "0.5",
                "--no-simulation",
            ]
        )
        == 0
    )
    assert "final state: undecided" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv,fragment",
    [
        (["final", "--omega", "0,0,1", "--k", "0,0,1", *TOP[:-1], "0"], "--alpha-v = 0 is outside the allowed range"),
        (["final", "--omega", "0,0,1", "--k", "0,0,1.2", *TOP], "k is the unit symmetry axis"),
        (["final", "--omega", "0,0", "--k", "0,0,1", *TOP], "--omega must be a vector of 3 components"),
        (["final", "--omega", "a,b,c", "--k", "0,0,1", *TOP], "is not a comma list of numbers"),
        (
            ["steady", "--q", "0.9", "--sigma", "1", "--fr-inv", "0.3", "--alpha-v", "0.5"],
            "q = 0.9 is outside the physical domain",
        ),
        (["steady", *TOP, "--branch", "--jellett", "1"], "--jellett is not used with --branch"),
        (["steady", *TOP, "--max-step", "0.1"], "only used with --branch"),
        (["steady", "--q", "-0.1"], "--sigma, --fr-inv, --alpha-v required (or a top in SI units"),
    ],
)
def test_errors_are_one_line(argv, fragment, capsys):
    if "arguments are required" in fragment or "comma list" in fragment:  # argparse's own errors exit at parsing
        with pytest.raises(SystemExit) as exc:
            main(argv)
        assert exc.value.code == 2
    else:
        assert main(argv) == 2
    err = capsys.readouterr().err
    assert fragment in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_existing_output_is_refused_before_computing(tmp_path, capsys):
    out = tmp_path / "x.nc"
    out.write_text("keep")
    assert main(["steady", *TOP, "-o", str(out)]) == 2
    assert "exists" in capsys.readouterr().err and out.read_text() == "keep"
