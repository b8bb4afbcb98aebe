"""Three-dimensional asperity pressed and slid by a rigid flat (report 3.3, 3.4, 9.2).

Body.  A hill z = surface(r) (a `geometry.Profile`, e.g. the `CosineHill`
of report 9.2, 2 um high and 10 um across its base) standing on a block, or
an elliptic paraboloid z = -(kappa_1 x^2 + kappa_2 y^2) / 2
(`geometry.EllipticParaboloid`, principal axes along x and y): the model
reads the surface over the plane, ``surface_xy(x, y)``.
The sliding direction is x, so the plane y = 0 is a plane of symmetry and
only the half y >= 0 is modelled (u_y = 0 on y = 0; the reported forces
are twice those of the half).  Support (3.3.1): u = 0 on the cut-off
boundary (the bottom of the block and its sides |x| = L, y = L).

Mesh (`MeshSpec`, `build_mesh`).  A uniform tensor grid of the box
[-L, L] x [0, L] x [-D, 0] in *reference* coordinates, cut into tetrahedra
(`skfem.MeshTet.init_tensor`) and refined by longest-edge bisection until
every element's longest edge is below ``tip_size + grading * d``, d the
distance of its centroid beyond ``refine_radius`` from the apex (or from a
segment along x through it); with ``depth_grading`` the finest region is
the disc of ``refine_radius`` on the top surface and the edge grows by
``depth_grading`` per unit depth below it, so the contact surface's
nodes are fine without filling the volume under them (the `standard` and
`fine` sliding presets: the contact area and force grow a ring of nodes
at a time).  The quadratic (10-node) mesh is then mapped
onto the body, vertices and edge midpoints alike (isoparametric P2
elements, curved faces):

    Z = foot + z + (body_surface_xy(x, y) - foot) (1 + z / D),

so the reference top z = 0 becomes the hill's surface exactly at the nodes
and the bottom z = -D stays flat (foot = the height of the hill's foot
relative to the apex; body_surface_xy(x, y) = body_surface(hypot(x, y)) for
a body of revolution, the surface itself for an `EllipticParaboloid`, whose
principal axes are x and y).  Displacements are P2 (`ElementTetP2`), four
quadrature points per element (degree 2), with the volumetric strain
replaced by its element mean (B-bar, the P2/P0 mixed element;
``volumetric="mean"``): with the full volumetric strain at four points
the 10-node tetrahedron locks under isochoric plastic flow (about one
constraint per displacement dof), and a locked junction can separate from
the flat while it slides; with B-bar it stays in contact.

Weak form: the incremental (backward-Euler) counterpart of report (3.22):
at each time step the equilibrium

    R(u) = int B^T sigma(eps(u); state_n, dt) dV - int N^T t(u) ds = 0

is solved by Newton with the material's consistent tangent at the
quadrature points (`BodnerPartom.update` or `J2Plasticity.update` with 6
strain components, or a linear elastic body), plus the contact tangent alpha_ij of (3.26, 3.27)
(`sliding.contact_tangent`).  Strains are [e11, e22, e33, e12, e13, e23]
(tensor shears, work product weights 1, 1, 1, 2, 2, 2).

Contact (3.3.2, 3.4.1).  The flat is the plane z = -w(t) (w the approach
from first touch at the apex) moved by delta(t) along x.  The contact
lives on the P2 nodes of the top facets near the apex, vertices and edge
midpoints: each 6-node facet is cut at its edge midpoints into 4 triangles,
and phi_i is the hat function of node i on these sub-triangles (P1
tractions on the sub-triangulation, the pairing with P2 displacements that
mortar methods for quadratic elements use; 6 Gauss points a sub-triangle).
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
sub-triangle's size about each node).  One condition a node, as many as
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
for much of the slide, and a run that stalls there stops (below; docs:
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
iterations and steps while that converges in a few iterations.

Time stepping (`solve_sliding`, marched by `march.march`): the flat's
motion is piecewise linear in time (`FlatMotion`); steps never cross a time of the step grid
(`step_grid`: each segment divided into the preset's steps for it, so runs
of presets with the same steps share those times); a step is cut in half when
Newton fails, gives non-finite values or the local update fails, or when
the equivalent inelastic strain changed anywhere by more than
``max_inelastic_step``; the time step grows back (x1.5) after easy steps,
up to the preset's cap (the segment's duration / its step count), from the
length it tried when the grid cut it short.  A run
whose accepted steps stay under ``STALL_FRACTION`` of their cap for
``STALL_STEPS`` steps in a row has stalled (past the critical coefficient,
above): it stops there with ``completed`` 0 and ``stop_reason``, keeping its
steps (the section "end" is then its last state), instead of grinding on at
that pace.

Through the slip instability (`SlidingModel.solve_through_slip`): a sliding
step whose Newton fails after it was cut below ``STALL_FRACTION`` of its cap
(where the steps would stall) is solved again from the state at its start through
damped solves, a pseudo-transient continuation whose dashpot on the
touching nodes makes each solve's problem unique; the step ends with the
plain Newton solve of the model.  Past the critical coefficient the
quasi-static path can turn back in the sliding displacement (the junction
would slip dynamically) and the step's problem has several solutions: the
damped motion selects the one the junction slips to, at the sliding
displacement where the cut steps stopped converging.  The same holds where a
touching node lets go although the junction's tangent was regular at the
accepted steps (the critical factor is taken there, not within the step).
The step is cut again only if that fails too.  ``damped_solves`` records it
per step.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
import xarray as xr
from skfem import Basis, ElementTetP2, ElementVector, FacetBasis, MeshTet, MeshTet2
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from asperity.fe.solvers import nonlinear
from asperity.fe.discretization.assembly import OrderedLU
from asperity.fe.contact.penalty import SMOOTHING, C1Penalty
from asperity.fe.errors import ContactZoneError, StepFailed
from asperity.fe.materials.elastic import METRIC6, equivalent_strain, von_mises
from asperity.fe.solvers.nonlinear import (Pace, Problem, ResidualSearch, check_local_update,
                                           strain_limited)
from asperity.fe.outputs import INELASTIC_THRESHOLD, VARIABLES, dataset, describe
from asperity.fe.presets import resolve
from asperity.fe.contact.sliding import FrictionLaw, ShearResistance, contact_tangent, drag_anchor
from asperity.io.run_report import StepProgress
from asperity.fe.drivers.march import Accepted, Marching, Trial, march

log = logging.getLogger(__name__)

#: the 6 edges of a tetrahedron (local vertex pairs)
_TET_EDGES = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]])
#: quadrature order in the volume (4 points per tetrahedron)
INTORDER = 2
#: quadrature order on each of the 4 sub-triangles of a contact facet (6 Gauss
#: points each, 24 per facet: exact for the P1 x P2 products of the node gaps on a
#: plane facet)
CONTACT_INTORDER = 3
#: default penalty factor c in kappa = c E' / h_facet
PENALTY_FACTOR_3D = 100.0
#: smoothing pressure of the C1 penalty / E' (the quadratic branch covers
#: pressures below half of it)
SMOOTHING_3D = SMOOTHING
#: a point's tangent counts as elastic when |D - C| <= this * |C|
TANGENT_ELASTIC_TOL = 1e-10
#: time step growth by 1.5 after a step without cuts that took at most 12
#: Newton iterations (a sliding junction often takes more than 5 per step: a
#: lower threshold never lets the step grow back after a cut)
PACE = Pace(fast=12, growth=1.5)
#: `SlidingModel.critical_factor`: the developed slip |b| / eps_b at which the
#: junction's tangent is taken (its stiffness across the slip, h / |b|, is then
#: 1e-6 of the stick stiffness), and the largest factor sought
DEVELOPED_SLIP = 1e6
CRITICAL_FACTOR_BOUND = 1e3
#: "at the junction": the largest inelastic strain lies less than this
#: fraction of the equivalent contact radius sqrt(A / pi) below the flat
JUNCTION_DEPTH_FRACTION = 0.25
#: a run has stalled when this many accepted steps in a row each advanced less
#: than STALL_FRACTION of their segment's step cap: at that pace the rest of the
#: motion would take thousands of steps (report 9.2's mu = 20 past the critical
#: coefficient); the run stops there with ``completed`` 0.  STALL_STEPS lies above
#: the longest such streak of a run that goes on to finish (docs: changelog, 'Sliding
#: of one asperity').
STALL_STEPS, STALL_FRACTION = 20, 1e-3
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

# ----------------------------------------------------------------------------- mesh
@dataclass(frozen=True)
class MeshSpec:
    """The half model's block and its grading (lengths in m).

    half_width L: the block spans |x| <= L, 0 <= y <= L; depth D below the
    foot of the hill; coarse_size: spacing of the initial tensor grid;
    tip_size: longest element edge within ``refine_radius`` of the
    refinement segment x in [refine_x0, refine_x1], y = 0, z = 0 (the top
    surface, reference coordinates); grading: growth of the longest edge
    per unit distance beyond that.  depth_grading: None, the finest region
    is the ball of ``refine_radius`` about the segment; a number g_z, it is
    the disc of ``refine_radius`` on the top surface, and the longest edge
    grows as tip_size + sqrt((grading rho)^2 + (g_z z)^2), rho the lateral
    distance beyond the disc and z the depth: the contact surface resolved
    finely without filling the volume below it at the same size.
    refine_radius_y: None, the region is round; a length, its semi-axis along
    y, ``refine_radius`` being the one along x (an elliptic contact with its
    principal axes along x and y, `geometry.EllipticParaboloid`): the disc
    becomes the ellipse of these semi-axes (the ball the ellipsoid with the
    smaller of them along z), and the distance beyond it is taken as
    (s - 1) / |grad s|, s = hypot((x - x_s) / r_x, y / r_y (, z / r_z)) the
    ellipse's scale through the point: s is convex and 1-homogeneous, so
    s(q) >= s(p) + grad s(p) . (q - p) and this is a lower bound of the
    distance to the ellipse (exact on its axes); the grading is at least as
    fine as the spec asks.
    """

    half_width: float
    depth: float
    coarse_size: float
    tip_size: float
    grading: float = 0.5
    refine_x0: float = 0.0
    refine_x1: float = 0.0
    refine_radius: float = 0.0
    depth_grading: float | None = None
    refine_radius_y: float | None = None

    def __post_init__(self):
        for k in ("half_width", "depth", "coarse_size", "tip_size", "grading"):
            v = getattr(self, k)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"mesh {k} must be positive, got {v!r}")
        if self.refine_x1 < self.refine_x0:
            raise ValueError("refine_x1 must be >= refine_x0")
        if not self.refine_radius >= 0:
            raise ValueError("refine_radius must be >= 0")
        if self.depth_grading is not None and not (math.isfinite(self.depth_grading)
                                                   and self.depth_grading > 0):
            raise ValueError(f"mesh depth_grading must be positive, got {self.depth_grading!r}")
        if self.refine_radius_y is not None and not (math.isfinite(self.refine_radius_y)
                                                     and self.refine_radius_y > 0
                                                     and self.refine_radius > 0):
            raise ValueError("refine_radius_y needs positive refine_radius and refine_radius_y, "
                             f"got {self.refine_radius!r} and {self.refine_radius_y!r}")

    @classmethod
    def for_hill(cls, geometry, contact_radius: float, preset: dict | None = None) -> "MeshSpec":
        """Default block of a hill: L = 1.4 x its footprint radius, D = its
        footprint radius, the finest elements within the preset's
        ``refine_fraction`` x the contact radius estimate of the apex (a ball,
        or a disc on the surface if the preset has a ``depth_grading``).  For an
        elliptic paraboloid the contact radius is the ellipse's long semi-axis: the
        region is the Hertz ellipse's shape (``refine_radius_y``), the tip size the
        fraction of its short semi-axis."""
        p = resolve("sliding", "standard") if preset is None else preset
        ext = float(geometry.extent)
        rx = ry = float(contact_radius)
        if hasattr(geometry, "contact_semi_axes"):
            rx, ry = geometry.contact_semi_axes(contact_radius)
        return cls(half_width=1.4 * ext, depth=ext, coarse_size=p["coarse_fraction"] * ext,
                   tip_size=p["tip_fraction"] * min(rx, ry), grading=p["grading"],
                   refine_radius=p["refine_fraction"] * rx,
                   refine_radius_y=None if rx == ry else p["refine_fraction"] * ry,
                   depth_grading=p["depth_grading"])


@dataclass
class HalfModelMesh:
    """The linear reference mesh, the mapped quadratic mesh and node sets."""

    reference: MeshTet          # box coordinates, linear
    mesh: MeshTet2              # physical (mapped) isoparametric mesh
    nodes_ref: np.ndarray       # (3, nnodes) reference coordinates of the P2 nodes
    spec: MeshSpec
    foot: float


def _refine(m: MeshTet, spec: MeshSpec, max_rounds: int = 80) -> MeshTet:
    for _ in range(max_rounds):
        p, t = m.p, m.t
        le = np.max(np.linalg.norm(p[:, t[_TET_EDGES[:, 0]]] - p[:, t[_TET_EDGES[:, 1]]], axis=0),
                    axis=0)
        c = p[:, t].mean(axis=1)
        xs = np.clip(c[0], spec.refine_x0, spec.refine_x1)
        if spec.refine_radius_y is not None:
            size = _elliptic_size(c, xs, spec)
        elif spec.depth_grading is None:
            d = np.maximum(np.sqrt((c[0] - xs) ** 2 + c[1] ** 2 + c[2] ** 2) - spec.refine_radius,
                           0.0)
            size = spec.tip_size + spec.grading * d
        else:
            rho = np.maximum(np.hypot(c[0] - xs, c[1]) - spec.refine_radius, 0.0)
            size = spec.tip_size + np.hypot(spec.grading * rho, spec.depth_grading * c[2])
        marked = np.nonzero(le > size)[0]
        if marked.size == 0:
            return m
        m = m.refined(marked)
    raise RuntimeError("mesh refinement did not finish; check tip_size and grading")


def _elliptic_size(c, xs, spec: MeshSpec) -> np.ndarray:
    """The longest edge allowed at the centroids c (3, ne) about the elliptic region of
    ``refine_radius`` (x) and ``refine_radius_y`` (y) (`MeshSpec`): the distance beyond
    it (s - 1) / |grad s|, s the region's scale through the centroid."""
    rx, ry = spec.refine_radius, spec.refine_radius_y
    rmin = min(rx, ry)
    q = [(c[0] - xs) / rx, c[1] / ry]
    r = [rx, ry]
    if spec.depth_grading is None:
        q.append(c[2] / rmin)
        r.append(rmin)
    q, r = np.array(q), np.array(r)[:, None]
    s = np.sqrt((q**2).sum(axis=0))
    grad = np.sqrt(((q / r) ** 2).sum(axis=0)) / np.maximum(s, 1e-300)   # |grad s|
    d = np.where(s > 1.0, (s - 1.0) / np.maximum(grad, 1e-300), 0.0)
    if spec.depth_grading is None:
        return spec.tip_size + spec.grading * d
    return spec.tip_size + np.hypot(spec.grading * d, spec.depth_grading * c[2])


