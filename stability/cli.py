"""The ``tippe`` command line (also ``python -m stability``).

Each subcommand lives in a module of :mod:`stability.commands` that states its ``HELP`` (one
line in ``tippe --help``) and ``DESCRIPTION``, and defines ``arguments(parser)`` (its options)
and ``run(args)``; :data:`COMMANDS` lists them, and :func:`build_parser` makes every
subparser from them the same way.

Errors end the program with exactly one line on stderr and no traceback
(docs/input_checks.md):

* a mistake in the command line or its values (argparse's own errors, :class:`ValueError`,
  :class:`TypeError`, including every :class:`~stability.errors.InputError` such as
  :class:`~stability.errors.DomainError`) and a file that cannot be read or written
  (:class:`OSError`): ``tippe CMD: error: ...``, exit status 2;
* a computation that failed: a chunk of a chunked atlas (:class:`~stability.errors.ChunkError`,
  the line says what was kept), a continuation that did not converge (any
  :class:`continuation.errors.ConvergenceError`), any other :class:`~stability.errors.TippeError`
  that is not bad input: ``tippe CMD: error: ...``, exit status 1;
* an interruption (Ctrl-C, SIGTERM, SIGHUP; :mod:`stability.interrupts`): exit status 130,
  one line saying what was kept or written, no partial output file, within 2 s whatever the
  command is doing;
* anything else is a bug of the program: one line ``tippe CMD: internal error: ...``, exit
  status 1. With ``--debug`` (anywhere on the command line) or the environment variable
  ``TIPPE_DEBUG=1`` the full traceback is shown instead, for every kind of error.

The library's messages name Python keywords (``pass overwrite=True to replace it``), never
flags; the error line renders them for ``tippe`` (:func:`render_message`): each ``keyword=value``
of :data:`KEYWORD_FLAGS` is followed by its flag when the command has it (``pass overwrite=True
(--overwrite) to replace it``).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import itertools
import os
import re
import sys
import warnings
from collections.abc import Collection, Sequence
from typing import NoReturn

__all__ = ["COMMANDS", "EXIT_FAILURE", "EXIT_INTERRUPTED", "EXIT_USAGE", "KEYWORD_FLAGS", "main", "render_message"]

#: subcommand modules under stability.commands, in the order ``tippe --help`` lists them
COMMANDS = ("atlas", "figures", "simulate", "validate", "neutral", "threshold", "steady", "final", "launch", "warmup")

#: exit statuses: bad input or file (2), a failed computation or a bug (1), interrupted (130)
EXIT_USAGE, EXIT_FAILURE, EXIT_INTERRUPTED = 2, 1, 130

_NEGATIVE_VALUE = re.compile(r"^-[\d.]")

#: library keyword -> the flag of ``tippe`` that sets it (its argparse ``dest`` is the keyword):
#: the one table by which the error line shows a library message's ``keyword=value`` with its
#: flag (:func:`render_message`)
KEYWORD_FLAGS: dict[str, str] = {
    k: "--" + k.replace("_", "-")
    for k in ("overwrite", "mask_unphysical", "force", "resume", "workers", "scheduler", "chunks")
}

_KEYWORD_VALUE = re.compile(r"\b(" + "|".join(KEYWORD_FLAGS) + r")=[^\s,;)]+")
#: a parameter named as a value or a bound: ``alpha_v = 2``, ``0 <= alpha_v``, ``alpha_v must ...``,
#: ``q is varied`` (the traced or searched one)
_AS_VALUE = r"(?<![\w-])()({kw})(?= (?:=|<=|<|>=|>|must|is varied|and [\w-]+ must) )"
_AS_BOUND = r"((?:<=|<|>=|>) )({kw})(?![\w(])"
#: the neutral curve's library phrase for a parameter that must be held fixed
_FIXED_MUST_GIVE = re.compile(r"\bfixed must give (\w+)")


def render_message(text: str, flags: Collection[str] | None = None) -> str:
    """A library message as ``tippe`` prints it: every ``keyword=value`` whose keyword is in
    :data:`KEYWORD_FLAGS` is followed by the flag, ``"pass overwrite=True (--overwrite) to
    replace it"``.

    With the flags of the command that failed (``flags``), a keyword whose flag the command
    does not have is left as it is, and the parameters the message names as a value or a bound
    become the command's flags: ``alpha_v = 2 is outside ...: 0 <= alpha_v`` -> ``--alpha-v = 2
    ...: 0 <= --alpha-v``; the neutral curve's ``fixed must give fr_inv`` -> ``give --fr-inv``.
    Formulas (``1 - mu q^2``) are left as they are: only a name beside ``=`` or a comparison is
    a parameter's value or bound.

    Parameters
    ----------
    text : str
        The message (it names keywords, never flags).
    flags : collection of str, optional
        The flags of the command that failed. None: every flag of the table, no parameter flags.

    Returns
    -------
    str
    """

    def with_flag(m: re.Match[str]) -> str:
        flag = KEYWORD_FLAGS[m.group(1)]
        return m.group(0) if (flags is not None and flag not in flags) or flag in text else f"{m.group(0)} ({flag})"

    text = _KEYWORD_VALUE.sub(with_flag, text)
    if flags is None:
        return text
    given = {flag[2:].replace("-", "_"): flag for flag in flags if flag.startswith("--")}
    text = _FIXED_MUST_GIVE.sub(lambda m: f"give {given[m[1]]}" if m[1] in given else m[0], text)
    for kw, flag in given.items():
        if kw in text:
            for pattern in (_AS_VALUE, _AS_BOUND):
                text = re.sub(pattern.format(kw=re.escape(kw)), lambda m, f=flag: m.group(1) + f, text)
    return text


class HelpFormatter(argparse.HelpFormatter):
    """Help with each option's default appended, ``(default: X)``, unless the help already
    names it or there is none to show (None, a flag that is off)."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text, default = action.help or "", action.default
        if (
            "default" in text
            or default in (None, argparse.SUPPRESS)
            or isinstance(default, bool)
            or not action.option_strings
        ):
            return text
        return f"{text} (default: %(default)s)"


