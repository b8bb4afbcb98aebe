"""How a sample becomes a response: representative hills, FE levels, and the gather onto
the plan's grid (asperity.population.geometry, .gather, .kinds)."""

import math

import numpy as np
import pytest
import xarray as xr

from asperity.population import gather as gathering
from asperity.population import geometry
from asperity.population import samples as population
from asperity.population.kinds import KINDS, Planning, SampleFailed
from asperity.population.plan import interference_grid, make_plan
from asperity.references import hertz
from asperity.scene import Asperity, Material, Units
from tests.scene_defaults import filled


def asperity(**section) -> Asperity:
    """The scene's asperity section with the schema's defaults, as the workflow reads it."""
    return Asperity.from_section(filled("asperity", section), Units("m", "Pa"))


def BY_CURVATURE(height, curvature, level):
    """The job spec of a sphere whose response depends on its curvature only."""
    return {"model": "fe", "curvature": curvature}


def test_representative_hill_has_the_surface_rms_slope_and_the_sample_curvature():
    """8.2: width/height = pi/(sqrt2 sigma_slope); 2.5.1: kappa = C k^2."""
    ratio = geometry.representative_width_to_height(0.13)
    hill = geometry.fe_geometry("cosine", False, 0.018e6, ratio)
    assert hill.tip_curvature == pytest.approx(0.018e6, rel=1e-12)
    # rms slope of C cos(k s) is k C / sqrt2
    assert hill.wavenumber * hill.amplitude / math.sqrt(2) == pytest.approx(0.13, rel=1e-12)


def _fake_sample(key, curvature, levels):
    """A 'FE' sample that is exactly Hertz, to test the gather's interpolation."""
    r = hertz.hertz_response(levels, curvature, 2e11, 0.3)
    ds = xr.Dataset({name: ("step", r[src]) for name, src in
                     (("force", "force"), ("contact_area", "contact_area"),
                      ("contact_radius", "contact_radius"), ("normal_stiffness", "stiffness"))})
    ds["interference"] = ("step", levels)
    ds["elastic"] = ("step", levels < 1e-7)  # yields between the levels around 1e-7
    ds["max_equivalent_strain"] = ("step", 0.1 * levels / 0.25e-6)  # 8 % at 0.2 um
    ds.attrs["key"] = key
    return ds


def test_gather_reproduces_a_power_law_between_and_below_levels():
    grid = interference_grid(1e-6, 121)
    plan = make_plan([0.0, 1e-6], [1e5, 2e5], grid, model="fe", job_spec=BY_CURVATURE,
                     shift_invariant=True, analytic=False)
    keys = dict(zip(plan["sample_curvature"].values, plan["key"].values))
    levels = np.geomspace(grid[5], 0.5e-6, 40)  # FE range ends at half the grid
    samples = {k: _fake_sample(k, c, levels) for c, k in keys.items()}
    gathered = gathering.gather(plan, samples)
    exact = hertz.hertz_asperities([0.0, 1e-6], [1e5, 2e5], grid, 2e11, 0.3)
    inside = grid <= levels[-1]
    # log-log monotone cubic on 40 levels per 3.7 decades; power law below: 1e-10
    np.testing.assert_allclose(gathered["force"].values[..., inside],
                               exact["force"].values[..., inside], rtol=1e-10, atol=0)
    assert not gathered["extrapolated"].values[..., inside].any()
    assert gathered["extrapolated"].values[..., ~inside].all()
    # beyond: the last tangent, a lower bound of the convex w^1.5
    beyond = gathered["force"].values[..., ~inside]
    assert np.all(beyond <= exact["force"].values[..., ~inside] * (1 + 1e-12))
    # the elastic and small-strain indicators switch midway between the steps around the limit
    for name, limit in (("elastic", 1e-7), ("small_strain", 0.2e-6)):
        i = np.searchsorted(levels, limit)
        switch = 0.5 * (levels[i - 1] + levels[i])
        expected = ((grid > 0) & (grid < switch)).astype(float)
        np.testing.assert_array_equal(gathered[name].values, np.broadcast_to(expected, gathered[name].shape))


