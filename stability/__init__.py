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
  motion, the high-spin classes; :func:`steady_branch` - the branch of tilted states, traced
  by the continuation engine; :func:`bifurcation_diagram` - every steady state of a real top
  against the equivalent upright spin in its unit (``stability.plotting.plot_bifurcation`` draws it);
* :func:`neutral_curve`, :func:`fold_curve` - neutral and fold curves of the linear models,
  traced by the continuation engine (:mod:`continuation`, which knows nothing of tops);
* :class:`TippeError` - the base of every exception the package raises on purpose
  (:mod:`stability.errors`; bad input is an :class:`InputError`, a ``ValueError``);
* ``ds.tippe`` - on every dataset the package returns: ``ds.tippe.product`` (its global
  attribute ``tippe_stability_product``, docs/datasets.md) and ``ds.tippe.plot()``, the
  product's figure (:mod:`stability.plotting.accessor`; registered by this module, below;
  matplotlib is imported only when a figure is drawn).

This module only re-exports, lazily (PEP 562): ``import stability`` imports none of numpy,
numba, scipy, xarray or matplotlib; each name is imported from the module that defines it on
first use (:data:`_EXPORTS`); the accessor ``ds.tippe`` is registered as soon as xarray is
imported (:func:`_register_accessor`), whichever module imports it. Subpackages (``stability.plotting`` ...) are reachable as
attributes too. Where each name lives, and which way imports go, is in docs/architecture.md.
"""

from __future__ import annotations

import importlib
import importlib.util
from typing import Any

#: public name -> the module that defines it (imported on first use)
_EXPORTS: dict[str, str] = {
    name: module
    for module, names in {
        ".errors": "AtlasFileError ChunkError DomainError InputError TippeError",
        ".grids.atlases": "atlas",
        ".grids.netcdf": "open_atlas write_dataset",
        ".linear.control_forms": "friction_loop state_space",
        ".linear.critical": "critical_spin threshold threshold_crossings thresholds",
        ".linear.spectra": "eigenvalues spectrum",
        ".models": "MODELS LinearModel get_model",
        ".linear.neutral_curves": "fold_curve neutral_curve",
        ".nonlinear.jacobian": "jacobian_eigenvalues",
        ".nonlinear.runs": "simulate",
        ".nonlinear.stickslip": "stick_slip",
        ".nonlinear.validation": "coulomb_growth validate",
        ".parameters": "DEFAULT_MU PARAMETERS check_domain",
        ".steady.classes": "class_atlas top_class",
        ".steady.final": "FinalState final_state",
        ".steady.branch": "steady_branch",
        ".steady.states": "steady_states",
        ".steady.diagram": "bifurcation_diagram",
        ".top": "Top ImplausibleTopWarning",
        ".stick": "Stick",
        ".launches.result": "launch Launch",
        ".launches.flip": "flip_time",
        ".launches.contact_map": "contact_loss_boundary",
        ".steady.margin": "contact_margin",
    }.items()
    for name in names.split()
}

__all__ = sorted(_EXPORTS)  # noqa: PLE0605 - the names of _EXPORTS (one list of the public names)


def __getattr__(name: str) -> Any:
    """A public name, imported from its module on first use; or a subpackage."""
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
        globals()[name] = value
        return value
    if not name.startswith("__"):
        try:
            return importlib.import_module(f"{__name__}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))


def _register_accessor() -> None:
    """Register ``ds.tippe`` (:mod:`stability.plotting.accessor`) as soon as xarray is there.

    ``import stability`` imports no xarray; but a user who opens a file with xarray directly
    (``xr.open_dataset("run.nc").tippe``) has xarray, and the accessor must be there too
    (docs/datasets.md). So: if xarray is already imported, register now; otherwise register
    right after xarray's own import completes (a finder on ``sys.meta_path`` that answers only
    for ``xarray``, delegates to the other finders, and runs the registration once after the
    module executed)."""
    import sys

    if "xarray" in sys.modules:
        importlib.import_module(".plotting.accessor", __name__)
        return

    class _AfterXarray:
        @staticmethod
        def find_spec(fullname: str, path: Any = None, target: Any = None) -> Any:
            if fullname != "xarray":
                return None
            sys.meta_path.remove(_AfterXarray)
            spec = importlib.util.find_spec("xarray")
            if spec is not None and spec.loader is not None:
                run = spec.loader.exec_module

                def exec_module(module: Any) -> None:
                    run(module)
                    importlib.import_module(".plotting.accessor", __name__)

                spec.loader.exec_module = exec_module  # type: ignore[method-assign]
            return spec

    sys.meta_path.insert(0, _AfterXarray)


_register_accessor()
