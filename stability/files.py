"""Output files: the one way the package writes a file, and what it refuses.

Layer 0 (docs/architecture.md): the standard library, the error hierarchy and the signal flag.

Every writer (netCDF datasets, chunk-wise atlases, figures, benchmark records) goes through
:func:`atomic_output`: the content is written under a unique temporary name in the target's
directory and committed only when complete.

* **No partial file.** Any exception or interruption removes the temporary file; the temporary
  is registered with :mod:`stability.interrupts`, whose emergency exit removes it too.
* **Exactly one winner** (``overwrite=False``). The refusal to replace an existing file holds at
  the moment of the commit, not only at the start: the commit is ``os.link(tmp, target)``, which
  fails atomically if ``target`` exists (POSIX, NFS and NTFS alike), then ``os.unlink(tmp)``. Two
  runs writing the same new name at once: one commits, the other gets ``FileExistsError`` ("...
  was created by another process while this run was computing; nothing was written"). A file
  system without hard links (vfat) cannot give that guarantee: the commit is refused with an
  error naming it (``overwrite=True`` still works there).
* **Only a regular file is replaced** (``overwrite=True``, ``os.replace``): a target that is a
  FIFO, a device, a socket, a directory or a symbolic link is refused, with or without
  ``overwrite`` (``os.lstat``: a link is not followed), before computing and again just before
  the commit.
* **A failed write names the file and the cause** (:func:`write_error`): the first ``OSError``
  with an error number in the exception's chain (ENOSPC, EFBIG, EDQUOT, EROFS, EIO), otherwise a
  diagnosis made when the failure happens (free space, the file size limit ``ulimit -f``, a
  read-only mount): ``OutputWriteError`` "cannot write 'a.nc': file size limit (ulimit -f) of
  1000000 bytes reached (NetCDF: HDF error); nothing was written". Clean-up errors never replace
  the first error.
* **Space is checked first** where the size is known (:func:`check_free_space`).
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from .errors import OutputWriteError, ParameterTypeError, TippeError
from .interrupts import Temporary, checkpoint

__all__ = ["TEMPORARY_PREFIX", "atomic_output", "check_free_space", "check_output_directory", "check_output_path"]
__all__ += ["close_quietly", "describe_kind", "format_bytes", "temporary_name", "write_error"]

#: temporary files are ``<dir>/.tippe-tmp-XXXXXXXX-<name>``: hidden, unique, and ending with the
#: target's name, so that their suffix is the target's (a figure's format is read off it)
TEMPORARY_PREFIX = ".tippe-tmp-"

#: error numbers that mean "the file could not be written" -> the cause as the message says it
#: (``{dir}``: the directory; ``{free}``, ``{limit}``: what :func:`_room` found, where known)
_CAUSES: dict[int | None, str] = {
    errno.ENOSPC: "no space left on the file system holding {dir}{free}",
    errno.EFBIG: "file size limit{limit} reached",
    errno.EROFS: "the file system holding {dir} is read-only",
    errno.EIO: "input/output error on the file system holding {dir}",
    getattr(errno, "EDQUOT", -1): "disk quota exceeded on the file system holding {dir}",
    None: "the netCDF/HDF5 library reported an error",
}

#: a file's type in words, by its letter in ``ls -l`` (:func:`stat.filemode`)
_KINDS = {"-": "a regular file", "d": "a directory", "l": "a symbolic link", "p": "a FIFO (named pipe)"}
_KINDS |= {"c": "a character device", "b": "a block device", "s": "a socket"}

#: the errors of ``os.link`` that mean "this file system has no hard links" (vfat)
_NO_LINKS = (errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EMLINK, errno.ENOSYS)


def describe_kind(mode: int) -> str:
    """What a file mode is, in words: ``"a FIFO (named pipe)"``, ``"a symbolic link"``, ..."""
    return _KINDS.get(stat.filemode(mode)[0], "not a regular file")


def format_bytes(n: float) -> str:
    """``1234567`` -> ``"1.23 MB"`` (decimal units)."""
    unit, size = next((u, s) for u, s in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3), ("", 0)) if n >= s)
    return f"{n / size:.3g} {unit}" if size else f"{float(n):.0f} bytes"


def _refuse_existing(p: Path, overwrite: bool) -> None:
    """Refuse an existing ``p`` unless it is a regular file and ``overwrite`` (a link is not followed)."""
    try:
        mode = os.lstat(p).st_mode
    except (FileNotFoundError, NotADirectoryError):  # the directory's problem is reported next
        return
    if stat.S_ISDIR(mode):
        raise IsADirectoryError(f"output path {str(p)!r} is a directory; give a file name")
    if not stat.S_ISREG(mode):
        kind = f"{describe_kind(mode)}; only a regular file can be replaced: remove it or choose another name"
        raise FileExistsError(f"output path {str(p)!r} is {kind}")
    if not overwrite:
        raise FileExistsError(f"output file {str(p)!r} exists; pass overwrite=True to replace it")


def check_output_path(path: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Fail early (before any computation) if ``path`` cannot be written.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``overwrite`` is False; or it exists and is not a regular file (a
        FIFO, a device, a socket, a symbolic link: refused even with ``overwrite``).
    IsADirectoryError
        ``path`` is a directory.
    FileNotFoundError, NotADirectoryError, PermissionError
        The directory does not exist, is not one, or is not writable.
    """
    if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
        raise ParameterTypeError(f"output path = {path!r} must be a file name (a non-empty str or path-like)")
    if not isinstance(overwrite, bool):
        raise ParameterTypeError(f"overwrite = {overwrite!r} must be True or False")
    _refuse_existing(Path(path), overwrite)
    check_output_directory(path)
    return Path(path)