def build_mesh(geometry, spec: MeshSpec) -> HalfModelMesh:
    """Graded tetrahedral half model of `geometry` on its block (module docstring)."""
    # skfem warns that it copies large refined arrays to C order: harmless
    logger = logging.getLogger("skfem")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        return _build_mesh(geometry, spec)
    finally:
        logger.setLevel(level)


def _build_mesh(geometry, spec: MeshSpec) -> HalfModelMesh:
    L, D, h0 = spec.half_width, spec.depth, spec.coarse_size
    if L <= geometry.extent * (1 - 1e-12) and not geometry.shallow:
        raise ValueError(f"the block half width {L:.4g} m must exceed the hill's footprint "
                         f"radius {geometry.extent:.4g} m")
    nx, ny, nz = (max(1, int(math.ceil(v / h0))) for v in (2 * L, L, D))
    m = MeshTet.init_tensor(np.linspace(-L, L, nx + 1), np.linspace(0.0, L, ny + 1),
                            np.linspace(-D, 0.0, nz + 1))
    m = _refine(m, spec)
    m = MeshTet(np.ascontiguousarray(m.p), np.ascontiguousarray(m.t))
    ref2 = MeshTet2.from_mesh(m)
    X = np.array(ref2.doflocs, dtype=float)
    foot = float(geometry.body_surface(np.array([geometry.extent]))[0])
    top = np.asarray(geometry.body_surface_xy(X[0], X[1]), float)
    Z = foot + X[2] + (top - foot) * (1.0 + X[2] / D)
    phys = X.copy()
    phys[2] = Z
    return HalfModelMesh(reference=m, mesh=MeshTet2(phys, np.ascontiguousarray(ref2.t)),
                         nodes_ref=X, spec=spec,
                         foot=foot)


