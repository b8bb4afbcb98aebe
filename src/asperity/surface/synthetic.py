"""Synthetic surfaces with known statistics, to verify the estimators (report 2.3, 2.6.1).

* :func:`quasirandom_series`, :func:`evaluate_series`,
  :func:`series_statistics`, :func:`series_moments_2d` -- the random-phase
  series of eq. (2.3) and its exact moments, eq. (2.4) (2.6.1, example 2);
* :func:`cosine_or_series_profile` -- the profiles of the report's two
  examples (2.6.1);
* :func:`anisotropic_series`, :func:`directional_profiles` -- a series
  surface stretched along x and its profiles in several directions (2.3.2);
* :func:`gaussian_map` -- a Gaussian random map with a Gaussian
  autocorrelation (the deterministic-surface route of 2.4.3).
"""

from __future__ import annotations

import math

import numpy as np

from asperity.surface.directional import FOURTH_ORDER
from asperity.surface.statistics import complete_moments

__all__ = [
    "quasirandom_series",
    "evaluate_series",
    "series_statistics",
    "series_moments_2d",
    "synthetic_profile",
    "anisotropic_series",
    "directional_profiles",
    "gaussian_map",
]


def quasirandom_series(
    n: int = 40,
    seed: int = 1,
    k_range: tuple[float, float] = (0.05, 1.2),
    exponent: float = 0.5,
    period: float = 500.0,
    sigma: float = 1.162,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A quasi-random profile series z(s) = sum C_i cos(k_i s + e_i), 1-D eq. (2.3) (2.6.1 ex. 2).

    Choice (the report does not give its distribution):

    * wavenumbers k_i = 2 pi m_i / ``period``, with n distinct integers m_i
      drawn uniformly without replacement among those giving k in
      ``k_range``, so the profile is periodic with ``period`` and sampled
      statistics over whole periods have no cross-term error between
      components;
    * amplitudes C_i proportional to k_i^(-exponent) (spectrum C^2 ~ k^-1
      for the default 0.5), scaled so the series sigma is ``sigma``;
    * phases e_i uniform in [0, 2 pi).

    The defaults (seed 1) give sigma = 1.1620, sigma_slope = 0.5926,
    sigma_curvature = 0.5135, beta = 0.7209, the range of the report's
    Fig. 2.12b (1.1620, 0.59221, 0.49315, 0.74954).

    Returns
    -------
    C, k, e : ndarray
        Amplitudes (m), angular wavenumbers (rad/m, sorted), phases (rad).
    """
    if int(n) < 1:
        raise ValueError(f"n must be a positive number of components; got {n}")
    lo = int(math.ceil(k_range[0] * period / (2.0 * math.pi)))
    hi = int(math.floor(k_range[1] * period / (2.0 * math.pi)))
    lo = max(lo, 1)
    if hi - lo + 1 < n:
        raise ValueError(
            f"k_range {k_range} holds only {max(0, hi - lo + 1)} harmonics of period {period}; "
            f"{n} needed: widen k_range or lengthen period"
        )
    rng = np.random.default_rng(seed)
    m = np.sort(rng.choice(np.arange(lo, hi + 1), size=int(n), replace=False))
    k = 2.0 * np.pi * m / period
    C = k ** (-float(exponent))
    C *= sigma / math.sqrt(0.5 * np.sum(C * C))
    e = rng.uniform(0.0, 2.0 * np.pi, size=int(n))
    return C, k, e


def evaluate_series(s, C, k, e, derivative: int = 0) -> np.ndarray:
    """z(s) = sum_i C_i cos(k_i s + e_i) (1-D eq. (2.3)) or its ``derivative``-th derivative.

    d^r/ds^r [C cos(k s + e)] = C k^r cos(k s + e + r pi/2), evaluated
    exactly; vectorized over s in blocks of bounded memory.
    """
    ss = np.asarray(s, dtype=np.float64)
    C = np.asarray(C, dtype=np.float64).ravel()
    k = np.asarray(k, dtype=np.float64).ravel()
    e = np.asarray(e, dtype=np.float64).ravel()
    if not (C.size == k.size == e.size):
        raise ValueError(f"C, k, e must have one value per component; got {C.size}, {k.size}, {e.size}")
    r = int(derivative)
    if r < 0:
        raise ValueError(f"derivative must be >= 0; got {derivative}")
    amp = C * k**r
    phase = e + r * np.pi / 2.0
    flat = ss.ravel()
    out = np.empty(flat.size)
    block = max(1, (1 << 21) // max(1, k.size))
    for start in range(0, flat.size, block):  # bounded-memory blocks, each vectorized
        sl = slice(start, start + block)
        out[sl] = np.cos(np.multiply.outer(flat[sl], k) + phase) @ amp
    return out.reshape(ss.shape)


def series_statistics(C, k) -> dict[str, float]:
    """Exact profile statistics of the series (2.3), 1-D eq. (2.4): m_p = 1/2 sum k^p C^2.

    Returns a dict with m0, m2, m4, sigma = sqrt(m0), sigma_slope =
    sqrt(m2), sigma_curvature = sqrt(m4), beta = sqrt(1.5) m2/sqrt(m0 m4)
    (2.4.1), peak_density = m4/(6 pi sqrt(3) m2) (2.3.1), zero_density and
    extremum_density (Longuet-Higgins, 2.3.1).
    """
    C = np.asarray(C, dtype=np.float64)
    k = np.asarray(k, dtype=np.float64)
    c2 = 0.5 * C * C
    vals = {
        "m0": float(c2.sum()),
        "m2": float((k**2 * c2).sum()),
        "m4": float((k**4 * c2).sum()),
    }
    vals["sigma"] = math.sqrt(vals["m0"])
    vals["sigma_slope"] = math.sqrt(vals["m2"])
    vals["sigma_curvature"] = math.sqrt(vals["m4"])
    return complete_moments(vals)


def series_moments_2d(C, kx, ky) -> dict[str, float]:
    """The nine spectral moments of the surface series (2.3), eq. (2.4): m_pq = 1/2 sum kx^p ky^q C^2."""
    C = np.asarray(C, dtype=np.float64)
    kx = np.asarray(kx, dtype=np.float64)
    ky = np.asarray(ky, dtype=np.float64)
    c2 = 0.5 * C * C
    out = {}
    for name in ("m00", "m20", "m11", "m02", *FOURTH_ORDER):
        p, q = int(name[1]), int(name[2])
        out[name] = float(np.sum(kx**p * ky**q * c2))
    return out


def synthetic_profile(kind: str, spacing: float, length: float, amplitude: float = 1.0,
                      wavenumber: float = 1.0, components: int = 40, seed: int = 1
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Positions 0, spacing, ... length and heights of the examples of 2.6.1: the cosine
    ``amplitude cos(wavenumber s)`` (``kind="cosine"``) or the quasi-random series."""
    x = np.arange(0.0, length + 0.5 * spacing, spacing)
    if kind == "cosine":
        return x, amplitude * np.cos(wavenumber * x)
    c, k, e = quasirandom_series(n=components, seed=seed)
    return x, evaluate_series(x, c, k, e)


def anisotropic_series(components: int, seed: int, aspect: float):
    """Amplitudes, wave vectors (kx, ky) and phases of a synthetic anisotropic surface (eq. 2.3).

    The 1-D quasi-random series of 2.6.1 with each wave vector turned to a
    random direction and its x component stretched by ``aspect``.
    """
    c, k, e = quasirandom_series(n=components, seed=seed)
    phi = np.random.default_rng(seed + 1).uniform(0.0, np.pi, c.size)
    return c, aspect * k * np.cos(phi), k * np.sin(phi), e


def directional_profiles(components: int, seed: int, aspect: float, spacing: float, length: float,
                         directions_deg) -> list[tuple[np.ndarray, np.ndarray]]:
    """Profiles z(s) = sum C cos((kx cos t + ky sin t) s + e) of :func:`anisotropic_series`
    along each direction t (degrees from the x axis)."""
    c, kx, ky, e = anisotropic_series(components, seed, aspect)
    s = np.arange(0.0, length + 0.5 * spacing, spacing)
    out = []
    for deg in directions_deg:  # a handful of directions
        t = np.radians(deg)
        out.append((s, evaluate_series(s, c, kx * np.cos(t) + ky * np.sin(t), e)))
    return out


def gaussian_map(points: int, spacing: float, sigma: float, correlation_length: float,
                 seed: int, aspect: float = 1.0) -> np.ndarray:
    """A Gaussian random height map with a Gaussian autocorrelation.

    White noise filtered in Fourier space by exp(-(aspect^2 kx^2 + ky^2) l^2 / 8),
    which gives the autocorrelation exp(-(x / (aspect l))^2 - (y / l)^2) (l:
    ``correlation_length``, along y; ``aspect`` > 1 stretches the surface along x, its
    lay), scaled to the standard deviation ``sigma`` (population, 1/n).  Periodic, so
    the eight-neighbour peak rule of 2.4.3 sees no edge effects.  Rows are y, columns x.
    """
    rng = np.random.default_rng(seed)
    noise = rng.standard_normal((points, points))
    k = 2 * np.pi * np.fft.fftfreq(points, d=spacing)
    k2 = k[:, None] ** 2 + (float(aspect) * k[None, :]) ** 2
    z = np.fft.ifft2(np.fft.fft2(noise) * np.exp(-k2 * correlation_length**2 / 8)).real
    z -= z.mean()
    return z * (sigma / z.std())
