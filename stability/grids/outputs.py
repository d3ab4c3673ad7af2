"""Output files: the one way the package writes a file, and what it refuses.

Every writer (netCDF datasets, chunk-wise atlases, the chunks of a resumable run, figures,
benchmark records) goes through :func:`atomic_output`: the content is written under a unique
temporary name in the target's directory and committed by :func:`commit` only when complete.

* **No partial file.** Any exception or interruption removes the temporary file; the temporary
  is registered with :mod:`stability.interrupts`, whose emergency exit removes it too.
* **Exactly one winner** (``overwrite=False``). The refusal to replace an existing file holds
  at the moment of the rename, not only at the start: two runs writing the same new name at
  once, one commits, the other gets ``FileExistsError`` ("... was created by another process
  while this run was computing; nothing was written"). The rename is atomic and refuses an
  existing target, by the first of these that the system supports:

  1. ``renameat2(..., RENAME_NOREPLACE)`` (Linux >= 3.15 with glibc >= 2.28: ext4, xfs, btrfs,
     tmpfs; ``renamex_np(RENAME_EXCL)`` on macOS);
  2. ``link(tmp, target)`` then ``unlink(tmp)`` (file systems with hard links, NFS included);
     killed in between, the temporary name stays behind as a second name of the complete file;
  3. ``open(target, O_CREAT | O_EXCL)`` to reserve the name, then ``rename`` (file systems with
     neither, e.g. vfat): killed in between, an empty target stays behind.

  On Windows ``os.rename`` itself refuses an existing target.
* **Only a regular file is replaced** (``overwrite=True``): a target that is a FIFO, a device,
  a socket, a directory or a symbolic link is refused, with or without ``overwrite``
  (``os.lstat``: a link is not followed), before computing and again just before the rename.
  Between that last check and the rename another process could still swap the path (a window of
  microseconds); closing it needs ``RENAME_EXCHANGE`` and is not attempted.
* **A failed write names the file and the cause** (:func:`write_error`): the first ``OSError``
  with an error number in the exception's chain (ENOSPC, EFBIG, EDQUOT, EROFS, EIO), otherwise
  a diagnosis made when the failure happens (free space, the file size limit ``ulimit -f``, a
  read-only mount): ``OutputWriteError`` "cannot write 'a.nc': file size limit (ulimit -f) of
  1000000 bytes reached (NetCDF: HDF error); nothing was written". The CLI exits with status 2.
  Clean-up errors never replace the first error.
* **Space is checked first** where the size is known (:func:`check_free_space`).
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from ..errors import OutputWriteError, ParameterTypeError, TippeError
from ..interrupts import Temporary, checkpoint

__all__ = [
    "TEMPORARY_PREFIX",
    "atomic_output",
    "check_free_space",
    "check_output_path",
    "close_quietly",
    "commit",
    "describe_kind",
    "temporary_name",
    "write_error",
]

#: temporary files are ``<dir>/.tippe-tmp-XXXXXXXX-<name>``: hidden, unique, and ending with the
#: target's name, so that their suffix is the target's (a figure's format is read off it)
TEMPORARY_PREFIX = ".tippe-tmp-"

#: error numbers that mean "the file could not be written" -> the cause as the message says it
_WRITE_ERRNOS: dict[int, str] = {
    errno.ENOSPC: "no space left on the file system holding {dir}",
    errno.EFBIG: "file size limit reached",
    errno.EROFS: "the file system holding {dir} is read-only",
    errno.EIO: "input/output error on the file system holding {dir}",
}
if hasattr(errno, "EDQUOT"):
    _WRITE_ERRNOS[errno.EDQUOT] = "disk quota exceeded on the file system holding {dir}"

#: errors of the no-replace primitives that mean "not supported here": try the next one
_UNSUPPORTED = {
    errno.EINVAL,
    errno.ENOSYS,
    errno.EPERM,
    errno.EXDEV,
    errno.EMLINK,
    getattr(errno, "ENOTSUP", errno.EINVAL),
    getattr(errno, "EOPNOTSUPP", errno.EINVAL),
}


# --- what a path is ------------------------------------------------------------------------------


def describe_kind(mode: int) -> str:
    """What a file mode is, in words: ``"a FIFO (named pipe)"``, ``"a symbolic link"``, ..."""
    for test, text in (
        (stat.S_ISREG, "a regular file"),
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISLNK, "a symbolic link"),
        (stat.S_ISFIFO, "a FIFO (named pipe)"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return text
    return "not a regular file"


def _lstat(p: Path) -> os.stat_result | None:
    try:
        return os.lstat(p)
    except (FileNotFoundError, NotADirectoryError):  # the directory's problem is reported next
        return None


def _as_path(what: str, path: object) -> Path:
    """A non-empty path-like as a Path, or a TypeError naming ``what``."""
    if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
        raise ParameterTypeError(f"{what} = {path!r} must be a file name (a non-empty str or path-like)")
    return Path(path)


def _refuse_existing(p: Path, st: os.stat_result, overwrite: bool) -> None:
    """Refuse an existing ``p`` unless it is a regular file and ``overwrite``."""
    if stat.S_ISDIR(st.st_mode):
        raise IsADirectoryError(f"output path {str(p)!r} is a directory; give a file name")
    if not stat.S_ISREG(st.st_mode):
        raise FileExistsError(
            f"output path {str(p)!r} is {describe_kind(st.st_mode)}; only a regular file can be "
            "replaced: remove it or choose another name"
        )
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
    p = _as_path("output path", path)
    if not isinstance(overwrite, bool):
        raise ParameterTypeError(f"overwrite = {overwrite!r} must be True or False")
    st = _lstat(p)
    if st is not None:
        _refuse_existing(p, st, overwrite)
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.exists():
        raise FileNotFoundError(f"output directory {str(parent)!r} of {str(p)!r} does not exist")
    if not parent.is_dir():
        raise NotADirectoryError(f"output directory {str(parent)!r} of {str(p)!r} is not a directory")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise PermissionError(f"output directory {str(parent)!r} of {str(p)!r} is not writable")
    # permission bits do not tell everything (root, read-only mounts, pseudo file systems):
    # create and remove a probe file, which is what writing will need
    try:
        fd, probe = tempfile.mkstemp(prefix=TEMPORARY_PREFIX, suffix=".probe", dir=parent)
    except OSError as exc:
        raise PermissionError(
            f"output directory {str(parent)!r} of {str(p)!r} is not writable ({exc.strerror})"
        ) from None
    os.close(fd)
    os.unlink(probe)
    return p


def _directory(p: Path) -> Path:
    return p.parent if str(p.parent) else Path(".")


def _fmt_bytes(n: float) -> str:
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{int(n)} bytes"


def check_free_space(path: str | os.PathLike, nbytes: float) -> None:
    """Refuse, before computing, an output of about ``nbytes`` that cannot fit: the free space of
    the file system holding ``path`` (``statvfs``, space available to this user) and the file
    size limit (``ulimit -f``, ``RLIMIT_FSIZE``). Unknown limits are not checked.

    Raises
    ------
    OutputWriteError
        With ``errno`` ENOSPC or EFBIG, naming the file, the size and the limit.
    """
    p = Path(path)
    d = _directory(p)
    try:
        vfs = os.statvfs(d)
        free = vfs.f_bavail * vfs.f_frsize
    except (OSError, AttributeError):
        free = None
    if free is not None and nbytes > free:
        raise OutputWriteError(
            f"cannot write {str(p)!r}: the output needs about {_fmt_bytes(nbytes)} and the file "
            f"system holding {str(d)!r} has {_fmt_bytes(free)} free; nothing was written",
            errno.ENOSPC,
            str(p),
        )
    limit = _fsize_limit()
    if limit is not None and nbytes > limit:
        raise OutputWriteError(
            f"cannot write {str(p)!r}: the output needs about {_fmt_bytes(nbytes)}, above the file "
            f"size limit (ulimit -f) of {limit} bytes; nothing was written",
            errno.EFBIG,
            str(p),
        )


def _fsize_limit() -> int | None:
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_FSIZE)
    except (ImportError, OSError, ValueError, AttributeError):
        return None
    return None if soft == resource.RLIM_INFINITY or soft < 0 else int(soft)


# --- the commit --------------------------------------------------------------------------------


def _noreplace_call() -> Any:
    """``(function, flags)`` of the system's atomic no-replace rename, or None."""
    if not (sys.platform.startswith("linux") or sys.platform == "darwin"):
        return None
    import ctypes

    try:
        libc = ctypes.CDLL(None, use_errno=True)
        if sys.platform == "darwin":  # pragma: no cover - not on the test machines
            fn = libc.renamex_np
            fn.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint]
            fn.restype = ctypes.c_int
            return lambda src, dst: fn(src, dst, 0x4)  # RENAME_EXCL
        fn = libc.renameat2
    except (OSError, AttributeError):
        return None
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    at_fdcwd, rename_noreplace = -100, 1
    return lambda src, dst: fn(at_fdcwd, src, at_fdcwd, dst, rename_noreplace)


