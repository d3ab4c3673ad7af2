"""The sign of each mode's growth rate, each measured against its own scale.

The stability flag of :mod:`stability.linear.spectra` calls a mode neutral when
``|Re s| <= 4 e + 16 u max|s|``: the second term is a floor relative to the *largest* mode, which
is right for a map of the spectrum but not for deciding on which side of a crossing a point
lies. Where the growth rates near the crossing are tiny, the floor (or the root's own bound
``e ~ u |s|``) swallows them: at ``alpha_v = 1e-12`` the sliding top's crossing mode has
``Re s ~ 0.3 alpha_v (sigma - sigma_c)``, at ``alpha_v = 1e12`` the slow modes' growth rates are
``O(1/alpha_v)`` beside a slip mode of ``-1.3 alpha_v`` (docs/hard_cases.md, section 3). The
questions that need a *sign* (thresholds and critical spins, the start points of neutral
curves, which mode leads) ask this module instead.

Per mode (:func:`mode_signs`):

1. a structural zero (``s = 0`` with bound 0, from an exactly zero trailing coefficient), or a
   root with ``Re s = 0`` of a conservative polynomial (``p(i w) = e^{i theta} P(w)``, ``P``
   real: the real part is zero by structure) is ``NEUTRAL``;
2. a root whose real part exceeds four times its own error bound, ``|Re s| > 4 e``, has that
   sign (``GROWS`` or ``DECAYS``);
3. otherwise the structured estimate ``g`` of :func:`stability.linear.roots.axis_growth` (one
   Newton step from ``i Im s`` with the real and imaginary parts of ``p(i w)`` evaluated
   separately) decides where ``|g| > 4 e_g``;
4. else the mode is ``UNRESOLVED``: its growth rate is within rounding of zero.

A point (the ``state`` of :func:`growth`) is ``UNSTABLE`` if some mode grows, else
``UNDECIDED`` if some mode is unresolved, else ``MARGINAL`` if some mode is neutral by
structure, else ``STABLE``.
The growth estimate of each mode (``Re s`` where it is resolved, ``g`` otherwise, ``-inf`` for
the structurally neutral ones) is returned too, for searches that follow the largest growth
rate (the pairs of thresholds near a fold, the interpolation of a start point).

The floor of the stability flag stays where it belongs, in the atlases (a map of
spectra, whose flag says "marginal" where a mode is within rounding of the axis relative to the
spectrum's scale): docs/hard_cases.md, section 3.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from .. import execution
from ..models import LinearModel, get_model
from .roots import axis_growth_many
from .spectra import MARGINAL, STABLE, UNSTABLE, Spectrum, spectrum

__all__ = [
    "DECAYS",
    "GROWS",
    "NEUTRAL",
    "UNDECIDED",
    "UNRESOLVED",
    "Growth",
    "axis_products",
    "conservative_phases",
    "growth",
    "mode_signs",
]

#: mode codes of :func:`mode_signs`
DECAYS, NEUTRAL, GROWS, UNRESOLVED = -1, 0, 1, 2

#: the point state "no mode grows, some mode's sign is unresolved" (besides the STABLE,
#: MARGINAL and UNSTABLE of :mod:`stability.linear.spectra`; -1 outside the domain)
UNDECIDED = 3


class Growth(NamedTuple):
    """Spectra with the sign of every mode's growth rate (:func:`growth`).

    Attributes
    ----------
    spectrum : Spectrum
        The spectra (:func:`stability.spectrum`).
    sign : numpy.ndarray of int8, shape grid + (n_modes,)
        ``DECAYS`` (-1), ``NEUTRAL`` (0), ``GROWS`` (1) or ``UNRESOLVED`` (2); ``UNRESOLVED``
        outside the domain.
    estimate : numpy.ndarray of float, shape grid + (n_modes,)
        The growth rate as resolved: ``Re s`` where ``|Re s| > 4 e``, else the structured
        estimate ``g``; ``-inf`` for a mode neutral by structure, NaN outside the domain.
    state : numpy.ndarray of int8, shape grid
        ``STABLE`` (0), ``MARGINAL`` (1), ``UNSTABLE`` (2), ``UNDECIDED`` (3); -1 outside.
    """

    spectrum: Spectrum
    sign: np.ndarray
    estimate: np.ndarray
    state: np.ndarray


def axis_products(c: np.ndarray) -> np.ndarray:
    """``c_k i^k`` for the coefficients ``c`` (..., n+1) of ``p(s)`` (highest power ``k`` first):
    the coefficients of ``p(i w)`` in powers of ``w``, exactly (products with 1, i, -1, -i)."""
    c = np.asarray(c, dtype=complex)
    products: np.ndarray = c * np.array([1.0, 1j, -1.0, -1j])[np.arange(c.shape[-1] - 1, -1, -1) % 4]
    return products


def conservative_phases(c: np.ndarray) -> np.ndarray:
    """The common phase of the ``c_k i^k`` (:func:`axis_products`) of each polynomial ``c``
    (..., n+1): 0 if all are real, 1 if all are imaginary (tested exactly: products with 1, i,
    -1, -i, so an exact zero part is structure), -1 if neither. A polynomial with a phase is
    conservative: a root with ``Re s = 0`` is neutral by structure (docs/conventions.md)."""
    d = axis_products(c)
    return np.where(np.all(d.imag == 0, axis=-1), 0, np.where(np.all(d.real == 0, axis=-1), 1, -1))


def mode_signs(c: np.ndarray, roots: np.ndarray, bound: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The sign of each root's real part and its growth estimate (module docstring).

    Parameters
    ----------
    c : array_like of complex, shape (..., n+1)
        The polynomials (highest power first) whose roots are ``roots``.
    roots : array_like of complex, shape (..., m)
        Roots (any method; NaN where there is none), ``m <= n``.
    bound : array_like of float, shape (..., m)
        Their absolute error bounds.

    Returns
    -------
    sign : numpy.ndarray of int8, shape (..., m)
        ``DECAYS``, ``NEUTRAL``, ``GROWS`` or ``UNRESOLVED`` (also for NaN roots).
    estimate : numpy.ndarray of float, shape (..., m)
        ``Re s`` where resolved by its bound, else ``g``; ``-inf`` where neutral by structure.
    """
    c = np.asarray(c, dtype=complex)
    r = np.asarray(roots, dtype=complex)
    e = np.asarray(bound, dtype=float)
    shape = r.shape
    flat_c = np.ascontiguousarray(np.broadcast_to(c, shape[:-1] + c.shape[-1:]).reshape(-1, c.shape[-1]))
    flat_r = r.reshape(-1, shape[-1])
    flat_e = e.reshape(-1, shape[-1])
    g = np.empty(flat_r.shape)
    eg = np.empty(flat_r.shape)
    w = np.ascontiguousarray(flat_r.imag)
    execution.pick(axis_growth_many, len(flat_c))(flat_c, w, g, eg)  # stability.execution's rule
    re = flat_r.real
    with np.errstate(invalid="ignore"):
        own = np.abs(re) > 4.0 * flat_e
        by_g = ~own & (np.abs(g) > 4.0 * eg)
    structural = ((re == 0) & (flat_r.imag == 0) & (flat_e == 0)) | (
        (re == 0) & (conservative_phases(flat_c) >= 0)[:, None]
    )
    sign = np.full(flat_r.shape, UNRESOLVED, dtype=np.int8)
    sign[own] = np.where(re[own] > 0, GROWS, DECAYS)
    sign[by_g] = np.where(g[by_g] > 0, GROWS, DECAYS)
    sign[structural] = NEUTRAL
    estimate = np.where(own | ~np.isfinite(g), re, g)
    estimate = np.where(structural, -np.inf, estimate)
    return sign.reshape(shape), estimate.reshape(shape)


