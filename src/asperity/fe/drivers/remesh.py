"""Meshes that follow the contact of an inelastic history (remeshing).

`inelastic.solve_asperity_history` with the preset key ``remesh`` does not
keep one mesh for the whole history: it starts on a mesh refined only
around the first contacts and, whenever the contact edge leaves the band
of radii the mesh was refined for (or the plastic zone grows past the
region refined for it), builds a new one and re-solves the step on it.

New mesh (`contact_mesh`).  skfem refines but does not coarsen, so every
mesh is rebuilt from the coarse graded rings (`mesh.AsperityMesh.initial`):

- the contact edge: the error estimator of the elastic solver (ZZ,
  `adapt`, `solve.adapted_model`, the preset's ``target_error``, ``theta``
  and ``sweeps``) drives the refinement at ``REMESH_LEVELS`` elastic
  interferences whose contact radii span the band [a / ``REMESH_BACK``,
  ``remesh_band`` a] around the current radius a.  The elastic radius of
  an interference is taken as the intersection radius over sqrt 2 (Hertz,
  report 6.1; exact for a paraboloid), so the band is set in contact
  radius, which is what a plastic contact (wider than an elastic one at
  the same interference) shares with the elastic solutions;
- the plastic zone: elements within their own size of a point of the
  plastic zone (equivalent inelastic strain above the solver's threshold
  and above ``PLASTIC_FRACTION`` of the largest) are refined
  until no longer than ``plastic_size`` x a, and so are those within
  (``remesh_band`` - 1) x max(the zone's extent, a) of it, so that the zone
  can grow;
- elsewhere the mesh is the coarse graded one (apex rings sized for the
  smallest radius of the band, not for first touch).

One mesh for the whole history (``remesh`` off, `edge_band`).  The elastic
adaptation resolves the elastic contact edges of its levels; a plastic
contact is wider at the same interference (on a sphere, up to the
intersection radius sqrt(2 R w) against the elastic sqrt(R w)), so its edge
crosses graded elements that the elastic levels left coarse, and the
located edge, hence the area, scatters by a few per cent from step to step.
The preset key ``edge_size`` refines, on top of the adapted mesh, the
elements within their own size of the top surface over ``EDGE_BAND`` x r_g
(r_g the intersection radius at the largest interference) until none is
longer than ``edge_size`` x r_g.

Transfer (`Transfer`).  Displacements are P2 fields: the new nodal values
are the old field evaluated at the new nodes (the inverse isoparametric
map of the old element containing each node, by Newton).  Internal
variables live at the quadrature points: in every old element, the six
values of a field at its six quadrature points define one P2 polynomial in
the element's reference coordinates (interpolation, the Vandermonde matrix
of the reference quadrature points inverted once), which is evaluated at
the reference coordinates of each new quadrature point in the old element
that contains it.  Chosen over an L2 projection onto continuous fields
(nodal recovery) because it is local: the plastic zone's edge, where the
inelastic strain has a kink and the hardness a jump in slope, is not
smeared over the neighbouring elements, and a field is transferred exactly
whenever it is a P2 polynomial in every old element (constants, fields
linear in r and z, also on the curved elements of the top).  A field that
is nowhere negative (equivalent plastic strain, plastic work, hardness,
damage) is kept nowhere negative: the polynomial of an element at the edge
of the plastic zone dips below zero between its yielded and its elastic
points.  Fields that are not finite floating-point numbers (flags, counts,
rupture times of unruptured points) take the value of the nearest old
quadrature point of the containing element.  Everything is vectorized over
points.

Then the step is re-solved on the new mesh from the transferred state at
its start (`inelastic.solve_asperity_history`): the new equilibrium and the
plastic increment of the step are computed on the new mesh.
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem import Basis, ElementTriP2

from asperity.fe.discretization.assembly import Discretization
from asperity.fe.materials.elastic import equivalent_strain
from asperity.fe.discretization.mesh import AsperityMesh
from asperity.fe.drivers.elastic import adapted_model

#: elastic interferences driving the refinement of the contact edge
REMESH_LEVELS = 3
#: the band of refined contact radii starts at a / REMESH_BACK
REMESH_BACK = 1.15
#: element candidates per point (nearest centroids): the nearest, then more for the
#: points outside it
CANDIDATES = (1, 8, 64)
#: a point counts as inside an element when no barycentric coordinate is below this
INSIDE = 1e-10
#: the plastic zone: inelastic strain above this fraction of the largest
PLASTIC_FRACTION = 0.01
#: refinement passes of the plastic zone at most
PLASTIC_PASSES = 12
#: radii the plastic contact edge of a history sweeps, as fractions of the
#: intersection radius r_g at the largest interference: on a sphere r_g / 4 is
#: the plastic edge at about a tenth of the largest interference, 1.1 r_g a
#: little pile-up at the largest
EDGE_BAND = (0.25, 1.1)

_P2 = ElementTriP2()


def element_sizes(mesh: AsperityMesh) -> np.ndarray:
    """Longest edge of every element (vertex mesh)."""
    p, t = mesh.vertices.p, mesh.vertices.t
    e = [np.hypot(*(p[:, t[i]] - p[:, t[j]])) for i, j in ((0, 1), (1, 2), (2, 0))]
    return np.max(e, axis=0)


def elastic_interference(geometry, radius) -> np.ndarray:
    """Interference whose elastic contact radius is about `radius`: the
    profile's drop at sqrt 2 x radius (Hertz: a^2 = R w, the intersection
    radius is sqrt(2 R w)), kept below the height of the hill."""
    r = np.sqrt(2.0) * np.asarray(radius, float)
    return np.minimum(-geometry.surface(r), 0.9 * geometry.height)


def refine_around(mesh: AsperityMesh, points: np.ndarray, size: float, reach: float = 0.0,
                  passes: int = PLASTIC_PASSES) -> AsperityMesh:
    """Refine the elements within their own size plus `reach` of any of
    `points` (2, n) until they are no longer than `size`."""
    if points.shape[1] == 0:
        return mesh
    tree = cKDTree(points.T)
    for _ in range(passes):
        h = element_sizes(mesh)
        centre = mesh.vertices.p[:, mesh.vertices.t].mean(axis=1)
        dist, _ = tree.query(centre.T)
        marked = np.flatnonzero((dist <= h + reach) & (h > size))
        if marked.size == 0:
            break
        mesh = mesh.refined(marked)
    return mesh


def edge_band(mesh: AsperityMesh, geometry, w_max: float, size: float) -> AsperityMesh:
    """`mesh` with the elements near the top surface over ``EDGE_BAND`` x r_g
    refined to at most ``size`` x r_g (r_g the intersection radius at `w_max`;
    module docstring)."""
    r_g = float(geometry.intersection_radius(np.array([w_max]))[0])
    lo, hi = EDGE_BAND
    # points closer than half the target size: every element near the band is found
    r = np.linspace(lo * r_g, hi * r_g, int(np.ceil(2 * (hi - lo) / size)) + 1)
    return refine_around(mesh, np.vstack((r, geometry.body_surface(r))), size * r_g)


def contact_mesh(geometry, material, preset: dict, radius: float, penalty_factor: float,
                 plastic_points=None) -> tuple[Discretization, float]:
    """A mesh for a contact of radius `radius` and its plastic zone (module
    docstring); returns its discretization and the largest contact radius
    whose edge it resolves."""
    band = float(preset["remesh_band"])
    radii = np.geomspace(radius / REMESH_BACK, band * radius, REMESH_LEVELS)
    levels = elastic_interference(geometry, radii)
    model, _ = adapted_model(geometry, material, levels, preset, "penalty", penalty_factor)
    mesh = model.mesh
    if plastic_points is not None and plastic_points.shape[1]:
        apex = np.array([[0.0], [float(geometry.body_surface(np.zeros(1))[0])]])
        extent = float(np.max(np.hypot(*(plastic_points - apex))))
        mesh = refine_around(mesh, plastic_points, preset["plastic_size"] * radius,
                             reach=(band - 1.0) * max(extent, radius))
    return Discretization(mesh), float(radii[-1])


def yielded_points(disc: Discretization, state, threshold: float) -> np.ndarray:
    """Positions (2, n) of the quadrature points of the plastic zone: an
    equivalent inelastic strain above `threshold` and above ``PLASTIC_FRACTION``
    of the largest (a viscoplastic body flows a little everywhere)."""
    eq = equivalent_strain(state.inelastic_strain)
    yielded = eq > max(threshold, PLASTIC_FRACTION * float(np.max(eq)))
    return disc.x[:, yielded]


def plastic_extent(disc: Discretization, state, threshold: float, geometry) -> float:
    """Largest distance of a point of the plastic zone from the apex (0 if none)."""
    pts = yielded_points(disc, state, threshold)
    if pts.shape[1] == 0:
        return 0.0
    z0 = float(geometry.body_surface(np.zeros(1))[0])
    return float(np.max(np.hypot(pts[0], pts[1] - z0)))


# --- point location ----------------------------------------------------------------
def _p2_values(X: np.ndarray) -> np.ndarray:
    """Reference P2 shape functions (6, n) at reference points X (2, n)."""
    return np.array([_P2.lbasis(X, i)[0] for i in range(6)])


def _p2_gradients(X: np.ndarray) -> np.ndarray:
    """Their reference gradients (6, 2, n)."""
    return np.array([_P2.lbasis(X, i)[1] for i in range(6)])


class Locator:
    """Old element and reference coordinates of points (inverse isoparametric
    map of the curved P2 triangles by Newton, vectorized)."""

    def __init__(self, disc: Discretization):
        sb = Basis(disc.m2, _P2, intorder=1)
        self.scalar_dofs = sb.element_dofs  # (6, ne): scalar P2 node numbers
        self.nodes = disc.m2.doflocs[:, self.scalar_dofs]  # (2, 6, ne)
        m = disc.mesh.vertices
        self.tree = cKDTree(m.p[:, m.t].mean(axis=1).T)
        self.ne = m.t.shape[1]

    def _reference(self, x: np.ndarray, cells: np.ndarray) -> np.ndarray:
        """Reference coordinates (2, n) of points x (2, n) in elements `cells`."""
        xe = self.nodes[:, :, cells]  # (2, 6, n)
        X = np.full(x.shape, 1.0 / 3.0)
        for _ in range(12):
            F = np.einsum("ain,in->an", xe, _p2_values(X))
            J = np.einsum("ain,ibn->abn", xe, _p2_gradients(X))  # dx_a / dX_b
            det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
            rx, ry = x[0] - F[0], x[1] - F[1]
            dX = np.array([(J[1, 1] * rx - J[0, 1] * ry) / det,
                           (-J[1, 0] * rx + J[0, 0] * ry) / det])
            X = X + dX
            if np.max(np.abs(dX)) < 1e-14:
                break
        return X

    def __call__(self, x: np.ndarray):
        """(cells (n,), reference coordinates (2, n)).  A point outside every
        element (the curved top of the new mesh may bulge past the old one by
        a sliver) gets the element it is least outside of, and its
        coordinates extrapolate that element's polynomial."""
        n = x.shape[1]
        cells = np.zeros(n, dtype=np.int64)
        X = np.zeros((2, n))
        worst = np.full(n, np.inf)
        todo = np.arange(n)
        for k in CANDIDATES:
            k = min(k, self.ne)
            _, cand = self.tree.query(x[:, todo].T, k)
            cand = cand.reshape(len(todo), k)
            xs = np.repeat(x[:, todo], k, axis=1)
            Xc = self._reference(xs, cand.ravel()).reshape(2, len(todo), k)
            out = -np.minimum(np.minimum(Xc[0], Xc[1]), 1.0 - Xc[0] - Xc[1])  # > 0 outside
            best = np.argmin(out, axis=1)
            rows = np.arange(len(todo))
            b_out = out[rows, best]
            better = b_out < worst[todo]
            sel = todo[better]
            cells[sel] = cand[rows, best][better]
            X[:, sel] = Xc[:, rows, best][:, better]
            worst[sel] = b_out[better]
            todo = todo[worst[todo] > INSIDE]
            if todo.size == 0 or k == self.ne:
                break
        return cells, X


