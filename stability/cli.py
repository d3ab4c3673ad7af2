"""The ``tippe`` command line (also ``python -m stability``).

Each subcommand lives in a module of :mod:`stability.commands` that exposes
``register(subparsers)`` (adds its parser and sets ``func``) ; :data:`COMMANDS` lists them.
Errors in the user's input end the program with one line on stderr and exit status 2,
never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import re
import sys
from collections.abc import Sequence

__all__ = ["main", "COMMANDS"]

#: subcommand modules under stability.commands, in the order ``tippe --help`` lists them
COMMANDS: tuple[str, ...] = ("atlas", "figures", "simulate", "validate", "neutral", "threshold", "bench")

_NEGATIVE_VALUE = re.compile(r"^-[\d.]")


def _join_negative_values(argv: list[str]) -> list[str]:
    """Turn ``--q -0.6:0.6:241`` into ``--q=-0.6:0.6:241`` (argparse would take it for an option)."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        a = argv[i]
        if (a.startswith("--") and "=" not in a and i + 1 < len(argv)
                and _NEGATIVE_VALUE.match(argv[i + 1])):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def build_parser() -> argparse.ArgumentParser:
    """The ``tippe`` parser with every registered subcommand."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        ver = version("tippe-stability")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        ver = "unknown"
    parser = argparse.ArgumentParser(
        prog="tippe", description="Linear stability and bifurcation analysis of the Tippe top.")
    parser.add_argument("--version", action="version", version=f"tippe-stability {ver}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in COMMANDS:
        importlib.import_module(f"stability.commands.{name}").register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    args_list = _join_negative_values(list(sys.argv[1:] if argv is None else argv))
    parser = build_parser()
    args = parser.parse_args(args_list)
    try:
        return int(args.func(args) or 0)
    except (ValueError, TypeError, OSError) as exc:
        print(f"tippe {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"tippe {args.command}: interrupted; no output file was left behind", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
