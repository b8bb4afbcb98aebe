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
contractions are dot products.

Integrators:

- `BodnerPartom.update` (backward Euler, the FE one): given the total
  strain at the end of the increment, the state at its start and dt.  The
  flow rule is coaxial with the elastic trial deviator, so the local problem
  reduces to one scalar unknown y = ln(c0 / dp), dp = c0 exp(-y) the
  equivalent inelastic strain increment, c0 = (2/sqrt3) D0 dt; in y the
  flow law inverts to q = Z_eff (2 y)^(-1/(2n)), a smooth and (for fixed Z)
  concave increasing residual even for the stiff n = 5.8, D0 = 1e8 set.
  Z^I and |beta| at the end of the step solve their own monotone scalar
  backward-Euler equations for each y (nested; closed forms for r = 1, 2),
  the damage kappa is explicit in the end stress.  All points iterate
  together (safeguarded Newton with bisection, masked convergence).  The
  consistent tangent is d sigma/d eps = partial_eps sigma - partial_y sigma
  (partial_eps R / partial_y R) on the reduced residual R(y, eps), the
  partial derivatives by complex-step differentiation (exact to rounding).
- `BodnerPartom.explicit`: the report's Euler predictor / trapezoidal
  corrector with the error indicator (3.33)-(3.36) and per-point adaptive
  sub-stepping, the reference integrator.  It also takes mixed control
  (some stress components prescribed), which the uniaxial driver uses.

Units are SI: stresses and hardnesses in Pa, m1 and m2 in 1/Pa, rates in 1/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

import numpy as np

from asperity.fe.materials.elastic import IsotropicElasticity

SQRT2 = math.sqrt(2.0)
SQRT3 = math.sqrt(3.0)
#: tensor components -> Mandel components
MANDEL = np.array([1.0, 1.0, 1.0, SQRT2])
#: the identity in 4 components
IDENTITY = np.array([1.0, 1.0, 1.0, 0.0])
#: the same for the 6 components (11, 22, 33, 12, 13, 23) of a 3-D body
MANDEL6 = np.array([1.0, 1.0, 1.0, SQRT2, SQRT2, SQRT2])
IDENTITY6 = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
_I = IDENTITY[:, None]
_I6 = IDENTITY6[:, None]
_W = MANDEL[:, None]
_MPA = 1.0e6
#: the supported numbers of components
COMPONENTS = (4, 6)


def _components(x) -> int:
    n = int(np.shape(x)[0])
    if n not in COMPONENTS:
        raise ValueError(f"strain/stress arrays have 4 or 6 components on their first axis, got {n}")
    return n


def _mandel_of(n: int) -> np.ndarray:
    return MANDEL if n == 4 else MANDEL6


def identity_of(n: int) -> np.ndarray:
    """The identity tensor in `n` (4 or 6) components."""
    return IDENTITY if n == 4 else IDENTITY6


def _ident(x) -> np.ndarray:
    """The identity (n, 1) matching the component count of x (n, N)."""
    return _I if np.shape(x)[0] == 4 else _I6


def to_mandel(x: np.ndarray) -> np.ndarray:
    """Tensor components (4 or 6, ...) -> Mandel components (shear times sqrt 2)."""
    x = np.asarray(x)
    n = _components(x)
    return x * _mandel_of(n).reshape((n,) + (1,) * (x.ndim - 1))


def from_mandel(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x)
    n = _components(x)
    return x / _mandel_of(n).reshape((n,) + (1,) * (x.ndim - 1))


def tangent_from_mandel(D: np.ndarray) -> np.ndarray:
    """Mandel d sigma / d eps (n, n, ...) -> tensor-component tangent (n = 4 or 6)."""
    n = _components(D)
    m = _mandel_of(n)
    s = (1.0 / m)[:, None] * m[None, :]
    return D * s.reshape((n, n) + (1,) * (D.ndim - 2))


def _dot(a, b):
    """Contraction of Mandel vectors (n, N) without conjugation (complex-step safe)."""
    if len(a) == 4:
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]


def _largest_principal6(sig):
    """Largest principal value of Mandel stresses (6, N), complex-step safe.

    The trigonometric solution of the characteristic cubic: with
    m = tr/3, p = sqrt(|dev|^2 / 6), r = det(dev / p) / 2 (clipped to
    [-1, 1]), sigma_1 = m + 2 p cos(arccos(r) / 3); sigma_1 = m where the
    deviator vanishes.
    """
    a, b, c = sig[0], sig[1], sig[2]
    t12, t13, t23 = sig[3] / SQRT2, sig[4] / SQRT2, sig[5] / SQRT2
    m = (a + b + c) / 3.0
    da, db, dc = a - m, b - m, c - m
    p2 = (da * da + db * db + dc * dc + 2.0 * (t12 * t12 + t13 * t13 + t23 * t23)) / 6.0
    ok = np.real(p2) > 1e-30 * (np.real(m) ** 2 + 1e-300)
    p = np.sqrt(np.where(ok, p2, 1.0))
    det = (da * (db * dc - t23 * t23) - t12 * (t12 * dc - t23 * t13)
           + t13 * (t12 * t23 - db * t13))
    r = det / (2.0 * p**3)
    r = np.where(np.real(r) >= 1.0, 1.0 - 1e-15, np.where(np.real(r) <= -1.0, -1.0 + 1e-15, r))
    phi = np.arccos(r) / 3.0
    return np.where(ok, m + 2.0 * p * np.cos(phi), m)


