"""Transverse moments of inertia derived from (q, mu), computed without cancellation.

In units of A0 (the transverse moment about the sphere centre O):

* about G (parallel axes, O -> G at distance q R): ``A_G = 1 - mu q^2``; it is the determinant
  of the mass matrix of eq. (11) and vanishes at the edge of the physical domain;
* about the contact point C (G -> C at distance (1 + q) R): ``A_C = A_G + mu (1 + q)^2
  = 1 + mu (1 + 2 q)``.

Near the domain edge ``1 - mu q^2`` loses all its digits to cancellation if evaluated
naively (relative error ``u / A_G``, so 1e-10 at ``A_G = 1e-6``). :func:`inertia_g`
evaluates it with error-free transformations (Dekker's product, Knuth's sum), which makes it
accurate to a few units of round-off relative to ``A_G`` itself, for the floating-point q and
mu given; :func:`inertia_contact` adds positive terms only.

One source, three engines. :func:`inertia_g` and :func:`inertia_contact` are written in plain
arithmetic and registered with :func:`numba.extending.register_jitable`: called from Python
they run as written, on floats or on numpy arrays (elementwise, broadcasting); called from
``@njit`` code they are compiled into the caller. The spectral kernel, the parameter domain and the models all use these, so
``A_G`` is the same number, bit for bit, wherever it is computed (``fastmath`` is off in every
compiled caller: no reassociation, no contraction into fused multiply-adds).
:func:`transverse_inertia_g` and :func:`transverse_inertia_contact` are their array front ends.
"""

from __future__ import annotations

import numpy as np

from stability.jit import register_jitable

__all__ = ["inertia_contact", "inertia_g", "transverse_inertia_contact", "transverse_inertia_g", "two_product"]

_SPLITTER = 134217729.0  # 2**27 + 1 (Veltkamp)


@register_jitable
def two_product(a, b):
    """``(p, e)`` with ``p = fl(a b)`` and ``a b = p + e`` exactly (Dekker's product).

    Each factor is split by Veltkamp's method into halves of 26 bits (``c = (2**27 + 1) x``,
    ``hi = c - (c - x)``, ``lo = x - hi``), whose pairwise products are exact; ``e`` is their sum
    minus ``p`` in an order that is exact (Dekker 1971). Exact barring overflow of ``c``
    (``|x| < 2**996``) and underflow of the products. Plain arithmetic: floats, numpy arrays
    (broadcast together), numba. The one home of the split; :func:`inertia_g` and the
    exact domain margins of :mod:`stability.parameters` use it.
    """
    p = a * b
    c = _SPLITTER * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLITTER * b
    bh = c - (c - b)
    bl = b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@register_jitable
def inertia_g(q, mu):
    """``A_G = 1 - mu q^2`` (units of A0), accurate relative to ``A_G`` near the domain edge.

    ``q q = t + te`` and ``mu t = u + ue'`` exactly (:func:`two_product`), so
    ``mu q^2 = u + ue`` with ``ue = ue' + mu te`` up to the rounding of ``ue``; then
    ``1 - u = s + se`` exactly (Knuth's sum, written out): ``A_G = s + (se - ue)``. Plain
    arithmetic: floats, numpy arrays (broadcast together), numba.
    """
    t, te = two_product(q, q)
    u, ue = two_product(mu, t)
    ue = ue + mu * te
    s = 1.0 + (-u)
    bb = s - 1.0
    se = (1.0 - (s - bb)) + (-u - bb)
    return s + (se - ue)


@register_jitable
def inertia_contact(q, mu, a_g):
    """``A_C = A_G + mu (1 + q)^2 = 1 + mu (1 + 2 q)`` from ``A_G`` (a sum of positive terms)."""
    return a_g + mu * ((1.0 + q) * (1.0 + q))


def transverse_inertia_g(q: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """``A_G = 1 - mu q^2`` (units of A0) of array arguments (:func:`inertia_g`).

    Parameters
    ----------
    q, mu : array_like
        Centre-of-mass offset and scaled mass (broadcast together).

    Returns
    -------
    numpy.ndarray
    """
    return inertia_g(np.asarray(q, dtype=float), np.asarray(mu, dtype=float))


def transverse_inertia_contact(q: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """``A_C = A_G + mu (1 + q)^2 = 1 + mu (1 + 2 q)`` (units of A0) of array arguments."""
    q = np.asarray(q, dtype=float)
    mu = np.asarray(mu, dtype=float)
    return inertia_contact(q, mu, inertia_g(q, mu))
