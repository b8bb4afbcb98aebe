"""Profile and map statistics of a rough surface (report sections 2.2-2.4.3).

Step one and two of the report's route (section 2): from sampled heights to
the spectral moments that govern the asperity population.

* :func:`derivatives` -- high-order central differences for slopes and
  curvatures (replaces the second-order fit of the report's Appendix A.1,
  which lost 4 % / 7 % on the cosine of Fig. 2.11).
* :func:`profile_statistics` -- the three ways of report 2.3.1 of obtaining
  the profile moments m0, m2, m4: sampling (standard deviations of z, z',
  z''), counting (Longuet-Higgins densities of zeros and extrema) and the
  definition (moments of the power spectral density); with each, the peak
  density D_p (2.3.1) and the wavelength spectrum parameter beta (2.4.1).
* :func:`directional_moments`, :func:`moment_invariants` -- the nine
  spectral moments m_pq of an anisotropic surface from profiles in three or
  more directions, and their seven invariants (2.3.2).
* :func:`map_statistics`, :func:`map_peaks` -- sampling of a 2-D height map
  and its asperity peaks by the eight-neighbour rule (2.4.3).
* :func:`quasirandom_series`, :func:`evaluate_series`,
  :func:`series_statistics`, :func:`series_moments_2d` -- the random-phase
  series of eq. (2.3) and its exact moments, eq. (2.4), used to verify the
  above (2.6.1).

Conventions.  Lengths are SI metres (:mod:`asperity.io` converts on
reading).  A profile is a 1-D array of heights at uniform spacing ``dx``; a
map is a 2-D array ``z[i, j] = z(x = j*dx, y = i*dy)``: axis 1 (along a row)
is x, axis 0 (along a column) is y.  Wavenumbers k are angular (rad/m), so
z = C cos(k s) has wavelength 2 pi / k, and a profile moment is
m_p = int P(k) k^p dk over k in (-inf, inf) (report 2.3.1).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import numpy as np
import xarray as xr

__all__ = [
    "METHODS",
    "DEFAULT_ORDER",
    "derivatives",
    "stencil",
    "power_spectrum",
    "profile_statistics",
    "directional_moments",
    "moment_invariants",
    "map_statistics",
    "map_peaks",
    "quasirandom_series",
    "evaluate_series",
    "series_statistics",
    "series_moments_2d",
]

METHODS = ("sampling", "counting", "spectral")
DEFAULT_ORDER = 8
MIN_POINTS_SPECTRAL = 4
_PEAK_FACTOR = 1.0 / (6.0 * math.pi * math.sqrt(3.0))  # D_p = m4/m2 * this (2.3.1)
_SQRT15 = math.sqrt(1.5)


# --------------------------------------------------------------------------
# validation helpers
# --------------------------------------------------------------------------


def _finite_array(z, ndim: int, what: str) -> np.ndarray:
    try:
        a = np.asarray(z, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{what} must be numeric heights: {exc}") from None
    if a.ndim != ndim:
        need = "1-D array of heights" if ndim == 1 else "2-D array z[y, x] of heights"
        raise ValueError(f"{what} must be a {need}; got an array of shape {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        idx = np.unravel_index(int(np.flatnonzero(bad.ravel())[0]), a.shape)
        where = f"index {idx[0]}" if ndim == 1 else f"(row {idx[0]}, column {idx[1]})"
        raise ValueError(
            f"{what} has a non-finite value ({a[idx]}) at {where}; "
            "all heights must be finite numbers (fill or crop the gaps first)"
        )
    return a


def _spacing(dx, name: str = "dx") -> float:
    try:
        h = float(dx)
    except (TypeError, ValueError):
        raise ValueError(f"spacing {name} must be a positive number; got {dx!r}") from None
    if not (math.isfinite(h) and h > 0.0):
        raise ValueError(f"spacing {name} must be a positive finite number; got {dx!r}")
    return h


def _check_order(order) -> int:
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)):
        raise ValueError(f"order must be an even integer >= 2; got {order!r}")
    if order < 2 or order % 2:
        raise ValueError(f"order must be an even integer >= 2; got {order}")
    return int(order)


# --------------------------------------------------------------------------
# finite differences
# --------------------------------------------------------------------------


@lru_cache(maxsize=None)
def stencil(order: int = DEFAULT_ORDER) -> tuple[np.ndarray, np.ndarray]:
    """Weights of the central difference formulas of even accuracy ``order`` = 2p.

    Returns ``(a, b)`` with ``a[j-1]``, ``b[j]`` (j = 1..p, ``b[0]`` the
    centre weight) such that, on a grid of spacing h,

        z'_i  ~ sum_{j=1}^{p} a_j (z_{i+j} - z_{i-j}) / h
        z''_i ~ (b_0 z_i + sum_{j=1}^{p} b_j (z_{i+j} + z_{i-j})) / h^2

    with the closed forms a_j = (-1)^{j+1} (p!)^2 / (j (p-j)! (p+j)!),
    b_j = 2 a_j / j, b_0 = -2 sum b_j (the maximal-order central formulas;
    p = 1 gives 1/2 and 1, -2).  Applied to cos(k s) they have relative
    errors (leading terms) (p!)^2 / (2p+1)! (kh)^{2p} for z' and
    2 (p!)^2 / (2p+2)! (kh)^{2p} for z''.
    """
    p = _check_order(order) // 2
    j = np.arange(1, p + 1)
    fp = math.factorial(p)
    a = np.array(
        [(-1) ** (jj + 1) * fp * fp / (jj * math.factorial(p - jj) * math.factorial(p + jj)) for jj in j]
    )
    b = np.empty(p + 1)
    b[1:] = 2.0 * a / j
    b[0] = -2.0 * b[1:].sum()
    a.setflags(write=False)
    b.setflags(write=False)
    return a, b


def derivatives(z, dx: float, order: int = DEFAULT_ORDER, axis: int = -1) -> tuple[np.ndarray, np.ndarray]:
    """Slope z' and curvature z'' at interior points, central differences (report 2.3.1).

    Parameters
    ----------
    z : array_like
        Heights sampled at uniform spacing ``dx`` along ``axis`` (any number
        of dimensions; each line along ``axis`` is a profile).
    dx : float
        Sampling interval (m).
    order : int, default 8
        Even order 2p of accuracy of the central formulas (see
        :func:`stencil`); the stencil spans 2p + 1 points.
    axis : int, default -1
        Axis along which to differentiate.

    Returns
    -------
    slope, curvature : ndarray
        Shape of ``z`` with ``order`` points fewer along ``axis``: the p points
        nearest each end, where a central stencil does not fit, are dropped.
        ``slope[..., i]`` belongs to ``z[..., i + p]``.

    Assumptions and accuracy
    ------------------------
    The formulas are exact for polynomials of degree 2p (slope) and 2p + 1
    (curvature).  They assume the profile is smooth at the sampling scale,
    i.e. band-limited with its energy well below the Nyquist wavenumber
    pi/dx.  For a component cos(k s) the relative error of the slope is
    (p!)^2/(2p+1)! (k dx)^{2p} + O((k dx)^{2p+2}) and of the curvature
    2 (p!)^2/(2p+2)! (k dx)^{2p}: for the default order 8 and the cosine of
    the report's Fig. 2.11 (k dx = 0.4) about 1e-6 and 2e-7, against the
    4 % and 7 % of the report's second-order fit (Appendix A.1).  Content
    near or above Nyquist (noise) is not filtered but amplified: choose the
    sampling interval to filter it out, as the report advises (2.3.1).
    """
    h = _spacing(dx)
    a, b = stencil(order)
    p = a.size
    zz = np.asarray(z, dtype=np.float64)
    if zz.ndim == 0:
        raise ValueError("derivatives need an array of heights, got a scalar")
    zz = np.moveaxis(zz, axis, -1)
    n = zz.shape[-1]
    if n < 2 * p + 1:
        raise ValueError(
            f"derivatives of order {2 * p} need at least {2 * p + 1} points along the "
            f"profile (the stencil width); got {n}"
        )
    m = n - 2 * p
    centre = zz[..., p : p + m]
    slope = np.zeros(zz.shape[:-1] + (m,))
    curv = b[0] * centre
    for jj in range(1, p + 1):  # loop over the stencil offsets, not over points
        up = zz[..., p + jj : p + jj + m]
        dn = zz[..., p - jj : p - jj + m]
        slope += a[jj - 1] * (up - dn)
        curv = curv + b[jj] * (up + dn)
    slope /= h
    curv /= h * h
    return np.moveaxis(slope, -1, axis), np.moveaxis(curv, -1, axis)


# --------------------------------------------------------------------------
# spectrum and counting helpers
# --------------------------------------------------------------------------


def power_spectrum(z, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """One-sided power spectral density of a profile (definition, report 2.2 / 2.3.1).

    The profile is demeaned, multiplied by a (periodic) Hann window w and
    transformed; the periodogram is normalized by the window power so that

        sum_j P_j dk = sum (w (z - zbar))^2 / sum w^2  ~  variance of z,

    with dk = 2 pi / (n dx), i.e. the expectation of ``sum P dk`` is the
    variance for a stationary profile (exactly the variance for white
    noise; for a sinusoid within O(1/(k L)) of its variance).  Negative
    wavenumbers are folded onto positive ones (factor 2 except at k = 0 and
    Nyquist), so the profile moments are m_p = sum_j k_j^p P_j dk.

    Returns
    -------
    k : ndarray
        Angular wavenumbers 2 pi j / (n dx), j = 0..n//2 (rad/m).
    P : ndarray
        Power spectral density (m^2 per rad/m = m^3).
    """
    zz = _finite_array(z, 1, "profile")
    h = _spacing(dx)
    n = zz.size
    if n < MIN_POINTS_SPECTRAL:
        raise ValueError(f"spectral method needs at least {MIN_POINTS_SPECTRAL} points; got {n}")
    w = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)
    X = np.fft.rfft(w * (zz - zz.mean()))
    dk = 2.0 * np.pi / (n * h)
    P = (np.abs(X) ** 2) / (np.sum(w * w) * n * dk)
    P[1 : (n + 1) // 2] *= 2.0  # fold k < 0 (Nyquist bin, n even, is not doubled)
    k = dk * np.arange(P.size)
    return k, P


def _crossings(d: np.ndarray) -> np.ndarray:
    """Fractional indices where ``d`` changes sign, linearly interpolated.

    Exact zeros are skipped when looking for a sign change; a crossing over
    a run of exact zeros is placed at the middle of the run.
    """
    nz = np.flatnonzero(d != 0.0)
    if nz.size < 2:
        return np.empty(0)
    a, b = nz[:-1], nz[1:]
    change = np.signbit(d[a]) != np.signbit(d[b])
    a, b = a[change], b[change]
    da, db = d[a], d[b]
    linear = a + da / (da - db)
    return np.where(b == a + 1, linear, 0.5 * (a + b))


def _density(pos: np.ndarray) -> float:
    """(count - 1) / (last - first): exact for a periodic sequence."""
    return (pos.size - 1) / (pos[-1] - pos[0])


# --------------------------------------------------------------------------
# profile statistics
# --------------------------------------------------------------------------

_PROFILE_VARS = {
    # name: (units, long_name)
    "mean_height": ("m", "mean profile height"),
    "mean_slope": ("1", "mean profile slope"),
    "mean_curvature": ("1/m", "mean profile curvature (second derivative)"),
    "sigma": ("m", "standard deviation of profile height"),
    "sigma_slope": ("1", "standard deviation of profile slope"),
    "sigma_curvature": ("1/m", "standard deviation of profile curvature (second derivative)"),
    "m0": ("m^2", "profile spectral moment m0 (variance of height)"),
    "m2": ("1", "profile spectral moment m2 (variance of slope)"),
    "m4": ("1/m^2", "profile spectral moment m4 (variance of curvature)"),
    "zero_density": ("1/m", "density of mean-height crossings along the profile"),
    "extremum_density": ("1/m", "density of extrema along the profile"),
    "peak_density": ("1/m^2", "surface peak density D_p = m4 / (6 pi sqrt(3) m2)"),
    "beta": ("1", "wavelength spectrum parameter beta = sqrt(1.5) m2 / sqrt(m0 m4)"),
}


def _deviations(sigma: float, s_slope: float, s_curv: float) -> dict[str, float]:
    """Standard deviations and the spectral moments they are (2.3.1: m0, m2, m4)."""
    return {"sigma": sigma, "sigma_slope": s_slope, "sigma_curvature": s_curv,
            "m0": sigma**2, "m2": s_slope**2, "m4": s_curv**2}


def _method_sampling(z, h, order, mean_z, sigma):
    slope, curv = derivatives(z, h, order)
    s_slope = float(np.std(slope, ddof=1))
    s_curv = float(np.std(curv, ddof=1))
    return {
        "mean_height": mean_z,
        "mean_slope": float(slope.mean()),
        "mean_curvature": float(curv.mean()),
        **_deviations(sigma, s_slope, s_curv),
    }, slope


def _method_counting(z, h, mean_z, sigma, slope):
    n = z.size
    zeros = _crossings(z - mean_z)
    extrema = _crossings(slope)
    if zeros.size < 2 or extrema.size < 2 or zeros[-1] <= zeros[0] or extrema[-1] <= extrema[0]:
        raise ValueError(
            "counting method needs at least 2 distinct crossings of the mean height and 2 "
            f"extrema (sign changes of the slope); the {n}-point profile has "
            f"{zeros.size} crossings and {extrema.size} extrema.  A profile spanning more "
            "than one wavelength of its longest component is needed, i.e. more points "
            "at this spacing"
        )
    d_zero = _density(zeros) / h  # positions are in samples
    d_extr = _density(extrema) / h
    s_slope = math.pi * sigma * d_zero  # 2.3.1
    s_curv = math.pi * s_slope * d_extr
    return {
        **_deviations(sigma, s_slope, s_curv),
        "zero_density": d_zero,
        "extremum_density": d_extr,
    }


def _method_spectral(z, h):
    k, P = power_spectrum(z, h)
    dk = k[1]
    k2 = k * k
    m0 = float(P.sum() * dk)
    m2 = float((k2 * P).sum() * dk)
    m4 = float((k2 * k2 * P).sum() * dk)
    return {
        "sigma": math.sqrt(m0),
        "sigma_slope": math.sqrt(m2),
        "sigma_curvature": math.sqrt(m4),
        "m0": m0,
        "m2": m2,
        "m4": m4,
    }


def _complete(vals: dict) -> dict:
    """Densities and beta from m0, m2, m4 (2.3.1, 2.4.1)."""
    m0, m2, m4 = vals["m0"], vals["m2"], vals["m4"]
    with np.errstate(divide="ignore", invalid="ignore"):
        vals.setdefault("zero_density", float(np.sqrt(np.float64(m2) / m0) / np.pi))
        vals.setdefault("extremum_density", float(np.sqrt(np.float64(m4) / m2) / np.pi))
        vals["peak_density"] = float(np.float64(m4) / m2 * _PEAK_FACTOR)
        vals["beta"] = float(_SQRT15 * np.float64(m2) / np.sqrt(np.float64(m0) * m4))
    return vals


def profile_statistics(
    z, dx: float, order: int = DEFAULT_ORDER, methods: Sequence[str] = METHODS
) -> xr.Dataset:
    """Statistics of one profile by the sampling, counting and spectral methods (report 2.3.1).

    Parameters
    ----------
    z : array_like
        Heights (m) at uniform spacing ``dx`` (m); all finite.
    dx : float
        Sampling interval (m).  It also sets the shortest wavelength the
        statistics see (the report's filtering by choice of Delta s, 2.3.1).
    order : int, default 8
        Order of the central differences for slopes and curvatures (see
        :func:`derivatives`).
    methods : sequence of str
        Any of ``"sampling"``, ``"counting"``, ``"spectral"`` (default: all).

    Returns
    -------
    xarray.Dataset
        Dimension ``method``; variables mean_height, mean_slope,
        mean_curvature, sigma, sigma_slope, sigma_curvature, m0, m2, m4,
        zero_density, extremum_density, peak_density, beta (NaN where a
        method does not define the quantity); scalars ``points`` and
        ``spacing``.  Select a method with a dict,
        ``ds.sel({"method": "counting"})``: ``method=`` is a keyword of
        ``Dataset.sel`` (interpolation method) and is not taken as the
        dimension.

    Methods
    -------
    sampling
        Means and (n-1) standard deviations of z (all n points) and of z',
        z'' (interior points, :func:`derivatives`); m0 = sigma^2,
        m2 = sigma_slope^2, m4 = sigma_curvature^2 (2.3.1).
    counting
        Longuet-Higgins (2.3.1): zeros are crossings of the mean height,
        extrema are sign changes of z'; crossing positions are linearly
        interpolated between samples; a density is (count - 1) /
        (last crossing - first crossing), exact for a periodic profile.
        sigma is the sampling one; sigma_slope = pi sigma D_zero,
        sigma_curvature = pi sigma_slope D_extr.
    spectral
        Moments of the Hann-windowed periodogram (:func:`power_spectrum`):
        m_p = sum k^p P dk, k angular wavenumber (definition, 2.2, 2.3.1).

    For every method, peak_density D_p = m4 / (6 pi sqrt(3) m2) (2.3.1) and
    beta = sqrt(1.5) m2 / sqrt(m0 m4) = sqrt(1.5) sigma_slope^2 /
    (sigma sigma_curvature) (2.4.1; a pure cosine gives sqrt(1.5) = 1.2247).
    zero_density and extremum_density are counted for the counting method
    and, for the others, the Longuet-Higgins predictions (1/pi) sqrt(m2/m0)
    and (1/pi) sqrt(m4/m2) from their moments.  Means of slope and
    curvature are defined by sampling only; mean height by sampling only
    (it is the level the counting method crosses).

    Raises
    ------
    ValueError
        On a non-finite height (naming its index), a bad spacing, an unknown
        method, or a profile too short for a method: sampling and counting
        need at least order + 2 points (two interior points), counting also
        2 crossings and 2 extrema, spectral at least 4 points.
    """
    zz = _finite_array(z, 1, "profile")
    h = _spacing(dx)
    order = _check_order(order)
    methods = tuple(methods)
    unknown = [m for m in methods if m not in METHODS]
    if unknown or not methods or len(set(methods)) != len(methods):
        raise ValueError(
            f"methods must be distinct names among {METHODS}; got {methods!r}"
        )
    n = zz.size
    need = order + 2
    for m in ("sampling", "counting"):
        if m in methods and n < need:
            raise ValueError(
                f"{m} method with order-{order} differences needs at least {need} points "
                f"(stencil width {order + 1} plus one, for two interior slopes); got {n}"
            )
    if "spectral" in methods and n < MIN_POINTS_SPECTRAL:
        raise ValueError(f"spectral method needs at least {MIN_POINTS_SPECTRAL} points; got {n}")

    mean_z = float(zz.mean())
    sigma = float(np.std(zz, ddof=1))
    results = {}
    slope = None
    if "sampling" in methods or "counting" in methods:
        samp, slope = _method_sampling(zz, h, order, mean_z, sigma)
        if "sampling" in methods:
            results["sampling"] = _complete(samp)
    if "counting" in methods:
        results["counting"] = _complete(_method_counting(zz, h, mean_z, sigma, slope))
    if "spectral" in methods:
        results["spectral"] = _complete(_method_spectral(zz, h))

    data_vars = {}
    for name, (units, long_name) in _PROFILE_VARS.items():
        values = np.array([results[m].get(name, np.nan) for m in methods], dtype=np.float64)
        data_vars[name] = ("method", values, {"units": units, "long_name": long_name})
    data_vars["points"] = ((), np.int64(n), {"units": "1", "long_name": "number of profile points"})
    data_vars["spacing"] = ((), h, {"units": "m", "long_name": "sampling interval of the profile"})
    ds = xr.Dataset(
        data_vars,
        coords={
            "method": (
                "method",
                list(methods),
                {"units": "1", "long_name": "method of estimating the profile moments (report 2.3.1)"},
            )
        },
        attrs={
            "title": "profile statistics (report 2.3.1)",
            "finite_difference_order": order,
            "counting_note": (
                "counting: sigma from sampling; sigma_slope = pi sigma D_zero, "
                "sigma_curvature = pi sigma_slope D_extr (Longuet-Higgins)"
            ),
            "spectral_note": "Hann-windowed periodogram normalized by the window power",
        },
    )
    return ds


# --------------------------------------------------------------------------
# anisotropic surfaces (2.3.2)
# --------------------------------------------------------------------------

_MOMENT_UNITS = {
    "m00": "m^2",
    "m20": "1",
    "m11": "1",
    "m02": "1",
    "m40": "1/m^2",
    "m31": "1/m^2",
    "m22": "1/m^2",
    "m13": "1/m^2",
    "m04": "1/m^2",
}
_INVARIANT_UNITS = {1: "m^2", 2: "1", 3: "1", 4: "1/m^2", 5: "1/m^4", 6: "1/m^4", 7: "1/m^6"}
_INVARIANT_TEXT = {
    1: "m00",
    2: "m20 + m02",
    3: "m20 m02 - m11^2",
    4: "m40 + 2 m22 + m04",
    5: "m40 m04 - 4 m13 m31 + 3 m22^2",
    6: "(m40 + m22)(m22 + m04) - (m31 + m13)^2",
    7: "det [[m40, m31, m22], [m31, m22, m13], [m22, m13, m04]]",
}
_FOURTH = ("m40", "m31", "m22", "m13", "m04")


def moment_invariants(m00, m20, m11, m02, m40=None, m31=None, m22=None, m13=None, m04=None) -> dict[int, float]:
    """The seven rotation invariants of the spectral moments (report 2.3.2).

    1. m00;  2. m20 + m02;  3. m20 m02 - m11^2;  4. m40 + 2 m22 + m04;
    5. m40 m04 - 4 m13 m31 + 3 m22^2;  6. (m40 + m22)(m22 + m04) - (m31 + m13)^2;
    7. m40 (m22 m04 - m13^2) - m31 (m31 m04 - m13 m22) + m22 (m31 m13 - m22^2).

    Returns a dict {number: value}; 4-7 only when all fourth-order moments
    are given (``None`` means not determined).
    """
    inv = {1: m00, 2: m20 + m02, 3: m20 * m02 - m11 * m11}
    if None not in (m40, m31, m22, m13, m04):
        inv[4] = m40 + 2.0 * m22 + m04
        inv[5] = m40 * m04 - 4.0 * m13 * m31 + 3.0 * m22 * m22
        inv[6] = (m40 + m22) * (m22 + m04) - (m31 + m13) ** 2
        inv[7] = m40 * (m22 * m04 - m13 * m13) - m31 * (m31 * m04 - m13 * m22) + m22 * (m31 * m13 - m22 * m22)
    return {key: float(val) for key, val in inv.items()}


def _distinct_directions(theta: np.ndarray, tol: float = 1e-9) -> int:
    t = np.sort(np.mod(theta, np.pi))
    gaps = np.diff(np.append(t, t[0] + np.pi))
    gaps = np.minimum(gaps, np.pi - gaps)  # directions near 0 and near pi are close
    return max(1, int(np.count_nonzero(gaps > tol)))


def directional_moments(theta, m0, m2, m4) -> xr.Dataset:
    """Spectral moments m_pq of an anisotropic surface from profiles in several directions (2.3.2).

    A profile along the unit vector (c, s) = (cos theta, sin theta) of the
    surface (2.3) has wavenumbers k_x c + k_y s, so by eq. (2.4) its moments are

        m0(theta) = m00,
        m2(theta) = m20 c^2 + 2 m11 c s + m02 s^2,
        m4(theta) = m40 c^4 + 4 m31 c^3 s + 6 m22 c^2 s^2 + 4 m13 c s^3 + m04 s^4.

    These linear systems are solved for the moments, by least squares when
    there are more profiles than unknowns.  Directions differing by pi are
    the same direction.

    Parameters
    ----------
    theta : array_like
        Direction of each profile, radians from the x axis.
    m0, m2, m4 : array_like
        Each profile's moments (e.g. from :func:`profile_statistics`).

    Returns
    -------
    xarray.Dataset
        Scalars m00 (mean of m0), m20, m11, m02 (>= 3 distinct directions
        needed), m40, m31, m22, m13, m04 (only with >= 5 distinct directions;
        otherwise the attribute ``fourth_order_moments`` says so), and
        invariant_1 .. invariant_7 (:func:`moment_invariants`) as far as
        computable.  With fewer than five directions invariant_4 is still
        given when the profiles determine it (e.g. three equally spaced
        directions: it is then 8/3 of the mean of m4).  Attributes give the
        condition numbers of the systems and the rms residuals.
    """
    th = _finite_array(theta, 1, "theta")
    a0 = _finite_array(m0, 1, "m0")
    a2 = _finite_array(m2, 1, "m2")
    a4 = _finite_array(m4, 1, "m4")
    if not (th.size == a0.size == a2.size == a4.size):
        raise ValueError(
            "theta, m0, m2, m4 must have one value per profile; got lengths "
            f"{th.size}, {a0.size}, {a2.size}, {a4.size}"
        )
    if th.size == 0:
        raise ValueError("directional_moments needs profiles in at least 3 distinct directions; got none")
    nd = _distinct_directions(th)
    if nd < 3:
        raise ValueError(
            f"directional_moments needs profiles in at least 3 distinct directions "
            f"(directions differing by pi are the same); got {nd}"
        )
    c, s = np.cos(th), np.sin(th)
    A2 = np.column_stack([c * c, 2.0 * c * s, s * s])
    A4 = np.column_stack([c**4, 4.0 * c**3 * s, 6.0 * c * c * s * s, 4.0 * c * s**3, s**4])

    def rms(A, x, y):
        return float(np.sqrt(np.mean((A @ x - y) ** 2)))

    x2 = np.linalg.lstsq(A2, a2, rcond=None)[0]
    mom = {"m00": float(a0.mean()), "m20": float(x2[0]), "m11": float(x2[1]), "m02": float(x2[2])}
    attrs = {
        "title": "spectral moments of an anisotropic surface from directional profiles (report 2.3.2)",
        "directions": nd,
        "profiles": int(th.size),
        "m0_spread": float(a0.max() - a0.min()),
        "condition_number_m2": float(np.linalg.cond(A2)),
        "residual_rms_m2": rms(A2, x2, a2),
    }
    if nd >= 5:
        x4 = np.linalg.lstsq(A4, a4, rcond=None)[0]
        mom.update(zip(_FOURTH, map(float, x4)))
        attrs["fourth_order_moments"] = f"determined from {nd} directions"
        attrs["condition_number_m4"] = float(np.linalg.cond(A4))
        attrs["residual_rms_m4"] = rms(A4, x4, a4)
        inv = moment_invariants(**mom)
    else:
        attrs["fourth_order_moments"] = f"not determined: {nd} directions given, 5 needed"
        inv = moment_invariants(**mom)
        # invariant 4 is the linear functional v.(m40..m04), v = (1, 0, 2, 0, 1);
        # it is determined when v lies in the row space of A4: v = A4^T y.
        v = np.array([1.0, 0.0, 2.0, 0.0, 1.0])
        y = np.linalg.lstsq(A4.T, v, rcond=None)[0]
        if np.linalg.norm(A4.T @ y - v) <= 1e-10 * np.linalg.norm(v):
            inv[4] = float(y @ a4)
    data_vars = {}
    for name, val in mom.items():
        p, q = int(name[1]), int(name[2])
        data_vars[name] = (
            (),
            val,
            {"units": _MOMENT_UNITS[name], "long_name": f"spectral moment m_{p}{q} of the surface, eq. (2.2)"},
        )
    for key, val in inv.items():
        data_vars[f"invariant_{key}"] = (
            (),
            val,
            {"units": _INVARIANT_UNITS[key], "long_name": f"moment invariant {key}: {_INVARIANT_TEXT[key]}"},
        )
    return xr.Dataset(data_vars, attrs=attrs)


# --------------------------------------------------------------------------
# 2-D maps (2.4.3)
# --------------------------------------------------------------------------


def _peak_mask(z: np.ndarray) -> np.ndarray:
    """Interior points strictly higher than their eight neighbours (2.4.3)."""
    c = z[1:-1, 1:-1]
    ny, nx = z.shape
    mask = np.ones(c.shape, dtype=bool)
    for di in (-1, 0, 1):  # the eight neighbour offsets, not the points
        for dj in (-1, 0, 1):
            if di or dj:
                mask &= c > z[1 + di : ny - 1 + di, 1 + dj : nx - 1 + dj]
    return mask


def _check_map(z, dx, dy):
    zz = _finite_array(z, 2, "map")
    if zz.shape[0] < 3 or zz.shape[1] < 3:
        raise ValueError(f"a map needs at least 3 x 3 points (one interior point); got shape {zz.shape}")
    return zz, _spacing(dx, "dx"), _spacing(dy, "dy")


def map_peaks(z, dx: float, dy: float, order: int = DEFAULT_ORDER) -> xr.Dataset:
    """Asperity peaks of a height map by the eight-neighbour rule (report 2.4.3).

    A peak is an interior point strictly higher than all eight nearest
    neighbours (boundary points, which lack neighbours, are never peaks).
    At each peak the second derivatives are central differences of order
    ``order`` (see :func:`stencil`; z_xy uses the tensor product of the
    first-derivative formulas), reduced to the largest even order that fits
    inside the map for peaks near the edge (2 for a peak next to the edge;
    the order used is returned in ``fd_order``).  For a component
    cos(k x) the relative error of z_xx is 2 (p!)^2/(2p+2)! (k dx)^{2p}
    (exactly 1 - 2 (1 - cos k dx)/(k dx)^2 for order 2).

    Parameters
    ----------
    z : array_like, shape (ny, nx)
        Heights, ``z[i, j] = z(x = j dx, y = i dy)`` (m).
    dx, dy : float
        Grid spacings along x (axis 1) and y (axis 0) (m).

    Returns
    -------
    xarray.Dataset
        Dimension ``peak``; x, y (m, origin at ``z[0, 0]``), row, column,
        height (above the mean height of the map), curvature =
        -(z_xx + z_yy)/2 (mean curvature, positive at a peak, the kappa of
        2.4.1 / 2.5.1: C k^2 for the hill C cos kx cos ky), z_xx, z_yy, z_xy,
        fd_order.
    """
    zz, hx, hy = _check_map(z, dx, dy)
    order = _check_order(order)
    pmax = order // 2
    ny, nx = zz.shape
    ii, jj = np.nonzero(_peak_mask(zz))
    ii += 1
    jj += 1
    # largest half-width that fits on both axes around each peak
    p = np.minimum.reduce([ii, ny - 1 - ii, jj, nx - 1 - jj, np.full(ii.shape, pmax)])
    # coefficient tables, row q = weights of the order-2q formulas, zero padded
    A = np.zeros((pmax + 1, pmax))
    B = np.zeros((pmax + 1, pmax + 1))
    for q in range(1, pmax + 1):  # loop over orders, not peaks
        a, b = stencil(2 * q)
        A[q, :q] = a
        B[q, : q + 1] = b
    off = np.arange(1, pmax + 1)
    a = A[p]  # (npk, pmax)
    b = B[p]
    # gathered values; offsets beyond a peak's p have zero weight, so clip indices
    def at(di, dj):
        return zz[np.clip(ii[:, None] + di, 0, ny - 1), np.clip(jj[:, None] + dj, 0, nx - 1)]

    z0 = zz[ii, jj]
    zxx = (b[:, 0] * z0 + np.sum(b[:, 1:] * (at(0, off) + at(0, -off)), axis=1)) / (hx * hx)
    zyy = (b[:, 0] * z0 + np.sum(b[:, 1:] * (at(off, 0) + at(-off, 0)), axis=1)) / (hy * hy)
    # z_xy = sum_{r,s} a_r a_s (z(+r,+s) - z(+r,-s) - z(-r,+s) + z(-r,-s)) / (dx dy), r on y, s on x
    di = off[None, :, None]
    dj = off[None, None, :]

    def at3(si, sj):
        return zz[
            np.clip(ii[:, None, None] + si * di, 0, ny - 1),
            np.clip(jj[:, None, None] + sj * dj, 0, nx - 1),
        ]

    w = a[:, :, None] * a[:, None, :]
    zxy = np.sum(w * (at3(1, 1) - at3(1, -1) - at3(-1, 1) + at3(-1, -1)), axis=(1, 2)) / (hx * hy)
    npk = ii.size
    mean_z = float(zz.mean())

    def var(values, units, long_name):
        return ("peak", values, {"units": units, "long_name": long_name})

    return xr.Dataset(
        {
            "x": var(jj * hx, "m", "x of the peak (column * dx)"),
            "y": var(ii * hy, "m", "y of the peak (row * dy)"),
            "row": var(ii.astype(np.int64), "1", "row index of the peak in the map (y)"),
            "column": var(jj.astype(np.int64), "1", "column index of the peak in the map (x)"),
            "height": var(z0 - mean_z, "m", "peak height above the mean height of the map"),
            "curvature": var(-0.5 * (zxx + zyy), "1/m", "mean peak curvature -(z_xx + z_yy)/2"),
            "z_xx": var(zxx, "1/m", "second derivative d2z/dx2 at the peak"),
            "z_yy": var(zyy, "1/m", "second derivative d2z/dy2 at the peak"),
            "z_xy": var(zxy, "1/m", "mixed second derivative d2z/dxdy at the peak"),
            "fd_order": var((2 * p).astype(np.int64), "1", "order of the central differences used"),
        },
        coords={"peak": ("peak", np.arange(npk), {"units": "1", "long_name": "peak number"})},
        attrs={
            "title": "asperity peaks of a height map, eight-neighbour rule (report 2.4.3)",
            "mean_height": mean_z,
            "finite_difference_order": order,
        },
    )


def map_statistics(z, dx: float, dy: float, order: int = DEFAULT_ORDER) -> xr.Dataset:
    """Sampling statistics and peak density of a height map (report 2.4.3, 2.3.1, 2.3.2).

    Mean height and (n-1) standard deviation over all points (2.4.3); means
    and standard deviations of slopes and curvatures along x (within rows,
    axis 1) and along y (within columns, axis 0) from :func:`derivatives`
    (central differences of ``order``, the order/2 points nearest the ends
    of each line dropped); peak count by the eight-neighbour rule
    (:func:`map_peaks`) and peak density = count / area of the tested
    interior, (nx - 2) dx (ny - 2) dy.

    The map also gives its nine spectral moments as covariances of the
    derivatives (stationary field, eq. (2.2)): m00 = sigma^2,
    m20 = var z_x, m02 = var z_y, m40 = var z_xx, m04 = var z_yy (the same
    samples as sigma_slope_x, ... above), and, on the points interior in both
    directions, m11 = cov(z_x, z_y), m31 = cov(z_xx, z_xy),
    m22 = var z_xy, m13 = cov(z_xy, z_yy) (z_xy = d/dy of z_x); with them
    the invariants of 2.3.2.

    Parameters
    ----------
    z : array_like, shape (ny, nx)
        ``z[i, j] = z(x = j dx, y = i dy)`` (m); at least order + 2 points
        along each axis.
    """
    zz, hx, hy = _check_map(z, dx, dy)
    order = _check_order(order)
    ny, nx = zz.shape
    need = order + 2
    if nx < need or ny < need:
        raise ValueError(
            f"map_statistics with order-{order} differences needs at least {need} points "
            f"along each axis; got shape {zz.shape} (rows, columns)"
        )
    p = order // 2
    mean_z = float(zz.mean())
    sigma = float(np.std(zz, ddof=1))
    zx, zxx = derivatives(zz, hx, order, axis=1)  # (ny, nx - 2p)
    zy, zyy = derivatives(zz, hy, order, axis=0)  # (ny - 2p, nx)
    zxy, _ = derivatives(zx, hy, order, axis=0)  # (ny - 2p, nx - 2p)
    # common interior
    zx_c = zx[p : ny - p, :]
    zy_c = zy[:, p : nx - p]
    zxx_c = zxx[p : ny - p, :]
    zyy_c = zyy[:, p : nx - p]

    def cov(u, v):
        u = u.ravel() - u.mean()
        v = v.ravel() - v.mean()
        return float(u @ v / (u.size - 1))

    s = {
        "mean_slope_x": float(zx.mean()),
        "mean_slope_y": float(zy.mean()),
        "mean_curvature_x": float(zxx.mean()),
        "mean_curvature_y": float(zyy.mean()),
        "sigma_slope_x": float(np.std(zx, ddof=1)),
        "sigma_slope_y": float(np.std(zy, ddof=1)),
        "sigma_curvature_x": float(np.std(zxx, ddof=1)),
        "sigma_curvature_y": float(np.std(zyy, ddof=1)),
    }
    mom = {
        "m00": sigma**2,
        "m20": s["sigma_slope_x"] ** 2,
        "m11": cov(zx_c, zy_c),
        "m02": s["sigma_slope_y"] ** 2,
        "m40": s["sigma_curvature_x"] ** 2,
        "m31": cov(zxx_c, zxy),
        "m22": cov(zxy, zxy),
        "m13": cov(zxy, zyy_c),
        "m04": s["sigma_curvature_y"] ** 2,
    }
    inv = moment_invariants(**mom)
    count = int(np.count_nonzero(_peak_mask(zz)))
    area = (nx - 2) * hx * (ny - 2) * hy

    def v(val, units, long_name):
        return ((), val, {"units": units, "long_name": long_name})

    data = {
        "mean_height": v(mean_z, "m", "mean height of the map"),
        "sigma": v(sigma, "m", "standard deviation of height"),
        "mean_slope_x": v(s["mean_slope_x"], "1", "mean slope along x"),
        "mean_slope_y": v(s["mean_slope_y"], "1", "mean slope along y"),
        "mean_curvature_x": v(s["mean_curvature_x"], "1/m", "mean second derivative along x"),
        "mean_curvature_y": v(s["mean_curvature_y"], "1/m", "mean second derivative along y"),
        "sigma_slope_x": v(s["sigma_slope_x"], "1", "standard deviation of slope along x"),
        "sigma_slope_y": v(s["sigma_slope_y"], "1", "standard deviation of slope along y"),
        "sigma_curvature_x": v(s["sigma_curvature_x"], "1/m", "standard deviation of second derivative along x"),
        "sigma_curvature_y": v(s["sigma_curvature_y"], "1/m", "standard deviation of second derivative along y"),
        # the profile moments of an isotropic surface with the same invariants (2.3.2):
        # m2 = (m20 + m02)/2, m4 = 3 (m40 + 2 m22 + m04)/8 (the averages over directions),
        # what the Nayak density of 2.4.1 takes
        "sigma_slope": v(float(np.sqrt(inv[2] / 2)), "1",
                         "standard deviation of slope of the isotropic equivalent, sqrt((m20 + m02)/2)"),
        "sigma_curvature": v(float(np.sqrt(3 * inv[4] / 8)), "1/m",
                             "standard deviation of curvature of the isotropic equivalent, "
                             "sqrt(3 (m40 + 2 m22 + m04)/8)"),
        "peak_count": v(np.int64(count), "1", "number of peaks (eight-neighbour rule)"),
        "peak_density": v(count / area, "1/m^2", "peaks per unit area of the tested interior"),
        "points_x": v(np.int64(nx), "1", "number of points along x"),
        "points_y": v(np.int64(ny), "1", "number of points along y"),
        "spacing_x": v(hx, "m", "grid spacing along x"),
        "spacing_y": v(hy, "m", "grid spacing along y"),
    }
    for name, val in mom.items():
        data[name] = v(val, _MOMENT_UNITS[name], f"spectral moment m_{name[1]}{name[2]} from derivative covariances")
    for key, val in inv.items():
        data[f"invariant_{key}"] = v(val, _INVARIANT_UNITS[key], f"moment invariant {key}: {_INVARIANT_TEXT[key]}")
    return xr.Dataset(
        data,
        attrs={
            "title": "height map statistics (report 2.4.3)",
            "finite_difference_order": order,
            "axes": "z[i, j] = z(x = j dx, y = i dy): x along rows (axis 1), y along columns (axis 0)",
        },
    )


# --------------------------------------------------------------------------
# random-phase series, eqs. (2.3), (2.4); verification example 2 of 2.6.1
# --------------------------------------------------------------------------


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
    return _complete(vals)


def series_moments_2d(C, kx, ky) -> dict[str, float]:
    """The nine spectral moments of the surface series (2.3), eq. (2.4): m_pq = 1/2 sum kx^p ky^q C^2."""
    C = np.asarray(C, dtype=np.float64)
    kx = np.asarray(kx, dtype=np.float64)
    ky = np.asarray(ky, dtype=np.float64)
    c2 = 0.5 * C * C
    out = {}
    for name in ("m00", "m20", "m11", "m02", *_FOURTH):
        p, q = int(name[1]), int(name[2])
        out[name] = float(np.sum(kx**p * ky**q * c2))
    return out