def test_below_its_first_level_an_asperity_touches_as_hertz():
    """An inelastic job's first levels sit on the apex's elements: two equal areas, whose
    power law was flat (2000 times Hertz's area at the smallest interference of
    smooth_aluminum). Below its first level the gather follows Hertz's first touch
    through it (area ~ w, force ~ w^1.5, radius and stiffness ~ w^0.5), exactly."""
    grid = interference_grid(1e-6, 121)
    plan = make_plan([0.0, 1e-6], [1e5, 2e5], grid, model="fe", job_spec=BY_CURVATURE,
                     shift_invariant=True, analytic=False)
    keys = dict(zip(plan["sample_curvature"].values, plan["key"].values))
    levels = np.geomspace(grid[40], 0.5e-6, 30)  # the first level well inside the grid
    samples = {}
    for c, k in keys.items():
        ds = _fake_sample(k, c, levels)
        area, force = ds["contact_area"].values.copy(), ds["force"].values.copy()
        area[0] = area[1]  # the apex's elements: the same area at the first two levels
        force[0] = 0.9 * force[1] * (levels[0] / levels[1]) ** 1.5
        samples[k] = ds.assign(contact_area=("step", area), force=("step", force))
    gathered = gathering.gather(plan, samples)
    below = (grid > 0) & (grid < levels[0])
    for c, k in keys.items():
        one = gathered.sel(curvature=c).isel(height=0)
        first = samples[k].isel(step=0)
        for name, p in (("contact_area", 1.0), ("force", 1.5), ("contact_radius", 0.5),
                        ("stiffness", 0.5)):
            expected = float(first[name if name != "stiffness" else "normal_stiffness"]) \
                * (grid[below] / levels[0]) ** p
            np.testing.assert_allclose(one[name].values[below], expected, rtol=1e-12)


def test_kinks_vanish_along_a_power_law_and_measure_a_bump():
    """`largest_kink`: the value over the log-log line through its neighbours, less 1. Along
    a power law it is round-off on any spacing; a point bumped by 3 % (where the contact
    edge of a job crosses a coarser element) reads 3 %, once it lies past KINK_FROM of the
    largest interference."""
    w = np.sort(np.random.default_rng(3).uniform(1e-9, 1e-6, 40))
    y = 3.0 * w**1.5
    assert gathering.largest_kink(w, y, start=0.0) < 1e-12
    late, early = np.flatnonzero(w >= 0.5e-6)[1], np.flatnonzero(w < 0.05e-6)[1]
    bumped = y.copy()
    bumped[late] *= 1.03
    assert gathering.largest_kink(w, bumped) == pytest.approx(0.03, rel=1e-9)
    bumped = y.copy()
    bumped[early] *= 1.03
    assert gathering.largest_kink(w, bumped) < 1e-12  # before a tenth of the range
    assert gathering.largest_kink(w, bumped, start=0.0) == pytest.approx(0.03, rel=1e-9)
    # a zero area at first touch makes its neighbour's kink undefined: left out
    bumped = y.copy()
    bumped[late] *= 1.03
    bumped[0] = 0.0
    assert gathering.largest_kink(w, bumped, start=0.0) == pytest.approx(0.03, rel=1e-9)


def test_the_gather_reports_how_much_its_jobs_curves_kink(caplog):
    """asperities.nc carries the largest kink of the FE jobs' force and area from a tenth
    of their range on, and the log says it with what refines it (for elastic jobs a finer
    preset: the edge band is for plastic contact edges)."""
    grid = interference_grid(1e-6, 121)
    plan = make_plan([0.0, 1e-6], [1e5, 2e5], grid, model="fe", job_spec=BY_CURVATURE,
                     shift_invariant=True, analytic=False)
    keys = dict(zip(plan["sample_curvature"].values, plan["key"].values))
    levels = np.geomspace(grid[5], 0.5e-6, 40)
    samples = {k: _fake_sample(k, c, levels) for c, k in keys.items()}
    smooth = gathering.gather(plan, samples)
    assert smooth.attrs["max_kink_force"] < 1e-12  # Hertz: power laws
    assert smooth.attrs["max_kink_contact_area"] < 1e-12
    assert smooth.attrs["kink_from"] == gathering.KINK_FROM
    key = plan["key"].values[0]
    area = samples[key]["contact_area"].values.copy()
    area[35] *= 1.03  # levels[35] is at 0.34 of the job's range
    samples[key] = samples[key].assign(contact_area=("step", area))
    with caplog.at_level("INFO", logger="asperity"):
        bumped = gathering.gather(plan, samples)
    assert bumped.attrs["max_kink_contact_area"] == pytest.approx(0.03, rel=1e-9)
    assert bumped.attrs["max_kink_force"] < 1e-12
    assert ("kink from step to step by up to 0.0 % in force and 3.0 % in contact area (from "
            "0.1 of each job's largest interference on); a finer accuracy preset") in caplog.text
    # inelastic jobs (histories: a time step) without the band are told of the band
    histories = {k: ds.assign(time_step=("step", np.ones(levels.size)))
                 for k, ds in samples.items()}
    caplog.clear()
    with caplog.at_level("INFO", logger="asperity"):
        gathering.gather(plan, histories)
    assert "asperity: {edge_band: true} refines the mesh where the plastic contact edge goes" \
        in caplog.text


