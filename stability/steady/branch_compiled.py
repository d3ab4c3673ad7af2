"""Compiled pieces of the steady branch's continuation problem (:mod:`stability.steady.branch`).

* :func:`component`: the one non-trivial component of the precessing-frame residual
  ``F = f(y) - lam G y`` of the nonlinear model's compiled right-hand side
  (:func:`stability.nonlinear.kernels.rhs`) at the no-slip steady state of tilt ``theta`` and
  precession rate ``lam`` (:func:`stability.steady.family.state_core`);
* :func:`divided`: that component divided by ``sin(theta)`` (the vertical branch divided out),
  evaluated at ``theta + i h`` so that the value and its ``theta`` derivative are exact to
  rounding, at ``theta = 0`` too;
* :func:`residual_and_jacobian`: the problem's scaled residual and its gradient in
  ``(theta, log lam)``;
* :func:`jellett`: Jellett's integral of the state and its gradient
  (:func:`stability.nonlinear.quantities.jellett_integral`, complex steps);
* :func:`step`: the engine's ``compiled_step`` hook (:mod:`continuation.problem`): the
  engine's corrector, tangent and ``det [J; t^T]`` compiled (:func:`continuation.compiled.step`,
  the loop of its Python path), then the problem's constraints and test function at the new point.
"""

from __future__ import annotations

import math

import numpy as np

from continuation.compiled import norm
from continuation.compiled import step as corrector_step
from stability.jit import OPTIONS, njit, register_jitable

from ..nonlinear.kernels import rhs as model_rhs
from ..nonlinear.quantities import jellett_integral
from .family import state_core

__all__ = [
    "H",
    "component",
    "constraint_values",
    "divided",
    "jellett",
    "residual_and_jacobian",
    "step",
]

_JIT = dict(OPTIONS, cache=True)

#: the complex step
H = 1e-30
#: below this |sin(theta)| (but not 0) dR/dtheta is interpolated from the vertical state
NEAR_VERTICAL = 1e-4


@njit(**_JIT)
def component(theta, lam, p, q, code, n_full):
    """``F . e_2`` at the steady state ``(theta, lam)`` (both may be complex), azimuth 0:
    ``F = f(y) - lam G y`` with ``(G y)_2 = (K x omega)_2 = omega_1``."""
    y = np.zeros(n_full, dtype=np.complex128)
    state_core(theta, lam, q, 0.0, y)
    f = model_rhs(code, 0.0, y, p)
    return f[1] - lam * y[0]


@njit(**_JIT)
def divided(theta, lam, p, q, code, n_full):
    """``(F . e_2) / sin(theta)`` and its ``theta`` derivative (complex step at ``theta + i h``)."""
    z = theta + 1j * H
    r = component(z, lam + 0j, p, q, code, n_full) / np.sin(z)
    return r.real, r.imag / H


@njit(**_JIT)
def residual_and_jacobian(theta, ell, p, q, code, n_full, weight):
    """``R = divided / (lam^2 + weight)`` and ``dR/d(theta, ell)``, ``ell = log lam``.

    ``weight`` is the size of the gravity terms in units of ``lam^2``: ``mu fr_inv |q|``
    (:attr:`stability.steady.branch.SteadyBranchProblem.weight`; ``0`` for degenerate parameters). The divided component is
    ``A(theta) lam^2 + weight b(theta)`` (quadratic in the rates on the no-slip manifold, the
    normal force's moment ``~ mu fr_inv q``), so ``R = (A lam_hat^2 + b) / (lam_hat^2 + 1)`` with
    ``lam_hat^2 = lam^2 / weight``: ``O(1)`` terms at every scale of ``mu fr_inv |q|`` (the
    family's scale invariance, ``J^2 / (mu fr_inv)`` a function of ``q, sigma, mu, c`` only),
    so the engine's absolute tolerance is one relative to the size of the terms. The ``lam`` derivative of the divided component is a complex step in
    ``lam`` (a central difference where ``sin(theta) = 0``); the ``theta`` derivative the complex
    step of :func:`divided`, except for ``0 < |sin(theta)| < NEAR_VERTICAL`` (see the code)."""
    lam = np.exp(ell)
    r, r_t = divided(theta, lam, p, q, code, n_full)
    s = np.sin(theta)
    if s != 0.0 and abs(s) < NEAR_VERTICAL:
        # the complex step of a quotient by sin(theta) loses ~u / sin(theta) in the derivative
        # (theta = pi in floating point has sin = 1.2e-16); dR/dtheta is odd about the vertical
        # state theta_v, so take it from theta_v +- NEAR_VERTICAL (relative error ~1e-8, which
        # only slows Newton's convergence a little)
        theta_v = 0.0 if theta < 1.0 else math.pi
        d = theta - theta_v
        ref = theta_v + (NEAR_VERTICAL if d >= 0 else -NEAR_VERTICAL)
        r_t = divided(ref, lam, p, q, code, n_full)[1] * d / (ref - theta_v)
    if s != 0.0:
        # the complex step relative to lam (lam is ~sqrt(mu fr_inv |q|), of any size)
        r_l = (component(theta + 0j, lam * (1.0 + 1j * H), p, q, code, n_full) / s).imag / (H * lam)
    else:
        d = 1e-6 * lam  # relative to lam (of the family's scale, any size)
        r_l = (divided(theta, lam + d, p, q, code, n_full)[0] - divided(theta, lam - d, p, q, code, n_full)[0]) / (
            2.0 * d
        )
    sc = lam * lam + weight
    return r / sc, r_t / sc, lam * (r_l / sc - r * 2.0 * lam / (sc * sc))


