"""The ``hertz`` kind: the analytic elastic sphere of report 6.1.

A closed form: no sample has a job of its own (`Kind.job` False). The spec names
the closed form's inputs (material, curvature, the plan's interference grid), so
its key still tells samples apart; the gather evaluates the closed form on the whole
grid, with the material of the plan's specs.
"""

from __future__ import annotations

import json

import numpy as np
import xarray as xr

from asperity.population.kinds.base import Kind
from asperity.references import hertz
from asperity.units import attrs


class Hertz(Kind):
    name = "hertz"
    job = False

    def check(self, asperity, material, effects):
        super().check(asperity, material, effects)
        if material is None:
            raise ValueError("asperity.model hertz needs the scene's `material` section")

    def spec(self, planning, height, curvature, level):
        return {"model": "hertz", "material": planning.material.spec(), "curvature": curvature,
                "interference": planning.grid}

    def solve(self, spec, key):
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
        ds.attrs.update(key=key, model="hertz", curvature=float(spec["curvature"]))
        return ds

    def gather(self, plan, samples):
        mat = json.loads(str(plan["spec"].values[0]))["material"]
        return hertz.hertz_asperities(plan["height"].values, plan["curvature"].values,
                                      plan["interference"].values, mat["youngs_modulus"],
                                      mat["poisson"])


HERTZ = Hertz()