def _option_tokens(args: Sequence[str]) -> list[str]:
    """The options (``--name``, without ``=value``) among ``args``, up to ``--``."""
    tokens = itertools.takewhile(lambda a: a != "--", args)
    return [a.split("=", 1)[0] for a in tokens if a.startswith("-") and len(a) > 1 and not _NEGATIVE_VALUE.match(a)]


class _Parser(argparse.ArgumentParser):
    """argparse with errors on one line (``prog: error: message``), without the usage block;
    every option's default shown in its help (:class:`HelpFormatter`); arguments it does not
    know reported by the subcommand that got them, with its help and ``did you mean``."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)
        self.commands: dict[str, _Parser] = {}  # the parser of each subcommand (build_parser)

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {_one_line(message)} (see {self.prog} --help)\n")

    def parse_args(self, args=None, namespace=None):
        """As argparse's, but arguments left over are reported by the subcommand that got them."""
        ns, extras = self.parse_known_args(args, namespace)
        if extras:
            self.commands.get(getattr(ns, "command", ""), self).unrecognized(extras)
        return ns

    def parse_known_args(self, args=None, namespace=None):
        """A subcommand checks its options first: a mistyped one is reported before a missing
        required one (``tippe final --alpha_v 0.5``: did you mean --alpha-v)."""
        if not self.commands and args is not None:
            unknown = [a for a in _option_tokens(args) if not self._known_option(a)]
            if unknown:
                self.unrecognized(unknown)
        return super().parse_known_args(args, namespace)

    def options(self) -> list[str]:
        """Every option string of the parser."""
        return [s for a in self._actions for s in a.option_strings]

    def _known_option(self, token: str) -> bool:
        opts = self.options()
        return token in opts or (token.startswith("--") and any(o.startswith(token) for o in opts))

    def unrecognized(self, extras: Sequence[str]) -> NoReturn:
        """Exit 2 after the command's own help and one error line that names the unknown
        arguments and, for a mistyped option, the closest one (``difflib``)."""
        import difflib

        opts = [o for o in self.options() if o.startswith("--")]
        hints = []
        for tok in _option_tokens(extras):
            close = difflib.get_close_matches(tok.replace("_", "-").lower(), opts, n=1, cutoff=0.6)
            if close and not self._known_option(tok):
                hints.append(f"did you mean {close[0]} (for {tok})?")
        sys.stderr.write(self.format_help() + "\n")
        self.error(f"unrecognized arguments: {' '.join(extras)}" + (f"; {' '.join(hints)}" if hints else ""))


def _one_line(text: str) -> str:
    return " ".join(str(text).split()) or "(no message)"


def _join_negative_values(argv: list[str]) -> list[str]:
    """Turn ``--q -0.6:0.6:241`` into ``--q=-0.6:0.6:241`` (argparse would take it for an option)."""
    out: list[str] = []
    for a in argv:
        if out and out[-1].startswith("--") and "=" not in out[-1] and _NEGATIVE_VALUE.match(a):
            out[-1] += "=" + a
        else:
            out.append(a)
    return out


