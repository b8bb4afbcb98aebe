"""Summits of a Gaussian anisotropic surface: the joint density of peak height, principal
curvatures and orientation (report 2.4.2, 2.5.2).

The report leaves this density out ("no such formula is presently available in a
closed form", 2.4.2).  It follows from the Gaussian field itself, as Longuet-Higgins
(1957) and Nayak (1971, 1973) derived the summit statistics and Bush, Gibson and
Keogh (1979, "Strongly anisotropic rough surfaces") applied them to contact.

A summit is a point where the gradient vanishes and the Hessian is negative definite.
With the curvature tensor K = -H (positive definite at a summit), the expected number
of summits per unit area with height in dz and curvature tensor in dK is the Kac-Rice
formula

    n(z, K) dz dK = p_grad(0) phi_4(z, K) det K dz dKxx dKxy dKyy,

because at one point of a stationary Gaussian field the gradient is independent of the
height and of the second derivatives.  p_grad(0) = 1 / (2 pi sqrt(m20 m02 - m11^2)) is
the gradient's density at zero, and phi_4 the normal density of (z, Kxx, Kxy, Kyy) with
covariance, from the spectral moments m_pq = int kx^p ky^q Phi(k) dk (report 2.3.2, eq.
2.2),

    var z = m00;  cov(z, Kxx) = m20,  cov(z, Kxy) = m11,  cov(z, Kyy) = m02;
    var Kxx = m40,  cov(Kxx, Kxy) = m31,  cov(Kxx, Kyy) = var Kxy = m22,
    cov(Kxy, Kyy) = m13,  var Kyy = m04.

In principal curvatures kappa_1 >= kappa_2 > 0 and the orientation alpha in [0, pi) of
the axis of kappa_1 (from x), K = R(alpha) diag(kappa_1, kappa_2) R(alpha)^T and
dKxx dKxy dKyy = (kappa_1 - kappa_2) dkappa_1 dkappa_2 dalpha, so that

    n(z, kappa_1, kappa_2, alpha) = p_grad(0) phi_4(z, K) kappa_1 kappa_2 (kappa_1 - kappa_2),

the four-fold density of eq. (2.8) times the summit density D = int n (summits per
unit area).  `AnisotropicDensity.pdf` is n / D, which integrates to one.  With
isotropic moments (m20 = m02 = m2, m40 = m04 = 3 m22 = m4, m11 = m31 = m13 = 0) its
marginal over height and mean curvature (kappa_1 + kappa_2) / 2 is Nayak's density of
2.4.1 (`asperity.peaks.isotropic.JointDensity`) and D = m4 / (6 pi sqrt(3) m2).

Quadrature (`AnisotropicDensity.nodes`): composite Gauss-Legendre in height, in
r = sqrt(kappa_1 / kappa_max) and in s = sqrt(t), t = kappa_2 / kappa_1 in (0, 1]
(dkappa_2 = kappa_1 dt).  The square roots gather the nodes where a strongly
anisotropic density varies fastest: at small kappa_1, on the scale of the smaller
curvature, and at elongated summits (small t).  Over alpha it is the trapezoid rule,
which converges geometrically for a smooth function of period pi.  The support is
[-HEIGHT_BELOW sigma, HEIGHT_ABOVE sigma] in height and [0, CURVATURE_SPAN s_K] in
kappa_1, s_K the standard deviation of the trace of K.  The density's integral over it
is one to 1e-8 for isotropic moments; on a field whose curvature variances differ
thirtyfold the default cells agree with a quadrature half again as fine to 1e-6 in the
summit density and 1e-5 in the contact's pressure and area down to a thousandth of the
summits touching (the tests).
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

__all__ = ["MOMENTS", "AnisotropicDensity", "curvature_tensor", "principal_curvatures"]

#: the spectral moments the density takes (report 2.3.2)
MOMENTS = ("m00", "m20", "m11", "m02", "m40", "m31", "m22", "m13", "m04")
#: the height support below and above the mean plane, in standard deviations of height
HEIGHT_BELOW, HEIGHT_ABOVE = 6.0, 7.0
#: the curvature support, in standard deviations of the trace of the curvature tensor
CURVATURE_SPAN = 9.0


def curvature_tensor(kappa_1, kappa_2, alpha) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(Kxx, Kxy, Kyy) of principal curvatures kappa_1, kappa_2 whose first axis makes
    the angle alpha with x; broadcasts."""
    k1, k2, a = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (kappa_1, kappa_2, alpha)))
    mean, half = 0.5 * (k1 + k2), 0.5 * (k1 - k2)
    c, s = np.cos(2.0 * a), np.sin(2.0 * a)
    return mean + half * c, half * s, mean - half * c


