"""A-posteriori error estimation and marking (h-adaptivity).

Zienkiewicz-Zhu estimator of the stress: the finite element stress
sigma_h (discontinuous between elements) is projected in L2 (weighted by
the volume element) onto continuous P2 fields, sigma*, and

    eta_K^2 = int_K (sigma* - sigma_h) : C : (sigma* - sigma_h) dV

estimates the energy-norm error on element K (C the compliance).  The
contact edge, where the pressure falls as a square root, is where it is
largest, so that is where the mesh is refined.

One mesh serves several load levels: each level's indicators are divided
by its own energy norm ||sigma_h||^2 and an element's indicator is the
largest over the levels; elements above ``theta`` times the largest
indicator are refined (`skfem.adaptive_theta`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from skfem import adaptive_theta

from asperity.fe.discretization.assembly import Discretization
from asperity.fe.materials.elastic import complementary_energy_density


class StressRecovery:
    """L2 projection of quadrature-point stresses onto continuous P2 fields."""

    def __init__(self, disc: Discretization, material):
        self.disc = disc
        self.material = material
        P = disc.scalar_p2_interpolation()
        W = disc.weights.ravel()
        M = (P.T @ sp.diags(W) @ P).tocsc()
        self.P = P
        self.W = W
        self.PtW = (P.T @ sp.diags(W)).tocsr()
        self.lu = spl.splu(M)

    def indicators(self, stress: np.ndarray):
        """Squared element indicators (ne, k) and squared norms (k,).

        `stress` has shape (4, ne, nq, k).
        """
        ne, nq = self.disc.weights.shape
        k = stress.shape[-1]
        s = stress.reshape(4, ne * nq, k)
        rhs = self.PtW @ np.moveaxis(s, 0, 1).reshape(ne * nq, 4 * k)
        nodal = self.lu.solve(rhs)
        rec = (self.P @ nodal).reshape(ne * nq, 4, k)
        err = np.moveaxis(rec, 1, 0) - s
        dens = complementary_energy_density(self.material, err)  # (ne*nq, k)
        eta2 = (dens * self.W[:, None]).reshape(ne, nq, k).sum(axis=1)
        norm2 = (complementary_energy_density(self.material, s) * self.W[:, None]).sum(axis=0)
        return eta2, norm2


def relative_indicator(eta2: np.ndarray, norm2: np.ndarray) -> np.ndarray:
    """Per element, the largest over levels of eta_K / ||sigma_h||."""
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(norm2 > 0, eta2 / norm2, 0.0)
    return np.sqrt(np.max(rel, axis=1))


def mark(indicator: np.ndarray, theta: float) -> np.ndarray:
    """Elements whose indicator exceeds theta times the largest."""
    return adaptive_theta(indicator, theta)
