"""Sparse direct factorizations reused as GMRES preconditioners (the 3-D sliding model).

A tangent is factorized and the factorization kept: the next systems, of the next Newton
iterations and steps, are solved by one cycle of restarted GMRES (``max_krylov``
iterations, to ``rtol``) preconditioned by it while that converges; when it does not,
the new matrix is factorized.

The factorization: SuperLU in a fill-reducing order kept per pattern, diagonal pivots
preferred (`assembly.OrderedLU`); for systems of `PARDISO_DOFS` unknowns or more, Intel
MKL's PARDISO (`PardisoLU`; Schenk and Gärtner 2004, through pypardiso) where it is
installed (x86-64 Linux and Windows), whose supernodal factorization in a nested
dissection order is several times faster on the large 3-D tangents. Below that size its
analysis, repeated whenever the contact set changes the pattern, costs more than its
factorization saves (`make bench CASE=linear` measures both).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

from asperity.fe.discretization.assembly import OrderedLU

#: systems of at least this many unknowns are factorized by PARDISO where it is installed
PARDISO_DOFS = 10_000

#: PARDISO's controls (iparm, numbered from 1 as in MKL's manual) for a real unsymmetric
#: matrix (type 11): 1, not the defaults; 2, METIS nested dissection; 8, no iterative
#: refinement; 10, pivots perturbed below 1e-13 of the largest; 11 and 13, scaling and
#: weighted matching (MKL's defaults for type 11)
IPARM = {1: 1, 2: 2, 8: 0, 10: 13, 11: 1, 13: 1}


def pardiso_available() -> bool:
    """Whether pypardiso and the MKL runtime it loads are installed."""
    try:
        import pypardiso  # noqa: F401
    except (ImportError, OSError):
        return False
    return True


class PardisoLU:
    """PARDISO factorizations of a sequence of general (unsymmetric) sparse matrices of one
    size, with ``factor(K).solve(b)`` as `OrderedLU`'s: the analysis (nested dissection
    order, symbolic factorization) is kept for as long as the pattern is, each new matrix
    of that pattern only factorized numerically. One MKL thread (the workflow runs its
    jobs in parallel), and the controls of `IPARM`: no iterative refinement, which would
    triple a solve's cost (the GMRES cycles these factors precondition refine, and
    SuperLU's solves do not either). A pivot PARDISO has to perturb (below 1e-13 of the
    largest) is a singular matrix, a RuntimeError as SuperLU's zero pivot is."""

    def __init__(self):
        import pypardiso

        self._solver = pypardiso.PyPardisoSolver(mtype=11)
        self._solver.libmkl.MKL_Set_Num_Threads(1)
        for index, value in IPARM.items():
            self._solver.set_iparm(index, value)
        self._pattern = None
        self._generation = 0

    def factor(self, K) -> "PardisoLU.Factors":
        """Factors of the sparse matrix `K`; raises RuntimeError where PARDISO fails."""
        from pypardiso.pardiso_wrapper import PyPardisoError

        K = sp.csr_matrix(K)
        K.sort_indices()
        solver = self._solver
        solver._check_A(K)
        zero = np.zeros(K.shape[0])
        try:
            if self._pattern is None or not (np.array_equal(self._pattern[0], K.indptr)
                                             and np.array_equal(self._pattern[1], K.indices)):
                solver.set_phase(11)
                solver._call_pardiso(K, zero)
                self._pattern = (K.indptr.copy(), K.indices.copy())
            solver.set_phase(22)
            solver._call_pardiso(K, zero)
        except PyPardisoError as exc:
            self._pattern = None
            raise RuntimeError(f"PARDISO: {exc}") from None
        if solver.get_iparm(14) > 0:  # pivots below 1e-13 of the largest, perturbed
            raise RuntimeError(f"PARDISO: the matrix is singular to working precision "
                               f"({solver.get_iparm(14)} pivots perturbed)")
        self._generation += 1
        return self.Factors(self, K, self._generation)

    def __del__(self):
        """Release PARDISO's memory (at interpreter exit the process does)."""
        solver = getattr(self, "_solver", None)
        if solver is not None:
            try:
                solver.free_memory(everything=True)
            except Exception:  # modules already torn down at interpreter exit
                pass

    class Factors:
        """The factors of one matrix; they hold while no later matrix is factorized."""

        def __init__(self, owner: "PardisoLU", K, generation: int):
            self.owner, self.K, self.generation = owner, K, generation

        def solve(self, b: np.ndarray) -> np.ndarray:
            owner = self.owner
            if owner._generation != self.generation:
                raise RuntimeError("PARDISO factors replaced by a later factorization")
            owner._solver.set_phase(33)
            return owner._solver._call_pardiso(self.K, np.asfortranarray(b, dtype=float))


class ReusedLU:
    """Factorizations reused as GMRES preconditioners while they work (module docstring):
    SuperLU, or PARDISO for `PARDISO_DOFS` unknowns and more where it is installed."""

    def __init__(self, rtol: float = 1e-10, max_krylov: int = 15):
        self.lu = None
        self.rtol = rtol
        self.max_krylov = max_krylov
        self.factorizations = 0
        self.krylov_solves = 0
        self._direct = None

    def reset(self):
        self.lu = None

    def _factor(self, K):
        if self._direct is None:
            big = K.shape[0] >= PARDISO_DOFS and pardiso_available()
            self._direct = PardisoLU() if big else OrderedLU(diag_pivot_thresh=0.1)
        self.lu = self._direct.factor(K)
        self.factorizations += 1

    def solve(self, K, rhs) -> np.ndarray:
        if self.lu is not None:
            lu = self.lu
            M = spl.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
            count = [0]

            def cb(_):
                count[0] += 1

            x, info = spl.gmres(K, rhs, M=M, rtol=self.rtol, atol=0.0, restart=self.max_krylov,
                                maxiter=1, callback=cb, callback_type="pr_norm")
            if info == 0 and np.all(np.isfinite(x)):
                self.krylov_solves += 1
                return x
        self._factor(K)
        return self.lu.solve(rhs)
