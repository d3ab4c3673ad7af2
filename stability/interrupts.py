"""Signals as flags: SIGINT, SIGTERM and SIGHUP are recorded, and the code acts on them at safe points.

Layer 0 (docs/architecture.md): the standard library only.

Why not Python's default: its SIGINT handler raises ``KeyboardInterrupt`` at whatever bytecode the
main thread is running. Measured on this package (issue 13, items 8, 9 and 11): inside xarray's
lock section (a deadlock, the partial file left), inside importlib's module lock (a hang), inside
llvmlite's ctypes callback (a segmentation fault), inside numba's unpickling callback
(``SystemError``), in a finalizer ("Exception ignored": the interrupt is lost). A flag cannot
land in the wrong place.

* :func:`install` (the command line, first thing in :func:`stability.cli.main`): the three
  signals set the flag and never raise. Long loops call :func:`checkpoint` at safe points
  (between slices of a compiled integration, between slabs of a netCDF write, between blocks of
  a grid, between chunks, and last just before a file is committed), which raises
  ``KeyboardInterrupt`` there, an ordinary exception whose unwinding removes the temporary files.
  The work between two checkpoints is cut small enough (slices, slabs, blocks) that a signal
  ends a command within a second or two (docs/hard_cases.md, "Signals and interruptions").
  A second signal is the emergency exit: the registered temporary files are removed, one line
  is written on stderr and the process exits with status 130 at once.
* :func:`deferred` (library calls: ``write_dataset``, ``write_atlas``, ``simulate``): the same
  flag for SIGINT only, in the main thread only, and only while the handler is Python's default
  (an application's own handler is left alone); the previous handler is restored on exit, and a
  SIGINT that arrived is raised as ``KeyboardInterrupt`` at the next :func:`checkpoint` or at the
  exit of the block. A second SIGINT raises at once, as Python does.
* :class:`Temporary`: files (and Zarr stores, directories) being written register themselves,
  so that the emergency exit removes what is not complete and says truthfully what was written.
* :data:`run`: what the command line's lines need, one small object: ``label`` (the program
  name, ``tippe atlas``), ``kept`` (what an interrupted command keeps, ``"the finished chunks are
  kept in ..."``), ``reported`` (the command line has printed its own line: the emergency exit
  prints none), ``committed`` (the output files committed, complete, since :func:`install`).
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import sys
import threading
from collections.abc import Iterator
from types import SimpleNamespace

__all__ = ["SIGNALS", "Temporary", "checkpoint", "deferred", "hold_until_exit", "install", "run", "uninstall"]

#: the signals the command line turns into a flag (SIGHUP where the platform has it)
SIGNALS: tuple[int, ...] = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))

#: the command line's state (module docstring): program name, what is kept, whether its line was
#: printed, the output files committed
run = SimpleNamespace(label="tippe", kept="", reported=False, committed=[])

#: the flag's state: the first signal received and not yet cleared; the mode ("cli", "library" or
#: None: nothing installed) and the handlers it replaced; the files being written (by id)
_state = SimpleNamespace(pending=None, mode=None, previous={}, temporaries={})


def checkpoint() -> None:
    """Raise ``KeyboardInterrupt("SIGINT received")`` if a signal is pending; otherwise nothing.

    Called at safe points: no lock is held, and the unwinding removes temporary files. Costs one
    attribute read.
    """
    if _state.pending is not None:
        raise KeyboardInterrupt(f"{signal.Signals(_state.pending).name} received")


def _handler(signum: int, frame: object) -> None:
    """Record the first signal; on the second, exit (command line) or raise (library)."""
    if _state.pending is None:
        _state.pending = signum
        return
    why = f"{signal.Signals(signum).name} received twice"
    if _state.mode == "cli":
        _emergency_exit(why)
    _restore()  # library: a second Ctrl-C interrupts at once, as Python's default does
    raise KeyboardInterrupt(why)


def _take(mode: str, signals: tuple[int, ...]) -> bool:
    """Make ``signals`` set the flag, in ``mode``; False outside the main thread (nothing done)."""
    if threading.current_thread() is not threading.main_thread():
        return False
    _restore()
    _state.mode, _state.previous = mode, {s: signal.signal(s, _handler) for s in signals}
    return True


def _restore() -> None:
    """Put the previous handlers back; clear the flag. (Outside the main thread, e.g. the
    command line run from a thread while its handlers are held, a handler cannot be set: the
    flag is cleared all the same.)"""
    for s, h in _state.previous.items():
        with contextlib.suppress(ValueError, OSError, TypeError):
            signal.signal(s, h if h is not None else signal.SIG_DFL)
    _state.previous, _state.mode, _state.pending = {}, None, None


def install(label: str = "tippe") -> bool:
    """Make SIGINT, SIGTERM and SIGHUP set the flag (the command line); reset :data:`run`.

    Parameters
    ----------
    label : str
        The program name the emergency exit's line starts with (``run.label``).

    Returns
    -------
    bool
        False outside the main thread (nothing installed; handlers can only be set there).
    """
    run.label, run.kept, run.reported, run.committed = label, "", False, []
    return _take("cli", SIGNALS)


def uninstall() -> None:
    """Undo :func:`install` (a command line run as a library function, e.g. in tests)."""
    if _state.mode == "cli":
        _restore()


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """SIGINT as a flag for the duration of a library call (see the module docstring).

    Inside :func:`install` (the command line) or another :func:`deferred`, outside the main
    thread, or when SIGINT has a handler other than Python's default: nothing changes. Otherwise
    a SIGINT is recorded, raised at the next :func:`checkpoint`, or at the exit of the block if
    none came; a second one raises at once.
    """
    own = _state.mode is None and signal.getsignal(signal.SIGINT) is signal.default_int_handler
    if not (own and _take("library", (signal.SIGINT,))):
        yield
        return
    try:
        yield
        checkpoint()  # a SIGINT that no checkpoint of the block took
    finally:
        _restore()


class Temporary:
    """A file (or a directory: a Zarr store) being written under a temporary name, for the
    emergency exit, which removes it.

    ``state``: ``"writing"`` (remove it), ``"committing"`` (being committed to ``target``),
    ``"committed"``, ``"removed"``.
    """

    def __init__(self, path: str, target: str | None = None) -> None:
        self.path, self.target, self.state = str(path), None if target is None else str(target), "writing"
        _state.temporaries[id(self)] = self

    def done(self, committed: bool) -> None:
        """The file was committed to its target (``committed``) or removed; forget it."""
        self.state = "committed" if committed else "removed"
        if committed and self.target is not None:
            run.committed.append(self.target)
        _state.temporaries.pop(id(self), None)


def hold_until_exit() -> bool:
    """The command has ended: block the signals for the rest of the process (its interpreter
    shutdown, which restores the default handlers: a SIGTERM then would kill it with status
    143 and no line), and say whether one arrived since the command's last check (handled by
    the flag, or now pending behind the block) that its line has not reported yet."""
    arrived = _state.pending is not None
    if hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread():
        signal.pthread_sigmask(signal.SIG_BLOCK, set(SIGNALS))
        arrived = arrived or bool(signal.sigpending() & set(SIGNALS))
    return arrived and not run.reported


def _emergency_exit(why: str) -> None:
    """Remove the incomplete temporary files, write one line, end the process with status 130."""
    written = list(run.committed)
    for tmp in list(_state.temporaries.values()):
        with contextlib.suppress(OSError):  # a commit under way: done if the two names are one file
            if tmp.state == "committing" and (not os.path.exists(tmp.path) or os.path.samefile(tmp.path, tmp.target)):
                written.append(tmp.target)
        with contextlib.suppress(OSError):  # a Zarr store being written is a directory
            shutil.rmtree(tmp.path, ignore_errors=True) if os.path.isdir(tmp.path) else os.unlink(tmp.path)
    mp = sys.modules.get("multiprocessing")  # a local dask cluster's workers: not orphaned
    for child in mp.active_children() if mp is not None else ():
        with contextlib.suppress(Exception):
            child.terminate()
    if not run.reported:
        names = ", ".join(map(repr, written))
        what = f"after {names} was written (complete)" if written else "no output file was written"
        kept = f"; {run.kept}" if run.kept and not written else ""
        with contextlib.suppress(OSError):
            os.write(2, f"{run.label}: interrupted ({why}); {what}{kept}\n".encode(errors="replace"))
    os._exit(130)
