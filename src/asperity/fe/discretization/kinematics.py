"""Kinematics of the two-dimensional inelastic driver: small strain, or
finite strain in logarithmic strain space.

`SmallStrain` is the linear kinematics of report 3.23: strains e = B u,
internal forces int B^T sigma dV, element matrices int B^T D B dV.

`FiniteStrain` is the total Lagrangian formulation with the *additive
plasticity in logarithmic strain space* of Miehe, Apel and Lambrecht
(Comput. Methods Appl. Mech. Engrg. 191 (2002) 5383-5425).  The material
of the small-strain theory (report 3.2.2: `J2Plasticity`, `BodnerPartom`,
its internal variables, damage and directional hardening, and its
consistent tangent) is used unchanged, fed with the Lagrangian Hencky
strain instead of the linearized one:

    F = I + Grad u,   C = F^T F,   E = 1/2 ln C,
    T, D = material.update(E, state, dt)     (the small-strain update),
    S = T : P,   P = 2 dE/dC,                (second Piola-Kirchhoff stress)
    dS/dE_GL = P^T : D : P + T : L,   L = 4 d^2E/dC^2,

with E_GL = (C - I) / 2 the Green-Lagrange strain whose variation
delta E_GL = sym(F^T Grad delta u) is the work conjugate of S (Miehe et al.,
eqs. 2.11, 2.13, 3.5).  The elastic response T = C_e : (E - E_p) of
moderate elastic strain (metals: E_e below 1 %) is then a Hencky
hyperelastic law, the inelastic strain accumulates additively in log
space, rigid rotations leave E (so the response) unchanged, and for
isotropic materials the scheme is the exponential-map return of
Eterovic and Bathe (1990) and Simo (1992).  The residual is

    R = int (delta E_GL : S) dV_0 + contact,

integrated over the undeformed body (dV_0 = R dR dZ in axisymmetry); the
contact with the rigid flat is exact in this setting: the flat is normal
to z, so the gap of a surface point is z + u_z - z_flat whatever its
radial motion, and the penalty traction is a force per undeformed area.

The derivatives of the isotropic matrix function E(C) use the
eigenvectors Q and eigenvalues lambda of C (the in-plane 2 x 2 block
and, in axisymmetry, the hoop stretch C_33 = (1 + u_r / R)^2) and the
divided differences of f = 1/2 ln (Daleckii-Krein):

    dE[A]      = Q (f[1](lambda_i, lambda_j) o A') Q^T,
    d^2E[A, B] = Q (sum_k f[2](lambda_i, lambda_k, lambda_j)
                    (A'_ik B'_kj + B'_ik A'_kj)) Q^T,

A' = Q^T A Q; the first divided differences are exact to round-off for
equal eigenvalues (the undeformed body), the second, which enter only
the tangent, to 1e-8 relative.
"""

from __future__ import annotations

import functools

import numpy as np
import scipy.sparse as sp

from asperity.fe.errors import StepFailed
from asperity.fe.materials.elastic import METRIC

#: kinematics of the inelastic driver
KINEMATICS = ("small", "finite")
#: close eigenvalues: below this relative distance the divided differences
#: are taken from their Taylor series
_CLOSE = 1e-4


def divided_log(a, b):
    """f[a, b] = (f(a) - f(b)) / (a - b) of f = 1/2 ln; f'(a) at a = b."""
    x = (a - b) / b
    close = np.abs(x) < _CLOSE
    xs = np.where(close, 1.0, x)
    far = 0.5 * np.log1p(xs) / (b * xs)
    near = (0.5 / b) * (1.0 + x * (-0.5 + x * (1.0 / 3.0 - 0.25 * x)))
    return np.where(close, near, far)


def divided_log2(a, b, c):
    """Second divided difference f[a, b, c] of f = 1/2 ln (symmetric in
    its arguments); f''/2 = -1 / (4 m^2) at the mean m where all three
    are within `_CLOSE` of each other."""
    lo = np.minimum(np.minimum(a, b), c)
    hi = np.maximum(np.maximum(a, b), c)
    mid = a + b + c - lo - hi
    span = hi - lo
    close = span < _CLOSE * hi
    den = np.where(close, 1.0, span)
    far = (divided_log(hi, mid) - divided_log(mid, lo)) / den
    m = (a + b + c) / 3.0
    return np.where(close, -0.25 / m**2, far)


