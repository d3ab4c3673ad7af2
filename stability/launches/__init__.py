"""What a real top does when it is launched: :func:`~stability.launches.result.launch` and
:func:`~stability.launches.flip.flip_time` (issue 23).

Layer 5 (docs/architecture.md), beside the recipes: it asks the linear layer (critical spin),
the nonlinear runs (:func:`stability.simulate`) and the steady layer (final state, branch
points, classes) and converts between a top in SI units and the nondimensional sets. This
``__init__`` imports nothing (the public names are re-exported by the ``stability`` facade;
inside the package, import a name from its module).
"""
