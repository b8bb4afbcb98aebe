"""The adhesive asperity's model: a mesh graded to the adhesive ring, its operators,
and the continuity test of a step (report 3.3.3, 7.3).

An `AdhesiveModel` is one mesh of the elastic asperity with the stiffness of
its body condensed onto the candidate surface dofs (K_S), the C1 penalty
rule (report 3.3.2) and the Lennard-Jones rule (report 3.3.3) on the same
surface facets, and the Newton problem of the energy Pi(u; w) on them
(`asperity.fe.solvers.adhesive`, where Pi and its tangent are stated).
`adhesive_model` builds the first one of a path up to the interference
w_max; a path whose mesh follows the contact makes new ones
(`AdhesiveModel.remeshed`).

Continuity of a step
--------------------
Along a branch the minimum energy Pi*(w) has the derivative F (the force),
so a step from w0 to w1 on one branch satisfies the energy balance

    Pi*(w1) - Pi*(w0) = (F0 + F1) / 2 (w1 - w0)

to the trapezoidal rule's error, while a jump releases a finite energy.  A
step is continuous if its energy balances and the surface stayed near the
tangent predictor or, where it did not (a contact zipping or peeling over
many elements), near the secant through a state solved halfway
(`AdhesiveModel.continuity`, `balanced`, `midpoint`).

Mesh
----
The adhesion acts within a ring of the contact edge a few d wide in
separation: sqrt(2 R d) wide for a stiff sphere, the cohesive length
l = E* dgamma / q_max^2 (`LennardJones.process_zone`, 6 nm for aluminum
with dgamma = 1 J/m^2, d = 0.3 nm) for a compliant one.  The edge moves
over the whole band 0 <= r <= r_band during the path, so the initial ring
mesh (`mesh.AsperityMesh`) is refined until every element is smaller than
h_ring + grading * (its distance to the band) (`band_mesh`), with

    h_ring = min(l / process_zone_elements, sqrt(2 R d) / ring_elements),

and r_band 1.1 times the larger of the radius where the undeformed gap at
the largest interference, less JKR's lift of the surface around the
contact (sqrt(2 pi a W / E*), an upper bound), is the cut-off, and the JKR
contact radius there plus 5 min(l, sqrt(2 R d)) (an adhesive contact is
never larger than JKR's).  The zone of candidate facets is the band; a
path whose adhesive ring reaches its last tenth (`AdhesiveModel.overflow`)
is restarted with a wider band.  The number of band facets grows like mu^2
(contact radius / cohesive length), and the cost with it (the dense
condensed stiffness is m x m in the band's nodes, the active set of the
tangent holds every node in contact).

Meshes that follow the contact: a band of more than ``follow_above``
ring elements (a large Tabor parameter) is not refined as a whole.  Only
a window of it is (`AdhesiveModel.window_for`): the cohesive zone, from
the edge of the surface held in the well of q (separation below
(1 + TIP_SEPARATION) d, past the peak of q) or the contact edge to the
surface within FINE_SEPARATION d of the flat, plus a margin of
``follow_margin_elements`` ring elements on either side (preset; or
``follow_margin`` times the radius that reaches, if that is larger: the
contact inside and the surface outside are graded away from it as above);
the candidate zone is still the whole band.  The margin trades the size
of the Newton tangent's active set, whose dense factorization is most of
the cost, against how often the mesh moves: a narrow margin keeps the
active set small at the price of more meshes along the path
(tests/fe/test_adhesion_follow.py checks such paths against the whole band
refined).  At a large Tabor parameter the surface held in the well is a
wide annulus around the contact (the tension of JKR's contact), where the
fields are smooth; the contact edge inside it (where the penalty takes
over from the adhesion, the edge of the contact area) gets a band of its
own, of elements EDGE_COARSENING times longer.  Refining the whole annulus
at h_ring instead (preset key ``edge_band`` False) puts every node of the
annulus in the active set of the Newton tangent, whose factorization
costs the cube of its size (`AdhesiveTangent`), where the smooth fields
need no such refinement.  A state whose edge or ring has come within a
quarter of the margin of its window's ends needs a new mesh (`window_for`
returns its bands); the path driver moves it there
(`asperity.fe.drivers.adhesive_trace`).  Each state keeps its mesh
(``AdhesiveState.model``); a mesh the path has left drops the sparse
factors of its body (`AdhesiveModel.release`), and `evaluate` makes them
again if it needs them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from asperity.fe.contact.adhesion import LennardJones, adhesion_zone
from asperity.fe.contact.penalty import PENALTY_FACTOR, C1Penalty, ContactZone, contact_edge
from asperity.fe.discretization.assembly import CondensedStiffness, Discretization
from asperity.fe.discretization.geometry import CosineHill, Profile
from asperity.fe.discretization.mesh import AsperityMesh, MeshSpec
from asperity.fe.errors import StepFailed
from asperity.fe.materials.elastic import equivalent_strain, von_mises
from asperity.fe.presets import PLANE_STRAIN_DOMAIN, resolve
from asperity.fe.solvers.adhesive import AdhesiveNewton, AdhesiveState, predictor
from asperity.references.adhesion import jkr_contact_radius

#: a mesh following the contact (`AdhesiveModel.window_for`): the fine band
#: spans the cohesive zone, from the edge of the surface held within
#: TIP_SEPARATION d of the well of q (or the contact edge) to the surface
#: within FINE_SEPARATION d of the flat, with the preset's margin on each
#: side (``follow_margin``, ``follow_margin_elements``); a contact edge
#: farther inside has a band of its own, of elements EDGE_COARSENING times
#: longer; a state whose edge or ring comes within a quarter of the margin
#: of its band's ends is moved to a new mesh (`asperity.fe.drivers.adhesive_trace`)
FINE_SEPARATION = 4.0
TIP_SEPARATION = 0.2
EDGE_COARSENING = 2.0


def tip_radius(geometry: Profile) -> float:
    """Radius of curvature at the apex [m]."""
    if isinstance(geometry, CosineHill):
        return 1.0 / geometry.tip_curvature
    radius = getattr(geometry, "radius", None)
    if radius is not None:
        return float(radius)
    r = 1e-3 * geometry.extent
    return float(r**2 / (2.0 * abs(geometry.surface(r))))


def band_mesh(geometry: Profile, windows, grading: float, spec: MeshSpec,
              max_rounds: int = 80) -> AsperityMesh:
    """The ring mesh refined until h <= h_w + grading * distance to band w, for
    some band w.

    Each band is the top surface r_lo <= r <= r_hi with its element size,
    ``windows = ((r_lo, r_hi, h_w), ...)`` (r_lo = 0: from the apex).
    Red-green-blue refinement of the elements too large for their
    distance, repeated.
    """
    mesh = AsperityMesh.initial(geometry, spec)
    for _ in range(max_rounds):
        m = mesh.vertices
        p = m.p[:, m.t]  # (2, 3, ne)
        edges = np.stack([np.hypot(*(p[:, i] - p[:, (i + 1) % 3])) for i in range(3)])
        size = edges.max(axis=0)
        c = p.mean(axis=1)
        depth = np.maximum(geometry.body_surface(c[0]) - c[1], 0.0)
        bound = np.full(size.shape, np.inf)
        for r_lo, r_hi, h in windows:
            off = np.maximum(np.maximum(c[0] - r_hi, r_lo - c[0]), 0.0)
            dist = np.maximum(np.hypot(off, depth) - 0.5 * size, 0.0)
            bound = np.minimum(bound, h + grading * dist)
        marked = np.nonzero(size > bound)[0]
        if marked.size == 0:
            return mesh
        mesh = mesh.refined(marked)
    raise RuntimeError("band refinement did not finish")


@dataclass
class _Scales:
    radius: float
    contact_modulus: float
    tabor: float
    process_zone: float
    ring: float
    h_ring: float
    r_band: float
    capped: bool


def _scales(geometry, material, adhesion: LennardJones, w_top: float, pre: dict,
            band_factor: float = 1.0) -> _Scales:
    R = tip_radius(geometry)
    Es = material.contact_modulus
    mu = adhesion.tabor_parameter(R, Es)
    lpz = adhesion.process_zone(Es)
    ring = math.sqrt(2.0 * R * adhesion.d)
    h = min(lpz / pre["process_zone_elements"], ring / pre["ring_elements"])
    W = adhesion.work_of_adhesion
    if geometry.axisymmetric:
        a_jkr = jkr_contact_radius(R, Es, W, max(w_top, 0.0))
        lift = math.sqrt(2.0 * math.pi * a_jkr * W / Es)  # JKR: the neck lifts the surface
    else:
        a_jkr = math.sqrt(2.0 * R * max(w_top, adhesion.d))
        lift = 0.0
    reach = max(w_top, 0.0) + adhesion.range - adhesion.d + lift
    if reach >= geometry.height:
        raise ValueError("the largest interference plus the adhesion range reaches the foot of the hill")
    r_geo = float(geometry.intersection_radius(np.array([reach]))[0])
    r_band = band_factor * 1.1 * max(r_geo, a_jkr + 5.0 * min(lpz, ring))
    r_band = min(r_band, 0.9 * geometry.extent)
    capped = r_band / h > pre["max_band_facets"]
    if capped:
        h = r_band / pre["max_band_facets"]
    return _Scales(R, Es, mu, lpz, ring, h, r_band, capped)


class AdhesiveModel:
    """Mesh graded to the adhesive band, condensed stiffness, both surface rules.

    The fine bands are ``window`` ((r_lo, r_hi, h), ...); the candidate zone
    is always 0 <= r <= r_band.  A model `follows` the contact if the band has more
    than ``follow_above`` ring elements: its fine band is then a window
    around the contact edge, by default the preset's
    ``follow_margin_elements`` ring elements at the apex, moved along the
    path (`window_for`, `remeshed`; module docstring, "Mesh"); else it is
    the whole band (0, r_band).
    """

    def __init__(self, geometry: Profile, material, adhesion: LennardJones, scales: _Scales,
                 preset: dict, penalty_factor: float = PENALTY_FACTOR,
                 window: tuple | None = None):
        if not getattr(material, "is_linear", False):
            raise NotImplementedError("adhesion is implemented for elastic materials only")
        t0 = time.perf_counter()
        self.geometry, self.material, self.adhesion = geometry, material, adhesion
        self.scales, self.preset, self.penalty_factor = scales, preset, penalty_factor
        self.follows = scales.r_band > preset["follow_above"] * scales.h_ring
        if window is None:
            h = scales.h_ring
            window = ((0.0, preset["follow_margin_elements"] * h if self.follows
                       else scales.r_band, h),)
        self.window = window
        if geometry.axisymmetric:
            L = preset["domain_factor"] * geometry.length_scale
        else:
            L = PLANE_STRAIN_DOMAIN * geometry.length_scale
        spec = MeshSpec(L, min(4.0 * scales.h_ring, 0.1 * scales.r_band), preset["growth"],
                        preset["n_theta"])
        self.mesh = band_mesh(geometry, self.window, preset["grading"], spec)
        self.disc = Discretization(self.mesh)
        top = self.disc.top
        outer = top.coords[0, 2::2]
        nf = int(np.searchsorted(outer, scales.r_band)) + 1
        nf = max(2, min(nf, top.nfacets - 1))
        self.zone = ContactZone(top, nf, geometry)
        self.azone = adhesion_zone(top, nf, geometry, preset["gauss_points"],
                                   preset["subdivisions"])
        self.cond = self._condensed()
        self.law = C1Penalty.for_zone(self.zone, material.contact_modulus, penalty_factor)
        self.newton = AdhesiveNewton(self.cond.stiffness, self.zone, self.law, self.azone,
                                     adhesion, preset["tolerance"], preset["max_iterations"])
        R = scales.radius
        #: force scale of the adhesion: 2 pi R dgamma, or sqrt(R / d) dgamma per length
        self.force_reference = (2 * np.pi * R * adhesion.dgamma if geometry.axisymmetric
                                else 2 * math.sqrt(R / adhesion.d) * adhesion.dgamma)
        # the last tenth of the band's facets must stay out of the adhesive range
        # (of its radius where the facets outside the fine band are graded)
        if self.follows:
            ends = top.coords[0, 2:2 * nf + 1:2]
            self.edge_facets = ends > 0.9 * ends[-1]
        else:
            self.edge_facets = np.arange(nf) >= int(0.9 * nf)
        self.setup_time = time.perf_counter() - t0

    @property
    def dofs(self) -> int:
        return len(self.disc.free)

    def _condensed(self) -> CondensedStiffness:
        _, D = self.material.response(np.zeros((4, 1)))
        return CondensedStiffness(self.disc, self.disc.stiffness(np.asarray(D)), self.zone.dofs)

    def release(self) -> None:
        """Drop the sparse factors of the body, the bulk of a model's memory.

        The path needs only the condensed stiffness (`AdhesiveNewton`); the
        factors serve `evaluate` (the fields inside the body), which factors
        the body again if they were dropped.  A path whose mesh follows the
        contact keeps every mesh a recorded state lies on; the path driver
        (`adhesive_trace.trace`) evaluates those states and drops the factors
        when the path moves to another mesh, so only the current mesh holds
        them.
        """
        self.cond.lu = None

    def continuity(self, old: AdhesiveState, new: AdhesiveState, pred: np.ndarray,
                   pre: dict) -> tuple[str, int]:
        """Whether `new` continues the branch of `old` (module docstring,
        "Continuity of a step"):
        ("continuous", "steep" or "jump", the Newton iterations spent on
        the test).

        Along a branch the minimum energy Pi*(w) has the derivative F
        (/ 2 pi, or / 2 in plane strain), so the trapezoidal rule
        Pi*(w1) - Pi*(w0) = (F0 + F1) / 2 (w1 - w0) holds to O(dw^2) even
        across the kinks where nodes enter or leave contact; a jump
        releases a finite energy that does not vanish with the step
        (`balanced`).  A step whose energy balances is continuous if the
        surface moved within d / 2 + 2 |dw| of the tangent predictor `pred`
        (the allowance covers the kinks where nodes enter or leave
        contact; the predictor's own move is capped at d + 2 |dw|, since
        du/dw blows up near a fold).  A jump of the surface that releases
        too little energy to show in the balance still moves it far from
        the predictor (a jump-in at a small Tabor parameter releases about
        as little energy as a continuous step's balance error, but moves the
        surface farther off the predictor than any continuous step; so both
        tests are needed), while the last continuous steps before a fold stay
        close to the predictor at min_step.

        Where a contact zips and peels over many ring elements (a large
        Tabor parameter) the predictor is no guide: the nodes that enter or
        leave contact within a step move several |dw| off it while the
        energy balances. Such a step is tested against the secant instead
        (`midpoint`): the state halfway, solved from `old`, must balance its
        energy with both ends and lie within d / 2 + |dw| of the mean of
        their surfaces. A jump J moves the secant's midpoint by J / 2
        whichever half it lies in, so the secant test misses the same jumps
        as the predictor test (J below d + 2 |dw|, the predictor's allowance
        and d / 2 more). A step whose energy balances but that fails the
        secant test too (or whose midpoint does not converge) is "steep":
        the path's step control (`adhesive_trace`) retries it once from the
        first midpoint it reaches before bisecting on. At the smallest steps
        (min_step * d), where a continuous branch cannot move far from its
        tangent, only the predictor counts: a jump is a move of more than
        jump_tolerance * d (0.25 d) away from it. Jumps smaller than these
        allowances are recorded as a steep continuous stretch.
        """
        d = self.adhesion.d
        dw = new.w - old.w
        off = np.max(np.abs(new.u - pred), initial=0.0)
        if abs(dw) <= pre["min_step"] * d:
            return ("continuous" if off <= pre["jump_tolerance"] * d else "jump"), 0
        if not self.balanced(old, new, pre):
            return "jump", 0
        if off <= 0.5 * d + 2.0 * abs(dw):
            return "continuous", 0
        verdict, iterations, _ = self.midpoint(old, new, pre)
        return verdict, iterations

    def balanced(self, old: AdhesiveState, new: AdhesiveState, pre: dict) -> bool:
        """The energy balance of the step from `old` to `new` (`continuity`):
        |Pi*(w1) - Pi*(w0) - (F0 + F1) / 2 (w1 - w0)| within
        energy_tolerance * d * max(|F|, F_ref / 20) plus, between two states
        both touching or both not, the rule's own truncation error, estimated
        as dw^2 |k1 - k0| / 6 (twice the trapezoidal error dw^3 F'' / 12, with
        F'' ~ (k1 - k0) / dw from the stiffnesses k at both ends).  Without
        the truncation term the geometric steps beyond 4 d (tens of d each)
        fail the balance through the trapezoidal rule's own error and are
        halved for nothing; it is not allowed across touching, where a
        jump-in moves the stiffness by the contact's own and could hide the
        energy it releases."""
        d = self.adhesion.d
        ff = self.zone.force_factor
        dw = new.w - old.w
        f0, f1 = old.force / ff, new.force / ff
        scale = max(abs(f0), abs(f1), 0.05 * self.force_reference / ff)
        balance = new.energy - old.energy - 0.5 * (f0 + f1) * dw
        same_side = (old.contact_force > 0) == (new.contact_force > 0)
        truncation = dw * dw * abs(new.stiffness - old.stiffness) / (6.0 * ff) if same_side else 0.0
        return abs(balance) <= pre["energy_tolerance"] * d * scale + truncation

    def midpoint(self, old: AdhesiveState, new: AdhesiveState,
                 pre: dict) -> tuple[str, int, float]:
        """The secant test of a step that left its predictor (`continuity`):
        the state at the middle of the step, solved from `old`'s predictor,
        balances its energy with both ends and its surface is within
        d / 2 + |dw| of theirs averaged ("continuous"); else "jump" if a
        half does not balance, "steep" if only the secant or the solve
        fails.  Returns (verdict, iterations, the largest departure from the
        secant [m]; NaN if the solve failed)."""
        d = self.adhesion.d
        wm = 0.5 * (old.w + new.w)
        try:
            u, parts, T, its = self.newton.solve(wm, predictor(old, wm))
        except StepFailed as exc:
            return "steep", exc.iterations, math.nan
        mid = self.newton.state(wm, u, parts, T)
        secant = np.max(np.abs(u - 0.5 * (old.u + new.u)), initial=0.0)
        if not (self.balanced(old, mid, pre) and self.balanced(mid, new, pre)):
            return "jump", its, secant
        verdict = "continuous" if secant <= 0.5 * d + abs(new.w - old.w) else "steep"
        return verdict, its, secant

    def window_for(self, state: AdhesiveState) -> tuple | None:
        """The fine bands `state` needs if this mesh's will not do, else None.

        The ring is the cohesive zone: the surface from the edge of the
        adhered region (the outermost node closer than (1 +
        TIP_SEPARATION) d to the flat, past the peak of q; the contact
        edge if beyond it; the apex if neither) to the outermost node
        within FINE_SEPARATION d of the flat (q there is 4 % of its peak).
        Its band must reach a quarter of the margin beyond it on either
        side (or the apex, or r_band); a new band extends a full margin
        beyond it, from the apex if that leaves less than a margin inside,
        at the ring's element size h_ring.  At a large Tabor parameter the
        surface inside the ring is held in the well of q (d < s < 1.2 d)
        over a wide annulus around the contact (the tension of JKR's
        contact), where the fields are smooth: only the contact edge
        (where the penalty takes over from the adhesion) needs a band of
        its own there, with the same margins and elements EDGE_COARSENING
        times longer (preset key ``edge_band``; without it the band reaches
        from the contact edge, or the apex, to the ring).  Returns the bands
        ((r_lo, r_hi, h), ...).
        """
        if not self.follows:
            return None
        d = self.adhesion.d
        r = self.zone.coords[0]
        pen = self.zone.node_penetration(state.u, state.w)
        touching = pen >= 0
        edge = contact_edge(r, -pen, touching) if touching.any() else 0.0
        near = pen > -(FINE_SEPARATION - 1.0) * d
        outer = max(float(r[near].max()) if near.any() else 0.0, edge)
        held = pen > -TIP_SEPARATION * d
        tip = max(float(r[held].max()) if held.any() else 0.0, edge)
        h = self.scales.h_ring
        margin = max(self.preset["follow_margin"] * outer,
                     self.preset["follow_margin_elements"] * h)
        r_band = self.scales.r_band

        def covers(lo, hi, size):  # a band of elements no longer than size spans lo..hi
            return any(a <= max(lo, 0.0) and b >= min(hi, r_band) and h_w <= size
                       for a, b, h_w in self.window)

        if self.preset["edge_band"]:
            apart = 0.0 < edge < tip - 2.0 * margin  # the contact edge needs a band of its own
            inner = tip if apart or edge == 0.0 else edge
        else:  # one band from the contact edge (or the apex)
            apart, inner = False, edge
        if covers(inner - 0.25 * margin, outer + 0.25 * margin, h) and (
                not apart or covers(edge - 0.25 * margin, edge + 0.25 * margin,
                                    EDGE_COARSENING * h)):
            return None
        lo = inner - margin if inner > 2.0 * margin else 0.0
        bands = [(lo, min(outer + margin, r_band), h)]
        if apart:
            lo = edge - margin if edge > 2.0 * margin else 0.0
            bands.append((lo, edge + margin, EDGE_COARSENING * h))
        return tuple(bands)

    def remeshed(self, window: tuple) -> "AdhesiveModel":
        """The model on a mesh with the fine bands `window` ((r_lo, r_hi, h), ...)."""
        return AdhesiveModel(self.geometry, self.material, self.adhesion, self.scales,
                             self.preset, self.penalty_factor, window)

    def overflow(self, state: AdhesiveState) -> bool:
        a = self.azone.penetration(state.u, state.w)
        near = a > -(self.adhesion.range - self.adhesion.d)
        return bool(np.any(near[self.edge_facets]))

    def evaluate(self, states) -> dict:
        """Contact radius and the field maxima of the states."""
        if self.cond.lu is None:  # released (`release`)
            self.cond = self._condensed()
        zone, disc, mat = self.zone, self.disc, self.material
        k = len(states)
        radius = np.zeros(k)
        gap_tip = np.zeros(k)
        for j, s in enumerate(states):  # one scalar search per state
            pen = zone.node_penetration(s.u, s.w)
            gap_tip[j] = self.adhesion.d - pen[0]
            if np.any(pen >= 0):
                radius[j] = contact_edge(zone.coords[0], -pen, pen >= 0)
        strain_max, mises_max = np.zeros(k), np.zeros(k)
        for lo in range(0, k, 8):
            sub = states[lo:lo + 8]
            f = np.array([-(zone.nodal(self.newton.parts(s.u, s.w)[0])
                            + self.azone.nodal(self.newton.parts(s.u, s.w)[2])) for s in sub]).T
            U = self.cond.full_displacement(f.reshape(zone.ndofs, len(sub)))
            strain = disc.strain(U)
            stress, _ = mat.response(strain)
            strain_max[lo:lo + len(sub)] = equivalent_strain(strain).reshape(-1, len(sub)).max(axis=0)
            mises_max[lo:lo + len(sub)] = von_mises(stress).reshape(-1, len(sub)).max(axis=0)
        return dict(contact_radius=radius, tip_separation=gap_tip,
                    max_equivalent_strain=strain_max, max_von_mises=mises_max)


def adhesive_model(geometry: Profile, material, adhesion: LennardJones, w_max: float,
                   accuracy="standard", penalty_factor: float | None = None,
                   band_factor: float = 1.0) -> AdhesiveModel:
    """The mesh and operators for a path up to the interference w_max."""
    pre = resolve("adhesive", accuracy)
    factor = PENALTY_FACTOR if penalty_factor is None else float(penalty_factor)
    scales = _scales(geometry, material, adhesion, float(w_max), pre, band_factor)
    return AdhesiveModel(geometry, material, adhesion, scales, pre, factor)
