"""The stages of the pipeline as functions of data (DESIGN.md, task graph).

Each function takes the datasets of the previous stage and the scene's
configuration subtrees (as a scene file spells them, in the scene's units)
and returns the dataset of its stage, in SI.  They know nothing of files or
of the workflow manager: the workflow scripts read, call one of these, and
write through ``asperity.io``.
"""

from __future__ import annotations

import logging
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import homogenize, peaks, surface, units
from asperity.population import adhesive as adhesive_interface
from asperity.references import greenwood_williamson
from asperity.references import hertz
from asperity.scene import materials
from asperity.population import models
from asperity.population.plan import interference_grid, make_plan, sample_grid
from asperity.unloading import family_table as unloading_family_table
from asperity.unloading import unloading_asperities

log = logging.getLogger("asperity")

Config = Mapping[str, Any]


def _attrs(units_: str, long_name: str) -> dict[str, str]:
    return {"units": units_, "long_name": long_name}


def length_factor(units_cfg: Config) -> float:
    return units.length_scale(units_cfg["length"])


def material_si(material: Config, units_cfg: Config) -> dict[str, Any]:
    """The scene's material in SI (`asperity.scene.materials.material_si`)."""
    return materials.material_si(material, units_cfg)


def velocity_si(asperity: Config, units_cfg: Config) -> float | None:
    """The flat's loading velocity [m/s] (report 8.2.2), None if the scene gives none."""
    v = asperity.get("velocity")
    return None if v is None else float(v) * length_factor(units_cfg)


# ---------------------------------------------------------------- surface


def synthetic_profile(generate: Config) -> tuple[np.ndarray, np.ndarray]:
    """Positions and heights of a synthetic profile of report 2.6.1, scene units."""
    x = np.arange(0.0, generate["length"] + 0.5 * generate["spacing"], generate["spacing"])
    if generate["kind"] == "cosine":
        return x, generate["amplitude"] * np.cos(generate["wavenumber"] * x)
    c, k, e = surface.quasirandom_series(n=generate["components"], seed=generate["seed"])
    return x, surface.evaluate_series(x, c, k, e)


def _series_reference(generate: Config, length: float) -> dict[str, float] | None:
    """Exact statistics of a synthetic profile (eq. 2.4 for a series), SI."""
    if generate["kind"] == "cosine":
        c, k = generate["amplitude"], generate["wavenumber"]
        amplitudes, wavenumbers = np.array([c]), np.array([k])
    else:
        amplitudes, wavenumbers, _ = surface.quasirandom_series(
            n=generate["components"], seed=generate["seed"]
        )
    exact = surface.series_statistics(amplitudes, wavenumbers)
    return {
        "sigma": exact["sigma"] * length,
        "sigma_slope": exact["sigma_slope"],
        "sigma_curvature": exact["sigma_curvature"] / length,
        "beta": exact["beta"],
    }


def surface_from_profile(z: np.ndarray, dx: float, surface_cfg: Config) -> xr.Dataset:
    """Profile statistics by sampling, counting and spectrum (2.3.1), SI input.

    For a synthetic profile the exact statistics are added as method
    ``exact`` (cosine: closed form; series: eq. 2.4).
    """
    ds = surface.profile_statistics(z, dx)
    generate = surface_cfg["profile"].get("generate")
    if generate:
        # the synthetic profile was written in scene units and read back in SI;
        # its exact statistics scale with the same factor
        length = dx / generate["spacing"]
        exact = _series_reference(generate, length)
        extra = xr.full_like(ds.isel(method=0), np.nan).expand_dims(method=["exact"])
        for name, value in exact.items():
            extra[name] = extra[name].copy(data=np.array([value]))
        extra["m0"] = extra["sigma"] ** 2
        extra["m2"] = extra["sigma_slope"] ** 2
        extra["m4"] = extra["sigma_curvature"] ** 2
        extra["peak_density"] = extra["m4"] / (6 * np.pi * np.sqrt(3) * extra["m2"])
        merged = xr.concat([ds, extra], dim="method", data_vars="all", coords="minimal")
        for name in ds.variables:
            merged[name].attrs = ds[name].attrs
        ds = merged
    ds.attrs["population_method"] = surface_cfg.get("method", "sampling")
    return ds


def surface_from_map(z: np.ndarray, dx: float, dy: float, surface_cfg: Config) -> xr.Dataset:
    """Statistics and peaks of a 2-D height map (2.4.3), SI input."""
    ds = xr.merge([surface.map_statistics(z, dx, dy), surface.map_peaks(z, dx, dy)])
    ds.attrs["population_method"] = "map"
    return ds


