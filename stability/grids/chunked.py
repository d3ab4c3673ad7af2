"""Atlases beyond memory and beyond one machine: lazy, chunked spectra and chunk-wise writing.

* :func:`lazy_spectra` (used by ``atlas(..., chunks=...)``) builds dask arrays with
  :func:`xarray.apply_ufunc` (``dask="parallelized"``): each chunk of the grid is one call of
  :func:`stability.spectrum` on that chunk's coordinates. The domain is checked before any
  chunk is computed (a refused grid refuses at once, as the in-memory atlas does).
* :func:`write_atlas` writes such a dataset to netCDF chunk by chunk: the file is created
  (dimensions, coordinates, attributes, as xarray writes them) under a temporary name next to
  the target; each chunk is computed (in this process, or on a dask.distributed cluster), written
  into its region and dropped; the file is renamed over the target only when complete
  (:func:`stability.grids.netcdf.atomic_output`). Memory stays at a few chunks whatever the grid size;
  an interruption leaves no output file.
* Resuming: with ``resume=True`` every finished chunk is also kept in a sidecar directory
  ``<output>.parts/`` (one ``.npz`` per chunk, each renamed into place when complete, and a
  manifest naming the atlas). A rerun with the same arguments reads the chunks found there and
  computes only the others; the directory is removed once the output file is in place. A
  sidecar written for a different atlas (other grid, model, method, chunks or package version)
  is refused with the reason, never mixed in.
* Where the chunks run: in this process by default, or on a dask.distributed cluster given as
  ``client`` (:func:`stability.grids.cluster.dask_client`).
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
from collections.abc import Callable
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..errors import ChunkError, ResumeError
from .leading import leading, zero_everywhere
from .netcdf import atomic_output, check_output_path
from ..models import LinearModel
from ..parameters import check_domain, check_flag, check_integer

__all__ = ["lazy_spectra", "normalize_chunks", "write_atlas", "parts_directory"]

#: per-chunk variables (the rest, max_growth_rate, follows from growth_rate)
_BLOCK_VARIABLES = ("growth_rate", "frequency", "eigenvalue_error_bound", "stability", "physical")


def normalize_chunks(chunks: int | dict[str, int], dims: list[str], sizes: dict[str, int]) -> dict[str, int]:
    """Chunk sizes along every grid dimension.

    Parameters
    ----------
    chunks : int or dict
        One size for every dimension, or sizes by dimension (the others whole).
    dims : list of str
        Grid dimensions.
    sizes : dict
        Their lengths.

    Returns
    -------
    dict of str to int

    Raises
    ------
    ValueError
        A size below 1 or a dimension the grid does not have.
    """
    if isinstance(chunks, dict):
        unknown = [k for k in chunks if k not in dims]
        if unknown:
            raise ValueError(f"chunks name {', '.join(map(repr, unknown))}, not grid dimensions "
                             f"(the grid has {', '.join(dims) or 'none'})")
        out = {d: check_integer(f"chunks[{d!r}]", chunks[d], minimum=1) if d in chunks else sizes[d]
               for d in dims}
    else:
        size = check_integer("chunks", chunks, minimum=1)
        out = {d: size for d in dims}
    return {d: min(v, sizes[d]) for d, v in out.items()}


def _check_grid_domain(values: dict[str, np.ndarray], dims: list[str], mask: bool) -> None:
    """Refuse a grid with a point outside the domain without building the whole grid.

    The bounds couple only (q, sigma, mu); fr_inv and alpha_v are checked alone.
    """
    if mask:
        return

    def shaped(k: str) -> np.ndarray:
        v = values[k]
        if v.ndim == 0:
            return v
        shape = [1] * len(dims)
        shape[dims.index(k)] = v.size
        return v.reshape(shape)

    check_domain(mask=False, **{k: shaped(k) for k in ("q", "sigma", "mu") if k in values})
    for k in ("fr_inv", "alpha_v"):
        if k in values:
            check_domain(mask=False, **{k: values[k]})


def _block_spectra(*args: np.ndarray, model: LinearModel, names: tuple[str, ...], mask: bool,
                   method: str) -> tuple[np.ndarray, ...]:
    """Spectra of one chunk: growth rate, frequency, bound, flag, physical."""
    from ..linear.spectra import spectrum

    p = dict(zip(names, args))
    shape = np.broadcast_shapes(*(np.shape(a) for a in args))
    sp = spectrum(model, mask_unphysical=mask, method=method, **p)
    n = model.n_modes
    ev = np.broadcast_to(sp.eigenvalues, shape + (n,))
    return (np.ascontiguousarray(ev.real), np.ascontiguousarray(ev.imag),
            np.broadcast_to(sp.error_bound, shape + (n,)).copy(),
            np.broadcast_to(sp.stability, shape).astype(np.int8),
            np.broadcast_to(sp.inside, shape).astype(np.int8))


def lazy_spectra(model: LinearModel, values: dict[str, np.ndarray], dims: list[str],
                 chunks: int | dict[str, int], *, mask_unphysical: bool, method: str) -> tuple:
    """Dask-backed spectra over a grid (see module docstring).

    Parameters
    ----------
    model : LinearModel
    values : dict of numpy.ndarray
        Parameters, 0-d (scalar coordinates) or 1-D (grid dimensions).
    dims : list of str
        Grid dimensions, in order.
    chunks : int or dict
        See :func:`normalize_chunks`.
    mask_unphysical : bool
        As for :func:`stability.atlas`.
    method : str
        Eigenvalue method.

    Returns
    -------
    tuple of dask.array.Array
        growth rate, frequency, error bound (grid + mode), stability flag and physical flag
        (grid).
    """
    from ..linear.spectra import METHODS

    if method not in METHODS:
        raise ValueError(f"method = {method!r} is not known; choose one of {', '.join(METHODS)}")
    sizes = {d: values[d].size for d in dims}
    ch = normalize_chunks(chunks, dims, sizes)
    _check_grid_domain(values, dims, mask_unphysical)
    names = tuple(values)
    inputs = []
    for k in names:
        v = values[k]
        inputs.append(xr.DataArray(v, dims=(k,)).chunk({k: ch[k]}) if v.ndim == 1 else xr.DataArray(v))
    n = model.n_modes
    out = xr.apply_ufunc(
        _block_spectra, *inputs,
        kwargs=dict(model=model, names=names, mask=mask_unphysical, method=method),
        input_core_dims=[[]] * len(inputs),
        output_core_dims=[["mode"], ["mode"], ["mode"], [], []],
        dask="parallelized",
        output_dtypes=[np.float64, np.float64, np.float64, np.int8, np.int8],
        dask_gufunc_kwargs={"output_sizes": {"mode": n}},
    )
    arrays = []
    for da in out:
        order = [d for d in dims if d in da.dims] + (["mode"] if "mode" in da.dims else [])
        da = da.transpose(*order)
        data = da.data
        if da.ndim != len(dims) + ("mode" in da.dims):  # pragma: no cover - a 0-d grid
            raise AssertionError("grid dimensions lost")
        arrays.append(data)
    return tuple(arrays)


# --- writing -----------------------------------------------------------------------------------

def _create_skeleton(ds: xr.Dataset, path: str, chunk_shape: dict[str, int]) -> None:
    """Create the netCDF file: dimensions, coordinates and attributes as xarray writes them,
    data variables defined (chunked like the dataset) but not yet written."""
    import netCDF4

    scalar_coords = [k for k, c in ds.coords.items() if c.ndim == 0]
    with netCDF4.Dataset(path, "w", format="NETCDF4") as nc:
        for d, n in ds.sizes.items():
            nc.createDimension(d, n)
        for k, c in ds.coords.items():
            fill = np.nan if c.dtype.kind == "f" else None
            var = nc.createVariable(k, c.dtype, c.dims, fill_value=fill)
            var.setncatts(dict(c.attrs))
            var[...] = c.values
        for k, v in ds.data_vars.items():
            fill = np.nan if v.dtype.kind == "f" else None
            cs = [chunk_shape.get(d, ds.sizes[d]) for d in v.dims]
            var = nc.createVariable(k, v.dtype, v.dims, fill_value=fill, chunksizes=cs or None,
                                    contiguous=not cs)
            attrs = dict(v.attrs)
            if scalar_coords:
                attrs["coordinates"] = " ".join(scalar_coords)
            var.setncatts(attrs)
        nc.setncatts(dict(ds.attrs))


def parts_directory(path: str | os.PathLike) -> Path:
    """The sidecar chunk store of an output file: ``<output>.parts/``."""
    p = Path(path)
    return p.with_name(p.name + ".parts")


def _identity(ds: xr.Dataset, chunk_shape: dict[str, int]) -> dict[str, Any]:
    """What a chunk store must match to be reused: grid, model, method, chunks, version."""
    h = hashlib.sha256()
    for k in sorted(ds.coords):
        h.update(k.encode())
        h.update(np.ascontiguousarray(ds.coords[k].values).tobytes())
    keep = ("model", "eigenvalue_method", "mask_unphysical", "source", "parameters", "grid_dimensions")
    return {"coordinates_sha256": h.hexdigest(), "chunks": chunk_shape,
            **{k: str(ds.attrs.get(k)) for k in keep}}


def _open_store(store: Path, ident: dict[str, Any]) -> set[str]:
    """Create or check the sidecar store; return the names of the chunks already there."""
    manifest = store / "manifest.json"
    if store.exists():
        if not manifest.is_file():
            raise ResumeError(f"cannot resume: {str(store)!r} exists but has no manifest.json "
                              "(not a chunk store of this package); remove it or choose another output")
        try:
            old = json.loads(manifest.read_text())
            if not isinstance(old, dict):
                raise ValueError
        except (ValueError, UnicodeDecodeError, OSError):
            raise ResumeError(f"cannot resume: {str(manifest)!r} is not a readable manifest; remove "
                              f"{str(store)!r} to start afresh") from None
        diff = [k for k in ident if old.get(k) != ident[k]]
        if diff:
            raise ResumeError(f"cannot resume from {str(store)!r}: it was written for a different atlas "
                              f"({', '.join(diff)} differ); remove it to start afresh")
        return {p.stem for p in store.glob("chunk-*.npz")}
    store.mkdir()
    tmp = store / ".manifest.json.tmp"
    tmp.write_text(json.dumps(ident, indent=1))
    os.replace(tmp, manifest)
    return set()


def _save_chunk(store: Path, name: str, block: dict[str, np.ndarray]) -> None:
    tmp = store / f".{name}.tmp.npz"
    np.savez(tmp, **block)
    os.replace(tmp, store / f"{name}.npz")


def _load_chunk(store: Path, name: str) -> dict[str, np.ndarray] | None:
    """A kept chunk, or None (to recompute it) if its file cannot be read."""
    try:
        with np.load(store / f"{name}.npz") as z:
            return {k: np.asarray(z[k]) for k in _BLOCK_VARIABLES}
    except Exception:  # unreadable or incomplete: computed again
        return None


def _chunk_slices(ds: xr.Dataset, dims: list[str], chunk_shape: dict[str, int]) -> list[tuple[str, dict[str, slice]]]:
    ranges = [range(0, ds.sizes[d], chunk_shape[d]) for d in dims]
    out = []
    for starts in product(*ranges):
        sl = {d: slice(s, min(s + chunk_shape[d], ds.sizes[d])) for d, s in zip(dims, starts)}
        name = "chunk-" + "-".join(str(s // chunk_shape[d]) for d, s in zip(dims, starts)) if dims else "chunk"
        out.append((name, sl))
    return out


def _spec(ds: xr.Dataset, dims: list[str]) -> dict[str, Any]:
    """What computing a chunk needs, read from an atlas's coordinates and attributes."""
    names = str(ds.attrs["parameters"]).split()
    return {"model": str(ds.attrs["model"]), "method": str(ds.attrs["eigenvalue_method"]),
            "mask": bool(int(ds.attrs["mask_unphysical"])), "names": names, "dims": dims,
            "values": {k: np.asarray(ds.coords[k].values, dtype=np.float64) for k in names}}


