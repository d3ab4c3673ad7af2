"""The names of :mod:`stability.files` (output files and their atomic commit) where the grids
used to import them from; the one home is :mod:`stability.files`."""

from ..files import *  # noqa: F403
from ..files import __all__  # noqa: F401
