"""Analytic interface laws fitted to the homogenized curves (report section 10).

A structural code needs the interface law as a formula; the report fits the
approach-pressure points (a_k, p_k), k = 1..M, of a homogenized interface
with the Oden-Martins normal compliance law (10.42)::

    p = c ((a - g) / a0)^m,      a0 = 1 um   (zero for a <= g)

(c, g, m material constants; g the translation "which appropriately locates
the zero point for the approach axis") by minimizing (10.43)::

    B(c, g, m) = sum_k [p(c, g, m, a_k) - p_k]^2

and notes that "the approach presented here is applicable to other
formulations, such as exponential normal compliance law", here::

    p = c exp(a / lambda)        (lambda: decay length; c = p at a = 0)

the law of a surface with exponentially distributed heights.

The residuals: ``absolute`` is the report's B (10.43); ``log`` minimizes
sum_k [ln p(a_k) - ln p_k]^2, each point weighted by its relative error,
which a curve over several decades needs (with absolute residuals the top
few points decide everything).  The fit is nonlinear least squares (scipy
``least_squares``, trust region, analytic Jacobian) on the variables
(ln c, g / L, m) or (ln c, lambda / L), L the span of the approaches;
started, for a free g, from the best log-linear fit over a grid of g below
the smallest approach.  Uncertainties: the covariance s^2 (J^T J)^-1 with
J the Jacobian of the residuals with respect to the parameters at the
optimum and s^2 = B / (M - P), the standard errors its diagonal's roots
(valid for independent residuals of equal variance in the fitted space).

The approach: a = h0 - h, h the separation of ``interface.nc`` and h0 the
scene's ``approach_origin`` (by default the largest separation of the
data: "the approach was measured from a rather large separation", 7.3).  The
report chooses the zero "where some noticeable normal load develops" (7.3)
or to match the experiment (8.2.2); g takes up what the origin leaves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import xarray as xr
from scipy import optimize

from asperity.friction import loading_branch
from asperity.scene import Laws
from asperity.scene.interface import LAWS, ApproachOrigin
from asperity.units import attrs

__all__ = ["A0", "LAWS", "PARAMETERS", "LawFit", "oden_martins", "exponential",
           "fit_oden_martins", "fit_exponential", "fit_law", "approach", "laws_dataset"]

A0 = 1e-6  # m: the report's dimensionality factor a0 = 1 um (10.42)
PARAMETERS = ("c", "g", "m", "decay_length")
PARAMETER_UNITS = {"c": "Pa", "g": "m", "m": "1", "decay_length": "m"}
RESIDUALS = ("absolute", "log")
_TOL = 1e-15



def oden_martins(a, c: float, g: float, m: float, a0: float = A0) -> np.ndarray:
    """p = c ((a - g)/a0)^m for a > g, 0 otherwise (10.42)."""
    u = (np.asarray(a, dtype=float) - g) / a0
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(u > 0.0, c * np.where(u > 0.0, u, 1.0) ** m, 0.0)


def exponential(a, c: float, decay_length: float) -> np.ndarray:
    """p = c exp(a / lambda): the exponential normal compliance law."""
    return c * np.exp(np.asarray(a, dtype=float) / decay_length)


@dataclass
class LawFit:
    """One fitted law: parameters (SI), standard errors, covariance, residuals."""

    law: str
    residual: str
    names: tuple[str, ...]
    values: dict[str, float]
    stderr: dict[str, float]
    covariance: np.ndarray  # over `free`, in their order
    free: tuple[str, ...]
    residuals: np.ndarray  # in the fitted space at the data points (Pa or ln)
    r_squared: float
    points: int
    predict: Callable[[np.ndarray], np.ndarray] = field(repr=False)
    fixed: tuple[str, ...] = ()

    @property
    def ssr(self) -> float:
        return float(np.sum(self.residuals**2))


def _check(a, p, residual: str, n_free: int):
    a = np.asarray(a, dtype=float)
    p = np.asarray(p, dtype=float)
    if a.shape != p.shape or a.ndim != 1:
        raise ValueError("approaches and pressures must be 1-D arrays of one length")
    if residual not in RESIDUALS:
        raise ValueError(f"residual {residual!r}: one of {', '.join(RESIDUALS)}")
    if a.size <= n_free:
        raise ValueError(f"{a.size} points cannot determine {n_free} parameters with an "
                         "uncertainty; widen the fit window (laws.pressure_range)")
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(p))):
        raise ValueError("the fit needs finite approaches and pressures")
    if residual == "log" and not np.all(p > 0.0):
        raise ValueError("log residuals need positive pressures")
    if np.count_nonzero(p > 0.0) < 2:
        raise ValueError("the fit needs at least two positive pressures")
    return a, p


def _covariance(jac: np.ndarray, residuals: np.ndarray) -> np.ndarray:
    """s^2 (J^T J)^-1 with column scaling for conditioning, s^2 = SSR / (M - P)."""
    m, n = jac.shape
    norms = np.linalg.norm(jac, axis=0)
    norms = np.where(norms > 0, norms, 1.0)
    js = jac / norms
    inv = np.linalg.pinv(js.T @ js)
    s2 = float(residuals @ residuals) / (m - n)
    return s2 * inv / np.outer(norms, norms)


def _r_squared(residuals: np.ndarray, observed: np.ndarray) -> float:
    sst = float(np.sum((observed - observed.mean()) ** 2))
    return 1.0 - float(residuals @ residuals) / sst if sst > 0 else math.nan


def _log_linear(x: np.ndarray, y: np.ndarray):
    """Least squares y = b0 + b1 x along the last axis (x, y broadcast): b0, b1, SSR."""
    xm, ym = x.mean(axis=-1, keepdims=True), y.mean(axis=-1, keepdims=True)
    sxx = ((x - xm) ** 2).sum(axis=-1)
    b1 = ((x - xm) * (y - ym)).sum(axis=-1) / sxx
    b0 = ym[..., 0] - b1 * xm[..., 0]
    ssr = ((y - b0[..., None] - b1[..., None] * x) ** 2).sum(axis=-1)
    return b0, b1, ssr


def fit_oden_martins(a, p, gap: float | None = None, residual: str = "absolute",
                     a0: float = A0) -> LawFit:
    """Fit p = c ((a - g)/a0)^m (10.42) by least squares (10.43 for ``absolute``).

    `gap` None fits g; a number fixes it (the report's steel: g = 0).
    Every data point must lie beyond the gap (a > g): with ``log`` residuals
    g stays below the smallest approach.
    """
    free_g = gap is None
    a, p = _check(a, p, residual, 3 if free_g else 2)
    span = float(a.max() - a.min()) or abs(float(a.max())) or a0
    a_min = float(a.min())
    pos0 = p > 0.0  # the start uses the positive points (absolute residuals allow others)
    lp = np.log(np.where(pos0, p, 1.0))
    if free_g:
        # start: the best log-linear fit over g = a_min - span * 10^k, k in [-4, 2]
        g_try = a_min - span * np.logspace(-4, 2, 121)
        x = np.log((a[None, pos0] - g_try[:, None]) / a0)
        b0, b1, ssr = _log_linear(x, np.broadcast_to(lp[pos0], x.shape))
        best = int(np.argmin(ssr))
        g0, lc0, m0 = float(g_try[best]), float(b0[best]), float(b1[best])
    else:
        g0 = float(gap)
        if np.any(a <= g0):
            raise ValueError(f"fixed gap {g0:.6g} m is not below every approach of the fit window "
                             f"(smallest {a_min:.6g} m)")
        b0, b1, _ = _log_linear(np.log((a[pos0] - g0) / a0), lp[pos0])
        lc0, m0 = float(b0), float(b1)

    def unpack(x):
        return (x[0], x[1] * span, x[2]) if free_g else (x[0], g0, x[1])

    def model_terms(x):
        lc, g, m = unpack(x)
        u = (a - g) / a0
        lu = np.log(np.where(u > 0, u, 1.0))
        pm = np.where(u > 0, np.exp(lc + m * lu), 0.0)
        return lc, g, m, u, lu, pm

    def fun(x):
        lc, g, m, u, lu, pm = model_terms(x)
        if residual == "log":
            return lc + m * lu - lp
        return pm - p

    def jac(x):
        lc, g, m, u, lu, pm = model_terms(x)
        pos = u > 0
        if residual == "log":
            cols = [np.ones_like(a), -m / np.where(pos, a - g, 1.0) * span, lu]
        else:  # d/d ln c, d/d (g/L), d/dm of c u^m
            cols = [pm, np.where(pos, -pm * m / np.where(pos, a - g, 1.0), 0.0) * span, pm * lu]
        if not free_g:
            cols = [cols[0], cols[2]]
        return np.stack(cols, axis=1)

    x0 = np.array([lc0, (g0) / span, m0]) if free_g else np.array([lc0, m0])
    lower = np.full(x0.size, -np.inf)
    upper = np.full(x0.size, np.inf)
    if free_g and residual == "log":  # the log needs a - g > 0 at every point
        upper[1] = (a_min - 1e-9 * span) / span
        x0[1] = min(x0[1], upper[1] - 1e-9)
    sol = optimize.least_squares(fun, x0, jac=jac, bounds=(lower, upper), method="trf",
                                 xtol=_TOL, ftol=_TOL, gtol=_TOL, max_nfev=2000)
    lc, g, m, u, lu, pm = model_terms(sol.x)
    c = math.exp(lc)
    res = fun(sol.x)
    # Jacobian of the residuals in the natural parameters (c, g, m)
    pos = u > 0
    if residual == "log":
        dc, dg, dm = np.full_like(a, 1.0 / c), -m / np.where(pos, a - g, 1.0), lu
    else:
        dc = pm / c
        dg = np.where(pos, -pm * m / np.where(pos, a - g, 1.0), 0.0)
        dm = pm * lu
    free = ("c", "g", "m") if free_g else ("c", "m")
    cols = {"c": dc, "g": dg, "m": dm}
    cov = _covariance(np.stack([cols[n] for n in free], axis=1), res)
    se = dict(zip(free, np.sqrt(np.clip(np.diag(cov), 0.0, None))))
    if not free_g:
        se["g"] = 0.0
    observed = lp if residual == "log" else p
    return LawFit(
        law="oden_martins", residual=residual, names=("c", "g", "m"),
        values={"c": c, "g": float(g), "m": float(m)}, stderr={k: float(v) for k, v in se.items()},
        covariance=cov, free=free, residuals=res, r_squared=_r_squared(res, observed), points=a.size,
        predict=lambda x, c=c, g=float(g), m=float(m): oden_martins(x, c, g, m, a0),
        fixed=() if free_g else ("g",),
    )


def fit_exponential(a, p, residual: str = "absolute") -> LawFit:
    """Fit p = c exp(a / lambda) by least squares (absolute or log residuals)."""
    a, p = _check(a, p, residual, 2)
    span = float(a.max() - a.min()) or 1.0
    pos0 = p > 0.0  # the start uses the positive points (absolute residuals allow others)
    lp = np.log(np.where(pos0, p, 1.0))
    b0, b1, _ = _log_linear(a[pos0], lp[pos0])
    if not b1 > 0:
        raise ValueError("the pressure does not grow with the approach: no exponential law")
    x0 = np.array([float(b0), 1.0 / (float(b1) * span)])

    def fun(x):
        lam = x[1] * span
        if residual == "log":
            return x[0] + a / lam - lp
        return np.exp(x[0] + a / lam) - p

    def jac(x):
        lam = x[1] * span
        if residual == "log":
            return np.stack([np.ones_like(a), -a / lam**2 * span], axis=1)
        pm = np.exp(x[0] + a / lam)
        return np.stack([pm, -pm * a / lam**2 * span], axis=1)

    sol = optimize.least_squares(fun, x0, jac=jac, method="trf", xtol=_TOL, ftol=_TOL, gtol=_TOL,
                                 max_nfev=2000, bounds=([-np.inf, 1e-12], [np.inf, np.inf]))
    c, lam = math.exp(sol.x[0]), float(sol.x[1] * span)
    res = fun(sol.x)
    pm = c * np.exp(a / lam)
    if residual == "log":
        cols = [np.full_like(a, 1.0 / c), -a / lam**2]
    else:
        cols = [pm / c, -pm * a / lam**2]
    cov = _covariance(np.stack(cols, axis=1), res)
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    observed = lp if residual == "log" else p
    return LawFit(
        law="exponential", residual=residual, names=("c", "decay_length"),
        values={"c": c, "decay_length": lam}, stderr={"c": float(se[0]), "decay_length": float(se[1])},
        covariance=cov, free=("c", "decay_length"), residuals=res,
        r_squared=_r_squared(res, observed), points=a.size,
        predict=lambda x, c=c, lam=lam: exponential(x, c, lam),
    )


def fit_law(law: str, a, p, residual: str = "absolute", gap: float | None = None) -> LawFit:
    if law == "oden_martins":
        return fit_oden_martins(a, p, gap=gap, residual=residual)
    if law == "exponential":
        return fit_exponential(a, p, residual=residual)
    raise ValueError(f"unknown law {law!r}; known: {', '.join(LAWS)}")


def approach(separation: np.ndarray, pressure: np.ndarray, origin: ApproachOrigin | None
             ) -> tuple[np.ndarray, float, str]:
    """a = h0 - h, h0 from the scene's ``approach_origin`` (see the module docstring).

    origin None: the largest separation; a separation: there; a pressure: where the
    loading curve reaches it, linear in log pressure between the points that bracket it.
    """
    h = np.asarray(separation, dtype=float)
    if origin is None:
        h0 = float(h.max())
        how = "the largest separation of the data"
    elif origin.separation is not None:
        h0 = origin.separation
        how = origin.described
    else:
        q = origin.pressure
        p = np.asarray(pressure, dtype=float)
        ok = p > 0
        order = np.argsort(p[ok])
        lp, hs = np.log(p[ok][order]), h[ok][order]
        if not (lp[0] <= math.log(q) <= lp[-1]):
            raise ValueError(f"laws.approach_origin.pressure {origin.given}: outside the "
                             f"computed pressures [{p[ok].min():.6g}, {p[ok].max():.6g}] Pa")
        h0 = float(np.interp(math.log(q), lp, hs))
        how = origin.described
    return h0 - h, h0, how


def laws_dataset(interface: xr.Dataset, laws: Laws) -> xr.Dataset:
    """Fitted laws of the loading curve, with uncertainties, residuals and the report's fits.

    `laws`: which laws, the residual (absolute: 10.43, or log), the fit window, the
    approach origin, the gap g of 10.42 if fixed, and the report's fits (for
    comparison; never used in the fit).
    """
    interface = loading_branch(interface)
    residual = laws.residual
    which = list(laws.laws)
    h = interface["separation"].values
    p = interface["nominal_pressure"].values
    a, h0, origin_how = approach(h, p, laws.approach_origin)
    lo, hi = laws.pressure_range if laws.pressure_range is not None else (0.0, np.inf)
    window = np.isfinite(p) & (p > 0) & (p >= lo) & (p <= hi)
    if window.sum() <= 3:
        raise ValueError(
            f"laws: {int(window.sum())} points with positive pressure in the window [{lo:.6g}, {hi:.6g}] Pa "
            f"(the data span [{np.nanmin(p):.6g}, {np.nanmax(p):.6g}] Pa); widen the fit window "
            "(laws.pressure_range) or the separations")
    gap = laws.gap

    fits = {law: fit_law(law, a[window], p[window], residual=residual, gap=gap) for law in which}
    report = laws.report.values if laws.report is not None else {}
    nl, npar = len(which), len(PARAMETERS)
    est = np.full((nl, npar), np.nan)
    se = np.full((nl, npar), np.nan)
    fixed = np.zeros((nl, npar), bool)
    rep = np.full((nl, npar), np.nan)
    cov = np.full((nl, npar, npar), np.nan)
    curve = np.full((nl, h.size), np.nan)
    resid = np.full((nl, h.size), np.nan)
    rel = np.full((nl, h.size), np.nan)
    report_curve = np.full((nl, h.size), np.nan)
    for i, law in enumerate(which):
        f = fits[law]
        for j, name in enumerate(PARAMETERS):
            if name in f.values:
                est[i, j] = f.values[name]
                se[i, j] = f.stderr[name]
                fixed[i, j] = name in f.fixed
            if name in report.get(law, {}):
                rep[i, j] = report[law][name]
        idx = [PARAMETERS.index(n) for n in f.free]
        cov[i][np.ix_(idx, idx)] = f.covariance
        curve[i] = f.predict(a)
        resid[i, window] = f.residuals
        with np.errstate(divide="ignore", invalid="ignore"):
            rel[i] = np.where(p > 0, curve[i] / p - 1.0, np.nan)
        if law in report:
            r = report[law]
            if law == "oden_martins" and {"c", "m"} <= set(r):
                report_curve[i] = oden_martins(a, r["c"], r.get("g", 0.0), r["m"])
            elif law == "exponential" and {"c", "decay_length"} <= set(r):
                report_curve[i] = exponential(a, r["c"], r["decay_length"])

    res_units = "1" if residual == "log" else "Pa"
    res_name = "ln p_fit - ln p" if residual == "log" else "p_fit - p (10.43)"
    long_par = "fitted parameter, SI, units per parameter in parameter_units"
    ds = xr.Dataset(
        {
            "approach": ("separation", a, attrs("m", f"approach a = h0 - h, h0 = {origin_how}")),
            "nominal_pressure": ("separation", p, attrs("Pa", "nominal contact pressure (loading; the data fitted)")),
            "in_window": ("separation", window, attrs("1", "point used in the fit (positive, in the pressure range)")),
            "estimate": (("law", "parameter"), est, attrs("see parameter_units", long_par)),
            "standard_error": (("law", "parameter"), se, attrs(
                "see parameter_units", "standard error sqrt(diag(s^2 (J^T J)^-1)); 0 for a fixed parameter")),
            "fixed": (("law", "parameter"), fixed, attrs("1", "parameter held fixed in the fit")),
            "covariance": (("law", "parameter", "parameter_2"), cov, attrs(
                "product of parameter_units", "covariance of the parameters s^2 (J^T J)^-1")),
            "report_value": (("law", "parameter"), rep, attrs(
                "see parameter_units", "the report's fitted parameter in SI, for comparison "
                "(section 10; as printed in attribute report_as_printed)")),
            "pressure_fit": (("law", "separation"), curve, attrs("Pa", "fitted law at the data's approaches")),
            "pressure_report": (("law", "separation"), report_curve, attrs(
                "Pa", "the report's law at the data's approaches (its own approach origin)")),
            "residual": (("law", "separation"), resid, attrs(res_units, f"residual {res_name} in the window")),
            "relative_error": (("law", "separation"), rel, attrs("1", "p_fit / p - 1")),
            "r_squared": ("law", [fits[l_].r_squared for l_ in which], attrs(
                "1", f"coefficient of determination of the fit ({residual} residuals)")),
            "rms_residual": ("law", [math.sqrt(fits[l_].ssr / fits[l_].points) for l_ in which],
                             attrs(res_units, "root mean square residual in the window")),
            "max_relative_error": ("law", [float(np.nanmax(np.abs(rel[i][window]))) for i in range(nl)],
                                   attrs("1", "largest |p_fit / p - 1| in the window")),
            "points": ("law", [fits[l_].points for l_ in which], attrs("1", "points fitted")),
        },
        coords={
            "separation": ("separation", h, dict(interface["separation"].attrs)),
            "law": ("law", which, attrs("1", "analytic law: oden_martins p = c ((a - g)/a0)^m (10.42); "
                                             "exponential p = c exp(a / decay_length)")),
            "parameter": ("parameter", list(PARAMETERS), attrs("1", "parameter of the law")),
            "parameter_2": ("parameter_2", list(PARAMETERS), attrs("1", "parameter of the law")),
            "parameter_units": ("parameter", [PARAMETER_UNITS[n] for n in PARAMETERS],
                                attrs("1", "SI unit of each parameter")),
        },
    )
    ds.attrs.update(
        a0=A0, residual=residual, approach_origin=h0, approach_origin_from=origin_how,
        pressure_window=f"[{lo:.6g}, {hi:.6g}] Pa",
        gap="fitted" if gap is None else f"fixed at {gap:.6g} m",
    )
    if laws.report is not None:
        ds.attrs["report_as_printed"] = laws.report.printed
        ds.attrs["report_source"] = laws.report.source
    return ds
