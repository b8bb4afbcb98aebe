"""Accuracy study of the finite element model on the Hertz problem (report 6.1).

The report verified its h-p adaptive model on an elastic sphere pressed by
a rigid flat (R = 1, E = 1000, nu = 0.3, w = 0.001 ... 0.02) against Hertz:

    r = sqrt(R w),   A = pi R w,   P = 4/3 E / (1 - nu^2) R^1/2 w^3/2

and its Fig. 6.5 (a table) shows errors of up to 17.5 % in load and 5.3 %
in contact radius (`REPORT_FIG_6_5`).  `hertz_accuracy_study` measures the
present model on the same problem:

- the paraboloid (`Paraboloid`, Hertz's own idealization: a half space with
  a paraboloidal gap, so the error is the model's numerical error) for
  every accuracy preset and every member of a refinement sequence;
- the true sphere (`Sphere`) for every preset, reported beside: its
  difference to Hertz is geometric (a / R up to 0.14), not numerical;
- the penalty method's own error against the exact (augmented Lagrangian)
  contact option on the same mesh (`penalty_error`), for a range of
  penalty factors, with the wall time of complete runs of each.

Default refinement sequence (`DEFAULT_REFINEMENT`)
--------------------------------------------------
Five members from very coarse to very fine.  Each step tightens the mesh
(ring growth ratio, sectors per ring, adaptive sweeps, target ZZ error)
*and* the cut-off radius of the block (``domain_factor``) together: on the
Hertz problem the load error of a fine mesh is dominated by the cut-off
(fixing u = 0 at L stiffens the body by about a / L), so refining the mesh
alone stalls at the cut-off error. What each member costs and reaches is
results/accuracy/hertz.nc (docs: the Verification page).

The contact radius error falls more slowly: the contact edge is located
between nodes (`contact.contact_edge`), so it is bounded by the element
size at the edge rather than by the energy norm.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

import numpy as np
import xarray as xr

from asperity.fe.contact.penalty import PENALTY_FACTOR
from asperity.fe.discretization.geometry import Paraboloid, Sphere
from asperity.fe.materials.elastic import LinearElastic
from asperity.fe.presets import resolve
from asperity.fe.drivers.elastic import hertz, penalty_error, solve_asperity

#: the refinement sequence of the study (see the module docstring); each
#: member is a complete accuracy dict (no 'base' needed; the keys not set
#: here -- Newton tolerances, adapt_levels -- come from 'fine')
DEFAULT_REFINEMENT: tuple[dict, ...] = (
    dict(base="fine", domain_factor=30.0, apex_fraction=0.3, growth=1.6, n_theta=3,
         sweeps=1, theta=0.5, target_error=0.1),
    dict(base="fine", domain_factor=100.0, apex_fraction=0.3, growth=1.4, n_theta=4,
         sweeps=2, theta=0.5, target_error=0.03),
    dict(base="fine", domain_factor=300.0, apex_fraction=0.3, growth=1.3, n_theta=5,
         sweeps=3, theta=0.5, target_error=0.01),
    dict(base="fine", domain_factor=1000.0, apex_fraction=0.25, growth=1.25, n_theta=7,
         sweeps=5, theta=0.45, target_error=0.003),
    dict(base="fine", domain_factor=10000.0, apex_fraction=0.15, growth=1.2, n_theta=10,
         sweeps=7, theta=0.4, target_error=0.0015),
)

#: report Fig. 6.5 (a table): Hertz and the report's FE, R = 1, E = 1000, nu = 0.3
REPORT_FIG_6_5 = dict(
    interference=np.array([0.002, 0.005, 0.01, 0.02]),
    hertz_contact_radius=np.array([0.04472, 0.07071, 0.10000, 0.14142]),
    hertz_force=np.array([1.3105e-01, 5.1803e-01, 1.4652e00, 4.1442e00]),
    fe_contact_radius=np.array([0.04237, 0.07001, 0.10092, 0.14809]),
    fe_force=np.array([1.5400e-01, 5.5400e-01, 1.5400e00, 4.5000e00]),
)
#: the report's largest relative errors: 17.5 % in load (w = 0.002), 5.3 %
#: in contact radius (w = 0.002)
REPORT_MAX_FORCE_ERROR = float(np.max(np.abs(
    REPORT_FIG_6_5["fe_force"] / REPORT_FIG_6_5["hertz_force"] - 1)))
REPORT_MAX_RADIUS_ERROR = float(np.max(np.abs(
    REPORT_FIG_6_5["fe_contact_radius"] / REPORT_FIG_6_5["hertz_contact_radius"] - 1)))

BODIES = ("paraboloid", "sphere")


def _run_record(ds: xr.Dataset) -> dict:
    return dict(
        force=ds.force.values,
        contact_radius=ds.contact_radius.values,
        dofs=float(ds.dofs.values[0]),
        wall_time=float(ds.attrs["total_wall_time"]),
        estimated_error=float(np.max(ds.estimated_error.values)),
        sweeps=float(ds.attrs.get("adaptive_sweeps", np.nan)),
    )


def _var(dims, values, units, long_name):
    """A Dataset variable tuple: `values` as an array with its units and long name."""
    return (dims, np.asarray(values), dict(units=units, long_name=long_name))


def _study_runs(presets: Sequence[str], refinement: Sequence[dict] | None
                ) -> tuple[list[str], list[str], list[tuple]]:
    """The runs of the study: their labels, kinds and (label, accuracy) pairs, the
    presets first; unknown presets and duplicate labels fail before any run."""
    refinement = DEFAULT_REFINEMENT if refinement is None else tuple(refinement)
    presets = tuple(presets)
    for p in presets:
        resolve("elastic", p)  # unknown names fail before any run
    members = [resolve("elastic", m) for m in refinement]
    labels = list(presets) + [f"refine-{i + 1}" for i in range(len(members))]
    if len(set(labels)) != len(labels):
        raise ValueError(f"run labels must be unique, got {labels}")
    kinds = ["preset"] * len(presets) + ["refinement"] * len(members)
    runs = [(p, p) for p in presets] + list(zip(labels[len(presets):], refinement))
    return labels, kinds, runs


def _solve_runs(geometries: dict, material, w: np.ndarray, runs: list[tuple],
                kinds: list[str]) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Force and contact radius (body, run, step) and the scalars (body, run) of every
    run: both bodies for a preset, the paraboloid only for a refinement member."""
    nb, nr, ns = len(BODIES), len(runs), len(w)
    force = np.full((nb, nr, ns), np.nan)
    contact_radius = np.full((nb, nr, ns), np.nan)
    scalars = {k: np.full((nb, nr), np.nan)
               for k in ("dofs", "wall_time", "estimated_error", "sweeps")}
    for j, (label, accuracy) in enumerate(runs):
        bodies = BODIES if kinds[j] == "preset" else ("paraboloid",)
        for body in bodies:
            i = BODIES.index(body)
            rec = _run_record(solve_asperity(geometries[body], material, w, accuracy=accuracy))
            force[i, j] = rec["force"]
            contact_radius[i, j] = rec["contact_radius"]
            for k in scalars:
                scalars[k][i, j] = rec[k]
    return force, contact_radius, scalars


