"""friction.nc and laws.nc through snakemake on the steel_hertz scene (report 9.1, 10).

One run of the real workflow (on a copy of the workflow files, only the
steel_hertz targets) is shared by the tests of this module; the rerun tests
come last because they edit the copy.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml

from asperity.io.netcdf import missing_attributes, read_dataset, scene_config

from .conftest import copy_workflow, planned_jobs, snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

OUT = "results/steel_hertz"
TARGETS = [f"{OUT}/friction.nc", f"{OUT}/laws.nc", f"{OUT}/figures/friction.png", f"{OUT}/figures/laws.png"]
CONFIG = ["--config", "scenes=[steel_hertz]"]  # last: --config takes every value after it


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    workdir = copy_workflow(tmp_path_factory.mktemp("workflow"))
    snakemake(workdir, *TARGETS, *CONFIG)
    return workdir


def test_friction_numbers_and_units(run):
    """tau_s = 167.2 MPa (the scene's), mu_shear = tau_s A_c / p of interface.nc to 1e-12,
    mu_interlocking = sqrt(2/pi) 0.160 (mean absolute slope), mu their sum."""
    ds = read_dataset(run / OUT / "friction.nc")
    interface = read_dataset(run / OUT / "interface.nc")
    assert missing_attributes(ds) == []
    assert float(ds["junction_shear_strength"]) == pytest.approx(167.2e6, rel=1e-12)
    assert ds["junction_shear_strength"].attrs["units"] == "Pa"
    assert ds["nominal_pressure"].attrs["units"] == "Pa" and ds["mu"].attrs["units"] == "1"
    expected = 167.2e6 * interface["contact_area_ratio"].values / interface["nominal_pressure"].values
    np.testing.assert_allclose(ds["mu_shear"].values, expected, rtol=1e-12)
    assert float(ds["mu_interlocking"]) == pytest.approx(0.16 * math.sqrt(2 / math.pi), rel=1e-12)
    np.testing.assert_allclose(ds["mu"].values, ds["mu_shear"].values + float(ds["mu_interlocking"]), rtol=1e-15)
    # the elastic bound: Hertzian junctions carry far less area per load than the
    # report's elasto-viscoplastic ones (0.093 at 2.2 MPa, Fig. 9.3); 9.1: "a purely
    # elastic approach underestimates the value of the coefficient of friction"
    assert float(ds["mu_shear"].max()) < 0.093 / 10
    # measured values and the report's estimate carried as given (8.37, 8.38, 9.1)
    np.testing.assert_array_equal(ds["measured_mu"].values, [0.215, 0.206])
    assert float(ds["report_mu"]) == 0.253 and float(ds["report_mu_shear"]) == 0.093
    # the tests' 2.195 MPa lies below this scene's computed pressures (>= 10 MPa at 3 sigma)
    assert float(ds["nominal_pressure"].min()) > 2.195e6
    assert np.all(np.isnan(ds["mu_at_measurement"].values))
    assert scene_config(ds)["friction"]["junction_shear_strength"] == 167.2


def test_laws_fit_of_the_steel_interface(run):
    """Oden-Martins and exponential fits in the scene's window [10, 2000] MPa, log residuals:
    the power law reproduces every fitted point within 3 %; the report's fit is carried in SI."""
    ds = read_dataset(run / OUT / "laws.nc")
    assert missing_attributes(ds) == []
    p = ds["nominal_pressure"].values
    window = ds["in_window"].values
    np.testing.assert_array_equal(window, (p >= 10e6) & (p <= 2000e6))
    om = ds["estimate"].sel(law="oden_martins")
    se = ds["standard_error"].sel(law="oden_martins")
    assert float(ds["max_relative_error"].sel(law="oden_martins")) < 0.03
    # the local exponent (a - g) (dp/da) / p of the data brackets the fitted m
    a, k = ds["approach"].values, read_dataset(run / OUT / "interface.nc")["normal_stiffness"].values
    m_local = ((a - float(om.sel(parameter="g"))) * k / p)[window]
    assert m_local.min() <= float(om.sel(parameter="m")) <= m_local.max()
    assert np.all(se.sel(parameter=["c", "g", "m"]).values > 0)
    rep = ds["report_value"].sel(law="oden_martins")
    assert float(rep.sel(parameter="c")) == pytest.approx(15.2e4, rel=1e-15)  # 15.2 N/cm^2 in Pa
    assert float(rep.sel(parameter="m")) == 2.25
    assert ds.attrs["residual"] == "log" and ds.attrs["a0"] == 1e-6
    assert list(ds["parameter_units"].values) == ["Pa", "m", "1", "m"]


def test_figures_are_pngs(run):
    for name in ("friction.png", "laws.png"):
        assert (run / OUT / "figures" / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_nothing_changed_runs_no_job(run):
    assert planned_jobs(snakemake(run, "-n", *TARGETS, *CONFIG)) == {}


def _edit_scene(run, section, key, value):
    path = run / "config" / "scenes" / "steel_hertz.yaml"
    scene = yaml.safe_load(path.read_text())
    scene[section][key] = value
    path.write_text(yaml.safe_dump(scene))


def test_friction_change_reruns_only_friction(run):
    _edit_scene(run, "friction", "junction_shear_strength", 150.0)
    jobs = planned_jobs(snakemake(run, "-n", *TARGETS, *CONFIG))
    assert set(jobs) == {"friction", "friction_figure"}, jobs


def test_laws_change_reruns_only_laws(run):
    snakemake(run, *TARGETS, *CONFIG)  # bring the friction edit up to date
    _edit_scene(run, "laws", "pressure_range", [20.0, 1000.0])
    jobs = planned_jobs(snakemake(run, "-n", *TARGETS, *CONFIG))
    assert set(jobs) == {"laws", "laws_figure"}, jobs
