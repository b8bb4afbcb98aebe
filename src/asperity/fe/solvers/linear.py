"""SuperLU factorizations reused as GMRES preconditioners (the 3-D sliding model).

A tangent is factorized (`assembly.OrderedLU`, diagonal pivots preferred) and the
factorization kept: the next systems, of the next Newton iterations and steps, are
solved by one cycle of restarted GMRES (``max_krylov`` iterations, to ``rtol``)
preconditioned by it while that converges; when it does not, the new matrix is
factorized.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse.linalg as spl

from asperity.fe.discretization.assembly import OrderedLU

class ReusedLU:
    """SuperLU factorizations reused as GMRES preconditioners while they work."""

    def __init__(self, rtol: float = 1e-10, max_krylov: int = 15):
        self.lu = None
        self.rtol = rtol
        self.max_krylov = max_krylov
        self.factorizations = 0
        self.krylov_solves = 0
        self._ordered = OrderedLU(diag_pivot_thresh=0.1)

    def reset(self):
        self.lu = None

    def _factor(self, K):
        self.lu = self._ordered.factor(K)
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
