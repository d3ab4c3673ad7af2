"""Where the chunks of a chunked atlas run: this process, a local cluster, or an existing one.

:func:`dask_client`: in this process by default (chunks one after the other, each using every
core through the kernel's threads); a LocalCluster on 127.0.0.1 with ``workers=N``; an existing
cluster with ``scheduler="tcp://host:port"`` or the path of a scheduler file. With a cluster,
results come back to this process to be written to netCDF
(:func:`stability.grids.chunked.write_atlas`), so no file system needs to be shared; a Zarr store
(and a resumable run) is written by the workers themselves, on a file system they share with
this process (:mod:`stability.grids.store`).
"""

from __future__ import annotations

import contextlib
import json
import logging
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from ..errors import InputError, require_extra
from ..parameters import check_integer

__all__ = ["dask_client"]


@contextlib.contextmanager
def dask_client(*, workers: int | None = None, scheduler: str | None = None) -> Iterator[Any]:
    """Where chunks run: None (this process), a LocalCluster, or an existing cluster.

    Parameters
    ----------
    workers : int, optional
        Start a LocalCluster of this many worker processes (one thread each) on 127.0.0.1,
        closed on exit.
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:port``) or the path of its scheduler
        file (``dask scheduler --scheduler-file``).

    Yields
    ------
    distributed.Client or None
        None when neither is given: chunks are computed in this process.
    """
    if workers is not None and scheduler is not None:
        raise InputError(
            f"workers = {workers!r} and scheduler = {scheduler!r} were both given: pass workers=N "
            "for a local cluster or scheduler=ADDRESS for an existing one, not both"
        )
    if workers is None and scheduler is None:
        yield None
        return
    require_extra("distributed", "cluster", "workers= or scheduler= (a dask cluster)")
    from distributed import Client, LocalCluster

    if workers is not None:
        if (workers := check_integer("workers", workers, minimum=1)) > 1024:
            raise InputError(f"workers = {workers} is outside the allowed range: 1 <= workers <= 1024")
        local = dict(threads_per_worker=1, host="127.0.0.1", dashboard_address=None, silence_logs=logging.CRITICAL)
        with LocalCluster(n_workers=workers, **local) as cluster, Client(cluster) as client:
            yield client
        return
    address = str(scheduler)
    if "://" not in address:  # a scheduler file, as `dask scheduler --scheduler-file` writes it
        if not Path(address).is_file():
            raise FileNotFoundError(
                f"scheduler {address!r} is neither an address (tcp://host:port) nor an existing scheduler file"
            )
        try:
            address = json.loads(Path(address).read_text())["address"]
        except (ValueError, KeyError, TypeError, UnicodeDecodeError):
            raise InputError(
                f"scheduler file {str(scheduler)!r} is not a dask scheduler file (JSON with an "
                "'address', as written by `dask scheduler --scheduler-file`)"
            ) from None
    try:
        client = Client(address, timeout="20s")
    except (OSError, TimeoutError) as exc:
        raise ConnectionError(
            f"cannot reach the dask scheduler {str(scheduler)!r} (address {address}): {exc}"
        ) from None
    with client:
        yield client
