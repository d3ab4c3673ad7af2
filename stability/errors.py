"""The exceptions the package raises on purpose: one hierarchy under :class:`TippeError`.

Layer 0 (docs/architecture.md): imports nothing from the package (only the engine's
:class:`continuation.errors.ConvergenceError`, to subclass it).

::

    TippeError
    +-- InputError (ValueError)            bad input: a value outside its range, an unknown name
    |   +-- DomainError                    a parameter outside the physical or computable domain
    |   +-- AtlasFileError                 a file given as an atlas is missing, unreadable, not one
    |   +-- RecipeError                    an atlas recipe that cannot be read or run
    |   +-- ResumeError                    a chunk store that cannot be resumed from
    |   +-- ResourceError                  a request that cannot fit in the memory available
    +-- ParameterTypeError (TypeError)     a value of the wrong type (the parameter checks of
    |                                      stability.parameters raise it)
    +-- OutputWriteError (OSError)         an output file could not be written (disk full, file
    |                                      size limit, ...): names the file and the cause
    +-- ChunkError (RuntimeError)          a chunk of a chunked atlas failed
    +-- ConvergenceError (RuntimeError,    a continuation did not converge
    |       continuation.ConvergenceError)
    +-- Interrupted                        a command was interrupted; says what was kept
    +-- MissingExtraError (ImportError)    a feature needs an optional dependency that is not
                                           installed; the message names the pip extra

Bad input keeps the ancestry of the built-in exceptions (``except ValueError`` catches a
:class:`DomainError`); a failure to compute is a :class:`RuntimeError`. The ``tippe`` command
line exits with status 2 on bad input (and on ``ValueError``, ``TypeError``, ``OSError``), 1 on a
failure to compute (:class:`ChunkError`, any :class:`continuation.errors.ConvergenceError`)
and 130 when interrupted (docs/input_checks.md); a missing optional dependency ends it with
status 1.
"""

from __future__ import annotations

from continuation.errors import ConvergenceError as _EngineConvergenceError

__all__ = [
    "AtlasFileError",
    "ChunkError",
    "ConvergenceError",
    "DomainError",
    "InputError",
    "Interrupted",
    "MissingExtraError",
    "OutputWriteError",
    "ParameterTypeError",
    "RecipeError",
    "ResourceError",
    "ResumeError",
    "RunError",
    "TippeError",
    "require_extra",
]


class TippeError(Exception):
    """Base of every exception the package raises on purpose."""


class InputError(TippeError, ValueError):
    """Bad input: a value outside its allowed range, an unknown name, an unusable file."""


class DomainError(InputError):
    """A parameter lies outside the physical domain (or is not finite, or is empty)."""


class ParameterTypeError(TippeError, TypeError):
    """A value of the wrong type (a str where a number is expected, ...)."""


class AtlasFileError(InputError):
    """A file given where an atlas is expected is missing, unreadable or not an atlas."""


class RecipeError(InputError):
    """A recipe file is malformed; the message names the file and the key."""


class ResumeError(InputError):
    """The sidecar chunk store cannot be used for this atlas (the message says why)."""


class ResourceError(InputError):
    """A request whose estimated memory exceeds what is available; the message gives the estimate,
    the parameter that sets it and a way out (:mod:`stability.resources`)."""


class OutputWriteError(TippeError, OSError):
    """An output file could not be written: the message names the file and the cause (no space
    left, the file size limit, a read-only file system, ...) and says that nothing was written.

    ``errno`` is the cause's error number when it is known (``errno.ENOSPC``, ``errno.EFBIG``,
    ...), else None; ``path`` is the output file. The original exception is the ``__cause__``.
    """

    def __init__(self, message: str, errno: int | None = None, path: str | None = None) -> None:
        super().__init__(message)
        self.errno = errno
        self.path = path


class ChunkError(TippeError, RuntimeError):
    """Computing one chunk of a chunked atlas failed (an exception in it, or its worker died).

    The message names the chunk and its slice of the grid, the cause, and what was kept: with
    ``resume=True`` the chunks finished before the failure stay in ``<output>.parts/`` and a
    rerun computes only the others. The original exception is the ``__cause__``.
    """


class RunError(TippeError, RuntimeError):
    """A nonlinear run failed (its integrator stopped before the end it was asked for)."""


class ConvergenceError(TippeError, _EngineConvergenceError):
    """A continuation did not converge (raised by the package's clients of the engine, e.g. a
    neutral curve's start point from which Newton's method finds no point of the curve).

    A :class:`continuation.errors.ConvergenceError`: ``except continuation.ConvergenceError``
    catches both the engine's and this one.
    """


class Interrupted(TippeError):
    """Raised by a command instead of ``KeyboardInterrupt`` to say what was kept (exit 130)."""


class MissingExtraError(TippeError, ImportError):
    """A feature needs an optional dependency that is not installed (:func:`require_extra`)."""


def require_extra(module: str, extra: str, feature: str) -> None:
    """Refuse ``feature`` with a :class:`MissingExtraError` naming the pip extra if ``module``
    cannot be imported (looked up, not imported).

    Parameters
    ----------
    module : str
        The optional dependency's import name (``"dask"``).
    extra : str
        The extra of the distribution that installs it (``"cluster"``).
    feature : str
        What asked for it, as the message names it (``"chunks="``).
    """
    import importlib.util

    # a top-level name (dask, distributed, zarr): no parent package is imported, so find_spec
    # raises nothing unless an import hook put a module without a spec under that name
    if importlib.util.find_spec(module) is None:
        raise MissingExtraError(
            f"{feature} needs {module}, which is not installed; install the package with "
            f"its {extra!r} extra: pip install 'tippe-stability[{extra}]' "
            f"(from a clone: pip install '.[{extra}]')",
            name=module,
        )
