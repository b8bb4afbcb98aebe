"""The Hertz accuracy study (report 6.1) and its figure.

One study run (module scope): the three presets for both bodies, the first
three members of the default refinement sequence, penalty factors 100 and
1000.  About 8 s on 2 shared cores.
"""

import numpy as np
import pytest

from asperity.studies.hertz import DEFAULT_REFINEMENT, hertz_accuracy_study

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def study():
    return hertz_accuracy_study(refinement=DEFAULT_REFINEMENT[:3],
                                penalty_factors=(100.0, 1000.0))


def test_layout(study):
    assert list(study["run"].values) == ["draft", "standard", "fine",
                                         "refine-1", "refine-2", "refine-3"]
    assert list(study["body"].values) == ["paraboloid", "sphere"]
    assert list(study["kind"].values) == ["preset"] * 3 + ["refinement"] * 3
    assert study.sizes["step"] == 5 and study.sizes["penalty_factor"] == 2
    assert study["force"].dims == ("body", "run", "step")
    # the sphere is run for the presets only
    sphere = study.sel(body="sphere")
    assert np.all(np.isnan(sphere.force.sel(run=["refine-1", "refine-2", "refine-3"])))
    assert np.all(np.isfinite(sphere.force.sel(run=["draft", "standard", "fine"])))
    assert np.all(study.wall_time.sel(body="paraboloid") > 0)
    np.testing.assert_allclose(study.max_force_error,
                               np.abs(study.force_error).max("step"))
    assert study.attrs["report_max_force_error"] == pytest.approx(0.175, abs=0.001)
    assert study.attrs["report_max_radius_error"] == pytest.approx(0.053, abs=0.001)


def test_paraboloid_preset_errors(study):
    p = study.sel(body="paraboloid")
    assert float(p.max_force_error.sel(run="standard")) < 0.01
    assert float(p.max_radius_error.sel(run="standard")) < 0.02
    assert float(p.max_force_error.sel(run="fine")) < 0.003
    # the presets are ordered
    e = p.max_force_error.sel(run=["draft", "standard", "fine"]).values
    assert np.all(np.diff(e) < 0), e
    d = p.dofs.sel(run=["draft", "standard", "fine"]).values
    assert np.all(np.diff(d) > 0), d


def test_sphere_differs_by_geometry(study):
    s = study.sel(body="sphere", run="fine")
    # softer than Hertz's half space, more so as a / R grows
    assert np.all(s.force_error < 0) and float(s.max_force_error) < 0.03


def test_errors_fall_along_the_refinement(study):
    runs = ["refine-1", "refine-2", "refine-3"]
    p = study.sel(body="paraboloid", run=runs)
    load, radius = p.max_force_error.values, p.max_radius_error.values
    assert load[-1] < load[0], load
    assert radius[-1] < radius[0], radius
    assert np.all(np.diff(p.dofs.values) > 0)


def test_penalty_error_falls_as_one_over_factor(study):
    f = study.penalty_force_error.sel(penalty_factor=[100.0, 1000.0]).values
    r = study.penalty_radius_error.sel(penalty_factor=[100.0, 1000.0]).values
    assert 3 < f[0] / f[1] < 30, f
    assert 3 < r[0] / r[1] < 30, r
    assert np.all(study.penalty_wall_time > 0) and float(study.exact_wall_time) > 0


def test_units_and_long_names_everywhere(study):
    for name, v in {**study.data_vars, **study.coords}.items():
        assert "units" in v.attrs, name
        assert v.attrs.get("long_name"), name
    for key in ("reference", "material", "radius"):
        assert key in study.attrs


def test_figure_has_three_panels(study):
    import matplotlib.pyplot as plt

    from asperity.plots.accuracy_hertz import accuracy_figure

    fig = accuracy_figure(study)
    try:
        assert len(fig.axes) == 3
        assert all(ax.get_xscale() == "log" and ax.get_yscale() == "log" for ax in fig.axes)
    finally:
        plt.close(fig)


def test_rejects_bad_arguments():
    with pytest.raises(ValueError):
        hertz_accuracy_study(presets=("nope",), refinement=(), penalty_factors=())
    with pytest.raises(ValueError):
        hertz_accuracy_study(interferences=(), refinement=(), penalty_factors=())
