"""Figures drawn from datasets (computation lives elsewhere).

Every plotting function takes a dataset and an optional ``ax``, returns the Figure and Axes,
and never calls ``plt.show``. The package style is applied with :func:`style`, a context
manager around ``plt.style.context``.
"""
from .atlas_plots import plot_growth_rate, save_figure, style
from .figures import atlas_figure

__all__ = ["atlas_figure", "plot_growth_rate", "save_figure", "style"]
