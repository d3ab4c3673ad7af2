"""Datasets on disk: netCDF writing in bounded slabs, and reading an atlas back with checks.

* :func:`write_dataset` writes any dataset of the package through
  :func:`stability.files.atomic_output` (a temporary file committed only when complete; no
  partial file; an existing file kept unless ``overwrite=True``; the refusal holds at the moment
  of the commit) with xarray's public ``to_netcdf``. Large variables are written in slabs of at
  most :data:`SLAB_BYTES` along their first dimension (as dask arrays, ``compute=False``), with an
  interruption point between slabs, so that Ctrl-C or SIGTERM is acted on within one slab (a
  fraction of a second) whatever the size.
* :func:`open_atlas` reads an atlas back and checks it with
  :func:`stability.grids.schema.validate_atlas`, slab by slab, before loading it; a file larger
  than the memory available is refused unless opened lazily (``chunks=``).
"""

from __future__ import annotations

import importlib.util
import os
import stat
import warnings
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..errors import AtlasFileError, ParameterTypeError
from ..files import atomic_output, check_output_path, describe_kind
from ..interrupts import checkpoint, deferred
from ..products import PRODUCT_ATTR
from .schema import ATLAS_VARIABLES, require_atlas, validate_atlas

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["ATLAS_VARIABLES", "PRODUCT_ATTR", "SLAB_BYTES", "atomic_output", "check_output_path", "open_atlas"]
__all__ += ["require_atlas", "write_dataset"]

#: largest piece of a variable written in one step (an interruption point between pieces)
SLAB_BYTES = 16 * 2**20


def _checked(block: np.ndarray) -> np.ndarray:
    """A slab of a variable on its way to the file: the interruption point between slabs."""
    checkpoint()
    return block


class _Slabs:
    """A numpy array as dask reads it, slab by slab, with an interruption point before each (not
    an array itself: ``dask.array.from_array`` would copy an array whole)."""

    def __init__(self, values: np.ndarray) -> None:
        self.values, self.shape, self.dtype, self.ndim = values, values.shape, values.dtype, values.ndim

    def __getitem__(self, key: object) -> np.ndarray:
        checkpoint()
        return self.values[key]