def _accuracy_variables(w: np.ndarray, ref: dict, force: np.ndarray,
                        contact_radius: np.ndarray, scalars: dict[str, np.ndarray],
                        kinds: list[str], runs: list[tuple]) -> dict:
    """The study's variables on ``body``, ``run`` and ``step``: the runs' results and
    their errors against Hertz (`ref`)."""
    force_error = force / ref["force"] - 1
    radius_error = contact_radius / ref["contact_radius"] - 1
    parameters = [repr(resolve("elastic", acc)) for _, acc in runs]
    br, brs = ("body", "run"), ("body", "run", "step")
    return dict(
        interference=_var("step", w, "m",
                          "interference of the rigid flat (approach from first touch)"),
        hertz_force=_var("step", ref["force"], "N", "Hertz force 4/3 E' R^1/2 w^3/2"),
        hertz_contact_radius=_var("step", ref["contact_radius"], "m",
                                  "Hertz contact radius (R w)^1/2"),
        force=_var(brs, force, "N", "total contact force (finite elements)"),
        contact_radius=_var(brs, contact_radius, "m", "contact radius (finite elements)"),
        force_error=_var(brs, force_error, "1",
                         "relative force error against Hertz (FE / Hertz - 1)"),
        radius_error=_var(brs, radius_error, "1",
                          "relative contact radius error against Hertz (FE / Hertz - 1)"),
        max_force_error=_var(br, np.max(np.abs(force_error), axis=-1), "1",
                             "largest |relative force error| over the steps"),
        max_radius_error=_var(br, np.max(np.abs(radius_error), axis=-1), "1",
                              "largest |relative contact radius error| over the steps"),
        dofs=_var(br, scalars["dofs"], "1", "degrees of freedom of the run's final mesh"),
        wall_time=_var(br, scalars["wall_time"], "s",
                       "total wall time of the run (meshing, adaptivity and all steps)"),
        max_estimated_error=_var(br, scalars["estimated_error"], "1",
                                 "largest ZZ estimate of the relative energy-norm error "
                                 "over the steps"),
        adaptive_sweeps=_var(br, scalars["sweeps"], "1", "adaptive refinement sweeps performed"),
        kind=_var("run", np.array(kinds, dtype=object), "1",
                  "'preset' (accuracy preset) or 'refinement' (member of the refinement sequence)"),
        accuracy_parameters=_var("run", np.array(parameters, dtype=object), "1",
                                 "resolved accuracy parameters of the run (repr of a dict)"),
    )


