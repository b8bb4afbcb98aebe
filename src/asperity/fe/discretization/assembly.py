"""Discretization: P2 fields on the curved mesh, strains, stiffness, condensation.

Displacements are 6-node (P2) vector fields on the 6-node curved mesh
(isoparametric).  The weak form is the total formulation (report 3.23)

    int_Omega eps(v) : sigma(u) dV = int_Gamma_c v . t ds,

with dV = r dr dz for a body of revolution (the factor 2 pi is applied to
the reported force, not to the equations) and dV = dx dz per unit length
in plane strain.  Strains at the quadrature points are ``B @ u`` with the
4 components of `material` (hoop strain u_r / r in axisymmetry).
Everything is vectorized over elements and quadrature points: the element
matrices are one `numpy.einsum`, scattered once into a sparse matrix.

Supports (report 3.3.1): u_r = 0 on the axis (symmetry plane), u = 0 on the
cut-off boundary.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from skfem import Basis, ElementTriP2, ElementVector

from asperity.fe.materials.elastic import METRIC
from asperity.fe.discretization.mesh import AsperityMesh

#: quadrature order on the triangles (6 points), enough for P2 on curved
#: 6-node triangles with the r weight and the hoop term u_r / r.
INTORDER = 4


@dataclass
class TopSurface:
    """The top surface as a chain of 3-node facets ordered outward.

    ``node_dofs`` are the u_z dofs of the surface nodes in order (vertex,
    mid-side, vertex, ...); facet k has the chain nodes 2k, 2k+1, 2k+2.
    ``node_r_dofs`` are the matching u_r dofs; ``coords`` (2, n) their positions.
    """

    node_dofs: np.ndarray
    node_r_dofs: np.ndarray
    coords: np.ndarray

    @property
    def nfacets(self) -> int:
        return (len(self.node_dofs) - 1) // 2

    def facet_nodes(self, nfacets: int | None = None) -> np.ndarray:
        n = self.nfacets if nfacets is None else nfacets
        k = np.arange(n)
        return np.vstack((2 * k, 2 * k + 1, 2 * k + 2))


class Discretization:
    """P2 displacement fields on an `AsperityMesh` for a given symmetry."""

    def __init__(self, mesh: AsperityMesh):
        self.mesh = mesh
        self.axisymmetric = bool(mesh.geometry.axisymmetric)
        m2 = mesh.quadratic()
        self.m2 = m2
        self.basis = Basis(m2, ElementVector(ElementTriP2()), intorder=INTORDER)
        basis = self.basis
        self.ndofs = basis.N
        self.element_dofs = basis.element_dofs  # (12, ne)
        x = np.array(basis.global_coordinates())  # (2, ne, nq)
        self.x = x
        dx = basis.dx  # (ne, nq)
        r = x[0]
        self.weights = dx * r if self.axisymmetric else dx.copy()
        nloc = self.element_dofs.shape[0]
        ne, nq = dx.shape
        B = np.zeros((4, nloc, ne, nq))
        for i, (phi, *_) in enumerate(basis.basis):
            g = phi.grad
            B[0, i] = g[0][0]
            B[1, i] = g[1][1]
            if self.axisymmetric:
                B[2, i] = np.asarray(phi)[0] / r
            B[3, i] = 0.5 * (g[0][1] + g[1][0])
        self.B = B
        self._Bsp = None
        self._dirichlet()
        self._top_surface()

    # --- dofs -----------------------------------------------------------------
    def _dirichlet(self):
        sets = self.mesh.boundary_facet_sets()
        m = self.mesh.vertices
        nod, fac = self.basis.nodal_dofs, self.basis.facet_dofs
        axis_f = sets["axis"]
        axis_v = np.unique(m.facets[:, axis_f])
        far_f = sets["far"]
        far_v = np.unique(m.facets[:, far_f])
        fixed = [nod[0, axis_v], fac[0, axis_f], nod[:, far_v].ravel(), fac[:, far_f].ravel()]
        self.fixed = np.unique(np.concatenate(fixed))
        free = np.ones(self.ndofs, dtype=bool)
        free[self.fixed] = False
        self.free = np.nonzero(free)[0]

    def _top_surface(self):
        mesh = self.mesh
        tf = mesh.top_facets()
        ends = mesh.oriented_top_facets()
        if ends.shape[1] and np.any(ends[1, :-1] != ends[0, 1:]):
            raise RuntimeError("top surface facets do not form a chain")
        nod, fac = self.basis.nodal_dofs, self.basis.facet_dofs
        nv = mesh.vertices.p.shape[1]
        chain_v = np.concatenate((ends[0, :1], ends[1]))
        nodes = np.empty(2 * len(tf) + 1, dtype=np.int64)  # node numbers in doflocs
        nodes[0::2] = chain_v
        nodes[1::2] = nv + tf
        dof_z = np.empty_like(nodes)
        dof_r = np.empty_like(nodes)
        dof_z[0::2], dof_r[0::2] = nod[1, chain_v], nod[0, chain_v]
        dof_z[1::2], dof_r[1::2] = fac[1, tf], fac[0, tf]
        self.top = TopSurface(dof_z, dof_r, self.m2.doflocs[:, nodes])

    # --- operators --------------------------------------------------------------
    @property
    def nqp(self) -> int:
        return self.weights.size

    def strain_operator(self) -> sp.csr_matrix:
        """Sparse B: (4 * ne * nq, ndofs), strain components at quadrature points."""
        if self._Bsp is None:
            B = self.B
            _, nloc, ne, nq = B.shape
            rows = np.arange(4 * ne * nq).reshape(4, 1, ne, nq)
            rows = np.broadcast_to(rows, B.shape)
            cols = np.broadcast_to(self.element_dofs[None, :, :, None], B.shape)
            self._Bsp = sp.csr_matrix(
                (B.ravel(), (rows.ravel(), cols.ravel())),
                shape=(4 * ne * nq, self.ndofs))
        return self._Bsp

    def strain(self, u: np.ndarray) -> np.ndarray:
        """Strains (4, ne, nq[, ncols]) of displacement vector(s) u (ndofs[, ncols])."""
        e = self.strain_operator() @ u
        ne, nq = self.weights.shape
        return e.reshape((4, ne, nq) + u.shape[1:])

    def stiffness(self, tangent: np.ndarray) -> sp.csr_matrix:
        """K = sum_q w_q B^T (METRIC * D_q) B, D uniform (4, 4) or (4, 4, ne, nq)."""
        B, W = self.B, self.weights
        D = METRIC[:, None] * tangent if tangent.ndim == 2 else METRIC[:, None, None, None] * tangent
        if tangent.ndim == 2:
            DB = np.einsum("ab,bjeq->ajeq", D, B, optimize=True)
        else:
            DB = np.einsum("abeq,bjeq->ajeq", D, B, optimize=True)
        DB *= W
        Ke = np.einsum("aieq,ajeq->ije", B, DB, optimize=True)
        ed = self.element_dofs
        nloc = ed.shape[0]
        rows = np.broadcast_to(ed[:, None, :], (nloc, nloc, ed.shape[1]))
        cols = np.broadcast_to(ed[None, :, :], (nloc, nloc, ed.shape[1]))
        K = sp.coo_matrix((Ke.ravel(), (rows.ravel(), cols.ravel())),
                          shape=(self.ndofs, self.ndofs)).tocsr()
        return K

    def scalar_p2_interpolation(self) -> sp.csr_matrix:
        """Sparse (ne * nq, n_scalar) interpolation of continuous scalar P2 fields."""
        sb = Basis(self.m2, ElementTriP2(), intorder=INTORDER)
        vals = np.array([np.asarray(phi) for (phi, *_) in sb.basis])  # (6, ne, nq)
        nloc, ne, nq = vals.shape
        rows = np.broadcast_to(np.arange(ne * nq).reshape(1, ne, nq), vals.shape)
        cols = np.broadcast_to(sb.element_dofs[:, :, None], vals.shape)
        return sp.csr_matrix((vals.ravel(), (rows.ravel(), cols.ravel())),
                             shape=(ne * nq, sb.N))


def _trailing(A: sp.csc_matrix, m: int) -> np.ndarray:
    """The trailing m x m block of a square CSC matrix, dense."""
    n = A.shape[0]
    start, stop = A.indptr[n - m], A.indptr[n]
    rows = A.indices[start:stop]
    cols = np.repeat(np.arange(m), np.diff(A.indptr[n - m:]))
    keep = rows >= n - m
    out = np.zeros((m, m))
    out[rows[keep] - (n - m), cols[keep]] = A.data[start:stop][keep]
    return out


#: SuperLU options of a symmetric factorization with diagonal pivots
SYMMETRIC = dict(diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))


def minimum_degree(K: sp.csc_matrix, **options):
    """SuperLU's factorization of `K` in its minimum degree order (on the pattern
    of K^T + K), and that order (scipy gives it only with the factors)."""
    lu = spl.splu(K, permc_spec="MMD_AT_PLUS_A", **options)
    return lu, np.argsort(lu.perm_c)


class CondensedStiffness:
    """The elastic stiffness condensed onto the candidate contact dofs S.

    The free dofs are ordered with S last, the rest I in SuperLU's minimum
    degree order of K_II (read from a factorization of K_II: scipy gives the
    ordering only with the factors), and factorized by SuperLU in that order
    without pivoting (K is symmetric positive definite).  The factorization of
    K_II that yields the order costs less than the fill the order saves (docs:
    changelog, 'Speed of the kernels').  With K = L U, the trailing blocks give
    the Schur complement K_S = K_SS - K_SI K_II^-1 K_IS = L_SS U_SS, the
    exact stiffness of the body seen from S, at the price of one sparse
    factorization.  Full displacements for forces acting on S are recovered
    with the same factors (`full_displacement`).
    """

    def __init__(self, disc: Discretization, K: sp.csr_matrix, surface_dofs: np.ndarray):
        self.disc = disc
        free = disc.free
        n = len(free)
        pos = np.full(disc.ndofs, -1)
        pos[free] = np.arange(n)
        spos = pos[surface_dofs]
        if np.any(spos < 0):
            raise RuntimeError("a contact dof is fixed by the supports")
        m = len(spos)
        Kff = K[free][:, free].tocsr()
        inner = np.ones(n, dtype=bool)
        inner[spos] = False
        inner = np.nonzero(inner)[0]
        _, order = minimum_degree(Kff[inner][:, inner].tocsc(), **SYMMETRIC)
        perm = np.concatenate((inner[order], spos))
        Kp = Kff[perm][:, perm].tocsc()
        lu = spl.splu(Kp, permc_spec="NATURAL", **SYMMETRIC)
        tail = np.arange(n - m, n)
        if not (np.array_equal(lu.perm_c[tail], tail) and np.array_equal(lu.perm_r[tail], tail)):
            raise RuntimeError("the factorization did not keep the contact dofs last")
        Ks = _trailing(lu.L, m) @ _trailing(lu.U, m)
        self.stiffness = 0.5 * (Ks + Ks.T)
        self.lu = lu
        self.perm = perm
        self.n = n
        self.m = m
        self.surface_dofs = surface_dofs

    def full_displacement(self, f_surface: np.ndarray) -> np.ndarray:
        """Displacement vector(s) (ndofs[, k]) for surface forces f_S (m[, k])."""
        disc = self.disc
        rhs = np.zeros((self.n,) + f_surface.shape[1:])
        rhs[self.n - self.m:] = f_surface
        x = self.lu.solve(rhs)
        u = np.zeros((disc.ndofs,) + f_surface.shape[1:])
        u[disc.free[self.perm]] = x
        return u


class OrderedLU:
    """SuperLU factorizations of a sequence of sparse matrices (a Newton tangent
    step after step), the fill-reducing ordering computed once per sparsity pattern.

    SuperLU orders the columns again at every factorization (minimum degree on
    the pattern of A^T + A, ``permc_spec="MMD_AT_PLUS_A"``), although a mesh's
    tangent keeps its pattern for a whole run, so that the ordering is repeated
    for nothing.  Here the first factorization of a pattern is SuperLU's own;
    its column order (postordered) is kept, and the next matrices of the same
    pattern are permuted symmetrically by it and factorized in their natural order
    with the same options.  The factors are SuperLU's up to round-off (their
    fill is the same; solutions agree to about 1e-14).  ``diag_pivot_thresh``
    and ``SymmetricMode`` are SuperLU's (0: pivots on the diagonal only).
    """

    def __init__(self, diag_pivot_thresh: float):
        self.options = dict(diag_pivot_thresh=float(diag_pivot_thresh),
                            options=dict(SymmetricMode=True))
        self._pattern = None

    def factor(self, K: sp.csc_matrix) -> "OrderedLU.Factors":
        """Factors of the CSC matrix `K`, with ``solve(b)`` for K x = b.  Raises
        SuperLU's RuntimeError (a zero pivot) as `scipy.sparse.linalg.splu` does."""
        K = K.tocsc()
        pattern = self._pattern
        if pattern is None or not (np.array_equal(pattern[0], K.indptr)
                                   and np.array_equal(pattern[1], K.indices)):
            lu, order = minimum_degree(K, **self.options)
            self._set_order(K, order)
            return self.Factors(lu, None)
        order, slots, indptr, indices = self._permuted
        Kp = sp.csc_matrix((K.data[slots], indices, indptr), shape=K.shape)
        return self.Factors(spl.splu(Kp, permc_spec="NATURAL", **self.options), order)

    def _set_order(self, K, order):
        """Keep `order` for K's pattern, and where each entry of K lands in
        K[order][:, order] (CSC, sorted indices)."""
        self._pattern = (K.indptr.copy(), K.indices.copy())
        tag = sp.csc_matrix((np.arange(1.0, K.nnz + 1.0), K.indices, K.indptr), shape=K.shape)
        Kp = tag[order][:, order].tocsc()
        Kp.sort_indices()
        self._permuted = (order, Kp.data.astype(np.int64) - 1, Kp.indptr, Kp.indices)

    class Factors:
        """LU factors of K, or of K[order][:, order] (`order` not None)."""

        def __init__(self, lu, order):
            self.lu = lu
            self.order = order

        def solve(self, b: np.ndarray) -> np.ndarray:
            if self.order is None:
                return self.lu.solve(b)
            x = np.empty_like(b, dtype=float)
            x[self.order] = self.lu.solve(np.asarray(b, float)[self.order])
            return x
