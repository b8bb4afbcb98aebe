"""The time steps of the 3-D asperity pressed and slid, for `march.march` (report 9.2).

Time stepping (`SlidingMarch`, run by `solid3d.solve_sliding`): the flat's motion
is piecewise linear in time (`flat_motion.FlatMotion`); steps never cross a time of
the step grid (`flat_motion.step_grid`); a step is cut in half when
Newton fails, gives non-finite values or the local update fails, or when
the equivalent inelastic strain changed anywhere by more than
``max_inelastic_step``; the time step grows back (x1.5) after easy steps,
up to the preset's cap (the segment's duration / its step count), from the
length it tried when the grid cut it short.  A run
whose accepted steps stay under ``stall_fraction`` (`solid3d.STALL_FRACTION`) of
their cap for ``stall_steps`` steps in a row has stalled (past the junction's
critical coefficient, `sliding_model`): it stops there with ``stop_reason``,
keeping its steps, instead of grinding on at that pace.

Through the slip instability: a sliding step whose Newton fails after it was cut
below ``stall_fraction`` of its cap (where the steps would stall) is solved again
from the state at its start through damped solves
(`sliding_model.SlidingModel.solve_through_slip`).  The step is cut again only if
that fails too.  ``damped_solves`` records it per step.

An accepted step drags the anchors of the sticking points, is recorded with the
critical factor of the sliding junction (`SlidingModel.critical_factor`, at the
start of sliding and after every sliding step; a warning the first time it is
below 1) and takes the snapshots due: the displacements and inelastic strain on the
plane of symmetry (`plane_snapshot`) and where the largest inelastic strain sits
relative to the junction (`largest_deformation`).
"""

from __future__ import annotations

import logging
import math
import time

import numpy as np

from asperity.fe.contact.sliding import FrictionLaw
from asperity.fe.discretization.half_model import HalfModel
from asperity.fe.drivers.flat_motion import FlatMotion, step_caps, step_grid
from asperity.fe.drivers.march import Accepted, Marching, Trial
from asperity.fe.drivers.sliding_model import CRITICAL_FACTOR_BOUND, SlidingModel
from asperity.fe.errors import ContactZoneError, StepFailed
from asperity.fe.materials.elastic import equivalent_strain
from asperity.fe.outputs import INELASTIC_THRESHOLD
from asperity.fe.solvers.nonlinear import Pace, strain_limited
from asperity.io.run_report import StepProgress

log = logging.getLogger(__name__)

#: time step growth by 1.5 after a step without cuts that took at most 12
#: Newton iterations (a sliding junction often takes more than 5 per step: a
#: lower threshold never lets the step grow back after a cut)
PACE = Pace(fast=12, growth=1.5)
#: "at the junction": the largest inelastic strain lies less than this
#: fraction of the equivalent contact radius sqrt(A / pi) below the flat
JUNCTION_DEPTH_FRACTION = 0.25


def _default_snapshots(motion: FlatMotion) -> dict:
    """The end of pressing and the end of `motion`: {name: time}."""
    times = np.asarray(motion.times, float)
    snapshots = {}
    for i in range(len(times) - 1):
        if motion.phase(times[i]) == "normal" and (i + 1 == len(times) - 1 or
                                                   motion.phase(times[i + 1]) != "normal"):
            snapshots["end of pressing"] = float(times[i + 1])
    snapshots["end"] = float(times[-1])
    return snapshots