def growth(
    model: str | LinearModel, *, mask_unphysical: bool = True, parallel: bool | None = None, **params: Any
) -> Growth:
    """Spectra of ``model`` at ``params`` (:func:`stability.spectrum`, the kernel) with the sign
    of every mode's growth rate decided against its own scale (module docstring).

    Parameters
    ----------
    model : str or LinearModel
    mask_unphysical : bool, default True
        As :func:`stability.spectrum` (outside points: state -1).
    parallel : bool, optional
        As :func:`stability.spectrum`.
    **params
        The model's parameters (broadcast together).

    Returns
    -------
    Growth
    """
    m = get_model(model)
    sp = spectrum(m, mask_unphysical=mask_unphysical, parallel=parallel, **params)
    shape = sp.inside.shape
    n = sp.eigenvalues.shape[-1]
    sign = np.full(shape + (n,), UNRESOLVED, dtype=np.int8)
    estimate = np.full(shape + (n,), np.nan)
    state = np.full(shape, -1, dtype=np.int8)
    if sp.inside.any():
        inside = sp.inside
        c = np.asarray(m.coefficients(**{k: np.asarray(v)[inside] for k, v in sp.params.items()}), dtype=complex)
        s, est = mode_signs(c, sp.eigenvalues[inside], sp.error_bound[inside])
        sign[inside], estimate[inside] = s, est
        # the point's state (module docstring): the first that holds of a growing, an unresolved,
        # a structurally neutral mode
        cases = [(s == k).any(axis=-1) for k in (GROWS, UNRESOLVED, NEUTRAL)]
        state[inside] = np.select(cases, [UNSTABLE, UNDECIDED, MARGINAL], STABLE)
    return Growth(sp, sign, estimate, state)
