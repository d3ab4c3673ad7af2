"""Signals as flags: SIGINT, SIGTERM and SIGHUP are recorded, and the code acts on them at safe points.

Layer 0 (docs/architecture.md): the standard library only.

Why not Python's default: its SIGINT handler raises ``KeyboardInterrupt`` at whatever bytecode the
main thread is running. Measured on this package (issue 13, items 8, 9 and 11): inside xarray's
lock section (a deadlock on the lock the unwinding then asks for, the partial file left), inside
importlib's module lock (a hang), inside llvmlite's ctypes callback (a segmentation fault),
inside numba's unpickling callback (``SystemError`` from a compiled call), in a finalizer or a
weakref callback ("Exception ignored": the interrupt is lost and the file is written with exit
status 0). A flag cannot land in the wrong place.

* :func:`install` (the command line, first thing in :func:`stability.cli.main`): the three
  signals set the flag and never raise. The code calls :func:`checkpoint` at safe points
  (between slices of a compiled integration, between slabs of a netCDF write, between blocks of
  a grid, between chunks, and last just before a file is committed), which raises
  ``KeyboardInterrupt`` there, an ordinary exception whose unwinding removes the temporary
  files. A second signal, or 2 s (:data:`WATCHDOG_SECONDS`) after the first without the process
  having ended, is the emergency exit: the registered temporary files are removed, one line is
  written on stderr, and the process exits with status 130 (``os._exit``: no Python code of the
  main thread is needed, so it works while the main thread is stuck in a C call that released
  the GIL, or in a lock).
* :func:`deferred` (library calls: ``write_dataset``, ``write_atlas``, ``simulate``): the same
  flag for SIGINT only, in the main thread only, and only while the handler is Python's default
  (an application's own handler, Jupyter's, a GUI loop's is left alone); the previous handler is
  restored on exit, and a SIGINT that arrived is raised as ``KeyboardInterrupt`` at the next
  :func:`checkpoint` or at the exit of the block. A second SIGINT raises at once, as Python does.
* :class:`Temporary`: files being written register themselves (state ``writing``,
  ``committing``, ``committed``, ``removed``), so that the emergency exit removes what is not
  complete and says truthfully what was written.

Outside the main thread (a dask worker thread, a thread of an application) nothing is installed;
:func:`checkpoint` still reads the flag of the main thread.
"""

from __future__ import annotations

import contextlib
import os
import select
import signal
import sys
import threading
import time
from collections.abc import Iterator

__all__ = [
    "SIGNALS",
    "WATCHDOG_SECONDS",
    "Temporary",
    "checkpoint",
    "committed",
    "deferred",
    "hold_until_exit",
    "install",
    "label",
    "mark_reported",
    "pending",
    "received",
    "set_kept",
    "set_label",
    "uninstall",
]

#: seconds between the first signal and the emergency exit of the command line
WATCHDOG_SECONDS = 2.0

#: the signals the command line turns into a flag (SIGHUP where the platform has it)
SIGNALS: tuple[int, ...] = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))


class _State:
    """The module's state (one per process)."""

    def __init__(self) -> None:
        self.pending: int | None = None  # the first signal received and not yet cleared
        self.count = 0  # signals received since it
        self.mode: str | None = None  # "cli", "library" or None (nothing installed)
        self.depth = 0  # nesting of install()/deferred()
        self.previous: dict[int, object] = {}
        self.wakeup_previous: int | None = None
        self.pipe: tuple[int, int] | None = None
        self.label = "tippe"
        self.kept = ""  # what an interrupted command keeps (chunks), for the message
        self.reported = False  # the command line has printed its interruption line
        self.temporaries: dict[int, Temporary] = {}
        self.committed: list[str] = []


_state = _State()


# --- the flag ----------------------------------------------------------------------------------


def pending() -> int | None:
    """The signal number received and not yet cleared, or None."""
    return _state.pending


def received() -> bool:
    """True if a signal was received (and not cleared)."""
    return _state.pending is not None


def _name(signum: int | None) -> str:
    try:
        return signal.Signals(signum).name
    except (ValueError, TypeError):
        return f"signal {signum}"


def checkpoint() -> None:
    """Raise ``KeyboardInterrupt("SIGINT received")`` if a signal is pending; otherwise nothing.

    Called at safe points: no lock is held, and the unwinding removes temporary files. Costs one
    attribute read.
    """
    if _state.pending is not None:
        raise KeyboardInterrupt(f"{_name(_state.pending)} received")