def _sgnpow(x, r):
    """sign(x) |x|^r, analytic for complex-step on either side of 0."""
    s = np.sign(np.real(x))
    return s * (s * x) ** r


def _where_pos(x, fn, default=0.0):
    """fn(x) where Re x > 0 else default, without evaluating fn at Re x <= 0."""
    pos = np.real(x) > 0
    safe = np.where(pos, x, 1.0)
    return np.where(pos, fn(safe), default)


@dataclass
class BPState:
    """State of Bodner-Partom material points (arrays over the point shape).

    Vectors are (4, *shape) (or (6, *shape) in 3-D) tensor components;
    scalars (*shape).
    ``kappa`` = [ln(1/w)]^(-1/p) is the rescaled damage that is integrated,
    ``damage`` = w.  ``converged`` and ``iterations`` describe the last local
    solve, ``dt_sub`` the last explicit sub-step (reused by the next call).
    """

    strain: np.ndarray
    stress: np.ndarray
    inelastic_strain: np.ndarray
    beta: np.ndarray
    plastic_work: np.ndarray
    hardness_iso: np.ndarray
    kappa: np.ndarray
    damage: np.ndarray
    time: np.ndarray
    ruptured: np.ndarray
    rupture_time: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    dt_sub: np.ndarray

    @property
    def shape(self) -> tuple:
        return self.plastic_work.shape

    @property
    def components(self) -> int:
        """Number of tensor components of the vectors (4 or 6)."""
        return int(np.shape(self.strain)[0])

    @property
    def hardness_dir(self) -> np.ndarray:
        """Z^D = beta : u with u = sigma / |sigma| (0 at zero stress)."""
        s = to_mandel(self.stress)
        b = to_mandel(self.beta)
        nrm = np.sqrt(np.sum(s * s, axis=0))
        with np.errstate(invalid="ignore", divide="ignore"):
            zd = np.sum(b * s, axis=0) / nrm
        return np.where(nrm > 0, zd, 0.0)

    @property
    def hardness(self) -> np.ndarray:
        """Z = Z^I + Z^D [Pa]."""
        return self.hardness_iso + self.hardness_dir

    def copy(self) -> "BPState":
        return BPState(**{f.name: np.array(getattr(self, f.name), copy=True) for f in fields(self)})

    def flat(self) -> dict:
        """Flattened Mandel arrays (internal)."""
        N = max(int(np.prod(self.shape)), 1)
        out = {}
        for f in fields(self):
            v = np.asarray(getattr(self, f.name))
            if f.name in _VECTOR_FIELDS:
                v = to_mandel(v.reshape(v.shape[0], N))
            else:
                v = v.reshape(N)
            out[f.name] = v
        return out

    @classmethod
    def from_flat(cls, d: dict, shape: tuple) -> "BPState":
        kw = {}
        for f in fields(cls):
            v = d[f.name]
            if f.name in _VECTOR_FIELDS:
                kw[f.name] = from_mandel(v).reshape((v.shape[0],) + shape)
            else:
                kw[f.name] = np.asarray(v).reshape(shape)
        return cls(**kw)


_VECTOR_FIELDS = ("strain", "stress", "inelastic_strain", "beta")


def _quiet_underflow(fn):
    """Run fn with floating-point underflow ignored (it is benign here: tiny
    flow rates and damage round to 0); other numpy errors keep their setting."""
    import functools

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with np.errstate(under="ignore"):
            return fn(*args, **kwargs)

    return wrapper


def _take(d: dict, idx) -> dict:
    return {k: (v[..., idx] if isinstance(v, np.ndarray) and v.ndim else v) for k, v in d.items()}