def principal_curvatures(kxx, kxy, kyy) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(kappa_1 >= kappa_2, alpha in [0, pi)) of a curvature tensor; the inverse of
    `curvature_tensor`."""
    kxx, kxy, kyy = (np.asarray(v, dtype=float) for v in (kxx, kxy, kyy))
    mean, half = 0.5 * (kxx + kyy), np.hypot(0.5 * (kxx - kyy), kxy)
    alpha = np.mod(0.5 * np.arctan2(2.0 * kxy, kxx - kyy), np.pi)
    return mean + half, mean - half, alpha


def _gauss_cells(lo: float, hi: float, cells: int, points: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of `cells` equal cells of `points`-point Gauss-Legendre on [lo, hi]."""
    x, w = np.polynomial.legendre.leggauss(points)
    edges = np.linspace(lo, hi, cells + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()


class AnisotropicDensity:
    """The joint density of summit height, principal curvatures and orientation of a
    Gaussian anisotropic surface from its nine spectral moments (module docstring).

    Parameters
    ----------
    moments : mapping
        m00 ... m04 (`MOMENTS`) in SI: m00 in m^2, m20, m11, m02 dimensionless,
        m40 ... m04 in 1/m^2 (as surface.nc carries them).
    mean_height : float
        The height of the mean plane, the origin of z.
    cells : (int, int, int)
        Gauss cells (4 points each) in height, kappa_1 and the ratio kappa_2/kappa_1.
    orientations : int
        Trapezoid points over alpha in [0, pi).

    Raises
    ------
    ValueError
        If a moment is missing or not finite, or the moments are not those of a
        Gaussian field (a covariance not positive definite).
    """

    def __init__(self, moments: Mapping[str, float], mean_height: float = 0.0,
                 cells: tuple[int, int, int] = (12, 16, 8), orientations: int = 32):
        missing = [k for k in MOMENTS if k not in moments]
        if missing:
            raise ValueError(f"the anisotropic summit density needs the spectral moments "
                             f"{', '.join(missing)} (surface.nc of a map or of directional profiles)")
        m = {k: float(moments[k]) for k in MOMENTS}
        bad = [k for k, v in m.items() if not math.isfinite(v)]
        if bad:
            raise ValueError(f"spectral moments {', '.join(bad)} are not finite")
        self.moments = m
        self.mean_height = float(mean_height)
        self.slope_covariance = np.array([[m["m20"], m["m11"]], [m["m11"], m["m02"]]])
        self.covariance = np.array([[m["m00"], m["m20"], m["m11"], m["m02"]],
                                    [m["m20"], m["m40"], m["m31"], m["m22"]],
                                    [m["m11"], m["m31"], m["m22"], m["m13"]],
                                    [m["m02"], m["m22"], m["m13"], m["m04"]]])
        for name, c in (("slopes (m20, m11, m02)", self.slope_covariance),
                        ("height and curvatures (m00 ... m04)", self.covariance)):
            if not np.all(np.linalg.eigvalsh(c) > 0):
                raise ValueError(f"the spectral moments of the {name} are not those of a Gaussian "
                                 "field: their covariance is not positive definite")
        self._precision = np.linalg.inv(self.covariance)
        self._log_scale = (-math.log(4.0 * math.pi ** 2 * math.sqrt(np.linalg.det(self.covariance)))
                           - math.log(2.0 * math.pi * math.sqrt(np.linalg.det(self.slope_covariance))))
        self.cells = tuple(int(c) for c in cells)
        self.orientations = int(orientations)
        self.sigma = math.sqrt(m["m00"])
        self.trace_deviation = math.sqrt(m["m40"] + 2.0 * m["m22"] + m["m04"])
        _, _, _, weights = self.nodes()
        #: summits per unit area [1/m^2]
        self.summit_density = float(weights.sum())

    # ---------------------------------------------------------------- the density
    def number_density(self, z, kappa_1, kappa_2, alpha) -> np.ndarray:
        """n(z, kappa_1, kappa_2, alpha): summits per unit area, height, curvature^2 and
        radian [1/(m^2 m (1/m)^2 rad)]; zero unless kappa_1 >= kappa_2 > 0.  Broadcasts."""
        kxx, kxy, kyy = curvature_tensor(kappa_1, kappa_2, alpha)
        k1, k2 = np.broadcast_arrays(np.asarray(kappa_1, dtype=float), np.asarray(kappa_2, dtype=float))
        z = np.asarray(z, dtype=float) - self.mean_height
        v = np.stack(np.broadcast_arrays(z, kxx, kxy, kyy), axis=-1)
        q = np.einsum("...i,ij,...j->...", v, self._precision, v)
        factor = np.where((k2 > 0) & (k1 >= k2), k1 * k2 * (k1 - k2), 0.0)
        return np.exp(self._log_scale - 0.5 * q) * factor

    def pdf(self, z, kappa_1, kappa_2, alpha) -> np.ndarray:
        """f(z, kappa_1, kappa_2, alpha) = n / D, the density of eq. (2.8), which
        integrates to one."""
        return self.number_density(z, kappa_1, kappa_2, alpha) / self.summit_density

    def _alphas(self) -> tuple[np.ndarray, float]:
        return np.arange(self.orientations) * (math.pi / self.orientations), math.pi / self.orientations

    def pdf_shape(self, z, kappa_1, kappa_2) -> np.ndarray:
        """f(z, kappa_1, kappa_2): the density over orientation integrated out (what the
        normal response of a summit against a flat depends on; 2.5.2)."""
        alpha, da = self._alphas()
        z, k1, k2 = np.broadcast_arrays(*(np.asarray(v, dtype=float)[..., None] for v in (z, kappa_1, kappa_2)))
        return self.pdf(z, k1, k2, alpha).sum(axis=-1) * da

    def support(self) -> tuple[float, float, float]:
        """(z_min, z_max, kappa_max): the box of the quadrature (module docstring)."""
        return (self.mean_height - HEIGHT_BELOW * self.sigma, self.mean_height + HEIGHT_ABOVE * self.sigma,
                CURVATURE_SPAN * self.trace_deviation)

    # ---------------------------------------------------------------- quadrature
    def _grid(self, above: float | None = None):
        """Gauss nodes and weights in height (over [above, z_max] if given), kappa_1 and
        t, with the Jacobian kappa_1 of t in the kappa_1 weights."""
        z_lo, z_hi, k_max = self.support()
        nz, nk, nt = self.cells
        if above is None:
            z, wz = _gauss_cells(z_lo, z_hi, nz)
        else:  # z = above + (z_hi - above) u^2: a response (z - above)^(3/2) is smooth in u
            lo = min(max(z_lo, float(above)), z_hi)
            u, wu = _gauss_cells(0.0, 1.0, nz)
            z, wz = lo + (z_hi - lo) * u * u, 2.0 * (z_hi - lo) * u * wu
        # kappa_1 = k_max r^2 and t = s^2: nodes gather at small curvatures, where the
        # smaller curvature's scale sets the density's, and at elongated summits
        r, wr = _gauss_cells(0.0, 1.0, nk)
        s, ws = _gauss_cells(0.0, 1.0, nt)
        k1 = k_max * r * r
        return z, wz, k1, 2.0 * k_max * r * wr * k1, s * s, 2.0 * s * ws

    def _summed(self, alpha, above: float | None = None):
        """(z, kappa_1, t, n weighted by the quadrature): shape (nz, nk, nt, alpha)."""
        z, wz, k1, wk, t, wt = self._grid(above)
        n = self.number_density(z[:, None, None, None], k1[None, :, None, None],
                                (k1[:, None] * t[None, :])[None, :, :, None], alpha)
        return z, k1, t, n * (wz[:, None, None] * wk[None, :, None] * wt[None, None, :])[..., None]

    def nodes(self, above: float | None = None):
        """Quadrature of the summits: (z, kappa_1, t, weights), z (nz,), kappa_1 (nk,),
        t = kappa_2 / kappa_1 (nt,) and weights (nz, nk, nt) such that
        sum(weights X(z, kappa_1, t kappa_1)) = int X n over height, curvatures and
        orientation, per unit area; `above`: only the heights above it (a flat at that
        separation touches these summits), with its cells over [above, z_max]."""
        alpha, da = self._alphas()
        z, k1, t, n = self._summed(alpha.reshape(1, 1, 1, -1), above)
        return z, k1, t, n.sum(axis=-1) * da

    def orientation_pdf(self, alpha) -> np.ndarray:
        """The density of the orientation alpha of kappa_1's axis over [0, pi) [1/rad]."""
        a = np.asarray(alpha, dtype=float)
        n = self._summed(a.reshape(1, 1, 1, -1))[3]
        return n.sum(axis=(0, 1, 2)).reshape(a.shape) / self.summit_density

    def expectation(self, fn) -> np.ndarray:
        """E[fn(z, kappa_1, kappa_2)] over the summits (fn broadcasts over (nz, nk, nt))."""
        z, k1, t, w = self.nodes()
        values = fn(z[:, None, None], k1[None, :, None], k1[None, :, None] * t[None, None, :])
        return np.tensordot(np.asarray(values, dtype=float) * np.ones(w.shape), w, axes=3) / w.sum()

    @classmethod
    def from_surface(cls, surface, **options) -> "AnisotropicDensity":
        """The density of the spectral moments in surface.nc (a map's derivative
        covariances at its lateral scale, or the moments of directional profiles)."""
        missing = [k for k in MOMENTS if k not in surface]
        if missing:
            raise ValueError(f"surface.nc has no spectral moments {', '.join(missing)}: the anisotropic "
                             "route needs a map or profiles in three or more directions")
        return cls({k: float(surface[k]) for k in MOMENTS}, **options)