def surface_from_statistics(surface_cfg: Config, units_cfg: Config) -> xr.Dataset:
    """Surface statistics given in the scene (report 2.6.2), as method ``given``."""
    length = length_factor(units_cfg)
    if "gaussian_heights" in surface_cfg:
        gh = surface_cfg["gaussian_heights"]
        ds = xr.Dataset(
            {
                "sigma_peak_height": ((), gh["sigma_peak_height"] * length,
                                      _attrs("m", "standard deviation of peak heights")),
                "tip_curvature": ((), 1.0 / (gh["radius"] * length),
                                  _attrs("1/m", "curvature of every asperity tip (1/R)")),
                "peak_density": ((), gh["peak_density"] / length**2,
                                 _attrs("1/m^2", "peaks per unit nominal area")),
            }
        )
        ds.attrs["population_method"] = "gaussian_heights"
        return ds
    st = surface_cfg["statistics"]
    values = {
        "mean_height": (st.get("mean_height", 0.0) * length, "m", "mean height"),
        "sigma": (st["sigma"] * length, "m", "standard deviation of height"),
        "sigma_slope": (st["sigma_slope"], "1", "standard deviation of slope"),
        "sigma_curvature": (st["sigma_curvature"] / length, "1/m", "standard deviation of curvature"),
        "peak_density": (st["peak_density"] / length**2, "1/m^2", "peaks per unit nominal area"),
    }
    ds = xr.Dataset(
        {name: ("method", [v], _attrs(u, ln)) for name, (v, u, ln) in values.items()},
        coords={"method": ("method", ["given"], _attrs("1", "how the statistics were obtained"))},
    )
    ds["m0"] = (ds["sigma"] ** 2).assign_attrs(_attrs("m^2", "spectral moment m0"))
    ds["m2"] = (ds["sigma_slope"] ** 2).assign_attrs(_attrs("1", "spectral moment m2"))
    ds["m4"] = (ds["sigma_curvature"] ** 2).assign_attrs(_attrs("1/m^2", "spectral moment m4"))
    ds["beta"] = (np.sqrt(1.5) * ds["m2"] / np.sqrt(ds["m0"] * ds["m4"])).assign_attrs(
        _attrs("1", "wavelength spectrum parameter beta (2.4.1)")
    )
    ds.attrs["population_method"] = "given"
    return ds


def series_convergence(generate: Config, units_cfg: Config) -> xr.Dataset:
    """Sampled statistics of a synthetic profile versus spacing, against exact (2.6.1).

    The report notes that the differences shrink with the spacing "but they
    do not vanish"; this dataset shows how fast they shrink here.
    """
    length = length_factor(units_cfg)
    exact = _series_reference(generate, length)
    names = ["sigma", "sigma_slope", "sigma_curvature", "beta"]
    spacings = np.asarray(generate["convergence_spacings"], float)
    rows = []
    for spacing in spacings:  # a handful of spacings; each call is vectorized
        x, z = synthetic_profile({**generate, "spacing": spacing})
        stats = surface.profile_statistics(z * length, spacing * length)
        rows.append(stats[names].sel({"method": ["sampling", "counting", "spectral"]}))
    ds = xr.concat(rows, dim="spacing")
    ds = ds.assign_coords(
        spacing=("spacing", spacings * length, _attrs("m", "sampling interval of the profile"))
    )
    for name in names:
        ds[name].attrs = rows[0][name].attrs
        err = np.abs(ds[name] / exact[name] - 1.0)
        ds[f"{name}_error"] = err.assign_attrs(
            _attrs("1", f"relative error of {rows[0][name].attrs['long_name']} against the series")
        )
        ds[f"{name}_exact"] = xr.DataArray(exact[name], attrs={
            "units": rows[0][name].attrs["units"],
            "long_name": f"{rows[0][name].attrs['long_name']} of the series (eq. 2.4)"})
    return ds


# ------------------------------------------------------------- population


def default_density(surface_ds: xr.Dataset) -> str:
    method = surface_ds.attrs.get("population_method")
    return {"gaussian_heights": "fixed_curvature", "map": "sampled"}.get(method, "nayak")


