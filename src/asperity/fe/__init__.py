"""The single-asperity finite element model (report sections 3, 6, 7, 9).

One asperity, a body of revolution or a plane-strain section standing on a
block of bulk material, pressed by a rigid flat: P2 elements on a curved
graded mesh refined adaptively near the contact edge; small strain; contact
by the C1 penalty of report 3.3.2 or exactly (augmented Lagrangian), the
contact edge located between nodes; Newton-Raphson with step cutting.
Bodies are elastic (`LinearElastic`, report 3.2.1, 6.1), elastic-plastic
(`J2Plasticity`) or viscoplastic (`BodnerPartom`, 3.2.2) along a
prescribed interference history (incremental, adaptive time steps, 3.6,
6.3), or elastic with Lennard-Jones adhesion on the free surface and jumps
into and out of contact (3.3.3, 7.3); and a 3-D half model of a hill,
elastic or viscoplastic, pressed and slid under friction (3.3.4, 9.2).

Drivers: `solve_asperity` (elastic), `solve_asperity_history`
(inelastic), `solve_asperity_adhesive` (adhesive), `solve_sliding` (3-D
sliding).  Packages by concern, each importing only those below it:

- `drivers`: what a job runs (`elastic`; `inelastic` with `inelastic_model`,
  `history_march` and `remesh`; `adhesive` with `adhesive_model` and
  `adhesive_trace`; `solid3d` with `flat_motion`, `sliding_model` and
  `sliding_march`), the time-marching ones through `march`;
- `solvers`: `nonlinear` (the one Newton iteration and step control of every
  driver, line searches), `newton` (the elastic contact problem, Uzawa),
  `adhesive` (the adhesive problem's Newton), `arclength` (through folds),
  `mixed` (a material point under mixed control), `time_error` (BDF2 and the
  time-integration error), `linear` (the 3-D model's reused LU);
- `contact`: the laws of the surface against the flat (`penalty`: penalty law,
  contact points, contact edge; `adhesion`: Lennard-Jones; `sliding`: the
  resistance of the junction);
- `discretization`: `geometry` (profiles), `mesh` (graded curved meshes,
  refinement), `adapt` (ZZ estimator, marking), `assembly` (P2 fields,
  stiffness, condensation onto the surface), `kinematics` (small and finite
  strain), `half_model_mesh` and `half_model` (the 3-D half model);
- `materials`: `elastic`, `j2`, `bodner_partom` (with `bodner_partom_state`,
  `bodner_partom_implicit`, `bodner_partom_explicit`), `tensors` (stress and
  tangent at quadrature points);

and beside them `presets` (accuracy of every kind of model), `outputs` (the
variables of every driver's Dataset), `analytic` (Hertz), `errors`
(`StepFailed`: one try of a step; `ConvergenceError`: a step after its cuts).

    >>> from asperity.fe import solve_asperity, Paraboloid, LinearElastic
    >>> ds = solve_asperity(Paraboloid(1.0), LinearElastic(1000.0, 0.3),
    ...                     [0.001, 0.002, 0.005, 0.01, 0.02])  # doctest: +SKIP
"""

from asperity.fe.contact.adhesion import LennardJones
from asperity.fe.drivers.adhesive import solve_asperity_adhesive
from asperity.fe.materials.bodner_partom import BodnerPartom
from asperity.fe.errors import ContactZoneError, ConvergenceError, RuptureError, StepFailed
from asperity.fe.discretization.geometry import (CosineHill, Cylinder, EllipticParaboloid,
                                                 Paraboloid, Profile, Sphere, TruncatedV)
from asperity.fe.drivers.inelastic import History, solve_asperity_history
from asperity.fe.materials.j2 import J2Plasticity
from asperity.fe.materials.elastic import IsotropicElasticity, LinearElastic
from asperity.fe.presets import ACCURACY
from asperity.fe.contact.sliding import FrictionLaw, ShearResistance
from asperity.fe.drivers.solid3d import FlatMotion, press_3d, solve_sliding
from asperity.fe.drivers.elastic import hertz, penalty_error, solve_asperity

__all__ = [
    "ACCURACY",
    "BodnerPartom",
    "ContactZoneError",
    "ConvergenceError",
    "CosineHill",
    "Cylinder",
    "EllipticParaboloid",
    "FlatMotion",
    "FrictionLaw",
    "History",
    "IsotropicElasticity",
    "J2Plasticity",
    "LennardJones",
    "LinearElastic",
    "Paraboloid",
    "Profile",
    "RuptureError",
    "ShearResistance",
    "Sphere",
    "StepFailed",
    "TruncatedV",
    "hertz",
    "penalty_error",
    "press_3d",
    "solve_asperity",
    "solve_asperity_adhesive",
    "solve_asperity_history",
    "solve_sliding",
]
