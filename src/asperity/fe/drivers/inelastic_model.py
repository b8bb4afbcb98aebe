"""The inelastic asperity's equilibrium at the end of a step: Newton on the full
system with per-point state (`solve_asperity_history`).

Method (the incremental counterpart of report 3.22, in the implicit form
that FE codes use): the time is divided into steps; at each step the
global equilibrium

    R(u) = int B^T sigma(eps(u); state_n, dt) dV + int t_N(a(u)) N ds = 0

is solved by Newton on the *full* system (all free dofs, no condensation,
which only holds for a linear body) with the material's consistent tangent
at the quadrature points plus the penalty contact tangent.  Internal
variables are carried per quadrature point and committed only when the
step is accepted.  Everything is vectorized over elements and quadrature
points (`Discretization.B`, sparse strain operator, one batched matmul for
the element matrices scattered into a sparsity pattern built once).

Points with negligible flow (`InelasticModel.point_time_steps`): a
rate-dependent material flows at every stressed point, but the exponential
flow law of Bodner-Partom makes the flow of most of the body vanishingly
small; the material update treats those points as elastic (time step 0),
which saves their local Newton iterations and tangents.

Linear solves: SuperLU with a symmetric minimum degree ordering of the
(structurally symmetric) tangent and diagonal pivots; if that fails or is
not finite, the default partial pivoting.
"""

from __future__ import annotations

import logging
import math
from dataclasses import replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

from asperity.fe.solvers import nonlinear
from asperity.fe.discretization.assembly import OrderedLU
from asperity.fe.contact.penalty import (PENALTY_FACTOR, C1Penalty, ContactZone,
                                         contact_edge_pressure)
from asperity.fe.errors import StepFailed
from asperity.fe.discretization.kinematics import SmallStrain, kinematics_for
from asperity.fe.materials.elastic import LinearElastic, equivalent_strain, von_mises
from asperity.fe.solvers.nonlinear import Problem, ResidualSearch, check_local_update

log = logging.getLogger(__name__)

#: the iterations that `PACE` counts are those to a residual of this x the
#: contact forces (or to the step's own tolerance, if looser): a tighter Newton
#: tolerance (the 'fine' preset's 1e-10) polishes a converged step and says
#: nothing of whether the step was too long, so it does not keep the steps short
PACE_TOLERANCE = 1e-8


#: points with negligible flow (see InelasticModel.point_time_steps)
FLOW_STRESS_MARGIN, NEGLIGIBLE_FLOW = 1.25, 1e-9


#: Newton's line search: the residual norm, halved at most this many times
LINE_SEARCH = ResidualSearch(halvings=6)


def elastic_part(material) -> LinearElastic:
    """The elastic constants of an inelastic material, for meshing."""
    return LinearElastic(material.E, material.nu)