_NOREPLACE: list = []


def _rename_noreplace_syscall(src: str, dst: str) -> bool:
    """Rename atomically unless ``dst`` exists; False if the system does not support it here."""
    if not _NOREPLACE:
        _NOREPLACE.append(_noreplace_call())
    call = _NOREPLACE[0]
    if call is None:
        return False
    import ctypes

    if call(os.fsencode(src), os.fsencode(dst)) == 0:
        return True
    e = ctypes.get_errno()
    if e == errno.EEXIST:
        raise FileExistsError(e, os.strerror(e), dst)
    if e in _UNSUPPORTED:
        return False
    raise OSError(e, os.strerror(e), dst)


def _link_noreplace(src: str, dst: str) -> bool:
    """``link`` then ``unlink``; False if the file system has no hard links."""
    try:
        os.link(src, dst)
    except FileExistsError:
        raise
    except OSError as exc:
        if exc.errno in _UNSUPPORTED or exc.errno == errno.EACCES:
            return False
        raise
    os.unlink(src)
    return True


def _exclusive_noreplace(src: str, dst: str) -> bool:
    """Reserve ``dst`` with ``O_CREAT | O_EXCL``, then rename over the placeholder."""
    fd = os.open(dst, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600)
    os.close(fd)
    os.replace(src, dst)
    return True


