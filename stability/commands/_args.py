"""Shared argument parsing for the ``tippe`` subcommands: parameter flags and ranges."""

from __future__ import annotations

import argparse

import numpy as np

from ..parameters import DEFAULT_MU

__all__ = ["parse_values", "add_parameter_flags", "parameter_values", "FLAGS"]

#: parameter name -> CLI flag
FLAGS = {"q": "--q", "fr_inv": "--fr-inv", "sigma": "--sigma", "alpha_v": "--alpha-v", "mu": "--mu"}


def parse_values(text: str, *, name: str = "value") -> float | np.ndarray:
    """Parse ``start:stop:num`` (``numpy.linspace``), a comma list, or one number.

    Raises
    ------
    ValueError
        With the flag name and the offending text.
    """
    t = text.strip()
    try:
        if ":" in t:
            parts = t.split(":")
            if len(parts) != 3:
                raise ValueError
            start, stop = float(parts[0]), float(parts[1])
            num = int(parts[2])
            if num < 1:
                raise ValueError(f"{name} = {text!r}: the number of points must be >= 1")
            return np.linspace(start, stop, num)
        if "," in t:
            vals = [float(v) for v in t.split(",") if v.strip()]
            if not vals:
                raise ValueError(f"{name} = {text!r} is empty")
            return np.array(vals)
        return float(t)
    except ValueError as exc:
        if str(exc):
            raise
        raise ValueError(f"{name} = {text!r} is not a number, a comma list or start:stop:num") from None


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