def _eigen2(a, b, e):
    """Eigen-decomposition of the symmetric 2 x 2 matrices [[a, e], [e, b]] in
    closed form (errors at the round-off of the matrix's own size): the
    eigenvalues m - r, m + r and (cos, sin) of the angle theta of the second
    eigenvector; the first is (-sin, cos)."""
    m, d = 0.5 * (a + b), 0.5 * (a - b)
    r = np.hypot(d, e)
    theta = 0.5 * np.arctan2(e, d)
    return m - r, m + r, np.cos(theta), np.sin(theta)


class SmallStrain:
    """Linear kinematics: e = B u (`assembly.Discretization.B`)."""

    finite = False

    def __init__(self, disc):
        self.disc = disc
        self.shape = disc.weights.shape  # (ne, nq)
        self.Bsp = disc.strain_operator()
        self.BspT = self.Bsp.T.tocsr()
        self.W4 = (METRIC[:, None, None] * disc.weights[None]).ravel()
        # strain-displacement matrices per point (ne, nq, 4, 12) for batched matmul
        self._Bm = np.ascontiguousarray(np.transpose(disc.B, (2, 3, 0, 1)))
        ne, nq = self.shape
        BtW = np.swapaxes(self._Bm * (METRIC[:, None] * disc.weights[:, :, None, None]), 2, 3)
        # (ne, 12, nq * 4): B^T W of all points of an element side by side
        self._BtW = np.ascontiguousarray(BtW.transpose(0, 2, 1, 3).reshape(ne, -1, nq * 4))

    def strain(self, u):
        """(strain (4, ne, nq), None)."""
        return self.disc.strain(u), None

    def internal_force(self, deformation, stress):
        return self.BspT @ (stress.ravel() * self.W4)

    def element_matrices(self, deformation, stress, D):
        """int B^T D B dV per element, (ne, 12, 12)."""
        ne, nq = self.shape
        D = np.asarray(D)
        if D.ndim == 2:
            DB = np.matmul(D[None, None], self._Bm)  # (ne, nq, 4, 12)
        else:
            DB = np.matmul(np.transpose(D, (2, 3, 0, 1)), self._Bm)
        return np.matmul(self._BtW, DB.reshape(ne, nq * 4, -1))


