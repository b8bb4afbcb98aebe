"""The ``elastic`` kind: the finite element asperity of a linear elastic body (report
6.1, 7.2, 7.3 without plasticity).

One job per curvature (shift invariant in height; one job in all for a self-similar
family), except the coupled cosine hill: one per sample, or with ``scaling:
self_similar`` one per aspect q = kappa z_p of its family (2.5.1, 8.2.2;
`asperity.population.plan.make_aspect_plan`). A job computes ``levels``
geometric interferences over its range with `asperity.fe.solve_asperity`, with the
``contact`` model of the scene (penalty or exact).
"""

from __future__ import annotations

import time

from asperity.population.geometry import fe_levels, self_similar, spec_geometry
from asperity.population.kinds.base import FiniteElementKind
from asperity.scene import Material, build


class Elastic(FiniteElementKind):
    name = "elastic"

    def scalable(self, asperity, material, effects):
        return self_similar(asperity, material, effects)

    def spec(self, planning, height, curvature, level):
        spec = self.base_spec(planning, height, curvature)
        spec["levels"] = int(planning.asperity.levels)
        spec["contact"] = planning.asperity.contact
        return spec

    def solve(self, spec, key):
        """`solve_asperity` at ``levels`` geometric interferences over the job's range;
        raises `SampleFailed` naming the sample and the step when Newton fails even
        with step cutting."""
        from asperity import fe

        curvature = float(spec["curvature"])
        geometry = spec_geometry(spec)
        first, top = spec["range"]
        material = build(Material.from_spec(spec["material"]), spec["effects"])
        cpu = time.process_time()
        try:
            ds = fe.solve_asperity(geometry, material, fe_levels(first, top, spec["levels"]),
                                   accuracy=spec["accuracy"], contact=spec["contact"])
        except (fe.ConvergenceError, fe.ContactZoneError) as err:
            raise self.failed(key, curvature, err) from err
        return self.record(ds, spec, key, geometry, float("nan"), time.process_time() - cpu)


ELASTIC = Elastic()