def _compute_block(spec: dict[str, Any], sl: dict[str, slice]) -> dict[str, np.ndarray]:
    """The per-chunk variables of one chunk of the grid (runs wherever the chunk is sent)."""
    from ..models import get_model

    dims = spec["dims"]
    args = []
    for k in spec["names"]:
        v = spec["values"][k]
        if v.ndim == 1:
            shape = [1] * len(dims)
            shape[dims.index(k)] = -1
            v = v[sl[k]].reshape(shape)
        args.append(v)
    out = _block_spectra(*args, model=get_model(spec["model"], warn=False), names=tuple(spec["names"]), mask=spec["mask"],
                         method=spec["method"])
    return dict(zip(_BLOCK_VARIABLES, out))


def _slice_block(ds: xr.Dataset, sl: dict[str, slice]) -> dict[str, np.ndarray]:
    """The per-chunk variables of an in-memory atlas."""
    return {k: np.asarray(ds[k].isel(sl).values) for k in _BLOCK_VARIABLES}


def write_atlas(ds: xr.Dataset, path: str | os.PathLike, *, overwrite: bool = False, client: Any = None,
                resume: bool = False, progress: bool | Callable[[int, int], None] = False,
                window: int | None = None) -> Path:
    """Write an atlas (lazy or not) to netCDF chunk by chunk, atomically.

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas from :func:`stability.atlas`, typically with ``chunks=``; an in-memory one is
        written in one chunk per dimension-size.
    path : path-like
        Target file.
    overwrite : bool, default False
        Replace an existing file.
    client : distributed.Client, optional
        Compute the chunks on this cluster (see :func:`stability.grids.cluster.dask_client`); in this
        process if None.
    resume : bool, default False
        Keep finished chunks in ``<output>.parts/`` and reuse those of an earlier interrupted
        run (module docstring). Without it nothing survives an interruption.
    progress : bool or callable, default False
        A progress bar on stderr (True), or ``progress(done, total)`` after each chunk;
        silent by default.
    window : int, optional
        Chunks in flight at once on a cluster (default: twice its threads); bounds memory.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ResumeError
        ``resume=True`` and ``<output>.parts/`` belongs to another atlas.
    """
    overwrite = check_flag("overwrite", overwrite)
    resume = check_flag("resume", resume)
    if window is not None:
        window = check_integer("window", window, minimum=1)
    if not isinstance(ds, xr.Dataset) or "stability" not in ds or "parameters" not in ds.attrs:
        raise TypeError(f"ds must be an atlas Dataset from stability.atlas, got {type(ds).__name__}")
    target = check_output_path(path, overwrite=overwrite)
    dims = [d for d in ds["stability"].dims]
    chunk_shape = {}
    for d in dims:
        c = ds.chunksizes.get(d) if ds.chunks else None
        chunk_shape[d] = int(c[0]) if c else ds.sizes[d]
    blocks = _chunk_slices(ds, dims, chunk_shape)
    store = parts_directory(target)
    done: set[str] = set()
    if resume:
        done = _open_store(store, _identity(ds, chunk_shape))
    report = _progress(progress, len(blocks))
    try:
        with atomic_output(target, overwrite=overwrite) as tmp:
            _create_skeleton(ds, tmp, chunk_shape)
            import netCDF4

            with netCDF4.Dataset(tmp, "a") as nc:
                nc.set_auto_mask(False)

                def put(name: str, sl: dict[str, slice], block: dict[str, np.ndarray], fresh: bool) -> None:
                    if resume and fresh:
                        _save_chunk(store, name, block)
                    idx = tuple(sl[d] for d in dims)
                    for k, v in block.items():
                        nc.variables[k][idx] = v
                    nc.variables["max_growth_rate"][idx] = block["growth_rate"][..., 0]
                    report()

                todo = []
                for name, sl in blocks:
                    kept = _load_chunk(store, name) if name in done else None
                    if kept is not None:
                        put(name, sl, kept, False)
                    else:
                        todo.append((name, sl))
                lazy = bool(ds.chunks)
                spec = _spec(ds, dims)
                failed = _Failure(store if resume else None, len(blocks))
                if client is None or not lazy:
                    for name, sl in todo:
                        try:
                            block = _compute_block(spec, sl) if lazy else _slice_block(ds, sl)
                        except Exception as exc:
                            raise failed(name, sl, exc, report.done) from exc
                        put(name, sl, block, True)
                else:
                    _run_on_cluster(client, spec, todo, put, window, failed, report)
                _write_leading(nc, blocks, dims)
    finally:
        report(close=True)
    if resume and store.exists():
        shutil.rmtree(store)
    return target