def population_density(surface_ds: xr.Dataset, population: Config):
    """The peak density of a scene: Nayak/Francis, fixed curvature, or sampled."""
    kind = population.get("density") or default_density(surface_ds)
    method = surface_ds.attrs.get("population_method")
    if kind == "fixed_curvature":
        if "sigma_peak_height" not in surface_ds:
            raise ValueError("population.density fixed_curvature needs surface.gaussian_heights")
        return peaks.FixedCurvatureDensity(
            sigma_p=float(surface_ds["sigma_peak_height"]),
            curvature=float(surface_ds["tip_curvature"]),
        )
    if kind == "sampled":
        if "peak" not in surface_ds.dims:
            raise ValueError("population.density sampled needs a 2-D map (surface.map)")
        bins = tuple(population.get("histogram_bins", (20, 20)))
        return peaks.SampledDensity.from_peaks(
            surface_ds["height"].values, surface_ds["curvature"].values, bins=bins
        )
    stats = surface_ds.sel({"method": method}) if "method" in surface_ds.dims else surface_ds
    return peaks.JointDensity(
        sigma=float(stats["sigma"]),
        sigma_slope=float(stats["sigma_slope"]),
        sigma_curvature=float(stats["sigma_curvature"]),
    )


def peak_density(surface_ds: xr.Dataset) -> float:
    """Peaks per unit area (1/m^2) from the surface dataset."""
    return _population_stat(surface_ds, "peak_density")


def _population_stat(surface_ds: xr.Dataset, name: str) -> float:
    """A statistic of the method that feeds the population."""
    value = surface_ds[name]
    if "method" in value.dims:
        value = value.sel({"method": surface_ds.attrs["population_method"]})
    return float(value)


def height_scale(surface_ds: xr.Dataset) -> float:
    """The standard deviation that `sigma` units of separation refer to."""
    if "sigma_peak_height" in surface_ds:
        return float(surface_ds["sigma_peak_height"])
    return _population_stat(surface_ds, "sigma")


def bounds(density, cfg: Config, units_cfg: Config, threshold: float) -> tuple[float, float, float, float]:
    """Integration/sampling rectangle: the effective support, or the scene's ranges."""
    length = length_factor(units_cfg)
    z0, z1, k0, k1 = density.support(threshold)
    if "height_range" in cfg:
        z0, z1 = (v * length for v in cfg["height_range"])
    if "curvature_range" in cfg:
        k0, k1 = (v / length for v in cfg["curvature_range"])
    return float(z0), float(z1), float(k0), float(k1)


