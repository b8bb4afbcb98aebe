"""Profile statistics of a rough surface (report 2.3.1).

Step one and two of the report's route (section 2): from sampled heights to
the spectral moments that govern the asperity population.

* :func:`derivatives` -- high-order central differences for slopes and
  curvatures (replaces the second-order fit of the report's Appendix A.1,
  which lost 4 % / 7 % on the cosine of Fig. 2.11).
* :func:`profile_statistics` -- the three ways of report 2.3.1 of obtaining
  the profile moments m0, m2, m4, on a dimension ``estimator``: sampling
  (standard deviations of z, z', z''), counting (Longuet-Higgins densities
  of zeros and extrema) and the definition (moments of the power spectral
  density, :mod:`asperity.surface.spectra`); with each, the peak density
  D_p (2.3.1) and the wavelength spectrum parameter beta (2.4.1).

The moments of an anisotropic surface from profiles in several directions
and their invariants (2.3.2) are in :mod:`asperity.surface.directional`, maps
in :mod:`asperity.surface.maps`, synthetic surfaces in
:mod:`asperity.surface.synthetic`.

The dimension is ``estimator``, not ``method``: ``method`` is a keyword of
xarray's ``sel`` (``ds.sel(method="sampling")`` would silently select
nothing), ``ds.sigma.sel(estimator="sampling")`` picks one estimate.

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

from asperity.surface.missing import defined_heights, longest_run
from asperity.surface.spectra import MIN_POINTS_SPECTRAL, spectral_moments

__all__ = [
    "ESTIMATORS",
    "ESTIMATOR_ATTRS",
    "DEFAULT_ORDER",
    "derivatives",
    "stencil",
    "profile_statistics",
    "complete_moments",
]

ESTIMATORS = ("sampling", "counting", "spectral")
ESTIMATOR_ATTRS = {"units": "1", "long_name": "estimator of the profile moments (report 2.3.1)"}
DEFAULT_ORDER = 8
_PEAK_FACTOR = 1.0 / (6.0 * math.pi * math.sqrt(3.0))  # D_p = m4/m2 * this (2.3.1)
_SQRT15 = math.sqrt(1.5)


# --------------------------------------------------------------------------
# validation helpers
# --------------------------------------------------------------------------


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


def derivatives(z, dx: float, order: int = DEFAULT_ORDER, axis: int = -1, curvature: bool = True
                ) -> tuple[np.ndarray, np.ndarray | None]:
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
    curvature : bool, default True
        False: the slope only (the curvature returned is None).

    Returns
    -------
    slope, curvature : ndarray
        Shape of ``z`` with ``order`` points fewer along ``axis``: the p points
        nearest each end, where a central stencil does not fit, are dropped.
        ``slope[..., i]`` belongs to ``z[..., i + p]``.  NaN (an undefined
        height) anywhere in a point's stencil, or at the point, makes its
        slope and curvature NaN.

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
    axis = axis % zz.ndim
    n = zz.shape[axis]
    if n < 2 * p + 1:
        raise ValueError(
            f"derivatives of order {2 * p} need at least {2 * p + 1} points along the "
            f"profile (the stencil width); got {n}"
        )
    m = n - 2 * p

    def along(start):  # the m points from `start` along `axis` (slices: no copy, contiguous blocks)
        index = [slice(None)] * zz.ndim
        index[axis] = slice(start, start + m)
        return zz[tuple(index)]

    centre = along(p)
    # in place, with one scratch array: a map's derivatives are bound by memory traffic
    slope = np.multiply(centre, 0.0)  # the slope's stencil skips the centre: NaN there all the same
    curv = np.multiply(centre, b[0] / (h * h)) if curvature else None
    tmp = np.empty(centre.shape)
    for jj in range(1, p + 1):  # loop over the stencil offsets, not over points
        up, dn = along(p + jj), along(p - jj)
        np.subtract(up, dn, out=tmp)
        tmp *= a[jj - 1] / h
        slope += tmp
        if curvature:
            np.add(up, dn, out=tmp)
            tmp *= b[jj] / (h * h)
            curv += tmp
    return slope, curv


# --------------------------------------------------------------------------
# counting helpers
# --------------------------------------------------------------------------


def _crossings(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Fractional indices where ``d`` changes sign within a run of finite values, and the run.

    Crossing positions are linearly interpolated between samples; exact
    zeros are skipped when looking for a sign change, and a crossing over a
    run of exact zeros is placed at the middle of the run.  NaN (an
    undefined value) separates runs: no crossing is counted across it.
    """
    finite = np.isfinite(d)
    run = np.cumsum(~finite)  # equal for two indices iff no NaN lies between them
    nz = np.flatnonzero(finite & (d != 0.0))
    if nz.size < 2:
        return np.empty(0), np.empty(0, dtype=np.int64)
    a, b = nz[:-1], nz[1:]
    change = (np.signbit(d[a]) != np.signbit(d[b])) & (run[a] == run[b])
    a, b = a[change], b[change]
    da, db = d[a], d[b]
    linear = a + da / (da - db)
    return np.where(b == a + 1, linear, 0.5 * (a + b)), run[a]


