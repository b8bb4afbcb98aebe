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

