"""Contact pieces: the C1 penalty law, surface integration, contact edge."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from asperity.fe import CosineHill, Cylinder, Sphere
from asperity.fe.discretization.assembly import Discretization
from asperity.fe.contact.penalty import AugmentedPenalty, C1Penalty, ContactZone, contact_edge
from asperity.fe.discretization.mesh import AsperityMesh, MeshSpec


def test_c1_penalty_is_the_report_law_and_continuously_differentiable():
    law = C1Penalty(kappa=np.array([50.0]), smoothing_pressure=2.0)
    eps = 2.0 / 50.0  # H / kappa
    a = np.array([[-1.0, 0.0, 0.5 * eps, eps, 3 * eps]])
    t, dt = law.traction(a)
    k = 50.0  # the report's H: the slope of the linear branch
    expected = [0, 0, k / (2 * eps) * (0.5 * eps) ** 2, k * eps / 2, k * (3 * eps - eps / 2)]
    np.testing.assert_allclose(t[0], expected, rtol=1e-12)
    # derivative matches finite differences and is continuous at 0 and eps
    x = np.linspace(-2 * eps, 4 * eps, 6001)[None, :]
    t, dt = law.traction(x)
    fd = np.gradient(t[0], x[0])
    np.testing.assert_allclose(fd[1:-1], dt[0, 1:-1], atol=1e-2 * 50)
    assert np.max(np.abs(np.diff(dt[0]))) < 50 * 1.1 * (x[0, 1] - x[0, 0]) / eps


def test_augmented_law():
    law = AugmentedPenalty(kappa=np.array([10.0]), multipliers=np.array([[1.0, 0.0, 1.0]]))
    t, dt = law.traction(np.array([[0.0, -0.1, -0.2]]))
    np.testing.assert_allclose(t, [[1.0, 0.0, 0.0]])
    np.testing.assert_allclose(dt, [[10.0, 0.0, 0.0]])


def _zone(geometry, rule=None, frac=0.5):
    spec = MeshSpec(domain_radius=20 * geometry.extent, apex_size=0.02 * geometry.extent)
    mesh = AsperityMesh.initial(geometry, spec)
    c = mesh.vertices.p[:, mesh.vertices.t].mean(axis=1)
    mesh = mesh.refined(np.nonzero(np.hypot(*c) < geometry.extent)[0])
    disc = Discretization(mesh)
    outer = disc.top.coords[0, 2::2]
    nf = int(np.searchsorted(outer, frac * geometry.extent)) + 1
    return ContactZone(disc.top, nf, geometry, rule), outer[nf - 1]


@pytest.mark.parametrize("rule", ["nodal", "gauss"])
def test_zone_integrates_the_surface_area(rule):
    sphere = Sphere(1.0, cap_angle_deg=60)
    zone, rmax = _zone(sphere, rule)
    ones = np.ones(zone.weights.shape)
    # spherical cap up to radius rmax: area 2 pi R h
    h = 1 - np.sqrt(1 - rmax**2)
    assert zone.total(ones) == pytest.approx(2 * np.pi * h, rel=1e-4)
    # nodal forces of a uniform traction sum to the resultant (without 2 pi)
    assert zone.nodal(ones).sum() == pytest.approx(zone.total(ones) / (2 * np.pi), rel=1e-12)
    # consistent matrix: row sums give the nodal vector
    np.testing.assert_allclose(zone.matrix(ones).sum(axis=1), zone.nodal(ones), atol=1e-14)


def test_plane_strain_zone_counts_both_halves():
    cyl = Cylinder(1.0)
    zone, xmax = _zone(cyl)
    ones = np.ones(zone.weights.shape)
    arc = np.arcsin(xmax)  # arc length of the half section up to xmax
    assert zone.total(ones) == pytest.approx(2 * arc, rel=1e-5)


def test_penetration_is_zero_at_first_touch_apex_and_grows_with_w():
    hill = CosineHill(0.5, 2.0)
    zone, _ = _zone(hill)
    u = np.zeros(zone.ndofs)
    pen = zone.node_penetration(u, 0.0)
    assert pen[0] == 0.0 and np.all(pen[1:] < 0)
    np.testing.assert_allclose(zone.node_penetration(u, 0.1) - pen, 0.1)


@settings(max_examples=60, deadline=None)
@given(a=st.floats(0.2, 0.8), h=st.floats(0.005, 0.05), shift=st.floats(0, 1))
def test_contact_edge_recovers_the_three_halves_law(a, h, shift):
    r = (np.arange(0, 1.0 / h) + shift) * h
    r[0] = 0.0
    gap = np.where(r > a, 0.3 * np.maximum(r - a, 0) ** 1.5, 0.0)
    touching = r <= a
    assert contact_edge(r, gap, touching) == pytest.approx(a, rel=1e-9)


def test_contact_edge_between_nodes_with_penetration():
    r = np.linspace(0, 1, 11)
    gap = np.array([-2e-3, -2e-3, -1e-3, -5e-4, 1e-2, 3e-2, 6e-2, 0.1, 0.15, 0.2, 0.3])
    a = contact_edge(r, gap, gap < 0)
    assert 0.3 <= a <= 0.4
    assert contact_edge(r, np.ones(11), np.zeros(11, bool)) == 0.0