def plan_dataset(
    surface_ds: xr.Dataset,
    population: Config,
    asperity: Config,
    material: Config,
    effects: list[str],
    units_cfg: Config,
    accuracy: str,
    adhesion: Config | None = None,
) -> xr.Dataset:
    """The samples a scene needs (DESIGN.md: the plan); `adhesion`: the scene's section,
    used with the effect ``adhesion`` (`asperity.population.adhesive`)."""
    density = population_density(surface_ds, population)
    threshold = population.get("support_threshold", 1e-4)
    z0, z1, k0, k1 = bounds(density, population, units_cfg, threshold)
    counts = population.get("samples", {})
    if models.is_coupled(asperity):  # hills exist above the mean plane only (2.5.1)
        heights = sample_grid(0.0, z1, counts.get("height", 11), positive=True)
    else:
        heights = sample_grid(z0, z1, counts.get("height", 11))
    curvatures = (
        np.array([density.curvature])
        if isinstance(density, peaks.FixedCurvatureDensity)
        else sample_grid(k0, k1, counts.get("curvature", 21), positive=True)
    )
    grid = interference_grid(z1 - z0, counts.get("interference", 241))
    adhesion_si = adhesive_interface.law_si(adhesion) if "adhesion" in effects else None
    if adhesion_si is not None:  # the attraction acts before contact: gap levels too
        if asperity["model"] != "fe":
            raise ValueError("effect `adhesion` needs a finite element asperity (asperity.model: fe)")
        grid = adhesive_interface.interference_grid(z1 - z0, counts.get("interference", 241),
                                                    adhesion_si)
    model = asperity["model"]
    analytic = models.is_analytic(asperity)
    mat = material_si(material, units_cfg) if material else {}
    velocity = velocity_si(asperity, units_cfg) if "velocity" in asperity else None
    width_to_height = None
    if asperity.get("geometry") == "cosine" and "width_to_height" not in asperity:
        width_to_height = models.representative_width_to_height(_population_stat(surface_ds, "sigma_slope"))
    shift_invariant = models.is_shift_invariant(asperity)
    scaled = models.self_similar(asperity, mat, effects) and curvatures.size > 1
    reference = None
    if scaled:
        given = asperity.get("reference_curvature")
        reference = given / length_factor(units_cfg) if given else float(np.sqrt(curvatures[0] * curvatures[-1]))
    levels_of, check_of = None, None
    if "unloading" in effects:
        if analytic or "plasticity" not in effects:
            raise ValueError("effect `unloading` needs an FE asperity with effect `plasticity` "
                             "(an elastic asperity unloads along its loading curve)")
        if not shift_invariant:
            raise ValueError("effect `unloading` needs an asperity whose response does not depend "
                             "on its peak height (mapping: representative, sphere or paraboloid)")

        def family(h, k):
            geometry = models.fe_geometry(asperity, k, width_to_height, h)
            _, top = models.job_range(geometry, asperity, grid, k, curvatures if scaled else None)
            return models.unloading_levels(top, asperity)

        def levels_of(h, k):
            levels, check = family(h, k)
            return np.sort(np.append(levels, check)) if np.isfinite(check) else levels

        def check_of(h, k):
            return family(h, k)[1]
    family_of = curvatures if scaled else None

    def job_spec(h, k, level):
        if analytic:  # no job: the key names the closed form's inputs
            return {"model": model, "material": mat, "curvature": k, "interference": grid}
        return models.job_spec(asperity, mat, effects, accuracy, curvature=k, height=h,
                               level=level, grid=grid, family=family_of,
                               width_to_height=width_to_height, velocity=velocity,
                               adhesion=adhesion_si)

    plan = make_plan(heights, curvatures, grid, model=model, job_spec=job_spec,
                     shift_invariant=shift_invariant, analytic=analytic,
                     unloading_levels=levels_of, reference_curvature=reference)
    if scaled and not materials.rate_independent(mat, effects):
        plan.attrs["scaling_assumption"] = (
            "self-similar scaling of a rate-dependent body (asperity.scaling: self_similar): "
            "rate effects of the scaled strain rates ignored, as the report does in 8.2.2")
    plan.attrs["shift_invariant"] = int(shift_invariant)
    if check_of is not None:
        check = np.array([check_of(h, k) for h, k in
                          zip(plan["sample_height"].values, plan["job_curvature"].values)])
        plan["left_out"] = ("sample", plan["unloading_level"].values == check, _attrs(
            "1", "unloading path computed to check the blend, left out of it (report 8.3, gamma_0)"))
    if width_to_height is not None:
        plan.attrs["width_to_height"] = width_to_height
    plan.attrs["support"] = f"height [{z0:.6g}, {z1:.6g}] m, curvature [{k0:.6g}, {k1:.6g}] 1/m"
    plan.attrs["support_threshold"] = threshold
    if adhesion_si is not None:
        plan.attrs["adhesion"] = (f"Lennard-Jones dgamma = {adhesion_si['dgamma']:g} J/m^2, "
                                  f"d = {adhesion_si['d']:g} m, cut-off {adhesion_si['cutoff']:g} d")
        plan.attrs["reach"] = adhesive_interface.reach(adhesion_si)
    log.info("plan: %d samples, %s", plan.sizes["sample"], plan.attrs["derived"])
    return plan


# ------------------------------------------------------------- asperities


def asperities_dataset(
    plan: xr.Dataset, asperity: Config, material: Config, units_cfg: Config,
    samples: Mapping[str, xr.Dataset] | None = None,
) -> xr.Dataset:
    """Responses of all samples on (height, curvature, interference)."""
    model = asperity["model"]
    if model == "hertz":
        mat = material_si(material, units_cfg)
        return hertz.hertz_asperities(
            plan["height"].values, plan["curvature"].values, plan["interference"].values,
            mat["youngs_modulus"], mat["poisson"],
        )
    if model == "fe" and "adhesion" in plan.attrs:  # both branches (asperity.population.adhesive)
        return adhesive_interface.gather(plan, samples or {})
    if model == "fe":
        return models.gather(plan, samples or {})
    raise ValueError(f"asperity.model {model!r} has no response on a sample grid")


# --------------------------------------------------------- homogenization


def separations(homogenization: Config, surface_ds: xr.Dataset, units_cfg: Config) -> np.ndarray:
    sep = homogenization.get("separations", {"start": 0.0, "stop": 3.0, "count": 31})
    scale = height_scale(surface_ds) if sep.get("unit", "sigma") == "sigma" else length_factor(units_cfg)
    return np.linspace(sep["start"], sep["stop"], sep["count"]) * scale