def test_gather_names_missing_samples():
    grid = interference_grid(1e-6, 20)
    plan = make_plan([0.0], [1e5, 2e5], grid, model="fe", job_spec=BY_CURVATURE,
                     shift_invariant=True, analytic=False)
    with pytest.raises(ValueError, match="2 samples missing"):
        gathering.gather(plan, {})


def test_fe_failure_names_sample_and_step(monkeypatch):
    """A sample whose Newton iterations fail even with step cutting stops its job
    with a message naming the sample (key, curvature) and the step."""
    from asperity import fe

    def fail(*args, **kwargs):
        raise fe.ConvergenceError(step=7, interference=3e-7, reached=1e-7, cuts=8)

    monkeypatch.setattr(fe, "solve_asperity", fail)
    planning = Planning(asperity=asperity(model="fe", geometry="sphere"),
                        material=Material(model="elastic", youngs_modulus=2e11, poisson=0.3),
                        effects=frozenset(), accuracy="draft", adhesion=None,
                        grid=interference_grid(1e-6, 20), family=None, width_to_height=None)
    spec = KINDS["elastic"].spec(planning, None, 1e5, math.nan)
    with pytest.raises(SampleFailed, match=r"sample abc \(curvature 100000 1/m\).*step 7"):
        population.solve(spec, "abc")


def test_fe_range_stops_short_of_the_foot_of_sphere_and_paraboloid():
    """A sphere's 45-degree cap is 0.293 R high, the paraboloid's R / 8: the largest
    interference is `max_radius_fraction` R, capped at 0.9 of that height."""
    from asperity import fe

    sphere = asperity(model="fe", geometry="sphere")
    assert geometry.max_interference(fe.Sphere(2.0), sphere) == pytest.approx(0.5, rel=1e-15)
    assert geometry.max_interference(fe.Sphere(2.0), asperity(model="fe", geometry="sphere", max_radius_fraction=0.5)) == \
        pytest.approx(0.9 * 2.0 * (1 - 2**-0.5), rel=1e-12)
    assert geometry.max_interference(fe.Paraboloid(2.0), sphere) == pytest.approx(0.9 * 0.25, rel=1e-12)


def test_tail_slope_ignores_one_jumping_step():
    """Beyond its last level a curve continues with the median step slope over the last
    10 % of its range: a force jump in one step (an inelastic contact node snapping onto
    the flat, seen on steel_glass_bead_representative at standard) does not set it; a
    straight line's slope is kept exactly."""
    w = np.linspace(1.0, 2.0, 41)
    line = 3.0 + 0.5 * w
    assert gathering.tail_slope(w, line) == pytest.approx(0.5, rel=1e-12)
    jumped = line.copy()
    jumped[-2:] += 0.4  # a jump between the third- and second-to-last level
    assert gathering.tail_slope(w, jumped) == pytest.approx(0.5, rel=1e-12)
    # a geometric elastic sequence: only the last step lies in the window (its last tangent)
    g = np.geomspace(1e-3, 1.0, 40)
    assert gathering.tail_slope(g, g**1.5) == pytest.approx((1 - g[-2] ** 1.5) / (1 - g[-2]), rel=1e-12)


@pytest.mark.parametrize("kind, effects", [("elastic", set()), ("adhesive", {"adhesion"}),
                                           ("hertz", set())])
def test_finite_strain_is_refused_without_plasticity(kind, effects):
    """The finite-strain kinematics are the inelastic asperity's; elsewhere the effect is an
    error naming it, not silently dropped."""
    material = Material("elastic", youngs_modulus=2e11, poisson=0.3)
    with pytest.raises(ValueError, match="effect `finite_strain` needs an FE asperity with "
                                         "effect `plasticity`"):
        KINDS[kind].check(asperity(model="fe", geometry="sphere"), material,
                          frozenset(effects | {"finite_strain"}))
    # with plasticity it is accepted, and it reaches the job as its kinematics
    from asperity.scene import kinematics
    steel = Material("j2", youngs_modulus=2e11, poisson=0.3, yield_stress=4e8)
    KINDS["inelastic"].check(asperity(model="fe", geometry="sphere"), steel,
                             frozenset({"plasticity", "finite_strain"}))
    assert kinematics(["finite_strain", "plasticity"]) == "finite"
    assert kinematics(["plasticity"]) == "small"