def _handler(signum: int, frame: object) -> None:
    """Record the signal; never raise (the command line), or raise on the second (library)."""
    st = _state
    st.count += 1
    if st.pending is None:
        st.pending = signum
        return
    if st.mode == "cli":
        _emergency_exit(f"{_name(signum)} received twice")
    # library: a second Ctrl-C interrupts at once, as Python's default does
    _restore()
    raise KeyboardInterrupt(f"{_name(signum)} received twice")


# --- installing --------------------------------------------------------------------------------


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def install(label: str = "tippe") -> bool:
    """Make SIGINT, SIGTERM and SIGHUP set the flag (the command line); start the watchdog.

    Parameters
    ----------
    label : str
        The program name the emergency exit's line starts with (see :func:`set_label`).

    Returns
    -------
    bool
        False outside the main thread (nothing installed; handlers can only be set there).
    """
    st = _state
    st.label = label
    if not _main_thread():
        return False
    if st.mode == "cli":
        st.depth += 1
        return True
    _restore()
    st.pending, st.count, st.kept, st.reported = None, 0, "", False
    st.committed.clear()
    st.mode, st.depth = "cli", 1
    st.previous = {s: signal.signal(s, _handler) for s in SIGNALS}
    # the C-level handler writes each signal's number to this pipe as it arrives, whatever the
    # main thread is doing: the watchdog thread wakes on it
    r, w = os.pipe()
    os.set_blocking(w, False)
    st.pipe = (r, w)
    try:
        st.wakeup_previous = signal.set_wakeup_fd(w, warn_on_full_buffer=False)
    except (ValueError, OSError):  # pragma: no cover - not the main thread, or not supported
        st.wakeup_previous = None
    threading.Thread(target=_watchdog, args=(r,), name="tippe-signal-watchdog", daemon=True).start()
    return True


def uninstall() -> None:
    """Undo :func:`install` (a command line run as a library function, e.g. in tests)."""
    st = _state
    if st.mode != "cli":
        return
    st.depth -= 1
    if st.depth <= 0:
        _restore()


def _restore() -> None:
    """Put the previous handlers back and stop the watchdog; clear the flag."""
    st = _state
    if st.mode is None:
        return
    if _main_thread():
        for s, h in st.previous.items():
            with contextlib.suppress(ValueError, OSError, TypeError):
                signal.signal(s, h if h is not None else signal.SIG_DFL)
        if st.pipe is not None:
            with contextlib.suppress(ValueError, OSError):
                signal.set_wakeup_fd(st.wakeup_previous if st.wakeup_previous is not None else -1)
    if st.pipe is not None:
        r, w = st.pipe
        st.pipe = None
        with contextlib.suppress(OSError):
            os.write(w, b"\0")  # wakes the watchdog, which sees the pipe gone and ends
        with contextlib.suppress(OSError):
            os.close(w)
    st.previous, st.mode, st.depth, st.pending, st.count = {}, None, 0, None, 0


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """SIGINT as a flag for the duration of a library call (see the module docstring).

    Inside :func:`install` (the command line) or outside the main thread, or when SIGINT has a
    handler other than Python's default: nothing changes. Otherwise a SIGINT is recorded, raised
    at the next :func:`checkpoint`, or at the exit of the block if none came; a second one raises
    at once.
    """
    st = _state
    if st.mode == "cli" or not _main_thread():
        yield
        return
    if st.mode == "library":
        st.depth += 1
        try:
            yield
        finally:
            st.depth -= 1
        return
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield
        return
    st.mode, st.depth, st.pending, st.count = "library", 1, None, 0
    st.previous = {signal.SIGINT: signal.signal(signal.SIGINT, _handler)}
    try:
        yield
        signum = st.pending
    except BaseException:
        _restore()
        raise
    _restore()
    if signum is not None:
        raise KeyboardInterrupt(f"{_name(signum)} received")


# --- temporary files and what was written ------------------------------------------------------


class Temporary:
    """A file being written under a temporary name, for the emergency exit.

    ``state``: ``"writing"`` (remove it), ``"committing"`` (being renamed to ``target``: if the
    temporary name is gone the target is complete), ``"committed"``, ``"removed"``.
    """

    def __init__(self, path: str, target: str | None = None) -> None:
        self.path, self.target, self.state = str(path), None if target is None else str(target), "writing"
        _state.temporaries[id(self)] = self

    def committing(self) -> None:
        self.state = "committing"

    def done(self, committed: bool) -> None:
        """The file was renamed to its target (``committed``) or removed; forget it."""
        self.state = "committed" if committed else "removed"
        if committed and self.target is not None:
            _state.committed.append(self.target)
        _state.temporaries.pop(id(self), None)


