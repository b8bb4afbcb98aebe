"""The adhesive asperity's equilibrium path under displacement control: step control,
jumps, retracing, meshes that follow the contact (report 7.3).

The rigid flat's position w is prescribed (displacement control, as the
report's load-deflection curves and the pipeline's interference grid):
w < 0 is a gap before touching (the tip at separation d - w), w > 0 an
interference.  The levels of a path (`adhesive_path`) run from the
cut-off to the deepest interference (approach) and back (retraction).
Every state is a stable equilibrium, a local minimum of the energy
Pi(u; w) (`asperity.fe.solvers.adhesive`), on the mesh of an
`AdhesiveModel` (`asperity.fe.drivers.adhesive_model`).

Control and jumps
-----------------
Along the path, each step starts from the tangent predictor.  A step is
continuous if the energy balance Pi*(w1) - Pi*(w0) = (F0 + F1)/2
(w1 - w0) holds (Pi* has the derivative F along a branch; a jump releases
a finite energy) and the surface stayed near the predictor, or, where it
did not (a contact zipping or peeling over many elements), near the
secant through a state solved halfway (`AdhesiveModel.continuity`).
Otherwise, or if Newton fails, the step's end is marked bad and the
bracket up to it is bisected (`_advance`): a continuous branch is
followed with steps small enough to be smooth, and where the step stays
discontinuous down to ``min_step * d`` the old branch has ended (a fold of
the equilibrium curve: jump-in on approach, jump-off on retraction) and
the minimum reached is on the other branch.  The state before the fold
and the state after the jump are both recorded, ``min_step * d`` apart,
the second flagged ``jump``.  This is the physical path under
displacement control; the unstable branch that joins the two is not
traced.

Where the bisection stalls, on the steep stretch before a fold at a large
Tabor parameter (it has cut a requested step MAX_HALVINGS times, or a
jump fails at the smallest step), the branch is instead followed by its
arc length in (u, w) through the fold and the jump solved from there
(`asperity.fe.solvers.arclength.through_fold`, pseudo-arc-length
continuation); a retraction passes it the branch out of contact that the
approach went along (`Landing`), from which a jump-off that does not
converge from the tangent predictor is solved again.  A stretch that turns
out to have no fold is followed to the step's end.  Paths on which the
bisection does not stall do not take the fold path.

Retracting, the flat first runs back over levels the approach reached
continuously; an elastic body's equilibria along a branch without a fold
depend on the flat's position only, so those levels are the approach's
states, not solved again (`_retrace`), down to the level the approach
jumped in at.  From there on, where the contact hangs on (the hysteresis
of report 7.3), every step is solved.

Meshes that follow the contact
------------------------------
Each state the path reaches is checked (`AdhesiveModel.window_for`): if
its edge or ring has come within a quarter of the margin of the window's
ends, the surface displacement is interpolated onto a mesh with a new
window and the equilibrium at the same flat position is re-solved there
(`_follow`), and the path goes on from that state (the energy balance is
checked between states of one mesh only).  A jump may land far outside
the window (jump-in): the landing state is moved, and re-solved, until its
window holds.  Each state keeps its mesh (``AdhesiveState.model``): the
bisection around the pull-off and the outputs use it.  Only the current
mesh keeps the sparse factors of its body; the states recorded on a mesh
the path has left are evaluated and that mesh's factors dropped
(`_release_behind`, `AdhesiveModel.release`), so the memory of a path does
not grow with its meshes at the rate of their factors.  A path whose
adhesive ring reaches the last tenth of the refined band raises
`Overflow` (the driver starts it again on a wider band).

Pull-off
--------
The largest tensile force on retraction is the minimum of the force on the
retract branch, located by bisecting the path around the smallest recorded
force (continuing the branch from it) until the neighbouring states are
d / 64 apart (`refine_pull_off`).
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, replace

import numpy as np

from asperity.fe.contact.adhesion import LennardJones
from asperity.fe.drivers.adhesive_model import AdhesiveModel
from asperity.fe.drivers.path import Steps, follow
from asperity.fe.errors import ConvergenceError, StepFailed
from asperity.fe.solvers.adhesive import (JUMP_ITERATION_FACTOR, AdhesiveState, on_nodes,
                                          predictor)
from asperity.fe.solvers.arclength import Landing, through_fold
from asperity.io.run_report import StepProgress

log = logging.getLogger(__name__)

#: halvings of one requested step (failed Newton or discontinuity) before the
#: branch is followed through its fold instead (`through_fold`)
MAX_HALVINGS = 60
#: a state whose edge or ring comes within a quarter of the margin of its
#: band's ends is moved to a new mesh (`_follow`, `AdhesiveModel.window_for`),
#: at most MAX_REMESH times in a row
MAX_REMESH = 8


class Overflow(Exception):
    """The adhesive ring reached the end of the refined band."""


def adhesive_path(adhesion: LennardJones, w_max: float, w_min: float | None = None,
                  steps_per_d: float = 6.0, far_steps: int = 16) -> np.ndarray:
    """Flat positions: approach from the cut-off to w_max, retract to w_min.

    Steps of d / steps_per_d within 4 d of first touch, growing as 15 % of
    |w| before it (the far tail of the attraction) and geometrically in
    `far_steps` steps beyond it up to w_max.  The approach starts where the
    tip is at the cut-off separation (no force); the retraction runs back
    over the same levels and on to `w_min` (default the start), below
    which the flat would have to go for a contact that hangs on (JKR-like)
    to let go.  w = 0 (first touch) is always a level.
    """
    d = adhesion.d
    h = d / steps_per_d
    start = -(adhesion.range - d)
    near = 4.0 * d

    def below(lo):  # levels from lo (< 0) up to 0
        out, w = [0.0], 0.0
        while w > lo:
            w -= max(h, 0.15 * min(-w, -lo) if -w > near else h)
            out.append(max(w, lo))
        return np.array(out[::-1])

    up = [below(start)]
    if w_max > 0:
        top = min(w_max, near)
        n = max(int(math.ceil(top / h)), 1)
        up.append(np.linspace(0, top, n + 1)[1:])
        if w_max > near:
            up.append(np.geomspace(near, w_max, far_steps + 1)[1:])
    approach = np.concatenate(up)
    approach = approach[approach <= w_max + 1e-12 * d] if w_max < 0 else approach
    retract = approach[::-1][1:]
    lo = start if w_min is None else min(w_min, start)
    if lo < start:
        retract = np.concatenate((retract[:-1], below(lo)[::-1][len(below(start)) - 1:]))
    return np.concatenate((approach, retract))


def _branches(path: np.ndarray) -> list[str]:
    out = ["approach"]
    for a, b in zip(path[:-1], path[1:]):
        out.append("approach" if b > a else ("retract" if b < a else out[-1]))
    return out


@dataclass
class _Record:
    state: AdhesiveState
    branch: str
    jump: bool
    requested: bool
    step: int


def _follow(state: AdhesiveState, step: int = 0) -> tuple[AdhesiveState, int]:
    """`state` moved onto a mesh whose fine band covers its contact edge.

    While the state's mesh will not do (`AdhesiveModel.window_for`), the
    surface displacement is interpolated onto the nodes of a mesh with the
    band it needs and the equilibrium at the same flat position re-solved
    from there (a jump may land far outside the band: the landing state
    then moves the band, and is re-solved, again).  Returns the state and
    the Newton iterations spent.
    """
    iterations = 0
    for _ in range(MAX_REMESH):
        old = state.model
        window = old.window_for(state)
        if window is None:
            return state, iterations
        model = old.remeshed(window)
        u0 = on_nodes(state, model)
        newton = model.newton
        try:
            u, parts, T, its = newton.solve(state.w, u0,
                                            JUMP_ITERATION_FACTOR * newton.max_iterations)
        except StepFailed as exc:
            raise ConvergenceError(step, state.w, state.w, 0,
                                   f"{exc} (re-solving on a new mesh at w = {state.w:.6g} m)"
                                   ) from None
        iterations += its
        state = newton.state(state.w, u, parts, T)
        state.model = model
    raise ConvergenceError(step, state.w, state.w, 0,
                           f"the fine band does not settle on the contact (at w = {state.w:.6g} m)")


class _Steps(Steps):
    """The adhesive path for `follow` (`asperity.fe.drivers.path`): Newton from the
    capped tangent predictor (`predictor`), the continuity test of the model
    (`AdhesiveModel.continuity`), jumps at ``min_step * d``, a steep or failed
    position retried once, the fold followed by arc length (`through_fold`,
    with `landing` for the jump from it), each state moved onto a mesh that
    follows its contact edge (`_follow`), `Overflow` where the ring reaches
    the end of the refined band."""

    retry_once = True

    def __init__(self, d: float, pre: dict, landing: Landing | None):
        self.limit, self.smallest = MAX_HALVINGS, pre["min_step"] * d
        self.pre, self.landing = pre, landing

    def solve(self, state: AdhesiveState, goal: float, small: bool):
        model = state.model
        newton = model.newton
        pred = predictor(state, goal)
        u, parts, T, its = newton.solve(
            goal, pred, JUMP_ITERATION_FACTOR * newton.max_iterations if small else None)
        new = newton.state(goal, u, parts, T)
        new.model = model
        return new, its, pred

    def continuity(self, state, new, predictor):
        return state.model.continuity(state, new, predictor, self.pre)

    def fold(self, state, target):
        return through_fold(state, target, self.pre, self.landing)

    def settle(self, new, step):
        return _follow(new, step)

    def check(self, new):
        if new.model.overflow(new):
            raise Overflow()


def _advance(state: AdhesiveState, target: float, pre: dict, step: int = 0,
             landing: Landing | None = None):
    """From a converged state to the flat position `target`, by the
    path-following driver (`follow`) with the adhesive path's steps
    (`_Steps`): a discontinuous step is bisected down to ``min_step * d``,
    where it is a jump; a position where Newton failed, or bad only by the
    predictor and secant tests ("steep"), is retried once, from the first
    midpoint reached, before the bisection goes on; where the bisection
    stalls (MAX_HALVINGS halvings since the start or the last fold, or a
    failed solve at the smallest step) the branch is followed through its
    fold.  Returns (final state, [(state before, state after) of each jump],
    iterations, halvings); raises `ConvergenceError` (naming `step` and the
    last position reached) when that fails too.
    """
    return follow(_Steps(state.model.adhesion.d, pre, landing), state, target, step)


def trace(model: AdhesiveModel, path, pre: dict, label: str = "",
           progress=None) -> list[_Record]:
    """States along the path with step control and jumps (module docstring),
    from `model`'s mesh (moved along with the contact if it follows it);
    `progress(line)`, if given, hears of every level reached."""
    newton = model.newton
    branches = _branches(path)
    # a progress line every ~5 s of a run past ~5 s (the job's log; logging only)
    ticker = StepProgress(log, f"adhesive path{' of ' + label if label else ''}: ",
                          total=len(path) - 1)
    t0 = time.perf_counter()
    try:
        u, parts, T, its = newton.solve(float(path[0]), np.zeros(model.zone.ndofs))
    except StepFailed as exc:
        raise ConvergenceError(0, float(path[0]), math.nan, 0, str(exc), label) from None
    state = newton.state(float(path[0]), u, parts, T, its)
    state.model = model
    try:
        state, more = _follow(state)
    except ConvergenceError as exc:
        exc.sample = label
        raise
    state.iterations = its + more
    state.wall_time = time.perf_counter() - t0
    records = [_Record(state, branches[0], False, True, 0)]
    landing = None  # of a retraction: built from the approach's records when it starts
    # the approach's levels (state, whether the level into it jumped) while the path
    # has only gone up; `mirror` indexes the one the retraction is at, if any (`_retrace`)
    ups, mirror = [(state, False)], None
    for n in range(1, len(path)):
        target, branch = float(path[n]), branches[n]
        t0 = time.perf_counter()
        if branch != "retract":
            landing = None
        elif landing is None:
            landing = Landing((r.state for r in records if r.branch == "approach"),
                               model.adhesion)
        if branch == "retract" and ups is not None:
            mirror = len(ups) - 1 if mirror is None else mirror
            back = _retrace(ups, mirror, target)
            ups = None if back is None else ups
        else:
            back = None
        if back is not None:
            state, mirror = back
            state.wall_time = time.perf_counter() - t0
            records.append(_Record(state, branch, False, True, n))
            ticker.update(n, n / (len(path) - 1), f"flat at w = {target:.4g} m ({branch}), "
                          f"force {state.force:.4g} N", 0)
            if progress is not None:
                progress(f"level {n} of {len(path) - 1} ({branch}): w = {target:.6g} m, force "
                         f"{state.force:.6g} N, retraced (the approach's state)")
            _release_behind(records, state)
            continue
        try:
            state, jumps, iterations, halvings = _advance(state, target, pre, n, landing)
        except ConvergenceError as exc:
            exc.sample = label
            raise
        if ups is not None and branch == "approach":
            ups.append((state, bool(jumps)))
        else:
            ups = None  # retraced no further once solved, nor after a second approach
        for before, after in jumps:
            if records[-1].state is not before:
                records.append(_Record(before, branch, False, False, n))
            records.append(_Record(after, branch, True, after is state, n))
        state.iterations, state.cuts = iterations, halvings
        state.wall_time = time.perf_counter() - t0
        if records[-1].state is not state:
            records.append(_Record(state, branch, False, True, n))
        ticker.update(n, n / (len(path) - 1), f"flat at w = {target:.4g} m ({branch}), "
                      f"force {state.force:.4g} N", iterations)
        if progress is not None:
            progress(f"level {n} of {len(path) - 1} ({branch}): w = {target:.6g} m, force "
                     f"{state.force:.6g} N, {iterations} Newton iterations, {halvings} cuts, "
                     f"{len(jumps)} jumps, {state.wall_time:.3g} s")
        _release_behind(records, state)
    return records


def evaluate_states(states) -> None:
    """The outputs (`AdhesiveState.fields`) of those `states` that lack them,
    each state on its own mesh."""
    todo = [s for s in states if s.fields is None]
    for model in {id(s.model): s.model for s in todo}.values():
        mine = [s for s in todo if s.model is model]
        ev = model.evaluate(mine)
        for j, s in enumerate(mine):
            s.fields = {name: values[j] for name, values in ev.items()}


def _release_behind(records: list, state: AdhesiveState) -> None:
    """Evaluate the recorded states on meshes other than `state`'s, and drop
    those meshes' factors (`AdhesiveModel.release`)."""
    behind = [r.state for r in records
              if r.state.model is not state.model and r.state.model.cond.lu is not None]
    evaluate_states(behind)
    for s in behind:
        s.model.release()


