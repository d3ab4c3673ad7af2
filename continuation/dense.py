"""Dense output of a traced curve: cubic Hermite interpolation with the stored tangents.

Between two consecutive points ``p0``, ``p1`` of a branch with unit tangents ``t0``, ``t1``
the curve is approximated by the cubic Hermite curve (:mod:`continuation.interpolation`)
parametrised by the chord length ``d = |p1 - p0|``. Its distance from the true curve is
``O(d^4)`` (on a circle of curvature ``kappa``: ``kappa^3 d^4 / 128`` at the middle of the
step, tests/test_continuation_engine.py; 5.6e-7 on the sliding model's ``(q, sigma)`` curve at
the default steps of :func:`continuation.neutral_curve`), against ``kappa d^2 / 8`` for the
polyline (the chord error). Points and tangents are interpolated in the
variables they are given in; the tangents need only be parallel to the curve (each is oriented
along its segment's chord and normalised here).

:func:`dense` takes either a :class:`continuation.Branch` or a dataset of
:func:`continuation.neutral_curve` / :func:`continuation.fold_curve` (which store the tangents as
``tangent_<name>`` variables) and returns the curve sampled ``n`` times per step.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .engine import Branch
from .interpolation import hermite_eval

__all__ = ["dense", "hermite_samples"]


def hermite_samples(points: np.ndarray, tangents: np.ndarray, n: int = 16) -> np.ndarray:
    """Sample the piecewise cubic Hermite curve through ``points`` ``n`` times per segment.

    Parameters
    ----------
    points : numpy.ndarray, shape (m, dim)
        Consecutive points of one branch.
    tangents : numpy.ndarray, shape (m, dim)
        Tangents at the points (any length; the sign is taken from each segment's chord).
    n : int
        Samples per segment (``tau = 0, 1/n, ..., (n-1)/n``); the last point is added.

    Returns
    -------
    numpy.ndarray, shape ((m - 1) n + 1, dim)
        The first sample of each segment is its start point exactly, the last row the
        branch's last point.
    """
    P = np.asarray(points, dtype=float)
    T = np.asarray(tangents, dtype=float)
    if P.ndim != 2 or T.shape != P.shape:
        raise ValueError(f"points and tangents must have the same shape (m, dim), got {P.shape} and {T.shape}")
    if int(n) < 1:
        raise ValueError(f"n = {n!r}; use n >= 1")
    n = int(n)
    m = len(P)
    if m < 2:
        return P.copy()
    chord = P[1:] - P[:-1]
    d = np.linalg.norm(chord, axis=1)
    T = T / np.where(np.linalg.norm(T, axis=1) > 0, np.linalg.norm(T, axis=1), 1.0)[:, None]
    t0 = T[:-1] * np.where(np.einsum("ij,ij->i", T[:-1], chord) < 0, -1.0, 1.0)[:, None]
    t1 = T[1:] * np.where(np.einsum("ij,ij->i", T[1:], chord) < 0, -1.0, 1.0)[:, None]
    # (segment, sample, dim): the Hermite curve of each segment at tau = 0, 1/n, ..., (n-1)/n
    tau = (np.arange(n) / n)[None, :, None]
    out = hermite_eval(P[:-1, None, :], t0[:, None, :], P[1:, None, :], t1[:, None, :], tau, d[:, None, None])
    return np.concatenate([out.reshape(-1, P.shape[1]), P[-1:]], axis=0)


def dense(result: Any, n: int = 16) -> Any:
    """The curve between the traced points, by cubic Hermite interpolation (error ``O(h^4)``).

    Parameters
    ----------
    result : Branch or xarray.Dataset
        A branch of :func:`continuation.trace` / :func:`continuation.trace_both`, or the
        dataset of :func:`continuation.neutral_curve` or :func:`continuation.fold_curve`.
    n : int, default 16
        Samples per step.

    Returns
    -------
    numpy.ndarray or xarray.Dataset
        For a branch: the samples, shape ``((m - 1) n + 1, dim)``. For a dataset: a dataset
        along dimension ``sample`` with the traced variables (the parameters and
        ``frequency``) and ``branch``; each branch is interpolated on its own.

    Examples
    --------
    >>> import continuation
    >>> import stability  # a client of the engine: the tippe top's neutral curves
    >>> ds = stability.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=0.5))
    >>> curve = continuation.dense(ds, 8)
    >>> curve.sizes["sample"] == 8 * (ds.sizes["point"] - 1) + 1
    True
    """
    if isinstance(result, Branch):
        return hermite_samples(result.points, result.tangents, n)
    import xarray as xr

    if not isinstance(result, xr.Dataset):
        raise TypeError(f"dense needs a Branch or a neutral-curve Dataset, got {type(result).__name__}")
    names = [str(k)[len("tangent_") :] for k in result.data_vars if str(k).startswith("tangent_")]
    if not names:
        raise ValueError("the dataset has no tangent_<name> variables (not made by neutral_curve or fold_curve?)")
    P = np.stack([result[k].values for k in names], axis=1)
    T = np.stack([result[f"tangent_{k}"].values for k in names], axis=1)
    br = result["branch"].values if "branch" in result else np.zeros(len(P), int)
    labels = np.unique(br)
    parts = [hermite_samples(P[br == b], T[br == b], n) for b in labels]
    S = np.concatenate(parts) if parts else np.zeros((0, len(names)))
    B = np.repeat(labels, [len(s) for s in parts])
    data = {k: ("sample", S[:, i], dict(result[k].attrs)) for i, k in enumerate(names)}
    data["branch"] = ("sample", B.astype(np.int32), {"long_name": "index of the traced branch"})
    out = xr.Dataset(data, coords={"sample": np.arange(len(S))})
    out.attrs.update(result.attrs)
    out.attrs["dense_output"] = f"cubic Hermite interpolation, {n} samples per step"
    return out