@njit(**_JIT)
def jellett(theta, ell, q, sigma, mu):
    """``J`` at the state of ``(theta, log lam)`` and ``dJ/dtheta``, ``dJ/d(log lam)``."""
    lam = np.exp(ell)
    y = np.zeros(8, dtype=np.complex128)
    state_core(theta + 1j * H, lam + 0j, q, 0.0, y)
    j1 = jellett_integral(y[0], y[1], y[2], y[3], y[4], y[5], q, sigma, mu)
    state_core(theta + 0j, lam * (1.0 + 1j * H), q, 0.0, y)  # dJ/d(log lam): a step relative to lam
    j2 = jellett_integral(y[0], y[1], y[2], y[3], y[4], y[5], q, sigma, mu)
    return j1.real, j1.imag / H, j2.imag / H


@njit(**_JIT)
def constraint_values(theta, jel, jmax, jmin, degenerate):
    """``[theta, pi - theta, 1 - |J| / jmax(, |J| / jmin - 1)]`` (``>= 0`` on the branch; the
    cuts of ``J`` relative to their own size, so that the engine locates them to rounding at
    every scale of ``J``)."""
    g = np.empty(4 if degenerate else 3)
    g[0] = theta
    g[1] = math.pi - theta
    g[2] = 1.0 - abs(jel) / jmax
    if degenerate:
        g[3] = abs(jel) / jmin - 1.0
    return g


@register_jitable
def _residual_into(p, q, code, n_full, weight, u, jacobian, F, J):
    """The residual in the form of :func:`continuation.corrector.newton` (``J`` always filled)."""
    F[0], J[0, 0], J[0, 1] = residual_and_jacobian(u[0], u[1], p, q, code, n_full, weight)


@njit(**_JIT)
def step(p, q, sigma, mu, code, n_full, degenerate, weight, jmax, jmin, *corrector):
    """The engine's ``compiled_step`` (:mod:`continuation.problem`) for the steady branch:
    ``(ok, iterations, n_rj, n_r, v, J, tangent_ok, t, det, g, tests)``, with ``g`` the
    constraints and ``tests = [d(log |J|)/ds]`` at ``u = v * scale`` (unit tangent in ``u``)."""
    r = corrector_step(_residual_into, (p, q, code, n_full, weight), *corrector)
    tests = np.empty(1)
    if not r[0]:
        return (*r, np.empty(0), tests)
    scale = corrector[4]  # (guess, t_plane, anchor, h, scale, tol, max_iter, max_move)
    u = r[4] * scale
    jel, jt, jl = jellett(u[0], u[1], q, sigma, mu)
    g = constraint_values(u[0], jel, jmax, jmin, degenerate)
    tu = r[7] * scale
    tu = tu / norm(tu)
    tests[0] = (jt * tu[0] + jl * tu[1]) / abs(jel)  # d(log |J|)/ds: scale-free
    return (*r, g, tests)