class InelasticModel:
    """Full (uncondensed) Newton on a fixed mesh with per point state."""

    def __init__(self, disc, geometry, material, preset: dict, r_candidate: float,
                 penalty_factor: float = PENALTY_FACTOR, tolerance: float | None = None,
                 kinematics: str = "small"):
        self.disc = disc
        self.geometry = geometry
        self.material = material
        self.preset = preset
        self.penalty_factor = float(penalty_factor)
        self.tolerance = preset["tolerance"] if tolerance is None else float(tolerance)
        self.max_iterations = preset["max_iterations"]
        self.kinematics = kinematics_for(disc, kinematics)
        # the linear kinematics also measure round-off and the time error
        self.linear = self.kinematics if not self.kinematics.finite else SmallStrain(disc)
        self.free = disc.free
        self.shape = disc.weights.shape  # (ne, nq)
        self._absBT = abs(self.linear.Bsp).T.tocsr()
        self._pattern()
        self._set_zone(r_candidate)
        self.factorizations = 0
        self._lu = OrderedLU(diag_pivot_thresh=0.0)

    def _pattern(self):
        """Sparsity of the free-free tangent, built once (CSC), and the map of
        every element matrix entry to its slot (entries on fixed dofs dropped)."""
        disc = self.disc
        n = len(self.free)
        pos = np.full(disc.ndofs, -1)
        pos[self.free] = np.arange(n)
        self._pos = pos
        ed = pos[disc.element_dofs]  # (12, ne)
        rows = np.broadcast_to(ed[:, None, :], (ed.shape[0],) + ed.shape)
        cols = np.broadcast_to(ed[None, :, :], (ed.shape[0],) + ed.shape)
        # element matrices are stored (ne, 12, 12): entry order e, i, j
        rows = np.moveaxis(rows, 2, 0).ravel()
        cols = np.moveaxis(cols, 2, 0).ravel()
        keep = (rows >= 0) & (cols >= 0)
        key = cols[keep].astype(np.int64) * n + rows[keep]
        ukey, inverse = np.unique(key, return_inverse=True)
        self._keep = np.flatnonzero(keep)
        self._slot = inverse
        self._nnz = len(ukey)
        self._indices = (ukey % n).astype(np.int32)
        counts = np.bincount(ukey // n, minlength=n)
        self._indptr = np.concatenate(([0], np.cumsum(counts))).astype(np.int32)
        self._keys = ukey
        self._n = n

    def _contact_slots(self):
        """Slots of the contact (facet) couplings of the zone's u_z dofs."""
        zone = self.zone
        fn = zone.facet_nodes
        g = self._pos[zone.dofs][fn]  # (3, nf) free positions
        ii = np.broadcast_to(g[:, None, :], (3, 3, g.shape[1])).ravel()
        jj = np.broadcast_to(g[None, :, :], (3, 3, g.shape[1])).ravel()
        if np.any(ii < 0):
            raise RuntimeError("a contact dof is fixed by the supports")
        key = jj.astype(np.int64) * self._n + ii
        slot = np.searchsorted(self._keys, key)
        if np.any(self._keys[np.minimum(slot, self._nnz - 1)] != key):
            raise RuntimeError("contact couplings outside the element pattern")
        return slot

    def _set_zone(self, r_candidate: float):
        top = self.disc.top
        outer = top.coords[0, 2::2]
        nf = int(np.searchsorted(outer, r_candidate)) + 1
        nf = max(2, min(nf, top.nfacets - 1))
        self.r_candidate = float(outer[nf - 1])
        self.zone = ContactZone(top, nf, self.geometry)
        self.law = C1Penalty.for_zone(self.zone, self.material.contact_modulus,
                                      self.penalty_factor)
        self._cslot = self._contact_slots()

    def grow_zone(self) -> bool:
        if self.zone.nfacets >= self.disc.top.nfacets - 1:
            return False
        self._set_zone(1.5 * self.r_candidate)
        return True

    @property
    def dofs(self) -> int:
        return len(self.free)

    # --- residual and tangent ------------------------------------------------
    def _contact(self, u, w):
        zone = self.zone
        a = zone.penetration(u[zone.dofs], w)
        t, dt = self.law.traction(a)
        return a, t, dt

    def evaluate(self, u, w, state, dt, tangent=True):
        """Residual (ndofs,) and the fields (with the point tangents ``D``)."""
        strain, deformation = self.kinematics.strain(u)
        dtp = self.point_time_steps(strain, state, dt)
        stress, D, new = self.material.update(strain, state, dtp, tangent=tangent)
        if dtp is not dt and hasattr(new, "time"):
            new.time = state.time + dt
        R = self.kinematics.internal_force(deformation, stress)
        _, t, tn = self._contact(u, w)
        R[self.zone.dofs] += self.zone.nodal(t)
        out = dict(strain=strain, stress=stress, state=new, traction=t, D=D, dtraction=tn,
                   deformation=deformation)
        return R, out

    def point_time_steps(self, strain, state, dt):
        """The time step of each point: `dt` where the material may flow, 0
        where its flow over the step is negligible, so that the material
        update treats those points as elastic (a rate-dependent material
        flows at every stressed point; the exponential flow law of
        Bodner-Partom makes most of the body's flow vanishingly small).

        Negligible: the inelastic strain the flow rule gives over dt at
        ``FLOW_STRESS_MARGIN`` times the elastic trial stress (an upper
        bound: the flow relaxes the stress and hardens) makes a Mises stress
        below ``NEGLIGIBLE_FLOW`` times the largest trial stress.
        """
        mat = self.material
        if not (np.ndim(dt) == 0 and dt > 0 and hasattr(mat, "rates")):
            return dt
        trial = np.tensordot(mat.tangent(), strain - state.inelastic_strain, axes=(1, 0))
        probe = replace(state, stress=FLOW_STRESS_MARGIN * trial)
        flow = equivalent_strain(mat.rates(probe)["inelastic_strain"]) * dt
        q = von_mises(trial)
        negligible = 3.0 * mat.G * flow <= NEGLIGIBLE_FLOW * float(np.max(q))
        if not np.any(negligible):
            return dt
        return np.where(negligible, 0.0, dt)

    def jacobian(self, out) -> sp.csc_matrix:
        """Consistent tangent on the free dofs: material plus contact penalty."""
        Ke = self.kinematics.element_matrices(out["deformation"], out["stress"], out["D"])
        data = np.bincount(self._slot, weights=Ke.ravel()[self._keep], minlength=self._nnz)
        zone = self.zone
        q = out["dtraction"] * zone.weights
        vals = np.einsum("fg,ig,jg->ijf", q, zone.N, zone.N)
        data += np.bincount(self._cslot, weights=vals.ravel(), minlength=self._nnz)
        return sp.csc_matrix((data, self._indices, self._indptr), shape=(self._n, self._n))

    def jacobian_reference(self, out) -> sp.csc_matrix:
        """The same tangent by the general assembly (`Discretization.stiffness`)."""
        K = self.disc.stiffness(np.asarray(out["D"]))
        zd = self.zone.dofs
        Kc = sp.coo_matrix(self.zone.matrix(out["dtraction"]))
        K = K + sp.csr_matrix((Kc.data, (zd[Kc.row], zd[Kc.col])), shape=K.shape)
        return K[self.free][:, self.free].tocsc()

    def factorize(self, out):
        """LU factors of the consistent tangent at `out`: SuperLU with a
        symmetric ordering, kept for the mesh's pattern (`OrderedLU`), and
        diagonal pivots (the tangent is structurally symmetric, nearly always
        symmetric positive definite), or, if that fails, with the default
        partial pivoting.  Returns (lu, K, pivoted)."""
        K = self.jacobian(out)
        self.factorizations += 1
        try:
            with np.errstate(all="ignore"):
                return self._lu.factor(K), K, False
        except RuntimeError:
            return spl.splu(K), K, True

    def newton_correction(self, out, Rf):
        """The Newton correction d: K d = -R with the tangent at `out`."""
        lu, K, pivoted = self.factorize(out)
        with np.errstate(all="ignore"):
            d = lu.solve(-Rf)
        if not np.all(np.isfinite(d)) and not pivoted:
            d = spl.splu(K).solve(-Rf)
        return d

    def solve_step(self, u0, w, state, dt, reference: float = 0.0):
        """Newton from u0 for the step ending at interference w; returns (u, out,
        its, paced): paced the iterations to ``PACE_TOLERANCE`` (or to the
        tolerance, if looser), the count the step control reads (`PACE`).

        Converged when ||R|| <= tolerance x the norm of the nodal contact
        forces: those of the current iterate, or, if larger, up to twice
        `reference` (the contact forces of the last accepted step), so that
        an overshooting predictor (a node pushed deep into the stiff
        penalty) does not inflate the scale; or at the round-off level of
        the internal forces.
        """
        step = _Step(self, w, state, dt, reference, max(self.tolerance, PACE_TOLERANCE))
        u, out, its = nonlinear.newton(step, u0, self.tolerance, self.max_iterations, LINE_SEARCH)
        return u, out, its, its if step.paced is None else step.paced

    # --- outputs -------------------------------------------------------------
    def point_position(self, index) -> tuple:
        """(r or x, depth below the undeformed top surface) [m] of quadrature
        point `index` (flat index over (ne, nq))."""
        x = self.disc.x.reshape(2, -1)[:, index]
        top = self.disc.top.coords
        depth = float(np.interp(x[0], top[0], top[1]) - x[1])
        return float(x[0]), max(depth, 0.0)

    def record(self, u, w, out) -> dict:
        zone = self.zone
        t = out["traction"]
        force = zone.total(t)
        radius = 0.0
        if force > 0:
            pen = zone.node_penetration(u[zone.dofs], w)
            radius = contact_edge_pressure(zone.coords[0], -pen, zone.node_traction(t), pen > 0)
            if self.kinematics.finite:  # the edge on the deformed surface
                top = self.disc.top
                radius += float(np.interp(radius, top.coords[0], u[top.node_r_dofs]))
        strain, stress, state = out["strain"], out["stress"], out["state"]
        e11, e22, e33, e12 = strain
        c = 0.5 * (e11 + e22)
        rad = np.sqrt((0.5 * (e11 - e22)) ** 2 + e12**2)
        principal = np.max(np.stack((np.abs(c + rad), np.abs(c - rad), np.abs(e33))))
        damage = getattr(state, "damage", None)
        ruptured = getattr(state, "ruptured", None)
        return dict(
            interference=w,
            force=force,
            contact_radius=radius,
            contact_area=math.pi * radius**2 if self.geometry.axisymmetric else 2 * radius,
            max_equivalent_strain=float(equivalent_strain(strain).max()),
            max_inelastic_strain=float(equivalent_strain(state.inelastic_strain).max()),
            max_von_mises=float(von_mises(stress).max()),
            max_principal_strain=float(principal),
            max_damage=0.0 if damage is None else float(np.max(damage)),
            ruptured_points=0 if ruptured is None else int(np.count_nonzero(ruptured)),
            overflow=bool(np.any(t[-1] > 0)),
        )


class _Step(Problem):
    """Equilibrium at the end of a step (`InelasticModel.solve_step`)."""

    def __init__(self, model: InelasticModel, w, state, dt, reference: float,
                 pace_tolerance: float):
        self.model, self.w, self.state, self.dt = model, w, state, dt
        self.force_scale = nonlinear.ContactScale(reference)
        self.pace_tolerance = pace_tolerance
        self.paced = None  # the first iteration with ||R|| <= pace_tolerance x scale

    def monitor(self, iteration, rn, scale, out):
        if self.paced is None and rn <= self.pace_tolerance * scale:
            self.paced = iteration

    def evaluate(self, u):
        R, out = self.model.evaluate(u, self.w, self.state, self.dt)
        return R[self.model.free], out

    def check(self, out, iteration):
        check_local_update(out["state"], iteration)

    def scale(self, u, out):
        return self.force_scale(float(np.linalg.norm(self.model.zone.nodal(out["traction"]))))

    def floor(self, u, out):
        """Round-off of the internal forces (sum of |terms|)."""
        m = self.model
        return 1e3 * np.finfo(float).eps * float(np.linalg.norm(
            (m._absBT @ np.abs(out["stress"].ravel() * m.linear.W4))[m.free]))

    def direction(self, u, Rf, out, tangent, iteration):
        try:
            d = self.model.newton_correction(out, Rf)
        except RuntimeError as exc:  # singular
            raise StepFailed(f"linear solve failed: {exc}", iteration) from None
        full = np.zeros_like(u)
        full[self.model.free] = d
        return full
