"""The expectation over the summits of a Gaussian anisotropic surface (report 2.5.2).

Eq. (2.8) integrates a summit's response over its height, principal curvatures and
orientation with the density of `asperity.peaks.anisotropic`.  Against a flat the
normal response does not depend on the orientation, so the orientation is integrated
out of the density first (`AnisotropicDensity.nodes`), and the response is needed on
(height, kappa_1, t = kappa_2 / kappa_1) only.  At a separation h (the flat's height
above the mean plane) a summit of height z has the interference w = z - h, and per
unit nominal area

    p(h) = int F(z - h, kappa_1, kappa_2) n,    A/A0 = int A(...) n,
    -dp/dh = int dF/dw n,                       contacts = int_{z > h} n,

n the summit number density (summits per unit area times the density of eq. 2.8),
integrated over z > h with Gauss cells of their own at each separation, so that the
onset of contact at z = h is a cell edge.

The summit's law is self-similar: an elastic elliptic paraboloid of curvatures kappa_1
>= kappa_2 = t kappa_1 pressed by w obeys

    F = c_F(t) E* w^(3/2) / sqrt(kappa_1),   A = c_A(t) w / kappa_1,
    sqrt(a b) = c_r(t) sqrt(w / kappa_1),    dF/dw = 3 F / (2 w),

Hertz's elliptic contact (Johnson 1985, 4.2; `asperity.references.hertz.elliptic_hertz`)
giving c_F, c_A, c_r once per ratio (`elliptic_law`).  ``hertz`` takes the sphere of the
mean curvature (kappa_1 + kappa_2) / 2 instead: the isotropic route's asperity on the
anisotropic density, which separates the effect of the summits' shape from that of
their statistics.

``fe`` is the elliptic contact times a departure from Hertz (force and area ratios,
`with_departure`) of finite element asperities: of 3-D elliptic paraboloids computed at a
few curvature ratios (`asperity.population.kinds.elliptic`; the ratio of the J2 body to
the elastic one, interpolated in ln t: `asperity.stages.routes.elliptic_departure`), or
of an axisymmetric sphere (`asperity.stages.routes.sphere_departure`); both are read at
equal Hertz peak pressure:
the ellipse's p0 = 3 F / (2 pi a b) = (3 c_F / (2 c_A)) E* sqrt(w kappa_1) is a sphere's
p0 = (2 / pi) E* sqrt(w kappa) at the same w for kappa = (3 pi c_F / (4 c_A))^2
kappa_1 (`peak_pressure_curvature`; kappa_1 itself when t = 1).  First yield of a Hertz
contact is set by p0 (p0 = 1.6 Y for nu = 0.3; Johnson 1985, 4.2 and 6.2), so equal p0
puts the ellipse and the sphere at the same stage of yield; for a material without a
length of its own (elastic, J2) the sphere's departure is a function of w kappa alone.
The J2 sphere of equal p0 departs from Hertz as the 3-D J2 elliptic paraboloid of
t = 1/4 does from its elastic twin, within 2 % (tests/fe/test_elliptic_3d.py).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np
import xarray as xr

from asperity.homogenize.validity import EXTRAPOLATED_FORCE
from asperity.peaks.anisotropic import AnisotropicDensity
from asperity.units import attrs

#: the sum validity.assess turns into extrapolated_load_fraction
EXTRAPOLATED = f"{EXTRAPOLATED_FORCE}_per_unit_area"

__all__ = ["LAWS", "elliptic_law", "mean_curvature_law", "peak_pressure_curvature", "with_departure",
           "anisotropic_interface"]

#: the summit laws of the anisotropic route
LAWS = ("elliptic", "hertz", "fe")

#: law(w, kappa_1, t) -> (force, contact_area, stiffness, contact_radius[, beyond]), broadcasting;
#: beyond: True where the response was extrapolated past what was computed
Law = Callable[[np.ndarray, np.ndarray, np.ndarray], tuple]


def _unit_ellipse(t):
    """c_F, c_A and c_r of the module docstring at the curvature ratios t (shaped as t)."""
    from asperity.references.hertz import elliptic_hertz

    ratios, where = np.unique(np.asarray(t, dtype=float), return_inverse=True)
    unit = elliptic_hertz(np.ones(ratios.shape), np.ones(ratios.shape), ratios, 1.0)
    radius = np.sqrt(unit["semi_axis_a"] * unit["semi_axis_b"])
    return tuple(v[where].reshape(np.shape(t)) for v in (unit["force"], unit["contact_area"], radius))


def peak_pressure_curvature(k1, t):
    """The curvature of the sphere whose Hertz peak pressure at every interference is the
    elliptic contact's of curvatures kappa_1 and t kappa_1: (3 pi c_F / (4 c_A))^2 kappa_1
    (module docstring)."""
    c_f, c_a, _ = _unit_ellipse(t)
    return (3.0 * math.pi * c_f / (4.0 * c_a)) ** 2 * k1


def elliptic_law(contact_modulus: float) -> Law:
    """Hertz's elliptic contact of the summit's principal curvatures (module docstring)."""
    def law(w, k1, t):
        c_f, c_a, c_r = _unit_ellipse(t)
        w = np.maximum(w, 0.0)
        force = c_f * contact_modulus * w ** 1.5 / np.sqrt(k1)
        return force, c_a * w / k1, 1.5 * c_f * contact_modulus * np.sqrt(w / k1), c_r * np.sqrt(w / k1)

    return law


def mean_curvature_law(contact_modulus: float) -> Law:
    """Hertz's sphere of the summit's mean curvature kappa_1 (1 + t) / 2."""
    def law(w, k1, t):
        w = np.maximum(w, 0.0)
        radius = 2.0 / (k1 * (1.0 + t))
        force = 4.0 / 3.0 * contact_modulus * np.sqrt(radius) * w ** 1.5
        return force, math.pi * radius * w, 2.0 * contact_modulus * np.sqrt(radius * w), np.sqrt(radius * w)

    return law


def with_departure(base: Law, departure: Callable) -> Law:
    """`base` (``elliptic_law``) times a departure from Hertz read at equal Hertz peak
    pressure (module docstring): ``departure(s, t)`` gives the force and area ratios, the
    force ratio's slope in s and whether s lies past what was computed, at s = w
    `peak_pressure_curvature` and ratio t (a sphere's ignores t); the stiffness by the
    product rule, the contact radius with the square root of the area ratio. The law
    returns a fifth array, True where the departure was held past its computed range
    (`anisotropic_interface` counts the load there)."""
    def law(w, k1, t):
        w = np.maximum(w, 0.0)
        k = peak_pressure_curvature(k1, t)
        force, area, stiffness, radius = base(w, k1, t)
        rf, ra, drf, beyond = departure(w * k, t)
        return force * rf, area * ra, stiffness * rf + force * drf * k, radius * np.sqrt(ra), beyond

    return law


def anisotropic_interface(density: AnisotropicDensity, law: Law, separations,
                          yield_pressure: float = math.nan) -> xr.Dataset:
    """Nominal pressure, contact area ratio, stiffness and contact count of the summits of
    `density` against a flat at each separation [m] (module docstring), with the sums
    the validity of independent asperities takes (`asperity.homogenize.validity.assess`):
    the mean contact radius and, with a finite `yield_pressure` [Pa], the share of
    contacting summits whose mean contact pressure F/A exceeds it; where the law marks
    its extrapolated responses (a fifth array), the pressure they carry."""
    h = np.asarray(separations, dtype=float)
    names = ("nominal_pressure", "contact_area_ratio", "normal_stiffness", "contact_count",
             "contact_radius_per_unit_area", "yielded_per_unit_area", EXTRAPOLATED)
    out = {k: np.zeros(h.size) for k in names}
    extrapolates = False  # whether the law marks its extrapolated responses
    for i, hk in enumerate(h):  # one quadrature per separation (its own cells above z = h)
        z, k1, t, weight = density.nodes(above=hk)
        if not weight.size:
            continue
        force, area, stiffness, radius, *beyond = law(z[:, None, None] - hk, k1[None, :, None],
                                                      t[None, None, :])
        touching = (z[:, None, None] > hk) * np.ones(weight.shape)
        for name, value in (("nominal_pressure", force), ("contact_area_ratio", area),
                            ("normal_stiffness", stiffness), ("contact_count", touching),
                            ("contact_radius_per_unit_area", radius)):
            out[name][i] = float(np.sum(value * weight))
        if beyond:
            extrapolates = True
            out[EXTRAPOLATED][i] = float(np.sum(force * beyond[0] * weight))
        if math.isfinite(yield_pressure):
            out["yielded_per_unit_area"][i] = float(np.sum((force > yield_pressure * area) * weight))
    meta = {
        "nominal_pressure": ("Pa", "nominal pressure: the summits' force per unit nominal area (2.8)"),
        "contact_area_ratio": ("1", "real contact area ratio A/A0"),
        "normal_stiffness": ("Pa/m", "normal stiffness -dp/dh per unit nominal area"),
        "contact_count": ("1/m^2", "summits in contact per unit nominal area"),
        "contact_radius_per_unit_area": ("1/m", "sum of the contacts' radii sqrt(a b) per unit area"),
        "yielded_per_unit_area": ("1/m^2", "summits in contact with F/A above the yield pressure, "
                                  "per unit area"),
    }
    meta[EXTRAPOLATED] = ("Pa", "nominal pressure carried by summits past the computed departure "
                          "from Hertz (held there)")
    if not math.isfinite(yield_pressure):
        del out["yielded_per_unit_area"], meta["yielded_per_unit_area"]
    if not extrapolates:
        del out[EXTRAPOLATED], meta[EXTRAPOLATED]
    data = {k: ("separation", out[k], attrs(*meta[k])) for k in out}
    data["mean_gap"] = ("separation", h.copy(), attrs(
        "m", "mean gap: the separation (independent summits move no mean plane)"))
    ds = xr.Dataset(data, coords={"separation": ("separation", h, attrs(
        "m", "height of the flat above the mean plane of the surface"))})
    ds.attrs.update({"summit_density": density.summit_density, "quadrature_cells": str(density.cells),
                     "orientations": density.orientations})
    return ds