def check_output_directory(path: str | os.PathLike) -> None:
    """Fail early if the directory that is to hold ``path`` does not exist, is not a directory
    or is not writable (a probe file is created and removed there: permission bits do not tell
    everything, for root, read-only mounts, pseudo file systems); ``path`` itself is not looked
    at (a Zarr store checks its own name).

    Raises
    ------
    FileNotFoundError, NotADirectoryError, PermissionError
        Naming the directory and ``path``.
    """
    p = Path(path)
    where = f"output directory {str(p.parent)!r} of {str(p)!r}"
    if not p.parent.exists():
        raise FileNotFoundError(f"{where} does not exist")
    if not p.parent.is_dir():
        raise NotADirectoryError(f"{where} is not a directory")
    try:
        os.unlink(temporary_name(p))
    except OSError as exc:
        raise PermissionError(f"{where} is not writable ({exc.strerror})") from None


def _room(d: Path) -> tuple[float | None, int | None, bool]:
    """The space available to this user on the file system holding ``d`` (``statvfs``), the
    file size limit (``ulimit -f``, ``RLIMIT_FSIZE``), in bytes (None where unknown), and
    whether the file system is mounted read-only."""
    free, limit, readonly = None, None, False
    with contextlib.suppress(OSError, AttributeError):
        vfs = os.statvfs(d)
        free, readonly = float(vfs.f_bavail * vfs.f_frsize), bool(vfs.f_flag & os.ST_RDONLY)
    with contextlib.suppress(ImportError, OSError, ValueError):
        import resource

        soft = resource.getrlimit(resource.RLIMIT_FSIZE)[0]
        limit = None if soft == resource.RLIM_INFINITY or soft < 0 else int(soft)
    return free, limit, readonly


