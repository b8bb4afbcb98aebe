"""What the drivers write: one table of per-step variables, one Dataset builder.

Every driver (`solve.solve_asperity`, `inelastic.solve_asperity_history`,
`adhesive.solve_asperity_adhesive`, `solid3d.solve_sliding`) returns an
`xarray.Dataset` on dim ``step`` whose variables are named in `VARIABLES`,
with their units and long name (the netCDF contract of DESIGN.md: units
and long_name on every variable).  A plane-strain section's forces,
areas and stiffnesses are per unit length of the ridge (`PLANE_STRAIN`).
"""

from __future__ import annotations

from dataclasses import asdict, is_dataclass

import numpy as np
import xarray as xr

#: flag of an inelastic body: no equivalent inelastic strain above this
INELASTIC_THRESHOLD = 1e-8
#: small strain limit of report 7.3 (largest principal strain magnitude)
SMALL_STRAIN_LIMIT = 0.08

#: name -> (units, long_name) of every per-step variable of the drivers
VARIABLES: dict[str, tuple[str, str]] = {
    "time": ("s", "time"),
    "interference": ("m", "interference of the rigid flat: its approach from first touch "
                          "(negative: gap before touching)"),
    "force": ("N", "total normal force of the flat on the asperity, compressive positive "
                   "(adhesion negative)"),
    "contact_force": ("N", "compressive part of the force (penalty contact, >= 0)"),
    "adhesive_force": ("N", "adhesive part of the force (Lennard-Jones attraction, <= 0)"),
    "contact_area": ("m^2", "real contact area: pi a^2 (adhesive: where the separation <= d); "
                            "3-D: the weights int phi_i ds of the contact facets' P2 nodes "
                            "with a positive pressure"),
    "contact_radius": ("m", "contact radius a (edge located between nodes)"),
    "normal_stiffness": ("N/m", "normal contact stiffness dF/dw (consistent tangent; adhesive: "
                                "along the branch)"),
    "tip_separation": ("m", "separation of the apex from the flat (d in contact)"),
    "max_equivalent_strain": ("1", "largest von Mises equivalent total strain at the quadrature "
                                   "points"),
    "max_inelastic_strain": ("1", "largest von Mises equivalent inelastic strain at the "
                                  "quadrature points"),
    "max_von_mises": ("Pa", "largest von Mises stress at the quadrature points"),
    "max_damage": ("1", "largest damage w at the quadrature points (0 without damage)"),
    "ruptured_points": ("1", "quadrature points ruptured so far (report 3.2.2: w -> 1)"),
    "elastic": ("1", "nothing yielded: von Mises stress below the yield stress everywhere "
                     "(elastic body), or no equivalent inelastic strain above "
                     f"{INELASTIC_THRESHOLD:g} anywhere (inelastic body)"),
    "small_strain": ("1", f"largest principal strain magnitude below {SMALL_STRAIN_LIMIT:g} "
                          "everywhere (report 7.3)"),
    "estimated_error": ("1", "ZZ estimate of the relative energy-norm error of the stress"),
    "branch": ("1", "segment of the path: 'approach' or 'retract' (adhesive), 'loading' or "
                    "'unloading' (history)"),
    "jump": ("1", "reached by a jump (discontinuity) from the previous step"),
    "requested": ("1", "a level of the requested path (else a state before a jump)"),
    "phase": ("1", "'normal' (pressing), 'sliding' or 'hold' segment of the motion"),
    "normal_displacement": ("m", "approach w of the rigid flat from first touch at the apex"),
    "tangential_displacement": ("m", "tangential (sliding) displacement delta of the rigid flat "
                                     "along x"),
    "normal_force": ("N", "normal contact force on the asperity (whole body, twice the half "
                          "model)"),
    "tangential_force": ("N", "tangential contact force on the asperity along the sliding "
                              "direction x"),
    "mean_pressure": ("Pa", "normal force / contact area"),
    "mean_tangential_traction": ("Pa", "tangential force / contact area (report 9.2: about "
                                       "64 MPa)"),
    "max_pressure": ("Pa", "largest contact pressure (3-D: at the contact facets' P2 nodes)"),
    "slip_fraction": ("1", "share of the touching area (the nodes' weights) whose slip |b| "
                           "reached eps_b"),
    "critical_shear_factor": ("1", "factor of the shear resistance at which the junction's "
                                   "tangent turns singular, every touching node sliding "
                                   "(critical friction coefficient / mu; below 1 the sliding "
                                   "problem is not unique; inf: none below 1000; NaN: not "
                                   "sliding)"),
    "dofs": ("1", "degrees of freedom (unknown displacement components)"),
    "newton_iterations": ("1", "Newton iterations of the step, including those of cut or "
                               "rejected tries (adhesive: and of the states added before it)"),
    "step_cuts": ("1", "times the step was cut: halved, or rejected and retried with a smaller "
                       "step (adhesive: failures and discontinuities)"),
    "damped_solves": ("1", "3-D sliding: damped solves of a step taken through the slip "
                           "instability, where Newton failed below the stall fraction of "
                           "the step cap (0: plain Newton; "
                           "sliding_model.SlidingModel.solve_through_slip)"),
    "time_step": ("s", "time step of the accepted step"),
    "integration_order": ("1", "time integration of the step: 1 backward Euler, 2 BDF2 "
                               "(0: initial state)"),
    "time_error": ("1", "estimated local time-integration error of the step: nodal forces of "
                        "the stress error relative to the contact forces, or damage error "
                        "relative to rupture (NaN: not estimated, rate-independent material)"),
    "wall_time": ("s", "wall time of the step, including its rejected tries and its share of "
                       "meshing, assembly, factorization and adaptivity"),
}