def _penalty_study(geometry, material, w: np.ndarray, factors: np.ndarray,
                   penalty_accuracy: str | dict) -> tuple[dict, dict]:
    """The penalty study's variables on ``penalty_factor`` and its attributes: the
    penalty method against exact contact on the same mesh, and the runs' wall times."""
    pe = penalty_error(geometry, material, w, accuracy=penalty_accuracy,
                       penalty_factors=tuple(factors))
    exact = solve_asperity(geometry, material, w, accuracy=penalty_accuracy, contact="exact")
    times = [solve_asperity(geometry, material, w, accuracy=penalty_accuracy,
                            penalty_factor=c).attrs["total_wall_time"] for c in factors]
    pf = "penalty_factor"
    data = dict(
        penalty_force_error=_var(pf, np.abs(pe.force_error).max("step").values, "1",
                                 "largest |penalty / exact - 1| of the force over the steps "
                                 "(same mesh)"),
        penalty_radius_error=_var(pf, np.abs(pe.radius_error).max("step").values, "1",
                                  "largest |penalty / exact - 1| of the contact radius over "
                                  "the steps (same mesh)"),
        penalty_max_penetration=_var(pf, pe.max_penetration.max("step").values, "1",
                                     "largest nodal penetration / interference over the steps"),
        penalty_wall_time=_var(pf, times, "s",
                               "total wall time of a complete penalty run with this factor"),
        exact_wall_time=_var((), exact.attrs["total_wall_time"], "s",
                             "total wall time of a complete run with exact contact "
                             "(augmented Lagrangian)"),
    )
    penalty_attrs = dict(penalty_accuracy=penalty_accuracy if isinstance(penalty_accuracy, str)
                         else repr(resolve("elastic", penalty_accuracy)),
                         penalty_dofs=int(pe.attrs["dofs"]))
    return data, penalty_attrs


