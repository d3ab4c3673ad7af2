"""Speed against accuracy: work-precision measurements, and the registry of suites.

Every measurement is one :class:`WorkPrecision` point: a method (at one setting), the wall
time per unit of work it took, and its error against an independent reference. A suite
(:class:`Suite`, registered by name in :data:`SUITES`) returns a list of them and says how its
chart is drawn (:class:`Panel`); ``tippe bench --suite NAME`` runs it and writes
``atlases/work_precision_NAME.png`` and ``.json``. Speed is quoted as a ratio against baselines
measured in the same run.

Suites:

* ``"eigen"`` (this module): the eigenvalue methods of the sliding model (eq. 11) on a large
  batch of points spread over the physical domain; time per point (best of ``repeat`` runs,
  after a warm-up that pays numba's compilation); error: the largest relative error per
  eigenvalue against mpmath at 50 digits (eigenvalues of ``M^-1 A``; each reference root
  paired with the nearest computed one). Methods: ``scipy.linalg.eig(A, M)`` point by point
  (baseline, what a user would write first, timed on ``loop_points`` points),
  ``numpy.linalg.eigvals(numpy.linalg.solve(M, A))`` on the whole batch (baseline), the
  package's paths ``spectrum(method=...)`` for ``"lapack"``, ``"polynomial"`` and ``"kernel"``
  (the default: domain check, error bounds and stability decision included), and the bare
  kernel (:func:`stability.linear.kernel.sliding_spectrum`, no domain check) with and without
  polishing. The baselines start from prebuilt ``M`` and ``A`` (their construction is not
  timed); the package's paths start from the parameters.
* ``"continuation"`` (:mod:`stability.performance_continuation`): the continuation's step
  settings against the exact fold of the sliding neutral curve, with brentq per column as the
  baseline.
* ``"integrators"`` (:mod:`stability.performance_integrators`): the integrators of the
  nonlinear runs against a tight DOP853 reference, and the stiff slip mode.
"""

from __future__ import annotations

import resource
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from .models import get_model

__all__ = ["WorkPrecision", "Panel", "Suite", "domain_sample", "eigen_reference", "eigen_errors",
           "eigen_work_precision", "peak_memory_mb", "best_time", "SUITES", "EIGEN_TARGET"]

_NAMES = ("q", "fr_inv", "sigma", "alpha_v", "mu")


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


def domain_sample(n: int, seed: int = 0) -> dict[str, np.ndarray]:
    """``n`` points spread over the physical domain of the sliding model.

    mu uniform in [0.5, 6]; q uniform in ``|q| < 0.98 / sqrt(mu)``; sigma uniform in
    ``[0.01, 1) x 2 (1 - mu q^2)``; fr_inv uniform in [0, 3]; alpha_v log-uniform in
    [1e-2, 1e1] (the distribution of the test suite's samples).
    """
    rng = np.random.default_rng(seed)
    mu = rng.uniform(0.5, 6.0, n)
    q = rng.uniform(-0.98, 0.98, n) / np.sqrt(mu)
    sigma = rng.uniform(0.01, 1.0, n) * 2.0 * (1.0 - mu * q * q)
    fr_inv = rng.uniform(0.0, 3.0, n)
    alpha_v = 10.0 ** rng.uniform(-2.0, 1.0, n)
    return {"q": q, "fr_inv": fr_inv, "sigma": sigma, "alpha_v": alpha_v, "mu": mu}


def eigen_reference(p: dict[str, np.ndarray], digits: int = 50) -> list[list[complex]]:
    """Eigenvalues of eq. (11) at ``digits`` digits (mpmath), matrices written out here."""
    import mpmath as mp

    out = []
    with mp.workdps(digits):
        i = mp.mpc(0, 1)
        for j in range(p["q"].size):
            q, F, sg, a, m = (mp.mpf(float(p[k][j])) for k in _NAMES)
            M = mp.matrix([[1, 0, i * m * q], [0, 1, 0], [-i * q, 0, 1]])
            A = mp.matrix([[-a + i * (sg - 1), i * (-(sg - 1) + m * q * F), i * a],
                           [-i, i, 0],
                           [-(q + i * a / m), q, -a / m]])
            out.append(list(mp.eig(M**-1 * A, left=False, right=False)))
    return out


