"""Joint probability density of asperity peak height and curvature.

Report sections 2.4.1 (Gaussian isotropic surfaces, the density of Nayak as
recast by Francis) and 2.4.3 (deterministic surfaces: a density sampled from
the peaks of a height map).  The densities here feed the expectation
integrals of section 2.5 (:mod:`asperity.homogenize`).

Three densities share one small interface: ``pdf(z, kappa)`` (``pdf(z)`` for
fixed curvature) evaluates the *dimensional* density f_{z kappa} (per unit
height per unit curvature), and ``support(...)`` returns the rectangle that
carries the probability mass, as the integration domain of eq. (2.5).

Nondimensional variables (report 2.4.1, with the errata of DESIGN.md)::

    xi   = (z - mean_height) / sigma                 peak height
    eta  = sqrt(1.5) kappa / sigma_curvature         peak (mean) curvature
    beta = sqrt(1.5) sigma_slope^2 / (sigma sigma_curvature)

so that f_{z kappa}(z, kappa) = f_{xi eta}(xi, eta) sqrt(1.5) / (sigma
sigma_curvature).  All functions are unit-agnostic; the pipeline uses SI
(heights in m, curvatures in 1/m, densities in 1/(m * 1/m) = 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "francis_density",
    "JointDensity",
    "FixedCurvatureDensity",
    "SampledDensity",
]

_SQRT_1_5 = math.sqrt(1.5)


def _check_beta(beta: float) -> float:
    beta = float(beta)
    if not np.isfinite(beta) or beta < 0.0:
        raise ValueError(f"wavelength spectrum parameter beta must be in [0, 1), got {beta!r}")
    if beta >= 1.0:
        raise ValueError(
            f"wavelength spectrum parameter beta = {beta:.6g} >= 1: the Nayak/Francis "
            "density of Gaussian random surfaces (report 2.4.1) is undefined there "
            "(1 - beta^2 <= 0). Such statistics come from a deterministic surface "
            "(a pure cosine has beta = sqrt(1.5) = 1.2247, report 2.6.1); use a "
            "density sampled from the peaks of a height map instead "
            "(SampledDensity.from_peaks, report 2.4.3)."
        )
    return beta


def _eta_factor(eta: np.ndarray) -> np.ndarray:
    """eta^2 - 1 + exp(-eta^2), accurate to a few ulp for all eta >= 0.

    Written as x + expm1(-x) with x = eta^2; for x < 0.05 the difference
    x + expm1(-x) loses digits to cancellation, so its Taylor series
    x^2/2 - x^3/6 + ... (truncated after x^8, relative remainder < 1e-14) is
    used instead.
    """
    x = eta * eta
    small = x < 0.05
    xs = np.where(small, x, 0.0)
    # Horner form of x^2 (1/2 - x/6 + x^2/24 - x^3/120 + x^4/720 - x^5/5040 + x^6/40320)
    coeffs = [1 / 40320, -1 / 5040, 1 / 720, -1 / 120, 1 / 24, -1 / 6, 1 / 2]
    poly = np.zeros_like(xs)
    for c in coeffs:  # seven scalar terms, not a loop over data
        poly = poly * xs + c
    series = xs * xs * poly
    with np.errstate(over="ignore", invalid="ignore"):
        direct = x + np.expm1(-x)
    return np.where(small, series, direct)


def francis_density(xi, eta, beta: float) -> np.ndarray:
    """Nondimensional joint density f_{xi eta} of peak height and curvature.

    Report 2.4.1 (Francis' form of Nayak's density), with the corrected
    exponent (DESIGN.md errata)::

        f = sqrt(3) / (pi sqrt(1 - beta^2)) (eta^2 - 1 + exp(-eta^2))
            exp(-(xi^2 - 2 beta xi eta + eta^2) / (2 (1 - beta^2)))

    for eta >= 0 and f = 0 for eta < 0.  It integrates to one over
    xi in R, eta >= 0.

    Parameters
    ----------
    xi, eta : array_like
        Nondimensional peak height and curvature; broadcast together.
    beta : float
        Wavelength spectrum parameter, 0 <= beta < 1 (random surfaces).

    Raises
    ------
    ValueError
        If beta is outside [0, 1): for beta >= 1 (deterministic surfaces,
        e.g. a pure cosine with beta = 1.2247) the Gaussian-surface density
        is undefined and a density sampled from a height map is needed.
    """
    beta = _check_beta(beta)
    xi = np.asarray(xi, dtype=float)
    eta = np.asarray(eta, dtype=float)
    one_m_b2 = 1.0 - beta * beta
    pre = math.sqrt(3.0) / (math.pi * math.sqrt(one_m_b2))
    positive = eta >= 0.0
    etap = np.where(positive, eta, 0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        q = (xi * xi - 2.0 * beta * xi * etap + etap * etap) / (2.0 * one_m_b2)
        e = np.exp(-q)
        g = _eta_factor(etap)
        val = np.where(e > 0.0, pre * g * e, 0.0)  # inf * 0 at eta = inf -> 0
    val = np.where(positive, val, 0.0)
    return np.where(np.isnan(xi) | np.isnan(eta), np.nan, val)


def _radius_bound(threshold: float, beta: float) -> float:
    """Radius r in (xi, eta) outside of which f_{xi eta} < threshold.

    Uses f <= C r^2 exp(-r^2 / (2 (1 + beta))) with C = sqrt(3)/(pi sqrt(1-beta^2)):
    eta^2 - 1 + exp(-eta^2) <= eta^2 <= r^2 and the quadratic form is
    bounded below by its smallest eigenvalue (1 - beta) times r^2.
    """
    from scipy.optimize import brentq  # here: an import most stages never need

    c = math.sqrt(3.0) / (math.pi * math.sqrt(1.0 - beta * beta))
    s = 2.0 * (1.0 + beta)
    r0 = math.sqrt(s)  # maximum of r^2 exp(-r^2/s)
    def bound(r):
        return math.log(c) + 2.0 * math.log(r) - r * r / s - math.log(threshold)
    if bound(r0) <= 0.0:
        return r0
    hi = 2.0 * r0
    while bound(hi) > 0.0:
        hi *= 2.0
    return brentq(bound, r0, hi, xtol=1e-12)


@dataclass(frozen=True)
class JointDensity:
    """Joint density of peak height and curvature of a Gaussian isotropic surface.

    Report 2.4.1 (Nayak / Francis) in dimensional form::

        f_{z kappa}(z, kappa) = f_{xi eta}(xi, eta) * (1 / sigma) * (sqrt(1.5) / sigma_curvature)
        xi = (z - mean_height) / sigma,   eta = sqrt(1.5) kappa / sigma_curvature

    Parameters
    ----------
    sigma, sigma_slope, sigma_curvature : float
        Standard deviations of profile height, slope and curvature
        (sigma, sigma-dot, sigma-double-dot of the report), all > 0.
    mean_height : float
        Mean surface height, the origin of xi.

    Raises
    ------
    ValueError
        If a deviation is not positive, or if beta is not in [0, 1).
    """

    sigma: float
    sigma_slope: float
    sigma_curvature: float
    mean_height: float = 0.0

    def __post_init__(self):
        for name in ("sigma", "sigma_slope", "sigma_curvature"):
            v = float(getattr(self, name))
            if not (np.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} must be a positive finite number, got {v!r}")
        _check_beta(self.beta)

    @property
    def beta(self) -> float:
        """Wavelength spectrum parameter sqrt(1.5) sigma_slope^2 / (sigma sigma_curvature)."""
        return _SQRT_1_5 * self.sigma_slope**2 / (self.sigma * self.sigma_curvature)

    @property
    def jacobian(self) -> float:
        """d(xi) d(eta) / (dz d(kappa)) = sqrt(1.5) / (sigma sigma_curvature)."""
        return _SQRT_1_5 / (self.sigma * self.sigma_curvature)

    def to_nondimensional(self, z, kappa):
        """(xi, eta) of dimensional peak height z and curvature kappa."""
        xi = (np.asarray(z, dtype=float) - self.mean_height) / self.sigma
        eta = _SQRT_1_5 * np.asarray(kappa, dtype=float) / self.sigma_curvature
        return xi, eta

    def to_dimensional(self, xi, eta):
        """(z, kappa) of nondimensional peak height xi and curvature eta."""
        z = self.mean_height + self.sigma * np.asarray(xi, dtype=float)
        kappa = self.sigma_curvature * np.asarray(eta, dtype=float) / _SQRT_1_5
        return z, kappa

    def pdf(self, z, kappa) -> np.ndarray:
        """Dimensional density f_{z kappa}(z, kappa) [1/(height * curvature)]; broadcasts."""
        xi, eta = self.to_nondimensional(z, kappa)
        return francis_density(xi, eta, self.beta) * self.jacobian

    def support(self, threshold: float = 1e-4, resolution: int = 1201):
        """Effective support of the density (report 2.5 (a), 2.6.2).

        The bounding box of the region where the *nondimensional* density
        f_{xi eta} exceeds `threshold`, found on a `resolution` x `resolution`
        grid over a box that provably contains that region (see
        :func:`_radius_bound`), padded by one grid step (kappa clamped at 0).

        Returns
        -------
        (z_min, z_max, kappa_min, kappa_max) in dimensional units.
        """
        threshold = float(threshold)
        if not threshold > 0.0:
            raise ValueError(f"threshold must be positive, got {threshold!r}")
        beta = self.beta
        r = _radius_bound(threshold, beta)
        xi = np.linspace(-r, r, resolution)
        eta = np.linspace(0.0, r, resolution)
        f = francis_density(xi[:, None], eta[None, :], beta)
        above = f > threshold
        if not above.any():
            raise ValueError(
                f"the density nowhere exceeds threshold {threshold:g} "
                f"(its maximum is below it); lower the threshold"
            )
        rows = np.flatnonzero(above.any(axis=1))
        cols = np.flatnonzero(above.any(axis=0))
        dxi = xi[1] - xi[0]
        deta = eta[1] - eta[0]
        xi_lo, xi_hi = xi[rows[0]] - dxi, xi[rows[-1]] + dxi
        eta_lo, eta_hi = max(eta[cols[0]] - deta, 0.0), eta[cols[-1]] + deta
        z_lo, k_lo = self.to_dimensional(xi_lo, eta_lo)
        z_hi, k_hi = self.to_dimensional(xi_hi, eta_hi)
        return float(z_lo), float(z_hi), float(k_lo), float(k_hi)


@dataclass(frozen=True)
class FixedCurvatureDensity:
    """Greenwood-Williamson population: Gaussian peak heights, one curvature.

    Report 7.1 (Greenwood & Williamson 1966): all asperities have the same
    tip radius R = 1/curvature, peak heights are normal with mean
    `mean_height` and standard deviation `sigma_p`::

        f_z(z) = exp(-(z - mean_height)^2 / (2 sigma_p^2)) / (sqrt(2 pi) sigma_p)

    The expectation (2.5) then reduces to a 1-D integral over z.
    """

    sigma_p: float
    curvature: float
    mean_height: float = 0.0

    def __post_init__(self):
        if not (np.isfinite(self.sigma_p) and self.sigma_p > 0.0):
            raise ValueError(f"sigma_p must be a positive finite number, got {self.sigma_p!r}")
        if not (np.isfinite(self.curvature) and self.curvature >= 0.0):
            raise ValueError(f"curvature must be finite and >= 0, got {self.curvature!r}")

    @property
    def radius(self) -> float:
        """Tip radius R = 1/curvature."""
        return math.inf if self.curvature == 0.0 else 1.0 / self.curvature

    def pdf(self, z) -> np.ndarray:
        """Normal density of peak height [1/height]."""
        xi = (np.asarray(z, dtype=float) - self.mean_height) / self.sigma_p
        return np.exp(-0.5 * xi * xi) / (math.sqrt(2.0 * math.pi) * self.sigma_p)

    def support(self, threshold: float = 1e-4):
        """(z_min, z_max, curvature, curvature): heights where phi(xi) exceeds `threshold`.

        Closed form xi = +-sqrt(-2 ln(threshold sqrt(2 pi))); e.g. 1e-12 gives
        +-7.28 sigma_p.  The curvature "range" is the single curvature, so
        that every density's support is the same 4-tuple.
        """
        threshold = float(threshold)
        top = 1.0 / math.sqrt(2.0 * math.pi)
        if not 0.0 < threshold < top:
            raise ValueError(f"threshold must be in (0, {top:.6f}), got {threshold!r}")
        x = math.sqrt(-2.0 * math.log(threshold / top))
        k = float(self.curvature)
        return self.mean_height - x * self.sigma_p, self.mean_height + x * self.sigma_p, k, k


def _data_range(x: np.ndarray) -> tuple[float, float]:
    """(min, max) of x; a single value c becomes c -+ |c|/2 (-+ 1/2 for c = 0)."""
    lo, hi = float(x.min()), float(x.max())
    if hi > lo:
        return lo, hi
    half = 0.5 * abs(lo) if lo != 0.0 else 0.5
    return lo - half, hi + half


class SampledDensity:
    """Piecewise-constant joint density sampled from a list of peaks (report 2.4.3).

    The range [z_min, z_max] x [kappa_min, kappa_max] is divided into
    nz x nk cells and::

        f_ij = n_ij / (N dz dkappa)

    with n_ij the number of peaks in cell (i, j) and N the total number of
    peaks, so that the histogram is a density (the report's n_p(i, j) / N_p
    divided by the cell area).  It integrates to the fraction of peaks inside
    the range: exactly one when `range` is None.  Cells are half-open
    [lo, hi) except the last, which includes its upper edge (as
    :func:`numpy.histogram2d`).  The peak list is kept: the "peaks" rule of
    :mod:`asperity.homogenize` averages over it exactly.

    Build with :meth:`from_peaks`.
    """

    def __init__(self, height_edges, curvature_edges, values, heights, curvatures):
        self.height_edges = np.asarray(height_edges, dtype=float)
        self.curvature_edges = np.asarray(curvature_edges, dtype=float)
        self.values = np.asarray(values, dtype=float)
        self.heights = np.asarray(heights, dtype=float)
        self.curvatures = np.asarray(curvatures, dtype=float)
        for a in (self.height_edges, self.curvature_edges, self.values, self.heights, self.curvatures):
            a.setflags(write=False)

    @classmethod
    def from_peaks(cls, height, curvature, bins=(20, 20), range=None):  # noqa: A002 (numpy's name)
        """Histogram density of peaks (z_i, kappa_i), eq. of report 2.4.3.

        Parameters
        ----------
        height, curvature : array_like, shape (N,)
            Peak heights and mean curvatures.
        bins : (int, int)
            Number of cells in height and curvature.
        range : ((z_min, z_max), (kappa_min, kappa_max)), optional
            Defaults to the range of the peaks; if all peaks share one value c
            of a variable, its range is c -+ |c|/2 (-+ 1/2 for c = 0).
        """
        height = np.asarray(height, dtype=float).ravel()
        curvature = np.asarray(curvature, dtype=float).ravel()
        if height.shape != curvature.shape:
            raise ValueError("height and curvature must have the same number of peaks")
        if height.size == 0:
            raise ValueError("no peaks: cannot sample a density from an empty list")
        if not (np.isfinite(height).all() and np.isfinite(curvature).all()):
            raise ValueError("peak heights and curvatures must be finite")
        if range is None:
            range = (_data_range(height), _data_range(curvature))
        counts, ez, ek = np.histogram2d(height, curvature, bins=bins, range=range)
        area = np.diff(ez)[:, None] * np.diff(ek)[None, :]
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            values = counts / (height.size * area)
        if not (np.all(area > 0.0) and np.isfinite(values).all()):
            raise ValueError(f"histogram cells too small to hold a density: range {range!r}")
        return cls(ez, ek, values, height, curvature)

    @property
    def count(self) -> int:
        """Number of peaks N."""
        return int(self.heights.size)

    def pdf(self, z, kappa) -> np.ndarray:
        """Piecewise-constant density, 0 outside the histogram range; broadcasts."""
        z = np.asarray(z, dtype=float)
        kappa = np.asarray(kappa, dtype=float)
        ez, ek = self.height_edges, self.curvature_edges
        i = np.searchsorted(ez, z, side="right") - 1
        j = np.searchsorted(ek, kappa, side="right") - 1
        # the last cell includes its upper edge
        i = np.where(z == ez[-1], ez.size - 2, i)
        j = np.where(kappa == ek[-1], ek.size - 2, j)
        inside = (i >= 0) & (i < ez.size - 1) & (j >= 0) & (j < ek.size - 1)
        vals = self.values[np.clip(i, 0, ez.size - 2), np.clip(j, 0, ek.size - 2)]
        return np.where(inside, vals, 0.0)

    def support(self, threshold=None):
        """The histogram range (z_min, z_max, kappa_min, kappa_max); `threshold` is ignored."""
        return (
            float(self.height_edges[0]),
            float(self.height_edges[-1]),
            float(self.curvature_edges[0]),
            float(self.curvature_edges[-1]),
        )

    def integral(self) -> float:
        """Exact integral of the histogram density (fraction of peaks inside the range)."""
        area = np.diff(self.height_edges)[:, None] * np.diff(self.curvature_edges)[None, :]
        return float((self.values * area).sum())
