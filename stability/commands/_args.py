"""Shared argument parsing for the ``tippe`` subcommands: parameter flags (their values are read by
:func:`stability.grids.ranges.parse_values`, which recipes use too)."""

from __future__ import annotations

import argparse

from ..grids.ranges import parse_values
from ..parameters import DEFAULT_MU

__all__ = ["add_parameter_flags", "parameter_values", "FLAGS"]


#: parameter name -> CLI flag
FLAGS = {"q": "--q", "fr_inv": "--fr-inv", "sigma": "--sigma", "alpha_v": "--alpha-v", "mu": "--mu"}


def add_parameter_flags(p: argparse.ArgumentParser, names: tuple[str, ...], *, required: tuple[str, ...]) -> None:
    """Add ``--q``, ``--fr-inv``, ... flags taking a number, a list or a range."""
    for name in names:
        p.add_argument(FLAGS[name], dest=name, metavar="VALUES", required=name in required,
                       default=DEFAULT_MU if name == "mu" else None,
                       help=f"{name}: a number, a comma list, or start:stop:num")


def parameter_values(args: argparse.Namespace, names: tuple[str, ...]) -> dict[str, object]:
    """Parsed values of the parameter flags that were given."""
    out: dict[str, object] = {}
    for name in names:
        v = getattr(args, name, None)
        if v is None:
            continue
        out[name] = parse_values(v, name=FLAGS[name]) if isinstance(v, str) else v
    return out
