"""Linear stability of a steady state, in the frame that precesses with it.

Method (docs/steady_states.md, sec. 4.2). The state of the sliding sphere
(:mod:`stability.nonlinear.sliding`) without its cyclic position ``X0`` is
``y = (omega, k, V0_h)`` (8 reals). In the frame turning at the precession rate ``lam`` about
``K`` a steady state is an equilibrium of ``F(y) = f(y) - lam G y``, ``f`` the model's
compiled right-hand side and ``G y = (K x omega, K x k, K x V0)`` the generator of rotations
about ``K``. Its Jacobian ``A = Df(y*) - lam G`` is taken by the complex step
(``J e_j = Im f(y + i h e_j) / h``, ``h = 1e-30``: exact to rounding, no subtraction), on the
model's own right-hand side through the compiled dispatch :func:`stability.nonlinear.kernels.rhs`.
Vertical states are invariant under the rotation: they are taken in the fixed frame
(``lam = 0``), where their spectrum is eq. (11)'s at the equivalent spin.

``A`` has three structural zero eigenvalues, which say nothing about stability and are removed
(:data:`REMOVED_NEUTRAL` names them):

1. ``k_norm``: ``|k|^2`` is an integral of ``k' = omega x k`` on all of ``R^8``; left null
   vector ``l1 = (0, k, 0)``. The ``|k|`` direction is not physical (the state space has
   ``|k| = 1``).
2. ``jellett``: Jellett's ``J = (K + q k) . I_G omega`` is conserved on ``|k| = 1`` by every
   contact force; ``l2 = grad J`` is a left null vector of ``A`` on ``ker l1``. Its right
   partner is the direction along the family (the neighbouring steady state at another
   ``J``, which precesses at another rate and so drifts along the orbit in this frame: a
   2 x 2 Jordan block with the next one).
3. ``rotation``: the symmetry about ``K``; the orbit direction ``v = G y*`` has ``A v = 0``
   (tilted states only: ``G y* = 0`` at a vertical state).

``W = ker l1 ∩ ker l2`` is invariant under ``A`` and contains ``v`` (``k . (K x k) = 0``, and
``J`` is invariant under rotations). With ``Q`` an orthonormal basis of
``span(l1, l2, v)^perp`` (the last columns of a complete QR of ``[l1, l2, v]``), the physical
eigenvalues are those of ``Q^T A Q``: 5 at a tilted state, 6 at a vertical one (eq. (11)'s
``s`` and ``conj(s)``). A mode is neutral if ``|Re s| <= 1e3 u ||A||_F`` (``u = 2^-53``; the
complex-step Jacobian and the small eigenproblem are accurate to a few ``u ||A||``), as
measured in docs/steady_states.md; :func:`modes_verdict` decides as docs/conventions.md does
(unstable if a mode grows beyond the tolerance, marginal if one is neutral and none grows,
stable otherwise).

Structural zeros that stay (real neutral families, flagged marginal by
:mod:`stability.steady.verdicts`): eq. (11)'s exact zero root at the vertical states when
``fr_inv = 0`` or ``q = 0``, the ``c = 0`` state at ``q = 0``, and, at ``alpha_v = 0``,
horizontal momentum (two more zeros).
"""

from __future__ import annotations

import math

import numpy as np

from stability.jit import njit

from ..errors import InputError
from ..execution import pick
from ..linear.spectra import spectrum
from ..nonlinear import get_nonlinear_model
from ..nonlinear.kernels import CODES
from ..nonlinear.kernels import rhs as model_rhs
from ..nonlinear.quantities import h_cg

__all__ = ["REMOVED_NEUTRAL", "ROTATION", "modes_verdict", "precessing_jacobians", "reduced_spectrum", "state_modes"]

#: the structural neutral directions removed before the growth rate is taken
REMOVED_NEUTRAL: dict[str, str] = {
    "k_norm": "|k|^2 is an integral of k' = omega x k on all of R^8 (left null vector (0, k, 0)); "
    "the |k| direction is not physical",
    "jellett": "Jellett's J = (K + q k) . I_G omega is conserved by every contact force (left null "
    "vector grad J on |k| = 1); its right partner is the family direction (the steady state "
    "at a neighbouring J)",
    "rotation": "symmetry about the vertical K: the orbit direction G y of a tilted state (A G y = 0; "
    "absent at the vertical states, which are invariant)",
}

#: a mode is neutral if |Re s| <= NEUTRAL_FACTOR * u * ||A||_F
NEUTRAL_FACTOR = 1e3
_U = 2.0**-53
_H = 1e-30

#: the generator of rotations about K on (omega, k, V0_h): G y = (K x omega, K x k, K x V0)
ROTATION = np.zeros((8, 8))
ROTATION[[0, 3, 6], [1, 4, 7]], ROTATION[[1, 4, 7], [0, 3, 6]] = -1.0, 1.0


#: batches of at least this many states get their Jacobians compiled; fewer run interpreted
#: (each state costs 8 interpreted right-hand sides, 0.76 ms measured: 512 of them about what
#: importing numba and loading the compiled one cost on a warm cache; benchmarks/cold_start.py)
JACOBIANS_COMPILED_FROM = 512


