"""The steps of an inelastic history (`solve_asperity_history`) for `march.march`:
what a try solves and checks, what an accepted step records, and when the run stops.

A step whose error indicator E (`solvers.time_error`) exceeds 2
``time_tolerance`` is rejected and retried with the time step h 0.9 (tol /
E)^(1/(p+1)) (p the order, at least 0.2 h); after an accepted step the time
step becomes h min(2, 0.9 (tol / E)^(1/(p+1))). (Rejecting only above twice
the tolerance: the estimate jumps when a node of the surface comes into
contact, and rejecting at the tolerance takes more steps for no gain in
accuracy.) E is recorded per step (``time_error``), its largest value and the
rejections it caused as attributes. With local error control the error of the
end of the history falls roughly in proportion to the tolerance
(tests/fe/test_inelastic_time_error.py). The Newton tolerance of a rate-
dependent material is 1e-2 ``time_tolerance`` where that is looser than the
preset's (``NEWTON_FRACTION``): equilibrium two orders tighter than the time
error of a step, in the same measure. Newton's scale is the contact force of
the current iterate (not the largest of the iterations: an overshooting
predictor pushes a node deep into the stiff penalty and would inflate it), or,
if larger, up to twice that of the last accepted step.

Other step control (the steps are marched by `march.march`): a step is
rejected and retried with half the time step (counted in ``step_cuts``, with
the error rejections) when Newton does not converge (or gives non-finite
values), or when the step is too coarse for the output: the interference
changed by more than ``max_interference_step`` times the largest interference,
or the equivalent inelastic strain changed somewhere by more than
``max_inelastic_step`` (a safety bound; the error control decides). Slow
Newton convergence shrinks the next time step. A step that would cross a knot
of the history ends on it.

Rupture (Bodner-Partom with damage, 3.15: w -> 1).  `BodnerPartom` declares
a point ruptured when w reaches ``omega_rupture`` or its inelastic strain
rate runs away past ``rupture_strain_rate``, then freezes its damage and
keeps a finite, softened state (Z sqrt(1 - w^2)).  The solver reports the
first rupture (step, time, interference and the position of the point:
attributes ``rupture_*``) and the number of ruptured points per step
(``ruptured_points``), and, by ``on_rupture``, continues (default: the
ruptured points keep the state the material gives them and are left out
of the time error), stops there (``"stop"``: the dataset ends at the
rupture step, ``completed`` 0, ``stop_reason`` says why), or raises
`RuptureError` naming the step, the interference and the position
(``"raise"``).  A Newton failure after a rupture says how many points
had ruptured.

Unloading: the history is followed in reverse.  The first time the force
falls to zero on unloading, the crossing is located by bisection of the
step (to ``event_tolerance`` of the largest interference) and the residual
interference is reported by linear interpolation of the force of the last
steps (attribute ``residual_interference``, NaN if the force never returned
to zero); with ``stop_at_zero_force`` (default) the run stops there, else
it follows the rest of the history.
"""

from __future__ import annotations

import logging
import math
import time

import numpy as np

from asperity.fe.errors import ContactZoneError, RuptureError, StepFailed
from asperity.fe.materials.elastic import equivalent_strain
from asperity.fe.solvers.nonlinear import Pace, strain_limited
from asperity.io.run_report import StepProgress
from asperity.fe.drivers.remesh import ContactMeshes, Transfer
from asperity.fe.drivers.march import Accepted, Marching, Trial
from asperity.fe.solvers.time_error import (bdf2_coefficients, bdf2_start, error_indicator,
                                            flow_rates, local_errors)
from asperity.fe.drivers.inelastic_model import InelasticModel

log = logging.getLogger(__name__)

#: on unloading, a force below this fraction of the largest force counts as zero
ZERO_FORCE = 1e-6


#: time-error controller: safety factor, largest growth, smallest factor, and
#: a step is rejected when its indicator exceeds REJECT x the tolerance
SAFETY, MAX_GROWTH, MIN_FACTOR, REJECT = 0.9, 2.0, 0.2, 2.0


#: Newton's say on the next time step: no growth after more than 4
#: iterations, a shrink by 0.7 after 10 or more
PACE = Pace(fast=4, growth=MAX_GROWTH, slow=10, shrink=0.7)


def error_factor(err: float, tol: float, order: int) -> float:
    """The time-error controller's factor on the step of an error indicator `err`
    against the tolerance `tol` for a method of `order`: 0.9 (tol / E)^(1/(p+1)), at
    least ``MIN_FACTOR`` (a rejected step's retry; an accepted one grows by at most
    ``MAX_GROWTH``)."""
    return max(MIN_FACTOR, SAFETY * (tol / err) ** (1.0 / (order + 1)))


