"""Speed against accuracy: work-precision measurements of the eigenvalue methods.

Every measurement is one :class:`WorkPrecision` point: a method, the wall time per grid
point it took on a large batch (best of ``repeat`` runs, after a warm-up that pays numba's
compilation), and its error against a reference on a sample of points. For the eigenvalue
methods the reference is mpmath at 50 digits (eigenvalues of ``M^-1 A`` of eq. 11), the error
the largest relative error per eigenvalue (each reference root paired with the nearest
computed one). Speed is quoted as a ratio against a baseline measured in the same run.

Methods compared (the sliding model, eq. 11):

* ``scipy loop``: ``scipy.linalg.eig(A, M)`` point by point (what a user would write first),
  timed on ``loop_points`` points (its time per point does not depend on the batch size);
* ``batched LAPACK``: ``numpy.linalg.eigvals(numpy.linalg.solve(M, A))`` on the whole batch;
* ``spectrum(method=...)`` for ``"lapack"``, ``"polynomial"`` and ``"kernel"``: the package's
  paths, each including the domain check, the error bounds and the stability decision;
* ``kernel, no polishing``: Cardano's roots (with deflation at separated scales) only.

The baselines start from prebuilt ``M`` and ``A`` (their construction is not timed); the
package's paths start from the parameters.

Other suites (continuation step-size settings against the exact location of a fold; the
integrators of the nonlinear runs) plug in by adding a function to :data:`SUITES` that returns
a list of :class:`WorkPrecision`; :func:`stability.plotting.work_precision.work_precision_figure`
draws any such list.
"""

from __future__ import annotations

import resource
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from .models import get_model

__all__ = ["WorkPrecision", "domain_sample", "eigen_reference", "eigen_errors", "eigen_work_precision",
           "peak_memory_mb", "SUITES"]

_NAMES = ("q", "fr_inv", "sigma", "alpha_v", "mu")


@dataclass(frozen=True)
class WorkPrecision:
    """One point of a work-precision chart.

    Attributes
    ----------
    method : str
        Label of the method and setting.
    seconds_per_point : float
        Wall time per grid point (best of the repeats).
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
    """

    method: str
    seconds_per_point: float
    error: float
    points: int
    baseline: bool = False
    default: bool = False
    note: str = ""

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


def _best_time(fn: Callable[[], Any], repeat: int) -> float:
    fn()  # warm-up: compilation, first touch of memory
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def peak_memory_mb() -> float:
    """Peak resident memory of this process so far, in MB (``ru_maxrss``)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def eigen_work_precision(points: int = 1_000_000, reference_points: int = 1000, loop_points: int = 20_000,
                         repeat: int = 3, seed: int = 0) -> list[WorkPrecision]:
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

    from . import kernel
    from .spectra import DEFAULT_METHOD, spectrum

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
    t = _best_time(lambda: loop(M, A, n_loop), max(1, repeat // 2))
    err = eigen_errors(loop(Ms, As, reference_points), ref).max()
    results.append(WorkPrecision("scipy loop", t / n_loop, err, n_loop, baseline=True,
                                 note="scipy.linalg.eig(A, M) per point"))
    t = _best_time(lambda: np.linalg.eigvals(np.linalg.solve(M, A)), repeat)
    err = eigen_errors(np.linalg.eigvals(np.linalg.solve(Ms, As)), ref).max()
    results.append(WorkPrecision("batched LAPACK", t / points, err, points, baseline=True,
                                 note="numpy.linalg.eigvals(solve(M, A)), whole batch"))
    del M, A
    for method in ("lapack", "polynomial", "kernel"):
        t = _best_time(lambda: spectrum("sliding", method=method, **big), repeat)
        err = eigen_errors(spectrum("sliding", method=method, **small).eigenvalues, ref).max()
        results.append(WorkPrecision(f"spectrum({method})", t / points, err, points,
                                     default=method == DEFAULT_METHOD,
                                     note="package path: domain check, bounds, decision"))
    for polish, label in ((3, "kernel"), (0, "kernel, no polishing")):
        t = _best_time(lambda: kernel.sliding_spectrum(*args, polish=polish), repeat)
        err = eigen_errors(kernel.sliding_spectrum(*(small[k] for k in _NAMES), polish=polish)[0], ref).max()
        results.append(WorkPrecision(label, t / points, err, points,
                                     note="stability.kernel.sliding_spectrum, from the parameters"))
    return results


#: name -> function returning a list of WorkPrecision (keyword arguments as eigen_work_precision
#: takes them where they apply). The continuation and integrator suites are added by their
#: modules when they provide one.
SUITES: dict[str, Callable[..., list[WorkPrecision]]] = {"eigen": eigen_work_precision}
