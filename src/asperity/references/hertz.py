"""Hertz contact of an elastic sphere with a rigid flat (report 6.1).

For a sphere of radius R = 1/kappa pressed by w into a rigid flat, with
plane-strain modulus E* = E / (1 - nu^2), report 6.1 (Hertz [48, 91])::

    r = sqrt(R w)                              contact radius
    A = pi R w = pi r^2                        contact area
    P = 4/3 E* R^(1/2) w^(3/2)                 load
    dP/dw = 2 E* r                             normal stiffness
    p0 = 3 P / (2 pi r^2) = (2/pi) E* sqrt(w/R)  maximum pressure

all zero for w <= 0.  These are the single-asperity responses X(z, kappa, w)
that :mod:`asperity.homogenize` integrates over the peak population; Hertz is
shift invariant (independent of the peak height z).

Functions are unit-agnostic; the dataset builder labels SI units.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

__all__ = ["hertz_response", "hertz_asperities", "plane_strain_modulus"]

_ATTRS = {
    "force": ("N", "normal contact force of one asperity (Hertz)"),
    "contact_area": ("m^2", "real contact area of one asperity (Hertz)"),
    "contact_radius": ("m", "contact radius of one asperity (Hertz)"),
    "stiffness": ("N/m", "normal contact stiffness dP/dw of one asperity (Hertz)"),
    "max_pressure": ("Pa", "maximum contact pressure of one asperity (Hertz)"),
}


def plane_strain_modulus(youngs_modulus, poisson):
    """E* = E / (1 - nu^2), checking E > 0 and -1 < nu <= 0.5."""
    e = np.asarray(youngs_modulus, dtype=float)
    nu = np.asarray(poisson, dtype=float)
    if np.any(~(e > 0.0)):
        raise ValueError("Young's modulus must be positive")
    if np.any(~((nu > -1.0) & (nu <= 0.5))):
        raise ValueError("Poisson's ratio must be in (-1, 0.5]")
    return e / (1.0 - nu * nu)


def hertz_response(interference, curvature, youngs_modulus, poisson) -> dict[str, np.ndarray]:
    """Hertz response of a sphere of curvature kappa = 1/R on a rigid flat (report 6.1).

    Parameters
    ----------
    interference : array_like
        Approach w of the flat into the undeformed sphere; no contact for w <= 0.
    curvature : array_like
        Tip curvature kappa = 1/R >= 0.  kappa = 0 is a flat (R infinite):
        its response is 0 at w <= 0 and infinite for w > 0.
    youngs_modulus, poisson : array_like
        Elastic constants of the sphere (the flat is rigid).  All arguments
        broadcast together.

    Returns
    -------
    dict with arrays ``force`` P = 4/3 E* R^(1/2) w^(3/2), ``contact_radius``
    r = sqrt(R w), ``contact_area`` A = pi R w, ``stiffness`` dP/dw = 2 E* r
    and ``max_pressure`` p0 = (2/pi) E* sqrt(w/R), with E* = E/(1-nu^2).
    """
    w = np.asarray(interference, dtype=float)
    kappa = np.asarray(curvature, dtype=float)
    if np.any(kappa < 0.0):
        raise ValueError("curvature of a peak must be >= 0")
    estar = plane_strain_modulus(youngs_modulus, poisson)
    wp = np.maximum(w, 0.0)
    touching = w > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        radius2 = np.where(touching, wp / kappa, 0.0)  # r^2 = R w
        r = np.sqrt(radius2)
        force = np.where(touching, (4.0 / 3.0) * estar * r * wp, 0.0)  # R^1/2 w^3/2 = r w
        area = np.pi * radius2
        stiffness = np.where(touching, 2.0 * estar * r, 0.0)
        p0 = np.where(touching, (2.0 / np.pi) * estar * np.sqrt(wp * kappa), 0.0)
    shape = np.broadcast_shapes(w.shape, kappa.shape, np.shape(estar))
    out = {
        "force": force,
        "contact_radius": r,
        "contact_area": area,
        "stiffness": stiffness,
        "max_pressure": p0,
    }
    return {k: np.broadcast_to(v, shape).copy() for k, v in out.items()}


def hertz_asperities(heights, curvatures, interferences, E, nu) -> xr.Dataset:
    """Hertz asperities on the (height, curvature, interference) grid of ``asperities.nc``.

    The response does not depend on the peak height (Hertz is shift
    invariant), so the height dimension is filled by broadcasting.

    Parameters
    ----------
    heights : array_like, shape (nh,)
        Peak heights [m].
    curvatures : array_like, shape (nk,)
        Tip curvatures 1/R [1/m], > 0.
    interferences : array_like, shape (nw,)
        Interferences w [m], increasing, starting at 0 or a positive value.
    E, nu : float
        Young's modulus [Pa] and Poisson's ratio of the asperity.
    """
    z = np.atleast_1d(np.asarray(heights, dtype=float))
    k = np.atleast_1d(np.asarray(curvatures, dtype=float))
    w = np.atleast_1d(np.asarray(interferences, dtype=float))
    if z.ndim != 1 or k.ndim != 1 or w.ndim != 1:
        raise ValueError("heights, curvatures and interferences must be 1-D")
    if np.any(np.diff(w) <= 0.0) or w[0] < 0.0:
        raise ValueError("interferences must be strictly increasing and start at >= 0")
    resp = hertz_response(w[None, :], k[:, None], E, nu)
    shape = (z.size, k.size, w.size)
    dims = ("height", "curvature", "interference")
    data_vars = {}
    for name in ("force", "contact_area", "contact_radius", "stiffness"):
        units, long_name = _ATTRS[name]
        data_vars[name] = (dims, np.broadcast_to(resp[name][None], shape).copy(),
                           {"units": units, "long_name": long_name})
    coords = {
        "height": ("height", z, {"units": "m", "long_name": "asperity peak height"}),
        "curvature": ("curvature", k, {"units": "1/m", "long_name": "asperity peak curvature 1/R"}),
        "interference": ("interference", w, {"units": "m", "long_name": "interference (approach of the flat into the asperity)"}),
    }
    attrs = {
        "title": "Hertz asperities: elastic sphere on a rigid flat (report 6.1)",
        "youngs_modulus": float(E),
        "poisson": float(nu),
    }
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def _eccentricity(ratio: np.ndarray) -> np.ndarray:
    """e^2 of the contact ellipse of two principal curvatures whose ratio B/A >= 1 (Johnson,
    *Contact Mechanics*, 1985, 4.2): B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)), solved by
    bisection on m = e^2 (60 halvings: to round-off)."""
    from scipy.special import ellipe, ellipk

    ratio = np.asarray(ratio, dtype=float)
    lo, hi = np.zeros(ratio.shape), np.full(ratio.shape, 1.0 - 1e-15)
    for _ in range(60):  # halvings of the bracket, all ellipses at once
        m = 0.5 * (lo + hi)
        k, e = ellipk(m), ellipe(m)
        with np.errstate(divide="ignore", invalid="ignore"):
            value = (e / (1.0 - m) - k) / (k - e)
        low = ~(value >= ratio)  # B/A grows with m from 1 at m = 0
        lo, hi = np.where(low, m, lo), np.where(low, hi, m)
    return np.where(ratio <= 1.0 + 1e-12, 0.0, 0.5 * (lo + hi))


def elliptic_hertz(interference, curvature_1, curvature_2, contact_modulus) -> dict[str, np.ndarray]:
    """Hertz's elliptic contact of a body with principal curvatures kappa_1, kappa_2 at its
    tip on a rigid flat (Johnson, *Contact Mechanics*, 1985, 4.2, eqs. 4.35-4.40).

    With A = kappa_small / 2 <= B = kappa_large / 2 and the pressure
    p0 sqrt(1 - x^2/a^2 - y^2/b^2) on the ellipse of semi-axes a >= b, e^2 = 1 - b^2/a^2:

        B / A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)),
        w = A e^2 a^2 K(e) / (K(e) - E(e)),   p0 = A E* e^2 a^2 / (b (K(e) - E(e))),
        F = 2/3 pi a b p0,   contact area pi a b,   dF/dw = 3 F / (2 w),

    K, E the complete elliptic integrals of the first and second kind (parameter e^2).
    Equal curvatures give the circular Hertz of `hertz_response`.  Returns ``force``,
    ``contact_area``, ``stiffness``, ``semi_axis_a``, ``semi_axis_b`` (arrays; zero at w <= 0).
    """
    from scipy.special import ellipe, ellipk

    w = np.maximum(np.asarray(interference, dtype=float), 0.0)
    k1, k2 = np.asarray(curvature_1, dtype=float), np.asarray(curvature_2, dtype=float)
    if np.any(np.minimum(k1, k2) <= 0):
        raise ValueError("elliptic Hertz needs positive principal curvatures at the tip")
    small, large = np.minimum(k1, k2) / 2.0, np.maximum(k1, k2) / 2.0
    m = _eccentricity(large / small)
    k, e = ellipk(m), ellipe(m)
    circle = m == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        # w / a^2 for the ellipse; A (1/2R of the circle: w = a^2 / R = 2 A a^2) for the circle
        factor = np.where(circle, 2.0 * small, small * m * k / (k - e))
    a = np.sqrt(w / factor)
    b = a * np.sqrt(1.0 - m)
    with np.errstate(divide="ignore", invalid="ignore"):
        p0 = np.where(circle, 2.0 * contact_modulus * a * small * 2.0 / np.pi,
                      small * contact_modulus * m * a * a / (b * (k - e)))
    p0 = np.where(w > 0, p0, 0.0)
    force = 2.0 / 3.0 * np.pi * a * b * p0
    with np.errstate(divide="ignore", invalid="ignore"):
        stiffness = np.where(w > 0, 1.5 * force / w, 0.0)
    return {"force": force, "contact_area": np.pi * a * b, "stiffness": stiffness,
            "semi_axis_a": a, "semi_axis_b": b}
