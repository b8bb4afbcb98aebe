"""The elastic-plastic sphere against a rigid flat: Kogut and Etsion's finite element fits.

Kogut, L. and Etsion, I., "Elastic-plastic contact analysis of a sphere and a rigid
flat", J. Appl. Mech. 69 (2002) 657-662. An elastic-perfectly plastic sphere (von
Mises, yield stress Y) of radius R pressed by w against a rigid flat yields first
below its surface at the critical interference

    w_c = (pi K H / (2 E*))^2 R,    K = 0.454 + 0.41 nu,    H = 2.8 Y,

where Hertz's load and area are P_c = (2/3) pi K H R w_c and A_c = pi R w_c. Their
finite element results, fitted in w / w_c (eqs. 11 and 12 of the paper):

    w / w_c <= 1:        P / P_c = (w / w_c)^1.5,          A / A_c = w / w_c (Hertz)
    1 <= w / w_c <= 6:   P / P_c = 1.03 (w / w_c)^1.425,   A / A_c = 0.93 (w / w_c)^1.136
    6 <= w / w_c <= 110: P / P_c = 1.40 (w / w_c)^1.263,   A / A_c = 0.94 (w / w_c)^1.146

independent of E / Y and nu in the ranges they computed. Past 110 w_c the sphere is
fully plastic (mean pressure about 2.8 Y); the fits stop there.
"""

from __future__ import annotations

import numpy as np

__all__ = ["critical_interference", "kogut_etsion"]

#: the largest w / w_c of the fits
FULLY_PLASTIC = 110.0


def _yield_pressure(poisson: float, yield_stress: float) -> float:
    """K H [Pa]: the largest Hertz pressure at first yield (module docstring)."""
    return (0.454 + 0.41 * poisson) * 2.8 * yield_stress


def critical_interference(radius: float, contact_modulus: float, poisson: float,
                          yield_stress: float) -> float:
    """w_c [m] of a sphere of `radius` [m] against a rigid flat (module docstring), with
    the contact modulus E* [Pa] and the sphere's Poisson ratio and yield stress [Pa]."""
    return (np.pi * _yield_pressure(poisson, yield_stress) / (2.0 * contact_modulus)) ** 2 * radius


def kogut_etsion(interference, radius: float, contact_modulus: float, poisson: float,
                 yield_stress: float) -> dict:
    """Force [N] and contact area [m^2] of the elastic-plastic sphere at `interference`
    [m] (module docstring), with ``w_c`` [m]; NaN past 110 w_c, where the fits stop."""
    w = np.asarray(interference, dtype=float)
    wc = critical_interference(radius, contact_modulus, poisson, yield_stress)
    pc = 2.0 / 3.0 * np.pi * _yield_pressure(poisson, yield_stress) * radius * wc
    ac = np.pi * radius * wc
    x = np.maximum(w, 0.0) / wc
    force = np.select([x <= 1.0, x <= 6.0, x <= FULLY_PLASTIC],
                      [x ** 1.5, 1.03 * x ** 1.425, 1.40 * x ** 1.263], np.nan) * pc
    area = np.select([x <= 1.0, x <= 6.0, x <= FULLY_PLASTIC],
                     [x, 0.93 * x ** 1.136, 0.94 * x ** 1.146], np.nan) * ac
    return {"force": force, "contact_area": area, "critical_interference": wc}
