"""Exact location of special points between two accepted points of a branch.

A *test function* ``phi(u, t)`` is a scalar evaluated at points of the curve (``t`` is the unit
tangent there). Between two accepted points ``u_a`` (pseudo-arclength ``h = 0``) and ``u_b``
(``h = h_b``) where ``phi`` changes sign, the curve is parametrised by ``h``: ``u(h)`` is the
corrector's solution of ``F(u) = 0``, ``t_a . (u - u_a) = h`` (a regular parametrisation while
the tangent turns by less than 90 degrees). The zero of ``phi(u(h), t(h))`` is found by Brent's
method to ``|dh| <= 1e-14 h_b`` (``scipy.optimize.brentq``).

Test functions used by the engine:

* fold (turning point) of component ``i``: ``phi = t_i``; at a simple fold ``t_i`` changes sign
  linearly in ``h`` and ``u_i`` is extremal, so the error of ``u_i`` there is quadratic in the
  error of ``h`` (negligible) and the other components are off by about
  ``|dt_i| / kappa`` (curvature ``kappa``), i.e. by the error of the Jacobian;
* a constraint ``g_j(u)`` reaching zero (end of a branch);
* any test function the problem provides.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["locate"]


def locate(
    point: Callable[[float], tuple[np.ndarray, np.ndarray]],
    phi: Callable[[np.ndarray, np.ndarray], float],
    h_a: float,
    h_b: float,
    phi_a: float,
    phi_b: float,
    at_a: tuple[np.ndarray, np.ndarray],
    at_b: tuple[np.ndarray, np.ndarray],
    rel_tol: float = 1e-14,
) -> tuple[float, np.ndarray, np.ndarray]:
    """Locate the zero of a test function between two points of a curve.

    Parameters
    ----------
    point : callable
        ``point(h) -> (u, t)``: the curve's point and unit tangent at pseudo-arclength ``h``.
    phi : callable
        Test function ``phi(u, t) -> float``.
    h_a, h_b : float
        Bracket in ``h``.
    phi_a, phi_b : float
        ``phi`` at the bracket's ends (opposite signs, or one of them zero).
    at_a, at_b : tuple of numpy.ndarray
        ``(u, t)`` at the ends (returned when ``phi`` is exactly zero there).
    rel_tol : float
        Tolerance on ``h`` relative to ``|h_b - h_a|``.

    Returns
    -------
    h, u, t
        The located point.

    Raises
    ------
    ValueError
        If ``phi_a`` and ``phi_b`` have the same (nonzero) sign.
    """
    if phi_a == 0:
        return h_a, at_a[0], at_a[1]
    if phi_b == 0:
        return h_b, at_b[0], at_b[1]
    if np.sign(phi_a) == np.sign(phi_b):
        raise ValueError("the test function does not change sign in the bracket")
    cache: dict[float, tuple[np.ndarray, np.ndarray]] = {}

    def f(h: float) -> float:
        if h == h_a:
            return phi_a
        if h == h_b:
            return phi_b
        cache[h] = point(h)
        return phi(*cache[h])

    from scipy.optimize import brentq  # here, not at import: a branch without events never pays for it

    width = abs(h_b - h_a)
    h = brentq(f, h_a, h_b, xtol=rel_tol * width + 1e-300, rtol=4.5 * np.finfo(float).eps, maxiter=200)
    if h not in cache:
        cache[h] = at_a if h == h_a else at_b if h == h_b else point(h)
    u, t = cache[h]
    return float(h), u, t
