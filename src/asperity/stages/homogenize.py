"""Stage `homogenize` (workflow/rules/homogenize.smk): the expectation over the population
(2.5, 2.6.2), the interface versus separation with its unloading branch (8.3), and
verification against closed forms (6.1, 7.1).

The functions take the scene's sections as the scene file spells them (validated, with
the defaults of config/schema.yaml) and turn them into `asperity.scene` objects."""

from __future__ import annotations

import logging
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import homogenize, peaks, scene
from asperity.homogenize import validity as validity_checks
from asperity.population.density import (bounds, height_scale, peak_density, population_density,
                                         scene_separations)
from asperity.population.kinds import kind_of_plan
from asperity.references import greenwood_williamson
from asperity.unloading import family_table as unloading_family_table
from asperity.unloading import unloading_asperities
from asperity.units import attrs

log = logging.getLogger("asperity")

Config = Mapping[str, Any]


def _fraction(out: xr.Dataset, name: str, long_name: str) -> xr.Dataset:
    """``<name>_per_unit_area`` over the contact count, as ``<name>_fraction`` (0 without contact)."""
    source = f"{name}_per_unit_area"
    if source not in out:
        return out
    fraction = xr.where(out["contact_count"] > 0, out[source] / out["contact_count"], 0.0)
    out[f"{name}_fraction"] = fraction.assign_attrs(attrs("1", long_name))
    return out.drop_vars([source, f"raw_{name}"])


def _homogenized(asperities: xr.Dataset, density, h: np.ndarray, rect,
                 homogenization: scene.Homogenization, surface_ds: xr.Dataset, **options) -> xr.Dataset:
    """`homogenize.interface_response` of a table, with the shares of contacting asperities;
    `options`: its ``reach`` and ``contact`` (adhesion)."""
    grid_dims = {"height", "curvature", "interference"}
    asperities = asperities[[v for v in asperities.data_vars if set(asperities[v].dims) == grid_dims]]
    out = homogenize.interface_response(
        asperities, density, h, bounds=rect, cells=homogenization.cells,
        rule=homogenization.rule, peak_density=peak_density(surface_ds), **options)
    out = _fraction(out, "extrapolated", "fraction of contacting asperities beyond their FE job's "
                    "largest interference")
    out = _fraction(out, "elastic", "fraction of contacting asperities still elastic (report 7.3, "
                    "Fig. 7.10)")
    return _fraction(out, "small_strain", "fraction of contacting asperities inside small-strain "
                     "theory, all strains below 8 % (report 7.3, Figs. 7.10, 7.14)")


#: separations added between unloading_from and the largest asperity rebound
REBOUND_POINTS = 25


def unloading_from(homogenization: scene.Homogenization, surface_ds: xr.Dataset) -> float:
    """Separation [m] from which the interface unloads: ``unloading_from`` (in the
    separations' unit) or the smallest separation."""
    if homogenization.unloading_from is None:
        return float(scene_separations(homogenization, surface_ds).min())
    return float(homogenization.unloading_from) * homogenization.separation_scale(height_scale(surface_ds))


