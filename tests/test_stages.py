"""Stages as functions of data: scene configuration in, SI datasets out."""

import json
import numpy as np
import pytest

from asperity.stages import population as population_stage
from asperity.stages import surface as surface_stage
from asperity.references import hertz
from tests.scene_defaults import filled

UNITS = {"length": "um", "pressure": "MPa"}
STEEL = filled("surface", {"statistics": {
    "sigma": 4.91, "sigma_slope": 0.16, "sigma_curvature": 0.0227,
    "peak_density": 0.000508}})


def test_given_statistics_in_si():
    ds = surface_stage.surface_from_statistics(STEEL, UNITS)
    assert float(ds["sigma"].sel(estimator="given")) == pytest.approx(4.91e-6)
    assert float(ds["sigma_curvature"].sel(estimator="given")) == pytest.approx(0.0227e6)
    assert float(ds["peak_density"].sel(estimator="given")) == pytest.approx(508e6)
    # beta = sqrt(1.5) sigma_slope^2 / (sigma sigma_curvature) (2.4.1)
    assert float(ds["beta"].sel(estimator="given")) == pytest.approx(
        np.sqrt(1.5) * 0.16**2 / (4.91 * 0.0227), rel=1e-12)


def test_plan_and_per_sample_response_agree_with_gathered():
    surface = surface_stage.surface_from_statistics(STEEL, UNITS)
    mat = {"youngs_modulus": 209000.0, "poisson": 0.3}
    plan = population_stage.plan_dataset(
        surface, filled("population", {"samples": {"height": 3, "curvature": 4, "interference": 20}}),
        filled("asperity", {"model": "hertz"}), filled("material", mat), [], UNITS, "standard")
    assert plan.sizes["sample"] == 12
    asperities = population_stage.asperities_dataset(plan)
    key = str(plan["key"].values[5])
    one = population_stage.sample_dataset(json.loads(str(plan["spec"].values[5])), key)
    k = one.attrs["curvature"]
    np.testing.assert_allclose(one["force"].values,
                               asperities["force"].sel(curvature=k).isel(height=0).values, rtol=1e-14)
    direct = hertz.hertz_response(plan["interference"].values, k, 209e9, 0.3)["force"]
    np.testing.assert_allclose(one["force"].values, direct, rtol=1e-14)
    assert one.attrs["key"] == key


def test_synthetic_map_statistics():
    gen = {"points": 128, "spacing": 1.0, "sigma": 2.0, "correlation_length": 8.0, "seed": 3, "aspect": 1.0}
    z = surface_stage.synthetic_map(gen)
    assert z.shape == (128, 128)
    assert z.std() == pytest.approx(2.0, rel=1e-12)
    assert abs(z.mean()) < 1e-12


def test_map_peak_density_matches_nayak():
    """A Gaussian isotropic map with autocorrelation exp(-r^2/l^2) has m2 = 2 sigma^2/l^2,
    m4 = 12 sigma^2/l^4, so D_p = m4/(6 pi sqrt3 m2) = 1/(pi sqrt3 l^2) (2.3.1).
    ~490 peaks: the Poisson spread is 4.5 %; bound 10 %."""
    gen = {"points": 512, "spacing": 2.0, "sigma": 1.0, "correlation_length": 20.0, "seed": 7, "aspect": 1.0}
    ds = surface_stage.surface_from_data(surface_stage.synthetic_map(gen), (2.0, 2.0), {"map": {"generate": gen}},
                                         {"length": "m"})
    expected = 1.0 / (np.pi * np.sqrt(3) * 20.0**2)
    assert float(ds["peak_density"]) == pytest.approx(expected, rel=0.10)
    # isotropic: 3 m22 = m40 = m04 (2.3.1), within the sampling spread of one map
    assert float(ds["m40"]) == pytest.approx(float(ds["m04"]), rel=0.10)
    assert 3 * float(ds["m22"]) == pytest.approx(float(ds["m40"]), rel=0.10)


FE_SPHERE = filled("asperity", {"model": "fe", "geometry": "sphere", "scaling": "none"})
STEEL_E = {"youngs_modulus": 209000.0, "poisson": 0.3}


def _fe_plan(population=None, material=STEEL_E, accuracy="draft"):
    surface = surface_stage.surface_from_statistics(STEEL, UNITS)
    population = population or {"samples": {"height": 3, "curvature": 4, "interference": 20}}
    return population_stage.plan_dataset(surface, filled("population", population), FE_SPHERE,
                                         filled("material", material), [], UNITS, accuracy)


def test_keys_hash_what_the_job_depends_on_only():
    """Two scenes that need the same asperity share its job (issue 6): more height
    samples or another homogenization leave the FE jobs' keys alone; a material
    constant or the preset changes every key."""
    plan = _fe_plan()
    keys = set(plan["key"].values)
    assert len(keys) == 4  # one job per curvature, heights derived by a shift
    more_heights = _fe_plan({"samples": {"height": 7, "curvature": 4, "interference": 20}})
    assert set(more_heights["key"].values) == keys
    assert set(_fe_plan(material={**STEEL_E, "youngs_modulus": 200000.0})["key"].values).isdisjoint(keys)
    assert set(_fe_plan(accuracy="standard")["key"].values).isdisjoint(keys)
    spec = json.loads(str(plan["spec"].values[0]))
    assert "height" not in spec and spec["material"]["youngs_modulus"] == 209e9
    from asperity.population.plan import sample_key
    assert sample_key(spec) == str(plan["key"].values[0])


def test_a_failed_sample_is_recorded_and_the_gather_names_it(monkeypatch):
    """A job that fails leaves a record naming sample and step; the gather refuses
    to homogenize over the hole and names it."""
    from asperity import fe
    from asperity.population.gather import gather

    plan = _fe_plan()
    keys = [str(k) for k in np.unique(plan["key"].values)]
    specs = {str(k): json.loads(str(s)) for k, s in zip(plan["key"].values, plan["spec"].values)}

    def fail(*args, **kwargs):
        raise fe.ConvergenceError(step=3, interference=1e-7, reached=5e-8, cuts=8)

    monkeypatch.setattr(fe, "solve_asperity", fail)
    record = population_stage.sample_dataset(specs[keys[0]], keys[0])
    assert record.attrs["status"] == "failed" and "step 3" in record.attrs["error"]
    assert keys[0] in record.attrs["error"]
    with pytest.raises(ValueError, match=rf"4 of 4 samples missing.*{keys[0]}.*step 3"):
        gather(plan, {keys[0]: record})
