"""Rate-independent J2 plasticity with linear isotropic hardening.

Yield function f = q - (yield_stress + H alpha), q the Mises stress and alpha
the equivalent plastic strain (alpha_dot = sqrt(2/3 eps_p_dot : eps_p_dot));
associated flow.  H = 0 is elastic-perfectly plastic.  In uniaxial tension
past yield the stress is

    sigma = yield_stress + E H / (E + H) (eps - yield_stress / E).

The update is the radial return (backward Euler, exact for proportional
paths with linear hardening):

    q_tr = sqrt(3/2) |s_tr|,  dp = <q_tr - yield(alpha_n)> / (3G + H),
    s = (1 - 3 G dp / q_tr) s_tr,

with the consistent tangent

    D = K I x I + 2 G theta P_dev - 2 G theta_bar N x N,
    theta = 1 - 3 G dp / q_tr,  theta_bar = 3G / (3G + H) - 3 G dp / q_tr,

N = s_tr / |s_tr|, P_dev = I - (1/3) 1 x 1 (Simo and Hughes, *Computational
Inelasticity*, 1998, 3.3, boxes 3.1-3.2).  The return is done in Mandel
components (shears times sqrt 2), where the tensor norm is the Euclidean one,
and the tangent converted back (`asperity.fe.materials.tensors`).  Arrays as in
`asperity.fe.materials.elastic` and `asperity.fe.materials.bodner_partom`: strains
/ stresses (n, *shape), tangents (n, n, *shape), tensor shear components; n = 4,
(11, 22, 33, 12) for the axisymmetric and plane-strain bodies, or n = 6, (11, 22,
33, 12, 13, 23) for the three-dimensional one (`solid3d`; ``initial_state(shape,
components=6)``), the same equations with the identity and P_dev of 6 components
(those of `bodner_partom`'s 6-component path); vectorized over all points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from asperity.fe.materials.elastic import IsotropicElasticity
from asperity.fe.materials.tensors import (COMPONENTS, from_mandel, identity_of,
                                           tangent_from_mandel, to_mandel)


@dataclass
class J2State:
    """Plastic state over the point shape: vectors (4 or 6, *shape), scalars (*shape)."""

    strain: np.ndarray
    stress: np.ndarray
    inelastic_strain: np.ndarray
    alpha: np.ndarray
    plastic_work: np.ndarray
    hardness: np.ndarray
    time: np.ndarray
    converged: np.ndarray

    @property
    def shape(self) -> tuple:
        return self.alpha.shape

    @property
    def damage(self) -> np.ndarray:
        return np.zeros(self.shape)

    @property
    def ruptured(self) -> np.ndarray:
        return np.zeros(self.shape, bool)

    @property
    def hardness_iso(self) -> np.ndarray:
        return self.hardness

    @property
    def hardness_dir(self) -> np.ndarray:
        return np.zeros(self.shape)

    def copy(self) -> "J2State":
        return J2State(**{f.name: np.array(getattr(self, f.name), copy=True) for f in fields(self)})


@dataclass(frozen=True)
class J2Plasticity(IsotropicElasticity):
    """E [Pa], nu, yield_stress [Pa], H hardening modulus d yield / d alpha [Pa]."""

    E: float
    nu: float
    yield_stress: float
    H: float = 0.0
    name: str = ""

    is_linear = False

    def __post_init__(self):
        if not (np.isfinite(self.E) and self.E > 0):
            raise ValueError(f"E must be positive, got {self.E!r}")
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {self.nu!r}")
        if not (np.isfinite(self.yield_stress) and self.yield_stress > 0):
            raise ValueError("yield_stress must be positive and finite")
        if not (np.isfinite(self.H) and self.H >= 0):
            raise ValueError("H must be >= 0")




    @property
    def stress_scale(self) -> float:
        return self.yield_stress




    def uniaxial_stress(self, strain):
        """Exact monotonic uniaxial stress for total axial strain (>= 0)."""
        e = np.asarray(strain, float)
        ey = self.yield_stress / self.E
        return np.where(e <= ey, self.E * e,
                        self.yield_stress + self.E * self.H / (self.E + self.H) * (e - ey))

    def initial_state(self, shape=(), components: int = 4) -> J2State:
        """Unstrained state at `shape` points with `components` (4, or 6 for 3-D)
        tensor components."""
        shape = tuple(shape) if np.iterable(shape) else (int(shape),)
        if components not in COMPONENTS:
            raise ValueError(f"components must be 4 or 6, got {components!r}")
        z4 = np.zeros((components,) + shape)
        z = np.zeros(shape)
        return J2State(strain=z4.copy(), stress=z4.copy(), inelastic_strain=z4.copy(),
                       alpha=z.copy(), plastic_work=z.copy(),
                       hardness=np.full(shape, float(self.yield_stress)), time=z.copy(),
                       converged=np.ones(shape, bool))

    def update(self, strain, state: J2State, dt=0.0, *, tangent: bool = True):
        """Radial return.  Returns (stress, tangent or None, new_state)."""
        shape = state.shape
        N = max(int(np.prod(shape)), 1)
        n = int(np.shape(strain)[0])
        if n != state.inelastic_strain.shape[0]:
            raise ValueError(f"strain has {n} components but the state "
                             f"{state.inelastic_strain.shape[0]}")
        identity = identity_of(n)
        _I = identity[:, None]
        eps = to_mandel(np.asarray(strain, float).reshape(n, N))
        epsp = to_mandel(state.inelastic_strain.reshape(n, N))
        alpha = state.alpha.reshape(N)
        G, K, H = self.G, self.K, self.H
        ee = eps - epsp
        tr = ee[0] + ee[1] + ee[2]
        s_tr = 2.0 * G * (ee - tr / 3.0 * _I)
        snorm = np.sqrt(np.sum(s_tr * s_tr, axis=0))
        q_tr = math.sqrt(1.5) * snorm
        sy = self.yield_stress + H * alpha
        f = q_tr - sy
        plastic = f > 1e-14 * self.yield_stress
        dp = np.where(plastic, f / (3.0 * G + H), 0.0)
        Nn = np.where(snorm > 0, s_tr / np.where(snorm > 0, snorm, 1.0), 0.0)
        ratio = np.where(plastic, 1.0 - 3.0 * G * dp / np.where(plastic, q_tr, 1.0), 1.0)
        s = s_tr * ratio
        sig = s + K * tr * _I
        epsp_new = epsp + math.sqrt(1.5) * dp * Nn
        q = q_tr - 3.0 * G * dp
        new = J2State(
            strain=from_mandel(eps).reshape((n,) + shape),
            stress=from_mandel(sig).reshape((n,) + shape),
            inelastic_strain=from_mandel(epsp_new).reshape((n,) + shape),
            alpha=(alpha + dp).reshape(shape),
            plastic_work=state.plastic_work + (q * dp).reshape(shape),
            hardness=(sy + H * dp).reshape(shape),
            time=state.time + np.broadcast_to(np.asarray(dt, float), shape),
            converged=np.ones(shape, bool))
        stress = new.stress
        if not tangent:
            return stress, None, new
        C = self.elastic_mandel(n)
        P = np.eye(n) - np.outer(identity, identity) / 3.0
        theta = ratio
        theta_bar = np.where(plastic, 3.0 * G / (3.0 * G + H) - (1.0 - ratio), 0.0)
        D = (K * np.outer(identity, identity)[:, :, None]
             + 2.0 * G * theta[None, None, :] * P[:, :, None]
             - 2.0 * G * theta_bar[None, None, :] * Nn[:, None, :] * Nn[None, :, :])
        D = np.where(plastic[None, None, :], D, C[:, :, None])
        return stress, tangent_from_mandel(D).reshape((n, n) + shape), new
