"""P2 fields of the 3-D half model: strains, supports and contact nodes (report 3.3, 9.2).

Displacements are P2 (`ElementTetP2`) on the mapped mesh (`half_model_mesh`), four
quadrature points per element (degree 2), with the volumetric strain
replaced by its element mean (B-bar, the P2/P0 mixed element;
``volumetric="mean"``): with the full volumetric strain at four points
the 10-node tetrahedron locks under isochoric plastic flow (about one
constraint per displacement dof), and a locked junction can separate from
the flat while it slides; with B-bar it stays in contact.  Strains are
[e11, e22, e33, e12, e13, e23] (tensor shears, work product weights 1, 1, 1, 2, 2, 2).

Supports (3.3.1): u = 0 on the cut-off boundary (the bottom of the block and its
sides |x| = L, y = L); u_y = 0 on the plane of symmetry y = 0 (the half model).

Contact (3.3.2, 3.4.1).  The contact lives on the P2 nodes of the top facets near
the apex, vertices and edge midpoints: each 6-node facet is cut at its edge
midpoints into 4 triangles, and phi_i is the hat function of node i on these
sub-triangles (P1 tractions on the sub-triangulation, the pairing with P2
displacements that mortar methods for quadratic elements use; 6 Gauss points a
sub-triangle).  A node's weighted quantity is int phi_i f ds / int phi_i ds: its
displacement (the operator ``V``), position and gap_offset-shifted height; a
traction (t_x, t_y, -t_N) interpolated from the nodes by the phi_i is integrated
against the P2 shape functions (``V^T``).  One condition a node, as many as
the surface has P2 nodes: with the penalty at the facets' quadrature
points (3 Gauss points per 6-node facet) a plastically flattened junction
satisfies its contact condition at only some of the points within its
edge ring, the pressure jumping between zero and about twice the mean
between neighbours (three conditions a facet are one and a half a node);
the nodes as points let the facets' corners lift inside the contact (the
consistent force of a uniform pressure on a 6-node facet's corner is
zero); the facets' vertices alone keep the pressure smooth but resolve
the contact's edge at the vertex spacing, twice the node spacing, so the
normal force grows by rings of vertices (docs: changelog, 'Sliding of one
asperity').

Assembly: the free-free tangent has one CSC pattern, built once with the slot of
every element entry (`HalfModel.scatter`, `HalfModel.matrix`); the element
matrices sum_q B^T W D B are one batched product (`HalfModel.element_matrices`).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTetP2, ElementVector, FacetBasis
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from asperity.fe.discretization.half_model_mesh import HalfModelMesh
from asperity.fe.materials.elastic import METRIC6

#: quadrature order in the volume (4 points per tetrahedron)
INTORDER = 2
#: quadrature order on each of the 4 sub-triangles of a contact facet (6 Gauss
#: points each, 24 per facet: exact for the P1 x P2 products of the node gaps on a
#: plane facet)
CONTACT_INTORDER = 3


def _subtriangle_rule(order: int = CONTACT_INTORDER) -> tuple[np.ndarray, np.ndarray]:
    """A composite rule on the reference triangle: the Gauss rule of `order` on each
    of its 4 triangles cut at the edge midpoints (points (2, 4 n), weights (4 n,))."""
    X, W = get_quadrature(RefTri, order)
    corners = np.array([[[0.0, 0.0], [0.5, 0.0], [0.0, 0.5]],
                        [[0.5, 0.0], [1.0, 0.0], [0.5, 0.5]],
                        [[0.0, 0.5], [0.5, 0.5], [0.0, 1.0]],
                        [[0.5, 0.5], [0.0, 0.5], [0.5, 0.0]]])       # (4, 3 corners, 2)
    lam = np.vstack((1.0 - X.sum(axis=0), X))                           # (3, n)
    pts = np.einsum("scd,cn->dsn", corners, lam).reshape(2, -1)
    return pts, np.tile(W / 4.0, 4)


def _subtriangle_hats(lam: np.ndarray) -> np.ndarray:
    """The hat functions of a triangle's 6 nodes on its 4 triangles cut at the edge
    midpoints, at points of barycentric coordinates `lam` (3, ...): (6, ...), the
    vertices 0, 1, 2, then the midpoints of the edges 01, 12, 20."""
    i, j, k = [0, 1, 2], [1, 2, 0], [2, 0, 1]
    return np.concatenate((np.maximum(2.0 * lam - 1.0, 0.0),
                           np.maximum(0.0, np.minimum(np.minimum(2.0 * lam[i], 2.0 * lam[j]),
                                                      1.0 - 2.0 * lam[k]))))


class HalfModel:
    """P2 displacement fields on the half model, contact surface, operators."""

    def __init__(self, geometry, mesh: HalfModelMesh, contact_radius: float,
                 volumetric: str = "mean"):
        self.geometry = geometry
        self.hm = mesh
        m2 = mesh.mesh
        element = ElementVector(ElementTetP2())
        self.basis = basis = Basis(m2, element, intorder=INTORDER)
        self.ndofs = basis.N
        self.element_dofs = basis.element_dofs            # (30, ne)
        ne, nq = basis.dx.shape
        self.shape = (ne, nq)
        self.weights = np.asarray(basis.dx)
        self.x = np.array(basis.global_coordinates())      # (3, ne, nq)
        nloc = self.element_dofs.shape[0]
        B = np.zeros((6, nloc, ne, nq))
        Nv = np.zeros((3, nloc, ne, nq))
        for i, (phi, *_) in enumerate(basis.basis):
            g = phi.grad
            B[0, i], B[1, i], B[2, i] = g[0][0], g[1][1], g[2][2]
            B[3, i] = 0.5 * (g[0][1] + g[1][0])
            B[4, i] = 0.5 * (g[0][2] + g[2][0])
            B[5, i] = 0.5 * (g[1][2] + g[2][1])
            Nv[:, i] = np.asarray(phi)
        if volumetric == "mean":
            # B-bar: the volumetric strain replaced by its element mean (the
            # P2/P0 mixed element): 10-node tetrahedra with 4 points lock
            # under isochoric plastic flow (about one volume constraint per
            # displacement dof), the element mean leaves ~4 dofs per constraint
            vol = B[0] + B[1] + B[2]                                       # (30, ne, nq)
            mean = np.sum(vol * self.weights, axis=2) / np.sum(self.weights, axis=1)
            B[:3] += (mean[:, :, None] - vol)[None] / 3.0
        elif volumetric != "full":
            raise ValueError("volumetric is 'mean' (B-bar) or 'full'")
        self.volumetric = volumetric
        self.B = B
        rows = np.broadcast_to(np.arange(6 * ne * nq).reshape(6, 1, ne, nq), B.shape)
        cols = np.broadcast_to(self.element_dofs[None, :, :, None], B.shape)
        self.Bsp = sp.csr_matrix((B.ravel(), (rows.ravel(), cols.ravel())),
                                 shape=(6 * ne * nq, self.ndofs))
        rows = np.broadcast_to(np.arange(3 * ne * nq).reshape(3, 1, ne, nq), Nv.shape)
        cols = np.broadcast_to(self.element_dofs[None, :, :, None], Nv.shape)
        self.Nsp = sp.csr_matrix((Nv.ravel(), (rows.ravel(), cols.ravel())),
                                 shape=(3 * ne * nq, self.ndofs))
        self.MW = (METRIC6[:, None, None] * self.weights[None]).ravel()
        self.absBT = abs(self.Bsp).T.tocsr()
        self._Bm = np.ascontiguousarray(np.transpose(B, (2, 3, 0, 1)))          # (ne, nq, 6, 30)
        self._BtW = np.ascontiguousarray(np.swapaxes(
            self._Bm * (METRIC6[:, None] * self.weights[:, :, None, None]),
            2, 3))                                                              # (ne, nq, 30, 6)
        # node -> dofs (3, nnodes): vertices then edge midpoints, as doflocs
        self.dofmap = np.hstack((basis.nodal_dofs, basis.edge_dofs))
        if not np.allclose(basis.doflocs[:, self.dofmap[0]], m2.doflocs):
            raise RuntimeError("unexpected dof numbering of the P2 tetrahedra")
        self._supports()
        self._pattern()
        self._contact_surface(contact_radius)
        self._symmetry_plane()

    # --- supports ------------------------------------------------------------------
    def _supports(self, tol=1e-9):
        X = self.hm.nodes_ref
        s = self.hm.spec
        L, D = s.half_width, s.depth
        scale = max(L, D)
        clamp = ((np.abs(X[2] + D) < tol * scale) | (np.abs(np.abs(X[0]) - L) < tol * scale)
                 | (np.abs(X[1] - L) < tol * scale))
        sym = np.abs(X[1]) < tol * scale
        self.node_top = np.abs(X[2]) < tol * scale
        self.node_sym = sym
        fixed = np.concatenate((self.dofmap[:, clamp].ravel(), self.dofmap[1, sym]))
        self.fixed = np.unique(fixed)
        self.boundary_dofs = np.unique(np.concatenate(
            (self.dofmap[:, clamp].ravel(), self.dofmap[:, sym].ravel(),
             self.dofmap[:, self.node_top].ravel())))
        free = np.ones(self.ndofs, bool)
        free[self.fixed] = False
        self.free = np.nonzero(free)[0]

    def _pattern(self):
        """CSC pattern of the free-free tangent and the slot of every element entry."""
        n = len(self.free)
        pos = np.full(self.ndofs, -1)
        pos[self.free] = np.arange(n)
        self._pos = pos
        ed = pos[self.element_dofs]                           # (30, ne)
        nl, ne = ed.shape
        rows = np.broadcast_to(ed.T[:, :, None], (ne, nl, nl))   # entry (e, i, j): row i
        cols = np.broadcast_to(ed.T[:, None, :], (ne, nl, nl))
        keep = (rows >= 0) & (cols >= 0)
        key = np.where(keep, cols.astype(np.int64) * n + rows, -1)
        ukey, inverse = np.unique(key[keep], return_inverse=True)
        slot = np.full(key.shape, -1, dtype=np.int64)
        slot[keep] = inverse
        self._slot = slot                                     # (ne, 30, 30)
        self._nnz = len(ukey)
        self._indices = (ukey % n).astype(np.int32)
        counts = np.bincount(ukey // n, minlength=n)
        self._indptr = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        self._n = n

    def scatter(self, elements, Ke) -> np.ndarray:
        s = self._slot[elements].ravel()
        v = Ke.ravel()
        k = s >= 0
        return np.bincount(s[k], weights=v[k], minlength=self._nnz)

    def element_matrices(self, D, elements=None) -> np.ndarray:
        """sum_q B^T W D B for `elements` (all by default); D (6, 6) or (6, 6, ne, nq)."""
        e = slice(None) if elements is None else elements
        Bm, BtW = self._Bm[e], self._BtW[e]
        ne = Bm.shape[0]
        nq = Bm.shape[1]
        D = np.asarray(D)
        if D.ndim == 2:
            DB = np.matmul(D, Bm)
        else:
            Dm = np.transpose(D, (2, 3, 0, 1))[e]
            DB = np.matmul(Dm, Bm)
        return np.matmul(BtW.transpose(0, 2, 1, 3).reshape(ne, -1, nq * 6),
                         DB.reshape(ne, nq * 6, -1))

    def matrix(self, data) -> sp.csc_matrix:
        return sp.csc_matrix((data, self._indices, self._indptr), shape=(self._n, self._n))

    # --- contact surface ---------------------------------------------------------------
    def _top_facets(self, radius: float) -> np.ndarray:
        m = self.hm.reference
        bf = m.boundary_facets()
        f = m.facets[:, bf]
        on_top = np.all(np.abs(m.p[2, f]) < 1e-9 * self.hm.spec.depth, axis=0)
        c = m.p[:, f].mean(axis=1)
        near = np.hypot(c[0], c[1]) < radius
        return bf[on_top & near]

    def _contact_surface(self, radius: float):
        facets = self._top_facets(radius)
        if facets.size == 0:
            raise ValueError("no top facet within the contact candidate radius")
        self.contact_radius = float(radius)
        element = ElementVector(ElementTetP2())
        fb = FacetBasis(self.hm.mesh, element, facets=facets, quadrature=_subtriangle_rule())
        self.cfacets = facets
        self.ctind = np.asarray(fb.tind)
        self.cdofs = np.asarray(fb.element_dofs)                 # (30, nf)
        if not np.array_equal(self.cdofs, self.element_dofs[:, self.ctind]):
            raise RuntimeError("unexpected dof order of the facet basis")
        val = np.array([np.asarray(phi) for phi, *_ in fb.basis])   # (30, 3, nf, nq)
        comp = np.argmax(np.abs(val).sum(axis=(2, 3)), axis=1)
        self.ccomp = comp
        self.cval = val[np.arange(len(comp)), comp]             # (30, nf, nq)
        self.cw = np.asarray(fb.dx)                              # (nf, nq)
        X = np.array(fb.global_coordinates())                    # (3, nf, nq)
        self.cX = X
        self.cz0 = X[2] + self.geometry.gap_offset_xy(X[0], X[1])
        area = self.cw.sum(axis=1)
        self.facet_size = np.sqrt(4.0 * area / math.sqrt(3.0))
        mref = self.hm.reference
        self._contact_nodes(mref.facets[:, facets], mref.p[:2])

    def _contact_nodes(self, fv, xy):
        """The contact's node operators (module docstring, "Contact").

        fv (3, nf) the vertices of the contact facets, xy (2, :) the vertices' x, y
        (the body's x, y: the mapping onto the hill moves only z, so each facet is
        the plane triangle of its vertices in x, y).  The contact nodes are the
        facets' 6 P2 nodes, vertices and edge midpoints; each facet is cut into 4
        triangles at its edge midpoints, and phi_i is the hat function of node i on
        these sub-triangles, integrated at their quadrature points:
        ``vw`` (nV,) = int phi_i ds; ``V`` (3 nV x free dofs): u -> the weighted
        displacements int phi_i u_c ds / vw_i, c = x, y, z stacked (``VT`` its
        transpose); ``vX`` (3, nV) the weighted position and
        ``vz0`` (nV,) the weighted gap_offset-shifted height of the body; ``vr`` the
        nodes' distance from the apex, ``vsize`` the mean size of their facets;
        ``vfacets`` (6, nf) the nodes of each facet (indices into these: its
        vertices, then the midpoints of its edges 01, 12, 20)."""
        nf, nq = self.cw.shape
        nv = xy.shape[1]
        a = fv[[0, 1, 2, 0, 1, 2]]
        b = fv[[0, 1, 2, 1, 2, 0]]
        key = np.minimum(a, b).astype(np.int64) * nv + np.maximum(a, b)
        nodes, nloc = np.unique(key, return_inverse=True)
        nloc = nloc.reshape(a.shape)                             # (6, nf)
        na, nb = nodes // nv, nodes % nv
        nxy = 0.5 * (xy[:, na] + xy[:, nb])                      # (2, nV)
        v = xy[:, fv]                                            # (2, 3, nf)
        J = np.stack((v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=-1)   # (2, nf, 2)
        d = self.cX[:2] - v[:, 0][:, :, None]                    # (2, nf, nq)
        st = np.linalg.solve(np.transpose(J, (1, 0, 2))[:, None],
                             np.transpose(d, (1, 2, 0))[..., None])[..., 0]
        lam = np.stack((1.0 - st[..., 0] - st[..., 1], st[..., 0], st[..., 1]))  # (3, nf, nq)
        if lam.min() < -1e-9:
            raise RuntimeError("contact points outside their facet")
        phi = _subtriangle_hats(lam)                             # (6, nf, nq)
        npts = nf * nq
        rows = np.broadcast_to(np.arange(npts).reshape(nf, nq), (6, nf, nq))
        cols = np.broadcast_to(nloc[:, :, None], (6, nf, nq))
        # phi_i w at the points, as a nodes x points matrix
        Pw = sp.csr_matrix(((phi * self.cw).ravel(), (cols.ravel(), rows.ravel())),
                           shape=(nodes.size, npts))
        self.vw = np.asarray(Pw.sum(axis=1)).ravel()
        Pw = sp.diags(1.0 / self.vw) @ Pw
        pos = self._pos                                          # dof -> free dof, or -1
        # u_c at the points: row c npts + point, from the dofs of component c
        r = (self.ccomp[:, None, None] * npts
             + np.arange(npts).reshape(nf, nq)[None]) * np.ones_like(self.cval, dtype=int)
        cc = np.broadcast_to(pos[self.cdofs][:, :, None], self.cval.shape)
        keep = cc >= 0
        N = sp.csr_matrix((self.cval[keep], (r[keep], cc[keep])),
                          shape=(3 * npts, self.free.size))
        self.V = (sp.block_diag((Pw, Pw, Pw)) @ N).tocsr()
        self.VT = self.V.T.tocsr()
        self.vX = np.stack([Pw @ x.ravel() for x in self.cX])
        self.vz0 = Pw @ self.cz0.ravel()
        self.vr = np.hypot(nxy[0], nxy[1])
        self.vsize = (np.bincount(nloc.ravel(), np.tile(self.facet_size, 6))
                      / np.bincount(nloc.ravel()))
        self.vfacets = nloc

    # --- symmetry plane (outputs) ------------------------------------------------------------
    def _symmetry_plane(self):
        m = self.hm.reference
        bf = m.boundary_facets()
        f = m.facets[:, bf]
        on = np.all(np.abs(m.p[1, f]) < 1e-9 * self.hm.spec.half_width, axis=0)
        f = f[:, on]
        nv = m.p.shape[1]
        edges = np.sort(m.edges, axis=0)
        ekey = edges[0].astype(np.int64) * nv + edges[1]
        order = np.argsort(ekey)

        def edge_id(a, b):
            k = np.minimum(a, b).astype(np.int64) * nv + np.maximum(a, b)
            i = np.searchsorted(ekey[order], k)
            return order[i]

        a, b, c = f
        ab, bc, ca = nv + edge_id(a, b), nv + edge_id(b, c), nv + edge_id(c, a)
        tri = np.hstack((np.vstack((a, ab, ca)), np.vstack((ab, b, bc)),
                         np.vstack((ca, bc, c)), np.vstack((ab, bc, ca))))
        nodes, inv = np.unique(tri, return_inverse=True)
        self.plane_nodes = nodes
        self.plane_triangles = inv.reshape(tri.shape)            # (3, ntri) into plane_nodes
        # element averages -> node averages of quadrature fields (for plotting)
        t2 = self.hm.mesh.t                                        # (4, ne) vertices
        ne = t2.shape[1]
        e2n = np.vstack((t2, nv + m.t2e)) if hasattr(m, "t2e") else None
        self._elem_nodes = e2n                                     # (10, ne)
        nn = self.hm.mesh.doflocs.shape[1]
        rows = e2n.ravel()
        cols = np.broadcast_to(np.arange(ne)[None, :], e2n.shape).ravel()
        P = sp.csr_matrix((np.ones(rows.size), (rows, cols)), shape=(nn, ne))
        cnt = np.asarray(P.sum(axis=1)).ravel()
        self._node_avg = sp.diags(1.0 / np.maximum(cnt, 1.0)) @ P

    def nodal_average(self, q) -> np.ndarray:
        """A quadrature field (ne, nq) averaged per element, then per node."""
        return self._node_avg @ np.asarray(q).mean(axis=1)

    def node_displacements(self, u) -> np.ndarray:
        return u[self.dofmap]                                      # (3, nnodes)

    def point_displacements(self, u) -> np.ndarray:
        return (self.Nsp @ u).reshape((3,) + self.shape)
