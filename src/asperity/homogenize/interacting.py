"""Interacting asperities: a map's peaks coupled through the elastic half-space.

The statistical route (report 2.5, GW 7.1) sums independent asperities.  Here
the peaks of a map, each with its own force-interference law, are coupled
through the displacement that every contact force causes at every other
summit (Ciavarella, Greenwood and Paggi, Wear 265 (2008) 729, "Inclusion of
interaction in the Greenwood and Williamson contact theory"; Afferrante,
Carbone and Demelio, Wear 278-279 (2012) 28, "Interacting and coalescing
Hertzian asperities"), and contact spots that overlap merge.

Problem solved
--------------
N peaks at (x_i, y_i) on a periodic cell Lx x Ly, heights z_i above the mean
plane of the map, mean curvatures kappa_i = 1/R_i, an elastic body of
contact modulus E* = E / (1 - nu^2) against a rigid flat at height h above
the mean plane.  Asperity i has the interference

    w_i = z_i - h - u_i,    u_i = sum_j K_ij(a_j) F_j,    F_i = law(w_i),      (1)

u_i the normal displacement of the summit (positive into the body) caused by
all contact forces.  The default law is Hertz (report 6.1; Johnson,
*Contact Mechanics*, 1985, 4.2): F = 4/3 E* R^1/2 w^3/2, a = (R w)^1/2 for
w > 0, else 0.  The law's own deformation of asperity i is in F_i(w_i); the
kernel is

    K_ij = g(r_ij, a_j) + c(r_ij)   (i != j),     K_ii = c(0).               (2)

g is the surface displacement per unit force of a Hertz pressure on a circle
of radius a (Johnson eqs. 3.41a, b, with pi p0 a^2 = 3F/2):

    r <= a:  g = 3 (2 a^2 - r^2) / (8 a^3 E*)    (or 3 / (8 a E*): Coalescence)
    r >= a:  g = 3 [(2 a^2 - r^2) asin(a/r) + a (r^2 - a^2)^1/2] / (4 pi a^3 E*)

which tends to the Boussinesq point force 1/(pi E* r) far from the spot
(g pi E* r = 1 + (a/r)^2/10 + ..., a series is used for a/r < 0.1 where the
closed form cancels).  c(r) is the smooth part of the periodic kernel:

Periodic kernel with zero mean: separation and mean plane as the BEM's
---------------------------------------------------------------------
The cell is one period of an infinite interface, as in the boundary-element
reference (``asperity.references.boundary_element``, ``periodic``): the
displacement of a periodic pressure p is u_q = 2 p_q / (E* |q|) at q != 0
and u_0 = 0 (ContactMechanics' PeriodicFFTElasticHalfSpace with
stiffness_q0 = 0).  Its Green's function (unit force at the origin, zero
mean over the cell) is

    G_per(r) = 1/(Lx Ly) sum_{q != 0} 2/(E* |q|) exp(i q.r) = 1/(pi E* r) + c(r),

r the minimum-image distance.  c is smooth and is evaluated by Ewald
splitting, 1/r = erfc(alpha r)/r + erf(alpha r)/r, whose second part has the
2-D transform (2 pi/q) erfc(q / 2 alpha) (Parry, Surf. Sci. 49 (1975) 433):

    pi E* c(r) = -erf(alpha r)/r + sum_{n != 0} erfc(alpha |r + n L|)/|r + n L|
                 + 1/(Lx Ly) sum_{q != 0} (2 pi/q) erfc(q/(2 alpha)) exp(i q.r)
                 - 2 pi^1/2 / (alpha Lx Ly),

the q-sum by numpy's FFT on a grid (the FFT kernel above, band limited by
erfc so that the grid carries it exactly), alpha = 12 / min(Lx, Ly); c is
tabulated once on the quadrant [0, Lx/2] x [0, Ly/2] (it is even in x and y)
and interpolated by bicubic splines at the minimum-image offsets of the
peak pairs.  At r = 0, pi E* L c(0) = 4 zeta(1/2) beta(1/2) = -3.9003 for a
square cell (the Epstein zeta function; Glasser and Zucker, Theor. Chem.
Adv. Persp. 5 (1980) 67).  The self term c(0) F_i enters every contacting
asperity: its force lowers the surface around it and, through the zero mean,
raises it elsewhere.  With this kernel the mean displacement of the surface
is zero for any set of forces: the deformed surface's mean plane stays put,
so h is the flat's height above the mean plane of the undeformed heights AND
the mean gap, exactly as in the boundary-element reference, which the
returned ``mean_gap`` (= h) records.

Solution
--------
Separations are solved from the largest down (a loading path), each from the
last solution.  At each, semismooth Newton on (1) with residual
R_i = w_i - z_i + h + u_i: the contacting set C = {w_i > 0} changes from
iteration to iteration; only its block of the Jacobian,
J_CC = I + dU/dw, dU_ij/dw_j = K_ij dF_j/dw + F_j dg/da (r_ij, a_j) da_j/dw,
is factorized (dense, n_c x n_c), the other interferences follow linearly;
a backtracking line search on |R| keeps the steps from overshooting.
Converged when max |R_i| <= tolerance (max z - h).  Where Newton from the last
solution does not converge (it can cycle between contacting sets at the kinks
of the equations: elongated spots on a map with a lay), the separation is
approached in halved steps from the last one solved, each from the state the
previous half step reached (`_approach`).  The normal stiffness is
that of the linearized system at the solution: dw_C/dh = -J_CC^-1 1,
k = -dp/dh = sum_C dF/dw J_CC^-1 1 / (Lx Ly).

Coalescence (Afferrante et al. 2012)
------------------------------------
Two contact spots whose circles overlap (r_ij < a_i + a_j, minimum image)
are one spot; merging is transitive (connected components).  A merged spot
keeps the sum of its members' areas and forces, so the total area and load
are those of (1); merging sets the number of spots (``contact_count``) and
the share of the load carried by spots of two or more asperities
(``merged_load_fraction``).  The elastic field a spot sends to its
neighbours is the superposition of its members' Hertz fields (2), which is
continuous as spots approach and overlap; one circle sqrt(A/pi) at the
force-weighted centroid is not used because it makes the equations jump when
spots merge.  For a law other than Hertz, g is still the Hertz field of the
spot's force and radius sqrt(A/pi) (its far field, 1/(pi E* r), is exact for
any pressure).

A summit inside another spot (r_ij < a_j, spots already merged) is where
superposition fails: Johnson's 3.41a gives u_i = w_j - r^2/(2 R_j) there (the
surface conforming to the flat), so du_i/dw_j = 1, and two summits inside each
other's spots have a singular pair Jacobian 1 - k_ij k_ji = 0: with the rest of
the interface eq. (1) can lose its solution (a fold: no root near the loading
path, as for two pixel-scale peaks of one hill).  By default
(``near_field="edge"``) the field of spot j is therefore held at its edge
value 3 F_j / (8 a_j E*) (= w_j / 2 for Hertz) for r < a_j (continuous with 3.41b,
du_i/dw_j = 1/2), which only affects merged spots; ``near_field="hertz"``
keeps 3.41a.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import xarray as xr
from scipy.special import erf, erfc

from asperity.homogenize.asperity_laws import hertz_law
from asperity.units import attrs

__all__ = ["hertz_displacement", "PeriodicKernel", "Equilibrium",
           "InteractingAsperities", "merge_spots", "interacting_interface"]

#: the field of a spot at a summit inside it (module docstring, Coalescence)
NEAR_FIELDS = ("edge", "hertz")
#: below this a/r the Hertz field is the series of pi E* r g in (a/r)^2
SERIES_LIMIT = 0.1


def _series_coefficients(terms: int = 10) -> np.ndarray:
    """Coefficients of pi E* r g(r, a) = sum_k c_k (a/r)^(2k) outside the spot, from the
    series of asin x and (1 - x^2)^1/2 (exact rationals; a loop over terms)."""
    s = [Fraction(math.comb(2 * n, n), 4**n * (2 * n + 1)) for n in range(terms + 2)]
    t = []
    for n in range(terms + 2):
        p = Fraction(1)
        for k in range(n):
            p *= (Fraction(1, 2) - k) / (k + 1)
        t.append(p * (-1) ** n)
    # b(x) = (2x^2 - 1) asin x + x (1 - x^2)^1/2 = sum b_n x^(2n+1);  phi = 3/4 b / x^3
    b = [(2 * s[n - 1] if n else 0) - s[n] + t[n] for n in range(terms + 2)]
    return np.array([float(Fraction(3, 4) * b[n]) for n in range(1, terms + 1)])


_PHI = _series_coefficients()
_DPHI = np.array([2 * k * c for k, c in enumerate(_PHI)])[1:]  # d phi/dx = x sum 2k c_k x^(2k-2)


def _phi(x: np.ndarray, near_field: str = "edge") -> tuple[np.ndarray, np.ndarray]:
    """phi(x) = pi E* r g(r, a) and d phi/dx, x = a/r >= 0 (module docstring, eq. 2);
    inside the spot (x > 1) Johnson 3.41a (``near_field="hertz"``) or the edge value."""
    shape = np.shape(x)
    x = np.atleast_1d(np.asarray(x, dtype=float))
    x2 = x * x
    phi = np.polynomial.polynomial.polyval(x2, _PHI)
    dphi = x * np.polynomial.polynomial.polyval(x2, _DPHI)
    big = x >= SERIES_LIMIT
    if np.any(big):
        xb = x[big]
        out = np.minimum(xb, 1.0)
        asin = np.arcsin(out)
        b = (2 * out * out - 1) * asin + out * np.sqrt(1 - out * out)
        p_out = 0.75 * b / out**3
        d_out = 0.75 * (4 * asin / out**2 - 3 * b / out**4)
        inn = np.maximum(xb, 1.0)
        if near_field == "hertz":  # inside the spot: Johnson 3.41a
            p_in = 3 * np.pi / 8 * (2 / inn - 1 / inn**3)
            d_in = 3 * np.pi / 8 * (-2 / inn**2 + 3 / inn**4)
        else:  # held at the edge value g(a, a) = 3 / (8 a E*)
            p_in = 3 * np.pi / 8 / inn
            d_in = -3 * np.pi / 8 / inn**2
        inside = xb > 1.0
        phi[big] = np.where(inside, p_in, p_out)
        dphi[big] = np.where(inside, d_in, d_out)
    return phi.reshape(shape), dphi.reshape(shape)


def hertz_displacement(r, radius, contact_modulus: float):
    """Surface displacement per unit force at distance r from the centre of a Hertz
    pressure of radius a (Johnson eqs. 3.41a, b), and its derivative in a.

    Returns (g, dg/da) in m/N and 1/N; r > 0 (r = 0 allowed when a > 0).
    """
    r = np.asarray(r, dtype=float)
    a = np.asarray(radius, dtype=float)
    r, a = np.broadcast_arrays(r, a)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(r > 0, a / r, np.inf)
        phi, dphi = _phi(np.where(np.isfinite(x), x, 1e300), "hertz")
        g = np.where(r > 0, phi / (np.pi * contact_modulus * r), 0.75 / (a * contact_modulus))
        ga = np.where(r > 0, dphi / (np.pi * contact_modulus * r * r), -0.75 / (a * a * contact_modulus))
    return g, ga


class PeriodicKernel:
    """Zero-mean periodic Green's function of the half-space, G_per = 1/(pi E* r) + c(r)
    (module docstring), c by Ewald splitting tabulated on ``points`` intervals per period
    and interpolated by bicubic splines."""

    def __init__(self, period, contact_modulus: float, points: int = 256):
        from scipy.interpolate import RectBivariateSpline

        self.period = _period(period)
        self.contact_modulus = float(contact_modulus)
        lx, ly = self.period
        lmin = min(lx, ly)
        alpha = 12.0 / lmin  # erfc(alpha lmin / 2) = 2e-17: the nearest images suffice
        nx = min(4096, 2 * math.ceil(points * lx / lmin / 2))
        ny = min(4096, 2 * math.ceil(points * ly / lmin / 2))
        kx = 2 * np.pi * np.fft.fftfreq(nx, lx / nx)
        ky = 2 * np.pi * np.fft.fftfreq(ny, ly / ny)
        q = np.hypot(ky[:, None], kx[None, :])
        hat = np.zeros_like(q)
        hat[q > 0] = 2 * np.pi / q[q > 0] * erfc(q[q > 0] / (2 * alpha))
        recip = np.fft.ifft2(hat).real * (nx * ny) / (lx * ly)
        xs = np.arange(nx // 2 + 1) * lx / nx
        ys = np.arange(ny // 2 + 1) * ly / ny
        X, Y = np.meshgrid(xs, ys)
        r = np.hypot(X, Y)
        with np.errstate(divide="ignore", invalid="ignore"):
            total = np.where(r > 0, -erf(alpha * r) / r, -2 * alpha / np.sqrt(np.pi))
        for mx in range(-2, 3):  # images, not peaks
            for my in range(-2, 3):
                if mx or my:
                    d = np.hypot(X + mx * lx, Y + my * ly)
                    total += erfc(alpha * d) / d
        total += recip[: ny // 2 + 1, : nx // 2 + 1] - 2 * np.sqrt(np.pi) / (alpha * lx * ly)
        self._spline = RectBivariateSpline(xs, ys, total.T / (np.pi * self.contact_modulus), kx=3, ky=3)

    def minimum_image(self, dx, dy):
        """Offsets folded into [-L/2, L/2]."""
        lx, ly = self.period
        dx = np.asarray(dx, dtype=float)
        dy = np.asarray(dy, dtype=float)
        return dx - lx * np.round(dx / lx), dy - ly * np.round(dy / ly)

    def correction(self, dx, dy):
        """c at the offsets (dx, dy) (m/N): G_per minus 1/(pi E* r) at the minimum image."""
        mx, my = self.minimum_image(dx, dy)
        return self._spline.ev(np.abs(mx), np.abs(my))

    def __call__(self, dx, dy):
        """G_per at the offsets (dx, dy) (m/N); infinite at r = 0."""
        mx, my = self.minimum_image(dx, dy)
        with np.errstate(divide="ignore"):
            return 1.0 / (np.pi * self.contact_modulus * np.hypot(mx, my)) + self.correction(dx, dy)


def _period(period) -> tuple[float, float]:
    p = np.broadcast_to(np.asarray(period, dtype=float), (2,))
    if not np.all(np.isfinite(p) & (p > 0)):
        raise ValueError(f"period must be positive and finite; got {period!r}")
    return float(p[0]), float(p[1])


def merge_spots(x, y, radius, period) -> np.ndarray:
    """Spot label of each contact (x, y, radius a > 0) on the periodic cell: contacts
    whose circles overlap (distance < a_i + a_j, minimum image) share a spot, transitively
    (connected components; Afferrante, Carbone and Demelio 2012).  Labels 0 .. n_spots-1."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    lx, ly = _period(period)
    x, y, a = (np.asarray(v, dtype=float) for v in (x, y, radius))
    n = x.size
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    dx = x[:, None] - x[None, :]
    dy = y[:, None] - y[None, :]
    d = np.hypot(dx - lx * np.round(dx / lx), dy - ly * np.round(dy / ly))
    i, j = np.nonzero(np.triu(d < a[:, None] + a[None, :], k=1))
    graph = coo_matrix((np.ones(i.size), (i, j)), shape=(n, n))
    return connected_components(graph, directed=False)[1].astype(np.int64)


