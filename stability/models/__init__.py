"""Registry of the linear models, by name (see :mod:`stability.models.base` for the contract).

Names (issue 15): ``"rolling"`` is the rolling top from first principles (eqs. 1, 2, 4, 5
linearised; the ``alpha_v -> infinity`` limit of ``"sliding"``; the linearisation of the
nonlinear rolling model), ``"rolling_eq8"`` the paper's eq. (8)-(9) as printed (``h = q``,
``sigma_hat = sigma / A_C``), which differs from it (docs/models.md). In tippe-stability 0.1.0
the name ``"rolling"`` meant eq. (8) as printed and the first-principles model was
``"rolling_first_principles"``; that old name still works for one release with a
:class:`DeprecationWarning`, and for one release a public lookup of the bare name
``"rolling"`` emits one :class:`FutureWarning` per process saying that its meaning changed
(silence it with ``warnings.filterwarnings("ignore", "model 'rolling' is now", FutureWarning)``).
The package's own lookups pass ``warn=False`` or the model object.
"""

from __future__ import annotations

import os
import sys
import warnings

from ..errors import InputError
from .base import LinearModel
from .rolling import Rolling
from .second_order import FixedPivot, RollingEq8
from .sliding import Sliding

__all__ = ["DEPRECATED_NAMES", "MODELS", "LinearModel", "get_model"]

#: name -> model instance
MODELS: dict[str, LinearModel] = {m.name: m for m in (FixedPivot(), Rolling(), RollingEq8(), Sliding())}

#: old name -> current name (kept for one release, with a DeprecationWarning)
DEPRECATED_NAMES: dict[str, str] = {"rolling_first_principles": "rolling"}

#: the FutureWarning on the changed meaning of "rolling" is given once per process
_ROLLING_WARNED = False

_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep


def _caller_stacklevel() -> int:
    """The ``stacklevel`` of the first frame outside the ``stability`` package (the user's call)."""
    frame, level = sys._getframe(1), 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    return level


def get_model(model: str | LinearModel, *, warn: bool = True) -> LinearModel:
    """Return the registered model called ``model`` (or ``model`` itself if already one).

    Parameters
    ----------
    model : str or LinearModel
        A name of :data:`MODELS` (or of :data:`DEPRECATED_NAMES`), or a model.
    warn : bool
        Give the one-per-process :class:`FutureWarning` on the changed meaning of ``"rolling"``
        (module docstring). The package's own lookups pass False.

    Raises
    ------
    ValueError
        If no model has that name; the message lists the registered names.
    """
    global _ROLLING_WARNED
    if isinstance(model, LinearModel):
        return model
    if isinstance(model, str) and model in DEPRECATED_NAMES:
        new = DEPRECATED_NAMES[model]
        warnings.warn(
            f"model {model!r} is deprecated and will be removed in the next release: it is now "
            f"called {new!r} (the rolling top from first principles)",
            DeprecationWarning,
            stacklevel=_caller_stacklevel(),
        )
        return MODELS[new]
    if not isinstance(model, str) or model not in MODELS:
        raise InputError(f"model = {model!r} is not a known model; choose one of {', '.join(MODELS)}")
    if model == "rolling" and warn and not _ROLLING_WARNED:
        _ROLLING_WARNED = True
        warnings.warn(
            "model 'rolling' is now the rolling top from first principles (eqs. 1, 2, 4, 5 "
            "linearised); in tippe-stability 0.1.0 it was eq. (8) as printed, which is "
            "now 'rolling_eq8'",
            FutureWarning,
            stacklevel=_caller_stacklevel(),
        )
    return MODELS[model]
