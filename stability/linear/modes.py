"""Mode labels that follow each eigenvalue continuously along a path in parameter space.

Sorting by growth rate (the atlas's ``mode`` order) relabels modes wherever two growth rates
cross, so a curve drawn for "mode 0" jumps from one branch to another. Here the eigenvalues
along a 1-D path are matched step by step: at each step every permutation of the ``n`` modes
(``n <= 3``: at most 6) is tried against a linear extrapolation of the previous two steps, and
the one with the smallest total distance is kept. The extrapolation carries each branch
straight through a transversal crossing.

Near-collisions. Where two eigenvalues pass closer to each other than they move in one step
(an avoided crossing: the frictionless limit alpha_v -> 0 near the stability boundary of the
frictionless top, where the pair splits as ``sqrt(alpha_v)``, docs/hard_cases.md) the matching
is *ambiguous*: the data on the path cannot tell which branch is which, and the nearest
prediction can jump between branches. A step is ambiguous when some matched eigenvalue lies
farther from its prediction than a quarter of the smallest distance between two eigenvalues
(so that another assignment is within a factor of about two of the best). Given a
``solve`` function, :func:`track_modes` then bisects the step, computing eigenvalues at the
midpoints, until every sub-step is unambiguous: each label then follows the analytic branch,
however close the pair comes, provided it does not collide exactly. At an exact collision (a
defective point, e.g. alpha_v = 0 exactly) both continuations are continuous and the choice is
arbitrary by nature; the bisection stops at ``max_depth`` and keeps the best match.
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import permutations

import numpy as np

from ..errors import InputError

__all__ = ["ambiguous_steps", "principal_mode", "structural_zeros", "track_modes"]


def _match(pred: np.ndarray, cur: np.ndarray, perms: list[list[int]]) -> tuple[np.ndarray, bool]:
    """Best assignment of ``cur`` to the predictions, and whether it is ambiguous (module
    docstring)."""
    cost = [np.abs(cur[p] - pred).sum() for p in perms]
    best = cur[perms[int(np.argmin(cost))]]
    n = cur.size
    if n < 2:
        return best, False
    gaps = [abs(best[a] - best[b]) for a in range(n) for b in range(a + 1, n)]
    gaps += [abs(pred[a] - pred[b]) for a in range(n) for b in range(a + 1, n)]
    return best, bool(np.max(np.abs(best - pred)) > 0.25 * min(gaps))


def ambiguous_steps(eigenvalues: np.ndarray) -> np.ndarray:
    """Steps of a path whose mode matching is ambiguous (module docstring).

    Parameters
    ----------
    eigenvalues : numpy.ndarray of complex, shape (m, n)
        Eigenvalues along the path, as for :func:`track_modes`.

    Returns
    -------
    numpy.ndarray of bool, shape (m,)
        True at ``i`` if the step from ``i - 1`` to ``i`` is ambiguous (False at 0 and where
        the path is broken by NaN).
    """
    ev = track_modes(eigenvalues)
    perms = [list(p) for p in permutations(range(ev.shape[1]))]
    out = np.zeros(ev.shape[0], dtype=bool)
    for i in _whole_steps(ev):
        out[i] = _match(ev[i - 1], ev[i], perms)[1]
    return out


def _whole_steps(ev: np.ndarray) -> np.ndarray:
    """The steps ``i - 1 -> i`` of a path (rows of ``ev``) with no NaN at either end."""
    whole = ~np.isnan(ev).any(axis=1)
    return np.nonzero(whole[1:] & whole[:-1])[0] + 1


def track_modes(
    eigenvalues: np.ndarray,
    *,
    path: np.ndarray | None = None,
    solve: Callable[[float], np.ndarray] | None = None,
    max_depth: int = 40,
) -> np.ndarray:
    """Reorder eigenvalues along a path so that each column is one continuous branch.

    Parameters
    ----------
    eigenvalues : numpy.ndarray of complex, shape (m, n)
        Eigenvalues at ``m`` successive points of a path (any order within a row); rows
        with NaN (masked points) break the path and restart the tracking.
    path : numpy.ndarray of float, shape (m,), optional
        The path parameter at the ``m`` points (needed with ``solve``).
    solve : callable, optional
        ``solve(t)`` returns the ``n`` eigenvalues at path parameter ``t``. If given, an
        ambiguous step (a near-collision, module docstring) is bisected until its sub-steps
        are unambiguous, at most ``max_depth`` times.
    max_depth : int, default 40
        Largest number of bisections of one step.

    Returns
    -------
    numpy.ndarray of complex, shape (m, n)
        The same eigenvalues, columns following branches.
    """
    ev = np.array(eigenvalues, dtype=complex, copy=True)
    if ev.ndim != 2 or ev.shape[1] < 1:
        raise InputError(
            f"eigenvalues has shape {ev.shape}; it must be (points, modes): one row of "
            "eigenvalues per point of the path"
        )
    n = ev.shape[1]
    if solve is not None and path is None:
        raise InputError("track_modes: solve needs the path parameter values (path=)")
    perms = [list(p) for p in permutations(range(n))]

    def bridge(ta: float, ea: np.ndarray, tb: float, eb: np.ndarray, depth: int) -> np.ndarray:
        best, amb = _match(ea, eb, perms)
        if not amb or depth == 0:
            return best
        tm = 0.5 * (ta + tb)
        em = bridge(ta, ea, tm, np.asarray(solve(tm), dtype=complex), depth - 1)
        return bridge(tm, em, tb, eb, depth - 1)

    for i in _whole_steps(ev):
        pred = 2 * ev[i - 1] - ev[i - 2] if i >= 2 and not np.isnan(ev[i - 2]).any() else ev[i - 1]
        best, amb = _match(pred, ev[i], perms)
        if amb and solve is not None:
            best = bridge(float(path[i - 1]), ev[i - 1], float(path[i]), ev[i], max_depth)
        ev[i] = best
    return ev


def principal_mode(eigenvalues: np.ndarray) -> np.ndarray:
    """The tracked branch that reaches the largest growth rate along the path.

    A branch that is exactly zero wherever it is defined is a structural zero mode (the sliding
    top's ``s = 0`` at ``fr_inv = 0``, eq. 11): neutral by structure, it would otherwise be
    "largest" wherever every other mode decays, and a figure of the principal mode would show a
    flat zero instead of the decaying gyroscopic mode. It is skipped unless every branch is one.

    Parameters
    ----------
    eigenvalues : numpy.ndarray of complex, shape (m, n)

    Returns
    -------
    numpy.ndarray of complex, shape (m,)
        NaN where the path is (all NaN: outside the domain).
    """
    tracked = track_modes(eigenvalues)  # checks the shape
    defined = ~np.isnan(tracked)
    if not defined.any():
        return tracked[:, 0]
    with np.errstate(invalid="ignore"):
        top = np.nanmax(np.where(defined, tracked.real, -np.inf), axis=0)
    structural = np.all(structural_zeros(tracked.real, tracked.imag) | ~defined, axis=0) & defined.any(axis=0)
    if not structural.all():
        top = np.where(structural, -np.inf, top)
    return tracked[:, int(np.argmax(top))]


def structural_zeros(
    growth_rate: np.ndarray, frequency: np.ndarray, error_bound: np.ndarray | None = None
) -> np.ndarray:
    """Modes that are structurally zero: ``s = 0`` exactly (and an error bound of exactly 0,
    which the spectra give only to roots known by structure), e.g. the sliding top's zero root
    at ``fr_inv = 0`` (eq. 11)."""
    zero = (np.asarray(growth_rate) == 0) & (np.asarray(frequency) == 0)
    if error_bound is not None:
        zero &= np.asarray(error_bound) == 0
    return zero