def _fraction(out: xr.Dataset, name: str, long_name: str) -> xr.Dataset:
    """``<name>_per_unit_area`` over the contact count, as ``<name>_fraction`` (0 without contact)."""
    source = f"{name}_per_unit_area"
    if source not in out:
        return out
    fraction = xr.where(out["contact_count"] > 0, out[source] / out["contact_count"], 0.0)
    out[f"{name}_fraction"] = fraction.assign_attrs(_attrs("1", long_name))
    return out.drop_vars([source, f"raw_{name}"])


def _homogenized(asperities: xr.Dataset, density, h: np.ndarray, rect, homogenization: Config,
                 surface_ds: xr.Dataset, **options) -> xr.Dataset:
    """`homogenize.interface_response` of a table, with the shares of contacting asperities;
    `options`: its ``reach`` and ``contact`` (adhesion)."""
    rule = homogenization.get("rule", "gauss")
    grid_dims = {"height", "curvature", "interference"}
    asperities = asperities[[v for v in asperities.data_vars if set(asperities[v].dims) == grid_dims]]
    out = homogenize.interface_response(
        asperities, density, h, bounds=rect, cells=tuple(homogenization.get("cells", (40, 40))),
        rule=rule, peak_density=peak_density(surface_ds), **options)
    out = _fraction(out, "extrapolated", "fraction of contacting asperities beyond their FE job's "
                    "largest interference")
    out = _fraction(out, "elastic", "fraction of contacting asperities still elastic (report 7.3, "
                    "Fig. 7.10)")
    return _fraction(out, "small_strain", "fraction of contacting asperities inside small-strain "
                     "theory, all strains below 8 % (report 7.3, Figs. 7.10, 7.14)")


#: separations added between unloading_from and the largest asperity rebound
REBOUND_POINTS = 25


def unloading_from(homogenization: Config, surface_ds: xr.Dataset, units_cfg: Config) -> float:
    """Separation [m] from which the interface unloads: ``unloading_from`` (in the
    separations' unit) or the smallest separation."""
    h = separations(homogenization, surface_ds, units_cfg)
    if "unloading_from" not in homogenization:
        return float(h.min())
    sep = homogenization.get("separations", {})
    scale = height_scale(surface_ds) if sep.get("unit", "sigma") == "sigma" else length_factor(units_cfg)
    return float(homogenization["unloading_from"]) * scale


def interface_dataset(
    asperities: xr.Dataset, surface_ds: xr.Dataset, plan: xr.Dataset,
    population: Config, homogenization: Config, units_cfg: Config,
    unloading: xr.Dataset | None = None,
) -> xr.Dataset:
    """Nominal pressure, contact area ratio, stiffness versus separation (2.5).

    With an `unloading` family (`unloading_dataset`), a ``branch``
    dimension: ``loading``, and ``unloading`` from the separation
    `unloading_from` back up (NaN below it), each asperity on the path from
    its own maximum interference (report 8.3).
    """
    density = population_density(surface_ds, population)
    threshold = float(plan.attrs.get("support_threshold", 1e-4))
    rect = bounds(density, homogenization, units_cfg, threshold)
    rule = homogenization.get("rule", "gauss")
    if isinstance(density, peaks.SampledDensity) and rule != "peaks":
        log.info("sampled density: rule %s over histogram cells", rule)
    h = separations(homogenization, surface_ds, units_cfg)
    if unloading is not None:
        # the unloading branch is steep (elastic rebound, 8.3): resolve the largest
        # rebound of the asperities present with REBOUND_POINTS more separations
        h0 = unloading_from(homogenization, surface_ds, units_cfg)
        w_max = unloading["maximum_interference"].values
        reach = w_max <= rect[1] - h0
        rebound = (w_max - unloading["residual_interference"].values)[:, reach]
        if rebound.size:
            extra = h0 + np.linspace(0.0, float(np.nanmax(rebound)), REBOUND_POINTS)[1:]
            h = np.unique(np.concatenate([h, extra]))
    if "branch" in asperities.dims:  # adhesion: approach and retraction (asperity.population.adhesive)
        out = adhesive_interface.by_branch(asperities, h, lambda table, **options: _homogenized(
            table, density, h, rect, homogenization, surface_ds, **options))
    else:
        out = _homogenized(asperities, density, h, rect, homogenization, surface_ds)
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
            _attrs("1/m^2", "asperities pressing the flat per unit nominal area"))
        p = unl["nominal_pressure"].values
        unl["normal_stiffness"] = ("separation", -np.gradient(p, up) if up.size > 1 else np.full(1, np.nan),
                                   _attrs("Pa/m", "normal stiffness -dp/dh of the unloading branch"))
        unl = unl.drop_vars(["in_contact_per_unit_area", "raw_in_contact"]).reindex(separation=h)
        for name in set(out.data_vars) - set(unl.data_vars):  # loading only (fractions, radius)
            unl[name] = xr.full_like(out[name], np.nan)
        out = xr.concat([out, unl[list(out.data_vars)]], dim="branch", data_vars="all",
                        coords="minimal", compat="override")
        out["density_integral"] = out["density_integral"].isel(branch=0, drop=True)
        out = out.assign_coords(branch=("branch", ["loading", "unloading"], _attrs(
            "1", "loading, or unloading from the separation unloading_from (report 8.3)")))
        out.attrs["unloading_from"] = h0
    out.attrs["rule"] = rule
    out.attrs["cells"] = str(tuple(homogenization.get("cells", (40, 40))))
    for name in ("accuracy", "fe_jobs", "fe_cpu_time", "max_newton_iterations", "max_step_cuts",
                 "max_dofs", "max_time_steps"):  # what the asperities cost (FE scenes)
        if name in asperities.attrs:
            out.attrs[name] = asperities.attrs[name]
    return out


