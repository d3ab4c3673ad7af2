"""The ``tippe`` command line: atlas writing, errors as one line with exit status 2.

Reference for the values: the library call with the same arguments (the CLI is a thin layer;
the numbers themselves are checked against mpmath in test_spectra_reference).
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import subprocess
import sys
from pathlib import Path

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
    rc = main(
        [
            "atlas",
            "--model",
            "sliding",
            "--q",
            "-0.6:0.6:25",
            "--fr-inv",
            "0,0.1,0.3",
            "--sigma",
            "1",
            "--alpha-v",
            "0.5",
            "--mask-unphysical",
            "-o",
            str(out),
            "--plot",
            str(png),
        ]
    )
    assert rc == 0
    assert "wrote" in capsys.readouterr().out
    ds = stability.open_atlas(out)
    ref = stability.atlas(
        "sliding", q=np.linspace(-0.6, 0.6, 25), fr_inv=[0, 0.1, 0.3], sigma=1.0, alpha_v=0.5, mask_unphysical=True
    )
    xr.testing.assert_allclose(ds.drop_attrs(), ref.drop_attrs(), rtol=0, atol=0)
    assert png.stat().st_size > 10_000


def test_refused_grid_leaves_no_file(tmp_path, capsys):
    out = tmp_path / "atlas.nc"
    rc = main(["atlas", "--q", "-0.6:0.6:25", "--fr-inv", "0.1", "--sigma", "1", "--alpha-v", "0.5", "-o", str(out)])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.count("\n") == 1 and "sigma = 1 is outside the physical domain" in err
    assert not out.exists()


def test_unwritable_output_fails_before_computing(tmp_path, capsys):
    rc = main(
        [
            "atlas",
            "--q",
            "0.1",
            "--fr-inv",
            "0.1",
            "--sigma",
            "1",
            "--alpha-v",
            "0.5",
            "-o",
            str(tmp_path / "no" / "such" / "dir.nc"),
        ]
    )
    assert rc == 2 and "does not exist" in capsys.readouterr().err


def test_python_m_stability_no_traceback(tmp_path):
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "stability",
            "atlas",
            "--q",
            "0.1",
            "--fr-inv",
            "nan",
            "--sigma",
            "1",
            "--alpha-v",
            "0.5",
            "-o",
            str(tmp_path / "a.nc"),
        ],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and "--fr-inv = nan is not finite" in r.stderr


# ------------------------------------------------------------------------------------------
# library messages name keywords; the command line shows its flags (stability.cli.KEYWORD_FLAGS)
# ------------------------------------------------------------------------------------------
_FLAG = re.compile(r"(?<![\w-])--[a-z]")


def _library_messages(tmp_path):
    """The library's messages that ask for an option, each raised by a library call."""
    import stability.recipes as recipes
    from stability.grids.cluster import dask_client

    existing = tmp_path / "a.nc"
    existing.write_text("")
    ds = stability.atlas("fixed_pivot", q=0.1, fr_inv=0.1, sigma=1.0)
    cases = [
        (FileExistsError, lambda: stability.write_dataset(ds, existing), "pass overwrite=True to replace it"),
        (
            stability.DomainError,
            lambda: stability.atlas("sliding", q=[0.1, 0.9], fr_inv=0.0, sigma=1.0, alpha_v=0.5),
            "pass mask_unphysical=True to compute the rest",
        ),
        (
            ValueError,
            lambda: dask_client(workers=1, scheduler="tcp://x:1").__enter__(),
            "pass workers=N for a local cluster or scheduler=ADDRESS for an existing one, not both",
        ),
    ]
    recipe = tmp_path / "r.toml"
    recipe.write_text(
        'title = "x"\nkind = "lines"\nx = "q"\n[grid]\nq = "0:0.2:3"\nfr_inv = 0.1\nsigma = 1.0\nalpha_v = 0.5\n'
    )
    xr.Dataset({"x": ("t", np.arange(3.0))}).to_netcdf(tmp_path / "r.nc")  # a file no recipe wrote
    cases.append(
        (
            stability.errors.RecipeError,
            lambda: recipes.compute(recipes.load_recipe(recipe)),
            "remove it or pass force=True to replace it",
        )
    )
    return cases


def test_library_messages_name_keywords_not_flags(tmp_path):
    """Each message names the keyword a Python caller passes, and no flag of ``tippe``."""
    for exc, call, fragment in _library_messages(tmp_path):
        with pytest.raises(exc) as info:
            call()
        msg = str(info.value)
        assert fragment in msg and not _FLAG.search(msg), msg


