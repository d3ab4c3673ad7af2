"""tippe-stability: linear stability and bifurcation analysis of the Tippe top.

The import package is ``stability`` (distribution name ``tippe-stability``). Public API:

* :func:`eigenvalues`, :func:`spectrum` - spectra of the linear models (eqs. 8-11);
* :func:`atlas`, :func:`open_atlas` - spectra over parameter grids as xarray datasets;
* :class:`Top` - a real top in SI units and its nondimensional parameters;
* :data:`MODELS` - the registry of linear models ("fixed_pivot", "rolling", "rolling_eq8", "sliding");
* :func:`state_space`, :func:`friction_loop` - python-control forms of the operators;
* :func:`threshold`, :func:`thresholds`, :func:`threshold_crossings`, :func:`critical_spin` -
  where stability changes;
* :func:`simulate`, :func:`jacobian_eigenvalues`, :func:`validate` - nonlinear runs and the
  check of the linear predictions against them;
* :func:`steady_states`, :func:`final_state`, :func:`top_class`, :func:`class_atlas` - where the
  top goes: the steady tilted states on a Jellett level and their stability, the end of a
  motion, the high-spin classes (the branch of tilted states is
  ``continuation.steady_branch``);
* :class:`TippeError` - the base of every exception the package raises on purpose
  (:mod:`stability.errors`; bad input is an :class:`InputError`, a ``ValueError``);
* ``ds.tippe`` - on every dataset the package returns: ``ds.tippe.product`` (its global
  attribute ``tippe_stability_product``, docs/datasets.md) and ``ds.tippe.plot()``, the
  product's figure (:mod:`stability.plotting.accessor`; registered here, matplotlib is
  imported only when a figure is drawn).

This module only re-exports; where each name lives, and which way imports go, is in
docs/architecture.md.
"""
from .errors import AtlasFileError, ChunkError, DomainError, InputError, TippeError
from .grids.atlases import atlas
from .grids.netcdf import open_atlas, write_dataset
from .linear.control_forms import friction_loop, state_space
from .linear.critical import critical_spin, threshold, threshold_crossings, thresholds
from .linear.spectra import eigenvalues, spectrum
from .models import MODELS, LinearModel, get_model
from .nonlinear.jacobian import jacobian_eigenvalues
from .nonlinear.runs import simulate
from .nonlinear.validation import coulomb_growth, validate
from .parameters import DEFAULT_MU, PARAMETERS, check_domain
from .plotting import accessor as _accessor  # registers ds.tippe  # noqa: F401
from .steady.classes import class_atlas, top_class
from .steady.final import FinalState, final_state
from .steady.states import steady_states
from .top import Top

__all__ = [
    "AtlasFileError", "ChunkError", "DEFAULT_MU", "DomainError", "InputError", "LinearModel", "MODELS", "PARAMETERS",
    "TippeError", "Top",
    "atlas", "check_domain", "eigenvalues", "friction_loop", "get_model", "open_atlas",
    "spectrum", "state_space", "write_dataset", "simulate", "jacobian_eigenvalues", "validate", "coulomb_growth",
    "threshold", "thresholds", "threshold_crossings", "critical_spin",
    "steady_states", "final_state", "FinalState", "top_class", "class_atlas",
]
