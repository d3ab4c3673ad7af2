"""Validation of the linear predictions by short nonlinear runs.

For each parameter point :func:`validate`

1. takes the leading mode ``s``: the mode with the largest growth rate (ties to the larger
   frequency) of the first-principles linearisation, from the spectral kernel
   (:func:`stability.spectrum` of the registered linear model that is the nonlinear model's
   linearisation, ``NonlinearModel.linear_model``: per-root accuracy and error bounds at any
   scale); a structural zero mode (``s = 0`` with error bound 0, from an exactly zero
   coefficient: the sliding model at ``fr_inv = 0``) is skipped by its structure, never by
   being small beside the largest mode (which at ``alpha_v = 1e12``, slip mode ``-1.3e12``,
   made the O(1) modes look like zeros and picked the slip mode);
2. takes the eigenvector of the nonlinear model's Jacobian (:func:`stability.jacobian_eigenvalues`)
   for the eigenvalue nearest ``s``, sharpened by two steps of inverse iteration with the shift
   ``s``, and the Jacobian's eigenvalue with its error bound ``jacobian_bound``
   (``8 n u ||A||_F kappa``, ``kappa`` the eigenvalue's condition number: LAPACK's error is
   absolute, ``~u`` of the largest mode, so at ``alpha_v = 1e9`` an O(1) mode's growth rate
   ``1e-11`` is not resolved, and ``jacobian_resolved`` says so);
3. starts the nonlinear model (:func:`stability.simulate`) on the upright spin
   ``omega = k = K`` plus that eigenvector scaled to a tilt ``|Phi| = amplitude``
   (default ``1e-4`` rad: the neglected terms are ``O(|Phi|^2)`` relative, ``1e-8``, far below
   the 1 % target even after the growth of the run), integrated by ``method`` (default
   ``"auto"``: the compiled Dormand-Prince, or LSODA where the slip mode is stiff, as
   :func:`stability.simulate` decides);
4. integrates over ``n_efold`` e-folding times ``1 / |Re s|`` (``n_periods`` periods
   ``2 pi / |Im s|`` for a neutral mode), capped at ``max_time``;
5. fits ``log |Phi(t)|`` and the unwrapped phase of ``Phi(t) = k_1 + i k_2`` by straight
   lines: the slopes are the measured growth rate and (fixed-frame) frequency;
6. returns the predictions of the registered linear operator that linearises the model
   (``NONLINEAR_MODELS[model].linear_model``: eq. 11 for ``"sliding"``, eq. (8) for
   ``"fixed_pivot"``, the first-principles ``"rolling"``) and of the Jacobian, the measured
   values, the relative errors, and whether the measurement is to be trusted.

A measurement is *resolved* only if everything holds: the growth rate is resolved,
``|Re s| > 1e-3 |s|`` (elsewhere the relative error of the growth rate is meaningless and the
error is reported relative to ``|s|``); the run succeeded (``status == 0``); every sample is
finite; and the log-linear fit is good (RMS residual of ``log |Phi|`` at most
:data:`FIT_RMS`). The variable ``status`` says which failed ("ok" otherwise); a run that
failed or gave non-finite samples also has ``sign_agrees = False`` and is reported by a
``RuntimeWarning``.

Eq. (8) as printed for the rolling top (model ``"rolling_eq8"``) is not the rolling sphere's
linearisation and is not what ``validate("rolling")`` predicts with (docs/nonlinear.md).

Coulomb friction alone (``alpha_v = 0``, ``alpha_k > 0``) has no linear operator (the
friction does not vanish with the slip); :func:`coulomb_growth` runs it and compares an
exponential with an algebraic (linear-in-time) fit of the tilt amplitude.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import xarray as xr

from ..errors import InputError, ParameterTypeError
from ..linear.modes import structural_zeros
from ..linear.roots import UNIT_ROUNDOFF
from ..linear.spectra import eigenvalues, spectrum
from ..models import MODELS
from ..parameters import DEFAULT_MU, check_choice, check_domain, check_interval, check_positive, parameter_attrs
from ..products import PRODUCT_ATTR
from . import get_nonlinear_model
from .integrators import SCIPY_METHODS, check_tolerances
from .jacobian import transverse_jacobian
from .runs import simulate

__all__ = ["FIT_RMS", "RESOLVED", "coulomb_growth", "validate"]

#: a growth rate is compared relatively where |Re s| > RESOLVED |s|
RESOLVED: float = 1e-3

#: the largest RMS residual of the fit of log|Phi(t)| by a straight line for a resolved measurement
#: (an exponential mode fits to ~1e-8: the O(|Phi|^2) terms and the integrator's error)
FIT_RMS: float = 1e-3


def _mode_start(model: str, v: np.ndarray) -> dict[str, Any]:
    """``omega``, ``k`` (and the sliding top's ``velocity``) of the upright spin ``omega = k = K``
    displaced along the transverse mode ``v`` (``omega, Phi[, V]``, complex, scaled)."""
    start = {"omega": [v[0].real, v[0].imag, 1.0], "k": [v[1].real, v[1].imag, np.sqrt(1.0 - abs(v[1]) ** 2)]}
    if model == "sliding":
        start["velocity"] = [v[2].real, v[2].imag]
    return start


def _leading(model: str, params: dict[str, Any]) -> tuple[complex, np.ndarray, np.ndarray, np.ndarray, np.ndarray, int]:
    """``(s, A, ev, vec, bound, i)``: the leading mode ``s`` of the first-principles linearisation,
    the model's transverse Jacobian ``A``, its eigenvalues, unit eigenvectors (columns) and
    error bounds, and the index ``i`` of the eigenvalue nearest ``s``.

    ``s`` comes from the kernel (per-root accuracy; the registered operator
    ``NONLINEAR_MODELS[model].linear_model`` is the linearisation for every model since
    ``"rolling"`` is the first-principles one, issue 15): the largest real part among the modes
    that are not structural zeros (``s = 0`` exactly with an error bound of exactly 0,
    :func:`stability.linear.modes.structural_zeros`); real parts equal within their error
    bounds tie, and the larger ``Im s`` wins. Every mode counts, however small beside the
    largest.

    The bound of the Jacobian's eigenvalue ``j`` is ``8 n u ||A||_F kappa_j`` with the condition
    number ``kappa_j = ||x_j|| ||y_j|| / |y_j^H x_j|`` (right and left eigenvectors; the rows of
    ``V^-1`` are the left ones scaled so that ``y_j^H x_j = 1``): LAPACK's backward error
    ``~n u ||A||`` carried to the eigenvalue to first order. Absolute: a mode far smaller than
    the largest is known only to ``~u ||A||``.
    """
    fp = spectrum(MODELS[get_nonlinear_model(model).linear_model], **params)
    values, e = np.asarray(fp.eigenvalues, dtype=complex), np.asarray(fp.error_bound, dtype=float)
    zero = structural_zeros(values.real, values.imag, e)
    cand = [i for i in range(values.size) if not zero[i]] or list(range(values.size))
    best = max(cand, key=lambda i: values[i].real)
    near = [i for i in cand if values[i].real >= values[best].real - (e[i] + e[best])]
    s = complex(values[max(near, key=lambda i: values[i].imag)])
    A, _ = transverse_jacobian(model, params)
    ev, vec = np.linalg.eig(A)
    n = A.shape[0]
    try:
        kappa = np.linalg.norm(np.linalg.inv(vec), axis=1) * np.linalg.norm(vec, axis=0)
    except np.linalg.LinAlgError:  # defective to working precision
        kappa = np.full(n, np.inf)
    bound = 8 * n * UNIT_ROUNDOFF * np.linalg.norm(A) * kappa
    return s, A, ev, vec, bound, int(np.argmin(np.abs(ev - s)))


def _one_point(model: str, params: dict[str, float], run: dict[str, Any]) -> dict[str, Any]:
    """The row of one point (module docstring); ``run`` holds the checked options of
    :func:`validate` (``amplitude, n_efold, n_periods, max_time, rtol, atol, method``)."""
    m = get_nonlinear_model(model)
    s, A, ev, vec, bound, i = _leading(m.name, params)
    s_jac, jac_bound = complex(ev[i]), float(bound[i])
    x = vec[:, i]
    for _ in range(2):  # inverse iteration with the kernel's eigenvalue as the shift
        try:
            y = np.linalg.solve(A - s * np.eye(len(x)), x)
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(y)) or not np.any(y):
            break
        x = y / np.linalg.norm(y)
    v = x / x[1] * run["amplitude"]  # |Phi| = amplitude, Phi real at t = 0
    growth_resolved = abs(s.real) > RESOLVED * abs(s)
    # n_efold e-folding times, else n_periods periods, else (s = 0) max_time, at most max_time
    t_end = run["max_time"]
    if growth_resolved:
        t_end = run["n_efold"] / abs(s.real)
    elif s.imag != 0.0:
        t_end = run["n_periods"] * 2.0 * np.pi / abs(s.imag)
    t_end = min(t_end, run["max_time"])
    # at least 8 samples per period so that the phase unwraps without aliasing
    n_samples = max(401, int(8 * t_end * abs(s.imag) / (2 * np.pi)) + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # reported below, once, with the point
        start = dict(t_eval=np.linspace(0.0, t_end, n_samples), **_mode_start(m.name, v))
        tolerances = {k: run[k] for k in ("rtol", "atol", "method")}
        ds = simulate(model, t_end=t_end, **start, **tolerances, **params)
    phi = ds.k.values[:, 0] + 1j * ds.k.values[:, 1]
    # the slopes of log|Phi| and of the unwrapped phase (least squares), and the RMS residual of
    # the first fit; NaN if fewer than two samples are finite and nonzero
    g = w = rms = np.nan
    ok = np.isfinite(phi) & (phi != 0)
    if ok.sum() >= 2:
        t, phi_ok = ds.time.values[ok], phi[ok]
        log_amp = np.log(np.abs(phi_ok))
        g_fit = np.polyfit(t, log_amp, 1)
        g = float(g_fit[0])
        w = float(np.polyfit(t, np.unwrap(np.angle(phi_ok)), 1)[0])
        rms = float(np.sqrt(np.mean((np.polyval(g_fit, t) - log_amp) ** 2)))
    lost = f"contact lost at t = {ds.attrs['event_time']:.6g} (the normal force reached zero; the model does not hold"
    lost += " beyond)"
    poor = f"poor fit: RMS residual {rms:.2g} of log|Phi| (at most {FIT_RMS:g} for a resolved measurement)"
    failures = (  # (failed, why): the first that holds is the status
        (ds.attrs["event"] != "none", lost),
        (ds.attrs["status"] != 0, f"integration failed ({ds.attrs['method']}): {ds.attrs['message']}"),
        (not np.all(np.isfinite(phi)), "the run's samples are not all finite"),
        (not rms <= FIT_RMS, poor),
    )
    failed, status = next((f for f in failures if f[0]), (False, "ok"))
    if status == "ok" and not growth_resolved:
        status = f"growth rate not resolved: |Re s| <= {RESOLVED:g} |s| (its error is relative to |s|)"

    def rel(meas: float, pred: float, scale: float) -> float:
        return abs(meas - pred) / (abs(pred) if abs(pred) > 0 else scale)

    def growth_error(s: complex) -> float:  # relative to |s| where the growth rate is not resolved
        return rel(g, s.real, abs(s)) if growth_resolved else abs(g - s.real) / abs(s)

    # the signs agree (neutral within RESOLVED |s| where the growth rate is not resolved); never for a failed run
    agrees = not failed and bool(np.sign(g) == np.sign(s.real) if growth_resolved else abs(g) <= RESOLVED * abs(s))
    return {
        "predicted_growth_rate": s.real,
        "predicted_frequency": s.imag,
        "jacobian_growth_rate": s_jac.real,
        "jacobian_frequency": s_jac.imag,
        "jacobian_bound": jac_bound,
        "jacobian_resolved": bool(abs(s_jac.real) > 4.0 * jac_bound),
        "measured_growth_rate": g,
        "measured_frequency": w,
        "growth_rate_error": growth_error(s),
        "frequency_error": rel(w, s.imag, abs(s)),
        "growth_rate_error_jacobian": growth_error(s_jac),
        "frequency_error_jacobian": rel(w, s_jac.imag, abs(s_jac)),
        "resolved": status == "ok",
        "sign_agrees": agrees,
        "duration": t_end,
        "final_tilt": float(abs(phi[-1])),
        "fit_rms": rms,
        "status": status,
        "_failed": failed,
    }


_LINEAR, _JACOBIAN = "the registered linear operator", "the nonlinear model's Jacobian"
_ERROR = "relative error of the measured {} against the {}"
_UNRESOLVED = " (relative to |s| where the growth rate is not resolved)"
_RUN = "of the nonlinear run"

_ERROR_LIN, _ERROR_JAC = (_ERROR.format("{}", w) for w in ("linear operator", "Jacobian"))
_BOUND = "error bound of the Jacobian's eigenvalue: 8 n u ||A||_F times its condition number (absolute: ~u of the"
_JAC_RESOLVED = (
    "the Jacobian's growth rate exceeds four times its error bound (else compare with predicted_growth_rate,"
)
_RESOLVED = "the measurement holds: growth rate resolved (|Re s| > 1e-3 |s|), the run succeeded, its samples are"
_AGREES = "sign of the measured growth rate agrees with the linearisation's (neutral where the growth rate is"

#: name -> (long_name, units, comment) of the validation dataset's variables
_VAR_ATTRS = {
    "predicted_growth_rate": ("predicted growth rate", "Omega", f"growth rate Re s of {_LINEAR}"),
    "predicted_frequency": ("predicted frequency", "Omega", f"frequency Im s of {_LINEAR} (fixed frame)"),
    "jacobian_growth_rate": ("Jacobian growth rate", "Omega", f"growth rate Re s of {_JACOBIAN}"),
    "jacobian_frequency": ("Jacobian frequency", "Omega", f"frequency Im s of {_JACOBIAN} (fixed frame)"),
    "measured_growth_rate": ("measured growth rate", "Omega", f"growth rate fitted to log|Phi(t)| {_RUN}"),
    "measured_frequency": ("measured frequency", "Omega", f"frequency fitted to the phase of Phi(t) {_RUN}"),
    "growth_rate_error": ("growth error (linear)", "1", _ERROR_LIN.format("growth rate") + _UNRESOLVED),
    "frequency_error": ("frequency error (linear)", "1", _ERROR_LIN.format("frequency")),
    "growth_rate_error_jacobian": ("growth error (Jacobian)", "1", _ERROR_JAC.format("growth rate") + _UNRESOLVED),
    "frequency_error_jacobian": ("frequency error (Jacobian)", "1", _ERROR_JAC.format("frequency")),
    "jacobian_bound": ("Jacobian error bound", "Omega", _BOUND + " largest mode)"),
    "jacobian_resolved": ("Jacobian resolved", None, _JAC_RESOLVED + " from the spectral kernel)"),
    "resolved": ("growth resolved", None, _RESOLVED + " finite and log|Phi| fits a straight line (see status)"),
    "sign_agrees": ("sign agrees", None, _AGREES + " unresolved; False where the run failed)"),
    "duration": ("duration", "1/Omega", "length of the run"),
    "final_tilt": ("final tilt |Phi|", "1", "tilt |Phi| at the end of the run"),
    "fit_rms": ("fit RMS residual", "1", "RMS residual of the straight-line fit of log|Phi(t)|"),
    "status": ("status", None, "ok, or why the measurement is not resolved"),
}


def validate(
    model: str,
    *,
    q: Any,
    fr_inv: Any,
    sigma: Any,
    alpha_v: Any = None,
    mu: Any = DEFAULT_MU,
    amplitude: float = 1e-4,
    n_efold: float = 4.0,
    n_periods: float = 10.0,
    max_time: float = 3000.0,
    rtol: float = 1e-11,
    atol: float = 1e-15,
    method: str = "auto",
) -> xr.Dataset:
    """Compare linear growth rates and frequencies with short nonlinear runs.

    Parameters
    ----------
    model : {"sliding", "rolling", "fixed_pivot"}
        Nonlinear model; its predictions come from the linear model of the same name and from
        its Jacobian (:func:`stability.jacobian_eigenvalues`).
    q, fr_inv, sigma, alpha_v, mu : float, array_like or xarray.DataArray
        Parameters, broadcast together to a list of points (``alpha_v`` for ``"sliding"`` only).
        An atlas subset is passed as its coordinates (``q=sub.q, fr_inv=sub.fr_inv, ...``):
        DataArrays broadcast by their dimension names, so coordinates along different
        dimensions make the whole grid of the subset (numpy arrays broadcast by position).
    amplitude : float, default 1e-4
        Initial tilt ``|Phi|`` along the leading eigenvector.
    n_efold, n_periods : float
        Length of a run in e-folding times or periods (the longer of the two).
    max_time : float
        Cap on the length of a run.
    rtol, atol : float
        Tolerances of the integrator.
    method : str, default "auto"
        Integrator of the runs: ``"auto"`` (the compiled Dormand-Prince 5(4), or LSODA where
        the slip mode is stiff, as :func:`stability.simulate` decides), ``"dopri5"``, or a
        scipy method (``"RK45"``, ``"DOP853"``, ``"Radau"``, ``"BDF"``, ``"LSODA"``); the
        integrator benchmark (``python benchmarks/run.py --suite integrators``) compares them on the fitted
        growth rate.

    Returns
    -------
    xarray.Dataset
        Along ``point``: the parameters, ``predicted_*`` (linear operator), ``jacobian_*``
        (with ``jacobian_bound``, ``jacobian_resolved``), ``measured_*``, the relative errors,
        ``resolved``, ``sign_agrees``, ``fit_rms`` and ``status`` (module docstring). A point
        whose run failed (or whose samples are not finite, or do not fit) is reported by a
        ``RuntimeWarning``.

    Examples
    --------
    >>> import stability
    >>> ds = stability.validate("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    >>> bool(ds.growth_rate_error.max() < 0.01)
    True
    >>> sub = stability.atlas("sliding", q=[-0.1, 0.1], fr_inv=[0.3, 1.0], sigma=1.0, alpha_v=0.5)
    >>> validate_grid = stability.validate("sliding", q=sub.q, fr_inv=sub.fr_inv, sigma=sub.sigma,
    ...                                    alpha_v=sub.alpha_v, n_efold=1.0)
    >>> validate_grid.sizes["point"]
    4
    """
    m = get_nonlinear_model(model)
    given = {"q": q, "fr_inv": fr_inv, "sigma": sigma, "mu": mu}
    if m.name == "sliding":
        if alpha_v is None:
            raise ParameterTypeError(
                "alpha_v is required for model 'sliding' (alpha_v > 0; for Coulomb friction alone use coulomb_growth)"
            )
        given["alpha_v"] = alpha_v
    elif alpha_v is not None:
        raise ParameterTypeError(f"model {m.name!r} takes no parameter alpha_v")
    named = {k: v for k, v in given.items() if isinstance(v, xr.DataArray)}
    if named:  # an atlas subset: broadcast by dimension name (the grid of the subset)
        for k, v in zip(named, xr.broadcast(*named.values())):
            given[k] = v.values
    arrays, _ = check_domain(maskable=False, **given)
    flat = {k: np.ravel(v) for k, v in arrays.items()}
    if m.name == "sliding" and np.any(flat["alpha_v"] == 0):
        raise InputError(
            "alpha_v = 0 has no exponential mode to validate (frictionless, or "
            "Coulomb only); the allowed range here is alpha_v > 0 (coulomb_growth "
            "handles alpha_k > 0)"
        )
    run = dict(amplitude=check_interval("amplitude", amplitude, 0.0, 0.1), n_efold=check_positive("n_efold", n_efold))
    run.update(n_periods=check_positive("n_periods", n_periods), max_time=check_positive("max_time", max_time))
    run.update(zip(("rtol", "atol"), check_tolerances(rtol=rtol, atol=atol)))
    run["method"] = check_choice("method", method, ("auto", "dopri5") + tuple(SCIPY_METHODS))
    rows = []
    for j in range(flat["q"].size):
        pt = {k: float(v[j]) for k, v in flat.items()}
        row = _one_point(m.name, pt, run)
        if row.pop("_failed"):
            where = ", ".join(f"{k} = {v:g}" for k, v in pt.items())
            warnings.warn(
                f"validate({m.name!r}): point {j} ({where}): {row['status']}; its measurement is not resolved",
                RuntimeWarning,
                stacklevel=2,
            )
        rows.append(row)
    data = {}
    for name in rows[0]:
        vals = np.array([r[name] for r in rows], dtype=object if name == "status" else None)
        long_name, units, comment = _VAR_ATTRS[name]
        units = {} if units is None else {"units": units}
        data[name] = ("point", vals, {"long_name": long_name, "comment": comment, **units})
    coords = {k: ("point", v, parameter_attrs(k)) for k, v in flat.items()}
    ds = xr.Dataset(data, coords=coords)
    title = f"validation of the linear {m.name} model by nonlinear runs"
    ds.attrs.update(Conventions="CF-1.10", title=title, source="stability.validate", model=m.name)
    ds.attrs.update(linear_model=m.linear_model, jacobian_of=f"nonlinear {m.name} model ({m.equations})")
    ds.attrs.update(run)
    ds.attrs["convention"] = "x ~ exp(s t), fixed frame, spin +1, t in 1/Omega"
    ds.attrs[PRODUCT_ATTR] = "validation"
    return ds


def coulomb_growth(
    *,
    q: float,
    fr_inv: float,
    sigma: float,
    alpha_k: float,
    mu: float = DEFAULT_MU,
    amplitude: float = 0.05,
    t_end: float = 600.0,
    scheme: str = "adaptive",
    step: float = 0.1,
    friction: str = "isotropic",
    slip_scale: float = 1e-4,
    rtol: float = 1e-8,
    atol: float = 1e-11,
) -> xr.Dataset:
    """Coulomb friction alone (``alpha_v = 0``): how the tilt grows, and whether it is exponential.

    The run starts on the upright spin plus the leading mode of the viscous model at
    ``alpha_v = alpha_k``, scaled to a tilt ``amplitude``. The tilt ``A(t) = |Phi(t)|`` is
    fitted two ways: ``log A = a + g t`` (exponential) and ``A = A0 + c t`` (algebraic).

    Two schemes:

    * ``"adaptive"``: the regularised law (``slip_scale``) integrated to tolerance (LSODA).
      The slip is extinguished within a fraction of a spin period and the sphere then rolls
      (sticks); at sticking the law is viscous with coefficient ``alpha_k / slip_scale``, so the
      growth is exponential with the rate of eq. (11) at ``alpha_v = alpha_k / slip_scale``
      (tiny, and tending to zero with ``slip_scale``: the rolling limit).
    * ``"fixed_step"``: the paper's fixed-step RK4 with the unregularised sign law
      (``slip_scale = 1e-12``) and step ``step``: the slip chatters at a size set by the step
      and never vanishes, and the tilt grows roughly linearly in time, at a rate that depends
      on the step (docs/nonlinear.md).

    Returns
    -------
    xarray.Dataset
        Along ``time``: ``tilt`` and ``slip_speed``; attributes ``exponential_residual`` and
        ``algebraic_residual`` (RMS relative residuals of the two fits), ``growth``
        (``"none"`` if the tilt changed by less than 1 %, else ``"algebraic"`` if the
        linear-in-time fit is the better one, else ``"exponential"``),
        ``exponential_rate``, ``algebraic_slope``, ``median_slip_speed``,
        ``sticking_growth_rate`` (eq. 11 at ``alpha_v = alpha_k / slip_scale``).
    """
    alpha_k = check_positive("alpha_k", alpha_k)
    check_choice("scheme", scheme, ("adaptive", "fixed_step"))
    amplitude = check_interval("amplitude", amplitude, 0.0, 0.1, closed="right")
    t_end = check_positive("t_end", t_end)
    top = dict(q=q, fr_inv=fr_inv, sigma=sigma, mu=mu)
    _, _, _, vec, _, i = _leading("sliding", {**top, "alpha_v": alpha_k})
    v = vec[:, i] / vec[1, i] * amplitude
    run = dict(t_end=t_end, dt=t_end / 3000, **_mode_start("sliding", v))
    run.update(**top, alpha_v=0.0, alpha_k=alpha_k, friction=friction)
    if scheme == "adaptive":
        ds = simulate("sliding", **run, slip_scale=slip_scale, method="LSODA", rtol=rtol, atol=atol)
    else:
        slip_scale = 1e-12
        ds = simulate("sliding", **run, slip_scale=slip_scale, method="rk4", step=step)
    t = ds.time.values
    tilt = np.hypot(ds.k.values[:, 0], ds.k.values[:, 1])
    pe = np.polyfit(t, np.log(tilt), 1)
    pa = np.polyfit(t, tilt, 1)
    res_e = float(np.sqrt(np.mean((np.exp(np.polyval(pe, t)) / tilt - 1) ** 2)))
    res_a = float(np.sqrt(np.mean((np.polyval(pa, t) / tilt - 1) ** 2)))
    s_stick = eigenvalues("sliding", **top, alpha_v=alpha_k / slip_scale)
    tilt_attrs = {"long_name": "tilt |Phi| = |k_1 + i k_2|", "units": "1"}
    out = xr.Dataset({"tilt": ("time", tilt, tilt_attrs), "slip_speed": ds.slip_speed}, coords={"time": ds.time})
    title, source = "Coulomb friction alone: growth of the tilt", "stability.nonlinear.validation.coulomb_growth"
    out.attrs.update(Conventions="CF-1.10", title=title, source=source, **top, alpha_k=alpha_k, alpha_v=0.0)
    out.attrs.update(friction=friction, amplitude=amplitude, scheme=scheme)
    out.attrs.update(step=step if scheme == "fixed_step" else 0.0, slip_scale=slip_scale)
    out.attrs.update(exponential_residual=res_e, algebraic_residual=res_a)
    growth = "none" if abs(tilt[-1] / tilt[0] - 1) < 1e-2 else "algebraic" if res_a < res_e else "exponential"
    out.attrs.update(growth=growth, algebraic_slope=float(pa[0]), exponential_rate=float(pe[0]))
    out.attrs.update(median_slip_speed=float(np.median(ds.slip_speed.values)))
    out.attrs.update(sticking_growth_rate=float(np.max(s_stick.real)), final_tilt=float(tilt[-1]))

    out.attrs[PRODUCT_ATTR] = "coulomb_growth"
    return out