@pytest.mark.parametrize(
    "argv, fragment",
    [
        (
            ["atlas", "--q", "0.1,0.9", "--fr-inv", "0", "--sigma", "1", "--alpha-v", "0.5"],
            "pass mask_unphysical=True (--mask-unphysical) to compute the rest",
        ),
        (
            [
                "atlas",
                "--q",
                "0.1,0.2",
                "--fr-inv",
                "0",
                "--sigma",
                "1",
                "--alpha-v",
                "0.5",
                "--chunks",
                "1",
                "--workers",
                "1",
                "--scheduler",
                "tcp://x:1",
            ],
            "pass workers=N (--workers) for a local cluster or scheduler=ADDRESS (--scheduler) for an existing one",
        ),
    ],
)
def test_command_line_shows_the_flags(argv, fragment, tmp_path, capsys):
    """The same messages through ``tippe``: the keyword followed by the command's flag, on the one
    error line (--overwrite and --force: tests/test_files.py)."""
    assert main([*argv, "-o", str(tmp_path / "a.nc")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and fragment in err


def test_keyword_flag_table():
    """Every entry of the table is a flag of some command that sets exactly that keyword (its
    argparse ``dest``); a flag is added only where the command has it, and never twice."""
    from stability.cli import KEYWORD_FLAGS, build_parser, render_message

    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    dests = {s: a.dest for p in sub.choices.values() for a in p._actions for s in a.option_strings}
    for keyword, flag in KEYWORD_FLAGS.items():
        assert dests.get(flag) == keyword, (keyword, flag)
    assert render_message("pass overwrite=True to replace it") == "pass overwrite=True (--overwrite) to replace it"
    assert render_message("pass overwrite=True to replace it", {"--force"}) == "pass overwrite=True to replace it"
    already = "use resume=True (--resume) to keep them"
    assert render_message(already) == already
    assert render_message("workers = 0 is outside the allowed range") == "workers = 0 is outside the allowed range"


@pytest.mark.parametrize(
    "argv",
    [
        ["threshold", "q", "--q", "0.1", "--fr-inv", "0.3", "--sigma", "1", "--alpha-v", "0.5"],
        ["neutral", "--x", "q", "--y", "sigma", "--q", "0.1", "--fr-inv", "0", "--alpha-v", "0.5"],
    ],
)
def test_a_searched_or_traced_parameter_given_a_value(argv, capsys):
    """The value of the parameter that is searched (threshold) or traced (neutral) is refused by
    the library (the parameter cannot be varied and fixed at once); the one error line names its
    flag, exit status 2 (bad input)."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--q is varied and cannot also be given a value" in err


#: library messages that still name a flag, with the reason
_FLAGS_ALLOWED = {
    "--scheduler-file": "the option of dask's own command (`dask scheduler --scheduler-file`), not of tippe",
    "--resume": "stability/grids/chunked.py's ChunkError; tests/test_faults.py asserts the message as it is",
}


def test_no_library_message_names_a_flag():
    """No string of the library outside the command line (stability.commands, stability.cli)
    names a ``--flag``, docstrings aside (they may tell what the command line does), except
    those of _FLAGS_ALLOWED."""
    import ast
    import pkgutil

    found = []
    for info in pkgutil.walk_packages(stability.__path__, "stability."):
        if info.name.startswith(("stability.commands", "stability.cli", "stability.__main__")):
            continue
        path = importlib.util.find_spec(info.name).origin
        tree = ast.parse(Path(path).read_text(), path)
        docstrings = {
            id(n.body[0].value)
            for n in ast.walk(tree)
            if isinstance(n, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
            and n.body
            and isinstance(n.body[0], ast.Expr)
            and isinstance(n.body[0].value, ast.Constant)
        }
        for const in ast.walk(tree):
            if isinstance(const, ast.Constant) and isinstance(const.value, str) and id(const) not in docstrings:
                for flag in re.findall(r"(?<![\w-])--[a-z][a-z-]*", const.value):
                    if flag not in _FLAGS_ALLOWED:
                        found.append(f"{info.name}:{const.lineno}: {flag}")
    assert not found, "library strings naming a flag of tippe:\n" + "\n".join(found)


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    from stability.cli import build_parser

    parser = build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(action.choices)


def test_every_option_of_every_subcommand_has_help():
    """Issue 15 item 5: every option has help text, every --model names its default in the help,
    and every subcommand's description names its model (the default one, or "sliding model only")."""
    subs = _subparsers()
    assert set(subs) == set(__import__("stability.cli", fromlist=["COMMANDS"]).COMMANDS)
    missing = []
    for name, sub in subs.items():
        text = sub.format_help()
        for action in sub._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            if not (action.help or "").strip() or action.help is argparse.SUPPRESS:
                missing.append(f"{name} {'/'.join(action.option_strings) or action.dest}")
            if action.option_strings == ["--model"]:
                assert f"(default: {action.default})" in " ".join(text.split()), name
                assert all(c in " ".join(text.split()) for c in action.choices), name
        if any(a.option_strings == ["--model"] for a in sub._actions) or name in ("steady", "final"):
            assert re.search(r"[Dd]efault model: \w+|[Ss]liding model only", " ".join(sub.description.split())), name
    assert not missing, f"options without help: {', '.join(missing)}"


def test_simulate_help_matches_the_library():
    """The choices and defaults `tippe simulate` shows are the ones stability.simulate uses
    (they are written in the command so that --help imports no integrator)."""
    import inspect

    from stability.nonlinear.integrators import COMPILED_METHODS, SCIPY_METHODS
    from stability.nonlinear.runs import simulate

    sub = _subparsers()["simulate"]
    by_dest = {a.dest: a for a in sub._actions}
    assert tuple(by_dest["method"].choices) == ("auto", *COMPILED_METHODS, *SCIPY_METHODS)
    for name, par in inspect.signature(simulate).parameters.items():
        if name == "progress":  # the command decides by the terminal (--progress/--no-progress)
            continue
        if name in by_dest and par.default is not inspect.Parameter.empty and not by_dest[name].required:
            if by_dest[name].default is None and par.default is not None:
                # unset on the command line (a top in SI units may give it): the help names the default
                assert f"default {par.default}" in by_dest[name].help, name
                continue
            assert by_dest[name].default == par.default, name