#: the variables of a plane-strain section: per unit length of the ridge
PLANE_STRAIN: dict[str, tuple[str, str]] = {
    "force": ("N/m", "total normal force per unit length of the ridge, compressive positive "
                     "(adhesion negative)"),
    "contact_force": ("N/m", "compressive part of the force per unit length (>= 0)"),
    "adhesive_force": ("N/m", "adhesive part of the force per unit length (<= 0)"),
    "contact_area": ("m", "contact width 2 a per unit length of the ridge (area per length)"),
    "contact_radius": ("m", "contact half width a (edge located between nodes)"),
    "normal_stiffness": ("N/m^2", "normal contact stiffness dF/dw per unit length (consistent "
                                  "tangent)"),
}


def describe(obj) -> str:
    """A one-line description of a geometry, material or law (its fields)."""
    if is_dataclass(obj):
        fields = ", ".join(f"{k}={v!r}" for k, v in asdict(obj).items())
        return f"{type(obj).__name__}({fields})"
    return repr(obj)


def accuracy_attrs(accuracy) -> dict:
    """The attributes naming a run's accuracy: ``accuracy``, the preset (for a dict of
    overrides its ``base``, standard unless named), and, where a dict changes keys of it,
    ``accuracy_overrides`` (e.g. ``edge_size=0.02``)."""
    if isinstance(accuracy, str):
        return dict(accuracy=accuracy)
    extra = dict(accuracy)
    out = dict(accuracy=extra.pop("base", "standard"))
    if extra:
        out["accuracy_overrides"] = ", ".join(f"{k}={v!r}" for k, v in sorted(extra.items()))
    return out


def dataset(rec: dict, geometry, material, accuracy, preset: dict, step_name: str,
            attrs: dict | None = None) -> xr.Dataset:
    """The per-step Dataset of a run: the arrays of `rec` on dim ``step``
    with units and long names from `VARIABLES` (`PLANE_STRAIN` for a
    plane-strain section), the step coordinate named `step_name`, and the
    attributes every run has (geometry, material, symmetry, accuracy and
    its parameters) updated by `attrs`."""
    axi = geometry.axisymmetric
    data = {}
    for name, values in rec.items():
        units, long_name = VARIABLES[name] if axi else PLANE_STRAIN.get(name, VARIABLES[name])
        data[name] = ("step", np.asarray(values), dict(units=units, long_name=long_name))
    n = len(next(iter(rec.values())))
    ds = xr.Dataset(data, coords=dict(step=("step", np.arange(n),
                                            dict(units="1", long_name=step_name))))
    ds.attrs.update(
        geometry=describe(geometry),
        material=describe(material),
        symmetry="axisymmetric" if axi else "plane strain (per unit length)",
        accuracy_parameters=repr(preset),
        **accuracy_attrs(accuracy),
    )
    ds.attrs.update(attrs or {})
    return ds
