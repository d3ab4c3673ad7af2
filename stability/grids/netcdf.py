"""Datasets on disk: atomic netCDF writing, and reading an atlas back with checks.

Writing goes to a temporary file in the target's directory, renamed over the target only when
complete (``os.replace`` is atomic on one file system): an interrupted or failed run leaves
no partial file, and an existing file is kept unless ``overwrite=True``.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import AtlasFileError
from ..products import PRODUCT_ATTR

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["atomic_output", "check_output_path", "write_dataset", "open_atlas", "PRODUCT_ATTR",
           "require_atlas"]

ATLAS_VARIABLES = ("growth_rate", "frequency", "max_growth_rate", "stability")


def require_atlas(ds: object, name: str = "ds") -> xr.Dataset:
    """``ds`` itself if it is an atlas dataset (the variables of :data:`ATLAS_VARIABLES`);
    otherwise a ``TypeError`` (not a Dataset) or ``ValueError`` (which variables are missing)."""
    import xarray as xr  # here: checking an output path imports no xarray (tippe --help)

    if not isinstance(ds, xr.Dataset):
        raise TypeError(f"{name} is a {type(ds).__name__}; it must be an atlas, an xarray.Dataset from "
                        "stability.atlas or stability.open_atlas")
    missing = [v for v in ATLAS_VARIABLES if v not in ds]
    if missing:
        raise ValueError(f"{name} has no {', '.join(missing)}: it is not an atlas (stability.atlas or "
                         f"stability.open_atlas; a simulate() run or a neutral curve has its own plots)")
    return ds


def check_output_path(path: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Fail early (before any computation) if ``path`` cannot be written.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``overwrite`` is False.
    FileNotFoundError, PermissionError
        The directory does not exist or is not writable.
    """
    p = _as_path("output path", path)
    if not isinstance(overwrite, bool):
        raise TypeError(f"overwrite = {overwrite!r} must be True or False")
    if p.is_dir():
        raise IsADirectoryError(f"output path {str(p)!r} is a directory; give a file name")
    if (p.exists() or p.is_symlink()) and not overwrite:
        raise FileExistsError(f"output file {str(p)!r} exists; pass overwrite=True to replace it")
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
        fd, probe = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".probe", dir=parent)
    except OSError as exc:
        raise PermissionError(f"output directory {str(parent)!r} of {str(p)!r} is not writable "
                              f"({exc.strerror})") from None
    os.close(fd)
    os.unlink(probe)
    return p


def _as_path(what: str, path: object) -> Path:
    """A non-empty path-like as a Path, or a TypeError naming ``what``."""
    if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
        raise TypeError(f"{what} = {path!r} must be a file name (a non-empty str or path-like)")
    return Path(path)


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike, *, overwrite: bool = False) -> Iterator[str]:
    """Yield a temporary file name next to ``path``; rename it to ``path`` only on success.

    The temporary file is removed on any exception (including ``KeyboardInterrupt``), so no
    partial output is ever left; the final file gets the usual permissions (umask).
    """
    p = check_output_path(path, overwrite=overwrite)
    directory = p.parent if str(p.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp" + p.suffix, dir=directory)
    os.close(fd)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, p)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def write_dataset(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Write ``ds`` to netCDF at ``path`` atomically.

    Parameters
    ----------
    ds : xarray.Dataset
    path : path-like
        Target file.
    overwrite : bool, default False
        Replace an existing file.

    Returns
    -------
    pathlib.Path
        The written path.
    """
    import xarray as xr  # here: checking an output path imports no xarray (tippe --help)

    if not isinstance(ds, xr.Dataset):
        raise TypeError(f"ds must be an xarray.Dataset, got {type(ds).__name__}")
    with atomic_output(path, overwrite=overwrite) as tmp:
        ds.to_netcdf(tmp, format="NETCDF4")
    return Path(path)


def open_atlas(path: str | os.PathLike) -> xr.Dataset:
    """Read an atlas written by :func:`stability.atlas` (or ``tippe atlas``).

    Parameters
    ----------
    path : path-like

    Returns
    -------
    xarray.Dataset
        Loaded into memory (the file is closed).

    Raises
    ------
    AtlasFileError
        The file is missing, unreadable (truncated, not netCDF) or not an atlas of this
        package; the message names the file.
    """
    import xarray as xr  # here: checking an output path imports no xarray (tippe --help)

    p = _as_path("atlas path", path)
    if p.is_dir():
        raise AtlasFileError(f"atlas file {str(p)!r} is a directory, not a netCDF file")
    if not p.is_file():
        raise AtlasFileError(f"atlas file {str(p)!r} does not exist")
    if not os.access(p, os.R_OK):
        raise AtlasFileError(f"atlas file {str(p)!r} is not readable (permission denied)")
    if p.stat().st_size == 0:
        raise AtlasFileError(f"atlas file {str(p)!r} is empty (0 bytes), not a netCDF file")
    try:
        with xr.open_dataset(p) as ds:
            ds = ds.load()
    except Exception as exc:  # netCDF4/h5 raise OSError, ValueError or their own types
        with open(p, "rb") as f:
            head = f.read(8)
        if head.startswith((b"\x89HDF", b"CDF")):
            raise AtlasFileError(f"atlas file {str(p)!r} is not a readable netCDF file: it cannot be read to "
                                 f"the end (truncated or damaged: {type(exc).__name__}: "
                                 f"{' '.join(str(exc).split())[:120]})") from None
        raise AtlasFileError(f"atlas file {str(p)!r} is not a readable netCDF file (it does not start "
                             "with a netCDF or HDF5 signature)") from None
    if ds.attrs.get(PRODUCT_ATTR) != "atlas":
        raise AtlasFileError(f"atlas file {str(p)!r} is not an atlas of tippe-stability: a netCDF file "
                             f"whose global attribute {PRODUCT_ATTR!r} is {ds.attrs.get(PRODUCT_ATTR)!r}, "
                             "not 'atlas'")
    missing = [v for v in ATLAS_VARIABLES if v not in ds]
    if missing:
        raise AtlasFileError(f"atlas file {str(p)!r} is not a complete atlas: missing variables {', '.join(missing)}")
    return ds
