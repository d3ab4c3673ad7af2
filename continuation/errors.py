"""The engine's exception: a corrector (Newton's method) that did not converge.

Generic, like the rest of the engine. A client may subclass it (``stability.errors`` does, to
put it under its own base class); code that catches the engine's failures catches this class.
"""

from __future__ import annotations

__all__ = ["ConvergenceError"]


class ConvergenceError(RuntimeError):
    """Newton's method did not reach the requested residual.

    A failure to compute, not bad input: a :class:`RuntimeError` (the ``tippe`` command line
    exits with status 1 on it, not 2).
    """
