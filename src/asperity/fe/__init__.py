"""The single-asperity finite element model (report sections 3, 6.1, 7).

One asperity, a body of revolution or a plane-strain section standing on a
block of bulk material, pressed by a rigid flat; elastic, small strain,
P2 elements on a curved graded mesh refined adaptively near the contact
edge; contact by the C1 penalty of report 3.3.2 or exactly (augmented
Lagrangian); Newton-Raphson with step cutting; Lennard-Jones adhesion
on the free surface with jumps into and out of contact (`adhesion`,
`adhesive`).

Modules: `geometry` (profiles), `mesh` (graded curved meshes, refinement),
`material` (stress and tangent at quadrature points), `assembly` (P2
fields, stiffness, condensation onto the surface), `contact` (penalty law,
contact points, contact edge), `newton` (Newton, step control, Uzawa),
`adapt` (ZZ estimator, marking), `presets` (accuracy), `solve` (driver,
Dataset), `analytic` (Hertz), `errors`; `inelastic` (J2 or Bodner-Partom
body along a prescribed interference history: incremental, full Newton on
a fixed mesh, adaptive time steps).

    >>> from asperity.fe import solve_asperity, Paraboloid, LinearElastic
    >>> ds = solve_asperity(Paraboloid(1.0), LinearElastic(1000.0, 0.3),
    ...                     [0.001, 0.002, 0.005, 0.01, 0.02])  # doctest: +SKIP
"""

from .adhesion import LennardJones
from .adhesive import interpolate_adhesive, smooth_aluminum_curves, solve_asperity_adhesive
from .errors import ContactZoneError, ConvergenceError
from .geometry import CosineHill, Cylinder, Paraboloid, Profile, Sphere, TruncatedV
from .inelastic import History, solve_asperity_history
from .material import LinearElastic
from .presets import ACCURACY
from .solve import hertz, penalty_error, solve_asperity

__all__ = [
    "ACCURACY",
    "ContactZoneError",
    "History",
    "ConvergenceError",
    "LennardJones",
    "CosineHill",
    "Cylinder",
    "LinearElastic",
    "Paraboloid",
    "Profile",
    "Sphere",
    "TruncatedV",
    "hertz",
    "interpolate_adhesive",
    "penalty_error",
    "smooth_aluminum_curves",
    "solve_asperity",
    "solve_asperity_adhesive",
    "solve_asperity_history",
]