#: the no-replace primitives in order of preference (the module docstring)
NOREPLACE_METHODS = (_rename_noreplace_syscall, _link_noreplace, _exclusive_noreplace)


def _rename_noreplace(src: str, dst: str) -> None:
    if os.name == "nt":  # pragma: no cover - os.rename refuses an existing target there
        os.rename(src, dst)
        return
    for method in NOREPLACE_METHODS:
        if method(src, dst):
            return
    raise OSError(errno.ENOTSUP, "no way to rename without replacing", dst)  # pragma: no cover


def commit(tmp: Temporary, target: Path, *, overwrite: bool) -> None:
    """Rename the complete temporary file ``tmp`` to ``target``: the last interruption point.

    With ``overwrite=False`` the rename refuses an existing target atomically; with
    ``overwrite=True`` it replaces only a regular file (the module docstring).

    Raises
    ------
    FileExistsError
        The target appeared meanwhile (another process), or is not a regular file.
    KeyboardInterrupt
        A signal is pending (:func:`stability.interrupts.checkpoint`): nothing is committed.
    """
    checkpoint()
    tmp.committing()
    try:
        if overwrite:
            st = _lstat(target)
            if st is not None:
                _refuse_existing(target, st, True)
            os.replace(tmp.path, target)
        else:
            try:
                _rename_noreplace(tmp.path, str(target))
            except FileExistsError:
                raise FileExistsError(
                    f"output file {str(target)!r} was created by another process while this run was "
                    "computing; nothing was written (pass overwrite=True to replace it)"
                ) from None
    except BaseException:
        tmp.state = "writing"
        raise
    tmp.done(committed=True)


def temporary_name(target: Path) -> str:
    """Create an empty, unique temporary file next to ``target``; return its name."""
    fd, name = tempfile.mkstemp(prefix=TEMPORARY_PREFIX, suffix="-" + target.name, dir=_directory(target))
    os.close(fd)
    return name