def build_parser() -> argparse.ArgumentParser:
    """The ``tippe`` parser with every registered subcommand."""
    from ._version import package_version

    parser = _Parser(
        prog="tippe",
        description="Linear stability and bifurcation analysis of the Tippe top.",
        epilog="Errors are reported on one line; add --debug (or set TIPPE_DEBUG=1) for a traceback.",
    )
    parser.add_argument("--version", action="version", version=f"tippe-stability {package_version()}")
    parser.add_argument("--debug", action="store_true", help="show the traceback of any error")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser, required=True)
    for name in COMMANDS:
        command = importlib.import_module(f"stability.commands.{name}")
        parser.commands[name] = p = sub.add_parser(name, help=command.HELP, description=command.DESCRIPTION)
        command.arguments(p)
        p.set_defaults(func=command.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status.

    The first thing it does is to make SIGINT, SIGTERM and SIGHUP set a flag
    (:func:`stability.interrupts.install`), before any heavy import: a signal at any moment,
    during start-up too, ends the command at the next safe point (at the latest 2 s later) with
    exit status 130, one line on stderr and no partial file, never a traceback, a hang or a
    swallowed interrupt. The handlers stay until the process exits when ``argv`` is None (the
    ``tippe`` program, ``python -m stability``); called with ``argv`` (as a library function,
    in tests) the previous handlers are restored on return.
    """
    from . import interrupts

    interrupts.install("tippe")
    try:
        status = _main(argv, interrupts)
    finally:
        if argv is not None:
            interrupts.uninstall()
    # the program (not a library call): from here to the end of the process a signal waits
    # (the interpreter's shutdown restores the default handlers); one that came after the
    # command's last check is reported as the others are
    if argv is None and interrupts.hold_until_exit():
        status = _interrupted(interrupts.run.label, None)
    return status


def _interrupted(prog: str, text: str | None) -> int:
    """Print the one line of an interrupted command, truthful about what was written."""
    from . import interrupts

    done = interrupts.run.committed
    if done:
        what = ", ".join(repr(f) for f in done)
        line = f"{prog}: interrupted after {what} {'was' if len(done) == 1 else 'were'} written (complete)"
    else:
        line = f"{prog}: interrupted; {_one_line(text) if text else 'no output file was left behind'}"
    interrupts.run.reported = True
    print(line, file=sys.stderr)
    return EXIT_INTERRUPTED


def _stdout_broken() -> bool:
    """True if stdout is a pipe whose reader has closed it (``poll`` reports POLLERR: the failed
    write's data may have been dropped from the buffer, so a flush alone does not tell); stdout
    is then sent to devnull so that the interpreter's final flush does not complain."""
    import select

    try:
        sys.stdout.flush()
        poller = select.poll()  # not on every platform: AttributeError, not broken
        poller.register(sys.stdout.fileno(), select.POLLOUT)
        if not any(ev & select.POLLERR for _, ev in poller.poll(0)):
            return False
    except BrokenPipeError:
        pass
    except (OSError, ValueError, AttributeError):
        return False
    with contextlib.suppress(OSError, ValueError, AttributeError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return True


def _main(argv: Sequence[str] | None, interrupts) -> int:
    from continuation.errors import ConvergenceError

    from .errors import Interrupted, TippeError

    args_list = list(sys.argv[1:] if argv is None else argv)
    env = os.environ.get("TIPPE_DEBUG", "").strip().lower()
    debug = "--debug" in args_list or env not in ("", "0", "no", "false")
    args_list = _join_negative_values([a for a in args_list if a != "--debug"])
    prog, flags = "tippe", None
    try:
        parser = build_parser()
        args = parser.parse_args(args_list)
        prog = f"tippe {args.command}"
        interrupts.run.label = prog
        flags = set(parser.commands[args.command].options())
        interrupts.checkpoint()  # a signal during start-up
        with warnings.catch_warnings():
            _model_name_warnings_as_lines(prog)
            status = int(args.func(args) or 0)
        interrupts.checkpoint()  # after the command's last safe point: its line says what was written
        return status
    except BrokenPipeError:
        if not _stdout_broken():
            print(f"{prog}: error: broken pipe", file=sys.stderr)
            return EXIT_USAGE
        done = interrupts.run.committed
        if done:  # the output is complete; only the report on stdout was lost
            print(
                f"{prog}: wrote {', '.join(repr(f) for f in done)}; the report on stdout could not be printed "
                "(its reader closed the pipe)",
                file=sys.stderr,
            )
            return 0
        return EXIT_FAILURE
    except (Interrupted, KeyboardInterrupt, Exception) as exc:
        if debug:
            raise
        if isinstance(exc, (Interrupted, KeyboardInterrupt)):
            return _interrupted(prog, str(exc) if isinstance(exc, Interrupted) else None)
        if not isinstance(exc, (ValueError, TypeError, OSError, TippeError, ConvergenceError)):  # a bug: one line
            print(
                f"{prog}: internal error: {type(exc).__name__}: {_one_line(exc)} "
                "(rerun with --debug or TIPPE_DEBUG=1 for the traceback)",
                file=sys.stderr,
            )
            return EXIT_FAILURE
        print(f"{prog}: error: {render_message(_one_line(exc), flags)}", file=sys.stderr)
        # bad input (every InputError is a ValueError) or a file: 2; a failure to compute
        # (ChunkError, ConvergenceError, any other TippeError): 1
        return EXIT_USAGE if isinstance(exc, (ValueError, TypeError, OSError)) else EXIT_FAILURE


def _model_name_warnings_as_lines(prog: str) -> None:
    """Show the library's warnings about model names (a deprecated name, the changed meaning of
    ``rolling``: :mod:`stability.models`) as one line ``tippe CMD: warning: ...``; call inside
    ``warnings.catch_warnings()``, which restores the previous state."""
    warnings.filterwarnings("default", message="model '", category=DeprecationWarning)
    previous = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, (FutureWarning, DeprecationWarning)) and str(message).startswith("model '"):
            print(f"{prog}: warning: {_one_line(message)}", file=sys.stderr)
            return
        previous(message, category, filename, lineno, file, line)

    warnings.showwarning = show


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