@njit(cache=True)
def _jacobians(Y, lam, p, code, n_full):
    """Complex-step Jacobians of the model's rhs on the first ``m`` components, minus lam G."""
    n, m = Y.shape
    out = np.empty((n, m, m))
    y = np.zeros(n_full, dtype=np.complex128)
    for i in range(n):
        # the step of a rate (omega, V0) relative to the state's rates, whose size is that of
        # the family's scale (any size); the axis k is a unit vector
        rates = 0.0
        for r in range(m):
            if r < 3 or r >= 6:
                rates = max(rates, abs(Y[i, r]))
        for j in range(m):
            for r in range(n_full):
                y[r] = 0.0
            for r in range(m):
                y[r] = Y[i, r]
            h = _H * rates if (j < 3 or j >= 6) and rates > 0.0 else _H
            y[j] += 1j * h
            f = model_rhs(code, 0.0, y, p)
            for r in range(m):
                out[i, r, j] = f[r].imag / h
        # - lam G (G: rotation about K on (omega, k, V0_h))
        for a in (0, 3, 6):
            out[i, a, a + 1] += lam[i]
            out[i, a + 1, a] -= lam[i]
    return out


def precessing_jacobians(y: np.ndarray, lam: np.ndarray, p: np.ndarray, model: str = "sliding") -> np.ndarray:
    """``A = Df(y) - lam G`` for a batch of states (complex step on the model's compiled rhs).

    Parameters
    ----------
    y : numpy.ndarray, shape (n, 8)
        States ``(omega, k, V0_h)``.
    lam : numpy.ndarray, shape (n,)
        Rate of the frame (the precession rate; 0: the fixed frame).
    p : numpy.ndarray
        Parameter vector of the kernels (:func:`stability.nonlinear.parameters.pack`).
    model : str
        A nonlinear model with a translating centre whose state is ``(omega, k, V0_h, X0)``.

    Returns
    -------
    numpy.ndarray, shape (n, 8, 8)
    """
    m = get_nonlinear_model(model)
    y = np.ascontiguousarray(np.atleast_2d(y), dtype=float)
    lam = np.ascontiguousarray(np.broadcast_to(np.asarray(lam, float), (y.shape[0],)))
    jacobians = pick(_jacobians, y.shape[0], below=JACOBIANS_COMPILED_FROM)  # stability.execution's rule
    return jacobians(y, lam, p, CODES[m.name], len(m.state))


def neutral_covectors(y: np.ndarray, *, q: float, sigma: float, mu: float) -> tuple[np.ndarray, np.ndarray]:
    """``l1 = (0, k, 0)`` and ``l2 = grad J`` at each state (shape ``(n, 8)`` each).

    ``grad J`` by the complex step of :func:`stability.nonlinear.quantities.h_cg` (the package's
    one formula of Jellett's integral) in the six directions of ``omega`` and ``k``; ``J`` does
    not depend on ``V0``."""
    y = np.atleast_2d(y)
    n = y.shape[0]
    l1 = np.zeros((n, 8))
    l1[:, 3:6] = y[:, 3:6]
    W = np.repeat(y[:, None, 0:3].astype(complex), 6, axis=1)
    K = np.repeat(y[:, None, 3:6].astype(complex), 6, axis=1)
    for j in range(3):
        W[:, j, j] += 1j * _H
        K[:, 3 + j, j] += 1j * _H
    g = h_cg(W.reshape(-1, 3), K.reshape(-1, 3), q=q, sigma=sigma, mu=mu).imag.reshape(n, 6) / _H
    l2 = np.zeros((n, 8))
    l2[:, 0:6] = g
    return l1, l2


def reduced_spectrum(
    y: np.ndarray,
    lam: np.ndarray,
    vertical: np.ndarray,
    p: np.ndarray,
    *,
    q: float,
    sigma: float,
    mu: float,
    model: str = "sliding",
) -> tuple[np.ndarray, np.ndarray]:
    """The physical eigenvalues of steady states, the structural zeros removed.

    Parameters
    ----------
    y : numpy.ndarray, shape (n, 8)
        Steady states ``(omega, k, V0_h)`` (any azimuth).
    lam : numpy.ndarray, shape (n,)
        Precession rates of the tilted states (ignored for the vertical ones: fixed frame).
    vertical : numpy.ndarray of bool, shape (n,)
        Which states are vertical (invariant under the rotation: ``l1``, ``l2`` removed only).
    p : numpy.ndarray
        Parameter vector of the kernels.
    q, sigma, mu : float

    Returns
    -------
    eigenvalues : numpy.ndarray of complex, shape (n, 6)
        Sorted by decreasing real part; tilted states have 5 (the 6th is NaN).
    scale : numpy.ndarray, shape (n,)
        ``||A||_F`` (for the neutral tolerance).
    """
    y = np.ascontiguousarray(np.atleast_2d(y), dtype=float)
    n = y.shape[0]
    vertical = np.broadcast_to(np.asarray(vertical, bool), (n,))
    lam = np.where(vertical, 0.0, np.broadcast_to(np.asarray(lam, float), (n,)))
    A = precessing_jacobians(y, lam, p, model)
    l1, l2 = neutral_covectors(y, q=q, sigma=sigma, mu=mu)
    ev = np.full((n, 6), np.nan + 0j)
    for sel in (~vertical, vertical):  # tilted states: the rotation's direction removed too
        if sel.any():
            L = np.stack([l1[sel], l2[sel]] + ([] if sel is vertical else [y[sel] @ ROTATION.T]), axis=2)
            Q = np.linalg.qr(L, mode="complete")[0][:, :, L.shape[2] :]  # (m, 8, 8 - removed)
            ev[sel, : 8 - L.shape[2]] = np.linalg.eigvals(np.swapaxes(Q, 1, 2) @ A[sel] @ Q)
    key = np.where(np.isnan(ev.real), -np.inf, ev.real)
    order = np.argsort(-key, axis=1, kind="stable")
    ev = np.take_along_axis(ev, order, axis=1)
    return ev, np.linalg.norm(A, axis=(1, 2))


