"""The ``elliptic`` kind: 3-D finite element elliptic paraboloids of a J2 body, one job per
curvature ratio t = kappa_2 / kappa_1, for the anisotropic route (report 2.4.2, 2.5.2).

A summit of a Gaussian anisotropic surface is an elliptic paraboloid of principal
curvatures kappa_1 >= kappa_2 = t kappa_1 (`asperity.peaks.anisotropic`). For a body
without a length of its own (elastic, rate-independent J2) a change of every length by
lambda leaves the stresses alone, so the force on a summit pressed by w is

    F(w; kappa_1, t) = F(w kappa_1; 1, t) / kappa_1^2

(the area likewise): the response depends on the ratio t and a scale. The plan
(`asperity.population.plan.make_ratio_plan`) therefore computes one job per ratio, at one
reference curvature, not one per pair of curvatures; the ratios are geometrically spaced
from that of the elongated summits (the 5 % quantile of t over the summits, at least
`SMALLEST_RATIO`) to 1 (a sphere's tip).

A job presses the paraboloid of its ratio (`asperity.fe.drivers.solid3d.press_3d`,
frictionless) to geometric levels from first yield to ``yield_multiple`` times first
yield (or the deepest interference the surface's summits can reach, if less), w_c the
first yield of the sphere of equal Hertz peak pressure
(`asperity.homogenize.anisotropic.peak_pressure_curvature`;
`asperity.references.kogut_etsion.critical_interference`); each level is pressed from
zero on a mesh sized for its own contact (`BLOCK` long semi-axes of it; the contact grows
thirtyfold over the levels, and one mesh made for the largest leaves the smallest within
one element), and the elastic
body of the same mesh beside it (one step: frictionless elastic contact is path
independent). The route reads the departure of the J2 body from the elastic one, force
over force and area over area on the same mesh, so that the mesh's and the finite
block's errors, a few percent against elliptic Hertz at draft, cancel to first
order (`asperity.stages.routes.elliptic_departure`); the elastic body's own error
against Hertz is kept in the table.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import xarray as xr

from asperity.population.kinds.base import FiniteElementKind
from asperity.scene import Material, build
from asperity.units import attrs

#: the smallest ratio kappa_2 / kappa_1 a job computes: a contact ellipse 4 times longer than
#: wide (1/16: 6 times, and about twice the CPU); more elongated summits take its departure
#: at equal Hertz peak pressure (`asperity.stages.routes.elliptic_departure`), which the
#: jobs of 1/16 and 1/4 at draft give alike within 3 % (force ratios 0.771 and 0.746 at 13.6 w_c,
#: 0.539 and 0.534 at 50 w_c)
SMALLEST_RATIO = 1.0 / 8.0
#: the half width and depth of a level's block, in long semi-axes of its Hertz contact: the
#: finite block is stiffer than the half space by about 1.1 a / L in force (2 % below and
#: above Hertz on this block: tests/fe/test_elliptic_3d.py), which the elastic twin of the
#: same mesh cancels; the geometry's own block (its footprint) is smaller than 3 a at a
#: thousand times first yield, where the elastic force exceeded Hertz's by 90 %
BLOCK = 20.0
#: the quantile of t over the summits below which the ratios do not go
RATIO_QUANTILE = 0.05


def first_yield(curvature: float, ratio: float, material: Material) -> float:
    """The interference [m] of first yield of the sphere of equal Hertz peak pressure of the
    elliptic paraboloid of `curvature` kappa_1 [1/m] and `ratio` (module docstring)."""
    from asperity.homogenize.anisotropic import peak_pressure_curvature
    from asperity.references.hertz import plane_strain_modulus
    from asperity.references.kogut_etsion import critical_interference

    kappa = float(peak_pressure_curvature(np.array(curvature), np.array(ratio)))
    return critical_interference(1.0 / kappa, plane_strain_modulus(material.youngs_modulus, material.poisson),
                                 material.poisson, material.yield_stress)


class Elliptic(FiniteElementKind):
    name = "elliptic"

    def check(self, asperity, material, effects):
        super().check(asperity, material, effects)
        if "plasticity" not in effects or material.model != "j2":
            raise ValueError(
                "asperity.geometry elliptic: the 3-D jobs over the curvature ratio carry the "
                "departure of a J2 body from Hertz (effects: [plasticity], material.model: j2); "
                "an elastic summit is Hertz's elliptic contact (route.law: elliptic)")
        other = sorted(set(effects) - {"plasticity"})
        if other:
            raise ValueError(f"asperity.geometry elliptic: effects {other} are not modelled on the "
                             "3-D elliptic summit (effects: [plasticity] only)")

    def ratio_spec(self, material: Material, accuracy: str, curvature: float, ratio: float,
                   deepest: float, yield_multiple: float) -> dict:
        """What the job of `ratio` depends on: the paraboloid (reference `curvature`
        kappa_1 [1/m], the ratio), its interference range (first yield to
        `yield_multiple` times it, or to `deepest` [m] if less, but at least twice first
        yield), the body and the preset."""
        w_c = first_yield(curvature, ratio, material)
        top = max(min(deepest, yield_multiple * w_c), 2.0 * w_c)
        return {"model": "fe", "geometry": "elliptic", "curvature": float(curvature),
                "ratio": float(ratio), "range": [w_c, top], "material": material.spec(),
                "effects": ["plasticity"], "accuracy": accuracy}

    def solve(self, spec, key):
        """The J2 paraboloid and its elastic twin pressed to each of the job's levels
        (`asperity.fe.presets.PRESS_3D`), each level from zero on the mesh of its own
        Hertz contact (a mesh made for the largest contact is too coarse for the smallest);
        `SampleFailed` naming the sample, the body and the level where the solver fails or
        finds no contact."""
        from asperity import fe
        from asperity.fe.discretization.geometry import EllipticParaboloid
        from asperity.fe.discretization.half_model_mesh import MeshSpec
        from asperity.fe.drivers.solid3d import press_3d
        from asperity.fe.presets import PRESS_3D, resolve
        from asperity.population.geometry import fe_levels
        from asperity.references.hertz import elliptic_hertz

        k1, t = float(spec["curvature"]), float(spec["ratio"])
        geometry = EllipticParaboloid(k1, t * k1)
        press = PRESS_3D[spec["accuracy"]]
        levels = fe_levels(*spec["range"], press["levels"])
        material = Material.from_spec(spec["material"])
        bodies = {"j2": build(material, spec["effects"]), "elastic": build(material, ())}
        modulus = bodies["elastic"].contact_modulus
        hertz = elliptic_hertz(levels, k1, t * k1, modulus)
        accuracy = {name: dict(base=spec["accuracy"], normal_steps=n)
                    for name, n in (("j2", press["normal_steps"]), ("elastic", 1))}
        preset = resolve("sliding", spec["accuracy"])
        meshes = [dataclasses.replace(MeshSpec.for_hill(geometry, a, preset), half_width=BLOCK * a,
                                      depth=BLOCK * a, coarse_size=BLOCK * a / 3.0)
                  for a in np.asarray(hertz["semi_axis_a"], float)]
        cpu, rows = time.process_time(), {name: [] for name in bodies}
        for name, body in bodies.items():
            for i, w in enumerate(levels):  # each level on the mesh of its own contact
                where = f", ratio {t:.4g}, {name} body, level {i} (w = {w:.4g} m)"
                try:
                    ds = press_3d(geometry, body, [w], accuracy=accuracy[name], mesh=meshes[i],
                                  contact_radius=float(hertz["semi_axis_a"][i]), progress=self.progress(key))
                except (fe.ConvergenceError, fe.ContactZoneError) as err:
                    raise self.failed(key, k1, err, where) from err
                if not ds.attrs.get("completed", 1) or not ds["normal_force"].values[-1] > 0:
                    raise self.failed(key, k1, RuntimeError(ds.attrs.get("stop_reason") or "no contact"),
                                      where)
                rows[name].append(ds)
        out = _levels_dataset(rows, levels, hertz)
        out.attrs.update(ratio=t, steps=int(sum(ds.attrs["steps"] for ds in rows["j2"])),
                         accuracy=spec["accuracy"])
        return self.record(out, spec, key, geometry, math.nan, time.process_time() - cpu)

    def gather(self, plan, samples):
        """The jobs on (ratio, level), with the departures of the J2 body from the elastic
        one and the interference in units of the sphere of equal peak pressure."""
        from asperity.homogenize.anisotropic import peak_pressure_curvature
        from asperity.population.gather import fe_cost, samples_by_key

        by_key = samples_by_key(plan, samples)
        order = np.argsort(plan["sample_ratio"].values)
        jobs = [by_key[str(plan["key"].values[i])] for i in order]
        ratios = plan["sample_ratio"].values[order]
        names = ("interference", "force", "contact_area", "elastic_force", "elastic_contact_area",
                 "hertz_force", "hertz_contact_area", "max_inelastic_strain")
        stacked = {n: np.stack([j[n].values for j in jobs]) for n in names}
        kappa = peak_pressure_curvature(plan["job_curvature"].values[order], ratios)
        data = {n: (("ratio", "level"), stacked[n], dict(jobs[0][n].attrs)) for n in names}
        data["scaled_interference"] = (("ratio", "level"), stacked["interference"] * kappa[:, None], attrs(
            "1", "interference times the curvature of the sphere of equal Hertz peak pressure"))
        data["force_departure"] = (("ratio", "level"), stacked["force"] / stacked["elastic_force"], attrs(
            "1", "force of the J2 summit over that of the elastic one on the same mesh"))
        data["area_departure"] = (("ratio", "level"), stacked["contact_area"] / stacked["elastic_contact_area"],
                                  attrs("1", "contact area of the J2 summit over that of the elastic one "
                                        "on the same mesh"))
        ds = xr.Dataset(data, coords={
            "ratio": ("ratio", ratios, attrs("1", "curvature ratio kappa_2 / kappa_1 of the job's summit")),
            "level": ("level", np.arange(stacked["force"].shape[1]), attrs("1", "interference level"))})
        ds.attrs.update(fe_cost(jobs))
        ds.attrs.update(kind=self.name, reference_curvature=float(plan.attrs["reference_curvature"]))
        return ds

    def interface(self, asperities, separations, homogenized):
        raise ValueError("asperity.geometry elliptic: its jobs serve the anisotropic route "
                         "(route: {kind: anisotropic, law: fe}), not the isotropic homogenization")


def _levels_dataset(rows: dict, levels: np.ndarray, hertz: dict) -> xr.Dataset:
    """The last rows of the presses of each body, one a level, with elliptic Hertz there."""
    def last(name, var):
        return np.array([ds[var].values[-1] for ds in rows[name]])

    def total(attr):
        return np.array([ds.attrs[attr] for ds in rows["j2"]])

    data = {
        "interference": ("step", levels, attrs("m", "interference of the flat")),
        "force": ("step", last("j2", "normal_force"), attrs("N", "normal force on the J2 summit")),
        "contact_area": ("step", last("j2", "contact_area"), attrs("m^2", "contact area of the J2 summit")),
        "elastic_force": ("step", last("elastic", "normal_force"), attrs(
            "N", "normal force on the elastic summit of the same mesh")),
        "elastic_contact_area": ("step", last("elastic", "contact_area"), attrs(
            "m^2", "contact area of the elastic summit of the same mesh")),
        "hertz_force": ("step", np.asarray(hertz["force"], float), attrs("N", "elliptic Hertz force")),
        "hertz_contact_area": ("step", np.asarray(hertz["contact_area"], float), attrs(
            "m^2", "elliptic Hertz contact area")),
        "max_inelastic_strain": ("step", last("j2", "max_inelastic_strain"), attrs(
            "1", "largest equivalent inelastic strain of the J2 summit")),
        "newton_iterations": ("step", total("total_newton_iterations"), attrs(
            "1", "Newton iterations of the J2 press to the level")),
        "step_cuts": ("step", total("total_step_cuts"), attrs("1", "step cuts of the J2 press to the level")),
        "dofs": ("step", total("dofs"), attrs("1", "degrees of freedom of the level's mesh")),
    }
    return xr.Dataset(data, coords={"step": ("step", np.arange(levels.size), attrs("1", "level index"))})


ELLIPTIC = Elliptic()
