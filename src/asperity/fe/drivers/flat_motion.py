"""The rigid flat's motion in the 3-D model and the times its steps land on (report 9.2).

The flat is the plane z = -w(t), w the approach from first touch at the apex, moved
by delta(t) along x; both are piecewise linear in time between knots (`FlatMotion`;
report 9.2: pressed, then slid at constant approach).  The steps of a run never cross
a time of the step grid (`step_grid`): each segment divided into the preset's steps
for it (``tangential_steps`` where the flat slides, else ``normal_steps``), its
duration over them the segment's step cap (`step_caps`); so runs of presets with the
same steps share those times.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

@dataclass(frozen=True)
class FlatMotion:
    """Piecewise linear approach w(t) and tangential displacement delta(t) of the flat.

    times [s], normal [m] (approach from first touch at the apex),
    tangential [m] (along x), knots of equal length.
    """

    times: tuple
    normal: tuple
    tangential: tuple

    def __post_init__(self):
        t = np.asarray(self.times, float)
        w = np.asarray(self.normal, float)
        d = np.asarray(self.tangential, float)
        if t.ndim != 1 or t.size < 2 or w.shape != t.shape or d.shape != t.shape:
            raise ValueError("a motion needs at least two knots of (time, normal, tangential)")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(w)) and np.all(np.isfinite(d))):
            raise ValueError("motion knots must be finite")
        if np.any(np.diff(t) <= 0):
            raise ValueError("motion times must increase")

    @classmethod
    def press_and_slide(cls, approach: float, slide: float, press_time=(0.0, 1800.0),
                        slide_time=(1800.0, 4000.0)) -> "FlatMotion":
        """Report 9.2: press to `approach` during press_time, then slide by
        `slide` during slide_time at constant approach."""
        t0, t1 = map(float, press_time)
        s0, s1 = map(float, slide_time)
        if not (t1 > t0 and s1 > s0 and s0 >= t1):
            raise ValueError("need press_time[0] < press_time[1] <= slide_time[0] < slide_time[1]")
        times = [t0, t1] + ([s0] if s0 > t1 else []) + [s1]
        normal = [0.0, approach] + ([approach] if s0 > t1 else []) + [approach]
        tang = [0.0, 0.0] + ([0.0] if s0 > t1 else []) + [slide]
        return cls(tuple(times), tuple(normal), tuple(tang))

    @property
    def start(self) -> float:
        return float(self.times[0])

    @property
    def end(self) -> float:
        return float(self.times[-1])

    def __call__(self, t):
        return (float(np.interp(t, self.times, self.normal)),
                float(np.interp(t, self.times, self.tangential)))

    def segment(self, t) -> int:
        tk = np.asarray(self.times)
        return int(np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2))

    def phase(self, t) -> str:
        """'normal' while the approach changes, 'sliding' while delta changes, else 'hold'."""
        i = self.segment(t)
        if self.tangential[i + 1] != self.tangential[i]:
            return "sliding"
        if self.normal[i + 1] != self.normal[i]:
            return "normal"
        return "hold"


def step_caps(motion: FlatMotion, preset: dict) -> list:
    """The largest time step [s] of each segment of `motion`: its duration over the
    preset's ``tangential_steps`` where the flat slides, else its ``normal_steps``."""
    times = np.asarray(motion.times, float)
    return [(times[i + 1] - times[i]) / n for i, n in enumerate(_segment_steps(motion, preset))]


def step_grid(motion: FlatMotion, preset: dict) -> np.ndarray:
    """The times every step of a run lands on: each segment of `motion` divided into
    its preset's steps (`step_caps`).  A step may be shorter (cut, or paced by Newton)
    but never crosses one of these times, so runs whose presets have the same steps
    (``standard`` and ``fine``) both report their force histories at these times and
    are compared there without interpolating either (`asperity.studies.sliding_accuracy`)."""
    times = np.asarray(motion.times, float)
    parts = [times[i] + (times[i + 1] - times[i]) * np.arange(n) / n
             for i, n in enumerate(_segment_steps(motion, preset))]
    return np.append(np.concatenate(parts), times[-1])


def _segment_steps(motion: FlatMotion, preset: dict) -> list:
    """The preset's steps for each segment of `motion` (`step_caps`)."""
    w_knots = np.asarray(motion.normal, float)
    d_knots = np.asarray(motion.tangential, float)
    steps = []
    for i in range(len(w_knots) - 1):
        sliding = d_knots[i + 1] != d_knots[i]
        steps.append(max(int(preset["tangential_steps" if sliding else "normal_steps"]), 1))
    return steps