class SlidingMarch(Marching):
    """The steps of `solve_sliding` for `march`: a try solves the step (through the
    slip instability once sliding steps are cut to where they would stall) and checks
    its inelastic strain step; an accepted step drags the anchors of the sticking
    points, is recorded with the critical factor of the sliding junction, takes the
    snapshots due and sets the next time step; the run stops when the steps stall."""

    def __init__(self, sm: SlidingModel, motion: FlatMotion, friction: FrictionLaw,
                 preset: dict, *, stall_steps, stall_fraction, snapshots, contact_section, say):
        self.sm, self.model, self.motion, self.friction = sm, sm.m, motion, friction
        self.stall_steps, self.stall_fraction = stall_steps, stall_fraction
        self.contact_section, self.say = contact_section, say
        self.d_knots = np.asarray(motion.tangential, float)
        self.caps = step_caps(motion, preset)
        self.grid = step_grid(motion, preset)
        self.max_inel = float(preset["max_inelastic_step"])
        self.max_cuts = int(preset["max_cuts"])
        if snapshots is None:
            snapshots = _default_snapshots(motion)
        self.snap_times = {k: float(v) for k, v in snapshots.items()}
        self.snap = {}
        self.end = motion.end
        self.t = t = motion.start
        self.w, self.delta = motion(t)
        self.state = sm.material.initial_state(self.model.shape, components=6)
        self.iface = sm.initial_interface(self.delta)
        self.u = np.zeros(self.model.ndofs)
        _, out0 = sm.evaluate(self.u, self.w, self.delta, self.state, self.iface, 0.0,
                              tangent=True)
        self.out_last = out0
        self.f_ref = 0.0  # contact force norm of the last accepted step
        self.rows = [dict(sm.record(self.u, self.w, self.delta, out0),
                          critical_shear_factor=math.nan, time=t, phase=motion.phase(t),
                          newton_iterations=0, step_cuts=0, damped_solves=0, time_step=0.0,
                          wall_time=0.0)]
        for k, ts in self.snap_times.items():
            if ts <= t:
                self.snap[k] = (t, plane_snapshot(self.model, self.u, self.state,
                                             out0["contact"]["tn"] if contact_section
                                             else None), {})
        # a progress line every ~5 s of a run past ~5 s (the job's log; logging only)
        self.ticker = StepProgress(log, "sliding: ")
        self.critical, self.warned = [], False  # critical_factor at the starts of sliding and after
        self.slow, self.stop_reason = 0, ""     # steps in a row below stall_fraction of their cap

    def begin(self, n, dt):
        t = self.t
        self.step_start = time.perf_counter()
        self.iterations = 0
        self.phase = self.motion.phase(t)
        self.cap = self.caps[self.motion.segment(t)]
        self.proposed = min(dt, self.cap)
        grid = self.grid
        knot = float(grid[np.searchsorted(grid, t + 1e-12 * max(abs(t), 1.0), side="right")])
        return self.cap, knot

    def attempt(self, n, t_new, cuts):
        sm, state, iface = self.sm, self.state, self.iface
        h = t_new - self.t
        w_new, d_new = self.motion(t_new)
        data = dict(h=h, w_new=w_new, d_new=d_new)
        u0 = sm.predict(self.u, self.out_last, w_new - self.w, d_new - self.delta)
        damped = 0
        try:
            try:
                u_new, out, its = sm.solve_step(u0, w_new, d_new, state, iface, h, self.f_ref)
            except StepFailed as exc:
                if not (self.phase == "sliding" and h < self.stall_fraction * self.cap):
                    raise
                # a sliding step cut to where its steps would stall: through the
                # slip instability
                self.iterations += exc.iterations
                u_new, out, its, damped = sm.solve_through_slip(self.u, w_new, d_new, state,
                                                                iface, h, self.f_ref)
            self.iterations += its
            step_inel = float(np.max(equivalent_strain(
                out["state"].inelastic_strain - state.inelastic_strain)))
            if step_inel > self.max_inel:
                return Trial(t_new, f"inelastic strain step {step_inel:.3g} > {self.max_inel:g}",
                             data=data)
        except StepFailed as exc:
            self.iterations += exc.iterations
            return Trial(t_new, str(exc), data=data)
        rec = sm.record(u_new, w_new, d_new, out)
        rec["critical_shear_factor"] = math.nan
        if self.phase == "sliding":
            rec["critical_shear_factor"] = sm.critical_factor(
                u_new, w_new, d_new, out, _direction(self.motion, self.d_knots, self.t))
        if rec["overflow"]:
            raise ContactZoneError(
                f"step {n} (t = {t_new:.6g} s): the contact reached the edge of the "
                f"candidate zone (radius {self.model.contact_radius:.4g} m); give a larger "
                f"contact_radius")
        data.update(u_new=u_new, out=out, rec=rec, damped=damped, step_inel=step_inel)
        return Trial(t_new, data=data)

    def failure(self, cuts, trial):
        d = trial.data
        return cuts.error(d["w_new"], self.w,
                          f"t = {trial.t_new:.6g} s, delta = {d['d_new']:.6g} m: {trial.reason}")

    def cut(self, n, dt, trial):
        self.say(f"step {n}: cut to dt = {dt:.4g} s ({trial.reason})")

    def accept(self, n, trial, cuts):
        d = trial.data
        sm, model, motion, friction = self.sm, self.model, self.motion, self.friction
        h, out, rec, damped, iterations = d["h"], d["out"], d["rec"], d["damped"], self.iterations
        self.iface = sm.commit(out, self.iface)
        self.f_ref = float(np.linalg.norm(out["contact"]["fc"]))
        self.u, self.t, self.w, self.delta, self.state = (d["u_new"], trial.t_new, d["w_new"],
                                                          d["d_new"], out["state"])
        u, t, w, delta, state, phase = self.u, self.t, self.w, self.delta, self.state, self.phase
        # the converged state with the dragged anchors, for the next predictor
        _, self.out_last = sm.evaluate(u, w, delta, state, self.iface, h)
        rows = self.rows
        rows.append(dict(rec, time=t, phase=phase, newton_iterations=iterations,
                         step_cuts=cuts.count, damped_solves=damped, time_step=h,
                         wall_time=time.perf_counter() - self.step_start))
        for k, ts in self.snap_times.items():
            if k not in self.snap and t >= ts * (1 - 1e-12):
                a_max = max(r["contact_area"] for r in rows)
                a_ref = math.sqrt(a_max / math.pi) if a_max > 0 else model.contact_radius / 2.5
                self.snap[k] = (t, plane_snapshot(model, u, state, out["contact"]["tn"]
                                             if self.contact_section else None),
                                largest_deformation(model, u, w, state, a_ref))
        self.ticker.update(n, (t - motion.start) / (motion.end - motion.start),
                           f"t = {t:.4g} of {motion.end:.4g} s ({phase}), approach {w:.4g} m, "
                           f"slide {delta:.4g} m", iterations)
        s_c = rec["critical_shear_factor"]
        self.say(f"step {n}: t = {t:.6g} of {motion.end:.6g} s, w = {w:.4g} m, "
                 f"delta = {delta:.4g} m, F_N = {rec['normal_force']:.4g} N, "
                 f"F_T = {rec['tangential_force']:.4g} N, A = {rec['contact_area']:.4g} m^2, "
                 f"{iterations} Newton iterations, {cuts.count} cuts"
                 + (f", through the slip in {damped} damped solves" if damped else "")
                 + ("" if math.isnan(s_c) else f", critical: {_critical_text(s_c, friction)}"))
        if phase != "sliding" and motion.phase(t) == "sliding" and t < motion.end * (1 - 1e-12):
            s_c = sm.critical_factor(u, w, delta, out, _direction(motion, self.d_knots, t))
            self.say(f"start of sliding at t = {t:.6g} s: the sliding junction's tangent "
                     + (f"turns singular at {_critical_text(s_c, friction)}"
                        if math.isfinite(s_c) else
                        f"stays regular up to {CRITICAL_FACTOR_BOUND:g} times the shear "
                        "resistance"))
        if not math.isnan(s_c):
            self._critical(t, s_c)
        # a step that ended on a time of the grid before its try's length grows from
        # that length, not from the rest of the way to the grid time
        reached = h if cuts.count else max(h, self.proposed)
        dt = strain_limited(PACE.factor(iterations, cuts.count) * reached, h, d["step_inel"],
                            self.max_inel)
        self.slow = self.slow + 1 if reached < self.stall_fraction * self.cap else 0
        stall = self.stall_steps
        if self.slow >= stall and t < motion.end * (1 - 1e-12):  # not on the last step
            self._stalled(n, (t - rows[-stall - 1]["time"]) / stall)
            return Accepted(dt, stop=True)
        return Accepted(dt)

    def _critical(self, t, s_c):
        """Keep the critical factor `s_c` of time `t`; warn the first time it is below 1."""
        self.critical.append(s_c)
        if s_c < 1.0 and not self.warned:
            self.warned = True
            log.warning("t = %.6g s: the sliding junction's tangent turns singular at %s, "
                        "below the shear resistance of the scene: the sliding problem of "
                        "this mesh is not unique near this state (Hassani et al. 2003); "
                        "expect step cuts, stalls and forces that depend on the mesh",
                        t, _critical_text(s_c, self.friction))

    def _stalled(self, n, pace):
        """Say why the run stops at step `n`, its last steps `pace` s long on average."""
        t, critical, friction, stall = self.t, self.critical, self.friction, self.stall_steps
        self.stop_reason = (
            f"stalled at step {n} (t = {t:.6g} s, delta = {self.delta:.4g} m): the last "
            f"{stall} steps advanced {pace:.3g} s each on average, under "
            f"{self.stall_fraction:g} of the step cap {self.cap:.4g} s; the remaining "
            f"{self.motion.end - t:.6g} s would take about {(self.motion.end - t) / pace:.3g} "
            "more steps" + (f"; smallest critical factor {_critical_text(min(critical), friction)}"
                            if critical else "")
            + ("; past it the sliding problem is not unique: a lower shear resistance, "
               "or a constant shear strength (asperity_sliding_junction), slides"
               if critical and min(critical) < 1.0 else ""))
        log.warning("%s", self.stop_reason)
        self.say(f"stopped: {self.stop_reason}")