def _retrace(ups: list, mirror: int, target: float):
    """The retraction's state at `target` when it runs back over a continuous
    stretch of the approach: (that state, its index in `ups`) or None.

    An elastic body with a conservative adhesion has no memory: its states
    are the local minima of Pi(u; w), and along a branch without a fold
    (Pi's Hessian positive definite) they are a function u(w) of the flat's
    position alone (implicit function theorem), whichever way the flat
    moves.  So while the retraction stands on the state the approach
    reached at level k, `ups[mirror]` (at the turn: the same state; `trace`
    keeps `ups` only while every level of the retraction was retraced), and the
    approach came to it from level k - 1 at `target` without a jump
    (`_advance`'s continuity test, `AdhesiveModel.continuity`, passed on
    every step in between), the retraction's equilibrium at `target` is the
    approach's state there, on the same mesh; solving it again would
    retrace the same branch, with the same tests, to the solver's
    tolerance.  A step the approach crossed with a jump (the jump-in) is
    solved: retracting, the contact hangs on past it (report 7.3's
    hysteresis).  The state returned is a copy with no Newton iterations or
    cuts of its own.  A jump smaller than the continuity test's allowance
    (recorded on approach as a steep continuous stretch) is retraced as the
    approach passed it.
    """
    if mirror < 1 or ups[mirror][1]:
        return None
    before = ups[mirror - 1][0]
    if before.w != target:
        return None
    return replace(before, iterations=0, cuts=0, wall_time=0.0), mirror - 1