def interface_dataset(
    asperities: xr.Dataset, surface_ds: xr.Dataset, plan: xr.Dataset,
    population_cfg: Config, homogenization_cfg: Config, units_cfg: Config,
    unloading: xr.Dataset | None = None, *, material_cfg: Config | None = None, effects=(),
    validity_cfg: Config | None = None,
) -> xr.Dataset:
    """Nominal pressure, contact area ratio, stiffness versus separation (2.5).

    With an `unloading` family (`unloading_dataset`), a ``branch``
    dimension: ``loading``, and ``unloading`` from the separation
    `unloading_from` back up (NaN below it), each asperity on the path from
    its own maximum interference (report 8.3).  With the scene's ``validity``
    limits (and its ``material``, `effects`), where the result holds
    (`asperity.homogenize.validity`).
    """
    units = scene.Units.from_section(units_cfg)
    homogenization = scene.Homogenization.from_section(homogenization_cfg, units)
    plastic = None
    if validity_cfg is not None and material_cfg:
        plastic = validity_checks.plasticity_of(scene.Material.from_scene(material_cfg, units),
                                                effects, fe_flag="elastic" in asperities)
    if validity_cfg is not None:
        asperities = validity_checks.with_indicators(asperities, plastic)
    density = population_density(surface_ds, scene.Population.from_section(population_cfg, units))
    threshold = float(plan.attrs["support_threshold"])
    rect = bounds(density, homogenization.height_range, homogenization.curvature_range, threshold)
    rule = homogenization.rule
    if isinstance(density, peaks.SampledDensity) and rule != "peaks":
        log.info("sampled density: rule %s over histogram cells", rule)
    h = scene_separations(homogenization, surface_ds)
    if unloading is not None:
        # the unloading branch is steep (elastic rebound, 8.3): resolve the largest
        # rebound of the asperities present with REBOUND_POINTS more separations
        h0 = unloading_from(homogenization, surface_ds)
        w_max = unloading["maximum_interference"].values
        reach = w_max <= rect[1] - h0
        rebound = (w_max - unloading["residual_interference"].values)[:, reach]
        if rebound.size:
            extra = h0 + np.linspace(0.0, float(np.nanmax(rebound)), REBOUND_POINTS)[1:]
            h = np.unique(np.concatenate([h, extra]))
    out = kind_of_plan(plan).interface(asperities, h, lambda table, **options: _homogenized(
        table, density, h, rect, homogenization, surface_ds, **options))
    if unloading is not None:
        up = h[h >= h0 - 1e-12 * abs(h0)]
        log.info("unloading branch from separation %.6g m over %d separations", h0, up.size)
        heights = asperities["height"].values
        parts = []
        for hk in up:  # one table per separation: each asperity on its own path (8.3)
            back = unloading_asperities(unloading, heights, h0, float(hk))
            parts.append(_homogenized(back, density, np.array([hk]), rect, homogenization, surface_ds))
        unl = xr.concat(parts, dim="separation", data_vars="all")
        unl["contact_count"] = unl["in_contact_per_unit_area"].assign_attrs(
            attrs("1/m^2", "asperities pressing the flat per unit nominal area"))
        p = unl["nominal_pressure"].values
        unl["normal_stiffness"] = ("separation", -np.gradient(p, up) if up.size > 1 else np.full(1, np.nan),
                                   attrs("Pa/m", "normal stiffness -dp/dh of the unloading branch"))
        unl = unl.drop_vars(["in_contact_per_unit_area", "raw_in_contact"]).reindex(separation=h)
        for name in set(out.data_vars) - set(unl.data_vars):  # loading only (fractions, radius)
            unl[name] = xr.full_like(out[name], np.nan)
        out = xr.concat([out, unl[list(out.data_vars)]], dim="branch", data_vars="all",
                        coords="minimal", compat="override")
        out["density_integral"] = out["density_integral"].isel(branch=0, drop=True)
        out = out.assign_coords(branch=("branch", ["loading", "unloading"], attrs(
            "1", "loading, or unloading from the separation unloading_from (report 8.3)")))
        out.attrs["unloading_from"] = h0
    out.attrs["rule"] = rule
    out.attrs["cells"] = str(homogenization.cells)
    for name in ("accuracy", "accuracy_overrides", "fe_jobs", "fe_cpu_time",
                 "max_newton_iterations", "max_step_cuts", "max_dofs",
                 "max_time_steps"):  # what the asperities cost (FE scenes)
        if name in asperities.attrs:
            out.attrs[name] = asperities.attrs[name]
    if validity_cfg is not None:  # where the result holds
        gaussian = isinstance(density, (peaks.JointDensity, peaks.FixedCurvatureDensity))
        measured = gaussian and "skewness" in surface_ds and "kurtosis" in surface_ds
        heights = (float(surface_ds["skewness"]), float(surface_ds["kurtosis"])) if measured else None
        out = validity_checks.assess(out, plastic, validity_checks.peak_statistics(density, rect),
                                     validity_checks.Limits(**validity_cfg), heights)
    return out


def unloading_dataset(asperities: xr.Dataset) -> xr.Dataset:
    """The blended family of unloading paths of every curvature (8.3, unloading.nc)."""
    return unloading_family_table(asperities)