def unloading_dataset(asperities: xr.Dataset) -> xr.Dataset:
    """The blended family of unloading paths of every curvature (8.3, unloading.nc)."""
    return unloading_family_table(asperities)


def expectation_dataset(
    surface_ds: xr.Dataset, population: Config, asperity: Config,
    homogenization: Config, units_cfg: Config,
) -> xr.Dataset:
    """E(X) for a constant X: the check of report 2.6.2 (eqs. 2.5 to 2.7)."""
    density = population_density(surface_ds, population)
    threshold = population.get("support_threshold", 1e-4)
    support = density.support(threshold)
    rect = bounds(density, homogenization, units_cfg, threshold)
    area = homogenization.get("area", 1.0) * length_factor(units_cfg) ** 2
    value = asperity.get("value", 1.0)
    res = homogenize.expectation(
        value, density, rect, cells=tuple(homogenization.get("cells", (20, 20))),
        rule=homogenization.get("rule", "trapezoid"), peak_density=peak_density(surface_ds), area=area,
    )
    scalar = lambda v, u, ln: ((), float(v), _attrs(u, ln))  # noqa: E731
    ds = xr.Dataset(
        {
            "value": scalar(value, "1", "the quantity X (constant)"),
            "integral": scalar(res.integral, "1", "integrated value of X, eq. (2.6)"),
            "normalization": scalar(res.normalization, "1", "integral I of the peak density, (2.7)"),
            "expectation": scalar(res.expectation, "1", "corrected expectation E(X)/I, eq. (2.7)"),
            "macroscopic": scalar(res.macroscopic, "1", "macroscopic value N_p E(X)"),
            "per_unit_area": scalar(res.per_unit_area, "1/m^2", "value of X per unit nominal area"),
            "support": ("bound", np.array(support, float),
                        _attrs("m or 1/m", "effective support: height min, max (m); curvature min, max (1/m)")),
            "rectangle": ("bound", np.array(rect, float),
                          _attrs("m or 1/m", "integration rectangle: height min, max (m); curvature min, max (1/m)")),
        },
        coords={"bound": ("bound", ["height_min", "height_max", "curvature_min", "curvature_max"],
                          _attrs("1", "which bound"))},
    )
    ds.attrs["rule"] = homogenization.get("rule", "trapezoid")
    ds.attrs["cells"] = str(tuple(homogenization.get("cells", (20, 20))))
    ds.attrs["beta"] = float(getattr(density, "beta", np.nan))
    return ds


