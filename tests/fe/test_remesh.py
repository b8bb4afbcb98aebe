"""Meshes that follow the contact (`asperity.fe.drivers.remesh`, the ``remesh`` preset
key of `solve_asperity_history`): transfer of the fields, remeshing at a load
reversal, a plastic zone crossing the refined region."""

from __future__ import annotations

import math

import numpy as np
import pytest

from asperity.fe import J2Plasticity, LinearElastic, Sphere, solve_asperity_history
from asperity.fe.drivers.inelastic import History
from asperity.fe.presets import resolve
from asperity.fe.drivers.remesh import EDGE_BAND, Transfer, contact_mesh, edge_band, integral

E, NU = 1000.0, 0.3
Y = E / 400  # elastic-perfectly plastic, E/Y = 400
W_C = (math.pi * 1.6 * Y / (2 * E / (1 - NU**2))) ** 2
SPHERE = Sphere(1.0)


@pytest.fixture(scope="module")
def meshes():
    """Two meshes of the unit sphere: for contact radii 0.05 and 0.1, the second
    with a plastic zone refined (so that it is finer there and coarser near the
    apex than the first)."""
    pre = resolve("inelastic", "draft")
    elastic = LinearElastic(E, NU)
    old, _ = contact_mesh(SPHERE, elastic, pre, 0.05, 100.0)
    zone = np.array([[0.0, 0.05, 0.1], [-0.03, -0.05, -0.02]])
    new, _ = contact_mesh(SPHERE, elastic, pre, 0.1, 100.0, plastic_points=zone)
    return old, new, Transfer(old, new)


def _top_facets(mesh):
    """Inner and outer radius and length of every top facet of a mesh."""
    p = mesh.vertices.p
    f = mesh.vertices.facets[:, mesh.top_facets()]
    return (np.minimum(p[0, f[0]], p[0, f[1]]), np.maximum(p[0, f[0]], p[0, f[1]]),
            np.hypot(*(p[:, f[0]] - p[:, f[1]])))


def test_edge_band_refines_the_top_where_the_plastic_edge_goes_and_nowhere_else(meshes):
    old, _, _ = meshes
    w_max, size = 0.005, 0.02
    r_g = math.sqrt(2 * w_max - w_max**2)  # the unit sphere's intersection radius
    lo, hi = EDGE_BAND[0] * r_g, EDGE_BAND[1] * r_g
    before = _top_facets(old.mesh)
    after = _top_facets(edge_band(old.mesh, SPHERE, w_max, size))
    in_band = [(b > lo) & (a < hi) for a, b, _ in (before, after)]
    assert before[2][in_band[0]].max() > 2 * size * r_g  # the band was coarser
    assert after[2][in_band[1]].max() <= size * r_g * (1 + 1e-9)
    # away from the band (beyond the elements next to it, which refine_around may
    # refine) the top is unchanged
    far = [(b < 0.25 * lo) | (a > 2 * hi) for a, b, _ in (before, after)]
    assert np.count_nonzero(far[0]) >= 5
    np.testing.assert_allclose(np.sort(after[2][far[1]]), np.sort(before[2][far[0]]))


def _nodal(disc):
    return np.concatenate((disc.basis.nodal_dofs, disc.basis.facet_dofs), axis=1), disc.m2.doflocs


def test_fields_the_old_mesh_represents_are_transferred_exactly(meshes):
    old, new, move = meshes
    assert old.weights.size != new.weights.size
    # constant and linear in (r, z) at the quadrature points: P2 in every element
    # (also on the curved ones of the top, whose map is P2)
    x = old.x
    for f in (lambda x: np.full(x.shape[1:], 2.5), lambda x: 1.0 + 2.0 * x[0] - 3.0 * x[1]):
        got = move.field(f(x))
        np.testing.assert_allclose(got, f(new.x), rtol=1e-12, atol=1e-12)
    # a vector field (4 components) linear in r, z; a field not nowhere-negative
    vec = np.stack((x[0], x[1], -x[0], x[0] - x[1]))
    want = np.stack((new.x[0], new.x[1], -new.x[0], new.x[0] - new.x[1]))
    np.testing.assert_allclose(move.field(vec), want, atol=1e-12)
    # a P2 (here linear) displacement field: exact at the new nodes
    dofs, p = _nodal(old)
    u = np.zeros(old.ndofs)
    u[dofs[0]] = 0.3 * p[0] - p[1]
    u[dofs[1]] = p[0] + 2.0
    v = move.displacement(u)
    dofs, q = _nodal(new)
    np.testing.assert_allclose(v[dofs[0]], 0.3 * q[0] - q[1], atol=1e-12)
    np.testing.assert_allclose(v[dofs[1]], q[0] + 2.0, atol=1e-12)


def test_every_field_of_a_material_state_is_transferred(meshes):
    old, new, move = meshes
    mat = J2Plasticity(E, NU, Y)
    state = mat.initial_state(old.weights.shape)
    state.alpha = 0.01 + 0.1 * old.x[0]  # linear: exact
    state.converged[0, 0] = False  # a flag: the value of the nearest old point
    moved = move.state(state)
    assert moved.shape == new.weights.shape
    np.testing.assert_allclose(moved.alpha, 0.01 + 0.1 * new.x[0], atol=1e-12)
    np.testing.assert_allclose(moved.hardness, Y, rtol=1e-12)
    assert moved.converged.dtype == bool and moved.converged.sum() >= new.weights.size - 6


