"""Shared fixtures and references: random points of the physical domain (seeded), mpmath roots
and the mpmath eigenvalues of eq. (11).

The tests exercise the installed package (issue 15 item 9): ``pytest`` (the console script)
does not put the repository root on ``sys.path`` and the import mode is ``importlib``
(pyproject.toml; ``tests/`` is on the path for these helpers). ``python -m pytest`` does put the
current directory first; when the installed package is not an editable install of this tree,
that entry is removed here before anything imports ``stability``, and
:func:`pytest_sessionstart` fails the run with a clear message if ``stability`` still comes
from somewhere other than the install.
"""

from __future__ import annotations

import json
import os
import sys
from importlib import metadata
from pathlib import Path

#: the repository this conftest belongs to
REPOSITORY = Path(__file__).resolve().parent.parent
#: the benchmark suites and their runner: beside the package, not installed; the tests of the
#: suites import them from here (``import suites``, ``import run``), appended so that they never
#: shadow an installed module
BENCHMARKS = REPOSITORY / "benchmarks"
if str(BENCHMARKS) not in sys.path:
    sys.path.append(str(BENCHMARKS))


def _install() -> tuple[bool, Path | None]:
    """(editable, source directory of an editable install) of the installed tippe-stability."""
    # the metadata of the install, not a stale tippe_stability.egg-info of the tree (which
    # `python -m pytest` would find first, through the current directory on sys.path)
    found = [
        d
        for d in metadata.distributions(name="tippe-stability")
        if Path(str(d.locate_file(""))).resolve() != REPOSITORY
    ]
    if not found:
        raise SystemExit(
            "tests/conftest.py: tippe-stability is not installed in this Python "
            f"({sys.executable}); install it first: pip install '.[test]'"
        )
    dist = found[0]
    info = json.loads(dist.read_text("direct_url.json") or "{}")
    editable = bool(info.get("dir_info", {}).get("editable", False))
    url = str(info.get("url", ""))
    source = Path(url[len("file://") :]).resolve() if editable and url.startswith("file://") else None
    return editable, source


_EDITABLE, _SOURCE = _install()
if not _EDITABLE:  # `python -m pytest` puts the current directory first: it would shadow the install
    sys.path[:] = [p for p in sys.path if Path(p or os.getcwd()).resolve() != REPOSITORY]


def pytest_sessionstart(session) -> None:
    """Fail at once if the tests would not exercise the installed package."""
    import pytest

    import stability

    here = Path(stability.__file__).resolve()
    # the tree's own package directory (a venv inside the repository, as the README makes, is an install)
    inside = here.parent == REPOSITORY / "stability"
    if _EDITABLE and _SOURCE is not None and _SOURCE != REPOSITORY:
        pytest.exit(
            f"tests/conftest.py: tippe-stability is installed editable from {_SOURCE}, not from "
            f"this repository ({REPOSITORY}): these tests would test that tree; reinstall "
            "with pip install -e . from here, or use this repository's venv",
            returncode=4,
        )
    if not _EDITABLE and inside:
        pytest.exit(
            f"tests/conftest.py: stability was imported from the source tree ({here}), not from "
            "the installed package; run `pytest` (not `python -m pytest`, which puts the current "
            "directory first on sys.path), or `python -P -m pytest`",
            returncode=4,
        )


import numpy as np  # noqa: E402
import pytest  # noqa: E402
import xarray as xr  # noqa: E402


def random_domain_points(n: int, seed: int, *, alpha_v: bool = True) -> dict[str, np.ndarray]:
    """``n`` points spread over the physical domain.

    mu in [0.5, 6]; q uniform in |q| < 0.98 / sqrt(mu) (the mass matrix stays invertible);
    sigma uniform in (0.02, 2 (1 - mu q^2)]; fr_inv uniform in [0, 3]; alpha_v log-uniform in
    [1e-2, 1e1].
    """
    rng = np.random.default_rng(seed)
    mu = rng.uniform(0.5, 6.0, n)
    q = rng.uniform(-0.98, 0.98, n) / np.sqrt(mu)
    sigma = rng.uniform(0.01, 1.0, n) * 2.0 * (1.0 - mu * q * q)
    fr_inv = rng.uniform(0.0, 3.0, n)
    out = {"q": q, "fr_inv": fr_inv, "sigma": sigma, "mu": mu}
    if alpha_v:
        out["alpha_v"] = 10.0 ** rng.uniform(-2.0, 1.0, n)
    return out


