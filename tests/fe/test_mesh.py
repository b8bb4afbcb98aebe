"""Meshes: graded, curved top on the true profile, valid after refinement."""

import numpy as np
import pytest

from asperity.fe import CosineHill, Paraboloid, Sphere, TruncatedV
from asperity.fe.discretization.assembly import Discretization
from asperity.fe.discretization.mesh import AsperityMesh, MeshSpec, project_to_profile, ring_radii

GEOMETRIES = [
    Sphere(1.0),
    Paraboloid(1.0, shallow=False),
    CosineHill.from_aspect(2.0, 1.0),   # steep
    CosineHill.from_aspect(100.0, 1.0),  # flat
    TruncatedV(0.1, 1.0),
]


def _mesh(geometry, refinements=2):
    spec = MeshSpec(domain_radius=50 * geometry.extent, apex_size=0.02 * geometry.extent)
    mesh = AsperityMesh.initial(geometry, spec)
    for _ in range(refinements):
        c = mesh.vertices.p[:, mesh.vertices.t].mean(axis=1)
        near = np.hypot(c[0], c[1]) < 0.5 * geometry.extent
        mesh = mesh.refined(np.nonzero(near)[0][::2])
    return mesh


def test_ring_radii_are_graded_and_hold_the_kinks():
    spec = MeshSpec(domain_radius=100.0, apex_size=0.01, growth=1.3)
    r = ring_radii(spec, kinks=(0.5, 2.0))
    assert r[0] == pytest.approx(0.01) and r[-1] == pytest.approx(100.0)
    assert np.all(np.diff(r) > 0)
    assert 0.5 in r and 2.0 in r
    ratios = r[1:] / r[:-1]
    assert ratios.max() < 1.3**2


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: type(g).__name__)
def test_top_nodes_lie_on_the_profile_after_refinement(geometry):
    mesh = _mesh(geometry)
    disc = Discretization(mesh)
    r, z = disc.top.coords
    # vertices and mid-side nodes of the top surface on the true curve
    np.testing.assert_allclose(z, geometry.body_surface(r), atol=1e-12 * geometry.extent)
    assert np.all(np.diff(r) > 0)  # ordered chain from the apex outward
    assert r[0] == 0.0
    # mid-side nodes sit on the perpendicular bisector of their chord
    a, m, b = disc.top.coords[:, 0:-1:2], disc.top.coords[:, 1::2], disc.top.coords[:, 2::2]
    da = np.hypot(*(m - a))
    db = np.hypot(*(m - b))
    np.testing.assert_allclose(da, db, rtol=1e-6)
    for kink in geometry.kinks:
        if kink < mesh.domain_radius:
            assert np.min(np.abs(r[0::2] - kink)) < 1e-12 * geometry.extent


@pytest.mark.parametrize("geometry", GEOMETRIES, ids=lambda g: type(g).__name__)
def test_elements_are_valid(geometry):
    mesh = _mesh(geometry)
    disc = Discretization(mesh)
    assert np.all(disc.basis.dx > 0)  # positive Jacobian at every quadrature point
    # volume of the meshed block: quarter disk sheared by the profile
    area = disc.basis.dx.sum()
    L = mesh.domain_radius
    assert area == pytest.approx(np.pi * L**2 / 4, rel=0.02)


def test_boundaries_are_split_into_top_axis_and_cut_off():
    mesh = _mesh(Sphere(1.0))
    sets = mesh.boundary_facet_sets()
    p, f = mesh.vertices.p, mesh.vertices.facets
    assert np.all(p[0, f[:, sets["axis"]]] == 0.0)
    far = p[:, f[:, sets["far"]]]
    rho = np.hypot(far[0], far[1] - Sphere(1.0).surface(far[0]))
    assert np.all(rho > 0.9 * mesh.domain_radius)
    n = sum(len(v) for v in sets.values())
    assert n == len(mesh.vertices.boundary_facets())


def test_projection_onto_a_circle():
    sphere = Sphere(1.0)
    t = np.array([0.1, 0.3])
    a = np.vstack((np.sin(t - 0.05), np.cos(t - 0.05) - 1))
    b = np.vstack((np.sin(t + 0.05), np.cos(t + 0.05) - 1))
    p = project_to_profile(sphere, a, b)
    np.testing.assert_allclose(np.hypot(p[0], p[1] + 1), 1.0, rtol=1e-12)
    np.testing.assert_allclose(np.arctan2(p[0], p[1] + 1), t, rtol=1e-9)
