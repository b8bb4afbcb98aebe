"""Newton's method for one material point under mixed control: the free strains of a
uniaxial stress state at the end of an implicit step (report 3.6, 5).

The uniaxial stress state of the 3-D model: the axial component (11) has its
strain prescribed (strain control: the free strains are 22, 33 and 12) or its
stress (stress control: all four are free), the other stresses are zero.
With the material's consistent tangent D (backward Euler, e.g.
`BodnerPartom.update`) the free strains eps_f solve sigma_f(eps) = sigma_f* by

    eps_f <- eps_f - D_ff^-1 (sigma_f(eps) - sigma_f*),

D evaluated at the first iterate and at every fourth after it (the strain
hardly moves after the first correction; the tangent costs more than the
stress), converged when the largest component of sigma_f - sigma_f* is
within the tolerance.  The iteration is not `nonlinear.newton`: that tests
the norm of the residual against a force scale, this its largest component
against a stress scale, and it takes full steps (no line search).
"""

from __future__ import annotations

import numpy as np


def solve_mixed_point(material, state, h, eps0, control, target, scale, tol, maxit=40):
    """Implicit step: find the free strains with zero lateral (and target axial) stress.

    ``material.update(eps, state, h, tangent=...)`` gives the stress, the
    tangent (when asked) and the new state; ``control`` is "strain" (the axial
    strain is ``target``) or "stress" (the axial stress is); ``eps0`` is the
    start of the free strains, ``tol * (|target| under stress control + scale)``
    the tolerance on the largest stress residual.  Returns (converged, stress,
    tangent, new state), the last three None if it did not converge in
    ``maxit`` iterations (or a value turned non-finite, or D_ff was singular).
    """
    free = [1, 2, 3] if control == "strain" else [0, 1, 2, 3]
    sig_t = np.zeros(4)
    eps = np.array(eps0, float)
    if control == "strain":
        eps[0] = target
    else:
        sig_t[0] = target
    atol = tol * (abs(target) * (control == "stress") + scale)
    D = None
    Dff = None
    for it in range(maxit):
        # Newton with the consistent tangent of the first iterate (the
        # strain hardly moves afterwards; saves the tangent computations)
        with np.errstate(all="ignore"):
            sig, Dk, new = material.update(eps, state, h, tangent=D is None or it % 4 == 0)
        if Dk is not None:
            D = Dk
            if not np.all(np.isfinite(D)):
                return False, None, None, None
            Dff = D[np.ix_(free, free)]
        if not (np.all(new.converged) and np.all(np.isfinite(sig))):
            return False, None, None, None
        r = sig[free] - sig_t[free]
        if np.max(np.abs(r)) <= atol:
            return True, sig, D, new
        try:
            d = np.linalg.solve(Dff, r)
        except np.linalg.LinAlgError:
            return False, None, None, None
        eps[free] -= d
        if not np.all(np.isfinite(eps)):
            return False, None, None, None
    return False, None, None, None
