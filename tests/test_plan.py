"""The plan: sample grid, keys that hash exactly what a job depends on, derived samples."""

import numpy as np
import pytest

from asperity.population.plan import interference_grid, job_keys, make_plan, sample_grid, sample_key

JOB = {"material": {"youngs_modulus": 2e11, "poisson": 0.3}, "effects": [], "accuracy": "standard"}


def spec_of(job, shift_invariant=True):
    """A job spec: `job` with the curvature (and the height where the response depends on it)."""
    return lambda h, k, level: {**job, "curvature": k, **({} if shift_invariant else {"height": h})}


def test_key_is_stable_and_sensitive():
    assert sample_key({"a": 1.0, "b": [1, 2]}) == sample_key({"b": [1, 2], "a": 1.0})
    assert sample_key({"a": 1.0}) != sample_key({"a": 1.0 + 1e-15})  # floats hashed exactly
    assert len(sample_key({"a": 1})) == 12


def test_interference_grid_geometric_from_zero():
    w = interference_grid(2e-6, 101)
    assert w[0] == 0.0 and w[-1] == pytest.approx(2e-6, rel=1e-15)
    ratios = w[2:] / w[1:-1]
    np.testing.assert_allclose(ratios, ratios[0], rtol=1e-12)  # constant ratio
    assert w[1] == pytest.approx(2e-11, rel=1e-12)
    with pytest.raises(ValueError, match="positive"):
        interference_grid(0.0, 10)


def test_sample_grid_avoids_zero_curvature():
    k = sample_grid(0.0, 10.0, 11, positive=True)
    assert k[0] == pytest.approx(0.5) and k[-1] == 10.0
    assert sample_grid(1.0, 3.0, 1) == pytest.approx([2.0])


def test_shift_invariant_model_derives_heights():
    plan = make_plan(np.linspace(-1, 1, 5), [1.0, 2.0, 3.0], interference_grid(1.0, 8),
                     model="hertz", job_spec=spec_of(JOB), shift_invariant=True, analytic=True)
    keys = plan["key"].values.reshape(5, 3)
    assert all(len(set(keys[:, j])) == 1 for j in range(3))  # one key per curvature
    assert len(set(keys.ravel())) == 3
    assert (plan["derived_from"].values != "").sum() == 12
    assert job_keys(plan) == []  # analytic: no job


def test_height_dependent_model_gets_a_job_per_sample():
    plan = make_plan(np.linspace(-1, 1, 4), [1.0, 2.0], interference_grid(1.0, 8),
                     model="fe", job_spec=spec_of(JOB, False), shift_invariant=False,
                     analytic=False)
    assert len(set(plan["key"].values)) == 8
    assert len(job_keys(plan)) == 8
    other = make_plan(np.linspace(-1, 1, 4), [1.0, 2.0], interference_grid(1.0, 8),
                      model="fe", job_spec=spec_of({**JOB, "accuracy": "fine"}, False),
                      shift_invariant=False, analytic=False)
    assert set(other["key"].values).isdisjoint(plan["key"].values)


def test_geometric_levels_are_numpys_geomspace_and_refuse_non_positive_ends():
    from asperity.population.plan import geometric_levels

    levels = geometric_levels(3.7e-10, 2.9e-5, 240)
    np.testing.assert_allclose(levels, np.geomspace(3.7e-10, 2.9e-5, 240), rtol=4e-16, atol=0)
    assert levels[0] == 3.7e-10 and levels[-1] == 2.9e-5
    for start, stop in ((0.0, 1.0), (-1.0, 1.0), (1.0, 0.0)):
        with pytest.raises(ValueError, match="start, stop > 0"):
            geometric_levels(start, stop, 4)
