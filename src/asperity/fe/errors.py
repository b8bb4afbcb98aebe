"""Exceptions of the finite element model."""

from __future__ import annotations


class ConvergenceError(RuntimeError):
    """Newton iterations failed at a load step even after step cutting.

    Attributes: `step` (index of the requested interference level),
    `interference` [m] (the level requested), `reached` [m] (the last
    interference at which a converged state exists), `cuts`, and `sample`
    (who failed: the pipeline's sample key, set by the caller that knows
    it; '' for none), which the message names first.
    """

    def __init__(self, step: int, interference: float, reached: float = float("nan"),
                 cuts: int = 0, detail: str = "", sample: str = ""):
        self.step = step
        self.interference = interference
        self.reached = reached
        self.cuts = cuts
        self.sample = sample
        msg = (f"Newton iterations did not converge at step {step} "
               f"(interference {interference:.6g} m) after {cuts} step cuts; "
               f"last converged interference {reached:.6g} m")
        if detail:
            msg += f": {detail}"
        self.message = msg
        super().__init__(msg)

    def __str__(self) -> str:
        return f"sample {self.sample}: {self.message}" if self.sample else self.message


class RuptureError(ConvergenceError):
    """A material point ruptured (report 3.2.2: w -> 1) in a history solved
    with ``on_rupture="raise"``.

    Attributes as `ConvergenceError` (`step`, `interference` and `reached`
    the interference of the rupture step, `cuts` 0) plus `time` [s] and
    `position` (r or x, depth below the surface) [m] of the first ruptured
    point and `count` (ruptured points).
    """

    def __init__(self, step: int, interference: float, time_: float, position, count: int):
        super().__init__(step, interference, interference)
        self.time = time_
        self.position = tuple(position)
        self.count = count
        self.message = (f"material ruptured at step {step} (time {time_:.6g} s, interference "
                        f"{interference:.6g} m): {count} point(s), the first at "
                        f"r = {position[0]:.6g} m, {position[1]:.6g} m below the surface")
        self.args = (self.message,)


class ContactZoneError(RuntimeError):
    """The contact reached the edge of the zone allowed to touch the flat."""


class StepFailed(Exception):
    """One try of an incremental step failed (the driver cuts the step and retries)."""

    def __init__(self, message: str, iterations: int = 0):
        super().__init__(message)
        self.iterations = iterations