class Transfer:
    """Fields of an old discretization on a new one (module docstring)."""

    def __init__(self, old: Discretization, new: Discretization):
        self.old, self.new = old, new
        loc = Locator(old)
        # displacements: scalar P2 interpolation at the new nodes
        cells, X = loc(new.m2.doflocs)
        phi = _p2_values(X)  # (6, n)
        nn = X.shape[1]
        S = sp.csr_matrix((phi.ravel(), (np.tile(np.arange(nn), 6),
                                         loc.scalar_dofs[:, cells].ravel())),
                          shape=(nn, old.m2.doflocs.shape[1]))
        self._S = S
        self._old_comp = _components(old)
        self._new_comp = _components(new)
        # quadrature points: the P2 polynomial through an element's point values
        Xq = old.basis.X  # (2, nq) reference quadrature points
        V = _p2_values(Xq).T  # (nq, 6)
        ne_new, nq_new = new.weights.shape
        qcells, qX = loc(new.x.reshape(2, -1))
        self._cells = qcells
        self._weights = _p2_values(qX).T @ np.linalg.pinv(V)  # (n, nq_old)
        d = ((qX[:, :, None] - Xq[:, None, :]) ** 2).sum(axis=0)
        self._nearest = np.argmin(d, axis=1)
        self._shape = (ne_new, nq_new)

    def displacement(self, u: np.ndarray) -> np.ndarray:
        """The P2 displacement vector of the old mesh on the new one."""
        out = np.zeros(self.new.ndofs)
        for c in range(2):
            out[self._new_comp[c]] = self._S @ u[self._old_comp[c]]
        return out

    def field(self, values) -> np.ndarray:
        """A quadrature-point field (..., ne, nq) of the old mesh on the new one."""
        v = np.asarray(values)
        lead = v.shape[:-2]
        if np.issubdtype(v.dtype, np.floating) and np.all(np.isfinite(v)):
            taken = v[..., self._cells, :]  # (..., n, nq_old)
            out = np.einsum("...nq,nq->...n", taken, self._weights)
            if np.all(v >= 0):
                out = np.maximum(out, 0.0)
        else:
            out = v[..., self._cells, self._nearest]
        return out.reshape(lead + self._shape)

    def state(self, state):
        """Every field of a material state (dataclass) on the new mesh."""
        return type(state)(**{f.name: self.field(getattr(state, f.name)) for f in fields(state)})

    def fields(self, d: dict) -> dict:
        """A dict of quadrature-point fields on the new mesh."""
        return {k: self.field(v) for k, v in d.items()}


