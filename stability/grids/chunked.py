"""Atlases beyond memory and beyond one machine: lazy, chunked spectra and chunk-wise writing.

* :func:`lazy_spectra` (used by ``atlas(..., chunks=...)``) builds dask arrays with
  :func:`xarray.apply_ufunc` (``dask="parallelized"``): each chunk of the grid is one call of
  :func:`stability.spectrum` on that chunk's coordinates. The domain is checked before any
  chunk is computed (a refused grid refuses at once, as the in-memory atlas does).
* :func:`write_atlas` writes such a dataset to netCDF chunk by chunk: the file is created
  (dimensions, coordinates, attributes, as xarray writes them) under a temporary name next to
  the target; each chunk is computed (in this process, or on a dask.distributed cluster), checked
  (exact dtypes and shapes: a block is never broadcast or cast into the file), written into its
  region (by one writer thread, in order, while the next chunk is computed) and dropped; the file is committed only when complete
  (:func:`stability.files.atomic_output`: no partial file, and an existing file, or one
  another run created meanwhile, is not replaced unless asked). Memory stays at a few chunks
  whatever the grid size; an interruption (checked between chunks) leaves no output file.
* To a Zarr store (an output named ``*.zarr``), and with ``resume=True``: the chunks are written
  by region into a Zarr store by whoever computes them (the workers of a cluster), each marked
  complete by its digest; a rerun reuses the complete chunks; a netCDF output is then written
  from the store (:mod:`stability.grids.store`).
* Where the chunks run: in this process by default, or on a dask.distributed cluster given as
  ``client`` (:func:`stability.grids.cluster.dask_client`).
"""

from __future__ import annotations

import contextlib
import os
import shutil
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from itertools import islice, product
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..errors import ChunkError, InputError, ParameterTypeError, require_extra
from ..files import atomic_output, check_free_space, check_output_directory, check_output_path, close_quietly
from ..interrupts import checkpoint, deferred
from ..models import LinearModel
from ..parameters import check_domain, check_flag, check_integer
from ..resources import atlas_file_bytes
from . import store
from .schema import MAP_VARIABLES, STORED_ATTR
from .store import parts_directory

__all__ = ["COMPRESSIONS", "VARIABLE_CHOICES", "lazy_spectra", "normalize_chunks", "parts_directory", "write_atlas"]


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
    if not isinstance(chunks, dict):
        chunks = dict.fromkeys(dims, check_integer("chunks", chunks, minimum=1))
    elif unknown := [k for k in chunks if k not in dims]:
        raise InputError(
            f"chunks name {', '.join(map(repr, unknown))}, not grid dimensions "
            f"(the grid has {', '.join(dims) or 'none'})"
        )
    return {
        d: min(check_integer(f"chunks[{d!r}]", chunks[d], minimum=1), sizes[d]) if d in chunks else sizes[d]
        for d in dims
    }


def _grid_shaped(v: np.ndarray, k: str, dims: list[str]) -> np.ndarray:
    """The values of parameter ``k`` shaped to broadcast over the grid ``dims`` (a 0-d one as it is)."""
    return v if v.ndim == 0 else v.reshape([-1 if d == k else 1 for d in dims])


def _block_spectra(
    *args: np.ndarray, model: LinearModel, names: tuple[str, ...], mask: bool, method: str
) -> tuple[np.ndarray, ...]:
    """Spectra of one chunk: growth rate, frequency, bound, flag, physical."""
    from ..linear.spectra import spectrum

    shape = np.broadcast_shapes(*(np.shape(a) for a in args))
    sp = spectrum(model, mask_unphysical=mask, method=method, **dict(zip(names, args)))
    ev = np.broadcast_to(sp.eigenvalues, shape + (model.n_modes,))
    # views of the fresh arrays, no copies (a writer that keeps only a map never reads most of
    # them; copying them cost a quarter of a map's writing time)
    flags = (np.broadcast_to(f, shape).astype(np.int8) for f in (sp.stability, sp.inside))
    return ev.real, ev.imag, np.broadcast_to(sp.error_bound, ev.shape), *flags