def check_free_space(path: str | os.PathLike, nbytes: float) -> None:
    """Refuse, before computing, an output of about ``nbytes`` that cannot fit: the free space of
    the file system holding ``path`` (``statvfs``, space available to this user) and the file
    size limit (``ulimit -f``). Unknown limits are not checked.

    Raises
    ------
    OutputWriteError
        With ``errno`` ENOSPC or EFBIG, naming the file, the size and the limit.
    """
    p, d = str(path), Path(path).parent
    free, limit, _ = _room(d)
    need = f"cannot write {p!r}: the output needs about {format_bytes(nbytes)}"
    if free is not None and nbytes > free:
        where = f"the file system holding {str(d)!r} has {format_bytes(free)} free"
        raise OutputWriteError(f"{need} and {where}; nothing was written", errno.ENOSPC, p)
    if limit is not None and nbytes > limit:
        where = f"the file size limit (ulimit -f) of {limit} bytes"
        raise OutputWriteError(f"{need}, above {where}; nothing was written", errno.EFBIG, p)


def temporary_name(target: Path, directory: bool = False) -> str:
    """Create an empty, unique temporary file (or directory) next to ``target``; return its name.
    It gets the mode a new file (directory) gets under the process's umask, which the kernel
    applies (``os.umask`` is never called: it is process-wide). Created exclusively: a name
    taken meanwhile is never replaced, another is drawn. (32 random bits keep the name 24
    characters longer than the target's only: a long output name still fits.)"""
    while True:
        name = os.path.join(target.parent, f"{TEMPORARY_PREFIX}{secrets.token_hex(4)}-{target.name}")
        with contextlib.suppress(FileExistsError):  # pragma: no cover - 2**32 names
            os.mkdir(name) if directory else open(name, "x").close()
            return name


@contextlib.contextmanager
def atomic_output(
    path: str | os.PathLike, *, overwrite: bool = False, expected_bytes: float | None = None
) -> Iterator[str]:
    """Yield a temporary file name next to ``path``; commit it to ``path`` only on success.

    Parameters
    ----------
    path : path-like
        The output file (checked by :func:`check_output_path`).
    overwrite : bool
        Replace an existing regular file.
    expected_bytes : float, optional
        The output's expected size, checked against the free space first
        (:func:`check_free_space`).

    The temporary file is removed on any exception, including an interruption; an error while
    writing is translated by :func:`write_error`. The file gets the usual permissions (umask:
    :func:`temporary_name`).

    The commit is the last interruption point (:func:`stability.interrupts.checkpoint`). With
    ``overwrite=False`` it refuses an existing target atomically (``os.link``, then
    ``os.unlink`` of the temporary name); with ``overwrite=True`` it replaces only a regular file
    (``os.replace``, after ``os.lstat`` again).

    Raises
    ------
    FileExistsError
        The target exists (``overwrite=False``), appeared meanwhile (another process), or is not
        a regular file.
    OutputWriteError
        The write failed (:func:`write_error`), or the file system has no hard links
        (``overwrite=False`` cannot be kept there).
    KeyboardInterrupt
        A signal is pending at the commit: nothing is committed.
    """
    p = check_output_path(path, overwrite=overwrite)
    if expected_bytes is not None:
        check_free_space(p, expected_bytes)
    tmp = Temporary(temporary_name(p), str(p))
    try:
        try:
            yield tmp.path
        except BaseException as exc:
            translated = write_error(exc, p, tmp.path)
            if translated is not None:
                raise translated from exc
            raise
        checkpoint()  # the last interruption point: after a signal nothing is committed
        tmp.state = "committing"
        try:
            if overwrite:
                _refuse_existing(p, True)  # again at the commit: only a regular file is replaced
                os.replace(tmp.path, p)
            else:
                try:
                    os.link(tmp.path, p)  # fails atomically if the name exists: exactly one winner
                except FileExistsError:
                    taken = f"output file {str(p)!r} was created by another process while this run was computing"
                    raise FileExistsError(f"{taken}; nothing was written (pass overwrite=True to replace it)") from None
                except OSError as exc:
                    if exc.errno not in _NO_LINKS:
                        raise
                    why = "has no hard links, which the commit that never replaces a file needs; pass overwrite=True"
                    msg = f"cannot write {str(p)!r}: the file system holding it {why} (nothing was written)"
                    raise OutputWriteError(msg, exc.errno, str(p)) from None
                os.unlink(tmp.path)
        except BaseException:
            tmp.state = "writing"  # nothing committed: the emergency exit must not report it written
            raise
        tmp.done(committed=True)
    finally:
        if tmp.state != "committed":
            with contextlib.suppress(OSError):  # an error here never replaces the one being handled
                os.unlink(tmp.path)
            tmp.done(committed=False)