def verification_dataset(
    surface_ds: xr.Dataset, interface: xr.Dataset, verification: str,
    material: Config, units_cfg: Config,
) -> xr.Dataset:
    """The homogenized interface beside a closed form, with relative errors."""
    if verification != "greenwood_williamson":
        raise ValueError(f"unknown verification {verification!r}")
    mat = material_si(material, units_cfg)
    closed = greenwood_williamson.gw_interface(
        interface["separation"].values,
        radius=1.0 / float(surface_ds["tip_curvature"]),
        sigma_p=float(surface_ds["sigma_peak_height"]),
        peak_density=float(surface_ds["peak_density"]),
        E=mat["youngs_modulus"], nu=mat["poisson"],
    )
    ds = xr.Dataset(coords={"separation": interface["separation"]})
    pressure = interface["nominal_pressure"]
    relevant = pressure >= 1e-6 * float(pressure.max())
    ds["relevant"] = relevant.assign_attrs(
        _attrs("1", "load at least 1e-6 of its maximum (where the 0.5% bound applies)"))
    for name in ("nominal_pressure", "contact_area_ratio", "contact_count"):
        if name not in interface or name not in closed:
            continue
        ds[name] = interface[name]
        ds[f"{name}_closed_form"] = closed[name].assign_attrs(
            _attrs(interface[name].attrs["units"], f"{interface[name].attrs['long_name']}, closed form"))
        err = xr.where(closed[name] > 0, np.abs(interface[name] / closed[name] - 1.0), 0.0)
        ds[f"{name}_error"] = err.assign_attrs(
            _attrs("1", f"relative error of {interface[name].attrs['long_name']} against the closed form"))
        ds.attrs[f"max_{name}_error"] = float(err.where(relevant).max())
    return ds


def sample_dataset(spec: Config, key: str) -> xr.Dataset:
    """The response of one sample job (DESIGN.md: samples/<key>.nc) from its spec
    (`asperity.population.models.job_spec`, stored in the plan): everything it depends on."""
    model = spec["model"]
    if model == "fe":
        return models.solve_job(spec, key)
    if model != "hertz":
        raise ValueError(f"sample {key}: asperity.model {model!r} has no per-sample model")
    mat = spec["material"]
    w = np.asarray(spec["interference"], float)
    res = hertz.hertz_response(w, float(spec["curvature"]), mat["youngs_modulus"], mat["poisson"])
    step = np.arange(w.size)
    ds = xr.Dataset(
        {
            "interference": ("step", w, _attrs("m", "interference of the flat with the peak")),
            "force": ("step", res["force"], _attrs("N", "normal contact force")),
            "contact_area": ("step", res["contact_area"], _attrs("m^2", "real contact area")),
            "stiffness": ("step", res["stiffness"], _attrs("N/m", "normal stiffness dF/dw")),
        },
        coords={"step": ("step", step, _attrs("1", "load step"))},
    )
    ds.attrs.update(key=key, model=model, curvature=float(spec["curvature"]))
    return ds


def sample_or_failure(spec: Config, key: str) -> xr.Dataset:
    """`sample_dataset`, or, when the job fails (`models.SampleFailed`), a record of
    the failure (attrs ``status`` "failed" and ``error`` naming sample and step):
    the other samples go on, and the gather refuses to homogenize over the hole
    and names it (`models.gather`)."""
    try:
        ds = sample_dataset(spec, key)
    except models.SampleFailed as err:
        log.error("%s", err)
        return xr.Dataset(attrs={"key": key, "status": "failed", "error": str(err),
                                 "curvature": float(spec.get("curvature", np.nan))})
    ds.attrs["status"] = "ok"
    return ds


def density_on_grid(surface_ds: xr.Dataset, population: Config, rect, n: int = 200):
    """The joint peak density on an n x n grid over `rect` (for figures)."""
    density = population_density(surface_ds, population)
    z = np.linspace(rect[0], rect[1], n)
    kappa = np.linspace(rect[2], rect[3], n)
    return z, kappa, density.pdf(z[:, None], kappa[None, :])


def synthetic_map(generate: Config) -> np.ndarray:
    """A Gaussian random height map (scene units) with a Gaussian autocorrelation.

    White noise filtered in Fourier space by exp(-k^2 l^2 / 8), which gives
    the autocorrelation exp(-r^2 / l^2) (l: correlation length), scaled to
    the standard deviation `sigma`.  Periodic, so the eight-neighbour peak
    rule of 2.4.3 sees no edge effects.
    """
    n, h = generate["points"], generate["spacing"]
    rng = np.random.default_rng(generate["seed"])
    noise = rng.standard_normal((n, n))
    k = 2 * np.pi * np.fft.fftfreq(n, d=h)
    k2 = k[:, None] ** 2 + k[None, :] ** 2
    z = np.fft.ifft2(np.fft.fft2(noise) * np.exp(-k2 * generate["correlation_length"] ** 2 / 8)).real
    z -= z.mean()
    return z * (generate["sigma"] / z.std())


