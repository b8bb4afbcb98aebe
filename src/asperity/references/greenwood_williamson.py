"""Greenwood-Williamson model in closed form (report 7.1; Greenwood & Williamson 1966).

Spherical asperities of one tip radius R, peak heights normal with mean 0 and
standard deviation sigma_p, n peaks per unit area, Hertz contact (report 6.1)
with a rigid flat at separation h from the mean peak height.  With
t = h / sigma_p, E* = E / (1 - nu^2) and::

    F_m(t) = integral_t^inf (s - t)^m phi(s) ds      (phi: standard normal pdf)

the expectations (2.5) over the population are, per unit nominal area::

    contact count          n F_0(t)
    contact area ratio     n pi R sigma_p F_1(t)
    nominal pressure       n (4/3) E* R^(1/2) sigma_p^(3/2) F_{3/2}(t)
    normal stiffness       n 2 E* R^(1/2) sigma_p^(1/2) F_{1/2}(t)   (= -dp/dh)

This is the reference against which the numerical homogenization of
:mod:`asperity.homogenize` is verified, as the report does in 7.1.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from asperity.references.hertz import plane_strain_modulus

__all__ = ["gw_integral", "gw_interface"]

_SQRT_2PI = math.sqrt(2.0 * math.pi)
_T_ASYMPTOTIC = -30.0  # below this, F_m(t) by its expansion in 1/|t|


def _f_negative_tail(m: float, t: np.ndarray) -> np.ndarray:
    """F_m(t) for t << 0: E[(Z + |t|)^m] = |t|^m sum_j C(m, 2j) (2j-1)!! |t|^(-2j).

    The mass below s = t (< 1e-197 for t < -30) is neglected; the series is
    asymptotic and truncated after j = 8 (remainder < 1e-30 relative at |t| = 30).
    """
    from scipy import special  # here, not at the top: an import most stages never need

    a = np.abs(t)
    total = np.ones_like(a)
    dfact = 1.0
    for j in range(1, 9):  # eight scalar terms
        dfact *= 2 * j - 1
        total = total + special.binom(m, 2 * j) * dfact * a ** (-2.0 * j)
    return a**m * total


def gw_integral(m: float, t) -> np.ndarray:
    """F_m(t) = integral_t^inf (s - t)^m phi(s) ds, m >= 0 (Greenwood-Williamson).

    Closed forms: F_0(t) = erfc(t/sqrt 2)/2, F_1(t) = phi(t) - t F_0(t); for
    other m the parabolic cylinder function identity::

        integral_0^inf x^m exp(-x^2/2 - t x) dx = Gamma(m+1) exp(t^2/4) D_{-m-1}(t)

    gives F_m(t) = Gamma(m+1) exp(-t^2/4) D_{-m-1}(t) / sqrt(2 pi)
    (scipy.special.pbdv; relative accuracy ~1e-11).  For t < -30 the
    expansion in 1/|t| is used (D overflows there).
    """
    from scipy import special  # here, not at the top: an import most stages never need

    m = float(m)
    if m < 0.0:
        raise ValueError("m must be >= 0")
    t = np.asarray(t, dtype=float)
    if m == 0.0:
        return 0.5 * special.erfc(t / math.sqrt(2.0))
    if m == 1.0:
        # phi(t) - t Q(t), written with the scaled erfc to avoid underflow:
        # Q(t) = phi(t) sqrt(pi/2) erfcx(t/sqrt 2) for t >= 0
        phi = np.exp(-0.5 * t * t) / _SQRT_2PI
        pos = t >= 0.0
        tp = np.where(pos, t, 0.0)
        f_pos = phi * (1.0 - tp * math.sqrt(math.pi / 2.0) * special.erfcx(tp / math.sqrt(2.0)))
        f_neg = phi - t * 0.5 * special.erfc(t / math.sqrt(2.0))
        return np.where(pos, f_pos, f_neg)
    far = t < _T_ASYMPTOTIC
    tt = np.where(far, 0.0, t)
    d, _ = special.pbdv(-m - 1.0, tt)
    near = math.gamma(m + 1.0) / _SQRT_2PI * np.exp(-0.25 * tt * tt) * d
    if np.any(far):
        return np.where(far, _f_negative_tail(m, np.where(far, t, _T_ASYMPTOTIC)), near)
    return near


def gw_interface(separation, radius, sigma_p, peak_density, E, nu) -> xr.Dataset:
    """Greenwood-Williamson interface laws on dim ``separation`` (report 7.1).

    Parameters
    ----------
    separation : array_like, shape (ns,)
        Separation h of the rigid flat from the mean peak height [m].
    radius : float
        Tip radius R of every asperity [m].
    sigma_p : float
        Standard deviation of peak heights [m].
    peak_density : float
        Peaks per unit nominal area n [1/m^2].
    E, nu : float
        Young's modulus [Pa] and Poisson's ratio of the asperities (rigid flat).

    Returns
    -------
    xarray.Dataset with nominal_pressure [Pa], contact_area_ratio [1],
    contact_count [1/m^2], normal_stiffness [Pa/m] and density_integral (= 1),
    the variables of :func:`asperity.homogenize.interface_response`.
    """
    h = np.atleast_1d(np.asarray(separation, dtype=float))
    R = float(radius)
    s = float(sigma_p)
    n = float(peak_density)
    if not (R > 0.0 and s > 0.0 and n > 0.0):
        raise ValueError("radius, sigma_p and peak_density must be positive")
    estar = float(plane_strain_modulus(E, nu))
    t = h / s
    count = n * gw_integral(0.0, t)
    area = n * math.pi * R * s * gw_integral(1.0, t)
    pressure = n * (4.0 / 3.0) * estar * math.sqrt(R) * s**1.5 * gw_integral(1.5, t)
    stiffness = n * 2.0 * estar * math.sqrt(R) * math.sqrt(s) * gw_integral(0.5, t)
    dims = ("separation",)
    return xr.Dataset(
        {
            "nominal_pressure": (dims, pressure, {"units": "Pa", "long_name": "nominal contact pressure (Greenwood-Williamson)"}),
            "contact_area_ratio": (dims, area, {"units": "1", "long_name": "real contact area per unit nominal area (Greenwood-Williamson)"}),
            "contact_count": (dims, count, {"units": "1/m^2", "long_name": "asperities in contact per unit nominal area (Greenwood-Williamson)"}),
            "normal_stiffness": (dims, stiffness, {"units": "Pa/m", "long_name": "normal contact stiffness -dp/dh (Greenwood-Williamson)"}),
            "density_integral": ((), 1.0, {"units": "1", "long_name": "integral I of the peak density (eq. 2.7), exact"}),
        },
        coords={"separation": (dims, h, {"units": "m", "long_name": "separation of the rigid flat from the mean peak height"})},
        attrs={
            "title": "Greenwood-Williamson closed form (report 7.1)",
            "radius": R,
            "sigma_p": s,
            "peak_density": n,
            "youngs_modulus": float(E),
            "poisson": float(nu),
        },
    )