@dataclass
class Equilibrium:
    """Solution of eq. (1) at one separation."""

    separation: float
    interference: np.ndarray  # w_i (m)
    force: np.ndarray  # F_i (N)
    area: np.ndarray  # A_i (m^2)
    stiffness: float  # -dp/dh (Pa/m)
    iterations: int
    residual: float  # max |R_i| (m)


class InteractingAsperities:
    """The peaks of a map and their coupling, eqs. (1)-(2) of the module docstring.

    The pairwise minimum-image distances and kernel corrections c(r_ij) (N x N) are
    built once; :meth:`solve` finds the equilibrium at one separation.

    Parameters
    ----------
    x, y : array_like
        Peak positions (m), any origin (folded into the cell).
    heights : array_like
        z_i above the mean plane of the map (m).
    curvatures : array_like
        kappa_i = 1/R_i > 0 (1/m).
    contact_modulus : float
        E* = E / (1 - nu^2) (Pa).
    period : float or (float, float)
        Cell size (Lx, Ly) (m).
    law : callable, optional
        ``law(w, index) -> (force, area, dforce_dw[, darea_dw])`` of the asperities
        `index` (numbers into the arrays given) at interferences `w`
        (arrays; zero at w <= 0); Hertz (`asperity.homogenize.asperity_laws.hertz_law`) by default.  Without
        ``darea_dw`` it is taken from the law by a central difference (step 1e-6 w),
        which only enters the Jacobian through the spots' near field.
    kernel_points : int
        Intervals per period of the table of c(r).
    near_field : {"edge", "hertz"}
        The field of spot j at a summit inside it (r < a_j): held at its edge value
        (default) or Johnson's 3.41a (module docstring, Coalescence).
    """

    def __init__(self, x, y, heights, curvatures, contact_modulus: float, period, *, law=None,
                 kernel_points: int = 256, near_field: str = "edge"):
        if near_field not in NEAR_FIELDS:
            raise ValueError(f"near_field must be one of {NEAR_FIELDS}; got {near_field!r}")
        self.near_field = near_field
        self.x, self.y, self.z, self.kappa = (np.asarray(v, dtype=float).ravel()
                                              for v in (x, y, heights, curvatures))
        n = self.x.size
        if not (self.y.size == self.z.size == self.kappa.size == n):
            raise ValueError("x, y, heights and curvatures must have the same length")
        for name, v in (("x", self.x), ("y", self.y), ("heights", self.z), ("curvatures", self.kappa)):
            if not np.all(np.isfinite(v)):
                raise ValueError(f"{name} must be finite")
        if not np.all(self.kappa > 0):
            raise ValueError("curvatures of the peaks must be positive (kappa = 1/R > 0)")
        if not contact_modulus > 0:
            raise ValueError(f"contact modulus must be positive; got {contact_modulus!r}")
        self.contact_modulus = float(contact_modulus)
        self.period = _period(period)
        self.area = self.period[0] * self.period[1]
        self.law = hertz_law(contact_modulus, self.kappa) if law is None else law
        self.kernel = PeriodicKernel(self.period, contact_modulus, kernel_points)
        dx, dy = self.kernel.minimum_image(self.x[:, None] - self.x[None, :],
                                           self.y[:, None] - self.y[None, :])
        i, j = np.triu_indices(n)  # c is even: one triangle, c(0) on the diagonal
        self._correction = np.empty((n, n))
        self._correction[i, j] = self.kernel.correction(dx[i, j], dy[i, j])
        self._correction[j, i] = self._correction[i, j]
        del i, j
        r = np.hypot(dx, dy)
        del dx, dy
        if np.any(r[~np.eye(n, dtype=bool)] == 0):
            raise ValueError("two peaks at the same position")
        np.fill_diagonal(r, np.inf)  # no Hertz field of an asperity on itself
        self._inv_r = 1.0 / r

    def _law(self, w, index):
        out = self.law(w, index)
        force, area, dforce = (np.asarray(v, dtype=float) for v in out[:3])
        if len(out) > 3:
            darea = np.asarray(out[3], dtype=float)
        else:
            step = 1e-6 * np.abs(w)
            darea = (np.asarray(self.law(w + step, index)[1]) - np.asarray(self.law(w - step, index)[1])) \
                / (2 * step)
        return force, area, dforce, darea

    def evaluate(self, w, separation: float, jacobian: bool = True):
        """Residual R_i = w_i - z_i + h + u_i of eq. (1) at the interferences w, and, with
        `jacobian`, the contacting set C, the columns dU/dw_C (N x n_c) and the law's
        outputs on C."""
        w = np.asarray(w, dtype=float)
        c = np.flatnonzero(w > 0)
        force, area, dforce, darea = self._law(w[c], c)
        radius = np.sqrt(area / np.pi)
        inv_r = self._inv_r[:, c]
        phi, dphi = _phi(radius[None, :] * inv_r, self.near_field)
        kernel = phi * inv_r / (np.pi * self.contact_modulus) + self._correction[:, c]
        residual = w - self.z + separation + kernel @ force
        if not jacobian:
            return residual
        with np.errstate(divide="ignore", invalid="ignore"):
            dradius = np.where(radius > 0, darea / (2 * np.pi * radius), 0.0)
        columns = kernel * dforce[None, :] + (dphi * inv_r * inv_r / (np.pi * self.contact_modulus)) \
            * (force * dradius)[None, :]
        return residual, c, columns, (force, area, dforce)

    def solve(self, separation: float, start=None, *, tolerance: float = 1e-10,
              max_iterations: int = 100, accept: float | None = None) -> Equilibrium:
        """Equilibrium at `separation` (m) by semismooth Newton from `start` (interferences;
        default the rigid w = z - h); converged when max |R| <= tolerance (max z - h).

        The equations are semismooth (the edge of each spot's field, where a neighbour's
        summit enters it), and Newton with its line search can stall above `tolerance`.
        With `accept`, a state whose max |R| <= accept (max z - h) is then returned (its
        ``residual`` says how far it is); without it, or above it, RuntimeError."""
        h = float(separation)
        scale = float(self.z.max()) - h
        w = self.z - h if start is None else np.array(start, dtype=float)
        if scale <= 0:  # no peak reaches the flat
            w = self.z - h
            zero = np.zeros_like(w)
            return Equilibrium(h, w, zero, zero.copy(), 0.0, 0, 0.0)
        limit = tolerance * scale
        residual, c, columns, law = self.evaluate(w, h)
        norm = np.linalg.norm(residual)
        stalled = False
        for iteration in range(max_iterations + 1):
            if np.abs(residual).max() <= limit:
                return self._equilibrium(h, w, residual, c, columns, law, iteration)
            if iteration == max_iterations or stalled:
                break
            step_c = np.linalg.solve(columns[c] + np.eye(c.size), -residual[c]) if c.size else np.zeros(0)
            step = -residual - columns @ step_c
            step[c] = step_c
            t = 1.0
            for _ in range(30):  # backtracking on |R|
                trial = self.evaluate(w + t * step, h)
                trial_norm = np.linalg.norm(trial[0])
                if trial_norm <= (1 - 1e-4 * t) * norm:
                    break
                t *= 0.5
            w = w + t * step
            residual, c, columns, law = trial
            stalled = t < 1e-6 or iteration == max_iterations - 1
            norm = trial_norm
        if accept is not None and np.abs(residual).max() <= accept * scale:  # stalled, close enough
            return self._equilibrium(h, w, residual, c, columns, law, iteration)
        raise RuntimeError(
            f"interacting asperities: Newton did not converge at separation {h:.6g} m after "
            f"{max_iterations} iterations (max residual {np.abs(residual).max():.3g} m, "
            f"target {limit:.3g} m)")

    def _equilibrium(self, h, w, residual, c, columns, law, iteration) -> Equilibrium:
        """The state at interferences `w` (with `evaluate`'s outputs there): forces, areas,
        and the stiffness of the linearized system, sum_C dF/dw (I + dU/dw)_CC^-1 1 / A0."""
        jcc = columns[c] + np.eye(c.size)
        stiffness = float(law[2] @ np.linalg.solve(jcc, np.ones(c.size))) / self.area
        force = np.zeros_like(w)
        area = np.zeros_like(w)
        force[c], area[c] = law[0], law[1]
        return Equilibrium(h, w, force, area, stiffness, iteration, float(np.abs(residual).max()))

    def spots(self, state: Equilibrium) -> np.ndarray:
        """Spot label of each contacting asperity of `state` (:func:`merge_spots`)."""
        c = np.flatnonzero(state.force > 0)
        return merge_spots(self.x[c], self.y[c], np.sqrt(state.area[c] / np.pi), self.period)


