"""Shared argument parsing for the ``tippe`` subcommands: parameter flags and ranges."""

from __future__ import annotations

import argparse

import numpy as np

from ..parameters import DEFAULT_MU

__all__ = ["parse_values", "add_parameter_flags", "parameter_values", "FLAGS", "Interrupted"]


class Interrupted(Exception):
    """Raised by a command instead of ``KeyboardInterrupt`` to say what was kept (exit 130)."""

#: parameter name -> CLI flag
FLAGS = {"q": "--q", "fr_inv": "--fr-inv", "sigma": "--sigma", "alpha_v": "--alpha-v", "mu": "--mu"}


def parse_values(text: str, *, name: str = "value") -> float | np.ndarray:
    """Parse ``start:stop:num`` (``numpy.linspace``), a comma list, or one number.

    Raises
    ------
    ValueError
        With the flag name, the offending text and the accepted forms.
    """
    forms = "a number, a comma list (0,0.1,0.3) or start:stop:num (-0.6:0.6:241, num >= 1)"
    t = str(text).strip()
    if not t:
        raise ValueError(f"{name} = {text!r} is empty; give {forms}")

    def number(part: str) -> float:
        try:
            return float(part)
        except ValueError:
            raise ValueError(f"{name} = {text!r}: {part.strip()!r} is not a number; give {forms}") from None

    if ":" in t:
        parts = t.split(":")
        if len(parts) != 3:
            raise ValueError(f"{name} = {text!r} has {len(parts)} fields; give {forms}")
        start, stop = number(parts[0]), number(parts[1])
        try:
            num = int(parts[2])
        except ValueError:
            raise ValueError(f"{name} = {text!r}: the number of points {parts[2].strip()!r} is not an "
                             "integer; give start:stop:num with num >= 1") from None
        if num < 1:
            raise ValueError(f"{name} = {text!r}: the number of points is {num}; the allowed range is num >= 1")
        if num > 10**9:
            raise ValueError(f"{name} = {text!r}: the number of points is {num}; the allowed range is num <= 1e9")
        return np.linspace(start, stop, num)
    if "," in t:
        vals = [number(v) for v in t.split(",") if v.strip()]
        if not vals:
            raise ValueError(f"{name} = {text!r} is empty; give {forms}")
        return np.array(vals)
    return number(t)


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
