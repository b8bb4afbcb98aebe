"""Strains, stiffness and condensation on curved P2 meshes."""

import numpy as np
import pytest
import scipy.sparse.linalg as spl

from asperity.fe import CosineHill, Cylinder, LinearElastic, Sphere
from asperity.fe.discretization.assembly import CondensedStiffness, Discretization, OrderedLU
from asperity.fe.materials.elastic import METRIC
from asperity.fe.discretization.mesh import AsperityMesh, MeshSpec

MAT = LinearElastic(200.0, 0.3)


def _disc(geometry, domain=5.0):
    spec = MeshSpec(domain_radius=domain * geometry.extent, apex_size=0.05 * geometry.extent)
    mesh = AsperityMesh.initial(geometry, spec)
    c = mesh.vertices.p[:, mesh.vertices.t].mean(axis=1)
    mesh = mesh.refined(np.nonzero(np.hypot(*c) < geometry.extent)[0])
    return Discretization(mesh)


def _field(disc, fr, fz):
    """Nodal interpolation of u = (fr(r, z), fz(r, z)) (exact for P2 if quadratic)."""
    x = disc.m2.doflocs
    u = np.zeros(disc.ndofs)
    nod, fac = disc.basis.nodal_dofs, disc.basis.facet_dofs
    nv = disc.mesh.vertices.p.shape[1]
    u[nod[0]], u[nod[1]] = fr(*x[:, :nv]), fz(*x[:, :nv])
    u[fac[0]], u[fac[1]] = fr(*x[:, nv:]), fz(*x[:, nv:])
    return u


@pytest.mark.parametrize("geometry", [Sphere(1.0), CosineHill.from_aspect(4.0, 1.0)])
def test_axisymmetric_patch_test(geometry):
    disc = _disc(geometry)
    a, b, c = 1e-3, -2e-3, 5e-4
    # u_r = a r, u_z = b z + c r: eps_rr = a, eps_zz = b, eps_tt = a, eps_rz = c / 2
    u = _field(disc, lambda r, z: a * r, lambda r, z: b * z + c * r)
    e = disc.strain(u)
    for k, value in enumerate([a, b, a, c / 2]):
        np.testing.assert_allclose(e[k], value, atol=1e-12)
    # energy u^T K u = int sigma : eps r dA
    K = disc.stiffness(MAT.tangent())
    eps = np.array([a, b, a, c / 2])
    density = np.sum(METRIC * (MAT.tangent() @ eps) * eps)
    assert u @ K @ u == pytest.approx(density * disc.weights.sum(), rel=1e-10)


def test_plane_strain_patch_test_and_rigid_modes():
    disc = _disc(Cylinder(1.0))
    u = _field(disc, lambda x, z: 2e-3 * x + 1e-3 * z, lambda x, z: -1e-3 * z)
    e = disc.strain(u)
    np.testing.assert_allclose(e[0], 2e-3, atol=1e-12)
    np.testing.assert_allclose(e[1], -1e-3, atol=1e-12)
    np.testing.assert_allclose(e[2], 0.0, atol=1e-15)
    np.testing.assert_allclose(e[3], 0.5e-3, atol=1e-12)
    K = disc.stiffness(MAT.tangent())
    for fr, fz in [(lambda x, z: 1 + 0 * x, lambda x, z: 0 * x),
                   (lambda x, z: 0 * x, lambda x, z: 1 + 0 * x),
                   (lambda x, z: -z, lambda x, z: x)]:
        rigid = _field(disc, fr, fz)
        assert np.abs(K @ rigid).max() < 1e-10 * np.abs(K).max()


def test_axisymmetric_vertical_translation_is_rigid_but_radial_is_not():
    disc = _disc(Sphere(1.0))
    K = disc.stiffness(MAT.tangent())
    up = _field(disc, lambda r, z: 0 * r, lambda r, z: 1 + 0 * r)
    assert np.abs(K @ up).max() < 1e-10 * np.abs(K).max()
    out = _field(disc, lambda r, z: 1 + 0 * r, lambda r, z: 0 * r)
    assert out @ K @ out > 0  # hoop strain 1 / r