def _components(disc: Discretization) -> np.ndarray:
    """(2, n_scalar): the vector dofs of every scalar P2 node (vertices, then edges)."""
    return np.concatenate((disc.basis.nodal_dofs, disc.basis.facet_dofs), axis=1)


def integral(disc: Discretization, values: np.ndarray) -> float:
    """Integral of a quadrature-point scalar field over the body (per radian
    for a body of revolution, per unit length in plane strain)."""
    return float(np.sum(disc.weights * values))


class ContactMeshes:
    """The meshes of one history: when a new one is due and how it is built.

    A mesh built for contact radius a and a plastic zone of extent e
    (largest distance of a yielded point from the apex) lasts while the
    contact radius stays below the band it resolves (``remesh_band`` x a)
    and the plastic zone's extent below e + (``remesh_band`` - 1)
    max(e, a), the region refined for it.
    """

    def __init__(self, geometry, material, preset: dict, penalty_factor: float,
                 threshold: float):
        self.geometry = geometry
        self.material = material  # elastic constants, for the elastic solver
        self.preset = preset
        self.penalty_factor = penalty_factor
        self.threshold = threshold

    def build(self, radius: float, disc: Discretization | None = None, state=None):
        """The mesh for contact radius `radius` and the plastic zone of
        `state` on `disc` (none: no plastic zone)."""
        band = float(self.preset["remesh_band"])
        pts = None if state is None else yielded_points(disc, state, self.threshold)
        new, self.radius_limit = contact_mesh(self.geometry, self.material, self.preset, radius,
                                              self.penalty_factor, pts)
        extent = 0.0 if state is None else plastic_extent(disc, state, self.threshold,
                                                            self.geometry)
        self.extent_limit = extent + (band - 1.0) * max(extent, radius)
        return new

    def due(self, radius: float, disc: Discretization, state) -> str:
        """Why the mesh must be rebuilt ('' if it need not)."""
        if radius > self.radius_limit:
            return "contact edge beyond the refined band"
        if plastic_extent(disc, state, self.threshold, self.geometry) > self.extent_limit:
            return "plastic zone beyond the refined region"
        return ""
