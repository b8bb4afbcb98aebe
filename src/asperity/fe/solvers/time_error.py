"""Time integration of an inelastic material along a step and the error estimate of
the step (report 3.4, 3.6, 3.33-3.36; `solve_asperity_history`).

Time integration of the material (report 3.6).  The material's own update
is backward Euler (BE): y_n+1 = y_n + dt f(y_n+1) for the internal
variables y (inelastic strain, hardness, damage).  For a rate-dependent
material (one with ``rates``: `BodnerPartom`) the solver makes it second
order, the variable-step BDF2

    y_n+1 = a y_n - b y_n-1 + c h f(y_n+1),   omega = h / h_prev,
    a = (1 + omega)^2 / (1 + 2 omega), b = omega^2 / (1 + 2 omega),
    c = (1 + omega) / (1 + 2 omega),

which is the material's backward-Euler update from the start value
y* = a y_n - b y_n-1 over c h (`bdf2_start`): no change to the material,
and the consistent tangent stays exact.  BDF2 is L-stable like BE (stiff
flow at fast-flowing points is damped, not oscillating) and stable for
step ratios below 1 + sqrt 2 (the controller grows the step at most
twofold).  The first step and the first step after a knot of the history
(where the loading rate jumps) are BE.  ``integration="euler"`` keeps BE
throughout.  A rate-independent material (`J2Plasticity`) has no time
scale: its "time" is a load parameter, its inelastic rate jumps at first
yield, at every knot and wherever a point starts or stops yielding, and
BE is its return map; it is integrated by BE and its steps are not
estimated (``time_error`` NaN): ``max_interference_step`` and
``max_inelastic_step`` control them.

Time-integration error (report 3.4, 3.33-3.36, carried over to the
implicit schemes).  The rate of the flow rule at the end of a step is
r_n+1 = (y_n+1 - y*) / (c h) (the material's increment over its time
step); the rates at the ends of the last steps give the local truncation
error of the step:

    BE:    e = h (r_n+1 - r_n) / 2 = (h^2 / 2) y'',  the difference between
           the backward-Euler increment and the trapezoidal one
           h (r_n + r_n+1) / 2 (the report's predictor-corrector
           difference, 3.36, for an implicit step);
    BDF2:  e = k h^3 y''',  k = (1 + omega)^2 / (6 omega (1 + 2 omega)),
           y''' the second divided difference of r_n-1, r_n, r_n+1.

The error of the inelastic strain is measured by what it does to the
equilibrium: the nodal forces of the stress error 2 G e (the inelastic
strain is deviatoric), relative to the contact forces, the measure of the
Newton residual; the error of the damage kappa (3.15) by the largest
|e_kappa| relative to its rupture value.  Ruptured points are left out.
The indicator of the step is

    E = max( ||B^T (2 G e) dV|| / ||f_contact||,  max |e_kappa| / kappa_r ).
"""

from __future__ import annotations

import math
from dataclasses import fields

import numpy as np


#: state fields integrated in time: combined into the start value of a BDF2 step
INTEGRATED = ("inelastic_strain", "beta", "plastic_work", "hardness_iso", "kappa")


def bdf2_coefficients(omega: float) -> tuple:
    """Variable-step BDF2 with step ratio omega = h_n / h_n-1:

        y_n+1 = a y_n - b y_n-1 + c h f(y_n+1),

    i.e. a backward-Euler step of c h from y* = a y_n - b y_n-1, and its
    local error constant k (error = k h^3 d3y/dt3).  omega = 1: (4/3, 1/3,
    2/3, 2/9)."""
    w = float(omega)
    d = 1.0 + 2.0 * w
    return (1.0 + w) ** 2 / d, w * w / d, (1.0 + w) / d, (1.0 + w) ** 2 / (6.0 * w * d)


def bdf2_start(state, previous, a: float, b: float):
    """The start value y* = a y_n - b y_n-1 of the integrated fields of a
    material state (dataclass); the other fields, and all the fields of
    ruptured points (their damage is frozen), are those of y_n."""
    ruptured = getattr(state, "ruptured", None)
    frozen = ruptured is not None and bool(np.any(ruptured))
    kw = {}
    for f in fields(state):
        v = getattr(state, f.name)
        if f.name in INTEGRATED:
            combined = a * v - b * getattr(previous, f.name)
            v = np.where(ruptured, v, combined) if frozen else combined
        kw[f.name] = v
    return type(state)(**kw)


def flow_rates(material, start, new, dt: float) -> dict:
    """End-of-step rates of the controlled variables: (new - start) / dt,
    the rates of the flow rule at the new state for a backward-Euler step
    of dt from `start`."""
    out = {"inelastic_strain": (new.inelastic_strain - start.inelastic_strain) / dt}
    if getattr(material, "damage", False) is True:
        out["kappa"] = (new.kappa - start.kappa) / dt
    return out


def local_errors(order: int, h: float, h_prev: float, r_new: dict, r_n: dict,
                 r_prev: dict | None) -> dict:
    """Local truncation error estimates of the step, from the rates at its end
    (r_new), at its start (r_n) and one step back (r_prev).

    Backward Euler: (h^2 / 2) d2y/dt2 = h (r_new - r_n) / 2, the difference
    between the backward-Euler and the trapezoidal increments.  BDF2:
    k h^3 d3y/dt3 with d3y/dt3 the second divided difference of the rates."""
    if order == 1:
        return {k: 0.5 * h * (r_new[k] - r_n[k]) for k in r_new}
    _, _, _, kc = bdf2_coefficients(h / h_prev)
    return {k: kc * h**3 * 2.0 * ((r_new[k] - r_n[k]) / h - (r_n[k] - r_prev[k]) / h_prev)
            / (h + h_prev) for k in r_new}


def error_indicator(model, errors: dict, out) -> float:
    """E of a step (module docstring): the nodal forces of the stress error
    2 G e of the inelastic strain error e, relative to the contact forces
    (the measure of the Newton residual), and the error of the damage
    kappa relative to its rupture value; ruptured points left out."""
    material = model.material
    new = out["state"]
    ruptured = getattr(new, "ruptured", None)
    keep = None if ruptured is None or not np.any(ruptured) else ~np.asarray(ruptured)
    e = errors["inelastic_strain"]
    if keep is not None:
        e = e * keep
    fc = float(np.linalg.norm(model.zone.nodal(out["traction"])))
    E = 0.0
    if fc > 0:
        fe = model.linear.internal_force(None, (2.0 * material.G) * e)
        E = float(np.linalg.norm(fe[model.free])) / fc
    if "kappa" in errors:
        ek = np.abs(errors["kappa"])
        if keep is not None:
            ek = ek[keep]
        if ek.size:
            E = max(E, float(np.max(ek)) / material.kappa_rupture)
    return E if np.isfinite(E) else math.inf
