"""Uniaxial material-point driver and the report's material tests.

The 1-D stress state of the 3-D model: the axial component (11) has its
strain or its stress prescribed as a piecewise linear function of time, the
other stresses (22, 33, 12) are zero.  With the implicit integrator the free
strains are found by Newton's method with the consistent tangent at each
step (`asperity.fe.solvers.mixed`); the explicit integrator (report 3.6)
takes the mixed control in rate form.

Adaptive steps (implicit): after each backward-Euler step the report's
indicator (3.36) is evaluated with the rates at both ends of the step,

    E = max_y |dt (y_dot(t + dt) - y_dot(t))| / (2 (|y(t + dt)| + floor)),

which is the local error estimate of the backward-Euler step (its error is
dt^2 / 2 y_ddot).  The flow enters through the stress (strain control:
|dt E (eps_n_dot(t+dt) - eps_n_dot(t))| / 2 relative to |sigma|) or the
strain (stress control: the equivalent inelastic strain error relative to
the total strain); Z^I and |beta| (relative to Z^I) and w are the other
control variables.  Floors: 1e-3 Z0 for stresses, 1e-3 Z0 / E for strains,
1e-4 for w.  A step with
E > tol, or whose local Newton (material or driver) did not converge, is
rejected and retried with a smaller step; the next step is scaled by
0.9 sqrt(tol / E) within [0.2, 2].  Steps end on the breakpoints of the
history.  A rate-independent material (no ``rates``) has E = 0.

Named tests (report 5, 6.3.1, 8.2.1): `b1900_creep`, `b1900_cyclic`,
`b1900_relaxation`, `b1900_load_creep`, `aluminum_tension`,
`sae1020_tension`.  The report's figures are not in the text; the load
levels and rates below are our choices (stated in each docstring).
"""

from __future__ import annotations

import math
import time as _time

import numpy as np
import xarray as xr

from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.solvers.mixed import solve_mixed_point

__all__ = [
    "run_uniaxial",
    "uniaxial_flow_stress",
    "b1900_histories",
    "b1900_creep",
    "b1900_cyclic",
    "b1900_relaxation",
    "b1900_load_creep",
    "aluminum_tension",
    "sae1020_tension",
]

_VARS = {
    "time": ("s", "time"),
    "strain": ("1", "axial strain eps_11"),
    "stress": ("Pa", "axial stress sigma_11"),
    "lateral_strain": ("1", "lateral strain eps_22"),
    "inelastic_strain": ("1", "axial inelastic strain eps_n_11"),
    "hardness": ("Pa", "hardness Z = Z^I + Z^D (J2: current yield stress)"),
    "hardness_isotropic": ("Pa", "isotropic hardness Z^I"),
    "hardness_directional": ("Pa", "directional hardness Z^D = beta : u"),
    "damage": ("1", "isotropic damage omega"),
    "plastic_work": ("J m-3", "plastic work W_p"),
    "dt": ("s", "time step ending at this step"),
}


class UniaxialError(RuntimeError):
    """The driver could not advance (step below its minimum)."""


def uniaxial_flow_stress(material: BodnerPartom, strain_rate: float, hardness: float | None = None):
    """Steady uniaxial flow stress at constant Z (report flow law inverted).

    Uniaxially J2 = sigma^2 / 3 and eps_n_11_dot = (2/sqrt3) D0
    exp[-1/2 (Z/sigma)^(2n)], so at steady flow (eps_n_dot = eps_dot)

        sigma = Z (2 ln((2/sqrt3) D0 / eps_dot))^(-1/(2n)).
    """
    Z = material.Z0 if hardness is None else hardness
    L = math.log(2.0 / math.sqrt(3.0) * material.D0 / strain_rate)
    return Z * (2.0 * L) ** (-0.5 / material.n)