def modes_verdict(ev: np.ndarray, scale: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Growth rate, number of neutral modes and the Jacobian's verdict (docs/conventions.md).

    A mode is neutral if ``|Re s| <= NEUTRAL_FACTOR u ||A||_F``; a state is unstable (2) if a
    mode grows beyond it, marginal (1) if a mode is neutral and none grows, stable (0)
    otherwise.

    Returns
    -------
    growth_rate : numpy.ndarray
        Largest real part (a neutral mode's is below the tolerance in magnitude).
    n_neutral : numpy.ndarray of int
    verdict : numpy.ndarray of int8
    """
    tol = NEUTRAL_FACTOR * _U * np.asarray(scale)[..., None]
    re = ev.real
    valid = ~np.isnan(re)
    neutral = valid & (np.abs(re) <= tol)
    grows = valid & (re > tol)
    verdict = np.where(grows.any(-1), 2, np.where(neutral.any(-1), 1, 0)).astype(np.int8)
    growth = np.max(np.where(valid, re, -np.inf), axis=-1)
    return growth, neutral.sum(-1), verdict


def state_modes(
    y: np.ndarray,
    lam: np.ndarray,
    vertical: np.ndarray,
    cosines: np.ndarray,
    spins: np.ndarray,
    p: np.ndarray,
    params: dict[str, float],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Eigenvalues, leading growth rate, its error bound, neutral count and verdict of steady
    states: tilted ones from the reduced Jacobian (:func:`reduced_spectrum`,
    :func:`modes_verdict`; bound ``NEUTRAL_FACTOR u ||A||_F``), vertical ones from eq. (11)
    (the Jacobian's only where eq. (11) cannot be evaluated: ``n = 0`` or an equivalent point
    outside its computable range). The vertical state ``c = +-1`` with spin ``n`` has ``|n|``
    times the spectrum of eq. (11) at the equivalent point
    :func:`stability.steady.family.equivalent_point` (``q c, fr_inv / n^2, alpha_v / |n|``),
    computed by :func:`stability.linear.spectra.spectrum` with its error bounds and its decision
    (rigorous where the reduced Jacobian's eigenvalues lose every digit: near ``A_G -> 0`` or at
    ``alpha_v >> |n|``); its bound is ``|n|`` times eq. (11)'s.
    What :func:`stability.steady_states` and :func:`stability.steady_branch` report."""
    ev, scale = reduced_spectrum(y, lam, vertical, p, q=params["q"], sigma=params["sigma"], mu=params["mu"])
    growth, n_neutral, verdict = modes_verdict(ev, scale)
    bound = NEUTRAL_FACTOR * _U * np.asarray(scale, float)
    q, fr_inv, alpha_v = params["q"], params["fr_inv"], params["alpha_v"]
    for i in np.nonzero(vertical)[0]:  # eq. (11)'s spectrum at the equivalent point, times |n|
        n = abs(spins[i])
        if not (n > 0.0 and math.isfinite(n)):
            continue  # eq. (11) cannot be evaluated: the Jacobian's
        point = dict(q=q * cosines[i], fr_inv=fr_inv / (n * n), alpha_v=alpha_v / n)
        try:
            sp = spectrum("sliding", **point, sigma=params["sigma"], mu=params["mu"])
        except InputError:  # an equivalent point outside eq. (11)'s computable range: the Jacobian's
            continue
        s = sp.eigenvalues * n
        pair = np.concatenate([s, np.conj(s)])  # the real state space carries each mode with conj(s)
        ev[i] = pair[np.argsort(-pair.real, kind="stable")]
        bound[i], growth[i] = float(sp.error_bound[0]) * n, ev[i, 0].real
        n_neutral[i], verdict[i] = 2 * int(np.sum(sp.neutral)), int(sp.stability)
    return ev, growth, bound, n_neutral, verdict
