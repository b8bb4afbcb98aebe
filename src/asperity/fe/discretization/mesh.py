"""Meshes of the asperity and its block: graded, curved, adaptively refined.

The computational domain is the hill on a block cut off at the distance
``domain_radius`` from the apex: in the meridian (r, z) plane a quarter disk
r >= 0, z <= 0 sheared vertically by the profile, i.e. the points
(r, z' + f(r)) with r^2 + z'^2 <= L^2.  Its boundaries are

- the top surface z = f(r) (traction free or in contact with the flat),
- the axis (or symmetry plane) r = 0, where u_r = 0,
- the cut-off boundary at distance ~L, where u = 0 (report 3.3.1).

The initial mesh is made of rings of radius rho_i growing geometrically
from the apex (``apex_size``, ratio ``growth``) to L, each cut into
``n_theta`` sectors, so elements are about ``growth - 1`` times their
distance from the apex: fine where the contact starts, coarse far away.
Kinks of the profile are moved onto ring radii so they are vertices.

For a shallow profile (`Profile.shallow`) the meshed top is the flat
tangent plane and the profile only enters the gap to the flat.

Elements are 6-node triangles (P2) with second-order geometry: the
mid-side nodes of the top surface lie on the true curve (projected along
the perpendicular bisector of the chord).  Refinement (skfem's red-green-
blue refinement of the vertex mesh) puts the new top vertices on the curve
as well.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from skfem import MeshTri1, MeshTri2

from asperity.fe.discretization.geometry import Profile


def project_to_profile(geometry: Profile, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Points of the profile on the perpendicular bisectors of chords a-b.

    `a`, `b` have shape (2, n) (columns r, z), both on the profile.  Solved
    by bisection along the bisector, vectorized over the chords.
    """
    mid = 0.5 * (a + b)
    d = b - a
    length = np.hypot(d[0], d[1])
    length = np.where(length > 0, length, 1.0)
    d = d / length
    normal = np.vstack((-d[1], d[0]))
    normal *= np.where(normal[1] < 0, -1.0, 1.0)  # pointing up (out of the body)

    def phi(s):
        r = mid[0] + s * normal[0]
        return geometry.body_surface(r) - (mid[1] + s * normal[1])

    lo = -length.copy()
    hi = length.copy()
    flo, fhi = phi(lo), phi(hi)
    ok = (flo >= 0) & (fhi <= 0)
    for _ in range(60):
        s = 0.5 * (lo + hi)
        fs = phi(s)
        lo = np.where(fs >= 0, s, lo)
        hi = np.where(fs >= 0, hi, s)
    s = 0.5 * (lo + hi)
    out = mid + s * normal
    # fall back to vertical projection where the bisector has no bracket
    vertical = np.vstack((mid[0], geometry.body_surface(mid[0])))
    out = np.where(ok, out, vertical)
    out[0] = np.maximum(out[0], 0.0)
    return out


@dataclass(frozen=True)
class MeshSpec:
    """Parameters of the initial graded mesh (see module docstring)."""

    domain_radius: float
    apex_size: float
    growth: float = 1.3
    n_theta: int = 6


def ring_radii(spec: MeshSpec, kinks=()) -> np.ndarray:
    """Ring radii from the apex to the cut-off, kinks included."""
    if not spec.apex_size < spec.domain_radius:
        raise ValueError("apex_size must be smaller than domain_radius")
    n = int(np.ceil(np.log(spec.domain_radius / spec.apex_size) / np.log(spec.growth)))
    n = max(n, 2)
    radii = spec.apex_size * (spec.domain_radius / spec.apex_size) ** (np.arange(n + 1) / n)
    for kink in kinks:
        if 0 < kink < spec.domain_radius:
            i = int(np.argmin(np.abs(radii - kink)))
            if i == len(radii) - 1:
                i -= 1
            radii[i] = kink
    radii = np.unique(radii)
    return radii


