"""The 3-D asperity's half model: its block and graded tetrahedral mesh (report 3.3.1, 9.2).

Body.  A hill z = surface(r) (a `geometry.Profile`) standing on a block, or an
elliptic paraboloid (`geometry.EllipticParaboloid`, principal axes along x and y):
the mesh reads the surface over the plane, ``body_surface_xy(x, y)``.  The sliding
direction x lies in the plane of symmetry y = 0, so only the half y >= 0 of the
block is meshed (its supports: `half_model.HalfModel`).

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
principal axes are x and y).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
from skfem import MeshTet, MeshTet2

from asperity.fe.presets import resolve

#: the 6 edges of a tetrahedron (local vertex pairs)
_TET_EDGES = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]])


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
