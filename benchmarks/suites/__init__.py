"""Speed against accuracy: the work-precision suites of ``python benchmarks/run.py`` and their registry.

Every measurement is one :class:`~suites.records.WorkPrecision` point: a method (at one
setting), the wall time per unit of work it took, and its error against an independent
reference. Every time comes from the one timer, :func:`suites.timing.best_times`
(the minimum over interleaved rounds). A suite is a module that defines its
:class:`~suites.records.Suite` as ``SUITE``: the function that measures, the title,
the chart's panels (:class:`~suites.records.Panel`, each with its required accuracy)
and its ``--quick`` configuration; :data:`SUITES` collects them by name. ``python benchmarks/run.py --suite
NAME`` runs one and writes ``atlases/work_precision_NAME.png`` and ``.json``. Speed is quoted
as a ratio against baselines measured in the same run.

Suites, one module each (each holds its problem, baselines, references and required accuracy):

* ``"eigen"`` (:mod:`suites.eigen`): the eigenvalue methods of the sliding model
  (eq. 11) on a large batch of points spread over the physical domain, against mpmath at 50
  digits;
* ``"continuation"`` (:mod:`suites.continuation`): the continuation's step settings
  against the exact fold of the sliding neutral curve, with brentq per column as the baseline;
* ``"integrators"`` (:mod:`suites.integrators`): the integrators of the nonlinear runs
  against a tight DOP853 reference, and the stiff slip mode;
* ``"steady"`` (:mod:`suites.steady`): the final state by Jellett's integral against a
  simulation long enough for the same accuracy, the branch of tilted states against its closed
  form (baselines: brentq per tilt, the engine's Python path), the class map of 1e6 tops.

Layer 7 (docs/architecture.md): the suites measure the layers below; nothing below imports them
(the charts, :mod:`stability.plotting.work_precision`, take the records duck-typed).
"""

from __future__ import annotations

from . import continuation, eigen, integrators, steady
from .continuation import FOLD_TARGET
from .eigen import EIGEN_TARGET
from .integrators import CROSSING_TARGET, GROWTH_TARGET
from .records import Panel, Suite, WorkPrecision, peak_memory_mb
from .steady import BRANCH_TARGET, FINAL_TARGET
from .timing import best_times

__all__ = [
    "BRANCH_TARGET",
    "CROSSING_TARGET",
    "EIGEN_TARGET",
    "FINAL_TARGET",
    "FOLD_TARGET",
    "GROWTH_TARGET",
    "SUITES",
    "Panel",
    "Suite",
    "WorkPrecision",
    "best_times",
    "peak_memory_mb",
]

#: name -> :class:`Suite`, in the order ``python benchmarks/run.py`` (``--suite all``) runs them; a new suite
#: is a module of this package with its ``SUITE``, and one entry here
SUITES: dict[str, Suite] = {s.name: s for s in (eigen.SUITE, continuation.SUITE, integrators.SUITE, steady.SUITE)}
