"""Mode labels that follow each eigenvalue continuously along a path in parameter space.

Sorting by growth rate (the atlas's ``mode`` order) relabels modes wherever two growth rates
cross, so a curve drawn for "mode 0" jumps from one branch to another. Here the eigenvalues
along a 1-D path are matched step by step: at each step every permutation of the ``n`` modes
(``n <= 3``: at most 6) is tried against a linear extrapolation of the previous two steps, and
the one with the smallest total distance is kept. Where two eigenvalues collide (a
defective point) the choice is arbitrary by nature; the extrapolation carries each branch
straight through a transversal crossing.
"""

from __future__ import annotations

from itertools import permutations

import numpy as np

__all__ = ["track_modes", "principal_mode"]


def track_modes(eigenvalues: np.ndarray) -> np.ndarray:
    """Reorder eigenvalues along a path so that each column is one continuous branch.

    Parameters
    ----------
    eigenvalues : numpy.ndarray of complex, shape (m, n)
        Eigenvalues at ``m`` successive points of a path (any order within a row); rows
        with NaN (masked points) break the path and restart the tracking.

    Returns
    -------
    numpy.ndarray of complex, shape (m, n)
        The same eigenvalues, columns following branches.
    """
    ev = np.array(eigenvalues, dtype=complex, copy=True)
    m, n = ev.shape
    perms = [list(p) for p in permutations(range(n))]
    for i in range(1, m):
        if np.isnan(ev[i]).any() or np.isnan(ev[i - 1]).any():
            continue
        if i >= 2 and not np.isnan(ev[i - 2]).any():
            pred = 2 * ev[i - 1] - ev[i - 2]
        else:
            pred = ev[i - 1]
        cost = [np.abs(ev[i, p] - pred).sum() for p in perms]
        ev[i] = ev[i, perms[int(np.argmin(cost))]]
    return ev


def principal_mode(eigenvalues: np.ndarray) -> np.ndarray:
    """The tracked branch that reaches the largest growth rate along the path.

    Parameters
    ----------
    eigenvalues : numpy.ndarray of complex, shape (m, n)

    Returns
    -------
    numpy.ndarray of complex, shape (m,)
    """
    tracked = track_modes(eigenvalues)
    with np.errstate(invalid="ignore"):
        best = np.nanargmax(np.nanmax(tracked.real, axis=0))
    return tracked[:, best]