def _write_leading(nc: Any, blocks: list[tuple[str, dict[str, slice]]], dims: list[str]) -> None:
    """Fill ``leading_growth_rate`` from the chunks written: whether the structural zero mode is
    left out is decided on the whole grid first (stability.grids.leading), then each chunk."""
    if "leading_growth_rate" not in nc.variables:
        return
    mdims = (*dims, "mode")

    def part(sl: dict[str, slice]) -> tuple[Any, ...]:
        idx = tuple(sl[d] for d in dims)
        bound = (xr.DataArray(nc.variables["eigenvalue_error_bound"][idx], dims=mdims)
                 if "eigenvalue_error_bound" in nc.variables else None)
        return (idx, xr.DataArray(nc.variables["growth_rate"][idx], dims=mdims),
                xr.DataArray(nc.variables["frequency"][idx], dims=mdims), bound,
                xr.DataArray(nc.variables["max_growth_rate"][idx], dims=dims))

    drop = bool(dims)
    if drop:
        flags = [zero_everywhere(*part(sl)[1:4]) for _, sl in blocks]
        drop = all(bool(e) for e, _ in flags) and any(bool(i) for _, i in flags)
    for _, sl in blocks:
        idx, g, f, b, m = part(sl)
        nc.variables["leading_growth_rate"][idx] = leading(g, f, b, m, drop=drop).values


