"""The names of :mod:`stability.files` (output files and their atomic commit) where the grids
used to import them from; the one home is :mod:`stability.files`."""

from ..files import (
    TEMPORARY_PREFIX,
    atomic_output,
    check_free_space,
    check_output_path,
    close_quietly,
    commit,
    describe_kind,
    temporary_name,
    write_error,
)

__all__ = [
    "TEMPORARY_PREFIX",
    "atomic_output",
    "check_free_space",
    "check_output_path",
    "close_quietly",
    "commit",
    "describe_kind",
    "temporary_name",
    "write_error",
]
