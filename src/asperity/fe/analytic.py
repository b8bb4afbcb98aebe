"""Closed-form references: Hertz contact of a paraboloid and of a cylinder."""

from __future__ import annotations

import numpy as np

from asperity.references.hertz import hertz_response, plane_strain_modulus


def hertz(radius: float, E: float, nu: float, interference) -> dict[str, np.ndarray]:
    """Hertz (report 6.1) for a paraboloid of radius R, from `asperity.references.hertz`.

    Returns contact_radius [m], contact_area [m^2], force [N] and
    normal_stiffness dP/dw = 2 E' r [N/m].
    """
    r = hertz_response(np.asarray(interference, dtype=float), 1.0 / radius, E, nu)
    return dict(contact_radius=r["contact_radius"], contact_area=r["contact_area"],
                force=r["force"], normal_stiffness=r["stiffness"])


def hertz_line_half_width(radius: float, E: float, nu: float, force_per_length) -> np.ndarray:
    """Half width of the contact of a cylinder: b = sqrt(4 P R / (pi E'))."""
    Es = plane_strain_modulus(E, nu)
    return np.sqrt(4 * np.asarray(force_per_length, dtype=float) * radius / (np.pi * Es))