def retract_indices(branch: np.ndarray) -> np.ndarray:
    """Records of the retraction, with the turning point (the deepest state) first."""
    idx = np.nonzero(branch == "retract")[0]
    if idx.size and idx[0] > 0:
        idx = np.concatenate(([idx[0] - 1], idx))
    return idx


def refine_pull_off(records: list, pre: dict, resolution: float) -> None:
    """Bisect the path around the largest tensile force on retraction.

    States at the midpoints between the minimum of the force and its
    neighbours on the same continuous branch (continued from the minimum,
    rejected if discontinuous from it) are inserted, until the neighbours
    are `resolution` apart.  Inserted records are not `requested`.
    """
    for _ in range(40):
        idx = list(retract_indices(np.array([r.branch for r in records])))
        if not idx:
            return
        i = min(idx, key=lambda k: records[k].state.force)
        src = records[i].state
        if src.force >= 0:
            return
        inserts = []
        for j in (i + 1, i - 1):  # the later index first: inserting keeps the other valid
            if j not in idx:
                continue
            b = max(i, j)  # records[b].jump: a discontinuity between b - 1 and b
            if records[b].jump or abs(records[j].state.w - src.w) <= resolution:
                continue
            mid = 0.5 * (records[j].state.w + src.w)
            try:
                new, jumps, its, cuts = _advance(src, mid, pre)
            except (ConvergenceError, Overflow):
                continue
            if jumps:  # not on the branch of the minimum
                continue
            new.iterations, new.cuts = its, cuts
            inserts.append((b, _Record(new, records[b].branch, False, False, records[b].step)))
        if not inserts:
            return
        for b, rec in inserts:  # descending b
            records.insert(b, rec)