def lazy_spectra(
    model: LinearModel,
    values: dict[str, np.ndarray],
    dims: list[str],
    chunks: int | dict[str, int],
    *,
    mask_unphysical: bool,
    method: str,
) -> tuple:
    """Dask-backed spectra over a grid (see module docstring).

    The domain is checked first without building the whole grid (the bounds couple only q,
    sigma and mu; fr_inv and alpha_v are checked alone).

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
        raise InputError(f"method = {method!r} is not known; choose one of {', '.join(METHODS)}")
    ch = normalize_chunks(chunks, dims, {d: values[d].size for d in dims})
    if not mask_unphysical:
        check_domain(mask=False, **{k: _grid_shaped(values[k], k, dims) for k in ("q", "sigma", "mu") if k in values})
        for k in ("fr_inv", "alpha_v"):
            if k in values:
                check_domain(mask=False, **{k: values[k]})
    inputs = [
        xr.DataArray(v, dims=(k,)).chunk({k: ch[k]}) if v.ndim == 1 else xr.DataArray(v) for k, v in values.items()
    ]
    out = xr.apply_ufunc(
        _block_spectra,
        *inputs,
        kwargs=dict(model=model, names=tuple(values), mask=mask_unphysical, method=method),
        input_core_dims=[[]] * len(inputs),
        output_core_dims=[["mode"], ["mode"], ["mode"], [], []],
        dask="parallelized",
        output_dtypes=[np.float64, np.float64, np.float64, np.int8, np.int8],
        dask_gufunc_kwargs={"output_sizes": {"mode": model.n_modes}},
    )
    return tuple(da.transpose(*[d for d in dims if d in da.dims], ...).data for da in out)


# --- writing -----------------------------------------------------------------------------------

#: what :func:`write_atlas` can store (``variables=``): every variable of the atlas, or the
#: smallest set that draws a stability map (:data:`stability.grids.schema.MAP_VARIABLES`)
VARIABLE_CHOICES = ("all", "map")

#: compressions of :func:`write_atlas` (netCDF4's filters; None: none)
COMPRESSIONS = (None, "zlib", "zstd")

#: the filter level of each compression: zstd's fastest standard level is 1, its "fast" levels
#: (negative) trade a few percent of size for speed; -1 compressed a chunk of the atlas 1.4x
#: faster than level 1 for 6 % more bytes (docs/performance.md), zlib's fastest level is 1
LEVELS = {"zlib": 1, "zstd": -1}

#: largest netCDF (HDF5) chunk of a variable in the file, in bytes: a chunk of the grid is
#: written as several file chunks of at most this size (shuffling and compressing ~1 MB pieces
#: was 1.5x faster than one 24 MB piece, and an uncompressed float64 file 1.7x)
FILE_CHUNK_BYTES = 2**21

#: what a float32 variable says about its rounding (:func:`write_atlas`): round to nearest with a
#: 24-bit significand, a relative error of at most 2**-24
FLOAT32_ATTRS = {
    "storage_dtype": "float32",
    "storage_relative_error": 2.0**-24,
    "storage_comment": "computed in float64 and rounded to float32 when written: relative error "
    "<= 2**-24 (5.96e-08) from the rounding, on top of the eigenvalue error bound "
    "(eigenvalue_error_bound, ~1e-15 |s|); the rounding keeps every sign (a value "
    "that would round to zero, a subnormal or infinity is refused), and the "
    "stability flag was decided in float64 before it",
}


def _file_chunks(shape: list[int], itemsize: int) -> list[int]:
    """The netCDF chunk shape of a variable written in pieces of ``shape``: ``shape`` cut along its
    leading dimensions by divisors of their sizes (so that every write covers whole file chunks,
    never part of a compressed one) until at most :data:`FILE_CHUNK_BYTES`."""
    out = list(shape)
    for i, n in enumerate(shape):
        rest = itemsize * int(np.prod(out[i + 1 :], dtype=np.int64))
        if rest * out[i] <= FILE_CHUNK_BYTES:
            break
        out[i] = max((d for d in range(1, n + 1) if n % d == 0 and d * rest <= FILE_CHUNK_BYTES), default=1)
    return out


def _create_skeleton(ds: xr.Dataset, path: str, chunk_shape: dict[str, int], stored: list[str], how: tuple) -> None:
    """Create the netCDF file: dimensions, coordinates and attributes as xarray writes them,
    data variables (``stored``) defined (chunked like the dataset, compressed as asked,
    floating ones as float32 if asked: ``how = (compression, float32)``) but not yet written."""
    import netCDF4

    (compression, float32), scalar = how, " ".join(k for k, c in ds.coords.items() if c.ndim == 0)
    level = {"compression": compression, "complevel": LEVELS[compression], "shuffle": True} if compression else {}
    with close_quietly(netCDF4.Dataset(path, "w", format="NETCDF4")) as nc:
        for d, n in ds.sizes.items():
            if d != "mode" or any("mode" in ds[k].dims for k in stored):
                nc.createDimension(d, n)
        for k, c in ds.coords.items():
            if set(c.dims) <= set(nc.dimensions):  # "<f8" read from Zarr: native order
                var = nc.createVariable(k, c.dtype.newbyteorder("="), c.dims, fill_value=_fill(c.dtype))
                var.setncatts(dict(c.attrs))
                var[...] = c.values
        for k in stored:
            v = ds[k]
            dtype = np.dtype(np.float32) if (float32 and v.dtype.kind == "f") else v.dtype.newbyteorder("=")
            cs = _file_chunks([chunk_shape.get(d, ds.sizes[d]) for d in v.dims], dtype.itemsize)
            filters = dict(chunksizes=cs or None, contiguous=not cs and not level, **(level if cs else {}))
            var = nc.createVariable(k, dtype, v.dims, fill_value=_fill(dtype), **filters)
            attrs = v.attrs | ({"coordinates": scalar} if scalar else {})
            var.setncatts(attrs | (FLOAT32_ATTRS if dtype != v.dtype else {}))
        nc.setncatts(dict(ds.attrs) | ({STORED_ATTR: "map"} if "growth_rate" not in stored else {}))
        if compression:  # the default file keeps the attributes of the atlas, as xarray writes it
            nc.setncatts({"compression": f"{compression} level {LEVELS[compression]}, byte shuffle (lossless)"})


def _fill(dtype: np.dtype) -> Any:
    return dtype.type(np.nan) if dtype.kind == "f" else None


def _as_float32(name: str, v: np.ndarray) -> np.ndarray:
    """``v`` rounded to float32, refused (:class:`~stability.errors.InputError`) where the rounding
    would not keep a value's sign and magnitude class: a finite nonzero value that would become
    zero, subnormal or infinite."""
    with np.errstate(over="ignore"):  # an overflow is refused below, by name
        w = v.astype(np.float32)
    tiny, big = np.finfo(np.float32).tiny, np.finfo(np.float32).max
    # two passes in the usual case: values below float32's normal range (the exact zeros of the
    # structural mode, anything that underflowed) and infinities are rare, and only they are
    # looked at again
    small = np.abs(w) < tiny
    bad = v[small][v[small] != 0] if small.any() else v[:0]
    if not bad.size and np.isinf(w).any():
        bad = v[np.isinf(w)][np.isfinite(v[np.isinf(w)])]
    if bad.size:
        raise InputError(
            f"float32=True: {name} = {float(bad[0])!r} is outside the normal range of float32 "
            f"({float(tiny)!r} to {float(big)!r} in magnitude); its rounding would "
            "change it beyond the stated bound: write with float32=False"
        )
    return w


def _compute_block(spec: dict[str, Any], sl: dict[str, slice]) -> dict[str, np.ndarray]:
    """The per-chunk variables of one chunk of the grid (runs wherever the chunk is sent)."""
    from ..models import get_model

    values, atlas = spec["values"], spec["identity"]
    args = [_grid_shaped(values[k][sl[k]] if values[k].ndim else values[k], k, spec["dims"]) for k in spec["names"]]
    how = dict(mask=bool(int(atlas["mask_unphysical"])), method=atlas["eigenvalue_method"])
    out = _block_spectra(*args, model=get_model(atlas["model"], warn=False), names=tuple(spec["names"]), **how)
    return dict(zip(store.BLOCK_LAYOUT, out))


def write_atlas(
    ds: xr.Dataset,
    path: str | os.PathLike,
    *,
    overwrite: bool = False,
    client: Any = None,
    resume: bool = False,
    progress: bool | Callable[[int, int], None] = False,
    window: int | None = None,
    variables: str = "all",
    compression: str | None = None,
    float32: bool = False,
) -> Path:
    """Write an atlas (lazy or not) chunk by chunk, atomically: to netCDF, or to a Zarr store.

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas from :func:`stability.atlas`, typically with ``chunks=``; an in-memory one is
        written in one chunk per dimension-size.
    path : path-like
        Target file; a name ending in ``.zarr`` is a Zarr store, written by region by whoever
        computes each chunk (:mod:`stability.grids.store`).
    overwrite : bool, default False
        Replace an existing file (or store).
    client : distributed.Client, optional
        Compute the chunks on this cluster (see :func:`stability.grids.cluster.dask_client`); in this
        process if None.
    resume : bool, default False
        Build the chunks in the Zarr store ``<output>.parts`` (:mod:`stability.grids.store`), kept
        when the run is interrupted or fails, and reuse the complete chunks of an earlier run's
        store (each checked against its digest); a netCDF output is then written from the
        store, and the store removed. Without it nothing survives an interruption.
    progress : bool or callable, default False
        A progress bar on stderr (True), or ``progress(done, total)`` after each chunk;
        silent by default.
    window : int, optional
        Chunks in flight at once on a cluster (default: twice its threads); bounds memory.
    variables : {"all", "map"}, default "all"
        What the file stores: every variable of the atlas, or for a map the leading growth rate
        and the stability flag only (:data:`stability.grids.schema.MAP_VARIABLES`; the file's
        attribute ``atlas_variables = "map"``; :func:`stability.open_atlas` reads both). netCDF only.
    compression : {None, "zlib", "zstd"}, default None
        netCDF4's compression of the data variables (:data:`LEVELS`, with the byte shuffle;
        file chunks of at most :data:`FILE_CHUNK_BYTES`): lossless.
    float32 : bool, default False
        Store the floating-point variables as float32: relative error <= 2**-24 from the
        rounding, stated in each such variable's attributes (``storage_relative_error``); the
        flags are decided in float64 before. A value whose rounding would leave the normal
        float32 range (become zero, subnormal or infinite) is refused
        (:class:`~stability.errors.InputError`), never stored changed. netCDF only.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ResumeError
        ``resume=True`` and ``<output>.parts`` belongs to another atlas (or version), is not a
        Zarr store, holds a chunk that does not match its digest (named), or is being written
        by another run (its lock: :func:`stability.grids.store.locked`).
    FileExistsError
        The output exists (or was created by another process during the run) and ``overwrite``
        is False, or is not a regular file (a Zarr store: not a store).
    stability.errors.OutputWriteError
        The output could not be written (named, with the cause).
    """
    overwrite, resume, float32 = map(check_flag, ("overwrite", "resume", "float32"), (overwrite, resume, float32))
    if window is not None:
        window = check_integer("window", window, minimum=1)
    if not isinstance(ds, xr.Dataset) or "stability" not in ds or "parameters" not in ds.attrs:
        raise ParameterTypeError(f"ds must be an atlas Dataset from stability.atlas, got {type(ds).__name__}")
    for name, value, choices in [
        ("variables", variables, VARIABLE_CHOICES),
        ("compression", compression, COMPRESSIONS),
    ]:
        if value not in choices:
            raise InputError(f"{name} = {value!r} is not a choice; choose one of {', '.join(map(str, choices))}")
    zarr_store = store.is_store_path(path)
    if zarr_store and (variables, compression, float32) != ("all", None, False):
        raise InputError(
            f"a Zarr store ({str(path)!r}) stores every variable of the atlas in float64, with Zarr's "
            f"default compression: variables = {variables!r}, compression = {compression!r}, "
            f"float32 = {float32!r} apply to netCDF files only"
        )
    if zarr_store:  # its name is checked by the store (a directory), its directory here
        check_output_directory(target := Path(path))
    else:
        target = check_output_path(path, overwrite=overwrite)
    dims, names = list(ds["stability"].dims), str(ds.attrs["parameters"]).split()
    ch = {d: int(ds.chunksizes[d][0]) if d in ds.chunksizes else ds.sizes[d] for d in dims}
    blocks = []  # (name, slice) of each chunk, in order
    for starts in product(*(range(0, ds.sizes[d], ch[d]) for d in dims)):
        name = "chunk-" + "-".join(str(s // ch[d]) for d, s in zip(dims, starts)) if dims else "chunk"
        blocks.append((name, {d: slice(s, min(s + ch[d], ds.sizes[d])) for d, s in zip(dims, starts)}))
    # what a chunk needs wherever it runs; the identity (the grid, model, method, masking, version) binds a store
    spec = dict(dims=dims, chunk_shape=ch, n_modes=ds.sizes.get("mode", 0), resume=resume, overwrite=overwrite)
    spec |= dict(names=names, values={k: np.asarray(ds[k].values, dtype=np.float64) for k in names})
    spec |= dict(
        variables=list(ds.data_vars), identity={"chunks": ch} | {k: str(ds.attrs.get(k)) for k in store.IDENTITY_ATTRS}
    )
    expected = atlas_file_bytes(spec["n_modes"], int(np.prod([ds.sizes[d] for d in dims], dtype=np.int64)))
    kept, done, bar = parts_directory(target) if resume else None, [0], None
    client = client if ds.chunks else None  # in memory: sliced here

    def report() -> None:  # one chunk more done: the bar, the callback
        done[0] += 1
        if bar is not None:
            bar.update(1)
        if callable(progress):
            progress(done[0], len(blocks))

    def failed(name: str, sl: dict[str, slice], exc: BaseException) -> ChunkError:
        where = ", ".join(f"{d}[{s.start}:{s.stop}]" for d, s in sl.items()) or "the whole grid"
        cause = f"{type(exc).__name__}: {exc}".strip().rstrip(":")
        if kept:
            how = (
                f"{done[0]} of {len(blocks)} chunks are kept in {kept}; rerun the same command (resume=True, --resume)"
            )
            how += " to compute only the others"
        else:
            how = f"no chunks were kept ({done[0]} of {len(blocks)} had been computed); use resume=True (--resume)"
            how += " to keep finished chunks across a failure"
        return ChunkError(f"chunk {name} ({where}) failed: {cause}; the output file was not written; {how}")

    def run(todo: list, put: Callable, task: Callable, here: bool = False) -> None:
        _run_on_cluster(None if here else client, spec, todo, put, task, window, failed)

    def netcdf(src: xr.Dataset, report: Callable[[], None]) -> None:
        """The netCDF file from ``src`` (the atlas, or the complete store): skeleton, chunks
        (computed, or read from ``src`` in memory or in a store), commit.

        ``leading_growth_rate`` is written chunk by chunk from the chunk in memory (never read
        back): each chunk with the structural zero mode left out while every chunk so far has it
        at every point inside (:func:`stability.grids.store.chunk_variables`), else as
        ``max_growth_rate``; at the end, unless every chunk has it and one has a point inside
        (:func:`stability.grids.store.provisional`), the chunks written with it left out are
        rewritten as ``max_growth_rate``, read from the file or recomputed. The values are those
        of deciding on the whole grid first, bit for bit."""
        import netCDF4

        lazy, summary = bool(src.chunks), {}  # each chunk's part of the whole-grid rule

        def compute(spec: dict[str, Any], sl: dict[str, slice]) -> dict[str, np.ndarray]:
            return _compute_block(spec, sl) if lazy else store.slice_block(src, sl)

        def cast(name: str, v: np.ndarray) -> np.ndarray:
            return _as_float32(name, v) if float32 and v.dtype.kind == "f" else v

        with atomic_output(target, overwrite=overwrite, expected_bytes=expected) as tmp:
            _create_skeleton(src, tmp, ch, stored, (compression, float32))
            checkpoint()
            with close_quietly(netCDF4.Dataset(tmp, "a")) as nc:
                nc.set_auto_mask(False)
                var = nc.variables

                def write(name: str, sl: dict[str, slice], block: dict[str, np.ndarray]) -> None:
                    store.check_block(block, tuple(sl[d].stop - sl[d].start for d in dims), spec["n_modes"], name)
                    try_drop = "leading_growth_rate" in var and all(e for e, _ in summary.values())
                    out, *summary[name] = store.chunk_variables(block, dims, try_drop)
                    rounded: dict[int, np.ndarray] = {}  # max_growth_rate, rounded once for both that may hold it
                    for k in stored:
                        if id(out[k]) not in rounded:
                            rounded[id(out[k])] = cast(k, out[k])
                        var[k][tuple(sl[d] for d in dims)] = rounded[id(out[k])]
                    checkpoint()

                # each chunk is written (rounded, compressed) by one writer thread, in order, while
                # the next is computed: netCDF4's writes and the compiled spectra release the GIL, so
                # the writing overlaps the spectra instead of following them (one chunk more in
                # memory); on a cluster, as each chunk lands. Progress is reported in this thread.
                with ThreadPoolExecutor(max_workers=1) as writer:
                    pending: list = []

                    def put(name: str, sl: dict[str, slice], block: dict[str, np.ndarray] | None) -> None:
                        if pending:
                            pending.pop().result()
                            report()
                        if block is not None:
                            pending.append(writer.submit(write, name, sl, block))

                    run(blocks, put, _compute_block if lazy else compute, here=not lazy)
                    put("", {}, None)
                for sl in store.provisional(summary, blocks) if "leading_growth_rate" in var else ():
                    checkpoint()
                    idx = tuple(sl[d] for d in dims)
                    if "max_growth_rate" in var:
                        var["leading_growth_rate"][idx] = np.asarray(var["max_growth_rate"][idx])
                    else:
                        g0 = np.ascontiguousarray(compute(spec, sl)["growth_rate"][..., 0])
                        var["leading_growth_rate"][idx] = cast("leading_growth_rate", g0)

    stored = [k for k in MAP_VARIABLES if k in ds] if variables == "map" else list(ds.data_vars)
    with deferred(), contextlib.ExitStack() as held:
        if progress and not callable(progress):
            from tqdm import tqdm

            bar = held.enter_context(tqdm(total=len(blocks), unit="chunk", desc="atlas", leave=True))
        if not (zarr_store or resume):
            netcdf(ds, report)
            return target
        require_extra("zarr", "cluster", "a Zarr store (an output ending in .zarr, or resume=True)")
        if resume:  # held until the output is written and the store removed
            held.enter_context(store.locked(parts_directory(target)))
        if not zarr_store:
            check_free_space(target, expected)
        task = _compute_block if ds.chunks else lambda spec, sl: store.slice_block(ds, sl)  # in memory: no client
        parts = store.write_store(ds, target, spec, blocks, run, task, report)
        if not zarr_store:
            with store.open_store(parts) as src:  # the netCDF file from the complete store, in the atlas's order
                netcdf(src[list(ds.variables)], lambda: None)
            shutil.rmtree(parts, ignore_errors=True)
        return target


def _run_on_cluster(
    client: Any, spec: dict, todo: list, put: Callable, task: Callable, window: int | None, failed: Callable
) -> None:
    """Run ``task(spec, sl)`` for each chunk ``(name, sl)`` of ``todo`` and hand ``put`` what it
    returns: in this process, one after the other (``client`` None), or on ``client`` with at
    most ``window`` chunks in flight (default: twice its threads), each handed over as it lands.

    A chunk whose task raises (or whose worker died more often than the scheduler's
    ``allowed-failures``, dask's ``KilledWorker``) ends the run with ``failed(name, sl, exc)``,
    a :class:`ChunkError`; the chunks still in flight are cancelled. A worker dying once is
    retried by dask elsewhere. A :class:`ChunkError` of a task run here is passed on as it is.
    """
    if client is not None:
        from distributed import as_completed

        landed = as_completed()
    pending, live = iter(todo), {}

    def submit() -> None:
        for name, sl in islice(pending, 1):
            if client is None:  # here, now: a finished future
                checkpoint()
                fut = Future()
                try:
                    fut.set_result(task(spec, sl))
                except Exception as exc:
                    fut.set_exception(exc)
            else:
                landed.add(fut := client.submit(task, spec, sl, pure=False))
            live[fut] = (name, sl)

    try:
        for _ in range(1 if client is None else window or 2 * max(1, sum(client.nthreads().values()))):
            submit()
        while live:
            fut = next(iter(live)) if client is None else next(landed)
            checkpoint()
            name, sl = live.pop(fut)
            try:
                out = fut.result()
            except Exception as exc:
                if isinstance(exc, ChunkError) and client is None:
                    raise
                raise failed(name, sl, exc) from exc
            put(name, sl, out)
            if client is not None:
                fut.release()
            submit()
    finally:
        if live and client is not None:
            client.cancel(list(live))