# ------------------------------------------------------------------------ materials
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


# ------------------------------------------------------------------------- linear solver
class _LinearSolver:
    """SuperLU factorizations reused as GMRES preconditioners while they work."""

    def __init__(self, rtol: float = 1e-10, max_krylov: int = 15):
        self.lu = None
        self.rtol = rtol
        self.max_krylov = max_krylov
        self.factorizations = 0
        self.krylov_solves = 0
        self._ordered = OrderedLU(diag_pivot_thresh=0.1)

    def reset(self):
        self.lu = None

    def _factor(self, K):
        self.lu = self._ordered.factor(K)
        self.factorizations += 1

    def solve(self, K, rhs) -> np.ndarray:
        if self.lu is not None:
            lu = self.lu
            M = spl.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
            count = [0]

            def cb(_):
                count[0] += 1

            x, info = spl.gmres(K, rhs, M=M, rtol=self.rtol, atol=0.0, restart=self.max_krylov,
                                maxiter=1, callback=cb, callback_type="pr_norm")
            if info == 0 and np.all(np.isfinite(x)):
                self.krylov_solves += 1
                return x
        self._factor(K)
        return self.lu.solve(rhs)


# ------------------------------------------------------------------------------ model
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
        self._absBT = abs(self.Bsp).T.tocsr()
        self._Bm = np.ascontiguousarray(np.transpose(B, (2, 3, 0, 1)))          # (ne, nq, 6, 30)
        self._BtW = np.ascontiguousarray(np.swapaxes(
            self._Bm * (METRIC6[:, None] * self.weights[:, :, None, None]), 2, 3))  # (ne, nq, 30, 6)
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

    def _scatter(self, elements, Ke) -> np.ndarray:
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


def solve_prescribed(model: HalfModel, material, displacement) -> tuple[np.ndarray, np.ndarray]:
    """Linear elastic body with u = displacement(x) on its whole boundary.

    `displacement` maps node coordinates (3, n) to displacements (3, n);
    returns the displacement dofs (ndofs,) and the stresses (6, ne, nq).
    For an affine field the exact solution is that field everywhere (the
    P2 isoparametric space contains it): the patch test.
    """
    ne = model.shape[0]
    Ke = model.element_matrices(material.tangent(6))
    nl = Ke.shape[1]
    ed = model.element_dofs
    rows = np.broadcast_to(ed.T[:, :, None], (ne, nl, nl)).ravel()
    cols = np.broadcast_to(ed.T[:, None, :], (ne, nl, nl)).ravel()
    K = sp.csr_matrix((Ke.ravel(), (rows, cols)), shape=(model.ndofs, model.ndofs))
    X = model.hm.mesh.doflocs
    U = np.asarray(displacement(X), float)
    u = np.zeros(model.ndofs)
    bd = model.boundary_dofs
    nodes_b = np.unique(np.nonzero(np.isin(model.dofmap, bd))[1])
    u[model.dofmap[:, nodes_b].ravel()] = U[:, nodes_b].ravel()
    bmask = np.zeros(model.ndofs, bool)
    bmask[model.dofmap[:, nodes_b].ravel()] = True
    inner = np.nonzero(~bmask)[0]
    rhs = -(K[inner][:, np.nonzero(bmask)[0]] @ u[bmask])
    u[inner] = spl.spsolve(K[inner][:, inner].tocsc(), rhs)
    strain = (model.Bsp @ u).reshape((6,) + model.shape)
    return u, np.tensordot(material.tangent(6), strain, axes=(1, 0))