#: halvings of a separation step whose Newton does not converge (`_approach`)
APPROACH_HALVINGS = 6


def _approach(model: "InteractingAsperities", h_from: float, w_from, h_to: float, solve: dict,
              halvings: int = APPROACH_HALVINGS) -> "Equilibrium":
    """The equilibrium at separation `h_to` from the one at `h_from` (interferences `w_from`,
    None: the rigid start).  Newton from there first; where it does not converge (it can
    cycle between contact sets at the kinks of the semismooth equations), the step in
    separation is halved and the flat approaches in two half steps, each from the state the
    last one reached, at most `halvings` times deep; the iterations of every half step are
    counted in the result's."""
    try:
        return model.solve(h_to, w_from, **solve)
    except RuntimeError:
        if halvings == 0:
            raise
    mid = 0.5 * (h_from + h_to)
    half = _approach(model, h_from, w_from, mid, solve, halvings - 1)
    state = _approach(model, mid, half.interference, h_to, solve, halvings - 1)
    state.iterations += half.iterations
    return state


def interacting_interface(x, y, heights, curvatures, separations, contact_modulus: float, period, *,
                          law=None, tolerance: float = 1e-10, max_iterations: int = 100,
                          near_field: str = "edge", accept: float | None = None) -> xr.Dataset:
    """Interface response of interacting, coalescing asperities (module docstring).

    Parameters
    ----------
    x, y, heights, curvatures : array_like
        The peaks: position (m), height above the map's mean plane (m), mean curvature
        1/R (1/m, positive).
    separations : array_like
        Heights h of the rigid flat above the mean plane (m).
    contact_modulus : float
        E* = E / (1 - nu^2) (Pa).
    period : float or (float, float)
        The periodic cell (Lx, Ly) = (nx dx, ny dy) of the map (m).
    law : callable, optional
        ``law(w, index) -> (force, area, dforce_dw[, darea_dw])`` of the asperities
        `index` at interferences `w`; Hertz at their curvatures if None.
    tolerance, max_iterations, accept
        Newton stops at max |R_i| <= tolerance (max z - h), or where it stalls at
        max |R_i| <= accept (max z - h) (:meth:`InteractingAsperities.solve`); the
        ``residual`` of each separation is returned.
    near_field : {"edge", "hertz"}
        The field of a spot at a summit inside it (:class:`InteractingAsperities`).

    Returns
    -------
    xarray.Dataset
        On dim ``separation`` (increasing): nominal_pressure, contact_area_ratio,
        contact_count (spots after merging), normal_stiffness (-dp/dh of the linearized
        system), mean_gap (= separation: zero-mean periodic kernel), merged_load_fraction,
        asperities_in_contact, iterations; attrs method, peaks, contact_modulus, period,
        cpu_time.
    """
    h = np.asarray(separations, dtype=float)
    if h.ndim != 1 or h.size == 0 or not np.all(np.isfinite(h)):
        raise ValueError("separations must be a non-empty 1-D array of finite numbers")
    start_time = time.process_time()
    model = InteractingAsperities(x, y, heights, curvatures, contact_modulus, period, law=law,
                                  near_field=near_field)
    names = ("nominal_pressure", "contact_area_ratio", "contact_count", "normal_stiffness",
             "mean_gap", "merged_load_fraction", "asperities_in_contact", "iterations", "residual")
    out = {name: np.full(h.size, np.nan) for name in names}
    w, reached = None, float(np.max(model.z))  # the flat touching the highest summit
    for k in np.argsort(h)[::-1]:  # largest separation first: the loading path
        state = _approach(model, reached, w, h[k], dict(
            tolerance=tolerance, max_iterations=max_iterations, accept=accept))
        w, reached = state.interference, h[k]
        total = state.force.sum()
        labels = model.spots(state)
        members = np.bincount(labels) if labels.size else np.zeros(0, dtype=np.int64)
        merged = members[labels] >= 2
        out["nominal_pressure"][k] = total / model.area
        out["contact_area_ratio"][k] = state.area.sum() / model.area
        out["contact_count"][k] = members.size / model.area
        out["normal_stiffness"][k] = state.stiffness
        out["mean_gap"][k] = h[k]
        out["merged_load_fraction"][k] = state.force[state.force > 0][merged].sum() / total if total > 0 else 0.0
        out["asperities_in_contact"][k] = labels.size / model.area
        out["iterations"][k] = state.iterations
        out["residual"][k] = state.residual
    meta = {
        "nominal_pressure": ("Pa", "nominal pressure: total force of the asperities over the cell area"),
        "contact_area_ratio": ("1", "real contact area ratio A/A0: sum of the asperities' areas over the cell"),
        "contact_count": ("1/m^2", "contact spots per unit area, overlapping asperity contacts merged"),
        "normal_stiffness": ("Pa/m", "normal stiffness -dp/dh of the linearized interacting system"),
        "mean_gap": ("m", "mean gap: equal to the separation (periodic kernel of zero mean)"),
        "merged_load_fraction": ("1", "share of the load carried by spots of two or more asperities"),
        "asperities_in_contact": ("1/m^2", "asperities in contact per unit area, before merging"),
        "iterations": ("1", "Newton iterations of the solve"),
        "residual": ("m", "largest residual of the interference equations at the solution"),
    }
    ds = xr.Dataset(
        {name: ("separation", out[name], attrs(*meta[name])) for name in names},
        coords={"separation": ("separation", h, attrs(
            "m", "height of the rigid flat above the mean plane of the surface"))},
    ).sortby("separation")
    ds.attrs.update({
        "method": "interacting asperities (Ciavarella et al. 2008; Afferrante, Carbone and Demelio "
                  "2012): peak force laws coupled by the zero-mean periodic half-space kernel with "
                  "Hertz near fields, semismooth Newton, overlapping spots merged",
        "peaks": int(model.z.size),
        "contact_modulus": float(contact_modulus),
        "period": np.array(model.period),
        "near_field": near_field,
        "cpu_time": time.process_time() - start_time,
    })
    return ds
