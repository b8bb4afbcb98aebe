"""Exceptions of the finite element model."""

from __future__ import annotations


class ConvergenceError(RuntimeError):
    """Newton iterations failed at a load step even after step cutting.

    Attributes: `step` (index of the requested interference level),
    `interference` [m] (the level requested), `reached` [m] (the last
    interference at which a converged state exists), `cuts`.
    """

    def __init__(self, step: int, interference: float, reached: float = float("nan"),
                 cuts: int = 0, detail: str = ""):
        self.step = step
        self.interference = interference
        self.reached = reached
        self.cuts = cuts
        msg = (f"Newton iterations did not converge at step {step} "
               f"(interference {interference:.6g} m) after {cuts} step cuts; "
               f"last converged interference {reached:.6g} m")
        if detail:
            msg += f": {detail}"
        super().__init__(msg)


class ContactZoneError(RuntimeError):
    """The contact reached the edge of the zone allowed to touch the flat."""


class StepFailed(Exception):
    """One try of an incremental step failed (the driver cuts the step and retries)."""

    def __init__(self, message: str, iterations: int = 0):
        super().__init__(message)
        self.iterations = iterations

