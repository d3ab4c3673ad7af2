"""What a real top does when it is launched: :func:`launch` and :func:`flip_time` (issue 23).

Layer 5 (docs/architecture.md), beside the recipes: it asks the linear layer (critical spin),
the nonlinear runs (:func:`stability.simulate`) and the steady layer (final state, branch
points, classes) and converts between a top in SI units and the nondimensional sets.
"""

from .flip import FlipRun, flip_time, launch_state, run_launch
from .result import Launch, launch

__all__ = ["FlipRun", "Launch", "flip_time", "launch", "launch_state", "run_launch"]
