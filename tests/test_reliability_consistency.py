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
    _run(
        "import numpy as np, xarray as xr; xr.Dataset({'a': ('x', np.zeros(2))}, "
        f"attrs={{'tippe_stability_product': 'simulate'}}).to_netcdf({str(path)!r})",
        tmp_path,
    )
    for first, second in (("stability", "xarray as xr"), ("xarray as xr", "stability")):
        out = _run(
            f"import {first}; import {second}; import xarray as xr; "
            f"print(xr.open_dataset({str(path)!r}).tippe.product)",
            tmp_path,
        )
        assert out.strip() == "simulate"


def test_one_name_for_an_ordinary_point():
    """Item 13: neutral_curve and steady_branch both call an ordinary point "regular" (the
    engine's name), never ""."""
    import stability

    nc = stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=0.5))
    br = stability.steady_branch(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5)
    for ds in (nc, br):
        kinds = set(ds.kind.values.astype(str))
        assert "regular" in kinds and "" not in kinds


def test_cli_mistyped_option_and_messages_in_cli_names(capsys):
    """Item 17: a mistyped option gets 'did you mean' and the subcommand's own help (exit 2),
    before any complaint about required options; library messages come out with the CLI's
    names (--alpha-v, not alpha_v; --fr-inv, not fixed). Reference: the flags argparse
    registered for the subcommand."""
    import pytest

    from stability.cli import main

    with pytest.raises(SystemExit) as stop:
        main(["final", "--alpha_v", "0.5"])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert "did you mean --alpha-v" in err and "usage: tippe final" in err and "arguments are required" not in err
    assert (
        main(
            ["final", "--q", "0", "--sigma", "0.8", "--fr-inv", "0.3", "--alpha-v", "-1", "--omega=0,0,1", "--k=0,0,1"]
        )
        == 2
    )
    err = capsys.readouterr().err
    assert "--alpha-v = -1 is outside the physical domain: --alpha-v >= 0" in err and "alpha_v" not in err
    assert main(["neutral", "--x", "q", "--y", "sigma", "--alpha-v", "0.5"]) == 2
    err = capsys.readouterr().err
    assert "give --fr-inv" in err and "fixed" not in err


def test_atlas_plot_of_a_2d_grid_is_a_map():
    """Item 16: --plot of a 2-D grid with many values of the second dimension draws the map
    (an image of the grid, one colour per point), not a line per value with a legend for each;
    a few values still give lines. Reference: the artists of the figure."""
    import numpy as np

    import stability
    from stability.commands.atlas import MAX_LINES, plot_figure

    ds = stability.atlas(
        "sliding", q=np.linspace(-0.3, 0.3, 21), sigma=np.linspace(0.5, 1.5, MAX_LINES + 5), fr_inv=0.3, alpha_v=0.5
    )
    fig = plot_figure(ds, "q")
    assert len(fig.axes[0].lines) < MAX_LINES and (fig.axes[0].images or fig.axes[0].collections)
    few = plot_figure(ds.isel(sigma=slice(0, 3)), "q")
    assert len(few.axes[0].lines) >= 3


def test_a_signal_after_the_last_check_is_reported_not_fatal(tmp_path):
    """Item 10: a SIGTERM that arrives once the command has ended (after 'wrote c.nc') either
    is reported as the others are (exit 130, one line: the flag was set before the hold), or,
    during the interpreter's shutdown (which restores the default handlers: exit 143 and no
    line before), waits behind the block and the process ends with its own status."""
    code = (
        "import os, signal, time; from stability import interrupts; interrupts.install('tippe x'); "
        "os.kill(os.getpid(), signal.SIGTERM); time.sleep(0.05); print(interrupts.hold_until_exit())"
    )
    assert _run(code, tmp_path).strip() == "True"
    code = (
        "import os, signal, time; from stability import interrupts; interrupts.install('tippe x'); "
        "print(interrupts.hold_until_exit()); os.kill(os.getpid(), signal.SIGTERM); time.sleep(0.05); "
        "print('alive')"
    )
    assert _run(code, tmp_path).split() == ["False", "alive"]


_DRAW = """
import sys, numpy as np, matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from stability.plotting import save_figure
eps = float(sys.argv[2])
x = np.linspace(0.0, 1.0, 37)
y = np.sin(3.0 * x) * (1.0 + eps)
fig, ax = plt.subplots(figsize=(3, 2), dpi=80)
ax.plot(x, y)
ax.pcolormesh(x, x, np.outer(y, y), shading="auto")
ax.set_xlim(0, 1); ax.set_ylim(-1.2, 1.2)
save_figure(fig, sys.argv[1])
"""


def test_figures_are_the_same_bytes_in_separate_processes(tmp_path):
    """Item 15: a figure drawn twice in separate processes is the same bytes, and so is one
    whose data differ by a few ulps (what another machine's compiled code gives): save_figure
    rounds the drawn data to 2^-30 of the axis span and colour range and writes no version
    metadata. Reference: the bytes of the files."""
    script = tmp_path / "draw.py"
    script.write_text(_DRAW)
    out = []
    for name, eps in (("a.png", "0"), ("b.png", "0"), ("c.png", "4e-16")):
        subprocess.run([sys.executable, str(script), str(tmp_path / name), eps], check=True, cwd=tmp_path)
        out.append((tmp_path / name).read_bytes())
    assert out[0] == out[1] == out[2]
    assert b"Matplotlib version" not in out[0]
