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
own error (`asperity.fe.solve.penalty_error`) falls as 1 / c; at c = 1000
it is a few 1e-5 in force and contact radius on the Hertz problem, well
below the discretization error.  The smoothing covers the pressures below
p_s / 2 with ``p_s = SMOOTHING * E'`` (SMOOTHING = 1e-3), i.e.
eps = p_s / kappa, which shrinks with the penalty so that the C1 law tends
to the exact condition as kappa grows.

Integration over the surface (`ContactZone`): the traction is evaluated
at contact points on each 3-node facet.  Default ``FACET_RULE = "nodal"``:
Simpson's rule, whose points are the facet's nodes, so there is one
contact condition per surface node.  The "gauss" rule (6 Gauss points)
imposes more conditions than a quadratic facet has unknowns; with a stiff
penalty the pressure then oscillates between the points and Newton's
active set creeps a few points per iteration (measured: 20-30 iterations
against 4-8 with the nodal rule, independent of the penalty factor).
Contact area and radius are not counted at the points (the report's
Fig. 8.15 staircase): the edge is interpolated between nodes
(`contact_edge`).  An explicit rule ``(points, weights)`` on the facet
coordinate [0, 1] may be passed instead of a name (the adhesion traction
of `asperity.fe.adhesion` is integrated with a composite Gauss rule).

Exact option: the same point-wise condition enforced exactly by an
augmented Lagrangian (Uzawa updates of the multipliers lambda at the
contact points, t_N = max(0, lambda + kappa a)) to a tolerance on the
penetration: the limit of the penalty method as kappa -> infinity on the
same discretization, so the difference measures the penalty's own error.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .assembly import TopSurface

#: penalty stiffness kappa = PENALTY_FACTOR * E' / h_facet
PENALTY_FACTOR = 1000.0
#: smoothing pressure H of the C1 penalty, as a fraction of E'
SMOOTHING = 1e-3
#: integration of the contact traction on each 3-node facet: "nodal"
#: (Simpson's rule, the points are the facet's nodes) or "gauss" (Gauss-
#: Legendre with GAUSS_POINTS points).  See `ContactZone`.
FACET_RULE = "nodal"
GAUSS_POINTS = 6


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
        # facet arc lengths
        self.lengths = (np.hypot(tang[0], tang[1]) * wq).sum(axis=1)
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
    idx = np.nonzero(touching)[0]
    if idx.size == 0:
        return 0.0
    i = idx[-1]
    if i + 1 >= len(r):
        return float(r[i])
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