@dataclass(frozen=True)
class BodnerPartom(IsotropicElasticity):
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

    # ------------------------------------------------------------ elastic




    @property
    def stress_scale(self) -> float:
        """A representative stress [Pa] (Z0), for tolerances and floors."""
        return self.Z0




    @property
    def kappa_rupture(self) -> float:
        """kappa at which w = omega_rupture."""
        return math.log(1.0 / self.omega_rupture) ** (-1.0 / self.damage_p)

    def damage_from_kappa(self, kappa):
        p = self.damage_p
        return _where_pos(kappa, lambda k: np.exp(-(k ** (-p))), 0.0)

    def _softening(self, w):
        if self.damage_softening == "report":
            return np.sqrt(1.0 - w * w)
        return 1.0 - w

    def damage_stress(self, sig):
        """Q_hat(sigma) [Pa] of Mandel stresses (4 or 6, N) (complex-step safe)."""
        if len(sig) == 6:
            smax = _largest_principal6(sig)
        else:
            a, b, c, t = sig[0], sig[1], sig[2], sig[3] / SQRT2
            mid = 0.5 * (a + b)
            rad = np.sqrt((0.5 * (a - b)) ** 2 + t * t)
            e1 = mid + rad
            smax = np.where(np.real(e1) >= np.real(c), e1, c)
        smax = np.where(np.real(smax) > 0, smax, 0.0)
        tr = sig[0] + sig[1] + sig[2]
        i1 = np.where(np.real(tr) > 0, tr, 0.0)
        dev = sig - tr / 3.0 * _ident(sig)
        q = np.sqrt(1.5 * _dot(dev, dev))
        return self.damage_A * smax + self.damage_B * q + self.damage_C * i1

    def kappa_rate(self, sig):
        """kappa_dot [1/s] for Mandel stresses (4, N)."""
        Qh = self.damage_stress(sig)
        H, nu = self.damage_H, self.damage_nu
        return self.damage_rate * _where_pos(Qh, lambda x: (x / H) ** nu, 0.0)

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
        s = sig - tr / 3.0 * _ident(sig)
        q = np.sqrt(1.5 * _dot(s, s))
        nrm = np.sqrt(_dot(sig, sig))
        u = np.where(nrm > 0, sig / np.where(nrm > 0, nrm, 1.0), 0.0)
        Z = zi.copy()
        if self.directional_hardening:
            Z = Z + _dot(beta, u)
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
            zdot = zdot - self.A1 * self.Z1 * _sgnpow((zi - self.Z2) / self.Z1, self.r1)
        bdot = np.zeros_like(beta)
        if self.directional_hardening:
            bdot = self.m2 * (self.Z3 * u - beta) * wdot
            if self.recovery:
                bn = np.sqrt(_dot(beta, beta))
                v = np.where(bn > 0, beta / np.where(bn > 0, bn, 1.0), 0.0)
                bdot = bdot - self.A2 * self.Z1 * (bn / self.Z1) ** self.r2 * v
        kdot = np.zeros_like(zi)
        if self.damage:
            kdot = np.where(ruptured, 0.0, self.kappa_rate(sig))
        return dict(epsn=epsn_dot, wp=wdot, zi=zdot, beta=bdot, kappa=kdot, damage=w, Z=Z)

    def _runaway(self, sig, zi, beta, kappa):
        """The equivalent inelastic strain rate is above rupture_strain_rate."""
        r = self._rates(sig, zi, beta, kappa, np.ones(zi.shape, bool))
        return np.sqrt(2.0 / 3.0 * _dot(r["epsn"], r["epsn"])) >= self.rupture_strain_rate

    def _damage_rate(self, kappa, w, kappa_dot):
        """w_dot = w p kappa^(-p-1) kappa_dot (0 at kappa = 0)."""
        p = self.damage_p
        pos = kappa > 0
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            wd = w * p * np.where(pos, kappa, 1.0) ** (-p - 1.0) * kappa_dot
        return np.where(pos & np.isfinite(wd), wd, 0.0)

    @_quiet_underflow
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

    # ------------------------------------------------- implicit (backward Euler)
    def _context(self, strain, state: BPState, dt):
        shape = state.shape
        N = max(int(np.prod(shape)), 1)
        d = state.flat()
        strain = np.asarray(strain, float)
        nc = _components(strain)
        if nc != state.components:
            raise ValueError(f"strain has {nc} components but the state {state.components}")
        eps = to_mandel(strain.reshape(nc, N))
        dtv = np.broadcast_to(np.asarray(dt, float), shape).reshape(N).astype(float)
        ctx = dict(epsn=d["inelastic_strain"], zi=d["hardness_iso"], beta=d["beta"],
                   kappa=d["kappa"], dt=dtv, c0=(2.0 / SQRT3) * self.D0 * dtv,
                   ruptured=d["ruptured"], stress=d["stress"])
        return ctx, d, eps, N, shape

    def _trial(self, eps, ctx):
        ee = eps - ctx["epsn"]
        tr = ee[0] + ee[1] + ee[2]
        p = self.K * tr
        s_tr = 2.0 * self.G * (ee - tr / 3.0 * _ident(ee))
        q_tr = np.sqrt(1.5 * _dot(s_tr, s_tr))
        return p, s_tr, q_tr

    def _stress_of(self, y, eps, ctx):
        p, s_tr, q_tr = self._trial(eps, ctx)
        dp = ctx["c0"] * np.exp(-y)
        q = q_tr - 3.0 * self.G * dp
        ok = np.real(q_tr) > 0
        ratio = np.where(ok, q / np.where(ok, q_tr, 1.0), 1.0)
        sig = s_tr * ratio + p * _ident(s_tr)
        return sig, q, dp, s_tr, q_tr

    def _direction(self, sig):
        nrm = np.sqrt(_dot(sig, sig))
        ok = np.real(nrm) > 0
        return np.where(ok, sig / np.where(ok, nrm, 1.0), 0.0)

    def _inner(self, dW, u, ctx, tol=1e-14, maxit=60):
        """Z^I, |beta|, c and b at the end of the step for given dW and u.

        Backward Euler of (3.13) and of the beta equation: with
        b = beta_n + m2 Z3 dW u, beta = b / c, c = 1 + m2 dW + A2 dt
        Z1^(1 - r2) |beta|^(r2 - 1), so |beta| solves the scalar
        |beta| (1 + m2 dW) + A2 dt Z1^(1-r2) |beta|^r2 = |b|.  Closed forms
        for r = 1, 2; otherwise safeguarded Newton on the real parts and one
        complex Newton correction (exact complex-step derivatives).
        """
        cplx = np.iscomplexobj(dW) or (u is not None and np.iscomplexobj(u))
        dt = ctx["dt"]
        if self.isotropic_hardening:
            a = 1.0 + self.m1 * dW
            rhs = ctx["zi"] + self.m1 * self.Z1 * dW
        else:
            a = 1.0 + 0.0 * dW
            rhs = ctx["zi"] + 0.0 * dW
        zstar = rhs / a
        if self.recovery and self.A1 > 0:
            k = dt * self.A1 * self.Z1
            z1, z2, r1 = self.Z1, self.Z2, self.r1
            d = zstar - z2
            if r1 == 2.0:
                sd = np.sign(np.real(d))
                zi = z2 + 2.0 * d / (1.0 + np.sqrt(1.0 + 4.0 * k / z1**2 * (sd * d) / a))
            elif r1 == 1.0:
                zi = z2 + a * d / (a + k / z1)
            else:
                def fz(z, a=a, rhs=rhs):
                    x = (z - z2) / z1
                    s = np.sign(np.real(x))
                    return (a * z - rhs + k * _sgnpow(x, r1),
                            a + k * r1 * (s * x) ** (r1 - 1.0) / z1)

                ar, rr, zr = np.real(a), np.real(rhs), np.real(zstar)
                zi = _safe_newton(lambda z: fz(z, ar, rr), np.minimum(zr, z2),
                                  np.maximum(zr, z2), zr, tol * self.Z0, maxit)
                if cplx:
                    f, df = fz(zi.astype(complex))
                    zi = zi - f / df
        else:
            zi = zstar
        if not self.directional_hardening:
            return zi, 0.0 * dW, None, None
        b = ctx["beta"] + self.m2 * self.Z3 * dW * u
        bb = np.sqrt(_dot(b, b))
        c1 = 1.0 + self.m2 * dW
        if self.recovery and self.A2 > 0:
            k2 = self.A2 * dt * self.Z1 ** (1.0 - self.r2)
            r2 = self.r2
            if r2 == 2.0:
                bn = 2.0 * bb / (c1 + np.sqrt(c1 * c1 + 4.0 * k2 * bb))
            elif r2 == 1.0:
                bn = bb / (c1 + k2)
            else:
                def fb(x, c1=c1, bb=bb):
                    return x * c1 + k2 * x**r2 - bb, c1 + k2 * r2 * x ** (r2 - 1.0)

                c1r, bbr = np.real(c1), np.real(bb)
                hi = bbr / c1r
                bn = _safe_newton(lambda x: fb(x, c1r, bbr), np.zeros_like(hi), hi, hi,
                                  tol * self.Z0, maxit)
                if cplx:
                    f, df = fb(bn.astype(complex))
                    bn = bn - f / df
            c = c1 + k2 * bn ** (r2 - 1.0)
        else:
            bn = bb / c1
            c = c1
        return zi, bn, c, b

    def _flow(self, y, eps, ctx):
        """Reduced flow residual R(y) = q - Z_eff (2 y)^(-1/(2n)) with the inner
        variables solved; complex-step safe.  Returns (R, sig, extras)."""
        sig, q, dp, s_tr, q_tr = self._stress_of(y, eps, ctx)
        dW = q * dp
        u = self._direction(sig) if self.directional_hardening else None
        zi, bn, c, b = self._inner(dW, u, ctx)
        Z = zi
        if self.directional_hardening:
            Z = Z + (_dot(ctx["beta"], u) + self.m2 * self.Z3 * dW) / c
        kraw = None
        if self.damage:
            kraw = ctx["kappa"] + ctx["dt"] * self.kappa_rate(sig) * (~ctx["ruptured"])
            kr = self.kappa_rupture
            kap = np.where(np.real(kraw) > kr, kr, kraw)
            Z = Z * self._softening(self.damage_from_kappa(kap))
        g = (2.0 * y) ** (-0.5 / self.n)
        R = q - Z * g
        return R, sig, dict(q=q, dp=dp, s_tr=s_tr, q_tr=q_tr, dW=dW, zi=zi, bn=bn, c=c, b=b,
                            kraw=kraw, Zeff=Z)

    def _reduced(self, y, eps, ctx):
        """R(y) and dR/dy (total, inner variables following) by one complex step."""
        hy = 1e-20 * (1.0 + np.abs(y))
        R, _, _ = self._flow(y + 1j * hy, eps, ctx)
        return np.real(R), np.imag(R) / hy

    @_quiet_underflow
    def update(self, strain, state: BPState, dt, *, tol: float = 1e-12, maxit: int = 80,
               tangent: bool = True):
        """Backward-Euler stress update.

        strain: total strain (4, *shape) (or (6, *shape) in 3-D, with a
        state of as many components) at the end of the increment; state:
        at its start; dt [s] (scalar or per point).  Returns
        ``(stress (n, *shape), tangent (n, n, *shape) or None, new_state)``;
        ``new_state.converged`` flags the points whose local Newton converged
        (``iterations`` counts its iterations).
        """
        ctx, d, eps, N, shape = self._context(strain, state, dt)
        p, s_tr, q_tr = self._trial(eps, ctx)
        active = (q_tr > 1e-14 * self.stress_scale) & (ctx["dt"] > 0)
        y = np.full(N, np.inf)
        conv = np.ones(N, bool)
        iters = np.zeros(N, int)
        ia = np.nonzero(active)[0]
        if ia.size:
            ya, ca, ita = self._solve_flow(eps[:, ia], _take(ctx, ia), q_tr[ia], tol, maxit)
            y[ia], conv[ia], iters[ia] = ya, ca, ita
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            _, sig, x = self._flow(y, eps, ctx)
        dp, dW = x["dp"], x["dW"]
        nrm_s = np.where(q_tr > 0, 1.5 / np.where(q_tr > 0, q_tr, 1.0), 0.0)
        epsn = ctx["epsn"] + dp * nrm_s * s_tr
        if self.directional_hardening:
            beta = x["b"] / x["c"]
        else:
            beta = ctx["beta"]
        kappa, w = ctx["kappa"], d["damage"]
        ruptured, t_r = d["ruptured"].copy(), d["rupture_time"].copy()
        if self.damage:
            kraw = x["kraw"]
            kr = self.kappa_rupture
            new = (kraw >= kr) & ~ruptured
            with np.errstate(divide="ignore", invalid="ignore"):
                frac = np.clip((kr - ctx["kappa"]) / (kraw - ctx["kappa"]), 0.0, 1.0)
            t_r = np.where(new, d["time"] + frac * ctx["dt"], t_r)
            ruptured = ruptured | new
            # creep runaway: the inelastic strain rate passes rupture_strain_rate
            with np.errstate(divide="ignore", invalid="ignore"):
                lost = (dp >= self.rupture_strain_rate * ctx["dt"]) & (ctx["dt"] > 0) & ~ruptured
            t_r = np.where(lost, d["time"] + ctx["dt"], t_r)
            ruptured = ruptured | lost
            kappa = np.minimum(kraw, kr)
            w = self.damage_from_kappa(kappa)
        new_flat = dict(strain=eps, stress=sig, inelastic_strain=epsn, beta=beta,
                        plastic_work=d["plastic_work"] + dW, hardness_iso=x["zi"], kappa=kappa,
                        damage=w, time=d["time"] + ctx["dt"], ruptured=ruptured,
                        rupture_time=t_r, converged=conv, iterations=iters, dt_sub=d["dt_sub"])
        new_state = BPState.from_flat(new_flat, shape)
        nc = eps.shape[0]
        stress = from_mandel(sig).reshape((nc,) + shape)
        if not tangent:
            return stress, None, new_state
        C = self.elastic_mandel(nc)
        D = np.broadcast_to(C[:, :, None], (nc, nc, N)).copy()
        ip = np.nonzero(active & (dp > 0))[0]
        if ip.size:
            D[:, :, ip] = self._consistent(y[ip], eps[:, ip], _take(ctx, ip))
        D = tangent_from_mandel(D).reshape((nc, nc) + shape)
        return stress, D, new_state

    def _consistent(self, y, eps, ctx):
        """Consistent tangent (Mandel, (nc, nc, n)) at converged plastic points:
        d sigma / d eps = partial_eps sigma + partial_y sigma (x) d y / d eps,
        d y / d eps = -partial_eps R / partial_y R (R the reduced residual)."""
        n = y.shape[0]
        nc = eps.shape[0]
        with np.errstate(all="ignore"):
            hy = 1e-20 * (1.0 + np.abs(y))
            R, s, _ = self._flow(y + 1j * hy, eps, ctx)
            R_y = np.imag(R) / hy
            sig_y = np.imag(s) / hy
            R_e = np.empty((nc, n))
            sig_e = np.empty((nc, nc, n))
            he = 1e-20 * np.maximum(np.max(np.abs(eps), axis=0), 1e-3)
            for j in range(nc):
                e = eps.astype(complex)
                e[j] = e[j] + 1j * he
                R, s, _ = self._flow(y.astype(complex), e, ctx)
                R_e[j] = np.imag(R) / he
                sig_e[:, j] = np.imag(s) / he
        good = np.isfinite(R_y) & (R_y != 0)
        dy_de = np.where(good, -R_e / np.where(good, R_y, 1.0), 0.0)      # (nc, n)
        return sig_e + sig_y[:, None, :] * dy_de[None, :, :]

    def _solve_flow(self, eps, ctx, q_tr, tol, maxit):
        """Safeguarded Newton on y for the active points (vectorized, masked).

        R(y) is increasing, R -> -inf (or < 0) at the lower end of the domain
        y_dom (q = 0 or y = 0) and R -> q_tr > 0 as y -> inf; for fixed Z it
        is concave, so Newton from the left converges monotonically.  Steps
        leaving the bracket are replaced by bisection (or expansion).
        """
        n = q_tr.shape[0]
        c0 = ctx["c0"]
        G3 = 3.0 * self.G
        with np.errstate(divide="ignore"):
            ydom = np.maximum(np.log(G3 * c0 / q_tr), 0.0)
        # initial guess: flow at the trial stress with the old hardness (left of the root)
        Zest = ctx["zi"].copy()
        if self.directional_hardening:
            p, s_tr, _ = self._trial(eps, ctx)
            Zest = Zest + _dot(ctx["beta"], self._direction(s_tr + p * _ident(s_tr)))
        if self.damage:
            Zest = Zest * self._softening(self.damage_from_kappa(ctx["kappa"]))
        Zest = np.maximum(Zest, 1e-6 * self.stress_scale)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            y0 = np.minimum(0.5 * (Zest / q_tr) ** (2.0 * self.n), 1e300)
            # better: the flow rate at the start of the step (small steps)
            sn = ctx["stress"]
            trn = sn[0] + sn[1] + sn[2]
            dn = sn - trn / 3.0 * _ident(sn)
            qn = np.sqrt(1.5 * _dot(dn, dn))
            Zn = ctx["zi"].copy()
            if self.directional_hardening:
                Zn = Zn + _dot(ctx["beta"], self._direction(sn))
            if self.damage:
                Zn = Zn * self._softening(self.damage_from_kappa(ctx["kappa"]))
            yn = 0.5 * (np.maximum(Zn, 1e-6 * self.stress_scale) / qn) ** (2.0 * self.n)
        yd = ydom + np.maximum(1e-9 * ydom, 1e-12)
        y = np.where(np.isfinite(yn) & (yn > yd) & (qn > 0), yn, np.maximum(y0, yd))
        lo = ydom.copy()
        hi = np.full(n, np.inf)
        conv = np.zeros(n, bool)
        iters = np.zeros(n, int)
        todo = np.arange(n)
        for _ in range(maxit):
            c = _take(ctx, todo) if todo.size < n else ctx
            yt = y[todo]
            with np.errstate(all="ignore"):
                R, dR = self._reduced(yt, eps[:, todo], c)
            neg = R < 0
            l = np.where(neg, np.maximum(lo[todo], yt), lo[todo])
            hh = np.where(~neg, np.minimum(hi[todo], yt), hi[todo])
            lo[todo], hi[todo] = l, hh
            iters[todo] += 1
            done = (np.abs(R) <= tol * q_tr[todo]) | (hh - l <= 1e-15 * yt)
            conv[todo[done]] = True
            with np.errstate(all="ignore"):
                ynew = yt - R / dR
            bad = ~np.isfinite(ynew) | (ynew <= l) | (ynew >= hh) | ~(dR > 0)
            # a good Newton step this small leaves a residual ~ its square: done
            small = ~bad & (np.abs(ynew - yt) <= 1e-7 * np.abs(yt))
            conv[todo[small]] = True
            bis = np.where(np.isfinite(hh), 0.5 * (l + hh), 2.0 * yt + 1.0)
            y[todo] = np.where(done, yt, np.where(bad, bis, ynew))
            done = done | small
            todo = todo[~done]
            if todo.size == 0:
                break
        return y, conv, iters

    # ------------------------------------------------------------ explicit
    @_quiet_underflow
    def explicit(self, strain, state: BPState, dt, *, tol: float = 1e-4, stress=None,
                 stress_mask=None, max_substeps: int = 2_000_000):
        """Euler predictor / trapezoidal corrector with error indicator (3.33-3.36).

        The strain goes linearly from ``state.strain`` to `strain` over dt;
        components where ``stress_mask`` (4,) is True instead have their
        stress going linearly to `stress` (mixed control; those strains are
        found from sigma_dot = C (eps_dot - eps_n_dot)).  Each point takes its
        own sub-steps: the predictor y_P = y + h y_dot (3.34), y_dot_P =
        f(y_P) (3.35), and the indicator (3.36)

            E = max |h (y_dot_P - y_dot)| / (2 (|y_P| + floor))

        over the stress, Z^I, beta, w (the report's control variables) and
        the inelastic strain (so that stress-controlled creep is controlled
        too), tensors by their norms; Z^I and beta are measured relative to
        the hardness |Z^I| (beta starts from 0, and what matters is its share
        of Z), eps_n relative to the total strain, the stress and the strain
        with floors of 1e-3 Z0 and 1e-3 Z0 / E, w with a floor of 1e-4.
        E > tol rejects the step and shrinks it; otherwise the corrector
        y + h (y_dot + y_dot_P) / 2 is taken; the next step is
        h 0.9 sqrt(tol / E) within [0.2 h, 2 h].  ``tol = inf`` takes one
        Heun step per call; dt = 0 is an elastic jump.  Returns
        ``(stress, new_state, info)`` with info = dict(substeps, rejected)
        per point.
        """
        ctx, d, eps1, N, shape = self._context(strain, state, dt)
        dtv = ctx["dt"]
        nc = eps1.shape[0]
        mask = np.zeros(nc, bool) if stress_mask is None else np.asarray(stress_mask, bool)
        C = self.elastic_mandel(nc)
        # slices of the stacked state (for nc = 4: 0:4, 4:8, 8:12, 12, 13:17, 17, 18)
        iE, iS, iN = slice(0, nc), slice(nc, 2 * nc), slice(2 * nc, 3 * nc)
        iZ, iB, iK, iW = 3 * nc, slice(3 * nc + 1, 4 * nc + 1), 4 * nc + 1, 4 * nc + 2
        a, b = ~mask, mask
        mixed = bool(b.any())
        # stacked state: eps iE, sig iS, eps_n iN, Z^I iZ, beta iB, kappa iK, W_p iW
        Y = np.concatenate([d["strain"], d["stress"], d["inelastic_strain"],
                            d["hardness_iso"][None], d["beta"], d["kappa"][None],
                            d["plastic_work"][None]])
        pos = dtv > 0
        inv_dt = np.where(pos, 1.0 / np.where(pos, dtv, 1.0), 0.0)
        rate_eps = (eps1 - Y[iE]) * inv_dt
        if mixed:
            sig1 = to_mandel(np.asarray(stress, float).reshape(nc, N))
            rate_sig = (sig1 - Y[iS]) * inv_dt
            Cbb_inv = np.linalg.inv(C[np.ix_(b, b)])
            Cba = C[np.ix_(b, a)]
            # eps_dot_b = Cbb^-1 (sig_dot_b - Cba eps_dot_a + (C eps_n_dot)_b)
            G1 = Cbb_inv @ (rate_sig[b] - Cba @ rate_eps[a])
            Cb_n = Cbb_inv @ C[b]                      # acting on eps_n_dot
        else:
            rate_sig = None
        if not pos.all():
            # dt = 0: an instantaneous, elastic jump to the prescribed values
            z = ~pos
            e_new = eps1[:, z].copy()
            if mixed:
                s1 = sig1[:, z]
                en = Y[iN][:, z]
                e_new[b] = Cbb_inv @ (s1[b] - Cba @ e_new[a] + (C @ en)[b])
            Y[iE, z] = e_new
            Y[iS, z] = C @ (e_new - Y[iN][:, z])
        ruptured = d["ruptured"].copy()
        t_r = d["rupture_time"].copy()
        t = np.zeros(N)
        h = np.where(np.isfinite(d["dt_sub"]) & (d["dt_sub"] > 0), d["dt_sub"], dtv)
        h = np.minimum(h, dtv)
        nsub = np.zeros(N, int)
        nrej = np.zeros(N, int)
        conv = np.ones(N, bool)
        fs = 1e-3 * self.stress_scale
        fe = fs / self.E
        hard = self.isotropic_hardening or self.recovery
        kr = self.kappa_rupture if self.damage else math.inf
        todo = np.nonzero(pos)[0]
        full = todo.size == N

        def f(Yv, re, g1, rup):
            r = self._rates(Yv[iS], Yv[iZ], Yv[iB], Yv[iK], rup)
            en = r["epsn"]
            if mixed:
                epsd = re.copy()
                epsd[b] = g1 + Cb_n @ en
                sigd = C @ (epsd - en)
            else:
                epsd = re
                sigd = C @ (re - en)
            F = np.concatenate([epsd, sigd, en, r["zi"][None], r["beta"], r["kappa"][None],
                                r["wp"][None]])
            if mixed:
                F[iS][b] = rate_sig[b][:, idx] if not full else rate_sig[b]
            return F, r["damage"]

        def n2(x):
            return np.sqrt(np.sum(x * x, axis=0))

        while todo.size:
            full = todo.size == N
            idx = todo
            Yt = Y if full else Y[:, todo]
            re = rate_eps if full else rate_eps[:, todo]
            g1 = (G1 if full else G1[:, todo]) if mixed else None
            rup = ruptured if full else ruptured[todo]
            tt = t if full else t[todo]
            rem = dtv if full else dtv[todo]
            hh = np.minimum(h if full else h[todo], rem - tt)
            F0, w0 = f(Yt, re, g1, rup)
            YP = Yt + hh * F0
            if self.damage:
                YP[iK] = np.minimum(YP[iK], kr)
            FP, wP = f(YP, re, g1, rup)
            dF = hh * (FP - F0)
            E = n2(dF[iS]) / (2.0 * (n2(YP[iS]) + fs))
            E = np.maximum(E, n2(dF[iN]) / (2.0 * (n2(YP[iE]) + fe)))
            zs = 2.0 * (np.abs(YP[iZ]) + fs)
            if hard:
                E = np.maximum(E, np.abs(dF[iZ]) / zs)
            if self.directional_hardening:
                E = np.maximum(E, n2(dF[iB]) / zs)
            if self.damage:
                wd0 = self._damage_rate(Yt[iK], w0, F0[iK])
                wdP = self._damage_rate(YP[iK], wP, FP[iK])
                Ew = np.abs(hh * (wdP - wd0)) / (2.0 * (np.abs(wP) + 1e-4))
                E = np.maximum(E, Ew)
            E = np.where(np.isfinite(E), E, np.inf)
            acc = (E <= tol) | (not np.isfinite(tol))
            Yc = Yt + 0.5 * hh * (F0 + FP)
            ia = todo[acc]
            if self.damage and ia.size:
                kold, knew = Yt[iK][acc], Yc[iK][acc]
                new = (knew >= kr) & ~ruptured[ia]
                with np.errstate(divide="ignore", invalid="ignore"):
                    frac = np.clip((kr - kold) / (knew - kold), 0.0, 1.0)
                t_r[ia] = np.where(new, d["time"][ia] + t[ia] + frac * hh[acc], t_r[ia])
                ruptured[ia] |= new
                Yc[iK] = np.minimum(Yc[iK], kr)
                lost = self._runaway(Yc[iS][:, acc], Yc[iZ][acc], Yc[iB][:, acc],
                                     Yc[iK][acc]) & ~ruptured[ia]
                t_r[ia] = np.where(lost, d["time"][ia] + t[ia] + hh[acc], t_r[ia])
                ruptured[ia] |= lost
            Y[:, ia] = Yc[:, acc]
            t[ia] += hh[acc]
            nsub[ia] += 1
            nrej[todo[~acc]] += 1
            with np.errstate(divide="ignore", invalid="ignore"):
                fac = np.where(E > 0, 0.9 * np.sqrt(tol / np.where(E > 0, E, 1.0)), 2.0)
            fac = np.clip(np.where(np.isnan(fac), 2.0, fac), 0.2, 2.0)
            hold = h[todo]
            # an accepted step cut short by the end of the increment keeps h
            keep = acc & (hh < hold) & (t[todo] >= dtv[todo] * (1.0 - 1e-14))
            h[todo] = np.where(keep, hold, hh * fac)
            left = t[todo] < dtv[todo] * (1.0 - 1e-14)
            over = nsub[todo] + nrej[todo] >= max_substeps
            conv[todo[over & left]] = False
            todo = todo[left & ~over]
        w = self.damage_from_kappa(Y[iK]) if self.damage else d["damage"]
        new_flat = dict(strain=Y[iE], stress=Y[iS], inelastic_strain=Y[iN],
                        beta=Y[iB], plastic_work=Y[iW], hardness_iso=Y[iZ],
                        kappa=Y[iK], damage=w, time=d["time"] + dtv, ruptured=ruptured,
                        rupture_time=t_r, converged=conv, iterations=nsub, dt_sub=h)
        st = BPState.from_flat(new_flat, shape)
        return st.stress, st, dict(substeps=nsub.reshape(shape), rejected=nrej.reshape(shape))


def _safe_newton(fun, lo, hi, x0, atol, maxit):
    """Vectorized Newton for an increasing f with f(lo) <= 0 <= f(hi).

    `fun` is elementwise (returns f, f' at all points); Newton steps that
    leave the bracket are replaced by bisection; masked convergence.
    """
    x = np.array(x0, float, copy=True)
    lo = np.array(lo, float, copy=True)
    hi = np.array(hi, float, copy=True)
    x = np.clip(x, lo, hi)
    todo = np.nonzero(hi > lo)[0]
    for _ in range(maxit):
        if todo.size == 0:
            break
        f, df = fun(x)
        f, df = f[todo], df[todo]
        xt = x[todo]
        neg = f < 0
        lo[todo] = np.where(neg, xt, lo[todo])
        hi[todo] = np.where(neg, hi[todo], xt)
        with np.errstate(all="ignore"):
            xn = xt - f / df
        bad = ~np.isfinite(xn) | (xn < lo[todo]) | (xn > hi[todo])
        xn = np.where(bad, 0.5 * (lo[todo] + hi[todo]), xn)
        done = (np.abs(xn - xt) <= atol) | (f == 0) | (hi[todo] - lo[todo] <= atol)
        x[todo] = xn
        todo = todo[~done]
    return x