def profile_file_name(direction_deg: float) -> str:
    """File name of the synthetic profile along `direction_deg`."""
    return f"profile_{direction_deg:g}deg.txt"


def anisotropic_series(generate: Config):
    """Amplitudes, wave vectors and phases of a synthetic anisotropic surface (eq. 2.3).

    The 1-D quasi-random series of 2.6.1 with each wave vector turned to a
    random direction and its x component stretched by `aspect`.
    """
    c, k, e = surface.quasirandom_series(n=generate["components"], seed=generate["seed"])
    phi = np.random.default_rng(generate["seed"] + 1).uniform(0.0, np.pi, c.size)
    return c, generate["aspect"] * k * np.cos(phi), k * np.sin(phi), e


def synthetic_directional_profiles(generate: Config) -> list[tuple[np.ndarray, np.ndarray]]:
    """Profiles z(s) = sum C cos((kx cos t + ky sin t) s + e) along each direction t."""
    c, kx, ky, e = anisotropic_series(generate)
    s = np.arange(0.0, generate["length"] + 0.5 * generate["spacing"], generate["spacing"])
    out = []
    for deg in generate["directions"]:  # a handful of directions
        t = np.radians(deg)
        out.append((s, surface.evaluate_series(s, c, kx * np.cos(t) + ky * np.sin(t), e)))
    return out


def surface_from_profiles(
    profiles: list[tuple[np.ndarray, float]], directions_deg: list[float], surface_cfg: Config,
) -> xr.Dataset:
    """Statistics of profiles along several directions and the surface moments (2.3.2).

    Each profile gets the statistics of `profile_statistics` (dim
    ``direction``); the moments m20, m11, m02 (3 directions or more) and the
    fourth-order moments (5 or more) follow by least squares from the
    chosen method's m0, m2, m4, with the invariants of 2.3.2.  For a
    synthetic surface the exact moments of eq. (2.4) are added as
    ``<moment>_exact``.
    """
    method = surface_cfg.get("method", "sampling")
    stats = xr.concat([surface.profile_statistics(z, dx) for z, dx in profiles], dim="direction",
                      data_vars="all", coords="minimal", compat="override")
    theta = np.radians(np.asarray(directions_deg, float))
    stats = stats.assign_coords(direction=("direction", theta, _attrs("rad", "profile direction from the x axis")))
    chosen = stats.sel({"method": method})
    moments = surface.directional_moments(theta, chosen["m0"].values, chosen["m2"].values, chosen["m4"].values)
    ds = xr.merge([stats, moments], combine_attrs="drop_conflicts")
    ds.attrs.update(moments.attrs)
    generate = surface_cfg["profiles"].get("generate")
    if generate:
        length = profiles[0][1] / generate["spacing"]
        c, kx, ky, _ = anisotropic_series(generate)
        exact = surface.series_moments_2d(c, kx, ky)
        for name, value in exact.items():
            if name not in ds:
                continue
            order = int(name[1]) + int(name[2])
            ds[f"{name}_exact"] = xr.DataArray(
                value * length ** (2 - order),
                attrs=_attrs(ds[name].attrs["units"], f"{ds[name].attrs['long_name']}, exact (eq. 2.4)"))
    ds.attrs["population_method"] = method
    return ds


def hertz_verification_dataset(single: Config, material: Config, units_cfg: Config) -> xr.Dataset:
    """One FE asperity against Hertz at the scene's presets (report 6.1, Fig. 6.5).

    The paraboloid (Hertz's own idealization) and the true sphere, one run
    per preset: `asperity.studies.hertz.hertz_accuracy_study` without its
    refinement sequence and penalty study.
    """
    from asperity.studies.hertz import hertz_accuracy_study

    length = length_factor(units_cfg)
    mat = material_si(material, units_cfg)
    ds = hertz_accuracy_study(
        radius=single["radius"] * length, youngs_modulus=mat["youngs_modulus"], poisson=mat["poisson"],
        interferences=tuple(v * length for v in single["interferences"]),
        presets=tuple(single.get("presets", ("standard", "fine"))), refinement=(), penalty_factors=(),
    )
    for body in ds["body"].values:
        for run in ds["run"].values:
            err = ds["max_force_error"].sel(body=body, run=run)
            if np.isfinite(err):
                ds.attrs[f"max_force_error_{body}_{run}"] = float(err)
                ds.attrs[f"max_radius_error_{body}_{run}"] = float(ds["max_radius_error"].sel(body=body, run=run))
    return ds