def _remove(tmp: Temporary) -> None:
    """Remove a temporary file; an error here never replaces the error being handled."""
    with contextlib.suppress(OSError):
        os.unlink(tmp.path)
    tmp.done(committed=False)


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
    writing is translated by :func:`write_error`. The final file gets the usual permissions
    (umask).
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
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp.path, 0o666 & ~umask)
        commit(tmp, p, overwrite=overwrite)
    finally:
        if tmp.state != "committed":
            _remove(tmp)


# --- translating write errors --------------------------------------------------------------------


def _chain(exc: BaseException) -> Iterator[BaseException]:
    seen = set()
    e: BaseException | None = exc
    while e is not None and id(e) not in seen:
        seen.add(id(e))
        yield e
        e = e.__cause__ or e.__context__


def _is_library_write_error(exc: BaseException) -> bool:
    """netCDF4 and h5 report a failed write as a RuntimeError "NetCDF: ..." (no errno)."""
    text = str(exc)
    return (type(exc) is RuntimeError and ("NetCDF" in text or "HDF" in text)) or type(exc).__name__ in (
        "HDF5ExtError",
        "NetCDF4Error",
    )


def write_error(
    exc: BaseException, target: Path, tmp: str | None = None, what: str | None = None
) -> OutputWriteError | None:
    """The :class:`~stability.errors.OutputWriteError` for a failure while writing ``target``,
    or None if ``exc`` is not a write failure (bad input, an interruption, a failed computation
    are passed on as they are).

    Parameters
    ----------
    exc : BaseException
    target : Path
        The output file (named in the message).
    tmp : str, optional
        The temporary file being written (its size is compared with the file size limit).
    what : str, optional
        The file named in the message, if not ``target`` (a chunk file of a chunk store).
    """
    if isinstance(exc, (KeyboardInterrupt, SystemExit, GeneratorExit, OutputWriteError)):
        return None
    if isinstance(exc, TippeError) and not isinstance(exc, OSError):
        return None
    found = None
    for e in _chain(exc):
        if isinstance(e, OSError) and e.errno in _WRITE_ERRNOS:
            found = e
            break
    library = any(_is_library_write_error(e) for e in _chain(exc))
    own_file = (
        isinstance(exc, OSError)
        and exc.filename is not None
        and tmp is not None
        and os.path.abspath(str(exc.filename)) == os.path.abspath(tmp)
    )
    if found is None and not library and not own_file:
        return None
    name = what or str(target)
    d = str(_directory(Path(target)))
    detail = " ".join(str(exc).split())[:160]
    if found is not None:
        code = found.errno
        cause = _WRITE_ERRNOS[code].format(dir=repr(d))
        if code == errno.EFBIG:
            cause = _fsize_text() or cause
    else:
        code, cause = _diagnose(d, tmp)
    return OutputWriteError(f"cannot write {name!r}: {cause} ({detail}); nothing was written", code, name)


def _fsize_text() -> str | None:
    limit = _fsize_limit()
    return None if limit is None else f"file size limit (ulimit -f) of {limit} bytes reached"


def _diagnose(directory: str, tmp: str | None) -> tuple[int | None, str]:
    """The probable cause of a write failure that carries no error number, found now."""
    try:
        vfs = os.statvfs(directory)
        if vfs.f_flag & getattr(os, "ST_RDONLY", 1):
            return errno.EROFS, f"the file system holding {directory!r} is read-only"
        free = vfs.f_bavail * vfs.f_frsize
        if free < 1_000_000:
            return errno.ENOSPC, f"no space left on the file system holding {directory!r} ({_fmt_bytes(free)} free)"
    except (OSError, AttributeError):
        pass
    limit = _fsize_limit()
    if limit is not None:
        size = 0
        with contextlib.suppress(OSError, TypeError):
            size = os.path.getsize(tmp) if tmp else 0
        if size + 1_000_000 >= limit:
            return errno.EFBIG, f"file size limit (ulimit -f) of {limit} bytes reached"
    return None, "the netCDF/HDF5 library reported an error"


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
