"""The 3-D asperity against the moving flat: residual, tangent, Newton (report 3.3, 3.4, 9.2).

Weak form: the incremental (backward-Euler) counterpart of report (3.22):
at each time step the equilibrium

    R(u) = int B^T sigma(eps(u); state_n, dt) dV - int N^T t(u) ds = 0

is solved by Newton with the material's consistent tangent at the
quadrature points (`BodnerPartom.update` or `J2Plasticity.update` with 6
strain components, or a linear elastic body), plus the contact tangent alpha_ij of (3.26, 3.27)
(`sliding.contact_tangent`).  Strains are [e11, e22, e33, e12, e13, e23]
(tensor shears, work product weights 1, 1, 1, 2, 2, 2).

Contact (3.3.2, 3.4.1).  The flat is the plane z = -w(t) (w the approach
from first touch at the apex) moved by delta(t) along x.  The contact lives on
the P2 nodes of the top facets near the apex, with the hat functions phi_i on
their sub-triangles (`half_model.HalfModel`).
At node i the weighted penetration a_i = int phi_i (Z + gap_offset + u_z +
w) ds / int phi_i ds gives the normal pressure t_N,i by the C1 penalty of
3.3.2 (`contact.C1Penalty`, kappa = c E' / h, h the mean size of the
node's facets); the tangential traction is the regularized sliding
resistance of 3.3.4 (`sliding.FrictionLaw`) of the weighted relative
displacement b_i = (X + u_x - delta, Y + u_y)_i - anchor_i, with the
anchors dragged after each accepted step (`sliding.drag_anchor`).  The
traction on the body, (t_x, t_y, -t_N) interpolated from the nodes by the
phi_i, is integrated against the P2 shape functions.  The contact area is
the weight int phi_i ds of the nodes with t_N > 0 (a staircase of a
sub-triangle's size about each node).

Shear resistance and the normal pressure.  The law as printed: h(t_N) at
the pressure of the current Newton iterate, with its full linearization
(the d t / d t_N d t_N / d a coupling of 3.26, 3.27, 20 times the penalty
stiffness with the mu = 20 of report 9.2), so that a point that enters the
contact during a step carries its shear resistance in that step and the
bound does not lag the pressure.  (With an explicit bound, h at the
pressure of the last accepted step, a point new to the contact would have
no shear resistance in its first step, and the sliding forces would depend
on the step size; issue #14.)  When the junction starts to slide the
coupled problem is stiff and Newton may need the step cut a few times.
Past the junction's critical friction coefficient
(`SlidingModel.critical_factor`, computed and reported where sliding starts
and after every sliding step) the problem of a slipping junction is not
unique and Newton may stall: report 9.2's mu = 20 is past it at `standard`
for much of the slide, and a run that stalls there stops (`sliding_march`; docs:
theory/single-asperity.md, 'Sliding').

Predictor: each step starts from the Euler predictor of the converged
state (the tangent and d R / d(w, delta) of the last step: the contact
points keep their stick or slip state), which carries a sticking junction
along with the flat.

Linear algebra.  The tangent is non-symmetric (friction); the bulk is
assembled into one CSC pattern built once (elastic element matrices
precomputed, only elements whose points' tangent differs from the elastic
one recomputed per iteration), the contact added as the sparse products
V^T diag(w alpha) V of the node operators, and solved with SuperLU; a
factorization is reused as the preconditioner of GMRES for the next
iterations and steps while that converges in a few iterations
(`linear.ReusedLU`).

Through the slip instability (`SlidingModel.solve_through_slip`): a sliding
step whose Newton fails after it was cut below ``stall_fraction`` of its cap
(where the steps would stall, `sliding_march`) is solved again from the state at
its start through damped solves, a pseudo-transient continuation whose dashpot on the
touching nodes makes each solve's problem unique; the step ends with the
plain Newton solve of the model.  Past the critical coefficient the
quasi-static path can turn back in the sliding displacement (the junction
would slip dynamically) and the step's problem has several solutions: the
damped motion selects the one the junction slips to, at the sliding
displacement where the cut steps stopped converging.  The same holds where a
touching node lets go although the junction's tangent was regular at the
accepted steps (the critical factor is taken there, not within the step).
The step is cut again only if that fails too (`sliding_march`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from asperity.fe.contact.penalty import SMOOTHING, C1Penalty
from asperity.fe.contact.sliding import FrictionLaw, ShearResistance, contact_tangent, drag_anchor
from asperity.fe.discretization.assembly import OrderedLU
from asperity.fe.discretization.half_model import HalfModel
from asperity.fe.errors import StepFailed
from asperity.fe.materials.elastic import equivalent_strain, von_mises
from asperity.fe.solvers import nonlinear
from asperity.fe.solvers.linear import ReusedLU
from asperity.fe.solvers.nonlinear import Problem, ResidualSearch, check_local_update

#: default penalty factor c in kappa = c E' / h_facet
PENALTY_FACTOR_3D = 100.0
#: smoothing pressure of the C1 penalty / E' (the quadratic branch covers
#: pressures below half of it)
SMOOTHING_3D = SMOOTHING
#: a point's tangent counts as elastic when |D - C| <= this * |C|
TANGENT_ELASTIC_TOL = 1e-10
#: `SlidingModel.critical_factor`: the developed slip |b| / eps_b at which the
#: junction's tangent is taken (its stiffness across the slip, h / |b|, is then
#: 1e-6 of the stick stiffness), and the largest factor sought
DEVELOPED_SLIP = 1e6
CRITICAL_FACTOR_BOUND = 1e3
#: `SlidingModel.solve_through_slip`: the dashpot on the touching points starts at
#: SLIP_DAMPING[0] times the normal penalty stiffness; after a damped solve that
#: converges it is divided by a factor of at most SLIP_DAMPING[1], down to
#: SLIP_DAMPING[2] times the stiffness, then the undamped step is solved.  A damped
#: solve that fails (in SLIP_DAMPED_ITERATIONS Newton iterations) takes the square
#: root of the factor and retries from the last converged one (a trust region on
#: the damping: it settles just above the junction's negative stiffness, where the
#: iterates run through the instability fastest); a factor near 1 that still fails
#: raises the damping by SLIP_DAMPING[1].  At most SLIP_DAMPED_SOLVES tries a step.
SLIP_DAMPING = (1.0, 4.0, 1e-6)
SLIP_DAMPED_ITERATIONS = 15
SLIP_DAMPED_SOLVES = 100


class _ElasticState:
    """State of a linear elastic body (no internal variables)."""

    def __init__(self, shape, components=6):
        self.strain = np.zeros((components,) + tuple(shape))
        self.stress = np.zeros_like(self.strain)
        self.inelastic_strain = np.zeros_like(self.strain)
        self.converged = np.ones(tuple(shape), bool)


class ElasticUpdate:
    """A linear elastic material (`LinearElastic`) behind the incremental interface."""

    is_linear = True

    def __init__(self, material):
        self.material = material
        self.E, self.nu = material.E, material.nu
        self.contact_modulus = material.contact_modulus
        self.D = material.tangent(6)

    def initial_state(self, shape, components=6):
        return _ElasticState(shape, components)

    def update(self, strain, state, dt, tangent=True):
        stress = np.tensordot(self.D, strain, axes=(1, 0))
        new = _ElasticState(strain.shape[1:])
        new.strain, new.stress = strain, stress
        return stress, (self.D if tangent else None), new


def _incremental(material):
    if hasattr(material, "update"):
        return material
    return ElasticUpdate(material)


def _elastic_tangent6(material) -> np.ndarray:
    lam, mu = material.lame
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[[0, 1, 2], [0, 1, 2]] += 2 * mu
    D[[3, 4, 5], [3, 4, 5]] = 2 * mu
    return D


@dataclass
class Interface:
    """State of the contact nodes: where each sticks on the flat (anchor,
    (2, nV), in the flat's frame)."""

    anchor: np.ndarray


class SlidingModel:
    """Residual, tangent and Newton of the 3-D asperity against the moving flat.

    ``trace``: set it to a list to record, per Newton iteration, (iteration,
    residual norm, force scale, contact nodes touching, of them slipping).
    """

    def __init__(self, model: HalfModel, material, friction: FrictionLaw,
                 penalty_factor: float = PENALTY_FACTOR_3D, tolerance: float = 1e-7,
                 max_iterations: int = 25, smoothing: float = SMOOTHING_3D,
                 line_search: int = 8):
        self.m = model
        self.material = _incremental(material)
        self.elastic = material
        self.friction = friction
        self.tolerance = float(tolerance)
        self.max_iterations = int(max_iterations)
        Ep = material.contact_modulus
        self.law = C1Penalty(penalty_factor * Ep / model.vsize, smoothing * Ep)
        self.line_search = int(line_search)
        self.penalty_factor = float(penalty_factor)
        self.C = _elastic_tangent6(material)
        self.Ke_el = model.element_matrices(self.C)
        self.data_el = model.scatter(slice(None), self.Ke_el)
        self.linear = ReusedLU()
        # the frictionless tangents of `critical_factor` (a pattern of their own)
        self._critical_lu = OrderedLU(diag_pivot_thresh=0.1)
        self.trace = None

    # --- contact --------------------------------------------------------------------------
    def contact(self, u, w, delta, anchors, tangent=True, friction: FrictionLaw | None = None,
                damping=None):
        """Contact tractions at the contact nodes: the penalty pressure t_N of the
        weighted penetration and the tangential traction with h(t_N) at this pressure
        (3.24-3.27) of the weighted slip; ``friction`` replaces the model's law.
        ``damping`` (start (2, nV), c (nV,) [Pa/m]) adds the dashpot -c (position -
        start) on the touching nodes (`solve_through_slip`).
        ``fc`` is the contact force on the free dofs."""
        m = self.m
        friction = self.friction if friction is None else friction
        U = (m.V @ u[m.free]).reshape(3, -1)                     # weighted u_x, u_y, u_z
        a = m.vz0 + U[2] + w
        tn, dtn = (x[:, 0] for x in self.law.traction(a[:, None]))
        pos = np.stack((m.vX[0] + U[0] - delta, m.vX[1] + U[1]))
        b = pos - anchors
        if friction.frictionless:
            txy = np.zeros_like(b)
            dt_db = np.zeros((2, 2) + a.shape)
            dt_dtn = np.zeros_like(b)
        else:
            txy, dt_db, dt_dtn = friction.traction(b, tn)
        if damping is not None:
            start, c = damping
            c = c * (tn > 0)
            txy = txy - c * (pos - start)
            dt_db = dt_db - np.eye(2)[:, :, None] * c
        tv = np.stack((txy[0], txy[1], -tn))                     # traction on the body
        fc = m.VT @ (m.vw * tv).ravel()
        out = dict(a=a, tn=tn, txy=txy, b=b, position=pos, fc=fc)
        if tangent:
            A = contact_tangent(dtn, dt_db, dt_dtn)                # (3, 3, nV)
            # R = f_int - f_c; a grows with w like with u_z, b falls with delta
            # like it grows with u_x
            nv = m.vw.size
            ij = np.arange(3)[:, None, None] * nv + np.arange(nv)   # (3, 1, nV)
            rows, cols = np.broadcast_arrays(ij, np.swapaxes(ij, 0, 1))   # (3, 3, nV)
            Aw = sp.csr_matrix(((m.vw * A).ravel(), (rows.ravel(), cols.ravel())),
                               shape=(3 * nv, 3 * nv))
            out["Aw"] = Aw                                          # the tangent: -V^T Aw V
            out["dR_dw"] = -(m.VT @ (m.vw * A[:, 2]).ravel())
            out["dR_ddelta"] = m.VT @ (m.vw * A[:, 0]).ravel()
        return out

    # --- residual and tangent ---------------------------------------------------------------
    def evaluate(self, u, w, delta, state, iface, dt, tangent=True, damping=None):
        m = self.m
        strain = (m.Bsp @ u).reshape((6,) + m.shape)
        stress, D, new = self.material.update(strain, state, dt, tangent=tangent)
        R = m.Bsp.T @ (stress.ravel() * m.MW)
        c = self.contact(u, w, delta, iface.anchor, tangent=tangent, damping=damping)
        R[m.free] -= c["fc"]
        return R, dict(strain=strain, stress=stress, D=D, state=new, contact=c)

    def jacobian(self, out) -> sp.csc_matrix:
        m = self.m
        data = self.data_el.copy()
        D = np.asarray(out["D"])
        if D.ndim == 4:
            dev = np.max(np.abs(D - self.C[:, :, None, None]), axis=(0, 1))
            bad = np.nonzero(np.any(dev > TANGENT_ELASTIC_TOL * np.abs(self.C).max(), axis=1))[0]
            if bad.size:
                Ke = m.element_matrices(D, bad) - self.Ke_el[bad]
                data += m.scatter(bad, Ke)
        return (m.matrix(data) - m.VT @ out["contact"]["Aw"] @ m.V).tocsc()

    def predict(self, u, out, dw, ddelta) -> np.ndarray:
        """Euler predictor: u + du with K du = -(dR/dw dw + dR/ddelta ddelta),
        the tangent and derivatives of the converged state `out` (the contact
        points keep their stick or slip state of the last step)."""
        m = self.m
        c = out["contact"]
        if "dR_dw" not in c or (dw == 0.0 and ddelta == 0.0):
            return u.copy()
        g = c["dR_dw"] * dw + c["dR_ddelta"] * ddelta
        try:
            du = self.linear.solve(self.jacobian(out), -g)
        except Exception:
            self.linear.reset()
            return u.copy()
        if not np.all(np.isfinite(du)):
            return u.copy()
        u0 = u.copy()
        u0[m.free] += du
        return u0

    def critical_factor(self, u, w, delta, out, direction: float = 1.0) -> float:
        """How far the shear resistance may be scaled before a sliding junction's
        tangent turns singular: the smallest s > 0 with K0 + s K1 singular.

        K0 is the tangent of the state `out` (its material tangent, the normal
        penalty of its touching nodes) without friction; K1 what the friction
        law adds when every touching point slides along the flat's motion
        (``direction`` +1 or -1 along x) with a developed slip, |b| = 1e6 eps_b.
        The contact tangents of both laws come from `contact`, and h of (3.21)
        enters (3.26, 3.27) linearly, so s h is exactly K0 + s K1: with a
        friction coefficient mu (c1 = mu), mu_c = s mu is a critical
        coefficient of the discrete problem, where its solution stops being
        unique (Hassani, Hild, Ionescu and Sakki, Comput.
        Methods Appl. Mech. Engrg. 192 (2003) 4517-4531).  At it a Newton
        direction from an all-slipping iterate is unbounded, and near it
        arbitrarily large.

        K1 = -V^T N V, V the node operator (`HalfModel`) and N the weighted
        contact tangents of the two laws' difference at the nodes (block
        diagonal, ``Aw`` of `contact`); N has nonzero rows R (the tangential
        components of the touching nodes) and columns C only.  So det(K0 +
        s K1) = det K0 det(I - s N V K0^-1 V^T), and the pencil reduces to the
        dense |R| x |R| matrix -N_RC (V K0^-1 V^T)_CR: one factorization of K0
        and |R| solves.  K0 + s K1 is singular where s = -1 / lambda for one
        of its real eigenvalues lambda.  Returns inf where there is no
        friction, no contact or no such s below `CRITICAL_FACTOR_BOUND`.
        """
        c = out["contact"]
        if self.friction.frictionless or not np.any(c["tn"] > 0):
            return math.inf
        eps = self.friction.slip_regularization
        anchors = c["position"].copy()
        anchors[0] += math.copysign(DEVELOPED_SLIP * eps, direction)   # b = -direction e_x |b|
        c0, c1 = (self.contact(u, w, delta, anchors, friction=law)
                  for law in (FrictionLaw(ShearResistance(), eps), self.friction))
        N = (c1["Aw"] - c0["Aw"]).tocsr()
        N.eliminate_zeros()
        rows, cols = N.nonzero()
        R, C = np.unique(rows), np.unique(cols)
        if R.size == 0:
            return math.inf
        K0 = self.jacobian(dict(out, contact=c0))
        V = self.m.V
        W = V[C] @ self._critical_lu.factor(K0).solve(V[R].T.toarray())  # (V K0^-1 V^T)_CR
        lam = np.linalg.eigvals(-(N[R][:, C].toarray() @ W))
        real = lam[(lam.imag == 0.0) & (lam.real < 0.0)].real
        s = -1.0 / real
        s = s[s <= CRITICAL_FACTOR_BOUND]
        return float(s.min()) if s.size else math.inf

    def solve_step(self, u0, w, delta, state, iface, dt, reference: float = 0.0):
        """Newton from u0 for the step ending at (w, delta); returns (u, out, its).

        Converged when ||R|| <= tolerance x the norm of the contact's nodal
        forces (`nonlinear.ContactScale`, ``reference`` that of the last
        accepted step) or at the round-off level of the internal forces.
        """
        return nonlinear.newton(_Step(self, w, delta, state, iface, dt, reference), u0,
                                self.tolerance, self.max_iterations,
                                ResidualSearch(self.line_search))

    def solve_through_slip(self, u0, w, delta, state, iface, dt, reference: float = 0.0):
        """The step ending at (w, delta) from the state u0 at its start, for a sliding
        junction where Newton from u0 fails (past its critical coefficient, or where a
        touching node lets go): a pseudo-transient continuation.  Returns (u, out,
        iterations, damped solves).

        Past the critical coefficient the step's problem need not have a solution
        near u0 (the sliding path turns back in delta: the junction would slip
        dynamically, a stick-slip event) and has more than one elsewhere.  Each
        damped solve adds a dashpot c (x - x_k) on the touching nodes' tangential
        positions x, x_k those of the last damped solution (the start: u0 at the
        step's flat position, so the body's points first follow the flat), with c a
        multiple of the normal penalty stiffness (`SLIP_DAMPING`): a proximal point
        iteration, i.e. backward Euler of the junction's damped motion with growing
        pseudo-time steps, the damping lowered as long as the solves converge.  With
        c large the tangent is regular whatever the friction coefficient; near the
        junction's negative stiffness the iterates run through the instability; as c
        falls they relax to an equilibrium the damped motion reaches, and the last
        solve is the undamped step itself, from there.
        The material takes the step's dt in every solve (the pseudo-time is not
        physical time), so the result is the backward-Euler step of the model, on the
        branch this motion selects.  Raises `StepFailed` after `SLIP_DAMPED_SOLVES`
        damped tries, or if the undamped solve fails.
        """
        first, factor, last = SLIP_DAMPING
        kappa = self.law.kappa
        s, s_ok, f, u = first, None, factor, u0
        # the touching nodes' positions at u (those of a solution: its own output)
        start = self.contact(u, w, delta, iface.anchor, tangent=False)["position"]
        total = solves = tries = 0
        while s >= last:
            if tries == SLIP_DAMPED_SOLVES:
                raise StepFailed(f"{tries} damped solves ({solves} converged) did not get "
                                 f"through: the damping at {s:.3g} times the penalty "
                                 "stiffness", total)
            tries += 1
            problem = _Step(self, w, delta, state, iface, dt, reference, damping=(start, s * kappa))
            try:
                u, out, its = nonlinear.newton(problem, u, self.tolerance, SLIP_DAMPED_ITERATIONS,
                                               ResidualSearch(self.line_search))
            except StepFailed as exc:
                total += exc.iterations
                if s_ok is None:             # not even the first: more damping
                    s *= factor
                    continue
                f = math.sqrt(f)
                if f < 1.05:                 # the last converged damping no longer holds
                    s_ok, f = s_ok * factor, factor
                s = s_ok / f
                continue
            total += its
            solves += 1
            start = out["contact"]["position"]
            s_ok, f = s, min(f * f, factor)
            s = s_ok / f
        try:
            u, out, its = self.solve_step(u, w, delta, state, iface, dt, reference)
        except StepFailed as exc:
            raise StepFailed(f"undamped solve after {solves} damped ones: {exc}",
                             total + exc.iterations) from None
        return u, out, total + its, solves

    def initial_interface(self, delta=0.0) -> "Interface":
        m = self.m
        return Interface(anchor=np.stack((m.vX[0] - delta, m.vX[1])))

    def commit(self, out, iface: "Interface") -> "Interface":
        """The interface state after an accepted step: anchors dragged
        (`sliding.drag_anchor`)."""
        c = out["contact"]
        return Interface(anchor=drag_anchor(iface.anchor, c["position"], c["tn"],
                                            self.friction.slip_regularization))

    # --- outputs ------------------------------------------------------------------------------
    def record(self, u, w, delta, out) -> dict:
        m = self.m
        c = out["contact"]
        tn, txy = c["tn"], c["txy"]
        fn = 2.0 * float(np.sum(tn * m.vw))
        ft = 2.0 * float(np.sum(txy[0] * m.vw))
        area = 2.0 * float(np.sum(m.vw * (tn > 0)))
        epn = equivalent_strain(out["state"].inelastic_strain)
        slip = (np.sqrt(c["b"][0] ** 2 + c["b"][1] ** 2)
                >= self.friction.slip_regularization * (1 - 1e-9))
        touching = tn > 0
        wsum = float(np.sum(m.vw * touching))
        return dict(
            normal_displacement=w, tangential_displacement=delta,
            normal_force=fn, tangential_force=ft, contact_area=area,
            mean_pressure=fn / area if area > 0 else 0.0,
            mean_tangential_traction=ft / area if area > 0 else 0.0,
            max_pressure=float(tn.max()),
            slip_fraction=float(np.sum(m.vw * (touching & slip)) / wsum) if wsum > 0 else 0.0,
            max_inelastic_strain=float(epn.max()),
            max_von_mises=float(von_mises(out["stress"]).max()),
            overflow=bool(np.any(touching & (m.vr > 0.85 * m.contact_radius))),
        )


class _Step(Problem):
    """Equilibrium at the end of a step (`SlidingModel.solve_step`)."""

    def __init__(self, sm: SlidingModel, w, delta, state, iface, dt, reference: float,
                 damping=None):
        self.sm, self.w, self.delta = sm, w, delta
        self.state, self.iface, self.dt = state, iface, dt
        self.damping = damping
        self.force_scale = nonlinear.ContactScale(reference)

    def evaluate(self, u):
        R, out = self.sm.evaluate(u, self.w, self.delta, self.state, self.iface, self.dt,
                                  damping=self.damping)
        return R[self.sm.m.free], out

    def check(self, out, iteration):
        check_local_update(out["state"], iteration)

    def scale(self, u, out):
        return self.force_scale(float(np.linalg.norm(out["contact"]["fc"])))

    def floor(self, u, out):
        m = self.sm.m
        return 1e3 * np.finfo(float).eps * float(np.linalg.norm(
            (m.absBT @ np.abs(out["stress"].ravel() * m.MW))[m.free]))

    def monitor(self, iteration, rn, scale, out):
        sm = self.sm
        if sm.trace is not None:
            c = out["contact"]
            slip = np.hypot(*c["b"]) >= sm.friction.slip_regularization
            sm.trace.append((iteration, float(rn), scale, int(np.sum(c["tn"] > 0)),
                             int(np.sum((c["tn"] > 0) & slip))))

    def direction(self, u, Rf, out, tangent, iteration):
        sm = self.sm
        try:
            d = sm.linear.solve(sm.jacobian(out), -Rf)
        except Exception as exc:                          # singular factorization
            sm.linear.reset()
            raise StepFailed(f"linear solve failed: {exc}", iteration) from None
        if not np.all(np.isfinite(d)):
            sm.linear.reset()  # newton raises
        full = np.zeros_like(u)
        full[sm.m.free] = d
        return full
