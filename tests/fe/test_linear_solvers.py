"""The direct solvers of the 3-D sliding model (`asperity.fe.solvers.linear`): PARDISO
against SuperLU on an unsymmetric sparse system, its analysis kept per pattern, stale
factors refused, and the choice by size (SuperLU where PARDISO is not installed)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from asperity.fe.discretization.assembly import OrderedLU
from asperity.fe.solvers import linear

needs_pardiso = pytest.mark.skipif(not linear.pardiso_available(),
                                   reason="pypardiso and MKL are installed on x86-64 only")


def _system(n=3000, seed=0):
    """A sparse, unsymmetric, diagonally dominant matrix of n unknowns: a 3-D 7-point
    Laplacian of a 10 x 10 x 30 grid plus an unsymmetric perturbation, as a tangent with
    friction is; and a right-hand side."""
    m = round(n / 300)
    one = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(10, 10))
    eye10 = sp.identity(10)
    lap = (sp.kron(sp.kron(sp.identity(m), eye10), one) + sp.kron(sp.kron(sp.identity(m), one), eye10)
           + sp.kron(sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(m, m)), sp.identity(100)))
    rng = np.random.default_rng(seed)
    skew = sp.random(lap.shape[0], lap.shape[0], density=2e-4, random_state=rng) * 0.3
    K = (lap + skew - skew.T * 0.5 + 0.1 * sp.identity(lap.shape[0])).tocsr()
    return K, rng.standard_normal(K.shape[0])


@needs_pardiso
def test_pardiso_solves_as_superlu():
    """PARDISO's solution is SuperLU's to 1e-10 of its largest entry, its residual at
    round-off (1e-12); a second matrix of the same pattern reuses the analysis and is
    solved as well; factors of an earlier matrix are refused once a later one is
    factorized; a singular matrix is a RuntimeError."""
    K, b = _system()
    pardiso = linear.PardisoLU()
    x = pardiso.factor(K).solve(b)
    ref = OrderedLU(diag_pivot_thresh=0.1).factor(K.tocsc()).solve(b)
    np.testing.assert_allclose(x, ref, rtol=0, atol=1e-10 * np.abs(ref).max())
    assert np.linalg.norm(K @ x - b) <= 1e-12 * np.linalg.norm(b)
    first_pattern = pardiso._pattern
    K2 = K.copy()
    K2.data *= 1.0 + 0.1 * np.sin(np.arange(K2.nnz))
    f2 = pardiso.factor(K2)
    assert pardiso._pattern is first_pattern                      # the analysis kept
    np.testing.assert_allclose(K2 @ f2.solve(b), b, rtol=0, atol=1e-10 * np.abs(b).max())
    stale = pardiso.factor(K)
    pardiso.factor(K2)
    with pytest.raises(RuntimeError, match="replaced"):
        stale.solve(b)
    singular = K.tolil()
    singular[5, :] = singular[4, :]                                  # two equal rows
    with pytest.raises(RuntimeError, match="singular"):
        linear.PardisoLU().factor(singular.tocsr())


def test_the_solver_by_size(monkeypatch):
    """`ReusedLU` factorizes with SuperLU below `PARDISO_DOFS` unknowns, and above it where
    PARDISO is not installed; with PARDISO above it where it is. Either way the solution
    is right (1e-10)."""
    K, b = _system()
    installed = linear.pardiso_available()

    def solver_of(threshold, available):
        monkeypatch.setattr(linear, "PARDISO_DOFS", threshold)
        monkeypatch.setattr(linear, "pardiso_available", lambda: available)
        reused = linear.ReusedLU()
        np.testing.assert_allclose(K @ reused.solve(K, b), b, rtol=0, atol=1e-10 * np.abs(b).max())
        return type(reused._direct)

    assert solver_of(10 * K.shape[0], installed) is OrderedLU
    assert solver_of(K.shape[0], False) is OrderedLU
    if installed:
        assert solver_of(K.shape[0], True) is linear.PardisoLU
