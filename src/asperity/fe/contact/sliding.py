"""Sliding resistance of the contact junction (report 3.3.4 and 3.4.1).

Interfacial shear strength (Francis' quadratic fit, report eq. 3.21)

    tau_s = h(sigma_n) = c0 + c1 sigma_n + c2 sigma_n^2,

with sigma_n >= 0 the normal contact pressure (the penalty traction t_N of
3.3.2).  A "friction coefficient" mu is the law c0 = c2 = 0, c1 = mu (the
Coulomb law; the sliding study of report 9.2 uses mu = 20 to model the
shear strength of a metallic junction).  Off contact (sigma_n = 0) there is
no shear: the constant c0 is switched on over the pressures
0 <= sigma_n <= ``onset_pressure`` by the C1 ramp phi of (3.25), so that
h(0) = 0 and h is C1 in sigma_n (with c0 = 0 the ramp does nothing).

Tangential traction (3.24): t = h(t_N) b / |b| for a relative tangential
displacement b != 0 of the asperity point against the flat (t = 0 at
b = 0), discontinuous at b = 0.  The report's C1 regularization (3.25)

    phi(x) = -1                            x <= -eps_b
             2 x / eps_b + (x / eps_b)^2    -eps_b <= x < 0
             2 x / eps_b - (x / eps_b)^2    0 <= x <= eps_b
             1                             eps_b <= x,

with components t_S = h phi(|b|) Psi_S, t_T = h phi(|b|) Psi_T along two
orthogonal directions S, T = N x S of the flat, Psi = b / |b|.  Here the
traction the flat exerts *on the body* opposes the body's slip:

    t = -h(t_N) phi(|b|) b / |b| = -h(t_N) g(|b|) b,
    g(r) = phi(r) / r = 2 / eps_b - r / eps_b^2  (r < eps_b),  1 / r  (r >= eps_b),

which is finite and continuous at b = 0 (g(0) = 2 / eps_b: a stiff linear
"stick" spring of stiffness 2 h / eps_b), the exact h b / |b| for
|b| >= eps_b, and C1 in b (d g / d r b b^T / r -> 0 as b -> 0).  Its
linearization (3.26, 3.27) is

    d t / d b   = -h [g I + g'(r) b b^T / r],
    d t / d t_N = -h'(t_N) g b,

with g' = -1 / eps_b^2 (r < eps_b) or -1 / r^2.  The full 3 x 3 contact
tangent alpha_ij of (3.26, 3.27) adds the normal penalty stiffness
d t_N / d a on N N and couples t to the approach a through d t_N / d a
(`contact_tangent`).

Slip history.  The report writes b as the total relative displacement,
which makes the law path independent: on a reversal the traction would not
turn until b has come back through zero.  Here b is measured from an
anchor (the point of the flat the material point sticks to), per contact
point: b = (x + u) - delta - anchor in the frame of the flat.  Within a
step the law above is used as printed; when the step is accepted the
anchor is dragged (`drag_anchor`): to the current position off contact
(t_N = 0, so a point touching anew starts unstrained), and to |b| = eps_b
where the point slides (|b| > eps_b), which leaves the traction unchanged
(phi = 1 there).  A reversal of the sliding then turns the traction after
a relative displacement of 2 eps_b, and the law is still C1 in b within
every step (the regularized Coulomb law with an elastic-slip split).

Arrays: b is (2, ...), t_N (...), all vectorized elementwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def regularized_sign(x, eps: float):
    """phi(x) of report (3.25) and d phi / dx, elementwise (eps > 0)."""
    if not eps > 0:
        raise ValueError(f"the regularization eps_b must be positive, got {eps!r}")
    x = np.asarray(x, dtype=float)
    s = x / eps
    inside = np.abs(s) < 1.0
    phi = np.where(inside, 2.0 * s - s * np.abs(s), np.sign(s))
    dphi = np.where(inside, (2.0 - 2.0 * np.abs(s)) / eps, 0.0)
    return phi, dphi


@dataclass(frozen=True)
class ShearResistance:
    """tau_s = c0 + c1 sigma_n + c2 sigma_n^2 (report 3.21), zero off contact.

    c0 [Pa], c1 [1], c2 [1/Pa]; ``onset_pressure`` [Pa]: the c0 term is
    ramped in by phi(sigma_n / onset_pressure) (3.25) so that h(0) = 0 and
    h is C1 (only used when c0 != 0).  The law must not be negative for
    sigma_n >= 0 up to the pressures reached (c0, c1 >= 0 is required; a
    negative c2 saturates it and is the caller's responsibility).
    """

    c0: float = 0.0
    c1: float = 0.0
    c2: float = 0.0
    onset_pressure: float = 1.0e6

    def __post_init__(self):
        for name in ("c0", "c1", "c2", "onset_pressure"):
            v = getattr(self, name)
            if not math.isfinite(v):
                raise ValueError(f"shear resistance {name} must be finite, got {v!r}")
        if self.c0 < 0 or self.c1 < 0:
            raise ValueError(f"c0 and c1 must be >= 0, got c0={self.c0!r}, c1={self.c1!r}")
        if not self.onset_pressure > 0:
            raise ValueError("onset_pressure must be positive")

    @classmethod
    def coulomb(cls, mu: float) -> "ShearResistance":
        """A friction coefficient: tau_s = mu sigma_n."""
        return cls(c0=0.0, c1=float(mu), c2=0.0)

    @property
    def frictionless(self) -> bool:
        return self.c0 == 0.0 and self.c1 == 0.0 and self.c2 == 0.0

    def __call__(self, sigma_n):
        """h(sigma_n) and dh / d sigma_n, elementwise; both 0 for sigma_n <= 0."""
        s = np.asarray(sigma_n, dtype=float)
        on = s > 0
        sp = np.where(on, s, 0.0)
        h = self.c1 * sp + self.c2 * sp * sp
        dh = np.where(on, self.c1 + 2.0 * self.c2 * sp, 0.0)
        if self.c0 != 0.0:
            phi, dphi = regularized_sign(sp, self.onset_pressure)
            h = h + self.c0 * phi
            dh = dh + np.where(on, self.c0 * dphi, 0.0)
        return h, dh


@dataclass(frozen=True)
class FrictionLaw:
    """Regularized sliding resistance (3.24, 3.25) with the law h of (3.21).

    ``slip_regularization`` is eps_b [m]: the relative displacement over
    which the traction builds up to h (the stick stiffness is 2 h / eps_b).
    """

    resistance: ShearResistance
    slip_regularization: float

    def __post_init__(self):
        if not (math.isfinite(self.slip_regularization) and self.slip_regularization > 0):
            raise ValueError(f"slip_regularization (eps_b) must be positive, got "
                             f"{self.slip_regularization!r}")

    @property
    def frictionless(self) -> bool:
        return self.resistance.frictionless

    def direction(self, b):
        """The regularized direction phi(|b|) b / |b| (2, ...) of (3.24, 3.25)
        (length < 1 for |b| < eps_b, 0 at b = 0)."""
        g, _ = self._g(b)
        return g * np.asarray(b, float)

    def _g(self, b):
        eps = self.slip_regularization
        b = np.asarray(b, dtype=float)
        r = np.sqrt(b[0] ** 2 + b[1] ** 2)
        stick = r < eps
        rs = np.where(stick, 1.0, r)
        g = np.where(stick, 2.0 / eps - r / eps**2, 1.0 / rs)
        # g'(r) / r, the factor of b b^T (finite at r = 0, where b b^T = 0)
        gpr = np.where(stick, -1.0 / (eps**2 * np.where(r > 0, r, 1.0)), -1.0 / rs**3)
        gpr = np.where(r > 0, gpr, 0.0)
        return g, gpr

    def traction(self, b, t_n):
        """Tangential traction on the body and its derivatives.

        b (2, ...) relative tangential displacement of the body against the
        flat, t_n (...) the normal pressure.  Returns ``(t, dt_db, dt_dtn)``:
        t (2, ...) = -h(t_N) phi(|b|) b / |b|, dt_db (2, 2, ...) (3.26,
        3.27: the S S, S T, T S, T T terms), dt_dtn (2, ...).
        """
        b = np.asarray(b, dtype=float)
        h, dh = self.resistance(t_n)
        g, gpr = self._g(b)
        t = -h * g * b
        eye = np.eye(2).reshape((2, 2) + (1,) * (b.ndim - 1))
        bb = b[:, None] * b[None, :]
        dt_db = -h * (g * eye + gpr * bb)
        dt_dtn = -dh * g * b
        return t, dt_db, dt_dtn

    def report_components(self, b_s, b_t, t_n):
        """(t_S, t_T) exactly as printed in 3.4.1: h(t_N) phi(|b|) Psi_S, Psi_T
        (the sign of the report: along b), for comparison."""
        b = np.stack((np.asarray(b_s, float), np.asarray(b_t, float)))
        t, _, _ = self.traction(b, t_n)
        return -t[0], -t[1]


def contact_tangent(dtn_da, dt_db, dt_dtn):
    """alpha_ij of (3.26, 3.27) in the global frame (x, y along the flat, z
    up; the flat's normal N = -e_z points into the body): the derivative of
    the traction vector on the body (t_x, t_y, -t_N) with respect to the
    displacement (u_x, u_y, u_z) of the body point, for a penetration
    a = z + u_z + w and slip b = (x + u_x - delta, y + u_y) - anchor.
    Shapes: dtn_da (...), dt_db (2, 2, ...), dt_dtn (2, ...) -> (3, 3, ...)."""
    dtn_da = np.asarray(dtn_da, float)
    A = np.zeros((3, 3) + dtn_da.shape)
    A[:2, :2] = dt_db
    A[:2, 2] = dt_dtn * dtn_da
    A[2, 2] = -dtn_da
    return A


def drag_anchor(anchor, position, t_n, eps: float):
    """The anchors after an accepted step (see the module docstring).

    anchor, position (2, ...): where each contact point sticks on the flat
    and where it is now (both in the flat's frame); t_n (...): its normal
    pressure.  Off contact the anchor follows the point; a sliding point
    (|b| > eps) drags its anchor to |b| = eps; a sticking one keeps it.
    """
    anchor = np.asarray(anchor, float)
    position = np.asarray(position, float)
    b = position - anchor
    r = np.sqrt(b[0] ** 2 + b[1] ** 2)
    slide = r > eps
    new = np.where(slide, position - eps * b / np.where(slide, r, 1.0), anchor)
    return np.where(np.asarray(t_n) > 0, new, position)