def _library_error(exc: BaseException) -> bool:
    """netCDF4 and h5 report a failed write as a RuntimeError "NetCDF: ..." (no errno)."""
    name, text = type(exc).__name__, str(exc)
    return name in ("HDF5ExtError", "NetCDF4Error") or (name == "RuntimeError" and ("NetCDF" in text or "HDF" in text))


def write_error(exc: BaseException, target: Path, tmp: str | None = None) -> OutputWriteError | None:
    """The :class:`~stability.errors.OutputWriteError` for a failure while writing ``target``,
    or None if ``exc`` is not a write failure (bad input, an interruption, a failed computation
    are passed on as they are).

    A write failure is an ``OSError`` in the exception's chain (``exc``, the exceptions it was
    raised from or during) with an error number of :data:`_CAUSES` (its cause), or, without one,
    a netCDF/HDF5 library error or an ``OSError`` on the temporary file ``tmp``, whose probable
    cause is found now: a read-only mount, less than 1 MB free, the temporary file within 1 MB of
    the file size limit (else: "the library reported an error").

    Parameters
    ----------
    exc : BaseException
    target : Path
        The output file (named in the message).
    tmp : str, optional
        The temporary file being written (its size is compared with the file size limit).
    """
    if not isinstance(exc, Exception) or isinstance(exc, TippeError):
        return None  # an interruption (KeyboardInterrupt, SystemExit, GeneratorExit), bad input, or translated
    chain = [exc]
    while (e := chain[-1].__cause__ or chain[-1].__context__) is not None and e not in chain:
        chain.append(e)
    code = next((e.errno for e in chain if isinstance(e, OSError) and e.errno in _CAUSES), None)
    name = getattr(exc, "filename", None)
    own_file = name is not None and tmp is not None and os.path.abspath(str(name)) == os.path.abspath(tmp)
    if code is None and not own_file and not any(map(_library_error, chain)):
        return None
    d = Path(target).parent
    free, limit, readonly = _room(d)
    if code is None:  # found now: a read-only mount, < 1 MB free, the file within 1 MB of the size limit
        size = os.path.getsize(tmp) if tmp is not None and os.path.isfile(tmp) else 0
        full, at_limit = free is not None and free < 1e6, limit is not None and size + 1e6 >= limit
        code = errno.EROFS if readonly else errno.ENOSPC if full else errno.EFBIG if at_limit else None
    free_text, limit_text = f" ({format_bytes(free or 0)} free)", f" (ulimit -f) of {limit} bytes"
    cause = _CAUSES[code].format(
        dir=repr(str(d)), free=free_text * (free is not None), limit=limit_text * (limit is not None)
    )
    detail = " ".join(str(exc).split())[:160]
    return OutputWriteError(f"cannot write {str(target)!r}: {cause} ({detail}); nothing was written", code, str(target))


@contextlib.contextmanager
def close_quietly(handle: Any) -> Iterator[Any]:
    """``with close_quietly(netCDF4.Dataset(...)) as nc``: closed at the end; if the block
    raised, an error of the close (HDF5 flushes on close, and fails again on a full disk) is
    dropped so that the first error is the one reported; on success a close error is raised
    (a failed flush is a failed write)."""
    try:
        yield handle
    except BaseException:
        with contextlib.suppress(Exception):
            handle.close()
        raise
    handle.close()