def _to_netcdf(ds: xr.Dataset, tmp: str) -> None:
    """``ds.to_netcdf(tmp)`` (xarray's public writer: the file is the one it writes). Every data
    variable above :data:`SLAB_BYTES`, and every dask-backed one, goes as dask slabs along its
    first dimension (``compute=False``, then dask's synchronous scheduler in this thread) with
    an interruption point before each, so that a signal is acted on between slabs and a lazy
    variable is never held whole in memory; a small dataset, or one without dask, in one call."""
    checkpoint()
    large = [k for k, v in ds.data_vars.items() if v.chunks is not None or (v.ndim and v.nbytes > SLAB_BYTES)]
    if large and importlib.util.find_spec("dask") is not None:
        import dask.array as da

        out = ds.copy(deep=False)
        for k in large:
            v = ds[k]
            if v.chunks is None:  # slabs read from the array itself (xarray's chunk() was 3x slower)
                rows = max(1, SLAB_BYTES * v.shape[0] // v.nbytes)
                data = da.from_array(_Slabs(v.values), chunks=(rows, *v.shape[1:]), name=False, meta=v.values[:0])
            else:
                data = da.map_blocks(_checked, v.data, dtype=v.dtype)
            out[k] = v.copy(deep=False, data=data)
        out.to_netcdf(tmp, format="NETCDF4", compute=False).compute(scheduler="synchronous")
    else:
        ds.to_netcdf(tmp, format="NETCDF4")
    checkpoint()


def write_dataset(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Write ``ds`` to netCDF at ``path`` atomically.

    Parameters
    ----------
    ds : xarray.Dataset
    path : path-like
        Target file: a new name, or an existing regular file with ``overwrite=True``.
    overwrite : bool, default False
        Replace an existing file.

    Returns
    -------
    pathlib.Path
        The written path.

    Raises
    ------
    FileExistsError
        The file exists (or was created by another process while this one was writing) and
        ``overwrite`` is False, or the path is not a regular file.
    stability.errors.OutputWriteError
        The file could not be written (no space left, the file size limit, ...): the message
        names the file and the cause; nothing is left behind.
    """
    import xarray as xr  # here: checking an output path imports no xarray (tippe --help)

    if not isinstance(ds, xr.Dataset):
        raise ParameterTypeError(f"ds must be an xarray.Dataset, got {type(ds).__name__}")
    with deferred(), atomic_output(path, overwrite=overwrite, expected_bytes=float(ds.nbytes)) as tmp:
        _to_netcdf(ds, tmp)
    return Path(path)


def open_atlas(path: str | os.PathLike, *, chunks: int | dict[str, int] | None = None) -> xr.Dataset:
    """Read an atlas written by :func:`stability.atlas` (or ``tippe atlas``).

    Parameters
    ----------
    path : path-like
        A netCDF file, or a Zarr store (a directory whose name ends in ``.zarr``,
        :mod:`stability.grids.store`).
    chunks : int or dict, optional
        Open lazily with dask chunks of these sizes (the file stays open until ``ds.close()``),
        for an atlas larger than memory. By default the atlas is loaded and the file closed.

    Returns
    -------
    xarray.Dataset

    Raises
    ------
    AtlasFileError
        The file is missing, not a regular file, unreadable (truncated, not netCDF), not an
        atlas of this package, or breaks the atlas layout (wrong data types, dimensions, flag
        values, NaN where a point is inside the domain, ...:
        :mod:`stability.grids.schema`); the message names the file and the rule.
    stability.errors.ResourceError
        Loading it would need more memory than is available (pass ``chunks=``).
    """
    import xarray as xr

    from ..resources import check_memory
    from .store import is_store_path, open_store

    store = isinstance(path, (str, os.PathLike)) and is_store_path(path) and Path(path).is_dir()
    p = Path(path if store else _atlas_path(path))
    try:
        ds = open_store(p) if store else xr.open_dataset(p)
    except Exception as exc:  # netCDF4/h5/zarr raise OSError, ValueError or their own types
        raise _unreadable(p, exc) from None
    try:
        product = ds.attrs.get(PRODUCT_ATTR)
        if product != "atlas":
            raise AtlasFileError(
                f"atlas file {str(p)!r} is not an atlas of tippe-stability: it has no global attribute "
                f"{PRODUCT_ATTR!r} (written by another program, or by xarray directly; stability.atlas and "
                "tippe atlas set it)"
                if product is None
                else f"atlas file {str(p)!r} is not an atlas: it is a {product!r} file of tippe-stability "
                "(open it with xarray.open_dataset)"
            )
        try:  # "not a complete atlas: missing variables ...", or the rule it breaks
            validate_atlas(
                ds, lambda text: AtlasFileError(f"atlas file {str(p)!r} is not a {_what(text)} atlas: {text}")
            )
        except AtlasFileError:
            raise
        except Exception as exc:  # a slab that cannot be read: the file is damaged past its header
            raise _unreadable(p, exc) from None
        if ds.attrs.get("model") == "rolling" and ds.attrs.get("model_equations") == "(8)-(9)":
            warnings.warn(
                f"atlas file {str(p)!r} was written by {ds.attrs.get('source', 'an older version')}: "
                "its model 'rolling' is eq. (8) as printed, which is now called 'rolling_eq8' "
                "('rolling' is now the rolling top from first principles)",
                FutureWarning,
                stacklevel=2,
            )
        if chunks is not None:
            return ds.chunk(chunks)
        check_memory(
            float(ds.nbytes),
            what=f"open_atlas({str(p)!r})",
            parameter="the file's size",
            way_out="pass chunks= (e.g. chunks=1000) to open it lazily, or select a slice with "
            "xarray.open_dataset(path).isel(...)",
        )
        try:
            loaded = ds.load()
        except Exception as exc:
            raise _unreadable(p, exc) from None
        ds.close()
        return loaded
    except BaseException:
        ds.close()
        raise


def _what(text: str) -> str:
    return "complete" if text.startswith("missing variables") else "valid"


def _atlas_path(path: object) -> str:
    """Check that ``path`` names a readable regular file; say what it is otherwise."""
    if not isinstance(path, (str, os.PathLike)) or not str(path).strip():
        raise ParameterTypeError(f"atlas path = {path!r} must be a file name (a non-empty str or path-like)")
    p = str(path)
    try:
        st = os.stat(p)
    except OSError as exc:
        why = "does not exist" if isinstance(exc, FileNotFoundError) else f"cannot be read ({exc.strerror})"
        raise AtlasFileError(f"atlas file {p!r} {why}") from None
    if not stat.S_ISREG(st.st_mode) or st.st_size == 0:
        what = "empty (0 bytes)" if stat.S_ISREG(st.st_mode) else describe_kind(st.st_mode)
        raise AtlasFileError(f"atlas file {p!r} is {what}, not a netCDF file")
    if not os.access(p, os.R_OK):
        raise AtlasFileError(f"atlas file {p!r} is not readable (permission denied)")
    return p


def _unreadable(p: Path, exc: BaseException) -> AtlasFileError:
    cause = f"{type(exc).__name__}: {' '.join(str(exc).split())[:120]}"
    if p.is_dir():  # a Zarr store: the chunk file that does not read
        from .store import damaged_chunk

        chunk = damaged_chunk(p)
        where = f"its chunk file {chunk!r} is damaged" if chunk else "it cannot be read"
        return AtlasFileError(f"atlas store {str(p)!r} is not a readable Zarr store: {where} ({cause})")
    with open(p, "rb") as f:
        head = f.read(8)
    if head.startswith((b"\x89HDF", b"CDF")):
        return AtlasFileError(
            f"atlas file {str(p)!r} is not a readable netCDF file: it cannot be read to the end "
            f"(truncated or damaged: {cause})"
        )
    return AtlasFileError(
        f"atlas file {str(p)!r} is not a readable netCDF file (it does not start with a netCDF or HDF5 signature)"
    )