def _check_history(history):
    h = np.asarray(history, float)
    if h.ndim != 2 or h.shape[1] != 2 or h.shape[0] < 2:
        raise ValueError("history is a list of at least two (time, value) pairs")
    t = h[:, 0]
    if not np.all(np.diff(t) > 0):
        raise ValueError("history times must increase strictly")
    if h[0, 1] != 0.0:
        raise ValueError("the history starts from rest: its first value must be 0")
    return t, h[:, 1]


def _record(state, t, dt):
    z = np.asarray(state.hardness_iso, float)
    zd = np.asarray(state.hardness_dir, float)
    return dict(time=t, strain=float(state.strain[0]), stress=float(state.stress[0]),
                lateral_strain=float(state.strain[1]),
                inelastic_strain=float(state.inelastic_strain[0]),
                hardness=float(z + zd), hardness_isotropic=float(z), hardness_directional=float(zd),
                damage=float(np.asarray(state.damage)), plastic_work=float(state.plastic_work),
                dt=dt)


def _eq_norm(x):
    """Equivalent (von Mises) norm sqrt(2/3 x:x) of tensor components (4,)."""
    x = np.asarray(x, float)
    return math.sqrt(2.0 / 3.0 * (x[0] ** 2 + x[1] ** 2 + x[2] ** 2 + 2.0 * x[3] ** 2))


def _indicator(material, r0, r1, new, h, control):
    """The report's indicator (3.36) from the rates at both ends of a step."""
    if r0 is None or r1 is None:
        return 0.0
    fs = 1e-3 * material.stress_scale
    dflow = 0.5 * h * _eq_norm(r1["inelastic_strain"] - r0["inelastic_strain"])
    if control == "strain":
        E = material.E * dflow / (abs(float(new.stress[0])) + fs)
    else:
        E = dflow / (_eq_norm(new.strain) + fs / material.E)
    zscale = abs(float(new.hardness_iso)) + fs
    if getattr(material, "isotropic_hardening", False) or getattr(material, "recovery", False):
        E = max(E, 0.5 * h * abs(float(r1["hardness_iso"] - r0["hardness_iso"])) / zscale)
    if getattr(material, "directional_hardening", False):
        db = _eq_norm(r1["beta"] - r0["beta"]) * math.sqrt(1.5)
        E = max(E, 0.5 * h * db / zscale)
    if getattr(material, "damage", False):
        E = max(E, 0.5 * h * abs(float(r1["damage"] - r0["damage"])) / (float(new.damage) + 1e-4))
    return E if np.isfinite(E) else math.inf


def _run_explicit(material, state, rows, times, values, control, steps, adaptive,
                  explicit_tol, stop_at_rupture):
    """Integrate with the explicit predictor-corrector over `steps` output intervals,
    appending each interval's record to `rows`: (accepted, rejected, rupture time)."""
    t0, T = float(times[0]), float(times[-1])
    n_acc = 0
    n_rej = 0
    rupture_time = None
    grid = np.union1d(np.linspace(t0, T, steps + 1), times)
    mask = np.array([False, True, True, True]) if control == "strain" else np.ones(4, bool)
    etol = explicit_tol if adaptive else math.inf
    for ta, tb in zip(grid[:-1], grid[1:]):
        target = float(np.interp(tb, times, values))
        strain = np.array(state.strain, float)
        stress = np.zeros(4)
        if control == "strain":
            strain[0] = target
        else:
            stress[0] = target
        with np.errstate(all="ignore"):
            _, state, info = material.explicit(strain, state, tb - ta, tol=etol,
                                               stress=stress, stress_mask=mask)
        n_acc += int(info["substeps"])
        n_rej += int(info["rejected"])
        if not np.all(state.converged):
            raise UniaxialError(f"explicit integration did not reach t = {tb}")
        rows.append(_record(state, float(tb), float(tb - ta)))
        if stop_at_rupture and np.any(state.ruptured):
            rupture_time = float(np.asarray(state.rupture_time))
            break
    return n_acc, n_rej, rupture_time


