"""tippe-stability: linear stability and bifurcation analysis of the Tippe top.

The import package is ``stability`` (distribution name ``tippe-stability``). Public API:

* :func:`eigenvalues`, :func:`spectrum` - spectra of the linear models (eqs. 8-11);
* :func:`atlas`, :func:`open_atlas` - spectra over parameter grids as xarray datasets;
* :class:`Top` - a real top in SI units and its nondimensional parameters;
* :data:`MODELS` - the registry of linear models ("fixed_pivot", "rolling", "sliding");
* :func:`state_space`, :func:`friction_loop` - python-control forms of the operators.
"""
from .grids.atlases import atlas
from .linear.control_forms import friction_loop, state_space
from .grids.chunked import ChunkError
from .grids.netcdf import AtlasFileError, open_atlas, write_dataset
from .models import MODELS, LinearModel, get_model
from .parameters import DEFAULT_MU, PARAMETERS, DomainError, check_domain
from .linear.spectra import eigenvalues, spectrum
from .nonlinear.runs import simulate
from .nonlinear.jacobian import jacobian_eigenvalues
from .nonlinear.validation import coulomb_growth, validate
from .top import Top
from .linear.critical import critical_spin, threshold, thresholds

__all__ = [
    "AtlasFileError", "ChunkError", "DEFAULT_MU", "DomainError", "LinearModel", "MODELS", "PARAMETERS", "Top",
    "atlas", "check_domain", "eigenvalues", "friction_loop", "get_model", "open_atlas",
    "spectrum", "state_space", "write_dataset", "simulate", "jacobian_eigenvalues", "validate", "coulomb_growth",
    "threshold", "thresholds", "critical_spin",
]