class Deformation:
    """F, the eigen-decomposition of C and the first divided differences at
    every point (flattened, n = ne * nq), from `FiniteStrain.strain`.

    Every symmetric tensor of the axisymmetric (or plane) body has the four
    stored components [11, 22, 33, 12]; so do its images under the
    eigenvectors of C, Q = [[-sin, cos, 0], [cos, sin, 0], [0, 0, 1]], which
    is symmetric and orthogonal: Q^T A Q = Q A Q^T is one (n, 4, 4) matrix
    ``M`` on stored components, and the matrix functions of C act on
    [11, 22, 33, 12] of the eigenbasis without coupling the hoop direction.
    """

    def __init__(self, H):
        hrr, hzz, htt, hrz, hzr = H
        self.F = np.stack((1.0 + hrr, 1.0 + hzz, 1.0 + htt, hrz, hzr))  # [rr, zz, 33, rz, zr]
        self.J = ((1.0 + hrr) * (1.0 + hzz) - hrz * hzr) * (1.0 + htt)
        # C - I = H + H^T + H^T H, from H (not from F = 1 + H: the strains of a
        # barely touched body are far below the round-off of C's unit diagonal)
        a = 2.0 * hrr + hrr**2 + hzr**2
        b = 2.0 * hzz + hzz**2 + hrz**2
        e = hrz + hzr + hrr * hrz + hzr * hzz
        mu0, mu1, c, s = _eigen2(a, b, e)
        self.mu = np.stack((mu0, mu1, htt * (2.0 + htt)), axis=1)  # eigenvalues of C - I
        lam = 1.0 + self.mu
        self.lam = lam
        self.admissible = bool(np.all(self.J > 0) and np.all(self.mu > -1.0))
        n = len(lam)
        M = np.zeros((n, 4, 4))
        s2, c2, sc = s * s, c * c, s * c
        M[:, 0, 0], M[:, 0, 1], M[:, 0, 3] = s2, c2, -2.0 * sc
        M[:, 1, 0], M[:, 1, 1], M[:, 1, 3] = c2, s2, 2.0 * sc
        M[:, 2, 2] = 1.0
        M[:, 3, 0], M[:, 3, 1], M[:, 3, 3] = -sc, sc, c2 - s2
        self.M = M
        # 2 f[lambda_i, lambda_j] on the stored components of the eigenbasis
        self.p = 2.0 * divided_log(lam[:, [0, 1, 2, 0]], lam[:, [0, 1, 2, 1]])  # (n, 4)
        self._piola = None

    def _map(self, v):
        """Q A Q^T of stored components (n, 4)."""
        return np.einsum("nab,nb->na", self.M, v)

    def log_strain(self):
        """E = 1/2 ln C, stored components (4, n)."""
        e = np.zeros((len(self.lam), 4))
        e[:, :3] = 0.5 * np.log1p(self.mu)
        return self._map(e).T

    def projection(self):
        """P = 2 dE/dC as a (n, 4, 4) matrix on stored components."""
        return np.einsum("nab,nb,nbc->nac", self.M, self.p, self.M)

    def second_piola(self, T):
        """S = P[T] (stored components (4, n)) of the log-space stress T (4, ...);
        the last one is kept, as the residual and the tangent of a Newton
        iterate both ask for it."""
        if self._piola is None or self._piola[0] is not T:
            self._piola = (T, self._map(self.p * self._map(T.reshape(4, -1).T)).T)
        return self._piola[1]

    def geometric(self, T):
        """T : L = 4 d^2E/dC^2 [T, .] as a (n, 4, 4) matrix on stored components.

        In the eigenbasis, Y_ij = sum_k f[l_i, l_k, l_j] (T_ik B_kj + B_ik T_kj)
        is linear in B; with T and B without in-plane/hoop coupling only five
        second divided differences enter."""
        lam = self.lam
        l0, l1, l2 = lam[:, 0], lam[:, 1], lam[:, 2]
        g000, g111, g222 = -0.25 / l0**2, -0.25 / l1**2, -0.25 / l2**2
        g001, g011 = divided_log2(l0, l0, l1), divided_log2(l0, l1, l1)
        t = self._map(T.T)  # T in the eigenbasis, (n, 4)
        L = np.zeros((len(lam), 4, 4))
        L[:, 0, 0], L[:, 0, 3] = 2.0 * g000 * t[:, 0], 2.0 * g001 * t[:, 3]
        L[:, 1, 1], L[:, 1, 3] = 2.0 * g111 * t[:, 1], 2.0 * g011 * t[:, 3]
        L[:, 2, 2] = 2.0 * g222 * t[:, 2]
        L[:, 3, 0], L[:, 3, 1] = g001 * t[:, 3], g011 * t[:, 3]
        L[:, 3, 3] = g001 * t[:, 0] + g011 * t[:, 1]
        return 4.0 * np.einsum("nab,nbc,ncd->nad", self.M, L, self.M, optimize=True)

    @functools.cached_property
    def strain_variation(self):
        """B_NL (n, 4, 5): delta E_GL = sym(F^T delta H) in stored components
        of the gradient components [rr, zz, 33, rz, zr] (`FiniteStrain`)."""
        Frr, Fzz, Ftt, Frz, Fzr = self.F
        Bn = np.zeros((len(Frr), 4, 5))
        Bn[:, 0, 0], Bn[:, 0, 4] = Frr, Fzr
        Bn[:, 1, 1], Bn[:, 1, 3] = Fzz, Frz
        Bn[:, 2, 2] = Ftt
        Bn[:, 3, 0], Bn[:, 3, 1], Bn[:, 3, 3], Bn[:, 3, 4] = 0.5 * Frz, 0.5 * Fzr, 0.5 * Frr, 0.5 * Fzz
        return Bn