def _density(pos: np.ndarray, run: np.ndarray) -> tuple[float, int]:
    """Crossings per unit index: sum over runs of (count - 1) / sum of (last - first).

    Exact for a periodic sequence; with undefined points, each run of
    defined values contributes its own span.  Returns the density and the
    number of counted intervals (0 when no run holds two crossings).
    """
    if pos.size < 2:
        return math.nan, 0
    first = np.flatnonzero(np.r_[True, run[1:] != run[:-1]])
    last = np.r_[first[1:] - 1, pos.size - 1]
    span = pos[last] - pos[first]
    intervals = int(np.sum(last - first))
    if intervals == 0 or not span.sum() > 0:
        return math.nan, 0
    return intervals / float(span.sum()), intervals


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


def mean_and_deviation(a: np.ndarray) -> tuple[float, float, int]:
    """Mean, (n-1) standard deviation and count of the finite entries of ``a``."""
    values = a[np.isfinite(a)]
    n = values.size
    if n < 2:
        return math.nan, math.nan, n
    mean = float(values.mean())
    dev = values - mean
    return mean, math.sqrt(float(dev @ dev) / (n - 1)), n


def _estimate_sampling(z, h, order, mean_z, sigma):
    slope, curv = derivatives(z, h, order)  # NaN wherever the stencil meets an undefined point
    mean_slope, s_slope, _ = mean_and_deviation(slope)
    mean_curv, s_curv, _ = mean_and_deviation(curv)
    return {
        "mean_height": mean_z,
        "mean_slope": mean_slope,
        "mean_curvature": mean_curv,
        **_deviations(sigma, s_slope, s_curv),
    }, slope


def _estimate_counting(z, h, mean_z, sigma, slope):
    zeros, zero_runs = _crossings(z - mean_z)
    extrema, extremum_runs = _crossings(slope)
    d_zero, n_zero = _density(zeros, zero_runs)
    d_extr, n_extr = _density(extrema, extremum_runs)
    if n_zero == 0 or n_extr == 0:
        raise ValueError(
            "counting method needs at least 2 distinct crossings of the mean height and 2 "
            f"extrema (sign changes of the slope); the {z.size}-point profile has "
            f"{zeros.size} crossings and {extrema.size} extrema.  A profile spanning more "
            "than one wavelength of its longest component is needed, i.e. more points "
            "at this spacing"
        )
    d_zero /= h  # positions are in samples
    d_extr /= h
    s_slope = math.pi * sigma * d_zero  # 2.3.1
    s_curv = math.pi * s_slope * d_extr
    return {
        **_deviations(sigma, s_slope, s_curv),
        "zero_density": d_zero,
        "extremum_density": d_extr,
    }


def _estimate_spectral(z, h, window_kind):
    m = spectral_moments(z, h, window_kind)
    return {
        "sigma": math.sqrt(m["m0"]),
        "sigma_slope": math.sqrt(m["m2"]),
        "sigma_curvature": math.sqrt(m["m4"]),
        **m,
    }


