"""Registry of the linear models, by name (see :mod:`stability.models.base` for the contract)."""

from __future__ import annotations

from .base import LinearModel
from .fixed_pivot import FixedPivot
from .rolling import Rolling
from .rolling_first_principles import RollingFirstPrinciples
from .sliding import Sliding

__all__ = ["LinearModel", "MODELS", "get_model"]

#: name -> model instance
MODELS: dict[str, LinearModel] = {m.name: m for m in (FixedPivot(), Rolling(), Sliding(),
                                                   RollingFirstPrinciples())}


def get_model(model: str | LinearModel) -> LinearModel:
    """Return the registered model called ``model`` (or ``model`` itself if already one).

    Raises
    ------
    ValueError
        If no model has that name; the message lists the registered names.
    """
    if isinstance(model, LinearModel):
        return model
    if not isinstance(model, str) or model not in MODELS:
        raise ValueError(f"model = {model!r} is not a known model; choose one of {', '.join(MODELS)}")
    return MODELS[model]