def _predicted_strain(state, control, target, h, same_segment, prev_strain, prev_h, D_last):
    """Predictor of the free strains of an implicit step: extrapolated along the segment,
    or from the last consistent tangent at the start of a segment."""
    eps0 = np.array(state.strain, float)
    if same_segment:
        eps0 = eps0 + (eps0 - prev_strain) * (h / prev_h)
    elif D_last is not None:
        free = [1, 2, 3] if control == "strain" else [0, 1, 2, 3]
        ds = np.zeros(4)
        de = np.zeros(4)
        if control == "strain":
            de[0] = target - float(state.strain[0])
        else:
            ds[0] = target - float(state.stress[0])
        rhs = ds[free] - D_last[np.ix_(free, [0])] @ de[:1] * (control == "strain")
        eps0 = eps0 + de
        eps0[free] += np.linalg.solve(D_last[np.ix_(free, free)], rhs)
    return eps0


def _run_implicit(material, state, rows, times, values, control, steps, adaptive, tol,
                  dt0, dt_min, dt_max, max_steps, newton_tol, stop_at_rupture):
    """Integrate by backward Euler with adaptive (or uniform) steps, appending each
    accepted step's record to `rows`: (accepted, rejected, rupture time)."""
    t0, T = float(times[0]), float(times[-1])
    n_acc = 0
    n_rej = 0
    rupture_time = None
    has_rates = hasattr(material, "rates")
    scale = float(material.stress_scale)
    dt = float(dt0) if dt0 is not None else (T - t0) / steps
    dt_min = dt_min if dt_min is not None else 1e-12 * (T - t0)
    dt_max = dt_max if dt_max is not None else (T - t0)
    r0 = material.rates(state) if has_rates else None
    seg_steps = None
    if not adaptive:
        seg_steps = np.maximum(1, np.round(steps * np.diff(times) / (T - t0))).astype(int)
    t = t0
    prev_strain = None
    prev_h = None
    D_last = material.tangent() if hasattr(material, "tangent") else None
    while t < T - 1e-12 * (T - t0):
        if n_acc + n_rej >= max_steps:
            raise UniaxialError(f"more than {max_steps} steps")
        k = int(np.searchsorted(times, t, side="right"))  # next breakpoint index
        k = min(k, len(times) - 1)
        t_bp = float(times[k])
        if seg_steps is not None:
            h = (times[k] - times[k - 1]) / seg_steps[k - 1]
        else:
            h = min(dt, dt_max)
        truncated = False
        if t + h >= t_bp - 0.05 * h:
            truncated = t + h > t_bp
            h = t_bp - t
        target = float(np.interp(t + h, times, values))
        # predictor of the free strains
        same_segment = prev_strain is not None and t > float(times[k - 1]) + 1e-12 * (T - t0)
        eps0 = _predicted_strain(state, control, target, h, same_segment, prev_strain, prev_h,
                                 D_last)
        ok, sig, D, new = solve_mixed_point(material, state, h, eps0, control, target,
                                            scale, newton_tol)
        if not ok:
            n_rej += 1
            dt = 0.25 * h
            if seg_steps is not None:
                raise UniaxialError(f"step at t = {t} did not converge (adaptive=False)")
            if dt < dt_min:
                raise UniaxialError(f"step below dt_min at t = {t}")
            continue
        r1 = material.rates(new) if has_rates else None
        E = _indicator(material, r0, r1, new, h, control) if seg_steps is None else 0.0
        if E > tol:
            n_rej += 1
            dt = h * max(0.2, 0.9 * math.sqrt(tol / E))
            if dt < dt_min:
                raise UniaxialError(f"step below dt_min at t = {t}")
            continue
        # accept
        prev_strain = np.array(state.strain, float)
        prev_h = h
        state, r0, D_last = new, r1, D
        t = t + h
        n_acc += 1
        rows.append(_record(state, t, h))
        fac = 2.0 if E <= 0 else min(2.0, max(0.2, 0.9 * math.sqrt(tol / E)))
        dt = fac * (dt if truncated else h)
        if stop_at_rupture and np.any(state.ruptured):
            rupture_time = float(np.asarray(state.rupture_time))
            break
    return n_acc, n_rej, rupture_time


