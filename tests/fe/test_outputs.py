"""The per-step Dataset: variables, units, long names, consistency."""

import numpy as np
import pytest

from asperity.fe import CosineHill, Cylinder, LinearElastic, solve_asperity
from asperity.fe.contact.penalty import EDGE_FROM_GAPS
from asperity.fe.outputs import VARIABLES

from .conftest import HERTZ_W


def test_every_variable_has_units_and_long_name(hertz_standard):
    ds = hertz_standard
    assert set(ds.data_vars) <= set(VARIABLES)
    assert set(ds.data_vars) == {
        "interference", "force", "contact_area", "contact_radius", "normal_stiffness",
        "max_equivalent_strain", "max_von_mises", "elastic", "estimated_error", "dofs",
        "newton_iterations", "step_cuts", "wall_time"}
    for name, var in ds.variables.items():
        assert var.attrs.get("units"), name
        assert var.attrs.get("long_name"), name
    assert ds.sizes["step"] == len(HERTZ_W)
    assert ds.force.attrs["units"] == "N"
    assert ds.contact_area.attrs["units"] == "m^2"
    assert ds.normal_stiffness.attrs["units"] == "N/m"
    assert ds.wall_time.attrs["units"] == "s"
    np.testing.assert_allclose(ds.interference.values, HERTZ_W)
    assert ds.elastic.dtype == bool and ds.elastic.all()  # no yield stress given
    assert np.all(ds.dofs.values == ds.dofs.values[0]) and ds.dofs.values[0] > 1000
    assert np.all(ds.newton_iterations.values >= 1)
    assert np.all(ds.step_cuts.values == 0)
    assert np.all(ds.wall_time.values > 0)
    assert ds.wall_time.sum() == pytest.approx(ds.attrs["total_wall_time"], rel=1e-6)
    assert np.all(ds.estimated_error.values < 0.02)
    for key in ("geometry", "material", "accuracy", "contact", "penalty_factor",
                "normal_stiffness_method", "contact_edge_method"):
        assert key in ds.attrs
    assert ds.attrs["contact_edge_method"] == EDGE_FROM_GAPS


def test_plane_strain_units_are_per_length():
    ds = solve_asperity(Cylinder(1.0), LinearElastic(1000.0, 0.3), [0.002, 0.01], accuracy="draft")
    assert ds.force.attrs["units"] == "N/m"
    assert ds.contact_area.attrs["units"] == "m"
    assert ds.normal_stiffness.attrs["units"] == "N/m^2"
    np.testing.assert_allclose(ds.contact_area.values, 2 * ds.contact_radius.values)
    assert "plane strain" in ds.attrs["symmetry"]


def test_elastic_flag_follows_the_yield_stress():
    hill = CosineHill.from_aspect(10.0, 1e-6)
    w = [1e-8, 5e-8, 2e-7]
    free = solve_asperity(hill, LinearElastic(70e9, 0.33), w, accuracy="draft")
    vm = free.max_von_mises.values
    assert np.all(np.diff(vm) > 0)
    limited = solve_asperity(hill, LinearElastic(70e9, 0.33, yield_stress=float(vm[1]) * 1.01),
                             w, accuracy="draft")
    np.testing.assert_array_equal(limited.elastic.values, [True, True, False])
    # the yield stress only classifies: same answer
    np.testing.assert_allclose(limited.force.values, free.force.values, rtol=1e-12)


def test_untouched_levels_and_order():
    hill = CosineHill(0.5, 2.0)
    mat = LinearElastic(1.0, 0.3)
    ds = solve_asperity(hill, mat, [-0.01, 0.0, 0.02, 0.01], accuracy="draft")
    assert ds.force.values[0] == 0 and ds.force.values[1] == 0
    assert ds.contact_radius.values[0] == 0 and ds.contact_area.values[1] == 0
    assert ds.force.values[2] > ds.force.values[3] > 0
    # elastic: path independent, the order does not matter
    again = solve_asperity(hill, mat, [0.01, 0.02], accuracy="draft")
    np.testing.assert_allclose(ds.force.values[[3, 2]], again.force.values, rtol=1e-6)


@pytest.mark.parametrize("bad", [[], [np.nan], [2.0]])
def test_bad_interferences_are_rejected(bad):
    with pytest.raises(ValueError):
        solve_asperity(CosineHill(0.5, 2.0), LinearElastic(1.0, 0.3), bad)


def test_bad_options_are_rejected():
    hill, mat = CosineHill(0.5, 2.0), LinearElastic(1.0, 0.3)
    with pytest.raises(ValueError, match="accuracy"):
        solve_asperity(hill, mat, [0.01], accuracy="ultra")
    with pytest.raises(ValueError, match="contact"):
        solve_asperity(hill, mat, [0.01], contact="lagrange")
    with pytest.raises(ValueError, match="adapt"):
        solve_asperity(hill, mat, [0.01], adapt="never")
    with pytest.raises(ValueError, match="unknown accuracy keys"):
        solve_asperity(hill, mat, [0.01], accuracy={"colour": 1})


def test_contact_zone_grows_when_the_contact_reaches_it(monkeypatch):
    import asperity.fe.drivers.elastic as solve

    hill, mat = CosineHill.from_aspect(13.4, 1.0), LinearElastic(1.0, 0.3)
    w = [0.02, 0.1]
    ref = solve_asperity(hill, mat, w, accuracy="draft")
    monkeypatch.setattr(solve, "CANDIDATE_FACTOR", 0.3)  # far too small a zone
    grown = solve_asperity(hill, mat, w, accuracy="draft")
    np.testing.assert_allclose(grown.force.values, ref.force.values, rtol=1e-3)
    np.testing.assert_allclose(grown.contact_radius.values, ref.contact_radius.values, rtol=1e-2)
