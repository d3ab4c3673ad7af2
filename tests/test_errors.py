"""The exception hierarchy (stability/errors.py) and the exit status of the command line for each
kind of error.

Reference: docs/input_checks.md and the module docstring of stability/errors.py: every exception
the package raises on purpose is a ``TippeError``; bad input keeps its ``ValueError`` ancestry
(so ``except ValueError`` still catches a ``DomainError``) and exits 2; a failure to compute
(``ChunkError``, a ``ConvergenceError`` of the engine or of the package) is a ``RuntimeError``
and exits 1.
"""

from __future__ import annotations

import pytest

import continuation
import stability
from stability import errors
from stability.cli import main

INPUT = (errors.DomainError, errors.AtlasFileError, errors.RecipeError, errors.ResumeError)


@pytest.mark.parametrize("cls", INPUT)
def test_bad_input_is_an_input_error_and_a_value_error(cls):
    assert issubclass(cls, errors.InputError) and issubclass(cls, ValueError)
    assert issubclass(cls, errors.TippeError)


@pytest.mark.parametrize("cls", [errors.ChunkError, errors.ConvergenceError])
def test_a_failure_to_compute_is_a_runtime_error_not_bad_input(cls):
    assert issubclass(cls, errors.TippeError) and issubclass(cls, RuntimeError)
    assert not issubclass(cls, ValueError) and not issubclass(cls, errors.InputError)


def test_convergence_errors_of_engine_and_package():
    """The engine (generic, imports nothing from stability) has its own class; the package's
    subclasses it, so ``except continuation.ConvergenceError`` catches both."""
    assert continuation.ConvergenceError is continuation.errors.ConvergenceError
    assert issubclass(continuation.ConvergenceError, RuntimeError)
    assert not issubclass(continuation.ConvergenceError, errors.TippeError)
    assert issubclass(errors.ConvergenceError, continuation.ConvergenceError)


def test_public_names_are_the_hierarchy_classes():
    assert stability.DomainError is errors.DomainError
    assert stability.AtlasFileError is errors.AtlasFileError
    assert stability.ChunkError is errors.ChunkError
    assert stability.TippeError is errors.TippeError and stability.InputError is errors.InputError
    assert issubclass(errors.ParameterTypeError, TypeError) and issubclass(errors.ParameterTypeError, errors.TippeError)


def test_a_neutral_start_that_does_not_converge_raises_the_packages_convergence_error():
    """Newton's method cannot reach a backward error of 1e-300: the package reports the start
    point with its own ConvergenceError (a TippeError and the engine's class)."""
    with pytest.raises(errors.ConvergenceError, match=r"start point \(q, sigma, w\) = \(0\.1, 0\.5, 3\)"):
        stability.neutral_curve(
            "sliding", "q", "sigma", fixed=dict(fr_inv=0.3, alpha_v=0.5), start=[(0.1, 0.5, 3.0)], tol=1e-300
        )


NEUTRAL = ["neutral", "--x", "q", "--y", "sigma", "--fr-inv", "0", "--alpha-v", "0.5"]


@pytest.mark.parametrize(
    "exc,status",
    [
        (continuation.ConvergenceError("the corrector did not converge"), 1),
        (errors.ConvergenceError("the corrector did not converge"), 1),
        (errors.ChunkError("chunk chunk-0 failed"), 1),
        (errors.DomainError("q = 2 is outside the physical domain"), 2),
        (errors.InputError("a bad value"), 2),
        (ValueError("a bad value"), 2),
        (errors.ParameterTypeError("a str"), 2),
        (errors.Interrupted("nothing was kept"), 130),
    ],
)
def test_cli_exit_status_by_kind_of_error(monkeypatch, capsys, exc, status):
    """One line on stderr; 2 for bad input, 1 for a failure to compute, 130 for an interruption."""
    import stability.linear.neutral_curves as nc

    def fail(*args, **kwargs):
        raise exc

    monkeypatch.setattr(nc, "neutral_curve", fail)
    assert main(NEUTRAL) == status
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and str(exc) in err
    assert "internal error" not in err
