"""Static coefficient of friction of the homogenized interface (report 9.1).

The report's estimate rests on two assumptions (9.1): sliding resistance
between similar metals comes from the formation and shearing of junctions
between contacting asperities, and shearing a junction takes the tangential
force (9.41)::

    T = tau_s A_c

with tau_s the shear strength of the junction, "in the first approximation
independent of normal pressure and equal to the shear strength of the bulk
material".  Per unit nominal area, with A_c the real contact area ratio and
F = p the nominal pressure (9.1, the formula after 9.41)::

    mu_shear = tau_s A_c / F

For a rough surface the report adds "the interlocking of asperities",
estimated "based on relative motion of inclined surfaces" as "the average
slope of the asperities" (9.1, Experimental Surface, refs. [32, 89])::

    mu = mu_shear + mu_interlocking

Which slope?  The report took 0.16 for the steel of section 8, whose
*standard deviation* of slope is 0.160 (8.2.1): it used the rms slope.  The
mean absolute slope E|z'| of a Gaussian surface is smaller by sqrt(2/pi)::

    E|z'| = sqrt(2/pi) sigma_slope  (= 0.1277 for sigma_slope = 0.160)

(z' ~ N(0, sigma_slope^2): the slope of a profile in the sliding direction,
whose variance is m2 = sigma_slope^2, report 2.3).  A scene chooses with
``interlocking``: ``mean_absolute_slope`` (the default),
``rms_slope`` (what the report's 0.16 is), ``none``, or a number.

Sliding direction (``friction.direction``).  The slope met by a body sliding
along the unit vector (cos theta, sin theta), theta from the x axis of the
surface, is the directional derivative z_x cos theta + z_y sin theta, Gaussian
with variance (report 2.3.2, eq. 2.4 for a profile along theta)::

    m(theta) = m20 cos^2 theta + 2 m11 cos theta sin theta + m02 sin^2 theta
             = (m20 + m02)/2 + (m20 - m02)/2 cos 2 theta + m11 sin 2 theta

the quadratic form of the slope covariance M = [[m20, m11], [m11, m02]] (m20 =
var z_x, m11 = cov(z_x, z_y), m02 = var z_y: ``asperity.surface.maps.map_statistics``
or ``asperity.surface.directional.directional_moments``).  Its extremes are the
eigenvalues of M, lambda = (m20 + m02)/2 -+ sqrt(((m20 - m02)/2)^2 + m11^2), at its
eigenvectors: the steepest direction theta_max = atan2(2 m11, m20 - m02) / 2 and the
lay (the direction of the smallest slope, along the grooves) theta_max + pi/2.
m(theta + pi) = m(theta).  The interlocking part along theta is that of the
scene's choice with sigma_slope -> sqrt(m(theta)); without a direction, the
direction average sqrt((m20 + m02)/2) (the mean of m over theta) as before.  An
isotropic profile has m(theta) = m2 = sigma_slope^2 for every theta: its sweep is
flat.

tau_s: the scene's ``junction_shear_strength``, else the bulk
shear strength from the material's yield stress by von Mises,
tau_s = yield_stress / sqrt(3).  Neither given is an error (a Bodner-Partom
material has no yield stress of its own: give tau_s).

The dataset is on dim ``separation`` (that of ``interface.nc``), with the
nominal pressure as a coordinate along it: with adhesion the pressure can be
negative and non-monotonic, which a ``nominal_pressure`` dimension could not
hold.  mu is NaN where the pressure is not positive (no load, or net
adhesive tension: the coefficient is undefined there).  Plot
``ds.mu.plot(x="nominal_pressure", xscale="log")``.  With a direction,
``mu_interlocking``, ``mu`` and ``mu_at_measurement`` gain a dim ``direction``
[rad] and ``sigma_slope_along`` gives sqrt(m(theta)).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from asperity.scene import Friction, Material
from asperity.units import attrs

__all__ = ["mean_absolute_slope", "slope_deviation", "slope_covariance", "slope_along", "lay",
           "junction_shear_strength", "mu_shear", "interlocking", "friction_dataset", "at_pressure",
           "loading_branch"]

SQRT_2_OVER_PI = math.sqrt(2.0 / math.pi)
INTERLOCKING = ("mean_absolute_slope", "rms_slope", "none")



def loading_branch(interface: xr.Dataset) -> xr.Dataset:
    """The loading branch of an interface (``branch`` dim, where the scene unloads):
    ``loading``, or ``approach`` where the scene has adhesion (the flat coming closer)."""
    if "branch" in interface.dims:
        branches = list(interface["branch"].values)
        return interface.sel(branch="loading" if "loading" in branches else "approach")
    return interface


def mean_absolute_slope(sigma_slope):
    """E|z'| = sqrt(2/pi) sigma_slope for a Gaussian slope z' ~ N(0, sigma_slope^2)."""
    return SQRT_2_OVER_PI * np.asarray(sigma_slope, dtype=float)


def slope_deviation(surface: xr.Dataset) -> float:
    """The rms profile slope sigma_slope = sqrt(m2) of the surface (report 2.3).

    The statistic of the estimator that feeds the population when the dataset
    has an ``estimator`` dim; for a map or anisotropic profiles (no isotropic
    sigma_slope) the direction average sqrt((m20 + m02)/2) of the
    directional slope variance m(theta) = m20 cos^2 + 2 m11 cos sin + m02 sin^2.
    """
    if "sigma_slope" in surface and "direction" not in surface["sigma_slope"].dims:
        value = surface["sigma_slope"]
        if "estimator" in value.dims:
            estimator = surface.attrs.get("population_estimator")
            if estimator in value["estimator"].values:
                value = value.sel(estimator=estimator)
            else:
                value = value.isel(estimator=0)
        return float(value)
    if "m20" in surface and "m02" in surface:
        return math.sqrt(0.5 * (float(surface["m20"]) + float(surface["m02"])))
    raise ValueError("the surface has no slope statistic (sigma_slope or m20, m02); "
                     "give friction.interlocking as a number or `none`")


def slope_covariance(surface: xr.Dataset) -> tuple[float, float, float] | None:
    """(m20, m11, m02) of a map or of anisotropic profiles (report 2.3.2); None for an
    isotropic profile (a ``sigma_slope`` without a ``direction`` dim, no m20).

    Raises ValueError if the surface has neither, or if the covariance
    [[m20, m11], [m11, m02]] is not positive semi-definite beyond round-off
    (least-squares moments of noisy profiles can be)."""
    if "m20" in surface and "m02" in surface:
        if "m11" not in surface:
            raise ValueError("the surface has m20 and m02 but no m11: the slope along a direction "
                             "needs all three (report 2.3.2)")
        m20, m11, m02 = (float(surface[name]) for name in ("m20", "m11", "m02"))
        lam_min, lam_max = _eigenvalues(m20, m11, m02)
        if not (lam_min >= -1e-12 * abs(lam_max)):
            raise ValueError(
                f"the slope covariance [[m20, m11], [m11, m02]] = [[{m20:.6g}, {m11:.6g}], [{m11:.6g}, "
                f"{m02:.6g}]] of the surface is not positive semi-definite (eigenvalues {lam_min:.6g}, "
                f"{lam_max:.6g}): no slope along a direction (friction.direction); measure more "
                "directions or drop the key")
        return m20, m11, m02
    if "sigma_slope" in surface and "direction" not in surface["sigma_slope"].dims:
        return None
    raise ValueError("the surface has no slope statistic (sigma_slope or m20, m02); "
                     "give friction.interlocking as a number or `none`")


def _eigenvalues(m20: float, m11: float, m02: float) -> tuple[float, float]:
    """lambda_min, lambda_max of [[m20, m11], [m11, m02]]: mean -+ radius (Mohr's circle)."""
    mean = 0.5 * (m20 + m02)
    radius = math.hypot(0.5 * (m20 - m02), m11)
    return mean - radius, mean + radius


def slope_along(surface: xr.Dataset, theta) -> np.ndarray:
    """rms slope sqrt(m(theta)) along directions theta [rad from the x axis] (2.3.2).

    m(theta) = m20 cos^2 + 2 m11 cos sin + m02 sin^2, evaluated as
    (m20 + m02)/2 + (m20 - m02)/2 cos 2 theta + m11 sin 2 theta (the same form;
    exactly the direction average where m20 = m02, m11 = 0), clipped at zero
    against round-off below the smallest eigenvalue.  An isotropic profile: its
    sigma_slope (`slope_deviation`) for every theta."""
    th = np.asarray(theta, dtype=float)
    cov = slope_covariance(surface)
    if cov is None:
        return np.full(th.shape, slope_deviation(surface))
    m20, m11, m02 = cov
    m = 0.5 * (m20 + m02) + 0.5 * (m20 - m02) * np.cos(2.0 * th) + m11 * np.sin(2.0 * th)
    return np.sqrt(np.maximum(m, 0.0))


def lay(m20: float, m11: float, m02: float) -> dict[str, float]:
    """The principal directions of the slope covariance M = [[m20, m11], [m11, m02]]:

    ``steepest`` = atan2(2 m11, m20 - m02) / 2 (the eigenvector of the larger
    eigenvalue), ``lay`` = steepest + pi/2 (that of the smaller: the direction of
    the smallest slope), both in [0, pi) rad; ``sigma_slope_along_lay`` =
    sqrt(lambda_min), ``sigma_slope_across_lay`` = sqrt(lambda_max).  Where
    m20 = m02 and m11 = 0 every direction is principal (isotropic slopes): lay pi/2."""
    lam_min, lam_max = _eigenvalues(m20, m11, m02)
    steepest = (0.5 * math.atan2(2.0 * m11, m20 - m02)) % math.pi
    return {"lay": (steepest + 0.5 * math.pi) % math.pi, "steepest": steepest,
            "sigma_slope_along_lay": math.sqrt(max(lam_min, 0.0)),
            "sigma_slope_across_lay": math.sqrt(max(lam_max, 0.0))}


def interlocking(surface: xr.Dataset, choice: Any, direction=None) -> tuple[float | np.ndarray, str]:
    """mu_interlocking and how it was obtained (report 9.1, refs. [32, 89]).

    direction None: with the direction-free slope `slope_deviation` (a float).
    direction an array of angles [rad from the x axis]: with the slope along each,
    `slope_along` (an array of direction's shape; constant for a number or none)."""
    shape = None if direction is None else np.shape(direction)
    if isinstance(choice, (int, float)) and not isinstance(choice, bool):
        if choice < 0:
            raise ValueError(f"friction.interlocking {choice} is negative")
        return (float(choice) if shape is None else np.full(shape, float(choice))), "given in the scene"
    if choice == "none":
        return (0.0 if shape is None else np.zeros(shape)), "neglected (smooth surface)"
    if choice not in INTERLOCKING:
        raise ValueError(f"friction.interlocking {choice!r}: one of {', '.join(INTERLOCKING)} or a number")
    if shape is None:
        if choice == "rms_slope":
            return slope_deviation(surface), "rms slope sigma_slope (what the report's 0.16 is, 9.1)"
        return (float(mean_absolute_slope(slope_deviation(surface))),
                "mean absolute slope sqrt(2/pi) sigma_slope of a Gaussian surface")
    slope = slope_along(surface, direction)
    if choice == "rms_slope":
        return slope, "rms slope sqrt(m(theta)) along the sliding direction (2.3.2; the report's 0.16, 9.1)"
    return (mean_absolute_slope(slope),
            "mean absolute slope sqrt(2/pi) sqrt(m(theta)) along the sliding direction (Gaussian surface)")


def junction_shear_strength(friction: Friction, material: Material | None) -> tuple[float, str]:
    """tau_s [Pa] and its origin: the scene's value, or yield_stress / sqrt(3)."""
    if friction.junction_shear_strength is not None:
        return friction.junction_shear_strength, "given in the scene"
    y = material.yield_stress if material is not None else None
    if y is not None and math.isfinite(float(y)):
        return float(y) / math.sqrt(3.0), "bulk shear strength yield_stress / sqrt(3) (von Mises)"
    raise ValueError(
        "friction: no junction shear strength tau_s (9.41): give friction.junction_shear_strength "
        "(in the scene's pressure unit) or material.yield_stress (tau_s = yield_stress / sqrt(3))")


def mu_shear(contact_area_ratio, nominal_pressure, tau_s: float) -> np.ndarray:
    """tau_s A_c / F per unit nominal area (9.41); NaN where F <= 0."""
    a = np.asarray(contact_area_ratio, dtype=float)
    p = np.asarray(nominal_pressure, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(p > 0.0, tau_s * a / np.where(p > 0.0, p, 1.0), np.nan)


def at_pressure(pressure: np.ndarray, values: np.ndarray, target) -> np.ndarray:
    """`values` at nominal pressure(s) `target`, linear in log pressure over the
    positive-pressure points; NaN outside their range."""
    p = np.asarray(pressure, dtype=float)
    v = np.asarray(values, dtype=float)
    ok = (p > 0.0) & np.isfinite(v)
    target = np.atleast_1d(np.asarray(target, dtype=float))
    if ok.sum() < 2:
        return np.full(target.shape, np.nan)
    order = np.argsort(p[ok])
    lp, lv = np.log(p[ok][order]), v[ok][order]
    with np.errstate(divide="ignore", invalid="ignore"):
        lt = np.log(target)
    out = np.interp(lt, lp, lv)
    return np.where(np.isfinite(lt) & (lt >= lp[0]) & (lt <= lp[-1]), out, np.nan)


def friction_dataset(interface: xr.Dataset, surface: xr.Dataset, friction: Friction,
                     material: Material | None) -> xr.Dataset:
    """mu_shear, mu_interlocking and mu of the loading branch (report 9.1, Figs. 9.1-9.3).

    Parameters
    ----------
    interface : interface.nc (dim ``separation``; ``branch`` selected to loading)
    surface : surface.nc (the slope statistic)
    friction : the scene's ``friction`` section: junction shear strength, interlocking,
        measured coefficients, the report's own estimate (for comparison only)
    material : the scene's material (its ``yield_stress`` if tau_s is not given), or None
    """
    interface = loading_branch(interface)
    tau_s, tau_origin = junction_shear_strength(friction, material)
    directed = friction.direction is not None
    theta = np.asarray(friction.direction, dtype=float) if directed else None
    mu_i, mu_i_origin = interlocking(surface, friction.interlocking, theta)
    p = interface["nominal_pressure"].values
    shear = mu_shear(interface["contact_area_ratio"].values, p, tau_s)
    sep = interface["separation"]
    ds = xr.Dataset(
        coords={
            "separation": ("separation", sep.values, dict(sep.attrs)),
            "nominal_pressure": ("separation", p, attrs("Pa", "nominal contact pressure (loading)")),
        })
    if directed:
        ds = ds.assign_coords(direction=("direction", theta, attrs(
            "rad", "sliding direction, angle from the x axis of the surface")))
    ds["mu_shear"] = ("separation", shear, attrs(
        "1", "coefficient of friction from junction shearing tau_s A_c / F (9.41)"))
    if directed:
        ds["mu_interlocking"] = ("direction", mu_i, attrs(
            "1", f"interlocking part of friction along the sliding direction: {mu_i_origin}"))
        ds["mu"] = (("separation", "direction"), shear[:, None] + mu_i[None, :], attrs(
            "1", "coefficient of friction along the sliding direction, shearing plus interlocking"))
    else:
        ds["mu_interlocking"] = ((), mu_i, attrs("1", f"interlocking part of friction: {mu_i_origin}"))
        ds["mu"] = ("separation", shear + mu_i, attrs("1", "coefficient of friction, shearing plus interlocking"))
    ds["contact_area_ratio"] = ("separation", interface["contact_area_ratio"].values,
                                attrs("1", "real contact area per unit nominal area (loading)"))
    ds["junction_shear_strength"] = ((), tau_s, attrs("Pa", f"junction shear strength tau_s: {tau_origin}"))
    try:
        s = slope_deviation(surface)
    except ValueError:
        s = math.nan
    ds["sigma_slope"] = ((), s, attrs("1", "rms slope of the surface (standard deviation of profile slope)"))
    ds["mean_absolute_slope"] = ((), float(mean_absolute_slope(s)),
                                 attrs("1", "mean absolute slope sqrt(2/pi) sigma_slope (Gaussian surface)"))
    if directed:
        ds = _with_direction(ds, surface, theta, friction.interlocking, mu_i_origin)

    measured = friction.measured
    if measured:
        labels = [m.label for m in measured]
        get = lambda key: np.array(  # noqa: E731
            [np.nan if getattr(m, key) is None else getattr(m, key) for m in measured])
        mp = get("nominal_pressure")
        ds = ds.assign_coords(measurement=("measurement", labels, attrs("1", "friction test")))
        ds["measured_mu"] = ("measurement", get("value"), attrs("1", "measured static coefficient of friction"))
        ds["measured_mu_uncertainty"] = ("measurement", get("uncertainty"),
                                         attrs("1", "estimated error of the measured coefficient"))
        ds["measured_nominal_pressure"] = ("measurement", mp, attrs("Pa", "nominal pressure of the test"))
        ds["mu_shear_at_measurement"] = ("measurement", at_pressure(p, shear, mp), attrs(
            "1", "computed mu_shear at the test's nominal pressure (NaN outside the computed range)"))
        if directed:
            ds["mu_at_measurement"] = (("measurement", "direction"),
                                       at_pressure(p, shear, mp)[:, None] + mu_i[None, :], attrs(
                "1", "computed mu along the sliding direction at the test's nominal pressure "
                     "(NaN outside the computed range)"))
        else:
            ds["mu_at_measurement"] = ("measurement", at_pressure(p, shear + mu_i, mp), attrs(
                "1", "computed mu at the test's nominal pressure (NaN outside the computed range)"))
        ds["measured_source"] = ("measurement", [m.source for m in measured],
                                 attrs("1", "where the measurement is reported"))
    report = friction.report
    if report is not None:
        names = {"shear": "mu_shear", "interlocking": "mu_interlocking", "total": "mu"}
        for key, name in names.items():
            if getattr(report, key) is not None:
                ds[f"report_{name}"] = ((), getattr(report, key), attrs(
                    "1", f"the report's {name} (for comparison, not computed here)"))
        if report.nominal_pressure is not None:
            ds["report_nominal_pressure"] = ((), report.nominal_pressure,
                                             attrs("Pa", "nominal pressure of the report's estimate"))
        ds.attrs["report_source"] = report.source
    if "valid" in interface:  # where the interface holds (asperity.homogenize.validity)
        from asperity.homogenize.validity import warn_invalid

        for name in ("valid", "validity"):
            ds[name] = ("separation", interface[name].values, dict(interface[name].attrs))
        warning = warn_invalid(ds, "friction")
        if warning:
            ds.attrs["validity_warning"] = warning
    positive = p > 0
    if positive.any():
        ds.attrs["pressure_range"] = f"[{p[positive].min():.6g}, {p[positive].max():.6g}] Pa"
    ds.attrs["junction_shear_strength_origin"] = tau_origin
    ds.attrs["interlocking"] = mu_i_origin
    return ds


def _with_direction(ds: xr.Dataset, surface: xr.Dataset, theta: np.ndarray, choice: Any,
                    origin: str) -> xr.Dataset:
    """``sigma_slope_along`` on dim direction and the attributes of the lay: where it is
    (eigenvectors of the slope covariance, `lay`), the extreme slopes, and whether mu
    depends on the direction at all (`origin`: how mu_interlocking was obtained)."""
    try:
        cov = slope_covariance(surface)
    except ValueError as err:  # no usable slope statistic: the interlocking was given or neglected
        known, cov, why = False, None, str(err).split(":")[0]
    else:
        known = True
    slope = slope_along(surface, theta) if known else np.full(theta.shape, np.nan)
    what = ("rms slope along the sliding direction sqrt(m20 cos^2 + 2 m11 cos sin + m02 sin^2) (2.3.2)"
            if cov is not None else "rms slope along the sliding direction (isotropic: sigma_slope in "
                                    "every direction; NaN: no slope statistic)")
    ds["sigma_slope_along"] = ("direction", slope, attrs("1", what))
    mu_i = ds["mu_interlocking"].values
    ds.attrs["mu_interlocking_range"] = f"[{mu_i.min():.6g}, {mu_i.max():.6g}] over the directions given"
    slope_based = isinstance(choice, str) and choice != "none"
    if not known:
        ds.attrs["lay"] = f"unknown: {why}"
        ds.attrs["direction_dependence"] = f"none: interlocking {origin}"
        return ds
    if cov is None:
        ds.attrs["lay"] = "none: an isotropic profile has one slope statistic"
        ds.attrs["direction_dependence"] = ("none: the surface is isotropic (one profile), m(theta) = m2 = "
                                            "sigma_slope^2 in every direction; mu is flat in direction")
        return ds
    principal = lay(*cov)
    deg = math.degrees
    for key in ("lay", "steepest"):
        ds.attrs[f"{key}_direction"] = principal[key]
    for key in ("sigma_slope_along_lay", "sigma_slope_across_lay"):
        ds.attrs[key] = principal[key]
    ds.attrs["lay"] = (
        f"lay (smallest rms slope) at {principal['lay']:.6g} rad ({deg(principal['lay']):.4g} deg) from x, "
        f"rms slope {principal['sigma_slope_along_lay']:.6g}; largest across it at "
        f"{principal['steepest']:.6g} rad ({deg(principal['steepest']):.4g} deg), "
        f"{principal['sigma_slope_across_lay']:.6g} (eigenvectors and sqrt of the eigenvalues of "
        "[[m20, m11], [m11, m02]]; attributes lay_direction, steepest_direction in rad)")
    ds.attrs["direction_dependence"] = (
        "mu_interlocking follows sqrt(m(theta)): mu depends on the direction, with period pi"
        if slope_based else f"none: interlocking {origin}")
    return ds