def plane_snapshot(model: HalfModel, u, state, tn=None) -> dict:
    nd = model.node_displacements(u)[:, model.plane_nodes]
    ep = model.nodal_average(equivalent_strain(state.inelastic_strain))[model.plane_nodes]
    return dict(ux=nd[0], uz=nd[2], ep=ep, **({} if tn is None else dict(tn=np.array(tn))))


def _direction(motion: FlatMotion, d_knots, t: float) -> float:
    """The flat's direction along x in the segment of the motion from t."""
    seg = motion.segment(t)
    return float(d_knots[seg + 1] - d_knots[seg])


def _critical_text(factor: float, friction: FrictionLaw) -> str:
    """`SlidingModel.critical_factor` in words: a friction coefficient for a Coulomb
    law, else a factor of the shear resistance ("none" where it is inf)."""
    r = friction.resistance
    if not math.isfinite(factor):
        return f"none below {CRITICAL_FACTOR_BOUND:g} times the shear resistance"
    if r.c0 == 0.0 and r.c2 == 0.0:
        return f"a friction coefficient {factor * r.c1:.3g}"
    return f"{factor:.3g} times the shear resistance"


def largest_deformation(model: HalfModel, u, w, state, a_ref: float) -> dict:
    """Where the largest equivalent inelastic strain sits, relative to the junction.

    Its depth below the flat (z = -w) in the deformed configuration is
    compared with ``JUNCTION_DEPTH_FRACTION`` a_ref, a_ref = sqrt(A_max / pi)
    the equivalent radius of the largest contact area of the run.
    """
    ep = equivalent_strain(state.inelastic_strain)
    if not np.any(ep > INELASTIC_THRESHOLD):
        return dict(largest_deformation="none (elastic)", largest_deformation_depth=math.nan)
    i = np.unravel_index(int(np.argmax(ep)), ep.shape)
    X = model.x[(slice(None),) + i]
    Ud = model.point_displacements(u)
    depth_all = -w - (model.x[2] + Ud[2])          # below the flat, deformed
    depth = float(depth_all[i])
    limit = JUNCTION_DEPTH_FRACTION * a_ref
    layer = depth_all <= limit
    where = "at the junction" if depth <= limit else "below the junction"
    return dict(
        largest_deformation=where,
        largest_deformation_criterion=(
            f"'at the junction' if the largest equivalent inelastic strain (quadrature points, "
            f"end of the run) lies less than {JUNCTION_DEPTH_FRACTION:g} a_ref below the flat "
            f"(deformed configuration; a_ref = sqrt(A_max / pi), A_max the largest contact area "
            f"of the run), else 'below the junction'"),
        largest_deformation_depth=depth,
        largest_deformation_depth_over_radius=depth / a_ref if a_ref > 0 else math.nan,
        largest_deformation_position=np.asarray(X, float),
        largest_deformation_displacement=np.asarray(Ud[(slice(None),) + i], float),
        largest_deformation_value=float(ep[i]),
        reference_contact_radius=a_ref,
        max_inelastic_strain_junction_layer=float(ep[layer].max()) if layer.any() else 0.0,
        max_inelastic_strain_below_layer=float(ep[~layer].max()) if (~layer).any() else 0.0,
    )
