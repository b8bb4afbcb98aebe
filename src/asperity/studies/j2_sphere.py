"""The J2 sphere beside two models of it: Kogut and Etsion's fits of the elastic-plastic
sphere, and the boundary elements of a paraboloid limited by the hardness (the reference
of the routes of J2 asperities, `asperity.stages.reference`).

An elastic-perfectly plastic sphere (radius R, E, nu, Y) pressed by a rigid flat
(`asperity.fe.solve_asperity_history`):

* to 300 w_c (w_c the interference of first yield, Kogut and Etsion, J. Appl. Mech. 69
  (2002) 657, eq. 3; `asperity.references.kogut_etsion`), on meshes graded over the range
  (`asperity.fe.drivers.inelastic.MESH_LEVELS`, from `MESH_RANGE` of the top), its force
  and contact area over the fits at 1 to 100 w_c (`KE_POINTS`);
* to R / 4, as a population's job is (first step `FIRST_STEP` of the range), on the mesh
  of `asperity.population.kinds.inelastic.mesh_levels` (from w_c) and on the finite element
  default (from a hundredth of the range): its force over the fits at 1 to 50 w_c;
* that job's force and area over the boundary elements of the paraboloid of radius R
  whose pressure is limited by the hardness 2.8 Y (Tabor), free boundary, `cells` x
  `cells` cells over 0.5 R (w / R <= 0.03) or 2.4 R, at w / R = `WR_POINTS`.

The fits hold where the sphere's contact is small against R; the hardness model holds
once the contact is fully plastic (about 100 w_c) and ignores the elastic core below
it: the two columns bracket the J2 route's reference from both sides.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from asperity.units import attrs

__all__ = ["KE_POINTS", "WR_POINTS", "j2_sphere_figure", "j2_sphere_study"]

#: interferences over w_c where the sphere is held against Kogut and Etsion's fits
KE_POINTS = (1.0, 2.0, 4.0, 6.0, 10.0, 20.0, 50.0, 100.0)
#: interferences over R where the population's job is held against the boundary elements
WR_POINTS = (0.001, 0.003, 0.01, 0.03, 0.1, 0.25)


def _press(sphere, body, top: float, levels, first: float, accuracy: str):
    from asperity import fe

    t0 = time.process_time()
    ds = fe.solve_asperity_history(sphere, body, fe.History((0.0, 1.0), (0.0, top)), accuracy=accuracy,
                                   mesh_levels=levels, initial_time_step=first)
    return ds, time.process_time() - t0


def _at(ds: xr.Dataset, w, name: str) -> np.ndarray:
    return np.interp(w, ds["interference"].values, ds[name].values)


def _hardness_paraboloid(radius: float, w_over_r, modulus: float, hardness: float, cells: int):
    """Force and contact area of the paraboloid of `radius` pressed by w = w_over_r R, its
    pressure limited by `hardness` (`cells` x `cells` free boundary elements)."""
    from asperity.references.boundary_element import solve_map

    w_over_r = np.asarray(w_over_r, dtype=float)
    force, area = np.full(w_over_r.size, np.nan), np.full(w_over_r.size, np.nan)
    for half, pick in ((0.25 * radius, w_over_r <= 0.03), (1.2 * radius, w_over_r > 0.03)):
        if not pick.any():
            continue
        x = (np.arange(cells) - (cells - 1) / 2) * (2 * half / cells)
        xx, yy = np.meshgrid(x, x)
        z = -(xx**2 + yy**2) / (2 * radius)
        w = w_over_r[pick] * radius
        ds = solve_map(z, x[1] - x[0], x[1] - x[0], -z.mean() - w, modulus, hardness=hardness,
                       boundary="free")
        order = np.argsort(-z.mean() - w)  # the separations come back increasing
        square = (2 * half) ** 2
        force[np.flatnonzero(pick)[order]] = ds["nominal_pressure"].values * square
        area[np.flatnonzero(pick)[order]] = ds["contact_area_ratio"].values * square
    return force, area


def j2_sphere_study(youngs_modulus: float, poisson: float, yield_stress: float, radius: float,
                    presets=("draft", "standard"), cells: int = 256) -> xr.Dataset:
    """The J2 sphere beside Kogut and Etsion's fits and the hardness-limited boundary
    elements, at each preset (module text); SI units."""
    from asperity import fe
    from asperity.fe.drivers.inelastic import MESH_LEVELS, MESH_RANGE
    from asperity.population.kinds.inelastic import FIRST_STEP, mesh_levels
    from asperity.references.hertz import plane_strain_modulus
    from asperity.references.kogut_etsion import critical_interference, kogut_etsion
    from asperity.scene import Material

    modulus = float(plane_strain_modulus(youngs_modulus, poisson))
    wc = critical_interference(radius, modulus, poisson, yield_stress)
    sphere, body = fe.Sphere(radius), fe.J2Plasticity(youngs_modulus, poisson, yield_stress)
    material = Material(model="j2", youngs_modulus=youngs_modulus, poisson=poisson, yield_stress=yield_stress)
    ke, ke_job = np.array(KE_POINTS), np.array(KE_POINTS[:-1])
    ref, ref_job = (kogut_etsion(v * wc, radius, modulus, poisson, yield_stress) for v in (ke, ke_job))
    bem_force, bem_area = _hardness_paraboloid(radius, WR_POINTS, modulus, 2.8 * yield_stress, cells)
    meshes = ("mesh_levels", "fe_default")
    out = {k: [] for k in ("force_over_ke", "area_over_ke", "cpu_time", "job_force_over_ke", "job_cpu_time",
                           "force_over_bem", "area_over_bem")}
    top, deep = 300 * wc, radius / 4
    for preset in presets:  # two presets, each a few FE runs
        ds, cpu = _press(sphere, body, top, np.geomspace(MESH_RANGE * top, top, MESH_LEVELS), 2e-3, preset)
        out["force_over_ke"].append(_at(ds, ke * wc, "force") / ref["force"])
        out["area_over_ke"].append(_at(ds, ke * wc, "contact_area") / ref["contact_area"])
        out["cpu_time"].append(cpu)
        jobs, cpus = [], []
        for levels in (mesh_levels(deep, 1.0 / radius, material), np.geomspace(MESH_RANGE * deep, deep, MESH_LEVELS)):
            job, cpu = _press(sphere, body, deep, levels, FIRST_STEP, preset)
            jobs.append(job)
            cpus.append(cpu)
        out["job_force_over_ke"].append([_at(job, ke_job * wc, "force") / ref_job["force"] for job in jobs])
        out["job_cpu_time"].append(cpus)
        w = np.array(WR_POINTS) * radius
        out["force_over_bem"].append(_at(jobs[0], w, "force") / bem_force)
        out["area_over_bem"].append(_at(jobs[0], w, "contact_area") / bem_area)
    dims = {"force_over_ke": ("preset", "w_over_wc"), "area_over_ke": ("preset", "w_over_wc"),
            "cpu_time": ("preset",), "job_force_over_ke": ("preset", "mesh", "w_over_wc_job"),
            "job_cpu_time": ("preset", "mesh"), "force_over_bem": ("preset", "w_over_r"),
            "area_over_bem": ("preset", "w_over_r")}
    meta = {
        "force_over_ke": ("1", "force of the sphere pressed to 300 w_c over Kogut and Etsion's"),
        "area_over_ke": ("1", "contact area of the sphere pressed to 300 w_c over Kogut and Etsion's"),
        "cpu_time": ("s", "CPU time of the sphere pressed to 300 w_c"),
        "job_force_over_ke": ("1", "force of the population's job (to R/4) over Kogut and Etsion's"),
        "job_cpu_time": ("s", "CPU time of the population's job (to R/4)"),
        "force_over_bem": ("1", "force of the job (mesh_levels) over the hardness-limited boundary elements'"),
        "area_over_bem": ("1", "contact area of the job (mesh_levels) over the hardness-limited boundary elements'"),
    }
    return xr.Dataset(
        {k: (dims[k], np.asarray(v, dtype=float), attrs(*meta[k])) for k, v in out.items()},
        coords={"preset": ("preset", list(presets), attrs("", "accuracy preset of the FE runs")),
                "w_over_wc": ("w_over_wc", ke, attrs("1", "interference over the critical interference w_c")),
                "w_over_wc_job": ("w_over_wc_job", ke_job, attrs("1", "interference over w_c, the job")),
                "mesh": ("mesh", list(meshes), attrs("", "the job's mesh: graded from w_c, or the FE default")),
                "w_over_r": ("w_over_r", np.array(WR_POINTS), attrs("1", "interference over the radius")),
                "w_over_wc_of_w_over_r": ("w_over_r", np.array(WR_POINTS) * radius / wc,
                                          attrs("1", "the same interferences over w_c"))},
        attrs={"youngs_modulus": youngs_modulus, "poisson": poisson, "yield_stress": yield_stress,
               "radius": radius, "critical_interference": wc, "cells": cells})


def j2_sphere_figure(ds: xr.Dataset):
    """(a) The sphere's force and area over Kogut and Etsion's against w / w_c, and the
    population's jobs' force; (b) the job's force and area over the hardness-limited
    boundary elements against w / w_c; one line style per preset."""
    import asperity.plots  # noqa: F401  (the package's non-interactive backend)
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
    for i, preset in enumerate(ds["preset"].values):
        d, style = ds.sel(preset=preset), ("-", "--", ":")[i % 3]
        a.semilogx(ds["w_over_wc"], d["force_over_ke"], "C0" + style, label=f"force, to 300 w_c ({preset})")
        a.semilogx(ds["w_over_wc"], d["area_over_ke"], "C1" + style, label=f"area, to 300 w_c ({preset})")
        a.semilogx(ds["w_over_wc_job"], d["job_force_over_ke"].sel(mesh="mesh_levels"), "C2" + style,
                   label=f"force, population's job ({preset})")
        b.semilogx(ds["w_over_wc_of_w_over_r"], d["force_over_bem"], "C0" + style, label=f"force ({preset})")
        b.semilogx(ds["w_over_wc_of_w_over_r"], d["area_over_bem"], "C1" + style, label=f"area ({preset})")
    a.axhline(1.0, color="0.5", lw=0.8)
    b.axhline(1.0, color="0.5", lw=0.8)
    a.set(xlabel="interference / w_c", ylabel="FE over Kogut and Etsion")
    b.set(xlabel="interference / w_c", ylabel="FE over the boundary elements at 2.8 Y")
    a.legend(fontsize=7)
    b.legend(fontsize=7)
    return fig
