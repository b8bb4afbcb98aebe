"""Contact with the rigid flat: penalty law (report 3.3.2), exact option, edge.

The flat is horizontal; it first touches the apex (z = 0) and is moved
down by the interference w.  A surface point at x with displacement u
penetrates it by

    a = z(x) + u_z(x) + w        (a = -s, the report's approach),

and the flat presses it down with the normal traction t_N(a).  Only u_z of
the top-surface nodes enters, so contact acts on the condensed surface dofs.

Penalty (report 3.3.2, Fig. 3.2): the C1 law

    t_N = 0                     a < 0
          H a^2 / (2 eps)       0 <= a < eps
          H (a - eps / 2)       a >= eps

whose linear branch has the slope H =: kappa, the penalty stiffness [Pa/m]
(the report's 1/epsilon of 3.4.1), and eps is the penetration over which
the law is smoothed.  Here ``kappa = c E' / h_f`` on each facet of arc
length h_f, E' = E / (1 - nu^2) the contact modulus,
``c = PENALTY_FACTOR = 1000``: the penetration is about p h_f / (c E'),
i.e. 0.1 % of the element size at a pressure equal to E'.  The penalty's
own error (`asperity.fe.drivers.elastic.penalty_error`) falls as 1 / c; at c = 1000
it is below 2e-4 in force and contact radius on the Hertz problem
(tests/fe/test_penalty_error.py), well below the discretization error.
The smoothing covers the pressures below p_s / 2 with
``p_s = SMOOTHING * E'`` (SMOOTHING = 1e-3), i.e. eps = p_s / kappa,
which shrinks with the penalty so that the C1 law tends to the exact
condition as kappa grows.

Integration over the surface (`ContactZone`): the traction is evaluated
at contact points on each 3-node facet.  Default ``FACET_RULE = "nodal"``:
Simpson's rule, whose points are the facet's nodes, so there is one
contact condition per surface node.  The "gauss" rule (6 Gauss points)
imposes more conditions than a quadratic facet has unknowns; with a stiff
penalty the pressure then oscillates between the points and Newton's
active set creeps a few points per iteration, whatever the penalty
factor, where the nodal rule converges in a few iterations.
Contact area and radius are not counted at the points (the report's
Fig. 8.15 staircase): the edge is interpolated between nodes, from the
gaps (`contact_edge`) or, for an inelastic body, from the pressures and
the gaps (`contact_edge_pressure`).  An explicit rule ``(points,
weights)`` on the facet coordinate [0, 1] may be passed instead of a name
(the adhesion traction of `asperity.fe.contact.adhesion` is integrated with a
composite Gauss rule).

Exact option: the same point-wise condition enforced exactly by an
augmented Lagrangian (Uzawa updates of the multipliers lambda at the
contact points, t_N = max(0, lambda + kappa a)) to a tolerance on the
penetration: the limit of the penalty method as kappa -> infinity on the
same discretization, so the difference measures the penalty's own error.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from asperity.fe.discretization.assembly import TopSurface

#: penalty stiffness kappa = PENALTY_FACTOR * E' / h_facet
PENALTY_FACTOR = 1000.0
#: smoothing pressure H of the C1 penalty, as a fraction of E'
SMOOTHING = 1e-3
#: integration of the contact traction on each 3-node facet: "nodal"
#: (Simpson's rule, the points are the facet's nodes) or "gauss" (Gauss-
#: Legendre with GAUSS_POINTS points).  See `ContactZone`.
FACET_RULE = "nodal"
GAUSS_POINTS = 6
#: how each edge locator places the contact edge (the datasets' ``contact_edge_method``)
EDGE_FROM_GAPS = "gap (3/2 power fit) between last node in contact and first out"
EDGE_FROM_PRESSURES = ("between last node in contact and first out, from the pressures "
                       "inside and the gaps outside (elastic and inelastic edge models, each "
                       "weighted by the other's disagreement)")


def _lagrange_quadratic(xi: np.ndarray):
    """Shape functions (3, n) and derivatives on [0, 1] with nodes 0, 1/2, 1."""
    N = np.vstack((2 * (xi - 0.5) * (xi - 1), -4 * xi * (xi - 1), 2 * xi * (xi - 0.5)))
    dN = np.vstack((4 * xi - 3, -8 * xi + 4, 4 * xi - 1))
    return N, dN


class ContactZone:
    """Contact points on the first `nfacets` top facets (the candidate zone).

    Unknowns are the u_z of the chain nodes 0 .. 2 nfacets (``ndofs``).
    The facets are the isoparametric traces of the P2 elements: position
    and displacement are quadratic in the facet coordinate, ``weights`` are
    the rule's weights times ds (times r for a body of revolution).
    """

    def __init__(self, top: TopSurface, nfacets: int, geometry, rule: str | None = None):
        self.nfacets = nfacets
        self.ndofs = 2 * nfacets + 1
        self.dofs = top.node_dofs[: self.ndofs]
        self.coords = top.coords[:, : self.ndofs]
        axisymmetric = bool(geometry.axisymmetric)
        self.axisymmetric = axisymmetric
        # height of the undeformed profile at the nodes (differs from the
        # meshed top for a shallow profile, whose shape is in the gap only)
        self.z_nodes = self.coords[1] + geometry.gap_offset(self.coords[0])
        fn = top.facet_nodes(nfacets)  # (3, nf)
        self.facet_nodes = fn
        rule = FACET_RULE if rule is None else rule
        if isinstance(rule, str):
            if rule == "nodal":
                xi, wq = np.array([0.0, 0.5, 1.0]), np.array([1.0, 4.0, 1.0]) / 6.0
            elif rule == "gauss":
                xi, wq = np.polynomial.legendre.leggauss(GAUSS_POINTS)
                xi, wq = 0.5 * (xi + 1), 0.5 * wq
            else:
                raise ValueError(f"unknown contact integration rule {rule!r}")
        else:  # an explicit rule (points, weights) on the facet coordinate [0, 1]
            xi, wq = (np.asarray(x, dtype=float) for x in rule)
            if xi.ndim != 1 or xi.shape != wq.shape or np.any((xi < 0) | (xi > 1)):
                raise ValueError("an explicit facet rule is (points in [0, 1], weights) of one shape")
            rule = "explicit"
        self.rule = rule
        N, dN = _lagrange_quadratic(xi)  # (3, ng)
        self.N = N
        X = self.coords[:, fn]  # (2, 3, nf)
        pos = np.einsum("cjf,jg->cfg", X, N)  # (2, nf, ng)
        tang = np.einsum("cjf,jg->cfg", X, dN)
        ds = np.hypot(tang[0], tang[1]) * wq  # (nf, ng)
        self.r = pos[0]
        self.z0 = pos[1] + geometry.gap_offset(pos[0])
        self.weights = ds * np.abs(pos[0]) if axisymmetric else ds
        # facet arc lengths, and the arc length weights of the points (no r)
        self.lengths = (np.hypot(tang[0], tang[1]) * wq).sum(axis=1)
        self.arc = ds
        # 2 pi for a body of revolution; 2 for the two halves of a plane section
        self.force_factor = 2 * np.pi if axisymmetric else 2.0

    def penetration(self, u: np.ndarray, w: float) -> np.ndarray:
        """a at the quadrature points (nf, ng) for surface u_z values u (ndofs)."""
        return self.z0 + np.einsum("jf,jg->fg", u[self.facet_nodes], self.N) + w

    def node_penetration(self, u: np.ndarray, w: float) -> np.ndarray:
        return self.z_nodes + u + w

    def nodal(self, q: np.ndarray) -> np.ndarray:
        """sum_g q N_j W into the nodes, q (nf, ng)."""
        out = np.zeros(self.ndofs)
        vals = np.einsum("fg,jg->jf", q * self.weights, self.N)
        np.add.at(out, self.facet_nodes.ravel(), vals.ravel())
        return out

    def matrix(self, q: np.ndarray) -> np.ndarray:
        """sum_g q N_i N_j W as a dense (ndofs, ndofs) matrix."""
        out = np.zeros((self.ndofs, self.ndofs))
        vals = np.einsum("fg,ig,jg->ijf", q * self.weights, self.N, self.N)
        fn = self.facet_nodes
        ii = np.broadcast_to(fn[:, None, :], vals.shape)
        jj = np.broadcast_to(fn[None, :, :], vals.shape)
        np.add.at(out, (ii.ravel(), jj.ravel()), vals.ravel())
        return out

    def node_traction(self, q: np.ndarray) -> np.ndarray:
        """A traction q (nf, ng) at the chain nodes (ndofs,): its lumped
        projection on the surface trace, sum_g q N_j ds / sum_g N_j ds (with
        the nodal rule, the facets' values at the node averaged by arc length)."""
        num, den = np.zeros(self.ndofs), np.zeros(self.ndofs)
        np.add.at(num, self.facet_nodes.ravel(),
                  np.einsum("fg,jg->jf", q * self.arc, self.N).ravel())
        np.add.at(den, self.facet_nodes.ravel(), np.einsum("fg,jg->jf", self.arc, self.N).ravel())
        return num / den

    def total(self, q: np.ndarray) -> float:
        """Resultant of a traction q (nf, ng): 2 pi int q r ds or 2 int q ds."""
        return float(self.force_factor * np.sum(q * self.weights))


@dataclass(frozen=True)
class C1Penalty:
    """The C1 penalty law of report 3.3.2, per facet stiffness kappa (nf,)."""

    kappa: np.ndarray
    smoothing_pressure: float

    @classmethod
    def for_zone(cls, zone: ContactZone, contact_modulus: float,
                 factor: float = PENALTY_FACTOR, smoothing: float = SMOOTHING):
        kappa = factor * contact_modulus / zone.lengths
        return cls(kappa, smoothing * contact_modulus)

    def traction(self, a: np.ndarray):
        """t_N(a) and dt_N/da, a of shape (nf, ng)."""
        k = self.kappa[:, None]
        eps = self.smoothing_pressure / k
        lin = a >= eps
        quad = (a >= 0) & ~lin
        t = np.where(lin, k * (a - 0.5 * eps), np.where(quad, 0.5 * k * a**2 / eps, 0.0))
        dt = np.where(lin, k, np.where(quad, k * a / eps, 0.0))
        dt = np.broadcast_to(dt, a.shape)
        return t, dt

    def potential(self, a: np.ndarray) -> np.ndarray:
        """Phi(a) with Phi' = t_N (the energy of the line search)."""
        k = self.kappa[:, None]
        eps = self.smoothing_pressure / k
        return np.where(a >= eps, k * (0.5 * a**2 - 0.5 * eps * a + eps**2 / 6),
                        np.where(a >= 0, k * a**3 / (6 * eps), 0.0))


@dataclass(frozen=True)
class AugmentedPenalty:
    """Augmented Lagrangian traction t = max(0, lambda + kappa a) (Uzawa)."""

    kappa: np.ndarray
    multipliers: np.ndarray  # (nf, ng)

    def traction(self, a: np.ndarray):
        k = self.kappa[:, None]
        x = self.multipliers + k * a
        on = x > 0
        return np.where(on, x, 0.0), np.where(on, np.broadcast_to(k, a.shape), 0.0)

    def potential(self, a: np.ndarray) -> np.ndarray:
        """Phi(a) with Phi' = t_N (the energy of the line search)."""
        k = self.kappa[:, None]
        x = np.maximum(self.multipliers + k * a, 0.0)
        return 0.5 * x**2 / k


def _last_in_contact(r: np.ndarray, touching: np.ndarray) -> tuple[int, float | None]:
    """The last node in contact, and the contact radius where no interval to a node out
    remains to locate the edge in (0 if no node touches, its radius if it ends the chain)."""
    idx = np.nonzero(touching)[0]
    if idx.size == 0:
        return -1, 0.0
    i = int(idx[-1])
    return i, (float(r[i]) if i + 1 >= len(r) else None)


def contact_edge(r: np.ndarray, gap: np.ndarray, touching: np.ndarray) -> float:
    """Contact radius from the nodal gaps along the surface chain.

    `r` the node radii (increasing), `gap` the separation from the flat
    (>= 0 off contact), `touching` the nodes in contact.  The edge lies
    between the last node in contact and the first one out.  Near a smooth
    contact edge the gap opens as (r - a)^{3/2} (square-root pressure), so
    a is fitted to the first two nodes out, g1 / g2 = ((r1 - a) / (r2 - a))^{3/2},
    used if it falls in that interval (else the gap is interpolated
    linearly between the two nodes).  Returns 0 if no node touches.
    """
    i, end = _last_in_contact(r, touching)
    if end is not None:
        return end
    r0, r1 = r[i], r[i + 1]
    g0, g1 = min(gap[i], 0.0), max(gap[i + 1], 0.0)
    # linear interpolation of the (signed) gap between the two nodes
    lin = r0 + (r1 - r0) * (-g0) / (g1 - g0) if g1 - g0 > 0 else r0
    if i + 2 < len(r) and gap[i + 2] > g1 > 0:
        rho = (g1 / gap[i + 2]) ** (2.0 / 3.0)
        a = (r1 - rho * r[i + 2]) / (1 - rho)
        if np.isfinite(a) and r0 <= a <= r1:
            return float(a)
    return float(lin)


def _balance(inside: float, outside: float) -> float:
    """Share of the interval in contact where the estimates from inside and
    from outside (as fractions of the interval) balance."""
    if np.isinf(inside):
        return 1.0
    total = inside + outside
    return inside / total if total > 0 else 0.5


def contact_edge_pressure(r: np.ndarray, gap: np.ndarray, pressure: np.ndarray,
                          touching: np.ndarray) -> float:
    """Contact radius of an inelastic body from the nodal pressures and gaps.

    The edge lies between the last node in contact r0 and the first one out
    r1 (spacing L).  With the penalty of report 3.3.2 a node in contact
    penetrates the flat by almost nothing, so the signed gap alone leaves
    the edge on r0 until r1 touches (the report's staircase of Fig. 8.15);
    the pressure says how far the contact has spread past r0.  As the edge
    moves from r0 to r1 the pressure p0 at r0 rises from zero and the gap g1
    at r1 closes to zero.  Each side gives the share of the interval in
    contact, s_in from the pressures (p_ at the node r_ before r0, and p0),
    1 - s_out from the gaps (g1, and g2 at r2), under two models of the
    edge's fields:

    - elastic, the Hertz solution of report 6.1 seen close to its edge:
      p^2 and g^{2/3} linear in r, so s_in = (a_p - r0) / L and
      1 - s_out = (r1 - a_g) / L with a_p and a_g the zeros of the lines
      through (r_, p_^2), (r0, p0^2) and (r1, g1^{2/3}), (r2, g2^{2/3});
    - inelastic, as across an element of a plastic contact: the pressure
      stays that of the node before up to the edge, so that r0 carries the
      share s_in = p0 / p_ of it, and the gap opens linearly,
      1 - s_out = g1 / (g' L) with g' = (g2 - g1) / (r2 - r1).

    Where a model's fields hold, its two estimates agree,
    d = |s_in - s_out| = 0, and each model's edge is where they balance,
    s = s_in / (s_in + 1 - s_out).  The two are weighted by the other's
    disagreement, s = (d_i s_e + d_e s_i) / (d_e + d_i), which is exact for
    either kind of edge, and a = r0 + s L.  Each model's s tends to 0 as r0
    comes into contact (p0 -> 0) and to 1 as r1 does (g1 -> 0), and grows as
    the pressure rises and the gap closes, so the edge moves continuously
    from node to node (the weights shift with the fields: the blend is
    continuous, not monotone by construction).  `r` the node radii
    (increasing), `gap` the separation from the flat, `pressure` the contact
    traction at the nodes, `touching` the nodes in contact.  Returns 0 if no
    node touches, the last node's radius if it is the last of the chain, and
    `contact_edge` (the gap alone) if the apex is the only node in contact.
    """
    i, end = _last_in_contact(r, touching)
    if end is not None:
        return end
    if i == 0:  # the apex alone: no pressure before it
        return contact_edge(r, gap, touching)
    r0, r1 = float(r[i]), float(r[i + 1])
    length = r1 - r0
    p0 = max(float(pressure[i]), 0.0)
    g1 = max(float(gap[i + 1]), 0.0)
    before = float(pressure[i - 1])
    # from inside (infinite: the pressure does not fall towards the edge)
    inelastic_in = p0 / before if before > 0 else np.inf
    if before > p0:
        rho = (p0 / before) ** 2
        elastic_in = rho * (r0 - float(r[i - 1])) / ((1 - rho) * length)
    else:
        elastic_in = np.inf
    # from outside
    if i + 2 < len(r) and gap[i + 2] > g1:
        ratio = g1 / float(gap[i + 2])
        span = (float(r[i + 2]) - r1) / length
        inelastic_out = ratio * span / (1 - ratio)
        rho = ratio ** (2.0 / 3.0)
        elastic_out = rho * span / (1 - rho)
    else:
        inelastic_out = elastic_out = 1.0 if g1 > 0 else 0.0
    s_e = _balance(elastic_in, elastic_out)
    s_i = _balance(inelastic_in, inelastic_out)
    d_e = abs(elastic_in + elastic_out - 1)
    d_i = abs(inelastic_in + inelastic_out - 1)
    if np.isinf(d_e) and np.isinf(d_i) or d_e + d_i == 0:
        share = 0.5 * (s_e + s_i)
    elif np.isinf(d_e):
        share = s_i
    elif np.isinf(d_i):
        share = s_e
    else:
        share = (d_i * s_e + d_e * s_i) / (d_e + d_i)
    return float(r0 + length * share)