def committed() -> list[str]:
    """Output files committed (complete) in this process since :func:`install`."""
    return list(_state.committed)


def set_label(label: str) -> None:
    """The program name of the emergency exit's line (``tippe atlas``)."""
    _state.label = str(label)


def set_kept(text: str) -> None:
    """What an interrupted command keeps (``"the finished chunks are kept in a.nc.parts"``), for the
    emergency exit's line; empty for nothing."""
    _state.kept = str(text)


def hold_until_exit() -> bool:
    """The command has ended: block the signals for the rest of the process (its interpreter
    shutdown, which restores the default handlers: a SIGTERM then would kill it with status
    143 and no line), and say whether one arrived since the command's last check (handled by
    the flag, or now pending behind the block) that its line has not reported yet."""
    arrived = _state.pending is not None
    if hasattr(signal, "pthread_sigmask") and _main_thread():
        signal.pthread_sigmask(signal.SIG_BLOCK, set(SIGNALS))
        arrived = arrived or bool(signal.sigpending() & set(SIGNALS))
    return arrived and not _state.reported


def label() -> str:
    """The program name set by :func:`set_label`."""
    return _state.label


def mark_reported() -> None:
    """The command line has printed its own interruption line: the emergency exit prints none."""
    _state.reported = True


_exit_lock = threading.Lock()


def _emergency_exit(why: str) -> None:
    """Remove the incomplete temporary files, write one line, end the process with status 130
    (once: a second caller, the watchdog or the handler, waits for the first to end the process)."""
    if not _exit_lock.acquire(blocking=False):
        while True:
            time.sleep(1.0)
    st = _state
    written = list(st.committed)
    for tmp in list(st.temporaries.values()):
        try:
            os.unlink(tmp.path)
        except FileNotFoundError:
            if tmp.state == "committing" and tmp.target is not None:
                written.append(tmp.target)  # renamed just now: the target is complete
        except OSError:
            pass
    _stop_children()
    if not st.reported:
        if written:
            what = "after " + ", ".join(repr(w) for w in written) + " was written (complete)"
        else:
            what = "no output file was written"
        kept = f"; {st.kept}" if st.kept and not written else ""
        line = f"{st.label}: interrupted ({why}); {what}{kept}\n"
        with contextlib.suppress(OSError):
            os.write(2, line.encode(errors="replace"))
    os._exit(130)


def _stop_children() -> None:
    """Terminate child processes (a local dask cluster's workers) that ``os._exit`` would orphan."""
    mp = sys.modules.get("multiprocessing")
    if mp is None:
        return
    with contextlib.suppress(Exception):
        for child in mp.active_children():
            with contextlib.suppress(Exception):
                child.terminate()


def _mine(r: int) -> bool:
    return _state.pipe is not None and _state.pipe[0] == r


def _wait(r: int, timeout: float | None) -> str:
    """``"signal"`` when a signal's byte arrives on the wake-up pipe, ``"timeout"``, or ``"stop"``
    (uninstalled: the pipe is no longer the installed one)."""
    end = None if timeout is None else time.monotonic() + timeout
    while True:
        remaining = None if end is None else max(0.0, end - time.monotonic())
        ready, _, _ = select.select([r], [], [], remaining)
        if not ready:
            return "timeout" if _mine(r) else "stop"
        data = os.read(r, 64)
        if not data or not _mine(r):
            return "stop"
        if any(data):  # signal numbers are never 0; uninstall writes a 0 byte
            return "signal"


def _watchdog(r: int) -> None:
    """Wait for the first signal on the wake-up pipe; end the process if a second one comes or
    if it still runs :data:`WATCHDOG_SECONDS` later."""
    try:
        if _wait(r, None) != "signal":
            return
        outcome = _wait(r, WATCHDOG_SECONDS)
        if outcome == "stop":
            return
        why = (
            f"{_name(_state.pending)} received twice"
            if outcome == "signal"
            else f"{_name(_state.pending)}; stopped {WATCHDOG_SECONDS:g} s after the signal"
        )
        _emergency_exit(why)
    except OSError:
        return
    finally:
        with contextlib.suppress(OSError):
            os.close(r)
