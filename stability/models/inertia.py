"""Transverse moments of inertia derived from (q, mu), computed without cancellation.

In units of A0 (the transverse moment about the sphere centre O):

* about G (parallel axes, O -> G at distance q R): ``A_G = 1 - mu q^2``; it is the determinant
  of the mass matrix of eq. (11) and vanishes at the edge of the physical domain;
* about the contact point C (G -> C at distance (1 + q) R): ``A_C = A_G + mu (1 + q)^2
  = 1 + mu (1 + 2 q)``.

Near the domain edge ``1 - mu q^2`` loses all its digits to cancellation if evaluated
naively (relative error ``u / A_G``, so 1e-10 at ``A_G = 1e-6``). :func:`transverse_inertia_g`
evaluates it with error-free transformations (Dekker's product, Knuth's sum), which makes it
accurate to a few units of round-off relative to ``A_G`` itself, for the floating-point q and
mu given; :func:`transverse_inertia_contact` adds positive terms only.
"""

from __future__ import annotations

import numpy as np

__all__ = ["transverse_inertia_g", "transverse_inertia_contact"]

_SPLITTER = 134217729.0  # 2**27 + 1 (Veltkamp)


def _split(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    c = _SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


def _two_product(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``a b = p + e`` exactly (Dekker)."""
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, e


def _two_sum(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``a + b = s + e`` exactly (Knuth)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def transverse_inertia_g(q: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """``A_G = 1 - mu q^2`` (units of A0), accurate relative to ``A_G`` near the domain edge.

    Parameters
    ----------
    q, mu : array_like
        Centre-of-mass offset and scaled mass.

    Returns
    -------
    numpy.ndarray
    """
    q = np.asarray(q, dtype=float)
    mu = np.asarray(mu, dtype=float)
    t, te = _two_product(q, q)
    u, ue = _two_product(mu, t)
    ue = ue + mu * te
    s, se = _two_sum(np.ones_like(u), -u)
    return s + (se - ue)


def transverse_inertia_contact(q: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """``A_C = A_G + mu (1 + q)^2 = 1 + mu (1 + 2 q)`` (units of A0), a sum of positive terms."""
    q = np.asarray(q, dtype=float)
    return transverse_inertia_g(q, mu) + np.asarray(mu, dtype=float) * (1.0 + q) ** 2
