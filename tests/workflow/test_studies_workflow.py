"""The report's studies that are no scene run by rules of their own (workflow/rules/studies.smk):
Fig. 7.6's adhesion curves, a target outside `rule all`."""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from asperity.io.netcdf import missing_attributes, read_dataset, scene_config
from asperity.studies.adhesion import smooth_aluminum_curves

from .conftest import planned_jobs, snakemake

pytestmark = [pytest.mark.workflow]

#: two small radii and a shallow approach keep the run to seconds (Tabor parameters 1.9, 2.4)
SMALL = {"radii": [1e-6, 2e-6], "max_interference": 2e-9}


def test_adhesion_curves_rule_writes_what_the_study_computes(workflow_copy):
    path = workflow_copy / "config" / "config.yaml"
    config = yaml.safe_load(path.read_text())
    assert "adhesion_curves" not in planned_jobs(snakemake(workflow_copy, "-n"))  # not in rule all
    config["adhesion_curves"].update(SMALL)
    path.write_text(yaml.safe_dump(config))
    snakemake(workflow_copy, "adhesion_curves")
    out = workflow_copy / "results" / "studies"
    ds = read_dataset(out / "adhesion_curves.nc")
    assert missing_attributes(ds) == []
    assert scene_config(ds)["adhesion_curves"]["radii"] == SMALL["radii"]
    assert (out / "adhesion_curves.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the same numbers as the study called directly with the config's values
    direct = smooth_aluminum_curves(radii=tuple(SMALL["radii"]), d=0.3e-9, dgamma=1.0,
                                    w_max=SMALL["max_interference"], accuracy="draft")
    for name in ("pull_off_force", "pull_off_interference", "tabor_parameter", "pull_off_force_dmt"):
        np.testing.assert_array_equal(ds[name].values, direct[name].values, err_msg=name)
    valid = ds["valid"].values
    np.testing.assert_array_equal(ds["force"].values[valid], direct["force"].values[valid])
    # and a second run plans nothing
    assert planned_jobs(snakemake(workflow_copy, "-n", "adhesion_curves")) == {}