# --------------------------------------------------------------------------- motion
@dataclass(frozen=True)
class FlatMotion:
    """Piecewise linear approach w(t) and tangential displacement delta(t) of the flat.

    times [s], normal [m] (approach from first touch at the apex),
    tangential [m] (along x), knots of equal length.
    """

    times: tuple
    normal: tuple
    tangential: tuple

    def __post_init__(self):
        t = np.asarray(self.times, float)
        w = np.asarray(self.normal, float)
        d = np.asarray(self.tangential, float)
        if t.ndim != 1 or t.size < 2 or w.shape != t.shape or d.shape != t.shape:
            raise ValueError("a motion needs at least two knots of (time, normal, tangential)")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(w)) and np.all(np.isfinite(d))):
            raise ValueError("motion knots must be finite")
        if np.any(np.diff(t) <= 0):
            raise ValueError("motion times must increase")

    @classmethod
    def press_and_slide(cls, approach: float, slide: float, press_time=(0.0, 1800.0),
                        slide_time=(1800.0, 4000.0)) -> "FlatMotion":
        """Report 9.2: press to `approach` during press_time, then slide by
        `slide` during slide_time at constant approach."""
        t0, t1 = map(float, press_time)
        s0, s1 = map(float, slide_time)
        if not (t1 > t0 and s1 > s0 and s0 >= t1):
            raise ValueError("need press_time[0] < press_time[1] <= slide_time[0] < slide_time[1]")
        times = [t0, t1] + ([s0] if s0 > t1 else []) + [s1]
        normal = [0.0, approach] + ([approach] if s0 > t1 else []) + [approach]
        tang = [0.0, 0.0] + ([0.0] if s0 > t1 else []) + [slide]
        return cls(tuple(times), tuple(normal), tuple(tang))

    @property
    def start(self) -> float:
        return float(self.times[0])

    @property
    def end(self) -> float:
        return float(self.times[-1])

    def __call__(self, t):
        return (float(np.interp(t, self.times, self.normal)),
                float(np.interp(t, self.times, self.tangential)))

    def segment(self, t) -> int:
        tk = np.asarray(self.times)
        return int(np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2))

    def phase(self, t) -> str:
        """'normal' while the approach changes, 'sliding' while delta changes, else 'hold'."""
        i = self.segment(t)
        if self.tangential[i + 1] != self.tangential[i]:
            return "sliding"
        if self.normal[i + 1] != self.normal[i]:
            return "normal"
        return "hold"


# ------------------------------------------------------------------------------ solver
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
        self.data_el = model._scatter(slice(None), self.Ke_el)
        self.linear = _LinearSolver()
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
                data += m._scatter(bad, Ke)
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
        slip = np.sqrt(c["b"][0] ** 2 + c["b"][1] ** 2) >= self.friction.slip_regularization * (1 - 1e-9)
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


#: the variables of `solve_sliding` (units and long names: `outputs.VARIABLES`)
OUTPUTS = ("time", "normal_displacement", "tangential_displacement", "normal_force",
           "tangential_force", "contact_area", "mean_pressure",
           "mean_tangential_traction", "max_pressure", "slip_fraction", "critical_shear_factor",
           "max_inelastic_strain", "max_von_mises", "phase", "newton_iterations", "step_cuts",
           "damped_solves", "time_step", "wall_time")


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
            (m._absBT @ np.abs(out["stress"].ravel() * m.MW))[m.free]))

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


def _snapshot(model: HalfModel, u, state, tn=None) -> dict:
    nd = model.node_displacements(u)[:, model.plane_nodes]
    ep = model.nodal_average(equivalent_strain(state.inelastic_strain))[model.plane_nodes]
    return dict(ux=nd[0], uz=nd[2], ep=ep, **({} if tn is None else dict(tn=np.array(tn))))


def step_caps(motion: FlatMotion, preset: dict) -> list:
    """The largest time step [s] of each segment of `motion`: its duration over the
    preset's ``tangential_steps`` where the flat slides, else its ``normal_steps``."""
    times = np.asarray(motion.times, float)
    return [(times[i + 1] - times[i]) / n for i, n in enumerate(_segment_steps(motion, preset))]


def step_grid(motion: FlatMotion, preset: dict) -> np.ndarray:
    """The times every step of a run lands on: each segment of `motion` divided into
    its preset's steps (`step_caps`).  A step may be shorter (cut, or paced by Newton)
    but never crosses one of these times, so runs whose presets have the same steps
    (``standard`` and ``fine``) both report their force histories at these times and
    are compared there without interpolating either (`benchmarks/sliding_convergence.py`)."""
    times = np.asarray(motion.times, float)
    parts = [times[i] + (times[i + 1] - times[i]) * np.arange(n) / n
             for i, n in enumerate(_segment_steps(motion, preset))]
    return np.append(np.concatenate(parts), times[-1])


def _segment_steps(motion: FlatMotion, preset: dict) -> list:
    """The preset's steps for each segment of `motion` (`step_caps`)."""
    w_knots = np.asarray(motion.normal, float)
    d_knots = np.asarray(motion.tangential, float)
    steps = []
    for i in range(len(w_knots) - 1):
        sliding = d_knots[i + 1] != d_knots[i]
        steps.append(max(int(preset["tangential_steps" if sliding else "normal_steps"]), 1))
    return steps


