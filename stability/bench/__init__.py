"""Speed against accuracy: the work-precision suites of ``tippe bench`` and their registry.

Every measurement is one :class:`~stability.bench.records.WorkPrecision` point: a method (at one
setting), the wall time per unit of work it took, and its error against an independent
reference. A suite (:class:`~stability.bench.records.Suite`, registered by name in
:data:`SUITES`) returns a list of them and says how its chart is drawn
(:class:`~stability.bench.records.Panel`); ``tippe bench --suite NAME`` runs it and writes
``atlases/work_precision_NAME.png`` and ``.json``. Speed is quoted as a ratio against baselines
measured in the same run.

Suites, one module each (each holds its problem, baselines, references and required accuracy):

* ``"eigen"`` (:mod:`stability.bench.eigen`): the eigenvalue methods of the sliding model
  (eq. 11) on a large batch of points spread over the physical domain, against mpmath at 50
  digits;
* ``"continuation"`` (:mod:`stability.bench.continuation`): the continuation's step settings
  against the exact fold of the sliding neutral curve, with brentq per column as the baseline;
* ``"integrators"`` (:mod:`stability.bench.integrators`): the integrators of the nonlinear runs
  against a tight DOP853 reference, and the stiff slip mode;
* ``"steady"`` (:mod:`stability.bench.steady`): the final state by Jellett's integral against a
  simulation long enough for the same accuracy, the branch of tilted states against its closed
  form (baselines: brentq per tilt, the engine's Python path), the class map of 1e6 tops.

Layer 7 (docs/architecture.md): the suites measure the layers below; nothing below imports them
(the charts, :mod:`stability.plotting.work_precision`, take the records duck-typed).
"""

from __future__ import annotations

from .continuation import CONTINUATION_TITLE, FOLD_TARGET, continuation_work_precision
from .eigen import EIGEN_TARGET, eigen_work_precision
from .integrators import CROSSING_TARGET, GROWTH_TARGET, INTEGRATOR_TITLE, integrator_work_precision
from .records import Panel, Suite, WorkPrecision, peak_memory_mb
from .steady import BRANCH_TARGET, FINAL_TARGET, STEADY_TITLE, steady_work_precision

__all__ = ["SUITES", "EIGEN_TARGET", "FOLD_TARGET", "CROSSING_TARGET", "GROWTH_TARGET", "FINAL_TARGET",
           "BRANCH_TARGET", "WorkPrecision", "Panel", "Suite", "peak_memory_mb"]


def _continuation_suite(repeat: int = 5, quick: bool = False) -> list[WorkPrecision]:
    """:func:`stability.bench.continuation.continuation_work_precision`, with the options
    ``tippe bench`` passes to it."""
    return continuation_work_precision(repeat=repeat, quick=quick)


def _integrator_suite(repeat: int = 3, quick: bool = False) -> list[WorkPrecision]:
    """:func:`stability.bench.integrators.integrator_work_precision`, with the options
    ``tippe bench`` passes to it."""
    return integrator_work_precision(repeat=repeat, quick=quick)


def _steady_suite(repeat: int = 3, quick: bool = False) -> list[WorkPrecision]:
    """:func:`stability.bench.steady.steady_work_precision`, with the options ``tippe bench``
    passes to it."""
    return steady_work_precision(repeat=repeat, quick=quick)


def _suites() -> dict[str, Suite]:
    return {
        "eigen": Suite(eigen_work_precision,
                       "eigenvalues of the sliding model (eq. 11) over the physical domain",
                       (Panel("largest relative error per eigenvalue vs mpmath, 50 digits",
                              "wall time per point [s]", target=EIGEN_TARGET),)),
        "continuation": Suite(_continuation_suite, CONTINUATION_TITLE,
                              (Panel("error of the located fold (q*, sigma*) vs closed form",
                                     "wall time per traced curve [s]", target=FOLD_TARGET),
                               Panel("largest error of the curve (dense output / spline) vs closed form",
                                     "wall time per traced curve [s]", x="curve_error",
                                     title="the curve between the points: Hermite dense output vs cubic spline")),
                              unit="curve", compare_at=("error", "curve_error")),
        "integrators": Suite(_integrator_suite, INTEGRATOR_TITLE,
                             (Panel("error of the 90-degree crossing time vs DOP853 rtol 1e-13 [1/Omega]",
                                    "wall time per run [s]", target=CROSSING_TARGET),
                              Panel("alpha_v (stiff slip mode, linear regime, 200 time units, rtol 1e-6)",
                                    "wall time per run [s]", x="alpha_v", select="stiff",
                                    title="cost against stiffness: explicit methods' time grows like alpha_v"),
                              Panel("relative error of the fitted growth rate vs DOP853 rtol 1e-13",
                                    "wall time per validation run [s]", select="growth", target=GROWTH_TARGET,
                                    title="validate(): growth rate fitted to a run (4 e-folds)")),
                             unit="run", compare_at=("error",)),
        "steady": Suite(_steady_suite, STEADY_TITLE,
                        (Panel("error of the final tilt against a settled reference run [deg] (the paper's Fr^-1 = 0.3 "
                               "run of Sec. 3(ii))", "wall time per prediction or run [s]", select="final",
                               target=FINAL_TARGET, title="final state: Jellett's integral vs simulations of "
                                                          "increasing length"),
                         Panel("largest relative error of the precession rate vs the closed form (S3)",
                               "wall time per branch (~200 points, spectra and flags) [s]", select="branch",
                               target=BRANCH_TARGET, title="the branch of tilted states (the paper's top)"),
                         Panel("number of tops", "wall time per call [s]", x="tops", select="classes",
                               title="class map: stability.top_class")),
                        unit="call"),
    }


#: name -> :class:`Suite`: "eigen" (:mod:`stability.bench.eigen`), "continuation"
#: (:mod:`stability.bench.continuation`), "integrators"
#: (:mod:`stability.bench.integrators`), "steady" (:mod:`stability.bench.steady`);
#: ``tippe bench --suite NAME`` runs one, ``tippe bench`` (``--suite all``) all of them.
SUITES: dict[str, Suite] = _suites()
