"""``ds.tippe``: which product of the package a dataset is, and its figure.

Importing :mod:`stability` registers the accessor (``xarray.register_dataset_accessor``), so
every ``xarray.Dataset`` has ``ds.tippe``:

* ``ds.tippe.product``: the value of the dataset's global attribute
  :data:`stability.products.PRODUCT_ATTR` (``"atlas"``, ``"neutral_curve"``, ...; the table is in
  docs/datasets.md), or None if it has none;
* ``ds.tippe.plot(**kw)``: the product's figure, drawn by the plotting function registered for
  it in :data:`PLOTS` (``kw`` are that function's options, e.g. ``ax=``), returning
  ``(Figure, Axes)`` as every plotting function does (:mod:`stability.plotting`).

As in xarray (``da.plot()``) and python-control (a result's ``.plot()``), the data knows what it
is and hands over to a plotting function; the function stays importable and callable on its own,
and draws the same thing.

This module imports only xarray: the plotting functions (and matplotlib) are imported when a
figure is drawn, so that ``import stability`` stays as fast as without the accessor.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

import xarray as xr

from ..errors import InputError
from ..products import PRODUCT_ATTR

__all__ = ["PLOTS", "TippeAccessor", "plotting_function"]

#: product -> its plotting function, as the name of a function of :mod:`stability.plotting`
#: (imported on first use) or a callable ``f(ds, **kw) -> (Figure, Axes)``. A new product's
#: figure is one entry here.
PLOTS: dict[str, str | Callable[..., Any]] = {
    "atlas": "plot_atlas",
    "flip_time_map": "plot_flip_time",
    "contact_loss_map": "plot_contact_loss_map",
    "neutral_curve": "plot_neutral_curve",
    "fold_curve": "plot_fold_curve",
    "nonlinear_run": "plot_run",
    "validation": "plot_validation",
    "coulomb_growth": "plot_coulomb_growth",
    "critical_spin": "plot_critical_spin",
    "steady_states": "plot_steady_states",
    "steady_branch": "plot_bifurcation",
    "final_state": "plot_final_state",
    "top_classes": "plot_class_map",
}


def plotting_function(product: str) -> Callable[..., Any]:
    """The plotting function registered for ``product`` in :data:`PLOTS`.

    Raises
    ------
    InputError
        If no figure is registered for ``product`` (the message lists those that are).
    """
    entry = PLOTS.get(product)
    if entry is None:
        raise InputError(
            f"{PRODUCT_ATTR} = {product!r}: no figure is registered for this product "
            f"(products with a figure: {', '.join(sorted(PLOTS))})"
        )
    return entry if callable(entry) else getattr(importlib.import_module("stability.plotting"), entry)


@xr.register_dataset_accessor("tippe")
class TippeAccessor:
    """``ds.tippe``: the product of a dataset of tippe-stability, and its figure (module docstring)."""

    def __init__(self, ds: xr.Dataset) -> None:
        self._ds = ds

    @property
    def product(self) -> str | None:
        """The dataset's product (its attribute :data:`~stability.products.PRODUCT_ATTR`), or None."""
        value = self._ds.attrs.get(PRODUCT_ATTR)
        return None if value is None else str(value)

    def plot(self, **kw: Any) -> Any:
        """Draw the product's figure: ``PLOTS[product](ds, **kw)``.

        Parameters
        ----------
        **kw
            Options of the plotting function (``ax=`` or ``axes=``, and its own).

        Returns
        -------
        (Figure, Axes) or (Figure, list of Axes)
            What the plotting function returns.

        Raises
        ------
        InputError
            If the dataset has no product attribute (not made by tippe-stability, or its
            attributes were dropped), or no figure is registered for its product.
        """
        product = self.product
        if product is None:
            raise InputError(
                f"this dataset has no global attribute {PRODUCT_ATTR!r}, so ds.tippe.plot() cannot "
                "tell which figure to draw: it was not made by tippe-stability, or its attributes "
                "were dropped (keep_attrs=False, or a new Dataset built from its variables); call a "
                "plotting function of stability.plotting directly"
            )
        return plotting_function(product)(self._ds, **kw)
