"""Verification against Hertz (report 6.1: R = 1, E = 1000, nu = 0.3).

The report's own FE errors were up to 17.5 % in load and 5 % in contact
radius (its Fig. 6.5).  Required here: the paraboloid (Hertz's
idealization: half space with a paraboloidal gap) within 1 % in load and
2 % in contact radius at every point at `standard`, within 0.3 % in load
at `fine`; the sphere and the curved paraboloid body differ from Hertz by
their own geometry (a / R up to 0.14) and get looser bounds.
"""

import numpy as np
import pytest

from asperity.fe import LinearElastic, Paraboloid, hertz, solve_asperity

from .conftest import HERTZ_MATERIAL, HERTZ_W


def _errors(ds):
    ref = hertz(1.0, HERTZ_MATERIAL, ds.interference.values)
    return (ds.force.values / ref["force"] - 1,
            ds.contact_radius.values / ref["contact_radius"] - 1,
            ds.normal_stiffness.values / ref["normal_stiffness"] - 1)


def test_paraboloid_standard_within_1_percent_load_2_percent_radius(hertz_standard):
    load, radius, stiffness = _errors(hertz_standard)
    assert np.all(np.abs(load) < 0.01), load
    assert np.all(np.abs(radius) < 0.02), radius
    # measured: load and radius within 0.2 %, stiffness within 1 %
    assert np.all(np.abs(load) < 0.003), load
    assert np.all(np.abs(radius) < 0.005), radius
    assert np.all(np.abs(stiffness) < 0.02), stiffness
    area = hertz_standard.contact_area.values
    np.testing.assert_allclose(area, np.pi * hertz_standard.contact_radius.values**2)


def test_exact_contact_option_agrees_with_hertz():
    ds = solve_asperity(Paraboloid(1.0), HERTZ_MATERIAL, HERTZ_W, contact="exact")
    load, radius, stiffness = _errors(ds)
    assert np.all(np.abs(load) < 0.01) and np.all(np.abs(radius) < 0.02)
    assert ds.attrs["contact"] == "exact"


def test_sphere_standard_reported_beside(sphere_standard):
    load, radius, _ = _errors(sphere_standard)
    # a sphere is softer than Hertz's half space as the contact grows
    # (measured -0.5 % at w = 0.001 to -1.4 % at w = 0.02 in load)
    assert np.all(np.abs(load) < 0.03), load
    assert np.all(np.abs(radius) < 0.02), radius
    assert np.all(np.diff(load) < 0.002)  # departs from Hertz as a / R grows


def test_curved_paraboloid_body_is_close_but_softer():
    ds = solve_asperity(Paraboloid(1.0, shallow=False), HERTZ_MATERIAL, HERTZ_W, accuracy="draft")
    load, radius, _ = _errors(ds)
    assert np.all(load < 0) and np.all(load > -0.02), load
    assert np.all(np.abs(radius) < 0.02), radius


def test_draft_is_coarser_but_close():
    ds = solve_asperity(Paraboloid(1.0), HERTZ_MATERIAL, HERTZ_W, accuracy="draft")
    load, radius, _ = _errors(ds)
    assert np.all(np.abs(load) < 0.02) and np.all(np.abs(radius) < 0.03)


def test_paraboloid_fine_within_0_3_percent_load():
    ds = solve_asperity(Paraboloid(1.0), HERTZ_MATERIAL, HERTZ_W, accuracy="fine")
    load, radius, _ = _errors(ds)
    assert np.all(np.abs(load) < 0.003), load
    assert np.all(np.abs(radius) < 0.005), radius


def test_long_hertz_curve_on_one_shared_mesh():
    w = np.linspace(0.0005, 0.02, 40)
    ds = solve_asperity(Paraboloid(1.0), HERTZ_MATERIAL, w)
    load, radius, stiffness = _errors(ds)
    assert np.all(np.abs(load) < 0.005), load
    assert np.all(np.abs(radius) < 0.01), radius
    # consistent tangent against a difference quotient of the forces
    fd = np.gradient(ds.force.values, w)[1:-1]
    np.testing.assert_allclose(ds.normal_stiffness.values[1:-1], fd, rtol=0.03)
    assert np.all(np.diff(ds.force.values) > 0) and np.all(np.diff(ds.contact_radius.values) > 0)


def test_per_level_meshes():
    ds = solve_asperity(Paraboloid(1.0), HERTZ_MATERIAL, HERTZ_W[::2], adapt="per_level",
                        accuracy="draft")
    load, radius, _ = _errors(ds)
    assert np.all(np.abs(load) < 0.02) and np.all(np.abs(radius) < 0.03)
    assert ds.attrs["mesh_strategy"] == "per_level"


def test_hertz_is_scale_free_in_E():
    soft = solve_asperity(Paraboloid(1.0), LinearElastic(1.0, 0.3), [0.01], accuracy="draft")
    stiff = solve_asperity(Paraboloid(1.0), LinearElastic(1e9, 0.3), [0.01], accuracy="draft")
    assert stiff.force.item() / soft.force.item() == pytest.approx(1e9, rel=1e-9)
    assert stiff.contact_radius.item() == pytest.approx(soft.contact_radius.item(), rel=1e-9)
