"""One FE job for a self-similar family (DESIGN.md, issue 6): a member derived by
scaling matches its direct run within 0.5 %."""

from __future__ import annotations

import numpy as np
import pytest

from asperity.population import samples as population
from asperity.population.gather import gather
from asperity.population.kinds import Planning, kind_of
from asperity.population.plan import interference_grid, make_plan
from asperity.scene import Asperity, Material, Units
from tests.scene_defaults import filled

ASPERITY = Asperity.from_section(
    filled("asperity", {"model": "fe", "geometry": "cosine", "width_to_height": 17.0, "levels": 24}),
    Units("m", "Pa"))
ELASTIC = Material(model="elastic", youngs_modulus=65e9, poisson=0.3)
J2 = Material(model="j2", youngs_modulus=65e9, poisson=0.3, yield_stress=320e6)


def responses(material, effects, curvatures, reference, accuracy):
    grid = interference_grid(4e-6, 121)
    family = np.asarray(curvatures) if reference is not None else None
    planning = Planning(asperity=ASPERITY, material=material, effects=frozenset(effects),
                        accuracy=accuracy, adhesion=None, grid=grid, family=family,
                        width_to_height=None)
    kind = kind_of("fe", effects)
    plan = make_plan([0.0], curvatures, grid, model="fe",
                     shift_invariant=True, analytic=False, reference_curvature=reference,
                     job_spec=lambda h, k, level: kind.spec(planning, h, k, level))
    keys = [str(k) for k in np.unique(plan["key"].values)]
    samples = {k: population.solve_planned(plan, k) for k in keys}
    return gather(plan, samples), len(keys)


# The two runs differ only by their meshes, adapted to different interference
# levels: at `draft` the elastic solver's own error (about 1 %) shows as +-0.8 %
# scatter between them, so the elastic case runs at `standard` (0.1 % on Hertz).
@pytest.mark.slow
@pytest.mark.parametrize("material, effects, accuracy", [(ELASTIC, [], "standard"),
                                                         (J2, ["plasticity"], "draft")],
                         ids=["elastic", "j2"])
def test_derived_member_matches_its_direct_run(material, effects, accuracy):
    k_ref, k = 2.0e4, 6.0e4  # the derived hill is a third of the computed one
    derived, jobs = responses(material, effects, [k_ref, k], k_ref, accuracy)
    assert jobs == 1
    direct, _ = responses(material, effects, [k], None, accuracy)
    d = derived.sel(curvature=k).isel(height=0)
    r = direct.sel(curvature=k).isel(height=0)
    w = d["interference"].values
    # compare where both computed (not extrapolated) and the force is not vanishing
    use = (w > 0) & ~d["extrapolated"].values & ~r["extrapolated"].values
    use &= r["force"].values > 1e-3 * r["force"].values[use].max()
    assert use.sum() > 30
    rel = np.abs(d["force"].values[use] / r["force"].values[use] - 1)
    assert rel.max() < 5e-3, rel.max()
    # the contact area rests on the edge located between nodes, whose position differs
    # between the two meshes by up to 3 % of the area for the elastic solver (measured
    # 3.0e-2 at standard; 4e-3 for J2 at draft): the derivation is exact, the meshes are not
    rel = np.abs(d["contact_area"].values[use] / r["contact_area"].values[use] - 1)
    assert rel.max() < 3.5e-2, rel.max()
