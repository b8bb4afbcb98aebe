"""Materials: stress and tangent at quadrature points, given the strain.

Strains and stresses are stored as 4 components (shape ``(4, ...)``):
``[e_11, e_22, e_33, e_12]`` with the *tensor* shear component e_12, where
1, 2 are the in-plane (r, z) or (x, z) directions and 3 is the hoop
direction (axisymmetric, e_33 = u_r / r) or the out-of-plane direction
(plane strain, e_33 = 0).  The work product is ``sum(METRIC * s * e)``
with ``METRIC = (1, 1, 1, 2)``.

Three-dimensional bodies use 6 components (shape ``(6, ...)``):
``[e_11, e_22, e_33, e_12, e_13, e_23]``, tensor shears, work product with
``METRIC6 = (1, 1, 1, 2, 2, 2)``.  `IsotropicElasticity`, `von_mises`,
`equivalent_strain` and `complementary_energy_density` decide by the
first axis of their array (4 or 6); `metric(n)` gives the weights.

A material is any object with

- ``response(strain) -> (stress, tangent)``: stress (4, ...) and the
  tangent d stress / d strain (4, 4, ...) or (4, 4) if uniform;
- ``is_linear`` (the tangent does not depend on the strain);
- ``contact_modulus`` [Pa] (scales the contact penalty);
- ``yield_stress`` [Pa] (``inf`` if none): the response counts as elastic
  while the von Mises stress stays below it.

Inelastic materials (report 3.2.2: `j2`, `bodner_partom`) add internal
state and its update on top of this interface.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

METRIC = np.array([1.0, 1.0, 1.0, 2.0])
METRIC6 = np.array([1.0, 1.0, 1.0, 2.0, 2.0, 2.0])


def metric(components: int) -> np.ndarray:
    """Work-product weights of `components` (4 or 6) tensor components."""
    if components == 4:
        return METRIC
    if components == 6:
        return METRIC6
    raise ValueError(f"strain/stress arrays have 4 or 6 components, got {components}")


class IsotropicElasticity:
    """The elastic part every material shares, from its ``E`` and ``nu`` (report 3.2.1).

    Moduli, the elastic tangent sigma = lambda tr(e) I + 2 mu e in tensor
    components (4, 4), and the stateless ``response`` of the solver
    interface.  Inelastic materials add their flow on top of it.
    """

    @property
    def G(self) -> float:
        """Shear modulus mu [Pa]."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def K(self) -> float:
        """Bulk modulus [Pa]."""
        return self.E / (3.0 * (1.0 - 2.0 * self.nu))

    @property
    def lame(self) -> tuple[float, float]:
        return self.K - 2.0 * self.G / 3.0, self.G

    @property
    def contact_modulus(self) -> float:
        """Plane-strain modulus E' = E / (1 - nu^2) [Pa]."""
        return self.E / (1 - self.nu**2)

    def elastic_mandel(self, components: int = 4) -> np.ndarray:
        """The elastic tangent in Mandel components (shear scaled by sqrt 2),
        (4, 4) or, for ``components=6``, (6, 6)."""
        metric(components)
        identity = np.zeros(components)
        identity[:3] = 1.0
        deviator = np.eye(components) - np.outer(identity, identity) / 3.0
        return self.K * np.outer(identity, identity) + 2.0 * self.G * deviator

    def tangent(self, components: int = 4) -> np.ndarray:
        """d stress / d strain in tensor components, (4, 4) or (6, 6)."""
        metric(components)
        lam, mu = self.lame
        D = np.zeros((components, components))
        D[:3, :3] = lam
        D[[0, 1, 2], [0, 1, 2]] += 2 * mu
        D[range(3, components), range(3, components)] = 2 * mu
        return D

    def response(self, strain: np.ndarray):
        D = self.tangent(np.shape(strain)[0])
        stress = np.tensordot(D, strain, axes=(1, 0))
        return stress, D


@dataclass(frozen=True)
class LinearElastic(IsotropicElasticity):
    """Linear isotropic elasticity (report 3.2.1): sigma = lambda tr(e) I + 2 mu e.

    E: Young's modulus [Pa]; nu: Poisson's ratio; yield_stress [Pa] only
    classifies the response (``elastic`` output), it does not change it.
    """

    E: float
    nu: float
    yield_stress: float = math.inf

    is_linear = True

    def __post_init__(self):
        if not (np.isfinite(self.E) and self.E > 0):
            raise ValueError(f"E must be positive, got {self.E!r}")
        if not -1.0 < self.nu < 0.5:
            raise ValueError(f"nu must lie in (-1, 0.5), got {self.nu!r}")
        if not self.yield_stress > 0:
            raise ValueError("yield_stress must be positive (inf if none)")


def von_mises(stress: np.ndarray) -> np.ndarray:
    """Von Mises equivalent stress of 4- (or 6-) component stresses."""
    if len(stress) == 6:
        s11, s22, s33, s12, s13, s23 = stress
        return np.sqrt(0.5 * ((s11 - s22) ** 2 + (s22 - s33) ** 2 + (s33 - s11) ** 2)
                       + 3.0 * (s12**2 + s13**2 + s23**2))
    s11, s22, s33, s12 = stress
    return np.sqrt(0.5 * ((s11 - s22) ** 2 + (s22 - s33) ** 2 + (s33 - s11) ** 2)
                   + 3.0 * s12**2)


def equivalent_strain(strain: np.ndarray) -> np.ndarray:
    """Von Mises equivalent strain sqrt(2/3 e':e') of 4- (or 6-) component strains."""
    if len(strain) == 6:
        e11, e22, e33, e12, e13, e23 = strain
        mean = (e11 + e22 + e33) / 3.0
        dev2 = ((e11 - mean) ** 2 + (e22 - mean) ** 2 + (e33 - mean) ** 2
                + 2 * (e12**2 + e13**2 + e23**2))
        return np.sqrt(2.0 / 3.0 * dev2)
    e11, e22, e33, e12 = strain
    mean = (e11 + e22 + e33) / 3.0
    dev2 = (e11 - mean) ** 2 + (e22 - mean) ** 2 + (e33 - mean) ** 2 + 2 * e12**2
    return np.sqrt(2.0 / 3.0 * dev2)


def complementary_energy_density(material, stress: np.ndarray) -> np.ndarray:
    """sigma : C : sigma with C the inverse tangent (for error norms)."""
    nc = len(stress)
    _, D = material.response(np.zeros((nc, 1)))
    D = np.asarray(D)
    if D.ndim == 2:
        C = np.linalg.inv(D)
        e = np.tensordot(C, stress, axes=(1, 0))
    else:  # per point tangents (4, 4, ...)
        Dm = np.moveaxis(D, (0, 1), (-2, -1))
        e = np.moveaxis(np.linalg.solve(Dm, np.moveaxis(stress, 0, -1)[..., None])[..., 0], -1, 0)
    return np.tensordot(metric(nc), stress * e, axes=(0, 0))
