"""The stability flag of a steady state: one rule for states, branches and final states.

Two independent verdicts exist (docs/steady_states.md, sec. 4):

* the energy criterion (closed form, :func:`stability.steady.family.energy_test`): with
  friction, a strict minimum of the effective potential ``U_J`` on the Jellett level is
  stable, a maximum unstable (Lyapunov function ``E - U_J(c*)``, ``dE/dt = -alpha_v |V_c|^2``;
  no Hopf bifurcation is possible);
* the reduced Jacobian in the precessing frame (:mod:`stability.steady.linearisation`).

They agree wherever both decide (tests/test_steady_stability.py). The flag is taken from the
energy criterion, which is exact to rounding where the Jacobian's eigenvalue is only
``~1e3 u ||A||`` accurate (near folds and branch points), with two rules the energy cannot see:

* structural zeros, flagged marginal as the linear atlases do (docs/conventions.md): at
  ``fr_inv = 0`` or ``q = 0`` the normal force has no moment about G at a no-slip state, and
  continua of rolling motions lie next to the vertical states (eq. (11)'s exact zero root) and,
  for ``q = 0``, next to the tilted state ``c = 0``; such a state is at best marginal;
* without friction (``alpha_v = 0``) the energy is conserved: no state is asymptotically
  stable; the flag is the Jacobian's, "stable" demoted to "marginal".

A test within ``REL_TOL`` of zero (relative to the size of its terms) is marginal: a state at a
fold or a branch point, or a level that touches one.
"""

from __future__ import annotations

from ..errors import InputError
from ..products import MARGINAL, STABLE, UNSTABLE

__all__ = ["REL_TOL", "RULE", "flag_of"]

#: relative tolerance of the energy test (a test below it in magnitude is marginal)
REL_TOL = 1e-12

#: the rule in words (datasets carry it as an attribute)
RULE = (
    "energy criterion (strict minimum of U_J = J^2/(2 D) + mu fr_inv (1 + q c) on the Jellett level: "
    "stable; maximum: unstable; |test| <= 1e-12 of its terms: marginal); structural zeros "
    "(fr_inv = 0 or q = 0 at the vertical states, q = 0 at the tilted state) marginal; alpha_v = 0: "
    "the reduced Jacobian's verdict with stable demoted to marginal"
)


def flag_of(
    kind: str,
    test: float,
    scale: float,
    *,
    q: float,
    fr_inv: float,
    alpha_v: float,
    jacobian_verdict: int | None = None,
) -> int:
    """The stability flag (0 stable, 1 marginal, 2 unstable) of one steady state.

    Parameters
    ----------
    kind : {"upright", "inverted", "tilted"}
    test, scale : float
        :func:`stability.steady.family.energy_test`.
    q, fr_inv, alpha_v : float
    jacobian_verdict : int, optional
        :func:`stability.steady.linearisation.modes_verdict`; required when ``alpha_v = 0``.

    A state with a structurally neutral mode (a neighbouring continuum of no-slip motions:
    vertical states at ``fr_inv = 0`` or ``q = 0``, the tilted state at ``q = 0``) is at best
    marginal.
    """
    if alpha_v == 0.0:
        if jacobian_verdict is None:
            raise InputError("alpha_v = 0: the flag needs the Jacobian's verdict (no dissipation)")
        return MARGINAL if jacobian_verdict == STABLE else int(jacobian_verdict)
    tol = REL_TOL * scale
    if test < -tol:
        return UNSTABLE
    structural = q == 0.0 or (kind != "tilted" and fr_inv == 0.0)
    return MARGINAL if test <= tol or structural else STABLE