def solve_sliding(geometry, material, motion: FlatMotion, friction: FrictionLaw,
                  accuracy="standard", mesh: MeshSpec | None = None,
                  contact_radius: float | None = None, penalty_factor: float = PENALTY_FACTOR_3D,
                  volumetric: str = "mean",
                  max_steps: int = 100_000, stall_steps: int = STALL_STEPS,
                  stall_fraction: float = STALL_FRACTION,
                  snapshots: dict | None = None, contact_section: bool = False,
                  progress=None) -> xr.Dataset:
    """A 3-D asperity pressed and slid by the rigid flat (report 9.2).

    Parameters
    ----------
    geometry
        a `Profile` (e.g. ``CosineHill(1e-6, pi / 5e-6)``: 2 um high, 10 um
        across; or a shallow `Paraboloid` for the Hertz check); its
        ``axisymmetric`` flag is ignored (the model is 3-D).
    material
        `BodnerPartom` or `J2Plasticity` (6-component updates) or `LinearElastic`.
    motion
        `FlatMotion`: approach and tangential displacement versus time.
    friction
        `FrictionLaw` (3.21, 3.24, 3.25).
    accuracy
        `presets.SLIDING_ACCURACY` preset name or dict: mesh sizes, steps per segment
        (caps), Newton tolerance, inelastic step limit.
    mesh
        override the block and grading (`MeshSpec`); default
        `MeshSpec.for_hill`.
    contact_radius
        estimate r of the contact radius (default: the geometric
        intersection radius at the largest approach); sizes the tip
        elements and the candidate contact zone (2.5 r + the sliding
        distance).
    max_steps
        stop after this many accepted steps (attribute ``completed`` 0).
    stall_steps, stall_fraction
        stop (``completed`` 0, with a warning) once `stall_steps` accepted steps in a row
        each advanced less than `stall_fraction` of their segment's step cap (the
        segment's duration over the preset's steps for it): the solver has stalled,
        as past the junction's critical friction coefficient; the steps so far are
        kept.
    snapshots
        {name: time}: the displacements and inelastic strain on the
        symmetry plane at these times (default: end of pressing and end).
    contact_section
        also the normal pressure at the contact nodes at these times (dims
        ``snapshot``, ``contact_node``), with the nodes' x, y and weights: the
        contact's shape (`press_3d`).
    progress
        optional callable(str) for progress lines.

    Returns an `xarray.Dataset`: per step (dim ``step``) the variables of
    `OUTPUTS`; the symmetry-plane section (dims ``plane_node``,
    ``plane_triangle``, ``corner``, ``snapshot``); attributes describing
    the mesh, the solver and where the largest deformation sits;
    ``completed`` (0 if the run stopped before the end of the motion) with
    ``stop_reason``.
    """
    t_start = time.perf_counter()
    if not (int(stall_steps) >= 1 and 0.0 <= stall_fraction < 1.0):
        raise ValueError(f"stall_steps must be >= 1 and stall_fraction in [0, 1), got "
                         f"{stall_steps} and {stall_fraction}")
    preset = resolve("sliding", accuracy)
    w_knots = np.asarray(motion.normal, float)
    d_knots = np.asarray(motion.tangential, float)
    w_max = float(w_knots.max())
    slide = float(np.abs(d_knots - d_knots[0]).max())
    if w_max >= geometry.height and not geometry.shallow:
        raise ValueError(f"approach {w_max:.4g} m reaches the foot of the hill "
                         f"(height {geometry.height:.4g} m)")
    if contact_radius is None:
        contact_radius = float(geometry.intersection_radius(np.array([max(w_max, 0.0)]))[0])
        if not contact_radius > 0:
            contact_radius = 0.1 * geometry.extent
    spec = mesh if mesh is not None else MeshSpec.for_hill(geometry, contact_radius, preset)
    hm = build_mesh(geometry, spec)
    cand = min(2.5 * contact_radius + slide, 0.95 * spec.half_width)
    model = HalfModel(geometry, hm, cand, volumetric=volumetric)
    sm = SlidingModel(model, material, friction, penalty_factor, preset["tolerance"],
                      preset["max_iterations"])
    t_mesh = time.perf_counter() - t_start
    say = progress or (lambda s: None)
    say(f"mesh: {hm.reference.t.shape[1]} tetrahedra, {model.ndofs} dofs "
        f"({len(model.free)} free), {model.cfacets.size} contact facets, {t_mesh:.2f} s")

    # --- time stepping: `march` with the steps of `_SlidingMarch`
    run = _SlidingMarch(sm, motion, friction, preset, stall_steps=stall_steps,
                        stall_fraction=stall_fraction, snapshots=snapshots,
                        contact_section=contact_section, say=say)
    march(run, run.caps[motion.segment(run.t)] / 2.0, max_steps)
    rows, t, u, w, state = run.rows, run.t, run.u, run.w, run.state
    stop_reason, critical = run.stop_reason, run.critical

    completed = t >= motion.end * (1 - 1e-12)
    if not stop_reason and not completed:
        stop_reason = f"max_steps ({max_steps}) reached at t = {t:.6g} s"
    snap = run.snap
    if "end" in run.snap_times and "end" not in snap:  # a run stopped early: its last state
        snap["end"] = (t, _snapshot(model, u, state, run.out_last["contact"]["tn"]
                                    if contact_section else None), {})
    total = time.perf_counter() - t_start
    head = dataset({name: np.array([r[name] for r in rows]) for name in OUTPUTS}, geometry,
                   material, accuracy, preset, "time step index")
    for name in OUTPUTS:     # forces and areas of the 3-D body, whatever the profile's flag
        units, long_name = VARIABLES[name]
        head[name].attrs.update(units=units, long_name=long_name)
    return _sliding_dataset(head, rows, model, sm, u, w, state, snap, dict(
        friction=describe(friction.resistance),
        slip_regularization=float(friction.slip_regularization),
        mesh=repr(spec),
        symmetry="half model y >= 0 (plane of symmetry y = 0 contains the sliding direction x)",
        elements=int(model.shape[0]), element_type="10-node tetrahedra (P2, isoparametric), "
        "4 quadrature points" + (", B-bar (element-mean volumetric strain)"
                                 if volumetric == "mean" else ""), dofs=int(model.ndofs), free_dofs=int(len(model.free)),
        tip_element_size=float(spec.tip_size), contact_facets=int(model.cfacets.size),
        contact_candidate_radius=float(model.contact_radius),
        penalty_factor=float(penalty_factor),
        critical_shear_factor=min(critical, default=math.inf),
        motion_times=np.asarray(motion.times, float), motion_normal=w_knots,
        motion_tangential=d_knots,
        steps=len(rows) - 1, total_step_cuts=int(sum(r["step_cuts"] for r in rows)),
        total_newton_iterations=int(sum(r["newton_iterations"] for r in rows)),
        steps_through_slip=int(sum(r["damped_solves"] > 0 for r in rows)),
        factorizations=int(sm.linear.factorizations), krylov_solves=int(sm.linear.krylov_solves),
        completed=int(completed), stop_reason=stop_reason,
        mesh_wall_time=t_mesh, total_wall_time=total))


def _default_snapshots(motion: FlatMotion) -> dict:
    """The end of pressing and the end of `motion`: {name: time}."""
    times = np.asarray(motion.times, float)
    snapshots = {}
    for i in range(len(times) - 1):
        if motion.phase(times[i]) == "normal" and (i + 1 == len(times) - 1 or
                                                   motion.phase(times[i + 1]) != "normal"):
            snapshots["end of pressing"] = float(times[i + 1])
    snapshots["end"] = float(times[-1])
    return snapshots