def test_stiffness_is_symmetric():
    disc = _disc(CosineHill.from_aspect(3.0, 1.0))
    K = disc.stiffness(MAT.tangent())
    assert abs(K - K.T).max() < 1e-12 * abs(K).max()


def test_condensed_stiffness_is_the_exact_schur_complement():
    disc = _disc(Sphere(1.0))
    K = disc.stiffness(MAT.tangent())
    S = disc.top.node_dofs[:15]
    cond = CondensedStiffness(disc, K, S)
    # compliance by direct solves with the free block
    free = disc.free
    Kff = K[free][:, free].tocsc()
    pos = np.full(disc.ndofs, -1)
    pos[free] = np.arange(len(free))
    E = np.zeros((len(free), len(S)))
    E[pos[S], np.arange(len(S))] = 1.0
    C = spl.splu(Kff).solve(E)[pos[S]]
    np.testing.assert_allclose(cond.stiffness @ C, np.eye(len(S)), atol=1e-9)
    # full displacement: K u = f on the free dofs, zero on the supports
    f = np.linspace(-1.0, 0.5, len(S))
    u = cond.full_displacement(f)
    assert np.all(u[disc.fixed] == 0)
    rhs = np.zeros(disc.ndofs)
    rhs[S] = f
    np.testing.assert_allclose((K @ u)[free], rhs[free], atol=1e-9 * np.abs(f).max())
    # and the condensed relation K_S u_S = f_S
    np.testing.assert_allclose(cond.stiffness @ u[S], f, atol=1e-9)


def test_ordered_lu_keeps_the_ordering_of_a_pattern_and_solves_as_superlu():
    """The second matrix of a pattern is factorized in the kept order: its solution
    agrees with SuperLU's own to 1e-12 and the fill is SuperLU's; a new pattern gets
    a new ordering; a zero pivot raises SuperLU's RuntimeError."""
    disc = _disc(Sphere(1.0))
    free = disc.free
    K1 = disc.stiffness(MAT.tangent())[free][:, free].tocsc()
    K2 = disc.stiffness(LinearElastic(70.0, 0.45).tangent())[free][:, free].tocsc()
    b = np.linspace(-1.0, 2.0, K1.shape[0])
    ordered = OrderedLU(diag_pivot_thresh=0.0)
    first, second = ordered.factor(K1), ordered.factor(K2)
    assert first.order is None and second.order is not None
    own = spl.splu(K2, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                   options=dict(SymmetricMode=True))
    x = second.solve(b)
    np.testing.assert_allclose(x, own.solve(b), rtol=0, atol=1e-12 * np.abs(x).max())
    assert second.lu.L.nnz + second.lu.U.nnz == own.L.nnz + own.U.nnz
    np.testing.assert_allclose(K2 @ x, b, rtol=0, atol=1e-9 * np.abs(b).max())
    # two right-hand sides at once: to round-off of the largest entry (a block solve may
    # order its operations otherwise than one right-hand side; 1e-12 relative to each entry
    # failed by 4e-12 on one small entry with another processor's BLAS kernels)
    B = np.stack([b, -2.0 * b], axis=1)
    np.testing.assert_allclose(second.solve(B)[:, 1], -2.0 * x, rtol=0, atol=1e-12 * np.abs(x).max())
    # another pattern (a smaller block): ordered afresh, still right
    K3 = K1[:200][:, :200].tocsc()
    third = ordered.factor(K3)
    assert third.order is None
    np.testing.assert_allclose(K3 @ third.solve(b[:200]), b[:200], atol=1e-9)
    zero = K2.copy()
    zero.data[:] = 0.0
    with pytest.raises(RuntimeError):
        ordered.factor(zero)


