"""The closed forms of an adhesive sphere: the JKR contact and jump-off, and the
Maugis-Dugdale pull-off (report 3.4.1; Johnson, Kendall and Roberts, Proc. R. Soc.
Lond. A 324 (1971) 301; Maugis, J. Colloid Interface Sci. 150 (1992) 243).

They size the adhesive finite element model's mesh (`asperity.fe.drivers.adhesive_model`) and
are what its jump-off and pull-off are checked against.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq, minimize_scalar


def jkr_contact_radius(radius: float, contact_modulus: float, work: float, w: float) -> float:
    """JKR contact radius at interference w: a^2 / R - sqrt(2 pi a work / E*) = w."""
    g = lambda a: a**2 / radius - math.sqrt(2 * math.pi * a * work / contact_modulus) - w
    lo, hi = 0.0, max(math.sqrt(radius * max(w, 0.0)), 1e-30)
    while g(hi) < 0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0 else (lo, mid)
    return hi


def jkr_jump_off(tabor_parameter: float, d: float) -> float:
    """JKR's jump-off interference under displacement control: the fold of
    w(a) = a^2 / R - sqrt(2 pi a W / E*) (`jkr_contact_radius`), at
    a^3 = pi W R^2 / (8 E*), where w = -3 a^2 / R = -(3/4) pi^(2/3) mu d with
    the Tabor parameter mu = (R W^2 / (E*^2 d^3))^(1/3) (report 3.4.1)."""
    return -0.75 * math.pi ** (2 / 3) * tabor_parameter * d


def maugis_pull_off(lam: float) -> float:
    """Pull-off force of the Maugis-Dugdale sphere over pi W R: from 2 (DMT,
    lam -> 0) to 3/2 (JKR, lam -> infinity).

    Maugis (J. Colloid Interface Sci. 150 (1992) 243) in the notation of
    Johnson and Greenwood (J. Colloid Interface Sci. 192 (1997) 326): with
    A = a (4 E* / (3 pi W R^2))^(1/3), P = F / (pi W R), m = c / a (c the
    edge of the cohesive zone) and s = sqrt(m^2 - 1),

        lam A^2 / 2 [s + (m^2 - 2) arctan s]
            + 4 lam^2 A / 3 [s arctan s - m + 1] = 1,
        P = A^3 - lam A^2 [s + m^2 arctan s];

    the pull-off is -min P over A, the most tensile force of the curve
    (reached under displacement control too).  For a Lennard-Jones law
    lam = 1.16 mu, mu the Tabor parameter (Johnson and Greenwood 1997).
    """
    def m_of(A):  # the cohesive zone of a contact radius A (f rises from -1 at m = 1)
        def f(m):
            q = math.sqrt(m * m - 1.0)
            at = math.atan(q)
            return (lam * A * A / 2 * (q + (m * m - 2) * at)
                    + 4 * lam * lam * A / 3 * (q * at - m + 1) - 1.0)
        hi = 2.0
        while f(hi) < 0:
            hi = 1.0 + 2.0 * (hi - 1.0)
        return brentq(f, 1.0, hi, xtol=1e-15, rtol=1e-15)

    def load(A):
        m = m_of(A)
        q = math.sqrt(m * m - 1.0)
        return A**3 - lam * A * A * (q + m * m * math.atan(q))

    grid = np.geomspace(1e-4, 10.0, 500)
    k = int(np.argmin([load(A) for A in grid]))
    best = minimize_scalar(load, bounds=(grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]),
                           method="bounded", options=dict(xatol=1e-12))
    return -float(best.fun)
