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

import xarray as xr

__all__ = ["AtlasFileError", "atomic_output", "check_output_path", "write_dataset", "open_atlas", "PRODUCT_ATTR"]

#: global attribute naming which product of this package a dataset is
PRODUCT_ATTR = "tippe_stability_product"

ATLAS_VARIABLES = ("growth_rate", "frequency", "max_growth_rate", "stability")


class AtlasFileError(ValueError):
    """A file given where an atlas is expected is missing, unreadable or not an atlas."""


def check_output_path(path: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Fail early (before any computation) if ``path`` cannot be written.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``overwrite`` is False.
    FileNotFoundError, PermissionError
        The directory does not exist or is not writable.
    """
    p = Path(path)
    if p.is_dir():
        raise IsADirectoryError(f"output path {str(p)!r} is a directory; give a file name")
    if p.exists() and not overwrite:
        raise FileExistsError(f"output file {str(p)!r} exists; pass overwrite=True (--overwrite) to replace it")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise FileNotFoundError(f"output directory {str(parent)!r} does not exist")
    if not os.access(parent, os.W_OK):
        raise PermissionError(f"output directory {str(parent)!r} is not writable")
    return p


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
    p = Path(path)
    if not p.is_file():
        raise AtlasFileError(f"atlas file {str(p)!r} does not exist")
    try:
        with xr.open_dataset(p) as ds:
            ds = ds.load()
    except Exception as exc:  # netCDF4/h5 raise OSError, ValueError or their own types
        raise AtlasFileError(f"{str(p)!r} is not a readable netCDF file ({type(exc).__name__}: {exc})") from None
    if ds.attrs.get(PRODUCT_ATTR) != "atlas":
        raise AtlasFileError(f"{str(p)!r} is not an atlas of tippe-stability "
                             f"(its global attribute {PRODUCT_ATTR!r} is {ds.attrs.get(PRODUCT_ATTR)!r})")
    missing = [v for v in ATLAS_VARIABLES if v not in ds]
    if missing:
        raise AtlasFileError(f"{str(p)!r} is not a complete atlas: missing variables {', '.join(missing)}")
    return ds