def test_supports():
    disc = _disc(Sphere(1.0))
    p = disc.m2.doflocs
    nod = disc.basis.nodal_dofs
    nv = nod.shape[1]
    axis = np.nonzero(p[0, :nv] == 0)[0]
    assert set(nod[0, axis]) <= set(disc.fixed)  # u_r = 0 on the axis
    inner = axis[np.abs(p[1, axis]) < 0.99 * disc.mesh.domain_radius]
    assert not set(nod[1, inner]) & set(disc.fixed)  # u_z free there (but at the cut-off)
    far = np.nonzero(np.hypot(p[0, : nod.shape[1]], p[1, : nod.shape[1]]) > 0.999 * disc.mesh.domain_radius)[0]
    assert set(nod[:, far].ravel()) <= set(disc.fixed)


def test_stiffness_accepts_a_tangent_per_quadrature_point():
    # the hook for inelastic materials: D given at every point
    disc = _disc(Sphere(1.0))
    D = MAT.tangent()
    ne, nq = disc.weights.shape
    per_point = np.broadcast_to(D[:, :, None, None], (4, 4, ne, nq)).copy()
    per_point[:, :, ::2] *= 2.0  # every other element twice as stiff
    K1 = disc.stiffness(per_point)
    K2 = disc.stiffness(D)
    u = np.random.default_rng(0).standard_normal(disc.ndofs)
    e = disc.strain(u)
    s = np.einsum("abeq,beq->aeq", per_point, e)
    work = np.sum(METRIC[:, None, None] * s * e * disc.weights)
    assert u @ K1 @ u == pytest.approx(work, rel=1e-10)
    assert u @ K1 @ u > u @ K2 @ u


@pytest.mark.parametrize("geometry", [Sphere(1.0), Cylinder(1.0)])
def test_mesh_fields_of_an_affine_field(geometry):
    """`inelastic.mesh_fields` (the fields drawn as Figs. 6.15-6.21) on u = (a r, b z + c r),
    exact in P2: the displacement at the vertices, det(I + grad u) = (1 + a)(1 + b) (times
    the hoop stretch 1 + a of a body of revolution) to round-off, and its sign flipped
    for a = -2 (every element inside out); the element mean of a uniform inelastic strain
    is its equivalent value."""
    from asperity.fe import J2Plasticity
    from asperity.fe.drivers.inelastic import END_FIELDS, mesh_fields
    from asperity.fe.materials.elastic import equivalent_strain

    disc = _disc(geometry)
    state = J2Plasticity(200.0, 0.3, 1.0).initial_state(disc.weights.shape)
    eps = np.array([1e-3, -2e-3, 1e-3, 5e-4])
    state.inelastic_strain[:] = eps[:, None, None]
    p = disc.mesh.vertices.p
    for a, b, c in ((1e-3, -2e-3, 5e-4), (-2.0, 0.5, 0.1)):
        ds = mesh_fields(disc, _field(disc, lambda r, z: a * r, lambda r, z: b * z + c * r),
                         state)
        assert set(END_FIELDS) <= set(ds.data_vars)
        np.testing.assert_allclose(ds["vertex_r"].values, p[0])
        np.testing.assert_allclose(ds["vertex_displacement_r"].values, a * p[0], atol=1e-14)
        np.testing.assert_allclose(ds["vertex_displacement_z"].values, b * p[1] + c * p[0],
                                   atol=1e-14)
        det = (1 + a) * (1 + b) * ((1 + a) if geometry.axisymmetric else 1.0)
        np.testing.assert_allclose(ds["element_jacobian"].values, det, rtol=1e-10)
        assert (ds["element_jacobian"].values <= 0).all() == (det <= 0)
    np.testing.assert_allclose(ds["element_inelastic_strain"].values,
                               float(equivalent_strain(eps[:, None]).ravel()[0]), rtol=1e-12)
    assert ds["triangle_vertices"].shape == (disc.mesh.vertices.t.shape[1], 3)
    for v in ds.variables.values():
        assert v.attrs["units"] and v.attrs["long_name"]
