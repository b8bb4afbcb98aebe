"""Asperity shapes: the top surface of the body as a profile z = f(r).

Every asperity is a protuberance of a deformable half space (report 3.3):
a hill of finite footprint (radius or half width `extent`) standing on a
block of bulk material whose top is flat at the hill's foot.  The profile
`surface(r)` gives the height of the undeformed top surface relative to the
apex, so ``surface(0) == 0`` and ``surface(r) <= 0``; beyond the footprint it
is constant (the flat top of the block).  The coordinate r is the radius for
a body of revolution (``axisymmetric=True``) and the distance from the
symmetry plane for a plane-strain section (``axisymmetric=False``).

The rigid flat starts touching the apex (first contact) and moves down by
the interference w; the surface can only touch it where ``surface(r) >= -w``
(the geometric intersection radius bounds the contact radius from above for
an elastic body, whose free surface only sinks under a compressive load).

All profiles are non-increasing in r; points where the profile has a kink
(`kinks`) are kept as mesh vertices.

The three-dimensional model (`solid3d`) reads the surface over the plane,
``surface_xy(x, y)`` (and ``body_surface_xy``, ``gap_offset_xy``): the profile at
r = hypot(x, y) for the bodies of revolution, the surface itself for the
`EllipticParaboloid`, which only that model takes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np


class Profile:
    """Common behaviour of asperity profiles (subclasses are frozen dataclasses)."""

    axisymmetric: bool
    #: shallow asperity: the body is the block under the tangent plane at the
    #: apex and the profile enters only through the initial gap (Hertz's
    #: half-space idealization); otherwise the body has the profile's shape.
    shallow: bool = False
    #: a short name used in records and hashes
    kind: ClassVar[str] = "profile"

    # --- to be provided by subclasses -----------------------------------
    @property
    def extent(self) -> float:
        """Radius (half width in plane strain) of the hill's footprint [m]."""
        raise NotImplementedError

    def _hill(self, r: np.ndarray) -> np.ndarray:
        """Profile on 0 <= r <= extent, relative to the apex."""
        raise NotImplementedError

    def _hill_slope(self, r: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    @property
    def kinks(self) -> tuple[float, ...]:
        """Radii where the profile is not smooth (kept as mesh vertices)."""
        return (self.extent,)

    # --- shared -----------------------------------------------------------
    @property
    def height(self) -> float:
        """Height of the apex above the foot of the hill [m]."""
        return float(-self._hill(np.array([self.extent]))[0])

    @property
    def length_scale(self) -> float:
        """The length the mesh and the computational block are sized by [m]."""
        return self.extent

    def surface(self, r) -> np.ndarray:
        """Height of the undeformed top surface above the apex (<= 0) [m]."""
        r = np.abs(np.asarray(r, dtype=float))
        inside = r <= self.extent
        return np.where(inside, self._hill(np.minimum(r, self.extent)), -self.height)

    def body_surface(self, r) -> np.ndarray:
        """Height of the top of the meshed body above the apex [m]."""
        if self.shallow:
            return np.zeros_like(np.asarray(r, dtype=float))
        return self.surface(r)

    def gap_offset(self, r) -> np.ndarray:
        """surface - body_surface: the part of the profile carried by the gap."""
        return self.surface(r) - self.body_surface(r)

    # --- the surface over the plane (the 3-D model, `solid3d`) ------------------
    def surface_xy(self, x, y) -> np.ndarray:
        """Height of the undeformed top surface at (x, y) above the apex [m]: the
        profile at r = hypot(x, y) for a body of revolution (overridden by
        `EllipticParaboloid`)."""
        return self.surface(np.hypot(x, y))

    def body_surface_xy(self, x, y) -> np.ndarray:
        """Height of the top of the meshed body at (x, y) above the apex [m]."""
        return self.body_surface(np.hypot(x, y))

    def gap_offset_xy(self, x, y) -> np.ndarray:
        """surface_xy - body_surface_xy: the part of the surface carried by the gap."""
        return self.gap_offset(np.hypot(x, y))

    def slope(self, r) -> np.ndarray:
        """d surface / d r."""
        r = np.abs(np.asarray(r, dtype=float))
        inside = r < self.extent
        return np.where(inside, self._hill_slope(np.minimum(r, self.extent)), 0.0)

    def intersection_radius(self, w) -> np.ndarray:
        """Radius where the undeformed surface meets the flat at interference w.

        Found by bisection (the profile is non-increasing), vectorized over w.
        Raises ``ValueError`` if the flat would reach the foot of the hill.
        """
        w = np.asarray(w, dtype=float)
        if np.any(w >= self.height):
            raise ValueError(
                f"interference {float(np.max(w)):.6g} m reaches the foot of the "
                f"hill (height {self.height:.6g} m); the flat would touch the block"
            )
        lo = np.zeros_like(w)
        hi = np.full_like(w, self.extent)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            above = self.surface(mid) >= -w
            lo = np.where(above, mid, lo)
            hi = np.where(above, hi, mid)
        return np.where(w > 0, 0.5 * (lo + hi), 0.0 * w)


def _check_positive(**values: float) -> None:
    for name, value in values.items():
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be positive and finite, got {value!r}")


@dataclass(frozen=True)
class CosineHill(Profile):
    """The report's asperity (2.5.1) as a body of revolution or a ridge.

    Profile z(r) = C cos(k r) for 0 <= r <= pi/k, i.e. from the peak down to
    the valley, so the peak is 2C above the valley and the tip curvature is
    kappa = C k^2 (as for z = C cos kx cos ky).  With ``axisymmetric=False``
    it is the plane-strain ridge z = C cos(k x).

    Width and height: the footprint diameter (valley to valley) is 2 pi / k
    and the height (peak to valley) is 2 C, so width / height = pi / (k C).
    """

    amplitude: float
    wavenumber: float
    axisymmetric: bool = True
    kind: ClassVar[str] = "cosine_hill"

    def __post_init__(self):
        _check_positive(amplitude=self.amplitude, wavenumber=self.wavenumber)

    @classmethod
    def from_aspect(cls, width_to_height: float, height: float,
                    axisymmetric: bool = True) -> "CosineHill":
        """Hill of a given peak-to-valley `height` and width/height ratio."""
        _check_positive(width_to_height=width_to_height, height=height)
        amplitude = 0.5 * height
        wavenumber = math.pi / (width_to_height * amplitude)
        return cls(amplitude, wavenumber, axisymmetric)

    @classmethod
    def from_tip(cls, tip_curvature: float, height: float,
                 axisymmetric: bool = True) -> "CosineHill":
        """Hill of peak-to-valley `height` with tip curvature kappa = C k^2."""
        _check_positive(tip_curvature=tip_curvature, height=height)
        amplitude = 0.5 * height
        return cls(amplitude, math.sqrt(tip_curvature / amplitude), axisymmetric)

    @property
    def tip_curvature(self) -> float:
        return self.amplitude * self.wavenumber**2

    @property
    def width_to_height(self) -> float:
        return math.pi / (self.wavenumber * self.amplitude)

    @property
    def extent(self) -> float:
        return math.pi / self.wavenumber

    @property
    def height(self) -> float:
        return 2.0 * self.amplitude

    def _hill(self, r):
        return self.amplitude * (np.cos(self.wavenumber * r) - 1.0)

    def _hill_slope(self, r):
        return -self.amplitude * self.wavenumber * np.sin(self.wavenumber * r)

    @property
    def kinks(self):
        return ()  # smooth: zero slope at the valley


@dataclass(frozen=True)
class Sphere(Profile):
    """A spherical cap of radius R on the block (report 6.1).

    The cap covers the polar angles up to `cap_angle_deg` (default 45 deg),
    i.e. r <= R sin(cap angle); the mesh is a region around the contact
    zone with a fixed far boundary, as in the report.
    """

    radius: float
    cap_angle_deg: float = 45.0
    axisymmetric: bool = True
    kind: ClassVar[str] = "sphere"

    def __post_init__(self):
        _check_positive(radius=self.radius)
        if not 0 < self.cap_angle_deg < 90:
            raise ValueError("cap_angle_deg must lie in (0, 90)")

    @property
    def extent(self) -> float:
        return self.radius * math.sin(math.radians(self.cap_angle_deg))

    def _hill(self, r):
        return np.sqrt(self.radius**2 - r**2) - self.radius

    def _hill_slope(self, r):
        return -r / np.sqrt(self.radius**2 - r**2)


@dataclass(frozen=True)
class Paraboloid(Profile):
    """The paraboloid z = -r^2 / (2 R): the shape Hertz theory assumes.

    By default (``shallow=True``) exactly Hertz's idealization: the elastic
    body is the half space under the tangent plane at the apex and the
    paraboloid is the initial gap to the flat, so the model converges to
    the Hertz solution.  With ``shallow=False`` the body itself has the
    paraboloid's shape: a hill out to r = `cap_ratio` * R (default 0.5,
    where the slope is 0.5) standing on the block; it is more compliant
    than the half space (about 0.5-1 % in load at a / R = 0.03-0.14).
    """

    radius: float
    cap_ratio: float = 0.5
    axisymmetric: bool = True
    shallow: bool = True
    kind: ClassVar[str] = "paraboloid"

    def __post_init__(self):
        _check_positive(radius=self.radius, cap_ratio=self.cap_ratio)

    @property
    def extent(self) -> float:
        return self.cap_ratio * self.radius

    def _hill(self, r):
        return -0.5 * r**2 / self.radius

    def _hill_slope(self, r):
        return -r / self.radius


@dataclass(frozen=True)
class EllipticParaboloid(Profile):
    """The elliptic paraboloid z = -(kappa_1 x^2 + kappa_2 y^2) / 2 (three-dimensional
    model only, `solid3d`): the tip of a body with principal curvatures kappa_1 along x
    and kappa_2 along y, the shape of Hertz's elliptic contact (Johnson, *Contact
    Mechanics*, 1985, 4.2).  Its principal axes are x and y, so y = 0 stays a plane of
    symmetry of the half model.

    By default (``shallow=True``) Hertz's idealization, as `Paraboloid`: the body is the
    block under the tangent plane at the apex and the paraboloid is the initial gap to
    the flat.  With ``shallow=False`` the body has the paraboloid's shape down to the
    height h = cap_ratio^2 / (2 kappa_min) of `Paraboloid`'s cap (cap_ratio R with R =
    1 / kappa_min along the long axis), on a block flat at that height: the footprint is
    the ellipse of semi-axes sqrt(2 h / kappa_1), sqrt(2 h / kappa_2).

    The profile of r (`surface`, `intersection_radius`, `extent`, `height`) is the
    section along the axis of the smaller curvature kappa_min, the long axis of the
    contact ellipse: `intersection_radius` is the long semi-axis of the ellipse where the
    undeformed surface meets the flat, and `extent` the footprint's long semi-axis.  The
    3-D model reads the surface over the plane, `surface_xy`, `body_surface_xy` and
    `gap_offset_xy`.  (The axisymmetric and plane-strain drivers read only the profile of
    r: they would model the long axis's section, not this body.)
    """

    curvature_1: float
    curvature_2: float
    cap_ratio: float = 0.5
    shallow: bool = True
    axisymmetric: ClassVar[bool] = False
    kind: ClassVar[str] = "elliptic_paraboloid"

    def __post_init__(self):
        _check_positive(curvature_1=self.curvature_1, curvature_2=self.curvature_2,
                        cap_ratio=self.cap_ratio)

    @property
    def curvature_min(self) -> float:
        return min(self.curvature_1, self.curvature_2)

    @property
    def extent(self) -> float:
        return self.cap_ratio / self.curvature_min

    def _hill(self, r):
        return -0.5 * self.curvature_min * r**2

    def _hill_slope(self, r):
        return -self.curvature_min * r

    def contact_semi_axes(self, long_semi_axis: float) -> tuple[float, float]:
        """The semi-axes (along x, along y) of the Hertz contact ellipse whose long
        semi-axis is `long_semi_axis`: its aspect b / a = sqrt(1 - e^2) depends only on
        kappa_2 / kappa_1 (Johnson 1985, 4.2, eq. 4.39; `references.hertz`), the long
        axis along the smaller curvature."""
        from asperity.references.hertz import _eccentricity

        ratio = max(self.curvature_1, self.curvature_2) / self.curvature_min
        short = float(long_semi_axis) * math.sqrt(1.0 - float(_eccentricity(ratio)))
        long_ = float(long_semi_axis)
        return (long_, short) if self.curvature_1 <= self.curvature_2 else (short, long_)

    def surface_xy(self, x, y) -> np.ndarray:
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        z = -0.5 * (self.curvature_1 * x**2 + self.curvature_2 * y**2)
        return np.maximum(z, -self.height)

    def body_surface_xy(self, x, y) -> np.ndarray:
        if self.shallow:
            return np.zeros(np.broadcast_shapes(np.shape(x), np.shape(y)))
        return self.surface_xy(x, y)

    def gap_offset_xy(self, x, y) -> np.ndarray:
        return self.surface_xy(x, y) - self.body_surface_xy(x, y)


@dataclass(frozen=True)
class Cylinder(Sphere):
    """A cylinder of radius R pressed along its generator (plane strain).

    The section is a circular cap (angles up to `cap_angle_deg`) on the block;
    quantities are per unit length of the cylinder.
    """

    axisymmetric: bool = False
    kind: ClassVar[str] = "cylinder"


@dataclass(frozen=True)
class TruncatedV(Profile):
    """The truncated V ridge of report 6.2 (plane strain by default).

    The report machined V grooves of included angle 45 deg (pitch 0.1 in,
    depth 0.125 in: 2 atan(0.05 / 0.125) = 43.6 deg) and truncated the
    ridges between them (its Fig. 6.8b).  The ridge has a flat top of half
    width `top_half_width` and flanks of included angle
    `included_angle_deg` (each flank at half that angle from the vertical)
    down to the valley `ridge_height` below the top.  The flat first
    touches the whole top at once; its corners are kept as mesh vertices.
    """

    top_half_width: float
    ridge_height: float
    included_angle_deg: float = 45.0
    axisymmetric: bool = False
    kind: ClassVar[str] = "truncated_v"

    def __post_init__(self):
        _check_positive(top_half_width=self.top_half_width, height=self.ridge_height)
        if not 0 < self.included_angle_deg < 180:
            raise ValueError("included_angle_deg must lie in (0, 180)")

    @property
    def flank_slope(self) -> float:
        """|dz/dx| of the flanks."""
        return 1.0 / math.tan(math.radians(0.5 * self.included_angle_deg))

    @property
    def extent(self) -> float:
        return self.top_half_width + self.ridge_height / self.flank_slope

    @property
    def height(self) -> float:
        return self.ridge_height

    def _hill(self, r):
        return -self.flank_slope * np.maximum(r - self.top_half_width, 0.0)

    def _hill_slope(self, r):
        return np.where(r > self.top_half_width, -self.flank_slope, 0.0)

    @property
    def kinks(self):
        return (self.top_half_width, self.extent)

    def intersection_radius(self, w):
        w = np.asarray(w, dtype=float)
        return np.maximum(super().intersection_radius(w), self.top_half_width)