class _SlidingMarch(Marching):
    """The steps of `solve_sliding` for `march`: a try solves the step (through the
    slip instability once sliding steps are cut to where they would stall) and checks
    its inelastic strain step; an accepted step drags the anchors of the sticking
    points, is recorded with the critical factor of the sliding junction, takes the
    snapshots due and sets the next time step; the run stops when the steps stall."""

    def __init__(self, sm: SlidingModel, motion: FlatMotion, friction: FrictionLaw,
                 preset: dict, *, stall_steps, stall_fraction, snapshots, contact_section, say):
        self.sm, self.model, self.motion, self.friction = sm, sm.m, motion, friction
        self.stall_steps, self.stall_fraction = stall_steps, stall_fraction
        self.contact_section, self.say = contact_section, say
        self.d_knots = np.asarray(motion.tangential, float)
        self.caps = step_caps(motion, preset)
        self.grid = step_grid(motion, preset)
        self.max_inel = float(preset["max_inelastic_step"])
        self.max_cuts = int(preset["max_cuts"])
        if snapshots is None:
            snapshots = _default_snapshots(motion)
        self.snap_times = {k: float(v) for k, v in snapshots.items()}
        self.snap = {}
        self.end = motion.end
        self.t = t = motion.start
        self.w, self.delta = motion(t)
        self.state = sm.material.initial_state(self.model.shape, components=6)
        self.iface = sm.initial_interface(self.delta)
        self.u = np.zeros(self.model.ndofs)
        _, out0 = sm.evaluate(self.u, self.w, self.delta, self.state, self.iface, 0.0,
                              tangent=True)
        self.out_last = out0
        self.f_ref = 0.0  # contact force norm of the last accepted step
        self.rows = [dict(sm.record(self.u, self.w, self.delta, out0),
                          critical_shear_factor=math.nan, time=t, phase=motion.phase(t),
                          newton_iterations=0, step_cuts=0, damped_solves=0, time_step=0.0,
                          wall_time=0.0)]
        for k, ts in self.snap_times.items():
            if ts <= t:
                self.snap[k] = (t, _snapshot(self.model, self.u, self.state,
                                             out0["contact"]["tn"] if contact_section
                                             else None), {})
        # a progress line every ~5 s of a run past ~5 s (the job's log; logging only)
        self.ticker = StepProgress(log, "sliding: ")
        self.critical, self.warned = [], False  # critical_factor at the starts of sliding and after
        self.slow, self.stop_reason = 0, ""     # steps in a row below stall_fraction of their cap

    def begin(self, n, dt):
        t = self.t
        self.step_start = time.perf_counter()
        self.iterations = 0
        self.phase = self.motion.phase(t)
        self.cap = self.caps[self.motion.segment(t)]
        self.proposed = min(dt, self.cap)
        grid = self.grid
        knot = float(grid[np.searchsorted(grid, t + 1e-12 * max(abs(t), 1.0), side="right")])
        return self.cap, knot

    def attempt(self, n, t_new, cuts):
        sm, state, iface = self.sm, self.state, self.iface
        h = t_new - self.t
        w_new, d_new = self.motion(t_new)
        data = dict(h=h, w_new=w_new, d_new=d_new)
        u0 = sm.predict(self.u, self.out_last, w_new - self.w, d_new - self.delta)
        damped = 0
        try:
            try:
                u_new, out, its = sm.solve_step(u0, w_new, d_new, state, iface, h, self.f_ref)
            except StepFailed as exc:
                if not (self.phase == "sliding" and h < self.stall_fraction * self.cap):
                    raise
                # a sliding step cut to where its steps would stall: through the
                # slip instability
                self.iterations += exc.iterations
                u_new, out, its, damped = sm.solve_through_slip(self.u, w_new, d_new, state,
                                                                iface, h, self.f_ref)
            self.iterations += its
            step_inel = float(np.max(equivalent_strain(
                out["state"].inelastic_strain - state.inelastic_strain)))
            if step_inel > self.max_inel:
                return Trial(t_new, f"inelastic strain step {step_inel:.3g} > {self.max_inel:g}",
                             data=data)
        except StepFailed as exc:
            self.iterations += exc.iterations
            return Trial(t_new, str(exc), data=data)
        rec = sm.record(u_new, w_new, d_new, out)
        rec["critical_shear_factor"] = math.nan
        if self.phase == "sliding":
            rec["critical_shear_factor"] = sm.critical_factor(
                u_new, w_new, d_new, out, _direction(self.motion, self.d_knots, self.t))
        if rec["overflow"]:
            raise ContactZoneError(
                f"step {n} (t = {t_new:.6g} s): the contact reached the edge of the "
                f"candidate zone (radius {self.model.contact_radius:.4g} m); give a larger "
                f"contact_radius")
        data.update(u_new=u_new, out=out, rec=rec, damped=damped, step_inel=step_inel)
        return Trial(t_new, data=data)

    def failure(self, cuts, trial):
        d = trial.data
        return cuts.error(d["w_new"], self.w,
                          f"t = {trial.t_new:.6g} s, delta = {d['d_new']:.6g} m: {trial.reason}")

    def cut(self, n, dt, trial):
        self.say(f"step {n}: cut to dt = {dt:.4g} s ({trial.reason})")

    def accept(self, n, trial, cuts):
        d = trial.data
        sm, model, motion, friction = self.sm, self.model, self.motion, self.friction
        h, out, rec, damped, iterations = d["h"], d["out"], d["rec"], d["damped"], self.iterations
        self.iface = sm.commit(out, self.iface)
        self.f_ref = float(np.linalg.norm(out["contact"]["fc"]))
        self.u, self.t, self.w, self.delta, self.state = (d["u_new"], trial.t_new, d["w_new"],
                                                          d["d_new"], out["state"])
        u, t, w, delta, state, phase = self.u, self.t, self.w, self.delta, self.state, self.phase
        # the converged state with the dragged anchors, for the next predictor
        _, self.out_last = sm.evaluate(u, w, delta, state, self.iface, h)
        rows = self.rows
        rows.append(dict(rec, time=t, phase=phase, newton_iterations=iterations,
                         step_cuts=cuts.count, damped_solves=damped, time_step=h,
                         wall_time=time.perf_counter() - self.step_start))
        for k, ts in self.snap_times.items():
            if k not in self.snap and t >= ts * (1 - 1e-12):
                a_max = max(r["contact_area"] for r in rows)
                a_ref = math.sqrt(a_max / math.pi) if a_max > 0 else model.contact_radius / 2.5
                self.snap[k] = (t, _snapshot(model, u, state, out["contact"]["tn"]
                                             if self.contact_section else None),
                                _largest_deformation(model, u, w, state, a_ref))
        self.ticker.update(n, (t - motion.start) / (motion.end - motion.start),
                           f"t = {t:.4g} of {motion.end:.4g} s ({phase}), approach {w:.4g} m, "
                           f"slide {delta:.4g} m", iterations)
        s_c = rec["critical_shear_factor"]
        self.say(f"step {n}: t = {t:.6g} of {motion.end:.6g} s, w = {w:.4g} m, "
                 f"delta = {delta:.4g} m, F_N = {rec['normal_force']:.4g} N, "
                 f"F_T = {rec['tangential_force']:.4g} N, A = {rec['contact_area']:.4g} m^2, "
                 f"{iterations} Newton iterations, {cuts.count} cuts"
                 + (f", through the slip in {damped} damped solves" if damped else "")
                 + ("" if math.isnan(s_c) else f", critical: {_critical_text(s_c, friction)}"))
        if phase != "sliding" and motion.phase(t) == "sliding" and t < motion.end * (1 - 1e-12):
            s_c = sm.critical_factor(u, w, delta, out, _direction(motion, self.d_knots, t))
            self.say(f"start of sliding at t = {t:.6g} s: the sliding junction's tangent "
                     + (f"turns singular at {_critical_text(s_c, friction)}"
                        if math.isfinite(s_c) else
                        f"stays regular up to {CRITICAL_FACTOR_BOUND:g} times the shear "
                        "resistance"))
        if not math.isnan(s_c):
            self._critical(t, s_c)
        # a step that ended on a time of the grid before its try's length grows from
        # that length, not from the rest of the way to the grid time
        reached = h if cuts.count else max(h, self.proposed)
        dt = strain_limited(PACE.factor(iterations, cuts.count) * reached, h, d["step_inel"],
                            self.max_inel)
        self.slow = self.slow + 1 if reached < self.stall_fraction * self.cap else 0
        stall = self.stall_steps
        if self.slow >= stall and t < motion.end * (1 - 1e-12):  # not on the last step
            self._stalled(n, (t - rows[-stall - 1]["time"]) / stall)
            return Accepted(dt, stop=True)
        return Accepted(dt)

    def _critical(self, t, s_c):
        """Keep the critical factor `s_c` of time `t`; warn the first time it is below 1."""
        self.critical.append(s_c)
        if s_c < 1.0 and not self.warned:
            self.warned = True
            log.warning("t = %.6g s: the sliding junction's tangent turns singular at %s, "
                        "below the shear resistance of the scene: the sliding problem of "
                        "this mesh is not unique near this state (Hassani et al. 2003); "
                        "expect step cuts, stalls and forces that depend on the mesh",
                        t, _critical_text(s_c, self.friction))

    def _stalled(self, n, pace):
        """Say why the run stops at step `n`, its last steps `pace` s long on average."""
        t, critical, friction, stall = self.t, self.critical, self.friction, self.stall_steps
        self.stop_reason = (
            f"stalled at step {n} (t = {t:.6g} s, delta = {self.delta:.4g} m): the last "
            f"{stall} steps advanced {pace:.3g} s each on average, under "
            f"{self.stall_fraction:g} of the step cap {self.cap:.4g} s; the remaining "
            f"{self.motion.end - t:.6g} s would take about {(self.motion.end - t) / pace:.3g} "
            "more steps" + (f"; smallest critical factor {_critical_text(min(critical), friction)}"
                            if critical else "")
            + ("; past it the sliding problem is not unique: a lower shear resistance, "
               "or a constant shear strength (asperity_sliding_junction), slides"
               if critical and min(critical) < 1.0 else ""))
        log.warning("%s", self.stop_reason)
        self.say(f"stopped: {self.stop_reason}")


