"""Stage `population` (workflow/rules/population.smk): the plan of asperity samples, one
sample's response, and the gather of all samples (report 2.4, 8.2)."""

from __future__ import annotations

import logging
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity import peaks
from asperity.population import adhesive as adhesive_interface
from asperity.population import models
from asperity.population.density import bounds, population_density, population_stat
from asperity.population.plan import interference_grid, make_plan, sample_grid
from asperity.references import hertz
from asperity.scene import length_factor, material_si, materials, velocity_si
from asperity.units import attrs

log = logging.getLogger("asperity")

Config = Mapping[str, Any]


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
        width_to_height = models.representative_width_to_height(population_stat(surface_ds, "sigma_slope"))
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
        plan["left_out"] = ("sample", plan["unloading_level"].values == check, attrs(
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
            "interference": ("step", w, attrs("m", "interference of the flat with the peak")),
            "force": ("step", res["force"], attrs("N", "normal contact force")),
            "contact_area": ("step", res["contact_area"], attrs("m^2", "real contact area")),
            "stiffness": ("step", res["stiffness"], attrs("N/m", "normal stiffness dF/dw")),
        },
        coords={"step": ("step", step, attrs("1", "load step"))},
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