def hertz_accuracy_study(radius: float = 1.0, youngs_modulus: float = 1000.0,
                         poisson: float = 0.3,
                         interferences: Sequence[float] = (0.001, 0.002, 0.005, 0.01, 0.02),
                         presets: Sequence[str] = ("draft", "standard", "fine"),
                         refinement: Sequence[dict] | None = None,
                         penalty_factors: Sequence[float] = (10.0, 100.0, 1000.0, 10000.0),
                         penalty_accuracy: str | dict = "standard") -> xr.Dataset:
    """Errors, mesh sizes and wall times of the FE model against Hertz.

    Parameters
    ----------
    radius, youngs_modulus, poisson
        the Hertz problem (report 6.1: 1, 1000, 0.3; dimensionless, read
        as SI).
    interferences
        the loading levels [m], solved on one shared adaptive mesh per run.
    presets
        accuracy presets run for both bodies (runs labelled by name).
    refinement
        accuracy dicts forming a refinement sequence, run for the
        paraboloid only (runs "refine-1", ...); default
        `DEFAULT_REFINEMENT`; ``()`` for none.
    penalty_factors
        factors c of the penalty study (paraboloid, `penalty_accuracy`);
        ``()`` skips it.
    penalty_accuracy
        accuracy of the penalty study's mesh.

    Returns
    -------
    Dataset on dims ``body`` ("paraboloid", "sphere"), ``run`` (presets,
    then the refinement members), ``step`` and ``penalty_factor``; the
    sphere is NaN for refinement runs.  Errors are relative and signed
    (FE / Hertz - 1); ``max_*`` are the largest magnitudes over the steps.
    """
    t_study = time.perf_counter()
    material = LinearElastic(float(youngs_modulus), float(poisson))
    w = np.asarray(interferences, dtype=float)
    if w.ndim != 1 or w.size == 0 or np.any(w <= 0):
        raise ValueError("interferences must be a non-empty 1-D sequence of positive values")
    labels, kinds, runs = _study_runs(presets, refinement)

    geometries = dict(paraboloid=Paraboloid(radius), sphere=Sphere(radius))
    force, contact_radius, scalars = _solve_runs(geometries, material, w, runs, kinds)

    ref = hertz(radius, material, w)
    data = _accuracy_variables(w, ref, force, contact_radius, scalars, kinds, runs)
    coords = dict(
        body=("body", np.array(BODIES, dtype=object),
              dict(units="1", long_name="body: Hertz's paraboloid (half space with a "
                                        "paraboloidal gap) or the true sphere")),
        run=("run", np.array(labels, dtype=object),
             dict(units="1", long_name="accuracy preset or member of the refinement sequence")),
        step=("step", np.arange(len(w)), dict(units="1", long_name="load step index")),
    )

    factors = np.asarray(penalty_factors, dtype=float)
    if factors.size:
        penalty_data, penalty_attrs = _penalty_study(geometries["paraboloid"], material, w,
                                                     factors, penalty_accuracy)
        data.update(penalty_data)
        pf = "penalty_factor"
        coords[pf] = (pf, factors, dict(units="1", long_name="penalty factor c in kappa = c E' / h"))
    else:
        penalty_attrs = {}

    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(
        title="accuracy of the finite element asperity model on the Hertz problem (report 6.1)",
        reference="Hertz: r = sqrt(R w), A = pi R w, P = 4/3 E / (1 - nu^2) R^1/2 w^3/2",
        radius=float(radius),
        youngs_modulus=float(youngs_modulus),
        poisson=float(poisson),
        material=f"LinearElastic(E={float(youngs_modulus)!r}, nu={float(poisson)!r})",
        contact="penalty",
        default_penalty_factor=float(PENALTY_FACTOR),
        mesh_strategy="shared",
        report_max_force_error=REPORT_MAX_FORCE_ERROR,
        report_max_radius_error=REPORT_MAX_RADIUS_ERROR,
        report_source="report Fig. 6.5 (table; w = 0.002 ... 0.02)",
        study_wall_time=time.perf_counter() - t_study,
        **penalty_attrs,
    )
    return ds
