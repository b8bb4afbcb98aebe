"""The plan runs only the finite element problems a scene's effects need (issue #6),
counted through Snakemake's dry run.

Small variants of the report's scenes (3 heights x 3 curvatures, at `draft`) are
written into a copy of the workflow; each scene's plan (a checkpoint) is made,
then one dry run lists every job the scenes still need.  The FE jobs of a scene
are the sample files its `asperities` job reads, and the `sample` row of the
dry run's job table counts the jobs of all scenes together.  Every count is
derived from the scene's own settings (curvatures, unloading levels), none is
copied from a run.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
import yaml

from asperity.io.netcdf import read_dataset
from asperity.population.plan import job_keys

from .conftest import REPO, copy_workflow, planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

HEIGHTS, CURVATURES = 3, 3
LEVELS = 3            # unloading levels (asperity.unloading_levels)
CHECK = 1             # the left-out check path of asperity.unloading_check (8.3, gamma_0)
ASPECTS = 4           # aspect jobs of the coupled hills' family (asperity.aspects)


def repo_scene(name: str) -> dict:
    scene = yaml.safe_load((REPO / "config" / "scenes" / f"{name}.yaml").read_text())
    for key in ("compare_with", "friction", "laws", "verification"):
        scene.pop(key, None)  # only the population matters here: no comparison scenes
    scene["population"]["samples"] = {"height": HEIGHTS, "curvature": CURVATURES, "interference": 41}
    return scene


def variant(base: str, *, effects=None, **asperity) -> dict:
    scene = repo_scene(base)
    if effects is not None:
        scene["effects"] = effects
    for key, value in asperity.items():
        if value is None:
            scene["asperity"].pop(key, None)
        else:
            scene["asperity"][key] = value
    return scene


def unloading(**asperity) -> dict:
    return variant("smooth_aluminum", effects=["plasticity", "unloading"], unloading_levels=LEVELS,
                   unloading_check=True, **asperity)


#: scene -> (definition, FE jobs it needs)
SCENES = {
    # elastic spheres (smooth_aluminum_elastic): one self-similar family, or one job per curvature
    "jc_elastic": (variant("smooth_aluminum_elastic"), 1),
    "jc_elastic_none": (variant("smooth_aluminum_elastic", scaling="none"), CURVATURES),
    # J2 spheres (smooth_aluminum): rate independent, still one family
    "jc_j2": (variant("smooth_aluminum"), 1),
    # and unloaded (8.3): one job per unloading level (and the check path), per curvature without scaling
    "jc_j2_unloading": (unloading(), LEVELS + CHECK),
    "jc_j2_unloading_none": (unloading(scaling="none"), CURVATURES * (LEVELS + CHECK)),
    # Bodner-Partom representative cosine hills (rough_aluminum_representative): rate dependent,
    # so `auto` runs every curvature; `self_similar` imposes the report's scaling (8.2.2);
    # without `plasticity` the body is elastic
    "jc_bp": (variant("rough_aluminum_representative", scaling=None), CURVATURES),
    "jc_bp_self_similar": (variant("rough_aluminum_representative", scaling="self_similar"), 1),
    "jc_bp_elastic": (variant("rough_aluminum_representative", effects=[], scaling=None), 1),
    # the coupled cosine hill (2.5.1) depends on its height too: one job per sample
    "jc_coupled": (variant("asperity_shape_coupled"), HEIGHTS * CURVATURES),
    # ... or, with scaling self_similar, the family of aspects (2.5.1, 8.2.2): one job per aspect,
    # whatever the number of samples, and the left-out check job
    "jc_coupled_family": (variant("asperity_shape_coupled", scaling="self_similar", aspects=ASPECTS),
                          ASPECTS),
    "jc_coupled_family_bp": (variant("rough_aluminum", aspects=ASPECTS, aspect_check=True),
                             ASPECTS + CHECK),
    # analytic Hertz asperities: no job at all
    "jc_hertz": (variant("asperity_shape_hertz"), 0),
}
if (REPO / "config" / "scenes" / "smooth_aluminum_adhesion.yaml").exists():
    # elastic spheres with adhesion (7.3): the range d does not scale, so one job per curvature
    SCENES["jc_adhesion"] = (variant("smooth_aluminum_adhesion"), CURVATURES)
CONFIG = ("--config", f"scenes=[{','.join(SCENES)}]", "accuracy=draft", "studies=False")


def asperities_inputs(proc) -> dict[str, list[str]]:
    """scene -> the sample files its `asperities` job reads, from a dry run's job list."""
    text = proc.stdout + proc.stderr
    found = {}
    for block in re.findall(r"^rule asperities:\n((?:    .*\n)+)", text, flags=re.M):
        fields = dict(re.findall(r"^    (\w+): (.*)$", block, flags=re.M))
        scene = re.fullmatch(r"results/(.+)/asperities\.nc", fields["output"]).group(1)
        found[scene] = [f for f in fields["input"].split(", ") if f.startswith("results/samples/")]
    return found