@dataclass
class AsperityMesh:
    """A linear triangle mesh of the asperity plus what makes it curved.

    `vertices` holds the 3-node mesh whose top-surface vertices lie on the
    profile; `top` flags those vertices.  `quadratic()` returns the 6-node
    mesh used for computing.
    """

    geometry: Profile
    vertices: MeshTri1
    top: np.ndarray
    domain_radius: float
    _quadratic: MeshTri2 | None = field(default=None, repr=False)

    # --- construction ----------------------------------------------------
    @classmethod
    def initial(cls, geometry: Profile, spec: MeshSpec) -> "AsperityMesh":
        radii = ring_radii(spec, geometry.kinks)
        nt = spec.n_theta
        theta = np.linspace(0.0, 0.5 * np.pi, nt + 1)
        rho, th = np.meshgrid(radii, theta, indexing="ij")  # (nr, nt+1)
        r = rho * np.cos(th)
        r[:, -1] = 0.0  # exactly on the axis
        zp = -rho * np.sin(th)
        z = zp + geometry.body_surface(r)
        p = np.hstack((np.zeros((2, 1)), np.vstack((r.ravel(), z.ravel()))))
        nr = len(radii)

        def v(i, j):  # vertex index of ring i (0-based), sector line j
            return 1 + i * (nt + 1) + j

        j = np.arange(nt)
        fan = np.vstack((np.zeros(nt, dtype=np.int64), v(0, j), v(0, j + 1)))
        ii, jj = np.meshgrid(np.arange(nr - 1), j, indexing="ij")
        ii, jj = ii.ravel(), jj.ravel()
        a, b, c, d = v(ii, jj), v(ii + 1, jj), v(ii + 1, jj + 1), v(ii, jj + 1)
        t = np.hstack((fan, np.vstack((a, b, c)), np.vstack((a, c, d))))
        top = np.zeros(p.shape[1], dtype=bool)
        top[0] = True
        top[v(np.arange(nr), 0)] = True
        mesh = MeshTri1(p, t)
        return cls(geometry, mesh, top, spec.domain_radius)

    # --- queries ------------------------------------------------------------
    @property
    def scale(self) -> float:
        return self.domain_radius

    def top_facets(self) -> np.ndarray:
        """Top-surface facets (indices into vertices.facets), ordered by r."""
        m = self.vertices
        bf = m.boundary_facets()
        f = m.facets[:, bf]
        bf = bf[self.top[f[0]] & self.top[f[1]]]
        rmin = m.p[0, m.facets[:, bf]].min(axis=0)
        return bf[np.argsort(rmin, kind="stable")]

    def oriented_top_facets(self) -> np.ndarray:
        """(2, n) vertex indices of top facets, inner end first, ordered by r."""
        m = self.vertices
        tf = self.top_facets()
        f = m.facets[:, tf].copy()
        swap = m.p[0, f[0]] > m.p[0, f[1]]
        f[:, swap] = f[::-1, swap]
        return f

    def boundary_facet_sets(self) -> dict[str, np.ndarray]:
        """Boundary facets split into 'top', 'axis' and 'far' (cut-off)."""
        m = self.vertices
        bf = m.boundary_facets()
        f = m.facets[:, bf]
        tol = 1e-12 * self.scale
        axis = (np.abs(m.p[0, f[0]]) <= tol) & (np.abs(m.p[0, f[1]]) <= tol)
        top = self.top[f[0]] & self.top[f[1]] & ~axis
        far = ~axis & ~top
        return {"top": bf[top], "axis": bf[axis], "far": bf[far]}

    def quadratic(self) -> MeshTri2:
        """The 6-node mesh with top mid-side nodes on the profile."""
        if self._quadratic is None:
            m2 = MeshTri2.from_mesh(self.vertices)
            tf = self.top_facets()
            nv = self.vertices.p.shape[1]
            ends = self.vertices.facets[:, tf]
            p = self.vertices.p
            doflocs = m2.doflocs.copy()
            doflocs[:, nv + tf] = project_to_profile(self.geometry, p[:, ends[0]], p[:, ends[1]])
            self._quadratic = replace(m2, doflocs=doflocs)
        return self._quadratic

    @property
    def nelements(self) -> int:
        return self.vertices.t.shape[1]

    # --- refinement ---------------------------------------------------------
    def refined(self, marked: np.ndarray) -> "AsperityMesh":
        """Red-green-blue refinement of the marked elements, top kept on the curve."""
        old = self.vertices
        ends = self.oriented_top_facets()
        nold = old.p.shape[1]
        new = old.refined(np.asarray(marked, dtype=np.int64))
        p = new.p.copy()
        top = np.zeros(p.shape[1], dtype=bool)
        top[:nold] = self.top
        if p.shape[1] > nold and ends.shape[1]:
            mids = 0.5 * (old.p[:, ends[0]] + old.p[:, ends[1]])
            cand = p[:, nold:]
            # exact match of the new vertices with the top chord midpoints
            keys_mid = mids[0] + 1j * mids[1]
            keys_new = cand[0] + 1j * cand[1]
            order = np.argsort(keys_mid)
            pos = np.searchsorted(keys_mid[order], keys_new)
            pos = np.clip(pos, 0, len(order) - 1)
            hit = keys_mid[order][pos] == keys_new
            which = order[pos[hit]]
            idx = nold + np.nonzero(hit)[0]
            top[idx] = True
            p[:, idx] = project_to_profile(
                self.geometry, old.p[:, ends[0, which]], old.p[:, ends[1, which]])
        mesh = MeshTri1(p, new.t)
        return AsperityMesh(self.geometry, mesh, top, self.domain_radius)
