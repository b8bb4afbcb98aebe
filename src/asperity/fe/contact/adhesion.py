"""Lennard-Jones adhesion on the free surface (report 3.3.2, 3.3.3, 3.4.1).

The law (report eq. 3.16, after Muller, Derjaguin and Toporov): two
surfaces at separation s attract each other with the pressure

    q(s) = 8 dgamma / (3 d) [(d / s)^3 - (d / s)^9],

dgamma the surface energy of adhesion (3.17) and d the intermolecular
distance (0.3-0.5 nm).  q vanishes at the equilibrium spacing s = d, is
repulsive below it, and peaks at s = 3^(1/6) d with q_max = 16 dgamma /
(9 sqrt(3) d) = 1.026 dgamma / d.  Its integral from the equilibrium
spacing is the work of adhesion,

    W(h) = int_h^inf q ds = (4 dgamma / 3) (d / h)^2 - (dgamma / 3) (d / h)^8,
    W(d) = dgamma.

How it joins the contact law
----------------------------
The separation of report 3.3.2, s = (x + u - p_o) . N - w - d, counts
from the equilibrium spacing: a point "touches" the flat when its physical
separation is d.  With the solver's penetration a (`asperity.fe.contact.penalty`,
a = -gap, the flat first touching the apex at w = 0 with the tip at the
equilibrium spacing d), the physical separation is s = d - a and the
normal traction on the surface (positive compressive, as in
`asperity.fe.contact.penalty`) is

    t(a) = C1 penalty t_N(a)      a >= 0     (contact, report 3.3.2)
           -q(d - a)              a < 0, d - a < s_c   (adhesion, 3.16)
           0                      d - a >= s_c          (beyond the cut-off)

Both branches vanish at a = 0 (q(d) = 0), so the traction is continuous;
its slope jumps there from q'(d) = 16 dgamma / d^2 (adhesive side) to 0
(the C1 penalty starts with zero slope).  The repulsive branch s < d of
3.16 is replaced by the penalty: the two surfaces cannot come closer than
d, up to the penalty's penetration.  The tangent of the adhesive branch is
dt/da = q'(s) = 8 dgamma / (3 d^2) [9 (d/s)^10 - 3 (d/s)^4]
= 8 dgamma / (d s) [3 (d/s)^9 - (d/s)^3], the report's alpha of 3.4.1 and
the beta of its Newton matrix (3.30), whose right-hand side q_i is this
traction (3.32) (both printed with the separation written as a).

Cohesive zone at the contact edge: where an adhesive contact holds, the
traction is the penalty's inside and -q outside; the ring where q acts
is sqrt(2 R d) wide for a stiff sphere and shrinks to the cohesive length
E* dgamma / q_max^2 (`process_zone`) for a compliant one.

Cut-off: the report integrates only where s < 4 d (3.4.1) because q is
"practically zero" beyond.  The traction is, but the work is not: the
tail beyond s_c carries W(s_c) ~ (4/3) (d / s_c)^2 dgamma, 8.3 % of dgamma
at s_c = 4 d, and a DMT pull-off 2 pi R W(d) would come out 8 % low.  The
cut-off is therefore a parameter (``cutoff`` = s_c / d), default
`DEFAULT_CUTOFF` = 16 (0.52 % of the work left out); ``cutoff=4``
reproduces the report.  Everything closed-form here is for the truncated
law: W_c(h) = W(h) - W(s_c) for h < s_c.

Rigid sphere (Derjaguin, exact for a paraboloid): a rigid paraboloid of
radius R at tip separation h from the flat is pulled by
F(h) = 2 pi R W_c(h) (`derjaguin_force`).  The Tabor parameter
mu = (R dgamma^2 / (E*^2 z0^3))^(1/3) is taken with z0 = d, the law's
equilibrium spacing.

Surface quadrature (3.4.1): q changes by orders of magnitude over a few d
of separation, so it is integrated with its own rule: every facet of the
candidate zone gets a composite Gauss rule (`composite_gauss`:
`subdivisions` equal parts of `gauss_points` points, default 2 x 5 = the
report's 10 points per direction), while the penalty keeps its nodal rule.
With the adhesive mesh graded to the ring (`asperity.fe.drivers.adhesive_model`) the
separation varies by a fraction of d across a facet; convergence of the
rule is tested (tests/fe/test_adhesion.py).  Points beyond the cut-off
contribute exactly zero (they are evaluated, which costs little, rather
than skipped).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from asperity.fe.contact.penalty import ContactZone

#: cut-off separation / d beyond which the adhesion is dropped (see module docstring)
DEFAULT_CUTOFF = 16.0
#: q_max d / dgamma = 16 / (9 sqrt 3)
PEAK_FACTOR = 16.0 / (9.0 * math.sqrt(3.0))


@dataclass(frozen=True)
class LennardJones:
    """The adhesion law 3.16: dgamma [J/m^2], d [m], cut-off s_c = cutoff * d."""

    dgamma: float
    d: float
    cutoff: float = DEFAULT_CUTOFF

    def __post_init__(self):
        for name in ("dgamma", "d"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be positive and finite, got {value!r}")
        if not (np.isfinite(self.cutoff) and self.cutoff > 1.5):
            raise ValueError(f"cutoff (s_c / d) must exceed 1.5, got {self.cutoff!r}")

    # --- the law of separation s ---------------------------------------------
    @property
    def range(self) -> float:
        """Cut-off separation s_c [m]."""
        return self.cutoff * self.d

    @property
    def peak_pressure(self) -> float:
        """q_max = 16 dgamma / (9 sqrt(3) d) [Pa], at s = 3^(1/6) d."""
        return PEAK_FACTOR * self.dgamma / self.d

    def pressure(self, s, truncated: bool = True) -> np.ndarray:
        """q(s) of eq. 3.16 [Pa] (attractive positive); zero beyond the cut-off."""
        s = np.asarray(s, dtype=float)
        x = self.d / s
        q = 8.0 * self.dgamma / (3.0 * self.d) * (x**3 - x**9)
        return np.where(s < self.range, q, 0.0) if truncated else q

    def pressure_slope(self, s, truncated: bool = True) -> np.ndarray:
        """dq/ds = 8 dgamma / (3 d^2) [9 (d/s)^10 - 3 (d/s)^4] [Pa/m] (report 3.4.1)."""
        s = np.asarray(s, dtype=float)
        x = self.d / s
        dq = 8.0 * self.dgamma / (3.0 * self.d**2) * (9.0 * x**10 - 3.0 * x**4)
        return np.where(s < self.range, dq, 0.0) if truncated else dq

    def work(self, h, truncated: bool = True) -> np.ndarray:
        """W(h) = int_h^s_c q ds [J/m^2] (to infinity if not `truncated`); W(d) ~ dgamma."""
        h = np.asarray(h, dtype=float)

        def full(s):
            x = self.d / s
            return self.dgamma * (4.0 / 3.0 * x**2 - x**8 / 3.0)

        if not truncated:
            return full(h)
        return np.where(h < self.range, full(np.minimum(h, self.range)) - full(self.range), 0.0)

    @property
    def work_of_adhesion(self) -> float:
        """W_c(d): the work the truncated law gives back from contact [J/m^2]."""
        return float(self.work(self.d))

    # --- the traction of the solver (penetration a = -gap) ---------------------
    def traction(self, a: np.ndarray):
        """Adhesive part of the normal traction t(a) and dt/da (see module docstring).

        Compressive positive, so the attraction is negative; zero where the
        point is in contact (a >= 0, the penalty's) or beyond the cut-off.
        """
        a = np.asarray(a, dtype=float)
        out = a < 0
        s = self.d - np.where(out, a, -self.d)  # separation (> d where adhesive)
        t = np.where(out, -self.pressure(s), 0.0)
        dt = np.where(out, self.pressure_slope(s), 0.0)
        return t, dt

    def potential(self, a: np.ndarray) -> np.ndarray:
        """Phi(a) with Phi' = t and Phi(0) = 0: W_c(d) - W_c(d - a) for a < 0 [J/m^2]."""
        a = np.asarray(a, dtype=float)
        s = self.d - np.minimum(a, 0.0)
        return np.where(a < 0, self.work_of_adhesion - self.work(s), 0.0)

    # --- scales ---------------------------------------------------------------------
    def tabor_parameter(self, radius: float, contact_modulus: float) -> float:
        """mu = (R dgamma^2 / (E*^2 d^3))^(1/3), z0 = d (the equilibrium spacing)."""
        mu = (np.asarray(radius, dtype=float) * self.dgamma**2
              / (np.asarray(contact_modulus, dtype=float)**2 * self.d**3)) ** (1.0 / 3.0)
        return float(mu) if np.ndim(mu) == 0 else mu

    def process_zone(self, contact_modulus: float) -> float:
        """Cohesive length E* dgamma / q_max^2 [m]: the width over which the
        adhesion acts at the edge of a JKR-like contact (Maugis)."""
        lpz = np.asarray(contact_modulus, dtype=float) * self.dgamma / self.peak_pressure**2
        return float(lpz) if np.ndim(lpz) == 0 else lpz


def derjaguin_force(adhesion: LennardJones, radius: float, separation) -> np.ndarray:
    """Attraction 2 pi R W_c(h) [N] of a rigid paraboloid at tip separation h (exact)."""
    return 2.0 * np.pi * radius * adhesion.work(separation)


def composite_gauss(gauss_points: int = 5, subdivisions: int = 2):
    """Composite Gauss-Legendre rule on [0, 1]: (points, weights)."""
    if gauss_points < 1 or subdivisions < 1:
        raise ValueError("gauss_points and subdivisions must be positive")
    x, w = np.polynomial.legendre.leggauss(int(gauss_points))
    x, w = 0.5 * (x + 1.0), 0.5 * w
    k = np.arange(int(subdivisions))[:, None]
    xi = ((k + x[None, :]) / subdivisions).ravel()
    wq = np.broadcast_to(w[None, :] / subdivisions, (int(subdivisions), len(w))).ravel()
    return xi, wq.copy()


def adhesion_zone(top, nfacets: int, geometry, gauss_points: int = 5,
                  subdivisions: int = 2) -> ContactZone:
    """The candidate facets with the composite Gauss rule for the adhesive traction."""
    return ContactZone(top, nfacets, geometry, rule=composite_gauss(gauss_points, subdivisions))
