"""Work-precision records: one measurement, a chart's panel, a suite, and the process's peak memory.

A measurement is one :class:`WorkPrecision` point: a method (at one setting), the wall time per
unit of work it took (:func:`suites.timing.best_times`), and its error against an
independent reference. A :class:`Suite` (each suite module defines its own ``SUITE``, collected
by name in :data:`suites.SUITES`) returns a list of them and says how its chart is
drawn (:class:`Panel`, which holds the required accuracy). Generic: nothing here knows about a
particular suite.
"""

from __future__ import annotations

import resource
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

__all__ = ["Panel", "Suite", "WorkPrecision", "peak_memory_mb"]


@dataclass(frozen=True)
class WorkPrecision:
    """One point of a work-precision chart.

    Attributes
    ----------
    method : str
        Label of the method and setting.
    seconds_per_point : float
        Wall time per unit of work (a grid point for the spectra, a traced curve for the
        continuation, a run for the integrators), best of the repeats.
    error : float
        Largest error against the reference (relative per eigenvalue for the spectra).
    points : int
        Batch size the time was measured on.
    baseline : bool
        True for the baselines the ratios are quoted against.
    default : bool
        True for the package's default path.
    note : str
        What the point measures, in a few words.
    series : str
        Points of one method at several settings share a series (joined by a line in the
        chart); default: the method's own.
    setting : str
        The setting of this point within its series (e.g. ``"rtol 1e-6"``).
    panel : str
        Which panel of the suite's chart the point belongs to (:class:`Panel`).
    extra : dict of str to float
        Other numbers measured with the point (a second error, evaluations, a parameter).
    component : bool
        A part of a path rather than a path a user calls (the bare kernel, without the domain
        check): drawn, but not ranked when the chart names the fastest method.
    """

    method: str
    seconds_per_point: float
    error: float
    points: int
    baseline: bool = False
    default: bool = False
    note: str = ""
    series: str = ""
    setting: str = ""
    panel: str = ""
    extra: dict[str, float] = field(default_factory=dict)
    component: bool = False

    def as_dict(self) -> dict[str, Any]:
        """Plain dictionary (for JSON)."""
        return asdict(self)


@dataclass(frozen=True)
class Panel:
    """One panel of a suite's chart.

    Attributes
    ----------
    xlabel, ylabel : str
        Axis labels.
    x : str
        ``"error"`` (a work-precision panel) or a key of :attr:`WorkPrecision.extra`.
    select : str
        Draws the results whose :attr:`WorkPrecision.panel` equals it.
    target : float, optional
        The required accuracy of the results drawn in this panel (vertical line; the fastest
        point left of it is named; ``python benchmarks/run.py`` prints the verdict against it).
    title : str
        The panel's own title.
    """

    xlabel: str
    ylabel: str
    x: str = "error"
    select: str = ""
    target: float | None = None
    title: str = ""


@dataclass(frozen=True)
class Suite:
    """A work-precision suite: what ``python benchmarks/run.py --suite NAME`` runs and draws.

    Attributes
    ----------
    name : str
        Its key in :data:`suites.SUITES` (``--suite NAME``, the files
        ``work_precision_NAME.png`` and ``.json``).
    run : callable
        Returns a list of :class:`WorkPrecision`; takes the keywords among ``points``,
        ``reference_points``, ``loop_points``, ``repeat`` and ``quick`` that it names.
    title : str
        What was measured (the chart's title, before the default/fastest summary).
    panels : tuple of Panel
        The chart's panels, left to right; each with its required accuracy
        (:attr:`Panel.target`), if it has one.
    unit : str
        The unit of work of ``seconds_per_point`` ("point", "curve", "run").
    compare_at : tuple of str
        Errors (``"error"`` or keys of :attr:`WorkPrecision.extra`) at which speed is compared
        at equal accuracy: against the fastest setting of each baseline whose error is at most
        the point's. Empty: plain ratios against each baseline (the eigen suite, whose
        baselines are single points).
    quick : mapping of str to value
        The keywords of ``run`` under ``python benchmarks/run.py --quick`` (where no flag gives them): the
        small configuration, in seconds rather than minutes.
    """

    name: str
    run: Callable[..., list[WorkPrecision]]
    title: str
    panels: tuple[Panel, ...]
    unit: str = "point"
    compare_at: tuple[str, ...] = ()
    quick: Mapping[str, Any] = field(default_factory=dict)


def peak_memory_mb() -> float:
    """Peak resident memory of this process so far, in MB (``ru_maxrss``)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
