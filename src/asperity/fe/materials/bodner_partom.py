"""Bodner-Partom elasto-viscoplasticity with hardening, recovery and damage.

Report section 3.2.2.  Strain rates split into elastic and nonelastic parts
(3.11), sigma_dot = C : (eps_dot - eps_n_dot) (3.12), and the flow rule

    eps_n_dot = lambda s,   lambda^2 = D0^2 / J2 exp[-(Z^2 (1 - w^2) / (3 J2))^n],

so that, with the Mises stress q = sqrt(3 J2), the equivalent inelastic
strain rate sqrt(2/3 eps_n_dot : eps_n_dot) is

    p_dot = (2 / sqrt 3) D0 exp[-1/2 (Z_eff / q)^(2 n)],   Z_eff = Z sqrt(1 - w^2)

(uniaxially p_dot = |eps_n_11_dot|).  The hardness Z = Z^I + Z^D is

- isotropic (3.13): Z^I_dot = m1 (Z1 - Z^I) W_p_dot - A1 Z1 ((Z^I - Z2) / Z1)^r1,
  Z^I(0) = Z0, with W_p_dot = sigma : eps_n_dot = q p_dot;
- directional (3.14): Z^D = beta : u, u = sigma / |sigma|,
  beta_dot = m2 (Z3 u - beta) W_p_dot - A2 Z1 (|beta| / Z1)^r2 beta / |beta|,
  beta(0) = 0;

and the isotropic damage w follows the rescaled form of (3.15)

    w_dot = p [ln(1/w)]^((p+1)/p) w (Q_hat / H_hat)^nu_d,
    Q_hat = A sigma_max^+ + B sqrt(3 J2) + C I1^+,  A + B + C = 1,

(the printed rescaled form lost the factor w of (3.15); without it w_dot is
infinite at w = 0).  With kappa = [ln(1/w)]^(-1/p) this is the linear

    kappa_dot = (p_hat / p) (Q_hat / H_hat)^nu_d,   w = exp(-kappa^(-p)),

which is what is integrated: it starts from w(0) = 0 (kappa = 0) as the
report says, it is not stiff, and w < 1 for every finite kappa (w -> 1 only
as kappa -> inf).  Rupture (report: w = 1) is therefore declared when w
reaches ``omega_rupture`` (kappa reaches kappa_r, the time interpolated
within the step), or, under a sustained load, when the damaged hardness
can no longer carry it: the equivalent inelastic strain rate passes
``rupture_strain_rate`` (the runaway of tertiary creep, which comes first
whenever Z sqrt(1 - w^2) falls to a few times the stress).  The damage is
then frozen, the point keeps a finite state, and ``ruptured`` and
``rupture_time`` record it (no numpy error, no NaN).  Directional damage (end of 3.2.2) is not
implemented (the report itself uses the isotropic part only).

Mechanisms are switched by flags, not by zero constants:
``isotropic_hardening`` (the m1 term), ``recovery`` (the A1 and A2 thermal
recovery terms), ``directional_hardening`` (beta, Z^D) and ``damage``.  With
all flags off Z = Z0 is constant.  The recovery term is taken odd,
sign(x)|x|^r1, so that Z^I recovers towards Z2 from either side.

Arrays follow `asperity.fe.materials.elastic`: strains and stresses are
``(4, *shape)`` with components (11, 22, 33, 12) and the tensor shear
component, tangents ``(4, 4, *shape)`` (d stress / d strain in the same
components, as ``LinearElastic.tangent``), or, for three-dimensional
bodies, ``(6, *shape)`` with components (11, 22, 33, 12, 13, 23) and
tangents ``(6, 6, *shape)``: every function decides by the first axis of
the strain (or stress) array, and the state carries the same number of
components (``initial_state(shape, components=6)``).  ``shape`` is that of the
quadrature points (e.g. (ne, nq), or () for one point).  Internally all
points are flattened and everything is vectorized (no loop over points);
tensors are handled in Mandel form (shear times sqrt 2) so that
contractions are dot products (`asperity.fe.materials.tensors`); the state
of the points is a `BPState` (`asperity.fe.materials.bodner_partom_state`).

Integrators:

- `BodnerPartom.update` (backward Euler, the FE one;
  `asperity.fe.materials.bodner_partom_implicit`): given the total strain at
  the end of the increment, the state at its start and dt, one scalar unknown
  per point, y = ln(c0 / dp) with dp the equivalent inelastic strain
  increment, and the consistent tangent by complex-step differentiation.
- `BodnerPartom.explicit` (`asperity.fe.materials.bodner_partom_explicit`):
  the report's Euler predictor / trapezoidal corrector with the error
  indicator (3.33)-(3.36) and per-point adaptive sub-stepping, the reference
  integrator.  It also takes mixed control (some stress components
  prescribed), which the uniaxial driver uses.

Units are SI: stresses and hardnesses in Pa, m1 and m2 in 1/Pa, rates in 1/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from asperity.fe.materials.bodner_partom_explicit import PredictorCorrector
from asperity.fe.materials.bodner_partom_implicit import BackwardEuler
from asperity.fe.materials.bodner_partom_state import BPState, quiet_underflow
from asperity.fe.materials.elastic import IsotropicElasticity
from asperity.fe.materials.tensors import (COMPONENTS, SQRT2, SQRT3, component_count,
                                           from_mandel, identity_like, largest_principal6,
                                           mandel_dot, signed_power, to_mandel, where_positive)

_MPA = 1.0e6


@dataclass(frozen=True)
class BodnerPartom(BackwardEuler, PredictorCorrector, IsotropicElasticity):
    """Bodner-Partom constants (SI) and switches (report 3.2.2).

    E [Pa], nu; D0 limiting shear strain rate [1/s]; n; Z0 initial hardness
    [Pa]; Z1 saturation hardness [Pa]; m1 [1/Pa]; Z2 minimum (recovered)
    hardness [Pa]; A1 [1/s]; r1; Z3 directional saturation [Pa]; m2 [1/Pa];
    A2 [1/s]; r2.  Damage (rescaled 3.15): damage_A, _B, _C (sum 1),
    damage_nu (the exponent nu), damage_p (p), damage_H (H_hat [Pa]),
    damage_rate (p_hat / p [1/s], 1 in the report's rescaling),
    omega_rupture (w at which rupture is declared), rupture_strain_rate
    [1/s] (with damage: rupture is also declared when the equivalent
    inelastic strain rate passes it, the runaway of tertiary creep under a
    sustained load, which comes before w reaches omega_rupture), damage_softening
    ``"report"`` (Z_eff = Z sqrt(1 - w^2), as printed) or ``"bodner"``
    (Z_eff = Z (1 - w), Bodner and Chan's form).
    """

    E: float
    nu: float
    D0: float
    n: float
    Z0: float
    Z1: float = math.nan
    m1: float = 0.0
    Z2: float = math.nan
    A1: float = 0.0
    r1: float = 2.0
    Z3: float = 0.0
    m2: float = 0.0
    A2: float = 0.0
    r2: float = 2.0
    damage_A: float = 1.0
    damage_B: float = 0.0
    damage_C: float = 0.0
    damage_nu: float = 10.0
    damage_p: float = 1.0
    damage_H: float = math.nan
    damage_rate: float = 1.0
    omega_rupture: float = 0.99
    rupture_strain_rate: float = 1.0
    damage_softening: str = "report"
    isotropic_hardening: bool = False
    recovery: bool = False
    directional_hardening: bool = False
    damage: bool = False
    yield_stress: float = math.inf
    name: str = ""

    is_linear = False

    def __post_init__(self):
        def pos(name):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be positive, got {v!r}")

        for k in ("E", "D0", "n", "Z0"):
            pos(k)
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {self.nu!r}")
        if self.isotropic_hardening:
            pos("Z1")
            if not self.m1 >= 0:
                raise ValueError("m1 must be >= 0")
        if self.recovery:
            pos("Z1")
            if not np.isfinite(self.Z2):
                raise ValueError("recovery needs Z2")
            if not (self.A1 >= 0 and self.r1 >= 1):
                raise ValueError("recovery needs A1 >= 0 and r1 >= 1")
        if self.directional_hardening:
            pos("Z1")
            if not (self.m2 >= 0 and self.Z3 >= 0):
                raise ValueError("directional hardening needs m2 >= 0 and Z3 >= 0")
            if self.recovery and not (self.A2 >= 0 and self.r2 >= 1):
                raise ValueError("directional recovery needs A2 >= 0 and r2 >= 1")
        if self.damage:
            for k in ("damage_nu", "damage_p", "damage_H", "damage_rate"):
                pos(k)
            abc = (self.damage_A, self.damage_B, self.damage_C)
            if min(abc) < 0 or abs(sum(abc) - 1.0) > 1e-12:
                raise ValueError(f"damage A, B, C must be >= 0 and sum to 1, got {abc}")
            if not 0.0 < self.omega_rupture < 1.0:
                raise ValueError("omega_rupture must lie in (0, 1)")
            if not self.rupture_strain_rate > 0:
                raise ValueError("rupture_strain_rate must be positive")
        if self.damage_softening not in ("report", "bodner"):
            raise ValueError("damage_softening is 'report' or 'bodner'")

    # ---------------------------------------------------------------- sets
    @classmethod
    def b1900_hf_871C(cls, **kw) -> "BodnerPartom":
        """B1900+Hf at 871 C, report section 5 (constants from its ref. [10]).

        E = 132 GPa is the report's correction of the printed 142 GPa;
        nu = 0.0805 is as printed (it does not enter uniaxial responses).
        Isotropic and directional hardening with thermal recovery.
        """
        c = dict(E=132.0e9, nu=0.0805, D0=1.0e4, n=1.03, Z0=2400.0 * _MPA,
                 Z1=3000.0 * _MPA, Z2=2400.0 * _MPA, Z3=1150.0 * _MPA,
                 m1=0.270 / _MPA, m2=1.52 / _MPA, A1=0.0055, A2=0.0055,
                 r1=2.0, r2=2.0, isotropic_hardening=True, recovery=True,
                 directional_hardening=True, name="B1900+Hf, 871 C (report 5)")
        c.update(kw)
        return cls(**c)

    @classmethod
    def aluminum_6061_t4(cls, **kw) -> "BodnerPartom":
        """Aluminum 6061-T4, report 6.3.1: the T6 set of its ref. [10] with
        the tension-test corrections E = 65 GPa, n = 5.8.  Isotropic
        hardening only (no Z2, A1 given: no recovery)."""
        c = dict(E=65.0e9, nu=0.33, D0=1.0e8, n=5.8, Z0=450.0 * _MPA,
                 Z1=550.0 * _MPA, m1=0.12 / _MPA, isotropic_hardening=True,
                 name="aluminum 6061-T4 (report 6.3.1)")
        c.update(kw)
        return cls(**c)

    @classmethod
    def aluminum_6061_t6(cls, **kw) -> "BodnerPartom":
        """The initial set of report 6.3.1 (6061-T6 of its ref. [10]):
        E = 73.9 GPa, n = 5.0, otherwise as `aluminum_6061_t4`."""
        c = dict(E=73.9e9, n=5.0, name="aluminum 6061-T6 (report 6.3.1, ref. [10])")
        c.update(kw)
        return cls.aluminum_6061_t4(**c)

    @classmethod
    def sae_1020(cls, **kw) -> "BodnerPartom":
        """Cold rolled SAE 1020 steel, report 8.2.1 (m1 printed '0.05 MPa',
        read as 0.05 1/MPa).  Isotropic hardening only."""
        c = dict(E=209.0e9, nu=0.3, D0=1.0e4, n=2.28, Z0=600.0 * _MPA,
                 Z1=1050.0 * _MPA, m1=0.05 / _MPA, isotropic_hardening=True,
                 name="SAE 1020 steel (report 8.2.1)")
        c.update(kw)
        return cls(**c)

    def with_damage(self, *, H: float, nu: float = 10.0, p: float = 1.0,
                    A: float = 1.0, B: float = 0.0, C: float = 0.0,
                    rate: float = 1.0, omega_rupture: float | None = None,
                    softening: str | None = None) -> "BodnerPartom":
        """This material with isotropic damage switched on (H = H_hat [Pa])."""
        kw = dict(damage=True, damage_H=H, damage_nu=nu, damage_p=p, damage_A=A,
                  damage_B=B, damage_C=C, damage_rate=rate)
        if omega_rupture is not None:
            kw["omega_rupture"] = omega_rupture
        if softening is not None:
            kw["damage_softening"] = softening
        return replace(self, **kw)

    def without(self, *mechanisms: str) -> "BodnerPartom":
        """Switch mechanisms off by name (flags of the dataclass)."""
        return replace(self, **{m: False for m in mechanisms})

    # ------------------------------------------------------------ scales
    @property
    def stress_scale(self) -> float:
        """A representative stress [Pa] (Z0), for tolerances and floors."""
        return self.Z0

    # ------------------------------------------------------------ damage
    @property
    def kappa_rupture(self) -> float:
        """kappa at which w = omega_rupture."""
        return math.log(1.0 / self.omega_rupture) ** (-1.0 / self.damage_p)

    def damage_from_kappa(self, kappa):
        p = self.damage_p
        return where_positive(kappa, lambda k: np.exp(-(k ** (-p))), 0.0)

    def _softening(self, w):
        if self.damage_softening == "report":
            return np.sqrt(1.0 - w * w)
        return 1.0 - w

    def damage_stress(self, sig):
        """Q_hat(sigma) [Pa] of Mandel stresses (4 or 6, N) (complex-step safe)."""
        if len(sig) == 6:
            smax = largest_principal6(sig)
        else:
            a, b, c, t = sig[0], sig[1], sig[2], sig[3] / SQRT2
            mid = 0.5 * (a + b)
            rad = np.sqrt((0.5 * (a - b)) ** 2 + t * t)
            e1 = mid + rad
            smax = np.where(np.real(e1) >= np.real(c), e1, c)
        smax = np.where(np.real(smax) > 0, smax, 0.0)
        tr = sig[0] + sig[1] + sig[2]
        i1 = np.where(np.real(tr) > 0, tr, 0.0)
        dev = sig - tr / 3.0 * identity_like(sig)
        q = np.sqrt(1.5 * mandel_dot(dev, dev))
        return self.damage_A * smax + self.damage_B * q + self.damage_C * i1

    def kappa_rate(self, sig):
        """kappa_dot [1/s] for Mandel stresses (4, N)."""
        Qh = self.damage_stress(sig)
        H, nu = self.damage_H, self.damage_nu
        return self.damage_rate * where_positive(Qh, lambda x: (x / H) ** nu, 0.0)

    # -------------------------------------------------------------- state
    def initial_state(self, shape=(), components: int = 4) -> BPState:
        """Unstrained state at `shape` points with `components` (4, or 6 for 3-D) tensor components."""
        shape = tuple(shape) if np.iterable(shape) else (int(shape),)
        if components not in COMPONENTS:
            raise ValueError(f"components must be 4 or 6, got {components!r}")
        z4 = np.zeros((components,) + shape)
        z = np.zeros(shape)
        return BPState(strain=z4.copy(), stress=z4.copy(), inelastic_strain=z4.copy(),
                       beta=z4.copy(), plastic_work=z.copy(),
                       hardness_iso=np.full(shape, float(self.Z0)), kappa=z.copy(),
                       damage=z.copy(), time=z.copy(), ruptured=np.zeros(shape, bool),
                       rupture_time=np.full(shape, np.inf), converged=np.ones(shape, bool),
                       iterations=np.zeros(shape, int), dt_sub=np.full(shape, np.nan))

    # ------------------------------------------------------- rates (explicit)
    def _rates(self, sig, zi, beta, kappa, ruptured):
        """Rates of the state for Mandel stresses (4 or 6, N) (real arrays)."""
        tr = sig[0] + sig[1] + sig[2]
        s = sig - tr / 3.0 * identity_like(sig)
        q = np.sqrt(1.5 * mandel_dot(s, s))
        nrm = np.sqrt(mandel_dot(sig, sig))
        u = np.where(nrm > 0, sig / np.where(nrm > 0, nrm, 1.0), 0.0)
        Z = zi.copy()
        if self.directional_hardening:
            Z = Z + mandel_dot(beta, u)
        w = self.damage_from_kappa(kappa) if self.damage else np.zeros_like(zi)
        Zeff = Z * self._softening(w) if self.damage else Z
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            x = np.where(q > 0, np.maximum(Zeff, 0.0) / np.where(q > 0, q, 1.0), np.inf)
            e = np.exp(-0.5 * x ** (2.0 * self.n))
        pdot = (2.0 / SQRT3) * self.D0 * np.where(q > 0, e, 0.0)
        epsn_dot = np.where(q > 0, 1.5 * pdot / np.where(q > 0, q, 1.0), 0.0) * s
        wdot = q * pdot
        zdot = np.zeros_like(zi)
        if self.isotropic_hardening:
            zdot = zdot + self.m1 * (self.Z1 - zi) * wdot
        if self.recovery:
            zdot = zdot - self.A1 * self.Z1 * signed_power((zi - self.Z2) / self.Z1, self.r1)
        bdot = np.zeros_like(beta)
        if self.directional_hardening:
            bdot = self.m2 * (self.Z3 * u - beta) * wdot
            if self.recovery:
                bn = np.sqrt(mandel_dot(beta, beta))
                v = np.where(bn > 0, beta / np.where(bn > 0, bn, 1.0), 0.0)
                bdot = bdot - self.A2 * self.Z1 * (bn / self.Z1) ** self.r2 * v
        kdot = np.zeros_like(zi)
        if self.damage:
            kdot = np.where(ruptured, 0.0, self.kappa_rate(sig))
        return dict(epsn=epsn_dot, wp=wdot, zi=zdot, beta=bdot, kappa=kdot, damage=w, Z=Z)

    def _runaway(self, sig, zi, beta, kappa):
        """The equivalent inelastic strain rate is above rupture_strain_rate."""
        r = self._rates(sig, zi, beta, kappa, np.ones(zi.shape, bool))
        return np.sqrt(2.0 / 3.0 * mandel_dot(r["epsn"], r["epsn"])) >= self.rupture_strain_rate

    def _damage_rate(self, kappa, w, kappa_dot):
        """w_dot = w p kappa^(-p-1) kappa_dot (0 at kappa = 0)."""
        p = self.damage_p
        pos = kappa > 0
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            wd = w * p * np.where(pos, kappa, 1.0) ** (-p - 1.0) * kappa_dot
        return np.where(pos & np.isfinite(wd), wd, 0.0)

    @quiet_underflow
    def rates(self, state: BPState) -> dict:
        """Rates at a state: inelastic_strain (4, *shape) tensor components,
        plastic_work, hardness_iso, beta (tensor), kappa, damage [1/s]."""
        shape = state.shape
        d = state.flat()
        r = self._rates(d["stress"], d["hardness_iso"], d["beta"], d["kappa"], d["ruptured"])
        w = r["damage"]
        if self.damage:
            wd = self._damage_rate(d["kappa"], w, r["kappa"])
        else:
            wd = np.zeros_like(w)
        nc = state.components
        return dict(inelastic_strain=from_mandel(r["epsn"]).reshape((nc,) + shape),
                    plastic_work=r["wp"].reshape(shape), hardness_iso=r["zi"].reshape(shape),
                    beta=from_mandel(r["beta"]).reshape((nc,) + shape),
                    kappa=r["kappa"].reshape(shape), damage=wd.reshape(shape))

    # ------------------------------------------ the increment (both integrators)
    def _context(self, strain, state: BPState, dt):
        shape = state.shape
        N = max(int(np.prod(shape)), 1)
        d = state.flat()
        strain = np.asarray(strain, float)
        nc = component_count(strain)
        if nc != state.components:
            raise ValueError(f"strain has {nc} components but the state {state.components}")
        eps = to_mandel(strain.reshape(nc, N))
        dtv = np.broadcast_to(np.asarray(dt, float), shape).reshape(N).astype(float)
        ctx = dict(epsn=d["inelastic_strain"], zi=d["hardness_iso"], beta=d["beta"],
                   kappa=d["kappa"], dt=dtv, c0=(2.0 / SQRT3) * self.D0 * dtv,
                   ruptured=d["ruptured"], stress=d["stress"])
        return ctx, d, eps, N, shape
