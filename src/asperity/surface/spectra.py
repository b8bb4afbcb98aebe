"""Power spectra and autocorrelation of profiles and maps (report 2.2, 2.3.1).

The spectral moments of a profile are the moments of its power spectral
density, m_p = int P(k) k^p dk (report 2.3.1, "calculation from the
definition").  The periodogram of a finite record is that density convolved
with the transform of the window the record is seen through:

* a record that is one period of a periodic surface (a synthetic series, a
  periodic simulation cell) needs no window: its plain periodogram
  (``window="none"``) gives the moments of every component below the Nyquist
  wavenumber exactly;
* a measured record is not periodic: its ends jump, and the jump's k^-2
  leakage would dominate m2 and m4.  A window that goes to zero at both ends
  (Hann, the default; Blackman, with lower side lobes and a wider main lobe)
  suppresses that leakage, at the price of some resolution of the longest
  waves.

Maps get the radially averaged two-dimensional density C(q) and the
autocorrelation function, both for log-log figures of the scales present.

Wavenumbers are angular (rad/m); densities are normalized so that their
integral over all wavenumbers is the variance of the (windowed) heights.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "WINDOWS",
    "window",
    "power_spectrum",
    "spectral_moments",
    "radial_power_spectrum",
    "autocorrelation",
    "CORRELATION_THRESHOLD",
    "correlation_length",
]

WINDOWS = ("hann", "blackman", "none")
MIN_POINTS_SPECTRAL = 4


def window(n: int, kind: str = "hann") -> np.ndarray:
    """The periodic window of ``n`` points: hann, blackman or none (rectangular)."""
    if kind not in WINDOWS:
        raise ValueError(f"window must be one of {WINDOWS}; got {kind!r}")
    t = 2.0 * np.pi * np.arange(n) / n
    if kind == "hann":
        return 0.5 - 0.5 * np.cos(t)
    if kind == "blackman":
        return 0.42 - 0.5 * np.cos(t) + 0.08 * np.cos(2.0 * t)
    return np.ones(n)


def power_spectrum(z, dx: float, window_kind: str = "hann") -> tuple[np.ndarray, np.ndarray]:
    """One-sided power spectral density of a profile (definition, report 2.2 / 2.3.1).

    The profile is demeaned, multiplied by the window w and transformed; the
    periodogram is normalized by the window power so that

        sum_j P_j dk = sum (w (z - zbar))^2 / sum w^2  ~  variance of z,

    with dk = 2 pi / (n dx): the expectation of ``sum P dk`` is the variance
    of a stationary profile; with ``window_kind="none"`` it is the variance
    of the record itself (Parseval).  Negative wavenumbers are folded onto
    positive ones (factor 2 except at k = 0 and Nyquist), so the profile
    moments are m_p = sum_j k_j^p P_j dk.

    Returns
    -------
    k : ndarray
        Angular wavenumbers 2 pi j / (n dx), j = 0..n//2 (rad/m).
    P : ndarray
        Power spectral density (m^2 per rad/m = m^3).
    """
    zz = np.asarray(z, dtype=np.float64)
    if zz.ndim != 1:
        raise ValueError(f"power_spectrum needs a 1-D profile; got shape {zz.shape}")
    if not np.all(np.isfinite(zz)):
        raise ValueError("power_spectrum needs finite heights (no undefined points)")
    h = float(dx)
    if not (math.isfinite(h) and h > 0.0):
        raise ValueError(f"spacing dx must be a positive finite number; got {dx!r}")
    n = zz.size
    if n < MIN_POINTS_SPECTRAL:
        raise ValueError(f"spectral method needs at least {MIN_POINTS_SPECTRAL} points; got {n}")
    w = window(n, window_kind)
    X = np.fft.rfft(w * (zz - zz.mean()))
    dk = 2.0 * np.pi / (n * h)
    P = (np.abs(X) ** 2) / (np.sum(w * w) * n * dk)
    P[1 : (n + 1) // 2] *= 2.0  # fold k < 0 (Nyquist bin, n even, is not doubled)
    k = dk * np.arange(P.size)
    return k, P


def spectral_moments(z, dx: float, window_kind: str = "hann") -> dict[str, float]:
    """m0, m2, m4 of a profile as moments of its periodogram: m_p = sum k^p P dk (2.3.1)."""
    k, P = power_spectrum(z, dx, window_kind)
    dk = k[1]
    k2 = k * k
    return {"m0": float(P.sum() * dk), "m2": float((k2 * P).sum() * dk),
            "m4": float((k2 * k2 * P).sum() * dk)}


def _window_2d(shape, kind):
    return window(shape[0], kind)[:, None] * window(shape[1], kind)[None, :]


def radial_power_spectrum(z, dx: float, dy: float, window_kind: str = "hann"
                          ) -> tuple[np.ndarray, np.ndarray]:
    """Radially averaged two-dimensional power spectral density C(q) of a map.

    C(qx, qy) = |FFT(w (z - zbar))|^2 / (N sum w^2 dqx dqy), so that
    sum C dqx dqy is the variance of the windowed heights; C is averaged
    over rings of width dq = min(dqx, dqy) about the origin.  For an
    isotropic surface the profile moments follow as
    m_p = int_0^inf q^(p+1) C(q) dq int_0^2pi cos^p t dt (m0 = 2 pi int q C dq).

    Parameters
    ----------
    z : (ny, nx) array, ``z[i, j] = z(x = j dx, y = i dy)``, all finite.

    Returns
    -------
    q : ndarray
        Ring centres (rad/m), from dq to the smaller Nyquist wavenumber.
    C : ndarray
        Ring averages (m^4: m^2 per (rad/m)^2); NaN for an empty ring.
    """
    zz = np.asarray(z, dtype=np.float64)
    if zz.ndim != 2 or min(zz.shape) < MIN_POINTS_SPECTRAL:
        raise ValueError(f"radial_power_spectrum needs a map of at least 4 x 4 points; got {zz.shape}")
    if not np.all(np.isfinite(zz)):
        raise ValueError("radial_power_spectrum needs finite heights (fill undefined points first)")
    ny, nx = zz.shape
    w = _window_2d(zz.shape, window_kind)
    X = np.fft.rfft2(w * (zz - zz.mean()))
    dqx, dqy = 2.0 * np.pi / (nx * dx), 2.0 * np.pi / (ny * dy)
    C = np.abs(X) ** 2 / (zz.size * np.sum(w * w) * dqx * dqy)
    # rfft2 holds qx >= 0 only: the half-plane qx > 0 (not the Nyquist column) stands for two
    weight = np.full(C.shape[1], 2.0)
    weight[0] = 1.0
    if nx % 2 == 0:
        weight[-1] = 1.0
    qx = dqx * np.arange(C.shape[1])
    qy = dqy * np.fft.fftfreq(ny, 1.0 / ny)
    q = np.hypot(qx[None, :], qy[:, None])
    dq = min(dqx, dqy)
    q_max = min(np.pi / dx, np.pi / dy)
    rings = np.rint(q / dq).astype(np.int64)
    nbins = int(q_max / dq)
    keep = (rings >= 1) & (rings <= nbins)
    wts = np.broadcast_to(weight[None, :], C.shape)[keep]
    total = np.bincount(rings[keep], weights=C[keep] * wts, minlength=nbins + 1)
    count = np.bincount(rings[keep], weights=wts, minlength=nbins + 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        ring_mean = total / count
    return dq * np.arange(1, nbins + 1), ring_mean[1:]


def autocorrelation(z, spacing, defined=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Autocorrelation of a profile or (radially averaged) of a map, over defined pairs only.

    R(r) = <z(x) z(x + r)> / <z^2> and the height-difference (structure)
    function A(r) = 1/2 <(z(x + r) - z(x))^2>, each averaged over the pairs
    of points a distance r apart that are both defined (zero padding, so a
    finite record is not treated as periodic); heights are taken about the
    mean of the defined points.  On a map the pairs are pooled over rings
    of width min(dx, dy).  A(r) = sigma^2 (1 - R(r)) for a stationary
    surface; on log-log axes A shows the self-affine range and where it
    saturates.

    Parameters
    ----------
    z : 1-D or 2-D array (``z[i, j] = z(x = j dx, y = i dy)``)
    spacing : dx for a profile, (dx, dy) for a map
    defined : boolean mask of measured points, or None (all)

    Returns
    -------
    r : lags (m), from one spacing to half the shorter side of the record
    R : normalized autocorrelation (1)
    A : height-difference autocorrelation (m^2)
    """
    import scipy.fft

    zz = np.asarray(z, dtype=np.float64)
    m = np.isfinite(zz) if defined is None else (np.asarray(defined, dtype=bool) & np.isfinite(zz))
    if not m.any():
        raise ValueError("autocorrelation needs at least one defined point")
    mean = float(zz[m].mean())
    zc = np.where(m, zz - mean, 0.0)
    mf = m.astype(np.float64)
    # lags up to half of each side: padding by half a side keeps the sums acyclic
    shape = tuple(scipy.fft.next_fast_len(n + n // 2, real=True) for n in zz.shape)
    axes = tuple(range(zz.ndim))
    f_m, f_z, f_zz = (scipy.fft.rfftn(a, shape, axes=axes) for a in (mf, zc, zc * zc))

    def correlate(fa, fb):  # sum_x a(x) b(x + lag), every lag
        return scipy.fft.irfftn(np.conj(fa) * fb, shape, axes=axes)

    pairs, product = correlate(f_m, f_m), correlate(f_z, f_z)
    squares = correlate(f_zz, f_m)  # sum over the pairs of z(x)^2
    spacings = np.atleast_1d(np.asarray(spacing, dtype=np.float64))
    if zz.ndim == 1:
        h = float(spacings[0])
        idx = np.arange(1, zz.size // 2 + 1)
        count = np.rint(pairs[idx])
        back = correlate(f_m, f_zz)[idx]  # sum over the pairs of z(x + r)^2
        prod, sq = product[idx], 0.5 * (squares[idx] + back)
        r = h * idx
    else:
        # a ring holds lag l with -l: sum of z(x)^2 over it is the sum of z(x + l)^2
        dx, dy = float(spacings[0]), float(spacings[-1])
        ly = np.fft.fftfreq(shape[0], 1.0 / shape[0])  # signed lags (rows)
        lx = np.fft.fftfreq(shape[1], 1.0 / shape[1])
        dr = min(dx, dy)
        rings = np.rint(np.hypot(lx[None, :] * dx, ly[:, None] * dy) / dr).astype(np.int64)
        n_lag = int(min(zz.shape[1] * dx, zz.shape[0] * dy) / 2 / dr)
        keep = (rings >= 1) & (rings <= n_lag)
        k = rings[keep]

        def ring_sum(a):
            return np.bincount(k, weights=a[keep], minlength=n_lag + 1)[1:]

        count, prod, sq = ring_sum(np.rint(pairs)), ring_sum(product), ring_sum(squares)
        r = dr * np.arange(1, n_lag + 1)
    variance = float(np.mean(zc[m] ** 2))
    with np.errstate(invalid="ignore", divide="ignore"):
        R = np.where(count > 0, prod / count, np.nan) / variance
        A = np.where(count > 0, (sq - prod) / count, np.nan)
    return r, R, A


#: the autocorrelation's decay that defines the correlation length (ISO 25178's Sal uses 0.2)
CORRELATION_THRESHOLD = 0.2


def correlation_length(r: np.ndarray, R: np.ndarray, threshold: float = CORRELATION_THRESHOLD) -> float:
    """The first lag at which the normalized autocorrelation `R(r)` (`autocorrelation`)
    falls to `threshold`, interpolated linearly between the lags around it (ISO 25178's
    autocorrelation length Sal at 0.2); NaN where it never does, ``r[0]`` where it does at
    once."""
    below = np.flatnonzero(R <= threshold)
    if below.size == 0:
        return math.nan
    i = int(below[0])
    if i == 0:
        return float(r[0])
    r0, r1, R0, R1 = r[i - 1], r[i], R[i - 1], R[i]
    return float(r0 + (R0 - threshold) * (r1 - r0) / (R0 - R1))