class _Failure:
    """Builds the :class:`ChunkError` of a failed chunk (what failed, what was kept)."""

    def __init__(self, store: Path | None, total: int) -> None:
        self.store, self.total = store, total

    def __call__(self, name: str, sl: dict[str, slice], exc: BaseException, done: int) -> ChunkError:
        where = ", ".join(f"{d}[{s.start}:{s.stop}]" for d, s in sl.items()) or "the whole grid"
        cause = f"{type(exc).__name__}: {exc}".strip().rstrip(":")
        if self.store is not None:
            kept = (f"{done} of {self.total} chunks are kept in {self.store}; rerun the same command "
                    "(resume=True, --resume) to compute only the others")
        else:
            kept = (f"no chunks were kept ({done} of {self.total} had been computed); use "
                    "resume=True (--resume) to keep finished chunks across a failure")
        return ChunkError(f"chunk {name} ({where}) failed: {cause}; the output file was not written; {kept}")


def _run_on_cluster(client: Any, spec: dict[str, Any], todo: list, put: Callable, window: int | None,
                    failed: _Failure, report: "_progress") -> None:
    """Submit chunks to ``client`` with at most ``window`` in flight; write each as it lands.

    A chunk whose task raises (or whose worker died more often than the scheduler's
    ``allowed-failures``, dask's ``KilledWorker``) ends the run with a :class:`ChunkError`; the
    chunks still in flight are cancelled. A worker dying once is retried by dask elsewhere.
    """
    from distributed import as_completed

    if window is None:
        window = 2 * max(1, sum(client.nthreads().values()))
    pending = iter(todo)
    names = {}
    ac = as_completed()
    try:
        for name, sl in pending:
            fut = client.submit(_compute_block, spec, sl, pure=False)
            names[fut.key] = (name, sl, fut)
            ac.add(fut)
            if len(names) >= window:
                break
        for fut in ac:
            name, sl, _ = names.pop(fut.key)
            try:
                block = fut.result()
            except Exception as exc:
                raise failed(name, sl, exc, report.done) from exc
            put(name, sl, block, True)
            fut.release()
            nxt = next(pending, None)
            if nxt is not None:
                f2 = client.submit(_compute_block, spec, nxt[1], pure=False)
                names[f2.key] = (*nxt, f2)
                ac.add(f2)
    finally:
        if names:
            client.cancel([f for _, _, f in names.values()])


class _progress:
    """Callable reporting chunk progress: a tqdm bar, a user callback, or nothing."""

    def __init__(self, how: bool | Callable[[int, int], None], total: int) -> None:
        self.total, self.done, self.bar, self.fn = total, 0, None, None
        if callable(how):
            self.fn = how
        elif how:
            from tqdm import tqdm

            self.bar = tqdm(total=total, unit="chunk", desc="atlas", leave=True)

    def __call__(self, close: bool = False) -> None:
        if close:
            if self.bar is not None:
                self.bar.close()
                self.bar = None
            return
        self.done += 1
        if self.bar is not None:
            self.bar.update(1)
        if self.fn is not None:
            self.fn(self.done, self.total)