class FiniteStrain:
    """Total Lagrangian kinematics with the logarithmic strain (module docstring)."""

    finite = True

    def __init__(self, disc):
        self.disc = disc
        self.shape = disc.weights.shape
        basis = disc.basis
        nloc = disc.element_dofs.shape[0]
        ne, nq = self.shape
        G = np.zeros((5, nloc, ne, nq))
        for i, (phi, *_) in enumerate(basis.basis):
            g = phi.grad
            G[0, i], G[1, i] = g[0][0], g[1][1]
            if disc.axisymmetric:
                G[2, i] = np.asarray(phi)[0] / disc.x[0]
            G[3, i], G[4, i] = g[0][1], g[1][0]
        rows = np.broadcast_to(np.arange(5 * ne * nq).reshape(5, 1, ne, nq), G.shape)
        cols = np.broadcast_to(disc.element_dofs[None, :, :, None], G.shape)
        self.Gsp = sp.csr_matrix((G.ravel(), (rows.ravel(), cols.ravel())),
                                 shape=(5 * ne * nq, disc.ndofs))
        self.GspT = self.Gsp.T.tocsr()
        Gm = np.transpose(G, (2, 3, 0, 1))  # (ne, nq, 5, 12)
        self._Gm = np.ascontiguousarray(Gm.reshape(ne * nq, 5, nloc))
        # (ne, 12, nq * 5): Grad^T of all points of an element side by side
        self._GmT = np.ascontiguousarray(np.swapaxes(Gm, 2, 3).transpose(0, 2, 1, 3)
                                         .reshape(ne, nloc, nq * 5))
        self.w = disc.weights.ravel()

    def strain(self, u):
        """(E (4, ne, nq) the Lagrangian Hencky strain, `Deformation`).

        An inverted point (det F <= 0) fails the Newton try (`StepFailed`),
        so that the step is cut."""
        d = Deformation((self.Gsp @ u).reshape(5, -1))
        if not d.admissible:
            raise StepFailed("an element is inverted (det F <= 0)", 0)
        return d.log_strain().reshape((4,) + self.shape), d

    def internal_force(self, deformation, stress):
        S = deformation.second_piola(stress)
        Bn = deformation.strain_variation  # (n, 4, 5)
        h = np.einsum("nai,an->in", Bn, METRIC[:, None] * S * self.w)
        return self.GspT @ h.ravel()

    def element_matrices(self, deformation, stress, D):
        """int Grad^T (B_NL^T M B_NL + Sigma) Grad dV_0 per element, (ne, 12, 12):
        M = P D P + T : L the material tangent dS/dE_GL, Sigma the initial
        stress matrix of S on the gradient components."""
        ne, nq = self.shape
        n = ne * nq
        T = stress.reshape(4, -1)
        D = np.asarray(D)
        Dn = D[None] if D.ndim == 2 else np.transpose(D.reshape(4, 4, n), (2, 0, 1))
        P = deformation.projection()
        M = np.einsum("nab,nbc,ncd->nad", P, np.broadcast_to(Dn, (n, 4, 4)), P, optimize=True)
        M += deformation.geometric(T)
        Bn = deformation.strain_variation
        K5 = np.einsum("nai,a,nab,nbj->nij", Bn, METRIC, M, Bn, optimize=True)
        Srr, Szz, Stt, Srz = deformation.second_piola(stress)
        K5[:, 0, 0] += Srr
        K5[:, 4, 4] += Srr
        K5[:, 3, 3] += Szz
        K5[:, 1, 1] += Szz
        K5[:, 2, 2] += Stt
        K5[:, 0, 3] += Srz
        K5[:, 3, 0] += Srz
        K5[:, 4, 1] += Srz
        K5[:, 1, 4] += Srz
        K5 *= self.w[:, None, None]
        KG = np.matmul(K5, self._Gm)  # (n, 5, 12)
        return np.matmul(self._GmT, KG.reshape(ne, nq * 5, -1))


def kinematics_for(disc, name: str):
    """The kinematics object of `name` (`KINEMATICS`) on discretization `disc`."""
    if name == "small":
        return SmallStrain(disc)
    if name == "finite":
        return FiniteStrain(disc)
    raise ValueError(f"kinematics must be one of {KINEMATICS}, got {name!r}")