def eigen_errors(ev: np.ndarray, reference: list[list]) -> np.ndarray:
    """Relative error of each reference eigenvalue (paired with the nearest computed one).

    Parameters
    ----------
    ev : numpy.ndarray of complex, shape (n, 3)
    reference : list of lists of mpmath numbers

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        ``|s - s_ref| / |s_ref|`` (absolute error where ``|s_ref| < 1e-40``, a structural zero).
    """
    import mpmath as mp

    out = np.zeros((len(reference), 3))
    for j, ref in enumerate(reference):
        left = [mp.mpc(complex(x)) for x in ev[j]]
        for k, r in enumerate(ref):
            d = [abs(x - r) for x in left]
            i = int(np.argmin([float(x) for x in d]))
            scale = abs(r) if abs(r) > mp.mpf(10) ** -40 else mp.mpf(1)
            out[j, k] = float(d[i] / scale)
            left.pop(i)
    return out


def best_time(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """Best (smallest) wall time of ``repeat`` calls of ``fn`` after one warm-up call, and the
    last result. The best, not the median: on this shared machine the other processes only
    ever add time, in bursts that can cover several consecutive runs."""
    if not (isinstance(repeat, int) and repeat >= 1):
        raise ValueError(f"repeat = {repeat!r} must be an integer >= 1")
    fn()
    best = np.inf
    out = None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return float(best), out


def _interleaved_best(fns: dict[str, tuple[Callable[[], Any], int]], repeat: int) -> dict[str, float]:
    """Best wall time of each function over ``repeat`` round-robin rounds, after one warm-up call
    each (compilation, first touch of memory)."""
    for fn, _ in fns.values():
        fn()
    best = dict.fromkeys(fns, np.inf)
    for _ in range(repeat):
        for name, (fn, _) in fns.items():
            t = time.perf_counter()
            fn()
            best[name] = min(best[name], time.perf_counter() - t)
    return best


def peak_memory_mb() -> float:
    """Peak resident memory of this process so far, in MB (``ru_maxrss``)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def eigen_work_precision(points: int = 1_000_000, reference_points: int = 1000, loop_points: int = 20_000,
                         repeat: int = 5, seed: int = 0) -> list[WorkPrecision]:
    """Work-precision points of the eigenvalue methods on the sliding model.

    Parameters
    ----------
    points : int
        Batch size for the timings (spread over the physical domain, :func:`domain_sample`).
    reference_points : int
        Sample size for the errors against mpmath at 50 digits.
    loop_points : int
        Points timed for the per-point scipy loop.
    repeat : int
        Timed repeats (the best is kept), after one warm-up run.
    seed : int
        Seed of the samples.

    Returns
    -------
    list of WorkPrecision
    """
    import scipy.linalg

    from .linear import kernel
    from .linear.spectra import DEFAULT_METHOD, spectrum

    model = get_model("sliding")
    big = domain_sample(points, seed)
    small = domain_sample(reference_points, seed + 1)
    ref = eigen_reference(small)
    args = [big[k] for k in _NAMES]
    M, A = model.matrices(**big)
    Ms, As = model.matrices(**small)
    results = []

    def loop(Mm, Am, n):
        return np.array([scipy.linalg.eig(Am[j], Mm[j], right=False) for j in range(n)])

    n_loop = min(loop_points, points)
    # the ratios the issue asks for come from one interleaved group (baselines, the default path
    # and the bare kernel timed round-robin, so a change of the machine's load hits them alike);
    # the slower cross-checks follow, after the baselines' matrices are freed
    group = {
        "scipy loop": (lambda: loop(M, A, n_loop), n_loop),
        "batched LAPACK": (lambda: np.linalg.eigvals(np.linalg.solve(M, A)), points),
        "spectrum(kernel)": (lambda: spectrum("sliding", method="kernel", **big), points),
        "kernel alone": (lambda: kernel.sliding_spectrum(*args, polish=3), points),
        "kernel alone, no polishing": (lambda: kernel.sliding_spectrum(*args, polish=0), points),
    }
    best = _interleaved_best(group, repeat)
    M = A = group = None  # free the baselines' matrices before the cross-checks
    best.update(_interleaved_best({f"spectrum({m})": (lambda m=m: spectrum("sliding", method=m, **big), points)
                                   for m in ("lapack", "polynomial")}, repeat))
    errors = {
        "scipy loop": loop(Ms, As, reference_points),
        "batched LAPACK": np.linalg.eigvals(np.linalg.solve(Ms, As)),
        **{f"spectrum({m})": spectrum("sliding", method=m, **small).eigenvalues
           for m in ("lapack", "polynomial", "kernel")},
        "kernel alone": kernel.sliding_spectrum(*(small[k] for k in _NAMES), polish=3)[0],
        "kernel alone, no polishing": kernel.sliding_spectrum(*(small[k] for k in _NAMES), polish=0)[0],
    }
    notes = {"scipy loop": "scipy.linalg.eig(A, M) per point",
             "batched LAPACK": "numpy.linalg.eigvals(solve(M, A)), whole batch"}
    for name in ("scipy loop", "batched LAPACK", "spectrum(lapack)", "spectrum(polynomial)", "spectrum(kernel)",
                 "kernel alone", "kernel alone, no polishing"):
        err = eigen_errors(errors[name], ref).max()
        n = n_loop if name == "scipy loop" else points
        if name in notes:
            results.append(WorkPrecision(name, best[name] / n, err, n, baseline=True, note=notes[name]))
        elif name.startswith("spectrum"):
            results.append(WorkPrecision(name, best[name] / n, err, n, default=name == f"spectrum({DEFAULT_METHOD})",
                                         note="package path: domain check, bounds, decision"))
        else:
            results.append(WorkPrecision(name, best[name] / n, err, n, component=True,
                                         note="stability.kernel.sliding_spectrum, from the parameters, "
                                              "no domain check"))
    return results


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
        Required accuracy (vertical line; the fastest point left of it is named).
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
    """A work-precision suite: what ``tippe bench --suite NAME`` runs and draws.

    Attributes
    ----------
    run : callable
        Returns a list of :class:`WorkPrecision`; takes the keywords among ``points``,
        ``reference_points``, ``loop_points``, ``repeat`` and ``quick`` that it names.
    title : str
        What was measured (the chart's title, before the default/fastest summary).
    panels : tuple of Panel
        The chart's panels, left to right.
    unit : str
        The unit of work of ``seconds_per_point`` ("point", "curve", "run").
    compare_at : tuple of str
        Errors (``"error"`` or keys of :attr:`WorkPrecision.extra`) at which speed is compared
        at equal accuracy: against the fastest setting of each baseline whose error is at most
        the point's. Empty: plain ratios against each baseline (the eigen suite, whose
        baselines are single points).
    """

    run: Callable[..., list[WorkPrecision]]
    title: str
    panels: tuple[Panel, ...]
    unit: str = "point"
    compare_at: tuple[str, ...] = ()


#: largest relative error per eigenvalue the issue requires
EIGEN_TARGET = 1e-13


def _continuation_suite(repeat: int = 5, quick: bool = False) -> list[WorkPrecision]:
    """:func:`stability.performance_continuation.continuation_work_precision` (imported on use)."""
    from .performance_continuation import continuation_work_precision

    return continuation_work_precision(repeat=repeat, quick=quick)


def _integrator_suite(repeat: int = 3, quick: bool = False) -> list[WorkPrecision]:
    """:func:`stability.performance_integrators.integrator_work_precision` (imported on use)."""
    from .performance_integrators import integrator_work_precision

    return integrator_work_precision(repeat=repeat, quick=quick)


#: required accuracy of the fold's coordinates (q*, sigma*) (the issue)
FOLD_TARGET = 1e-10

#: required accuracy of the 90-degree crossing time, in time units 1/Omega: the level at which
#: docs/nonlinear.md calls the scene's run converged (2e-7 from rtol 1e-9 to 1e-13)
CROSSING_TARGET = 1e-6

#: required relative accuracy of the growth rate fitted to a validation run: the agreement of
#: the fit with the linear operator at the benchmark's point (8.8e-7), so that the integrator
#: does not decide a validation's reading (stability.performance_integrators)
GROWTH_TARGET = 1e-6

CONTINUATION_TITLE = ("neutral curve of the sliding model in (q, sigma), fr_inv = 0, alpha_v = 0.5, mu = 2.28: "
                      "continuation vs brentq per column")
INTEGRATOR_TITLE = ("nonlinear sliding top, the paper's Fr^-1 = 0.3 run (Sec. 3(ii)), the stiff slip mode "
                    "and a validation run: integrators")


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
    }


#: name -> :class:`Suite`: "eigen" (this module), "continuation"
#: (:mod:`stability.performance_continuation`), "integrators"
#: (:mod:`stability.performance_integrators`); ``tippe bench --suite NAME`` runs one,
#: ``tippe bench`` (``--suite all``) all three.
SUITES: dict[str, Suite] = _suites()