def press_3d(geometry, material, approach, accuracy="standard", mesh: MeshSpec | None = None,
             contact_radius: float | None = None, penalty_factor: float = PENALTY_FACTOR_3D,
             progress=None) -> xr.Dataset:
    """The flat pressed onto the 3-D asperity without sliding or friction: `solve_sliding`
    with the flat moving only normally, w(t) through 0 and the approaches of `approach`
    (a number or increasing sequence [m]) at t = 1, 2, ... s, each segment in the
    preset's ``normal_steps`` steps, and a frictionless law (t_x = t_y = 0, report
    3.3.2).  The steps land on the knots (`step_grid`), so each approach is a row, and a
    snapshot ``approach i`` with the contact section (``contact_pressure`` at the contact
    nodes ``contact_x``, ``contact_y``: the contact's shape).

    Returns `solve_sliding`'s Dataset with ``normal_stiffness`` dF/dw [N/m] added: the
    derivative of the force history, second-order differences on the non-uniform steps
    (`numpy.gradient`), one-sided at the ends."""
    w = np.atleast_1d(np.asarray(approach, float))
    if w.ndim != 1 or not (np.all(np.isfinite(w)) and w[0] > 0 and np.all(np.diff(w) > 0)):
        raise ValueError(f"approach must be positive and increasing, got {approach!r}")
    times = tuple(float(t) for t in range(w.size + 1))
    motion = FlatMotion(times, (0.0,) + tuple(w), (0.0,) * (w.size + 1))
    scale = contact_radius if contact_radius is not None else float(
        geometry.intersection_radius(w[-1:])[0])
    ds = solve_sliding(geometry, material, motion, FrictionLaw(ShearResistance(), 1e-3 * scale),
                       accuracy=accuracy, mesh=mesh, contact_radius=contact_radius,
                       penalty_factor=penalty_factor, progress=progress, contact_section=True,
                       snapshots={f"approach {i}": t for i, t in enumerate(times[1:])})
    f, wd = ds["normal_force"].values, ds["normal_displacement"].values
    ds["normal_stiffness"] = ("step", np.gradient(f, wd), dict(
        units="N/m", long_name="normal contact stiffness dF/dw (differences of the force history)"))
    return ds


def _direction(motion: FlatMotion, d_knots, t: float) -> float:
    """The flat's direction along x in the segment of the motion from t."""
    seg = motion.segment(t)
    return float(d_knots[seg + 1] - d_knots[seg])


def _critical_text(factor: float, friction: FrictionLaw) -> str:
    """`SlidingModel.critical_factor` in words: a friction coefficient for a Coulomb
    law, else a factor of the shear resistance ("none" where it is inf)."""
    r = friction.resistance
    if not math.isfinite(factor):
        return f"none below {CRITICAL_FACTOR_BOUND:g} times the shear resistance"
    if r.c0 == 0.0 and r.c2 == 0.0:
        return f"a friction coefficient {factor * r.c1:.3g}"
    return f"{factor:.3g} times the shear resistance"


