"""Steady states of the sliding top: tilted states, their stability, the bifurcation diagram, the
final state and the high-spin classes (layer 4, docs/architecture.md; derivation in
docs/steady_states.md).

=====================  ===================================================================
module                 job
=====================  ===================================================================
``family``             the closed forms (the one home of D, P, lambda, J, E, branch points,
                       folds, c0, the roots of a Jellett level, the energy criterion)
``linearisation``      Jacobian of the nonlinear model's rhs in the precessing frame, the
                       three structural neutral directions removed, growth rates
``verdicts``           the stability flag of a steady state (one rule)
``products``           inputs and dataset attributes shared by the products
``states``             :func:`~stability.steady.states.steady_states`
``branch``             the continuation problem and
                       :func:`~stability.steady.branch.steady_branch`
``final``              :func:`~stability.steady.final.final_state`
``classes``            :func:`~stability.steady.classes.top_class`,
                       :func:`~stability.steady.classes.class_atlas`
``diagram``            :func:`~stability.steady.diagram.bifurcation_diagram` (a real top,
                       against the equivalent upright spin in its unit)
=====================  ===================================================================

Imports layers 0-3 only. This ``__init__`` imports nothing (the public names are re-exported
by the ``stability`` facade; inside the package, import a name from its module).
"""
