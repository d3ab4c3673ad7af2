"""Figures drawn from datasets (computation lives elsewhere).

The convention, for every public plotting function of this package:

* it takes the data (a dataset of the package) and an optional
  ``ax`` (one panel) or ``axes`` (a sequence, one Axes per panel), and draws there; without
  them it makes a new :class:`matplotlib.figure.Figure` (not pyplot's: nothing is shown, no
  global state, so it works in scripts, notebooks and worker processes alike);
* it returns ``(Figure, Axes)``, or ``(Figure, list of Axes)`` when it draws several panels;
* it never computes a dataset, never calls ``plt.show`` and never saves: save with
  :func:`save_figure` (atomic), style with :func:`style` (a context manager around
  ``plt.style.context``).

``ds.tippe.plot()`` (:mod:`stability.plotting.accessor`, registered when :mod:`stability` is
imported) picks the function for a dataset from its product attribute.

Functions (imported on first use, so that ``import stability`` does not import matplotlib):

* atlases: :func:`plot_atlas` (by its grid), :func:`plot_growth_rate`, :func:`atlas_figure`,
  :func:`plot_stability_map` (with :func:`growth_norm`);
* neutral and fold curves: :func:`plot_neutral_curve`, :func:`plot_fold_curve`;
* nonlinear runs: :func:`plot_run`, the paper's Figs. 5-9 (:mod:`stability.plotting.scene_plots`);
  a run's normal force and event (contact lost, stick reached): :func:`plot_contact_run`; a run
  that flies and lands: :func:`plot_flight_run`; a stick-slip run with its switches: :func:`plot_stick_slip`; where
  a launch loses its contact: :func:`plot_contact_loss_map`;
* validation: :func:`plot_validation`, :func:`plot_coulomb_growth`;
* a real top: :func:`plot_critical_spin`, :func:`plot_flip_time`, :func:`plot_flip_estimates`;
* steady states: :func:`plot_steady_states` (the states of a Jellett level on its effective
  potential), :func:`plot_final_state`, :func:`plot_bifurcation`, :func:`plot_class_map`,
  :func:`plot_settle`, :func:`plot_settle_approach`;
* recipes: :func:`recipe_figure`.

The work-precision charts of the benchmarks follow the same convention but live beside the
package, in ``benchmarks/suites/charts.py``.
"""

from __future__ import annotations

import importlib
from typing import Any

#: module of this package -> the public names it defines
_MODULES: dict[str, str] = {
    "figures": "plot_atlas atlas_figure",
    "launch_plots": "plot_flip_time plot_flip_estimates plot_critical_spin",
    "atlas_plots": "plot_growth_rate save_figure style",
    "maps": "plot_stability_map plot_neutral_curve plot_fold_curve growth_norm",
    "scene_plots": "plot_run",
    "contact_plots": "plot_contact_loss_map plot_contact_run plot_flight_run plot_stick_slip",
    "validation_plots": "plot_validation plot_coulomb_growth",
    "steady_plots": "plot_steady_states plot_final_state plot_bifurcation plot_class_map plot_settle "
    "plot_settle_approach",
    "recipe_figures": "recipe_figure",
}
#: public name -> the module of this package that defines it (imported on first use)
_EXPORTS: dict[str, str] = {name: module for module, names in _MODULES.items() for name in names.split()}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(f"{__name__}.{_EXPORTS[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
