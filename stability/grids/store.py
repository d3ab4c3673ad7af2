"""Atlases as Zarr stores, written by region by whoever computes the chunks, and resumed from them.

:func:`write_store` (``write_atlas(ds, "atlas.zarr")``, ``tippe atlas -o atlas.zarr``) writes an
atlas with xarray's public API only:

1. ``ds.to_zarr(parts, compute=False)`` lays out the store: every variable of the atlas
   (:mod:`stability.grids.schema`, the same names, dimensions, attributes and dtypes as the
   netCDF atlas), chunked like the grid, with its coordinates and attributes, no data yet; plus
   the per-chunk record ``chunk_digest`` (one uint64 per chunk of the grid, dimensions
   ``<dim>_chunk``, one Zarr chunk each; 0: not written).
2. Each chunk of the grid is computed and written into its region with
   ``to_zarr(parts, region=...)`` (:func:`_write_region`) by the process that computed it: on a
   dask cluster, the workers themselves, which return only the chunk's summary (two flags: what
   the leading growth rate's whole-grid rule needs of it, :func:`chunk_variables`): the
   client never holds a chunk, and its memory does not grow with the grid. The regions are the
   Zarr chunks, so concurrent writers never share a chunk file. The digest (sha256 of the atlas's
   identity, the chunk's slice and the bytes of its arrays, first 8 bytes) is written **last**,
   in a second region write: a chunk is complete exactly when its digest is non-zero.
3. When every chunk is written, the leading growth rate's rule is decided over the whole grid
   (:func:`provisional`: from the per-chunk flags; those of a chunk reused on resuming from its
   data, read anyway to check its digest), the few chunks written provisionally with the zero
   mode left out are rewritten from ``max_growth_rate``, and the directory is renamed to its
   name: the rename commits it (no partial store under the output's name; an existing store is
   replaced only with ``overwrite=True``).

Resuming (``resume=True``): the store is built in ``<output>.parts`` (:func:`parts_directory`)
instead of a hidden temporary directory, and kept when the run is interrupted or fails. A rerun
opens it, refuses it if it belongs to another atlas (other coordinates, model, method, masking,
chunks or package version: :class:`~stability.errors.ResumeError` naming what differs), reads
``chunk_digest`` and recomputes the digest of every chunk marked complete from what the store
holds: a chunk that disagrees (edited, swapped, copied from another store) is refused naming it;
a chunk that cannot be read (a truncated chunk file) is computed again, with a warning; the
chunks marked incomplete (never written, or interrupted between the data and the digest) are
computed. The result equals the atlas computed in one go, bit for bit. A run holds ``<output>.parts`` locked
(:func:`locked`) until its output is written: a second run on the same store is refused at
once. The store must be on a file system the workers share with the client (always true of a
LocalCluster).
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import os
import secrets
import shutil
import warnings
from collections.abc import Callable, Iterator
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..errors import ChunkError, OutputWriteError, ResumeError
from ..files import TEMPORARY_PREFIX, temporary_name
from ..interrupts import Temporary, checkpoint
from .leading import leading, zero_everywhere

__all__ = ["IDENTITY_ATTRS", "check_block", "chunk_variables", "damaged_chunk", "is_store_path", "locked"]
__all__ += ["open_store", "parts_directory", "provisional", "slice_block", "write_store"]

#: the attributes a resumed store must share with the atlas being written
IDENTITY_ATTRS = ("model", "eigenvalue_method", "mask_unphysical", "source", "parameters", "grid_dimensions")

#: the arrays of one chunk (the rest, max_growth_rate, follows from growth_rate): their dtype;
#: the first three have the ``mode`` dimension
BLOCK_LAYOUT = dict.fromkeys(("growth_rate", "frequency", "eigenvalue_error_bound"), np.dtype(np.float64))
BLOCK_LAYOUT |= dict.fromkeys(("stability", "physical"), np.dtype(np.int8))


def check_block(block: dict[str, np.ndarray], shape: tuple[int, ...], n_modes: int, name: str) -> None:
    """The arrays of chunk ``name`` exactly as the file's variables need them (never broadcast
    or cast), else a :class:`ChunkError`."""

    def wrong(text: str) -> ChunkError:
        return ChunkError(f"chunk {name} was computed wrongly: it {text} (a bug; nothing was written)")

    if set(block) != set(BLOCK_LAYOUT):
        raise wrong(f"has the arrays {', '.join(sorted(block))}; a chunk has {', '.join(sorted(BLOCK_LAYOUT))}")
    for k, dtype in BLOCK_LAYOUT.items():
        want = shape + ((n_modes,) if dtype.kind == "f" else ())
        if block[k].dtype != dtype:
            raise wrong(f"has {k} of dtype {block[k].dtype}; a chunk stores it as {dtype}")
        if block[k].shape != want:
            raise wrong(f"has {k} of shape {block[k].shape}; this chunk of the grid has shape {want}")


def slice_block(ds: xr.Dataset, sl: dict[str, slice]) -> dict[str, np.ndarray]:
    """The per-chunk variables of a chunk of an atlas in memory or in a store."""
    return {k: ds[k].isel(sl).transpose(*ds["stability"].dims, ...).values for k in BLOCK_LAYOUT}


def chunk_variables(
    block: dict[str, np.ndarray], dims: list[str], try_drop: bool = True
) -> tuple[dict[str, np.ndarray], bool, bool]:
    """The atlas variables of one chunk, and its part of the leading growth rate's whole-grid
    rule (:mod:`stability.grids.leading`): ``max_growth_rate``, and ``leading_growth_rate`` with
    the structural zero mode left out if the chunk has it at every point inside (``try_drop``;
    else ``max_growth_rate`` itself, the same array); whether it has (never on a 0-d grid), and
    whether the chunk has a point inside (False where not looked at)."""
    top = block["growth_rate"][..., 0]
    out = dict(block, max_growth_rate=top, leading_growth_rate=top)
    if not (try_drop and dims):
        return out, False, False
    g, f, b = (
        xr.DataArray(block[k], dims=(*dims, "mode")) for k in ("growth_rate", "frequency", "eigenvalue_error_bound")
    )
    everywhere, inside = zero_everywhere(g, f, b)
    if bool(everywhere):
        out["leading_growth_rate"] = leading(g, f, b, xr.DataArray(top, dims=dims), drop=True).values
    return out, bool(everywhere), bool(inside)


def provisional(done: dict[str, tuple[bool, bool]], blocks: list) -> list[dict[str, slice]]:
    """The leading growth rate's whole-grid rule (:mod:`stability.grids.leading`) from the chunks'
    summaries ``done[name] = (zero mode at every point inside, a point inside)``: the zero mode is
    left out iff every chunk has it at every point inside and one chunk has a point inside; else
    the slices of the chunks written with it left out, to be rewritten as ``max_growth_rate``."""
    if all(e for e, _ in done.values()) and any(i for _, i in done.values()):
        return []
    return [sl for name, sl in blocks if done[name][0]]


def is_store_path(path: str | os.PathLike) -> bool:
    """Whether ``path`` names a Zarr store (its name ends in ``.zarr``)."""
    return str(path).rstrip("/\\").endswith(".zarr")


def parts_directory(path: str | os.PathLike) -> Path:
    """The store of a resumable run of output ``path``: ``<output>.parts``."""
    return Path(path).with_name(Path(path).name + ".parts")


@contextlib.contextmanager
def locked(parts: Path) -> Iterator[None]:
    """Hold the resumable store ``parts`` (created empty if new) for a whole run: an exclusive
    ``fcntl.flock`` on its directory, which the kernel releases when the run ends, however it
    ends (a killed run leaves no stale lock). A second run on the same store is refused at once
    (:class:`ResumeError`), instead of racing the first over the same chunks. Where there is no
    such lock (not POSIX, some network file systems) the run goes unlocked. An empty directory
    created here is removed at the end (a run refused before writing leaves none)."""
    if os.path.lexists(parts) and not parts.is_dir():
        raise ResumeError(
            f"cannot resume: {str(parts)!r} exists and is not a Zarr store; remove it or choose another output"
        )
    parts.mkdir(exist_ok=True)
    fd = os.open(parts, os.O_RDONLY)
    try:
        with contextlib.suppress(ImportError, OSError):  # no flock here: unlocked
            import fcntl

            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                raise ResumeError(
                    f"cannot resume: another run is writing {str(parts)!r} now (it holds the store's lock); "
                    "wait for it to end, or stop it and rerun"
                ) from None
        yield
    finally:
        os.close(fd)
        with contextlib.suppress(OSError):
            parts.rmdir()  # only if empty


def open_store(path: str | os.PathLike, record: bool = False) -> xr.Dataset:
    """The atlas in a complete Zarr store, opened lazily (xarray's zarr backend, not dask),
    without its per-chunk record ``chunk_digest`` unless ``record``."""
    ds = xr.open_dataset(path, engine="zarr", consolidated=False, chunks=None)
    return ds if record else ds.drop_vars([v for v in ("chunk_digest",) if v in ds.variables])


def damaged_chunk(path: str | os.PathLike) -> str | None:
    """The first chunk file of the store ``path`` that cannot be read (``"growth_rate/c/0/0/0/0"``,
    relative to the store), or None if every chunk reads: each chunk of each array read once,
    through zarr's public API (for the message of a store that failed to load; None too if its
    metadata does not read)."""
    import itertools

    with contextlib.suppress(Exception):  # also no zarr (the extra), or metadata that does not read
        import zarr

        for name, array in sorted(zarr.open_group(str(path), mode="r").arrays()):
            for index in itertools.product(*(range(n) for n in array.cdata_shape)):
                try:
                    array.blocks[index]
                except Exception:
                    return f"{name}/{array.metadata.encode_chunk_key(index)}"
    return None


def _digest(spec: dict[str, Any], sl: dict[str, slice], block: dict[str, np.ndarray]) -> np.uint64:
    """sha256 of the atlas's identity, the chunk's slice and its arrays (name, dtype, shape,
    bytes): its first 8 bytes, never 0 (0 marks a chunk not written)."""
    h = hashlib.sha256(repr(spec["identity"]).encode())
    h.update(repr([(d, sl[d].start, sl[d].stop) for d in spec["dims"]]).encode())
    for k in sorted(block):
        a = np.ascontiguousarray(block[k])
        h.update(f"{k} {a.dtype.str} {a.shape}".encode())
        h.update(a.data)  # the array's own bytes, not a copy
    return np.uint64(max(1, int.from_bytes(h.digest()[:8], "little")))


def _index(sl: dict[str, slice], spec: dict[str, Any]) -> dict[str, slice]:
    """The chunk's region in the per-chunk record."""
    ch = spec["chunk_shape"]
    return {f"{d}_chunk": slice(sl[d].start // ch[d], sl[d].start // ch[d] + 1) for d in spec["dims"]}


def _write_region(spec: dict[str, Any], sl: dict[str, slice], path: str, compute: Callable) -> tuple[bool, bool]:
    """Compute one chunk (``compute(spec, sl)``: :func:`stability.grids.chunked._compute_block`),
    write it into its region of the store, then its digest; return only (zero mode at every
    point inside, a point inside). Runs wherever the chunk is sent."""
    dims = spec["dims"]
    block = compute(spec, sl)
    check_block(block, tuple(sl[d].stop - sl[d].start for d in dims), spec["n_modes"], "of the store")
    out, everywhere, inside = chunk_variables(block, dims)
    part = xr.Dataset({k: ((*dims, "mode")[: out[k].ndim], out[k]) for k in spec["variables"]})
    part.to_zarr(path, region={d: sl[d] for d in dims}, mode="r+", consolidated=False)
    mark = _digest(spec, sl, block) if spec["resume"] else np.uint64(1)  # only a rerun reads the digest
    # the digest after the data: the chunk is complete when it is written
    digest = xr.Dataset({"chunk_digest": ([f"{d}_chunk" for d in dims], np.full((1,) * len(dims), mark))})
    digest.to_zarr(path, region=_index(sl, spec), mode="r+", consolidated=False)
    return everywhere, inside


def _reopen(path: Path, ds: xr.Dataset, spec: dict[str, Any], blocks: list) -> dict[str, tuple[bool, bool]]:
    """The chunks of an earlier run's store that are complete and check out (see module
    docstring), with their summaries; a store of another atlas or a chunk that disagrees with
    its digest is a :class:`ResumeError`."""
    try:
        old = open_store(path, record=True)
    except Exception:
        raise ResumeError(
            f"cannot resume: {str(path)!r} exists but is not a readable Zarr store of this package; "
            "remove it or choose another output"
        ) from None
    with old:
        diff = [k for k in IDENTITY_ATTRS if str(old.attrs.get(k)) != str(ds.attrs.get(k))]
        diff += [k for k in ds.coords if k not in old.coords or not np.array_equal(old[k], ds[k], equal_nan=True)]
        if "chunk_digest" not in old or "stability" not in old:
            diff.append("layout")
        elif old["stability"].encoding.get("chunks") not in (None, tuple(spec["chunk_shape"].values())):
            diff.append("chunks")
        if diff:
            raise ResumeError(
                f"cannot resume from {str(path)!r}: it was written for a different atlas "
                f"({', '.join(diff)} differ); remove it to start afresh"
            )
        digests, done = old["chunk_digest"].values, {}
        for name, sl in blocks:
            checkpoint()
            mark = digests[tuple(s.start for s in _index(sl, spec).values())]
            if mark == 0:
                continue
            try:
                block = slice_block(old, sl)
            except Exception as exc:  # a chunk file truncated or damaged: computed again
                warnings.warn(
                    f"chunk {name} of {str(path)!r} cannot be read ({type(exc).__name__}): computed again", stacklevel=5
                )
                continue
            if _digest(spec, sl, block) != mark:
                raise ResumeError(
                    f"cannot resume: chunk {name} of {str(path)!r} does not match its digest (edited, "
                    f"damaged or from another run); remove {str(path)!r} to start afresh"
                )
            done[name] = chunk_variables(block, spec["dims"])[1:]
    return done


def write_store(
    ds: xr.Dataset, target: Path, spec: dict, blocks: list, run: Callable, task: Callable, report: Callable
) -> Path:
    """The Zarr part of :func:`stability.grids.chunked.write_atlas` (module docstring): the
    complete store, renamed to ``target`` (a store's name, :func:`is_store_path`) or left in
    ``<target>.parts`` for the netCDF writer (``spec["resume"]`` only); its path.

    ``spec`` is :func:`stability.grids.chunked.write_atlas`'s: the grid (``dims``,
    ``chunk_shape``, ``n_modes``), ``variables`` (the atlas variables stored), ``identity``,
    ``resume`` and ``overwrite``; ``blocks`` the (name, slice) of each chunk; ``run(todo, put,
    task)`` runs ``task(spec, sl)`` for each chunk of ``todo`` where the chunks run
    and hands ``put`` what it returns; ``task(spec, sl)`` computes a chunk; ``report()`` counts
    one (done or reused).
    """
    import dask.array as da

    resume, commit, overwrite = spec["resume"], is_store_path(target), spec["overwrite"]
    if commit:
        _check_target(target, overwrite)
    tmp = None  # a hidden store of this call only, removed by the emergency exit too (not .parts: kept)
    parts = parts_directory(target) if resume else Path(temporary_name(target, directory=True))
    if not resume:
        tmp = Temporary(str(parts), str(target))
    done: dict[str, tuple[bool, bool]] = {}

    def put(name: str, sl: dict[str, slice] | None, summary: tuple[bool, bool]) -> None:
        done[name] = summary
        report()
        checkpoint()

    try:
        if resume and any(parts.iterdir()):  # empty: just created by the lock
            for name, summary in _reopen(parts, ds, spec, blocks).items():
                put(name, None, summary)
        else:  # the layout, no values (resume: into the locked directory as it is: mode "a")
            layout = xr.zeros_like(ds[spec["variables"]].chunk(spec["chunk_shape"]))
            counts = [-(-ds.sizes[d] // n) for d, n in spec["chunk_shape"].items()]
            layout["chunk_digest"] = ([f"{d}_chunk" for d in spec["dims"]], da.zeros(counts, dtype=np.uint64, chunks=1))
            layout.to_zarr(parts, mode="a" if resume else "w", compute=False, consolidated=False)
        # the chunk function itself goes along to the workers (a test's injected fault too)
        run(
            [(name, sl) for name, sl in blocks if name not in done],
            put,
            partial(_write_region, path=str(parts), compute=task),
        )
        for sl in provisional(done, blocks) if "leading_growth_rate" in spec["variables"] else ():
            checkpoint()
            with open_store(parts) as stored:
                fixed = stored["max_growth_rate"].isel(sl).load().rename("leading_growth_rate")
            fixed.to_dataset().drop_vars(list(fixed.coords)).to_zarr(parts, region=sl, mode="r+", consolidated=False)
        if commit:
            _commit(parts, target, overwrite, tmp)
    except BaseException:
        if not resume:
            shutil.rmtree(parts, ignore_errors=True)
        raise
    finally:
        if tmp is not None and tmp.state != "committed":
            tmp.done(committed=False)
    return target if commit else parts


def _check_target(target: Path, overwrite: bool) -> None:
    """A new name, or (``overwrite=True``) an existing Zarr store; never anything else."""
    if os.path.lexists(target) and not overwrite:
        raise FileExistsError(f"output {str(target)!r} exists; pass overwrite=True to replace it")
    if os.path.lexists(target) and (target.is_symlink() or not (target / "zarr.json").is_file()):
        raise FileExistsError(f"output {str(target)!r} exists and is not a Zarr store; it is never replaced")


def _commit(parts: Path, target: Path, overwrite: bool, tmp: Temporary | None) -> None:
    """Rename the complete store to its name; an existing store (``overwrite``) is moved aside
    first and removed after, or put back if the rename fails. Another process creating the name
    meanwhile wins (the rename of a directory onto a non-empty one fails): FileExistsError; any
    other failure of the rename: OutputWriteError naming the cause."""
    checkpoint()
    kept, old = "it was removed" if tmp is not None else f"it is kept in {str(parts)!r}", None
    if os.path.lexists(target):
        _check_target(target, overwrite)
        old = target.with_name(f"{TEMPORARY_PREFIX}old-{secrets.token_hex(6)}-{target.name}")
        os.rename(target, old)
    if tmp is not None:
        tmp.state = "committing"
    try:
        os.rename(parts, target)
    except OSError as exc:
        if tmp is not None:
            tmp.state = "writing"
        if old is not None:
            try:
                os.rename(old, target)
            except OSError:
                kept += f"; the store it replaces could not be put back and is in {str(old)!r}"
        nothing = f"nothing was replaced (the complete store: {kept})"
        if exc.errno in (errno.EEXIST, errno.ENOTEMPTY, errno.ENOTDIR) and os.path.lexists(target):
            raise FileExistsError(
                f"output {str(target)!r} was created by another process while this run was computing; {nothing}"
            ) from None
        why = f"renaming the complete store to it failed ({exc.strerror})"
        raise OutputWriteError(f"cannot write {str(target)!r}: {why}; {nothing}", exc.errno, str(target)) from exc
    if tmp is not None:
        tmp.done(committed=True)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