def _largest_deformation(model: HalfModel, u, w, state, a_ref: float) -> dict:
    """Where the largest equivalent inelastic strain sits, relative to the junction.

    Its depth below the flat (z = -w) in the deformed configuration is
    compared with ``JUNCTION_DEPTH_FRACTION`` a_ref, a_ref = sqrt(A_max / pi)
    the equivalent radius of the largest contact area of the run.
    """
    ep = equivalent_strain(state.inelastic_strain)
    if not np.any(ep > INELASTIC_THRESHOLD):
        return dict(largest_deformation="none (elastic)", largest_deformation_depth=math.nan)
    i = np.unravel_index(int(np.argmax(ep)), ep.shape)
    X = model.x[(slice(None),) + i]
    Ud = model.point_displacements(u)
    depth_all = -w - (model.x[2] + Ud[2])          # below the flat, deformed
    depth = float(depth_all[i])
    limit = JUNCTION_DEPTH_FRACTION * a_ref
    layer = depth_all <= limit
    where = "at the junction" if depth <= limit else "below the junction"
    return dict(
        largest_deformation=where,
        largest_deformation_criterion=(
            f"'at the junction' if the largest equivalent inelastic strain (quadrature points, "
            f"end of the run) lies less than {JUNCTION_DEPTH_FRACTION:g} a_ref below the flat "
            f"(deformed configuration; a_ref = sqrt(A_max / pi), A_max the largest contact area "
            f"of the run), else 'below the junction'"),
        largest_deformation_depth=depth,
        largest_deformation_depth_over_radius=depth / a_ref if a_ref > 0 else math.nan,
        largest_deformation_position=np.asarray(X, float),
        largest_deformation_displacement=np.asarray(Ud[(slice(None),) + i], float),
        largest_deformation_value=float(ep[i]),
        reference_contact_radius=a_ref,
        max_inelastic_strain_junction_layer=float(ep[layer].max()) if layer.any() else 0.0,
        max_inelastic_strain_below_layer=float(ep[~layer].max()) if (~layer).any() else 0.0,
    )


def _sliding_dataset(ds: xr.Dataset, rows, model: HalfModel, sm: SlidingModel, u, w, state,
                     snap, attrs):
    """The per-step Dataset `ds` with the symmetry-plane sections, the profile
    below the apex and the attributes."""
    # symmetry-plane section (Fig. 9.5)
    X = model.hm.mesh.doflocs[:, model.plane_nodes]
    names = list(snap)
    if names:
        ds = ds.assign_coords(snapshot=("snapshot", np.array(names, dtype=object),
                                        dict(units="1", long_name="instant of the section")))
        ds["snapshot_time"] = ("snapshot", np.array([snap[n][0] for n in names]),
                               dict(units="s", long_name="time of the section"))
        for key, var, units, ln in (("ux", "plane_ux", "m", "horizontal displacement u_x"),
                                    ("uz", "plane_uz", "m", "vertical displacement u_z"),
                                    ("ep", "plane_inelastic_strain", "1",
                                     "von Mises equivalent inelastic strain (element means "
                                     "averaged at the nodes)")):
            ds[var] = (("snapshot", "plane_node"), np.array([snap[n][1][key] for n in names]),
                       dict(units=units, long_name=f"{ln} on the symmetry plane y = 0"))
        if "tn" in snap[names[0]][1]:
            ds["contact_pressure"] = (("snapshot", "contact_node"),
                                      np.array([snap[n][1]["tn"] for n in names]), dict(
                units="Pa", long_name="normal pressure t_N at the contact node (penalty)"))
            for var, val, units, ln in (
                    ("contact_x", model.vX[0], "m", "x of the contact node (weighted, undeformed)"),
                    ("contact_y", model.vX[1], "m", "y of the contact node (weighted, undeformed)"),
                    ("contact_weight", model.vw, "m^2", "weight int phi_i ds of the contact node "
                     "(half model)")):
                ds[var] = ("contact_node", val, dict(units=units, long_name=ln))
            ds = ds.assign_coords(contact_node=("contact_node", np.arange(model.vw.size), dict(
                units="1", long_name="contact node (P2 node of a top facet)")))
    ds["plane_x"] = ("plane_node", X[0], dict(units="m", long_name="x of the node (undeformed)"))
    ds["plane_z"] = ("plane_node", X[2], dict(units="m", long_name="z of the node above the apex (undeformed)"))
    ds["plane_triangles"] = (("plane_triangle", "corner"), model.plane_triangles.T.astype(np.int32),
                             dict(units="1", long_name="node indices (into plane_node) of the "
                                  "linear sub-triangles of the 6-node faces on y = 0"))
    ds = ds.assign_coords(
        plane_node=("plane_node", np.arange(X.shape[1]), dict(units="1", long_name="node on the symmetry plane")),
        plane_triangle=("plane_triangle", np.arange(model.plane_triangles.shape[1]),
                        dict(units="1", long_name="triangle on the symmetry plane")),
        corner=("corner", np.arange(3), dict(units="1", long_name="triangle corner")))
    # inelastic strain versus depth below the flat, under the apex
    a_max = max(r["contact_area"] for r in rows)
    a_ref = math.sqrt(a_max / math.pi) if a_max > 0 else model.contact_radius / 2.5
    ep = equivalent_strain(state.inelastic_strain)
    Ud = model.point_displacements(u)
    xd = model.x + Ud
    depth = -w - xd[2]
    nodes = model.hm.nodes_ref
    apex = int(np.argmin(np.sum(nodes**2, axis=0)))
    cx = float(model.hm.mesh.doflocs[0, apex] + u[model.dofmap[0, apex]])
    under = np.hypot(xd[0] - cx, xd[1]) <= a_ref
    edges = np.linspace(0.0, 3.0 * a_ref, 16)
    mids = 0.5 * (edges[1:] + edges[:-1])
    k = np.clip(np.searchsorted(edges, depth, side="right") - 1, -1, mids.size)
    prof = np.full(mids.size, np.nan)
    sel = under & (k >= 0) & (k < mids.size)
    if sel.any():
        np.fmax.at(prof, k[sel], ep[sel])
    ds = ds.assign_coords(depth=("depth", mids, dict(units="m", long_name="depth below the flat (bin centre)")))
    ds["inelastic_strain_below_apex"] = ("depth", prof, dict(
        units="1", long_name="largest equivalent inelastic strain at this depth within a_ref "
        "(horizontally) of the apex, end of the run"))
    attrs.update(_largest_deformation(model, u, w, state, a_ref))
    for name in names:          # the same at the other sections (e.g. end of pressing)
        if name != "end":
            key = name.replace(" ", "_")
            for k, v in snap[name][2].items():
                if k.startswith(("largest_deformation", "reference_contact", "max_inelastic")) \
                        and not k.endswith("criterion"):
                    attrs[f"{key}_{k}"] = v
    attrs["apex_x_end"] = cx
    sliding = np.array([r["phase"] == "sliding" and r["contact_area"] > 0 for r in rows])
    if sliding.any():
        tau = np.array([r["mean_tangential_traction"] for r in rows])[sliding]
        attrs["mean_tangential_traction_sliding"] = float(tau.mean())
        attrs["mean_tangential_traction_sliding_method"] = (
            "mean over the sliding steps with contact of tangential force / contact area "
            "(report 9.2: about 64 MPa)")
    ds.attrs.update({k: v for k, v in attrs.items()})
    return ds