@pytest.fixture
def domain_points():
    """Factory fixture for :func:`random_domain_points`."""
    return random_domain_points


def mp_polyroots(coeffs, **kwargs):
    """``mpmath.polyroots`` of coefficients in descending powers, on any mpmath version.

    mpmath 1.4 deprecates the descending order and takes ``asc=True`` for ascending
    coefficients; mpmath 1.3 has no ``asc`` keyword (it raises TypeError).
    """
    import mpmath

    try:
        return mpmath.polyroots(list(coeffs)[::-1], asc=True, **kwargs)
    except TypeError:
        return mpmath.polyroots(list(coeffs), **kwargs)


def mp_sliding_eigenvalues(q, fr_inv, sigma, alpha_v, mu, dps: int = 50) -> list:
    """Eigenvalues of eq. (11), ``M x' = A x``, at ``dps`` digits (``mpmath.eig`` of ``M^-1 A``,
    the matrices typed from the paper, independently of :mod:`stability.models.sliding`)."""
    import mpmath as mp

    with mp.workdps(dps):
        q, F, sg, a, m = (mp.mpf(float(v)) for v in (q, fr_inv, sigma, alpha_v, mu))
        i = mp.mpc(0, 1)
        M = mp.matrix([[1, 0, i * m * q], [0, 1, 0], [-i * q, 0, 1]])
        A = mp.matrix(
            [
                [-a + i * (sg - 1), i * (-(sg - 1) + m * q * F), i * a],
                [-i, i, 0],
                [-(q + i * a / m), q, -a / m],
            ]
        )
        return list(mp.eig(M**-1 * A, left=False, right=False))


def assert_same_atlas(a: xr.Dataset, b: xr.Dataset) -> None:
    """Two atlases identical in every value, coordinate and attribute but ``history``."""
    a, b = a.copy(), b.copy()
    a.attrs.pop("history", None)
    b.attrs.pop("history", None)
    xr.testing.assert_identical(a, b)


def kept_chunks(out) -> int:
    """The chunks the resumable store of output ``out`` (``<out>.parts``, a Zarr store) marks
    complete: a non-zero digest (:mod:`stability.grids.store`)."""
    from stability.grids.store import parts_directory

    with xr.open_dataset(parts_directory(out), engine="zarr", consolidated=False, chunks=None) as z:
        return int((z["chunk_digest"].values != 0).sum())


def interrupt_resumable_run(ds: xr.Dataset, out, monkeypatch, kept: int) -> None:
    """Run ``write_atlas(ds, out, resume=True)`` and press Ctrl-C once ``kept`` chunks are done:
    the resumable store then holds those chunks and no output file exists (both asserted)."""
    import stability.grids.chunked as dist

    real = dist._compute_block
    calls = []

    def compute(spec, sl):
        if len(calls) == kept:
            raise KeyboardInterrupt
        calls.append(sl)
        return real(spec, sl)

    monkeypatch.setattr(dist, "_compute_block", compute)
    with pytest.raises(KeyboardInterrupt):
        dist.write_atlas(ds, out, resume=True)
    monkeypatch.undo()
    assert not out.exists() and kept_chunks(out) == kept


def assert_resume_completes(ds: xr.Dataset, out, reference: xr.Dataset, monkeypatch, missing: int) -> None:
    """After a faulted run: ``write_atlas(ds, out, resume=True)`` computes only the ``missing``
    chunks not kept in the parts store, removes the store and writes an atlas identical to
    ``reference``. Undoes the caller's ``monkeypatch`` first (the injected fault), then counts
    the calls of the real chunk function."""
    import stability
    import stability.grids.chunked as dist

    monkeypatch.undo()
    calls = []
    original = dist._compute_block
    monkeypatch.setattr(dist, "_compute_block", lambda spec, sl: calls.append(sl) or original(spec, sl))
    dist.write_atlas(ds, out, resume=True)
    assert len(calls) == missing  # only the chunks not kept
    assert not dist.parts_directory(out).exists()
    assert_same_atlas(stability.open_atlas(out), reference)
