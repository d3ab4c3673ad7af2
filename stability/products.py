"""Which product of the package a dataset is: the global attribute that names it.

Every ``xarray.Dataset`` the package returns carries the global attribute
:data:`PRODUCT_ATTR` (``"tippe_stability_product"``), set where the dataset is built; its values
are listed, with the function that makes each, in docs/datasets.md. It survives a round trip
through netCDF, so a file says what it holds (:func:`stability.open_atlas` refuses a file whose
value is not ``"atlas"``), and ``ds.tippe.plot()`` draws the figure of the product
(:mod:`stability.plotting.accessor`).

Layer 0 (docs/architecture.md): the attribute's name is needed by every layer that builds a
dataset (``linear``, ``nonlinear``, ``grids``, ``recipes``), so it lives below them all.
"""

from __future__ import annotations

__all__ = ["PRODUCT_ATTR"]

#: global attribute naming which product of this package a dataset is
PRODUCT_ATTR = "tippe_stability_product"