@pytest.fixture(scope="module")
def counted(tmp_path_factory):
    """The plans made, then one dry run of every scene's interface."""
    workdir = copy_workflow(tmp_path_factory.mktemp("job_counts"))
    for name, (scene, _) in SCENES.items():
        (workdir / "config" / "scenes" / f"{name}.yaml").write_text(yaml.safe_dump(scene))
    snakemake(workdir, *[f"results/{name}/plan.nc" for name in SCENES], *CONFIG)
    proc = snakemake(workdir, "-n", *[f"results/{name}/interface.nc" for name in SCENES], *CONFIG)
    plans = {name: read_dataset(workdir / "results" / name / "plan.nc") for name in SCENES}
    return planned_jobs(proc), asperities_inputs(proc), plans


@pytest.mark.parametrize("name", list(SCENES))
def test_fe_jobs_per_scene(counted, name):
    """A scene's asperities read exactly the FE jobs its effects need, each a distinct key."""
    _, inputs, plans = counted
    expected = SCENES[name][1]
    samples = inputs[name]
    assert len(samples) == expected, (name, samples)
    assert len(set(samples)) == expected
    assert sorted(f"results/samples/{k}.nc" for k in job_keys(plans[name])) == sorted(samples)
    assert int(plans[name]["job"].sum()) == expected
    assert plans[name].sizes["sample"] >= HEIGHTS * CURVATURES  # every sample planned, most derived


def test_sample_jobs_of_the_dry_run_are_the_distinct_keys(counted):
    """The dry run plans one `sample` job per distinct key over all scenes (here no two
    scenes share one: their bodies or shapes differ), and the blend of unloading
    paths (rule `unloading`) only for the two scenes with the effect."""
    jobs, inputs, _ = counted
    distinct = {f for files in inputs.values() for f in files}
    assert len(distinct) == sum(n for _, n in SCENES.values())
    assert jobs["sample"] == len(distinct)
    assert jobs["asperities"] == jobs["interface"] == len(SCENES)
    unloaded = [name for name, (scene, _) in SCENES.items() if "unloading" in scene.get("effects", [])]
    assert jobs["unloading"] == len(unloaded) == 2
    assert set(jobs) == {"sample", "asperities", "unloading", "interface"}, jobs


def test_what_each_effect_puts_in_the_job_specs(counted):
    """The unloaded family computes the reference asperity to LEVELS (+ check) depths; without
    scaling each curvature computes its own; an elastic spec has no unloading level; the
    loading rate enters only a rate-dependent body's spec; adhesion only with the effect."""
    _, _, plans = counted

    def specs(name):
        plan = plans[name]
        return [json.loads(s) for s in plan["spec"].values[plan["job"].values]]

    family = specs("jc_j2_unloading")
    assert len({s["curvature"] for s in family}) == 1
    assert len({s["unloading_level"] for s in family}) == LEVELS + CHECK
    per_curvature = specs("jc_j2_unloading_none")
    assert len({s["curvature"] for s in per_curvature}) == CURVATURES
    np.testing.assert_allclose(sorted({s["curvature"] for s in per_curvature}),
                               plans["jc_j2_unloading_none"]["curvature"].values, rtol=1e-15)
    assert all("unloading_level" not in s and "levels" in s for s in specs("jc_elastic"))
    assert all("velocity" in s for s in specs("jc_bp"))        # rate dependent: the rate is an input
    assert all("velocity" not in s for s in specs("jc_j2"))     # J2: any rate gives the same answer
    # the family of aspects: every job the coupled hill of the reference curvature, its
    # amplitude the aspect over it; the Bodner-Partom family's jobs know the rate
    for name in ("jc_coupled_family", "jc_coupled_family_bp"):
        fam = specs(name)
        assert len({s["curvature"] for s in fam}) == 1 and len({s["height"] for s in fam}) == len(fam)
        assert all(s["mapping"] == "coupled" for s in fam)
    assert all("velocity" in s for s in specs("jc_coupled_family_bp"))
    assert plans["jc_coupled_family_bp"]["left_out"].values.sum() == CHECK
    adhesive = [name for name in SCENES if any("adhesion" in s for s in specs(name))]
    assert adhesive == [name for name, (scene, _) in SCENES.items() if "adhesion" in scene.get("effects", [])]
