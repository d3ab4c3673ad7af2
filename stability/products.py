"""Which product of the package a dataset is: the global attribute that names it.

Every ``xarray.Dataset`` the package returns carries the global attribute
:data:`PRODUCT_ATTR` (``"tippe_stability_product"``), set where the dataset is built; its values
are listed, with the function that makes each, in docs/datasets.md. It survives a round trip
through netCDF, so a file says what it holds (:func:`stability.open_atlas` refuses a file whose
value is not ``"atlas"``), and ``ds.tippe.plot()`` draws the figure of the product
(:mod:`stability.plotting.accessor`).

Also here, for the same reason: the stability flags every dataset with a ``stability``
variable uses (:data:`STABLE`, :data:`MARGINAL`, :data:`UNSTABLE`; CF ``flag_values`` and
``flag_meanings``), one home for the spectra, the steady states, the recipes, the figures and the
command line.

Layer 0 (docs/architecture.md): the attribute's name is needed by every layer that builds a
dataset (``linear``, ``nonlinear``, ``grids``, ``recipes``), so it lives below them all.
"""

from __future__ import annotations

__all__ = ["FLAG_MEANINGS", "FLAG_NAMES", "FLAG_VALUES", "MARGINAL", "PRODUCT_ATTR", "STABLE", "UNSTABLE"]

#: global attribute naming which product of this package a dataset is
PRODUCT_ATTR = "tippe_stability_product"

#: the stability flags (docs/conventions.md: unstable if a mode grows, marginal if none grows and
#: one is neutral, stable otherwise)
STABLE, MARGINAL, UNSTABLE = 0, 1, 2
#: the flags in order, and their CF ``flag_meanings``
FLAG_VALUES = (STABLE, MARGINAL, UNSTABLE)
FLAG_MEANINGS = "stable marginal unstable"
#: flag -> its name
FLAG_NAMES: dict[int, str] = dict(zip(FLAG_VALUES, FLAG_MEANINGS.split()))