class HistoryMarch(Marching):
    """The steps of `solve_asperity_history` for `march`: a try solves the step's
    equilibrium with BDF2 or backward Euler and checks its interference and inelastic
    strain steps and time error; an accepted step may first be re-solved on a new mesh
    (``remesh``), then is recorded, checked for rupture and the zero-force crossing of
    unloading, and sets the next time step (module docstring)."""

    def __init__(self, model: InelasticModel, meshes: ContactMeshes, history, *,
                 r_candidate, tolerance, kinematics, integration, dw_max, dt_cap,
                 max_inelastic_step, max_cuts, time_tolerance, event_tolerance, w_max,
                 stop_at_zero_force, on_rupture, remesh, remesh_times, rg, progress):
        self.model, self.meshes, self.history = model, meshes, history
        # what a new mesh's model is made with (`_remeshed`)
        self.r_cand, self.tolerance, self.kinematics = r_candidate, tolerance, kinematics
        self.material = model.material
        self.rate_dependent = hasattr(self.material, "rates")
        self.integration, self.dw_max, self.dt_cap = integration, dw_max, dt_cap
        self.max_inelastic_step, self.max_cuts = max_inelastic_step, max_cuts
        self.time_tolerance, self.event_tolerance = time_tolerance, event_tolerance
        self.w_max, self.stop_at_zero_force, self.on_rupture = w_max, stop_at_zero_force, on_rupture
        self.remesh, self.rg, self.progress = remesh, rg, progress
        self.remesh_times = sorted(float(x) for x in np.atleast_1d(remesh_times))
        self.end = history.end
        self.interior_knots = np.asarray(history.times, float)[1:-1]
        self.t = float(history.times[0])
        self.w = float(history(self.t))
        # a progress line every ~5 s of a run past ~5 s (the job's log; logging only)
        self.ticker, self.t_first = StepProgress(log, "asperity history: "), self.t
        self.state = self.material.initial_state(model.shape)
        self.u = np.zeros(model.disc.ndofs)
        self.u_prev, self.t_prev = None, None
        self.rows = []
        # rates of the controlled variables at the end of the last two steps (the
        # body starts at rest), the state one step back and that step's length
        self.r_n = {k: np.zeros_like(v)
                    for k, v in flow_rates(self.material, self.state, self.state, 1.0).items()}
        self.r_prev, self.state_prev, self.h_prev = None, None, math.nan
        self.f_ref = 0.0  # contact force norm of the last accepted step
        # initial state (assumed stress free, w <= 0 or first touch)
        _, out0 = model.evaluate(self.u, self.w, self.state, 0.0, tangent=False)
        self.rows.append(dict(
            model.record(self.u, self.w, out0), time=self.t, branch=history.branch(self.t),
            newton_iterations=0, step_cuts=0, time_step=0.0, integration_order=0,
            time_error=0.0, wall_time=0.0, dofs=model.dofs))
        self.residual = math.nan
        self.f_max = 0.0
        self.error_rejections = 0
        self.rupture = None
        self.stop_reason = ""
        self.factorizations = 0  # of the models replaced by remeshing
        self.redo = False  # the step is being re-solved on a new mesh
        self.carried = 0  # Newton iterations of a step solved on the mesh it left
        self.remeshed_steps = []

    def begin(self, n, dt):
        self.step_start = time.perf_counter()
        self.iterations, self.carried = self.carried, 0
        t = self.t
        self.branch = self.history.branch(t)
        # BDF2 from the second step on, restarted with backward Euler after a
        # knot of the history (where the loading rate jumps)
        at_knot = bool(np.any(np.abs(self.interior_knots - t) <= 1e-12 * self.end))
        self.order = 2 if (self.integration == "bdf2" and self.rate_dependent
                           and self.state_prev is not None and not at_knot) else 1
        return self.dt_cap, self.history.next_knot(t)

    def attempt(self, n, t_new, cuts):
        model, t, w, u, state = self.model, self.t, self.w, self.u, self.state
        h = t_new - t
        w_new = float(self.history(t_new))
        data = dict(h=h, w_new=w_new)
        if abs(w_new - w) > self.dw_max * (1 + 1e-9):
            return Trial(t_new, "interference step too large", data=data)
        reason, shrink = None, 0.5
        # predictor: extrapolate the last increment on the same branch
        u0 = u.copy()
        if self.u_prev is not None and self.rows[-1]["branch"] == self.branch \
                and t - self.t_prev > 0:
            u0 += (h / (t - self.t_prev)) * (u - self.u_prev)
        order = self.order
        if order == 2:
            a, b, c, _ = bdf2_coefficients(h / self.h_prev)
            start, h_m = bdf2_start(state, self.state_prev, a, b), c * h
        else:
            start, h_m = state, h
        try:
            u_new, out, its, to_pace = model.solve_step(u0, w_new, start, h_m, self.f_ref)
        except StepFailed as exc:
            self.iterations += exc.iterations
            return Trial(t_new, str(exc), data=data)
        self.iterations += its
        # what the step control reads: the tries before in full, this one to PACE_TOLERANCE
        paced = self.iterations - its + to_pace
        new = out["state"]
        if order == 2 and hasattr(new, "time"):
            new.time = state.time + h
        eps_step = float(np.max(equivalent_strain(new.inelastic_strain - state.inelastic_strain)))
        r_new = flow_rates(self.material, start, new, h_m)
        if self.rate_dependent:
            err = error_indicator(
                model, local_errors(order, h, self.h_prev, r_new, self.r_n, self.r_prev), out)
        else:
            err = math.nan
        tol = self.time_tolerance
        if eps_step > self.max_inelastic_step:
            reason = "inelastic strain step too large"
        elif err > REJECT * tol:
            reason = f"time error {err:.3g} above the tolerance {tol:g}"
            shrink = error_factor(err, tol, order)
            self.error_rejections += 1
        if reason is not None:
            return Trial(t_new, reason, shrink, data=data)
        rec = model.record(u_new, w_new, out)
        if rec["overflow"]:
            if not model.grow_zone():
                raise ContactZoneError("the contact reached the outer edge of the top surface "
                                       f"at step {n} (interference {w_new:.6g} m)")
            return Trial(t_new, again=True)  # same step on the larger zone (not a cut)
        f_zero = ZERO_FORCE * self.f_max
        if (self.branch == "unloading" and rec["force"] <= f_zero
                and self.rows[-1]["force"] > f_zero and math.isnan(self.residual)
                and abs(w_new - w) > self.event_tolerance * self.w_max):
            # locate the zero force crossing: not a cut
            return Trial(t_new, again=True, dt=0.5 * h)
        data.update(u_new=u_new, out=out, new=new, rec=rec, r_new=r_new, err=err,
                    eps_step=eps_step, paced=paced)
        return Trial(t_new, data=data)

    def failure(self, cuts, trial):
        detail = trial.reason
        if self.rupture is not None:
            detail += (f" ({self.rows[-1]['ruptured_points']} points ruptured since step "
                       f"{self.rupture['step']})")
        return cuts.error(trial.data["w_new"], self.w, detail)

    def _remeshed(self, n, trial) -> bool:
        """A new mesh around the contact and the plastic zone of the step, the state at
        its start transferred, the step to be re-solved on it; whether it was built."""
        d = trial.data
        rec, new = d["rec"], d["new"]
        forced = bool(self.remesh_times) and trial.t_new >= self.remesh_times[0] * (1 - 1e-12)
        why = "" if self.redo or not (self.remesh or forced) else (
            "forced" if forced else self.meshes.due(rec["contact_radius"], self.model.disc, new))
        self.redo = False
        if not why:
            return False
        if forced:
            self.remesh_times.pop(0)
        model = self.model
        new_disc = self.meshes.build(max(rec["contact_radius"], 1e-3 * self.rg), model.disc, new)
        move = Transfer(model.disc, new_disc)
        self.factorizations += model.factorizations
        self.r_cand = max(self.r_cand, model.r_candidate)
        self.model = InelasticModel(new_disc, model.geometry, self.material, model.preset,
                                    self.r_cand, model.penalty_factor, self.tolerance,
                                    self.kinematics)
        self.u = move.displacement(self.u)
        self.u_prev = None if self.u_prev is None else move.displacement(self.u_prev)
        self.state = move.state(self.state)
        self.r_n = move.fields(self.r_n)
        self.state_prev, self.r_prev = None, None  # restart with backward Euler
        _, out_t = self.model.evaluate(self.u, self.w, self.state, 0.0, tangent=False)
        self.f_ref = float(np.linalg.norm(self.model.zone.nodal(out_t["traction"])))
        self.remeshed_steps.append(n)
        self.redo = True
        self.carried = self.iterations
        return True

    def accept(self, n, trial, cuts):
        d = trial.data
        h = d["h"]
        if self._remeshed(n, trial):
            return Accepted(h, redo=True)
        rec, err, order = d["rec"], d["err"], self.order
        self.u_prev, self.t_prev = self.u, self.t
        self.state_prev, self.h_prev = self.state, h
        self.r_prev, self.r_n = self.r_n, d["r_new"]
        self.u, self.t, self.w, self.state = d["u_new"], trial.t_new, d["w_new"], d["new"]
        t, w, branch, iterations = self.t, self.w, self.branch, self.iterations
        self.f_ref = float(np.linalg.norm(self.model.zone.nodal(d["out"]["traction"])))
        self.rows.append(dict(
            rec, time=t, branch=branch, newton_iterations=iterations, step_cuts=cuts.count,
            time_step=h, integration_order=order, time_error=err,
            wall_time=time.perf_counter() - self.step_start, dofs=self.model.dofs))
        t_end = self.end
        self.ticker.update(n, (t - self.t_first) / (t_end - self.t_first),
                           f"t = {t:.4g} of {t_end:.4g} s ({branch}), interference {w:.4g} m, "
                           f"force {rec['force']:.4g} N", iterations)
        if self.progress is not None:
            self.progress(f"step {n} ({branch}): t = {t:.6g} of {t_end:.6g} s, w = {w:.6g} m, "
                          f"force {rec['force']:.6g} N, {iterations} Newton iterations, "
                          f"{cuts.count} cuts, {self.rows[-1]['wall_time']:.3g} s")
        # next time step: the error controller, limited by Newton and the caps
        tol = self.time_tolerance
        if math.isnan(err) or err <= 0:
            fac = MAX_GROWTH
        else:
            fac = min(MAX_GROWTH, error_factor(err, tol, order))
        dt = PACE.factor(d["paced"], cuts.count, fac) * h
        v = self.history.velocity(t)
        if v > 0:
            dt = min(dt, self.dw_max / v)
        dt = strain_limited(dt, h, d["eps_step"], self.max_inelastic_step)
        f_zero = ZERO_FORCE * self.f_max
        self.f_max = max(self.f_max, rec["force"])
        if rec["ruptured_points"] and self.rupture is None and self._ruptured(n, rec):
            return Accepted(dt, stop=True)
        if branch == "unloading" and rec["force"] <= f_zero and self.rows[-2]["force"] > f_zero \
                and math.isnan(self.residual):
            self.residual = _zero_force_crossing(self.rows)  # the first crossing only
            if self.stop_at_zero_force:
                return Accepted(dt, stop=True)
        return Accepted(dt)

    def _ruptured(self, n, rec) -> bool:
        """Record the first rupture (step `n`); raise or say to stop, by ``on_rupture``."""
        state, t, w = self.state, self.t, self.w
        rt = getattr(state, "rupture_time", None)
        mask = np.asarray(state.ruptured).ravel()
        first = (int(np.argmin(np.where(mask, np.asarray(rt).ravel(), np.inf)))
                 if rt is not None else int(np.argmax(mask)))
        pos = self.model.point_position(first)
        t_r = float(np.asarray(rt).ravel()[first]) if rt is not None else t
        self.rupture = dict(step=n, time=t_r if math.isfinite(t_r) else t, interference=w,
                            position=pos[0], depth=pos[1])
        if self.on_rupture == "raise":
            raise RuptureError(n, w, self.rupture["time"], pos, rec["ruptured_points"])
        if self.on_rupture == "stop":
            self.stop_reason = (f"material ruptured at step {n} (interference {w:.6g} m): "
                                f"{rec['ruptured_points']} point(s), the first at "
                                f"r = {pos[0]:.6g} m, {pos[1]:.6g} m below the surface")
            return True
        return False


def _zero_force_crossing(rows) -> float:
    """Interference where the unloading force reaches zero.

    The last step has F ~ 0 (the penalty force vanishes once the surface
    separates; below ``ZERO_FORCE`` x the largest force counts as zero: the
    smoothed penalty leaves a vanishing force at first touch), so the force
    of the last two steps before it is extrapolated linearly to zero, the
    result kept between the last of them and the zero-force step.
    """
    b, a = rows[-1], rows[-2]
    lo, hi = sorted((b["interference"], a["interference"]))
    est = b["interference"]
    if len(rows) >= 3 and rows[-3]["force"] > a["force"] > 0:
        c = rows[-3]
        slope = (c["force"] - a["force"]) / (c["interference"] - a["interference"])
        if slope > 0:
            est = a["interference"] - a["force"] / slope
    return float(np.clip(est, lo, hi))