def expectation_dataset(
    surface_ds: xr.Dataset, population_cfg: Config, asperity: Config,
    homogenization_cfg: Config, units_cfg: Config,
) -> xr.Dataset:
    """E(X) for a constant X: the check of report 2.6.2 (eqs. 2.5 to 2.7)."""
    units = scene.Units.from_section(units_cfg)
    population = scene.Population.from_section(population_cfg, units)
    homogenization = scene.Homogenization.from_section(homogenization_cfg, units)
    density = population_density(surface_ds, population)
    threshold = population.support_threshold
    support = density.support(threshold)
    rect = bounds(density, homogenization.height_range, homogenization.curvature_range, threshold)
    value = scene.Asperity.from_section(asperity, units).value
    res = homogenize.expectation(
        value, density, rect, cells=homogenization.cells, rule=homogenization.rule,
        peak_density=peak_density(surface_ds), area=homogenization.area,
    )
    scalar = lambda v, u, ln: ((), float(v), attrs(u, ln))  # noqa: E731
    ds = xr.Dataset(
        {
            "value": scalar(value, "1", "the quantity X (constant)"),
            "integral": scalar(res.integral, "1", "integrated value of X, eq. (2.6)"),
            "normalization": scalar(res.normalization, "1", "integral I of the peak density, (2.7)"),
            "expectation": scalar(res.expectation, "1", "corrected expectation E(X)/I, eq. (2.7)"),
            "macroscopic": scalar(res.macroscopic, "1", "macroscopic value N_p E(X)"),
            "per_unit_area": scalar(res.per_unit_area, "1/m^2", "value of X per unit nominal area"),
            "support": ("bound", np.array(support, float),
                        attrs("m or 1/m", "effective support: height min, max (m); curvature min, max (1/m)")),
            "rectangle": ("bound", np.array(rect, float),
                          attrs("m or 1/m", "integration rectangle: height min, max (m); curvature min, max (1/m)")),
        },
        coords={"bound": ("bound", ["height_min", "height_max", "curvature_min", "curvature_max"],
                          attrs("1", "which bound"))},
    )
    ds.attrs["rule"] = homogenization.rule
    ds.attrs["cells"] = str(homogenization.cells)
    ds.attrs["beta"] = float(getattr(density, "beta", np.nan))
    return ds


def verification_dataset(
    surface_ds: xr.Dataset, interface: xr.Dataset, verification: str,
    material: Config, units_cfg: Config,
) -> xr.Dataset:
    """The homogenized interface beside a closed form, with relative errors."""
    if verification != "greenwood_williamson":
        raise ValueError(f"unknown verification {verification!r}")
    mat = scene.Material.from_scene(material, scene.Units.from_section(units_cfg))
    closed = greenwood_williamson.gw_interface(
        interface["separation"].values,
        radius=1.0 / float(surface_ds["tip_curvature"]),
        sigma_p=float(surface_ds["sigma_peak_height"]),
        peak_density=float(surface_ds["peak_density"]),
        E=mat.youngs_modulus, nu=mat.poisson,
    )
    ds = xr.Dataset(coords={"separation": interface["separation"]})
    pressure = interface["nominal_pressure"]
    relevant = pressure >= 1e-6 * float(pressure.max())
    ds["relevant"] = relevant.assign_attrs(
        attrs("1", "load at least 1e-6 of its maximum (where the 0.5% bound applies)"))
    for name in ("nominal_pressure", "contact_area_ratio", "contact_count"):
        if name not in interface or name not in closed:
            continue
        ds[name] = interface[name]
        ds[f"{name}_closed_form"] = closed[name].assign_attrs(
            attrs(interface[name].attrs["units"], f"{interface[name].attrs['long_name']}, closed form"))
        err = xr.where(closed[name] > 0, np.abs(interface[name] / closed[name] - 1.0), 0.0)
        ds[f"{name}_error"] = err.assign_attrs(
            attrs("1", f"relative error of {interface[name].attrs['long_name']} against the closed form"))
        ds.attrs[f"max_{name}_error"] = float(err.where(relevant).max())
    return ds


def hertz_verification_dataset(single: Config, material: Config, units_cfg: Config) -> xr.Dataset:
    """One FE asperity against Hertz at the scene's presets (report 6.1, Fig. 6.5).

    The paraboloid (Hertz's own idealization) and the true sphere, one run
    per preset: `asperity.studies.hertz.hertz_accuracy_study` without its
    refinement sequence and penalty study.
    """
    from asperity.studies.hertz import hertz_accuracy_study

    units = scene.Units.from_section(units_cfg)
    length = units.length_factor
    mat = scene.Material.from_scene(material, units)
    ds = hertz_accuracy_study(
        radius=single["radius"] * length, youngs_modulus=mat.youngs_modulus, poisson=mat.poisson,
        interferences=tuple(v * length for v in single["interferences"]),
        presets=tuple(single["presets"]), refinement=(), penalty_factors=(),
    )
    for body in ds["body"].values:
        for run in ds["run"].values:
            err = ds["max_force_error"].sel(body=body, run=run)
            if np.isfinite(err):
                ds.attrs[f"max_force_error_{body}_{run}"] = float(err)
                ds.attrs[f"max_radius_error_{body}_{run}"] = float(ds["max_radius_error"].sel(body=body, run=run))
    return ds