def _uniaxial_dataset(rows, material, integrator, control, n_acc, n_rej, wall, rupture_time):
    """The Dataset of the records `rows` on dim ``step``, with the run's attributes."""
    data = {k: ("step", np.array([r[k] for r in rows], float)) for k in _VARS}
    ds = xr.Dataset(data, coords={"step": np.arange(len(rows))})
    for k, (u, ln) in _VARS.items():
        ds[k].attrs.update(units=u, long_name=ln)
    ds["step"].attrs.update(units="1", long_name="step index (0: initial state)")
    ds.attrs.update(
        title="uniaxial material point test",
        integrator=integrator,
        control=control,
        material=getattr(material, "name", "") or type(material).__name__,
        steps=int(n_acc),
        rejected_steps=int(n_rej),
        wall_time=float(wall),
        ruptured=int(rupture_time is not None),
    )
    if rupture_time is not None:
        ds.attrs["rupture_time"] = rupture_time
    return ds


def run_uniaxial(material, history, integrator: str = "implicit", control: str = "strain",
                 steps: int = 100, adaptive: bool = True, *, tol: float = 1e-3,
                 explicit_tol: float = 1e-5, dt0: float | None = None,
                 dt_min: float | None = None, dt_max: float | None = None,
                 max_steps: int = 200_000, newton_tol: float = 1e-8,
                 stop_at_rupture: bool = True) -> xr.Dataset:
    """Drive one material point through a uniaxial history.

    material: `BodnerPartom` or `J2Plasticity` (anything with
    ``initial_state``, ``update`` and, for ``integrator="explicit"``,
    ``explicit``); history: [(time [s], value), ...] piecewise linear, value
    the axial strain (``control="strain"``) or stress [Pa]
    (``control="stress"``), first value 0.  ``steps``: the initial step is
    the duration / steps (``dt0`` overrides it); with ``adaptive=False`` the
    steps are uniform (at least one per segment).  Implicit: ``tol`` is the
    tolerance of the error indicator.  Explicit: ``steps`` output intervals,
    each integrated with the report's predictor-corrector to
    ``explicit_tol`` (one Heun step per interval if not adaptive).

    Returns an xarray Dataset on dim ``step`` (step 0 is the initial state):
    time, strain, stress, lateral_strain, inelastic_strain, hardness,
    hardness_isotropic, hardness_directional, damage, plastic_work, dt;
    attributes integrator, control, material, steps (accepted integration
    steps: explicit sub-steps included), rejected_steps, wall_time [s],
    ruptured (0/1) and rupture_time [s] if ruptured.
    """
    if integrator not in ("implicit", "explicit"):
        raise ValueError("integrator is 'implicit' or 'explicit'")
    if control not in ("strain", "stress"):
        raise ValueError("control is 'strain' or 'stress'")
    times, values = _check_history(history)
    t0 = float(times[0])
    wall0 = _time.perf_counter()
    state = material.initial_state(())
    rows = [_record(state, t0, 0.0)]

    if integrator == "explicit":
        if not hasattr(material, "explicit"):
            raise ValueError(f"{type(material).__name__} has no explicit integrator")
        n_acc, n_rej, rupture_time = _run_explicit(
            material, state, rows, times, values, control, steps, adaptive, explicit_tol,
            stop_at_rupture)
    else:
        n_acc, n_rej, rupture_time = _run_implicit(
            material, state, rows, times, values, control, steps, adaptive, tol, dt0, dt_min,
            dt_max, max_steps, newton_tol, stop_at_rupture)

    wall = _time.perf_counter() - wall0
    return _uniaxial_dataset(rows, material, integrator, control, n_acc, n_rej, wall,
                             rupture_time)