def test_a_kinked_nonnegative_field_stays_nonnegative_and_is_conserved(meshes):
    """The equivalent plastic strain of a zone: zero outside, growing inside
    (a kink at its edge, which no P2 polynomial follows).  The transfer keeps it
    nonnegative and its integral over the body within 1 % (measured 0.1 %)."""
    old, new, move = meshes
    d = np.hypot(old.x[0], old.x[1] + 0.04)
    alpha = np.maximum(0.0, 0.05 - d)
    got = move.field(alpha)
    assert got.min() >= 0.0
    assert integral(new, got) == pytest.approx(integral(old, alpha), rel=0.01)
    d_new = np.hypot(new.x[0], new.x[1] + 0.04)
    assert np.all(got[d_new > 0.05 + 0.02] == 0.0)  # no spreading beyond the old elements


ACC = dict(base="draft", growth=1.3, n_theta=6, sweeps=3, adapt_levels=6)
#: a finer fixed mesh: `standard` without remeshing
FINE_FIXED = dict(base="standard", remesh=False)


@pytest.fixture(scope="module")
def reversal():
    """J2 sphere loaded to 10 w_c and unloaded: fixed `standard` mesh, and
    `draft` with a new mesh forced at the load reversal."""
    hist = History.load_unload(10 * W_C, 1.0)
    mat = J2Plasticity(E, NU, Y)
    ref = solve_asperity_history(SPHERE, mat, hist, accuracy=FINE_FIXED)
    forced = solve_asperity_history(SPHERE, mat, hist, accuracy="draft",
                                    remesh_times=(hist.times[1],))
    return ref, forced, hist


@pytest.mark.slow
def test_remeshing_at_the_load_reversal(reversal):
    ref, ds, hist = reversal
    k = int(np.argmax(ds.interference.values))
    assert ds.attrs["remeshes"] == 1 and list(ds.attrs["remeshed_steps"]) == [k]
    assert ds.time.values[k] == pytest.approx(hist.times[1], rel=1e-12)
    assert ds.dofs.values[k] != ds.dofs.values[k - 1]
    # the unloading branch on the new mesh, against the fixed finer mesh at equal
    # interference: the force within 1 % of the largest force (measured 0.41 %;
    # the same history without the remesh, on the draft mesh throughout: 0.19 %)
    def unloading(d):
        j = int(np.argmax(d.interference.values))
        return d.interference.values[j:][::-1], d.force.values[j:][::-1]

    w_ref, F_ref = unloading(ref)
    w_new, F_new = unloading(ds)
    touching = F_ref > 0
    dev = np.abs(np.interp(w_ref, w_new, F_new) - F_ref)[touching]
    assert np.max(dev) < 0.01 * float(ref.force.max()), np.max(dev) / float(ref.force.max())
    # the residual interference, set by the unloading on the new mesh: within
    # 3 % (measured 1.7 %; without the remesh 0.02 %)
    assert ds.attrs["residual_interference"] == pytest.approx(
        ref.attrs["residual_interference"], rel=0.03)
    assert np.all(np.diff(ds.force.values[k:]) <= 0)


@pytest.fixture(scope="module")
def crossing():
    """J2 sphere pressed to 30 w_c with remeshing (`draft` made finer), against
    the fixed `standard` mesh: the plastic zone appears near w_c and grows
    past every region refined for it."""
    hist = History.loading(30 * W_C, 1.0)
    mat = J2Plasticity(E, NU, Y)
    ds = solve_asperity_history(SPHERE, mat, hist, accuracy=dict(ACC, remesh=True))
    ref = solve_asperity_history(SPHERE, mat, hist, accuracy=FINE_FIXED)
    return ds, ref


@pytest.mark.slow
def test_plastic_zone_crossing_the_refined_region(crossing):
    ds, ref = crossing
    steps = np.asarray(ds.attrs["remeshed_steps"])
    assert len(steps) >= 3
    w, F, A = ds.interference.values, ds.force.values, ds.contact_area.values
    # no jump across a remeshed step: its force and area against the geometric
    # mean of the steps on either side, relative to the same measure of the
    # steps without remeshing (the curvature of the curves)
    lnF, lnA, lnw = np.log(F[1:]), np.log(A[1:]), np.log(w[1:])

    def kink(y):
        slope_l = (y[1:-1] - y[:-2]) / (lnw[1:-1] - lnw[:-2])
        slope_r = (y[2:] - y[1:-1]) / (lnw[2:] - lnw[1:-1])
        return np.abs(slope_r - slope_l)  # at step index 2 ... n-1

    # at step index s the kink is kink(...)[s - 2]; compared where the curves are
    # smooth (beyond 3 w_c: the first contacts jump from node to node) with the
    # largest kink at the steps that kept their mesh (the edge moves from node to
    # node): measured 0.12 against 1.34 in force, 0.42 against 0.76 in area
    smooth = w[2:-1] >= 3 * W_C
    at = np.zeros(smooth.shape, bool)
    at[steps[(steps >= 2) & (steps < len(w) - 1)] - 2] = True
    for y in (lnF, lnA):
        k = kink(y)
        assert np.max(k[at & smooth]) <= np.max(k[~at & smooth]), (k[at & smooth],
                                                                         k[~at & smooth])
    # and the curves agree with the fixed finer mesh over the second half: force
    # within 3 %, area within 4 % (measured 1.9 % and 3.2 %; the same preset
    # without remeshing: 1.2 % and 6.6 %)
    late = w >= 0.5 * w[-1]
    Fr = np.interp(w[late], ref.interference.values, ref.force.values)
    Ar = np.interp(w[late], ref.interference.values, ref.contact_area.values)
    assert np.max(np.abs(F[late] / Fr - 1)) < 0.03
    assert np.max(np.abs(A[late] / Ar - 1)) < 0.04
