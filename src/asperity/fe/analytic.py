"""Closed-form references: Hertz contact of a paraboloid and of a cylinder."""

from __future__ import annotations

import numpy as np


def hertz(radius: float, E: float, nu: float, interference) -> dict[str, np.ndarray]:
    """Hertz (report 6.1): r = sqrt(R w), A = pi R w, P = 4/3 E/(1-nu^2) R^1/2 w^3/2.

    Returns contact_radius [m], contact_area [m^2], force [N] and
    normal_stiffness dP/dw = 2 E' r [N/m].
    """
    w = np.asarray(interference, dtype=float)
    Es = E / (1 - nu**2)
    wp = np.maximum(w, 0.0)
    a = np.sqrt(radius * wp)
    return dict(
        contact_radius=a,
        contact_area=np.pi * a**2,
        force=4.0 / 3.0 * Es * np.sqrt(radius) * wp**1.5,
        normal_stiffness=2 * Es * a,
    )


def hertz_line_half_width(radius: float, E: float, nu: float, force_per_length) -> np.ndarray:
    """Half width of the contact of a cylinder: b = sqrt(4 P R / (pi E'))."""
    Es = E / (1 - nu**2)
    return np.sqrt(4 * np.asarray(force_per_length, dtype=float) * radius / (np.pi * Es))