# ------------------------------------------------------------ named tests
def b1900_histories() -> dict:
    """The section-5 histories for B1900+Hf at 871 C: name -> (history, control).

    The report gives the kinds of test and the durations, not the levels
    (they are in its figures); ours:

    - ``creep``: 600 MPa reached in 10 s, held to 1000 s (5 (b), Fig. 5.1);
    - ``cyclic``: 10 strain cycles +-0.8 % at 1e-4 1/s (Fig. 5.2);
    - ``relaxation``: strain to 1 % at 2e-6 1/s over 5000 s, then held for
      5000 s (Fig. 5.3);
    - ``load_creep``: stress to 600 MPa at 0.6 MPa/s over 1000 s, then held
      for 1000 s (Fig. 5.4).
    """
    amp, rate = 0.008, 1e-4
    quarter = amp / rate
    cyc = [(0.0, 0.0)]
    for i in range(10):
        t = 4 * quarter * i
        cyc += [(t + quarter, amp), (t + 3 * quarter, -amp), (t + 4 * quarter, 0.0)]
    return {
        "creep": ([(0.0, 0.0), (10.0, 600e6), (1000.0, 600e6)], "stress"),
        "cyclic": (cyc, "strain"),
        "relaxation": ([(0.0, 0.0), (5000.0, 0.01), (10000.0, 0.01)], "strain"),
        "load_creep": ([(0.0, 0.0), (1000.0, 600e6), (2000.0, 600e6)], "stress"),
    }


def _run_named(name, material=None, **kw):
    history, control = b1900_histories()[name]
    material = material or BodnerPartom.b1900_hf_871C()
    ds = run_uniaxial(material, history, control=control, **kw)
    ds.attrs["title"] = f"B1900+Hf 871 C {name} test (report 5)"
    return ds


def b1900_creep(**kw) -> xr.Dataset:
    """Creep at 600 MPa (report 5 (b), Fig. 5.1); see `b1900_histories`."""
    return _run_named("creep", **kw)


def b1900_cyclic(**kw) -> xr.Dataset:
    """10 tension-compression cycles (report 5 (c), Fig. 5.2)."""
    return _run_named("cyclic", **kw)


def b1900_relaxation(**kw) -> xr.Dataset:
    """5000 s loading then 5000 s relaxation (report 5 (c), Fig. 5.3)."""
    return _run_named("relaxation", **kw)


def b1900_load_creep(**kw) -> xr.Dataset:
    """1000 s loading then 1000 s creep (report 5 (c), Fig. 5.4)."""
    return _run_named("load_creep", **kw)


def _tension(material, title: str, strain_rate: float, max_strain: float, **kw) -> xr.Dataset:
    """Constant strain-rate tension to `max_strain`."""
    ds = run_uniaxial(material, [(0.0, 0.0), (max_strain / strain_rate, max_strain)],
                      control="strain", **kw)
    ds.attrs["title"] = title
    return ds


def aluminum_tension(strain_rate: float = 1e-3, max_strain: float = 0.05, material=None,
                     **kw) -> xr.Dataset:
    """Tension of aluminum 6061-T4 (report 6.3.1, Fig. 6.14) at a constant
    strain rate (ours: 1e-3 1/s to 5 %)."""
    return _tension(material or BodnerPartom.aluminum_6061_t4(),
                    "aluminum 6061 tension (report 6.3.1, Fig. 6.14)", strain_rate, max_strain, **kw)


def sae1020_tension(strain_rate: float = 1e-3, max_strain: float = 0.05, material=None,
                    **kw) -> xr.Dataset:
    """Tension of SAE 1020 steel (report 8.2.1, Fig. 8.13) at a constant
    strain rate (ours: 1e-3 1/s to 5 %)."""
    return _tension(material or BodnerPartom.sae_1020(),
                    "SAE 1020 steel tension (report 8.2.1, Fig. 8.13)", strain_rate, max_strain, **kw)