def complete_moments(vals: dict) -> dict:
    """Densities and beta from m0, m2, m4 (2.3.1, 2.4.1)."""
    m0, m2, m4 = vals["m0"], vals["m2"], vals["m4"]
    with np.errstate(divide="ignore", invalid="ignore"):
        vals.setdefault("zero_density", float(np.sqrt(np.float64(m2) / m0) / np.pi))
        vals.setdefault("extremum_density", float(np.sqrt(np.float64(m4) / m2) / np.pi))
        vals["peak_density"] = float(np.float64(m4) / m2 * _PEAK_FACTOR)
        vals["beta"] = float(_SQRT15 * np.float64(m2) / np.sqrt(np.float64(m0) * m4))
    return vals


def _check_estimators(estimators) -> tuple[str, ...]:
    estimators = tuple(estimators)
    unknown = [m for m in estimators if m not in ESTIMATORS]
    if unknown or not estimators or len(set(estimators)) != len(estimators):
        raise ValueError(f"estimators must be distinct names among {ESTIMATORS}; got {estimators!r}")
    return estimators


def profile_statistics(
    z, dx: float, order: int = DEFAULT_ORDER, estimators: Sequence[str] = ESTIMATORS, *,
    defined=None, window: str = "hann",
) -> xr.Dataset:
    """Statistics of one profile by the sampling, counting and spectral methods (report 2.3.1).

    Parameters
    ----------
    z : array_like
        Heights (m) at uniform spacing ``dx`` (m); finite wherever defined.
    dx : float
        Sampling interval (m).  It also sets the shortest wavelength the
        statistics see (the report's filtering by choice of Delta s, 2.3.1).
    order : int, default 8
        Order of the central differences for slopes and curvatures (see
        :func:`derivatives`).
    estimators : sequence of str
        Any of ``"sampling"``, ``"counting"``, ``"spectral"`` (default: all).
    defined : boolean array, optional
        True where the height was measured (default: every point, and then
        every height must be finite).  See "Undefined points" below.
    window : str
        The periodogram's window for the spectral method
        (:func:`asperity.surface.spectra.power_spectrum`): ``hann``
        (default), ``blackman``, or ``none`` for a record that is one
        period of a periodic surface (then the moments of its components
        are exact).

    Returns
    -------
    xarray.Dataset
        Dimension ``estimator``; variables mean_height, mean_slope,
        mean_curvature, sigma, sigma_slope, sigma_curvature, m0, m2, m4,
        zero_density, extremum_density, peak_density, beta (NaN where an
        estimator does not define the quantity); scalars ``points``,
        ``points_defined`` and ``spacing``.  ``ds.sigma.sel(estimator=
        "counting")`` picks one estimate.

    Estimators
    ----------
    sampling
        Means and (n-1) standard deviations of z (all n defined points) and
        of z', z'' (:func:`derivatives`, where the stencil is wholly
        defined); m0 = sigma^2, m2 = sigma_slope^2, m4 = sigma_curvature^2
        (2.3.1).
    counting
        Longuet-Higgins (2.3.1): zeros are crossings of the mean height,
        extrema are sign changes of z'; crossing positions are linearly
        interpolated between samples; a density is (count - 1) /
        (last crossing - first crossing), exact for a periodic profile,
        summed over the runs of defined points.  sigma is the sampling
        one; sigma_slope = pi sigma D_zero, sigma_curvature = pi
        sigma_slope D_extr.
    spectral
        Moments of the windowed periodogram: m_p = sum k^p P dk, k angular
        wavenumber (definition, 2.2, 2.3.1).  A periodogram needs an
        unbroken record: with undefined points it is taken over the longest
        run of defined points (attribute ``spectral_record``).

    For every estimator, peak_density D_p = m4 / (6 pi sqrt(3) m2) (2.3.1)
    and beta = sqrt(1.5) m2 / sqrt(m0 m4) = sqrt(1.5) sigma_slope^2 /
    (sigma sigma_curvature) (2.4.1; a pure cosine gives sqrt(1.5) =
    1.2247).  zero_density and extremum_density are counted by the
    counting estimator and, for the others, the Longuet-Higgins predictions
    (1/pi) sqrt(m2/m0) and (1/pi) sqrt(m4/m2) from their moments.  Means of
    slope and curvature are defined by sampling only; mean height by
    sampling only (it is the level the counting method crosses).

    Undefined points: heights there are ignored; a slope or curvature is
    used only where its whole stencil is defined, a crossing only between
    two defined neighbours, densities are per defined length.

    Raises
    ------
    ValueError
        On a non-finite defined height (naming its index), a bad spacing,
        an unknown estimator, or a profile too short for an estimator:
        sampling and counting need at least order + 2 points (two slopes
        with a whole stencil), counting also 2 crossings and 2 extrema,
        spectral at least 4 points in a row.
    """
    zz, mask = defined_heights(z, defined, 1, "profile")
    h = _spacing(dx)
    order = _check_order(order)
    estimators = _check_estimators(estimators)
    n = zz.size
    need = order + 2
    for m in ("sampling", "counting"):
        if m in estimators and n < need:
            raise ValueError(
                f"{m} method with order-{order} differences needs at least {need} points "
                f"(stencil width {order + 1} plus one, for two interior slopes); got {n}"
            )
    attrs = {
        "title": "profile statistics (report 2.3.1)",
        "finite_difference_order": order,
        "counting_note": (
            "counting: sigma from sampling; sigma_slope = pi sigma D_zero, "
            "sigma_curvature = pi sigma_slope D_extr (Longuet-Higgins)"
        ),
        "spectral_note": (f"{window}-windowed periodogram normalized by the window power"
                          if window != "none" else "plain periodogram (no window): the record is one period"),
    }
    record = zz
    if "spectral" in estimators and not mask.all():
        run = longest_run(mask)
        record = zz[run]
        attrs["spectral_record"] = (f"the longest run of defined points, {run.start} to {run.stop - 1} "
                                    f"({record.size} of {n} points)")
    if "spectral" in estimators and record.size < MIN_POINTS_SPECTRAL:
        raise ValueError(f"spectral method needs at least {MIN_POINTS_SPECTRAL} points; got {record.size}")

    values = zz[mask]
    mean_z = float(values.mean())
    sigma = float(np.std(values, ddof=1)) if values.size > 1 else math.nan
    results = {}
    if "sampling" in estimators or "counting" in estimators:
        samp, slope = _estimate_sampling(zz, h, order, mean_z, sigma)
        if np.count_nonzero(np.isfinite(slope)) < 2:
            raise ValueError(
                f"sampling method with order-{order} differences needs at least two points whose "
                f"whole stencil ({order + 1} points) is defined; the profile has "
                f"{np.count_nonzero(np.isfinite(slope))}"
            )
        if "sampling" in estimators:
            results["sampling"] = complete_moments(samp)
    if "counting" in estimators:
        results["counting"] = complete_moments(_estimate_counting(zz, h, mean_z, sigma, slope))
    if "spectral" in estimators:
        results["spectral"] = complete_moments(_estimate_spectral(record, h, window))

    data_vars = {}
    for name, (units, long_name) in _PROFILE_VARS.items():
        vals = np.array([results[m].get(name, np.nan) for m in estimators], dtype=np.float64)
        data_vars[name] = ("estimator", vals, {"units": units, "long_name": long_name})
    data_vars["points"] = ((), np.int64(n), {"units": "1", "long_name": "number of profile points"})
    data_vars["points_defined"] = ((), np.int64(values.size),
                                   {"units": "1", "long_name": "number of defined profile points"})
    data_vars["spacing"] = ((), h, {"units": "m", "long_name": "sampling interval of the profile"})
    return xr.Dataset(
        data_vars,
        coords={"estimator": ("estimator", list(estimators), ESTIMATOR_ATTRS)},
        attrs=attrs,
    )
