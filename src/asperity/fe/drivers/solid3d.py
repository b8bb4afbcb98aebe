"""Three-dimensional asperity pressed and slid by a rigid flat (report 3.3, 3.4, 9.2).

Body.  A hill z = surface(r) (a `geometry.Profile`, e.g. the `CosineHill`
of report 9.2, 2 um high and 10 um across its base) standing on a block, or
an elliptic paraboloid z = -(kappa_1 x^2 + kappa_2 y^2) / 2
(`geometry.EllipticParaboloid`, principal axes along x and y): the model
reads the surface over the plane, ``surface_xy(x, y)``.
The sliding direction is x, so the plane y = 0 is a plane of symmetry and
only the half y >= 0 is modelled (u_y = 0 on y = 0; the reported forces
are twice those of the half).  Support (3.3.1): u = 0 on the cut-off
boundary (the bottom of the block and its sides |x| = L, y = L).

The model by concern: the block and its graded tetrahedral mesh mapped onto the
body (`discretization.half_model_mesh`); the P2 displacements with B-bar strains,
the supports and the contact nodes' operators (`discretization.half_model`); the
residual, tangent and Newton of a step (the incremental form of report 3.22), with
the penalty pressure and the sliding resistance of report 3.3.2 and 3.3.4 at the
contact nodes and the solve through the slip instability (`sliding_model`; its
linear solves `solvers.linear`); the flat's motion and the times the steps land on
(`flat_motion`); the time steps (`sliding_march`), marched by `march.march`.

This module runs them: `solve_sliding` presses and slides the flat along a
`FlatMotion` and returns per step the variables of `OUTPUTS` with the sections of
the plane of symmetry; a run whose accepted steps stay under ``STALL_FRACTION`` of
their cap for ``STALL_STEPS`` steps in a row has stalled (past the junction's
critical friction coefficient) and stops with ``completed`` 0 and ``stop_reason``,
keeping its steps (the section "end" is then its last state).  `press_3d` presses
without friction and adds the normal stiffness; `solve_prescribed` solves the
linear elastic body with the displacements prescribed on its boundary (the patch
test).
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
import xarray as xr

from asperity.fe.contact.sliding import FrictionLaw, ShearResistance
from asperity.fe.discretization.half_model import HalfModel
from asperity.fe.discretization.half_model_mesh import MeshSpec, build_mesh
from asperity.fe.drivers.flat_motion import FlatMotion
from asperity.fe.drivers.march import march
from asperity.fe.drivers.sliding_march import SlidingMarch, largest_deformation, plane_snapshot
from asperity.fe.drivers.sliding_model import PENALTY_FACTOR_3D, SlidingModel
from asperity.fe.materials.elastic import equivalent_strain
from asperity.fe.outputs import VARIABLES, dataset, describe
from asperity.fe.presets import resolve

#: a run has stalled when this many accepted steps in a row each advanced less
#: than STALL_FRACTION of their segment's step cap: at that pace the rest of the
#: motion would take thousands of steps (report 9.2's mu = 20 past the critical
#: coefficient); the run stops there with ``completed`` 0.  STALL_STEPS lies above
#: the longest such streak of a run that goes on to finish (docs: changelog, 'Sliding
#: of one asperity').
STALL_STEPS, STALL_FRACTION = 20, 1e-3


#: the variables of `solve_sliding` (units and long names: `outputs.VARIABLES`)
OUTPUTS = ("time", "normal_displacement", "tangential_displacement", "normal_force",
           "tangential_force", "contact_area", "mean_pressure",
           "mean_tangential_traction", "max_pressure", "slip_fraction", "critical_shear_factor",
           "max_inelastic_strain", "max_von_mises", "phase", "newton_iterations", "step_cuts",
           "damped_solves", "time_step", "wall_time")


def solve_prescribed(model: HalfModel, material, displacement) -> tuple[np.ndarray, np.ndarray]:
    """Linear elastic body with u = displacement(x) on its whole boundary.

    `displacement` maps node coordinates (3, n) to displacements (3, n);
    returns the displacement dofs (ndofs,) and the stresses (6, ne, nq).
    For an affine field the exact solution is that field everywhere (the
    P2 isoparametric space contains it): the patch test.
    """
    ne = model.shape[0]
    Ke = model.element_matrices(material.tangent(6))
    nl = Ke.shape[1]
    ed = model.element_dofs
    rows = np.broadcast_to(ed.T[:, :, None], (ne, nl, nl)).ravel()
    cols = np.broadcast_to(ed.T[:, None, :], (ne, nl, nl)).ravel()
    K = sp.csr_matrix((Ke.ravel(), (rows, cols)), shape=(model.ndofs, model.ndofs))
    X = model.hm.mesh.doflocs
    U = np.asarray(displacement(X), float)
    u = np.zeros(model.ndofs)
    bd = model.boundary_dofs
    nodes_b = np.unique(np.nonzero(np.isin(model.dofmap, bd))[1])
    u[model.dofmap[:, nodes_b].ravel()] = U[:, nodes_b].ravel()
    bmask = np.zeros(model.ndofs, bool)
    bmask[model.dofmap[:, nodes_b].ravel()] = True
    inner = np.nonzero(~bmask)[0]
    rhs = -(K[inner][:, np.nonzero(bmask)[0]] @ u[bmask])
    u[inner] = spl.spsolve(K[inner][:, inner].tocsc(), rhs)
    strain = (model.Bsp @ u).reshape((6,) + model.shape)
    return u, np.tensordot(material.tangent(6), strain, axes=(1, 0))


def solve_sliding(geometry, material, motion: FlatMotion, friction: FrictionLaw,
                  accuracy="standard", mesh: MeshSpec | None = None,
                  contact_radius: float | None = None, penalty_factor: float = PENALTY_FACTOR_3D,
                  volumetric: str = "mean",
                  max_steps: int = 100_000, stall_steps: int = STALL_STEPS,
                  stall_fraction: float = STALL_FRACTION,
                  snapshots: dict | None = None, contact_section: bool = False,
                  progress=None) -> xr.Dataset:
    """A 3-D asperity pressed and slid by the rigid flat (report 9.2).

    Parameters
    ----------
    geometry
        a `Profile` (e.g. ``CosineHill(1e-6, pi / 5e-6)``: 2 um high, 10 um
        across; or a shallow `Paraboloid` for the Hertz check); its
        ``axisymmetric`` flag is ignored (the model is 3-D).
    material
        `BodnerPartom` or `J2Plasticity` (6-component updates) or `LinearElastic`.
    motion
        `FlatMotion`: approach and tangential displacement versus time.
    friction
        `FrictionLaw` (3.21, 3.24, 3.25).
    accuracy
        `presets.SLIDING_ACCURACY` preset name or dict: mesh sizes, steps per segment
        (caps), Newton tolerance, inelastic step limit.
    mesh
        override the block and grading (`MeshSpec`); default
        `MeshSpec.for_hill`.
    contact_radius
        estimate r of the contact radius (default: the geometric
        intersection radius at the largest approach); sizes the tip
        elements and the candidate contact zone (2.5 r + the sliding
        distance).
    max_steps
        stop after this many accepted steps (attribute ``completed`` 0).
    stall_steps, stall_fraction
        stop (``completed`` 0, with a warning) once `stall_steps` accepted steps in a row
        each advanced less than `stall_fraction` of their segment's step cap (the
        segment's duration over the preset's steps for it): the solver has stalled,
        as past the junction's critical friction coefficient; the steps so far are
        kept.
    snapshots
        {name: time}: the displacements and inelastic strain on the
        symmetry plane at these times (default: end of pressing and end).
    contact_section
        also the normal pressure at the contact nodes at these times (dims
        ``snapshot``, ``contact_node``), with the nodes' x, y and weights: the
        contact's shape (`press_3d`).
    progress
        optional callable(str) for progress lines.

    Returns an `xarray.Dataset`: per step (dim ``step``) the variables of
    `OUTPUTS`; the symmetry-plane section (dims ``plane_node``,
    ``plane_triangle``, ``corner``, ``snapshot``); attributes describing
    the mesh, the solver and where the largest deformation sits;
    ``completed`` (0 if the run stopped before the end of the motion) with
    ``stop_reason``.
    """
    t_start = time.perf_counter()
    if not (int(stall_steps) >= 1 and 0.0 <= stall_fraction < 1.0):
        raise ValueError(f"stall_steps must be >= 1 and stall_fraction in [0, 1), got "
                         f"{stall_steps} and {stall_fraction}")
    preset = resolve("sliding", accuracy)
    w_knots = np.asarray(motion.normal, float)
    d_knots = np.asarray(motion.tangential, float)
    w_max = float(w_knots.max())
    slide = float(np.abs(d_knots - d_knots[0]).max())
    if w_max >= geometry.height and not geometry.shallow:
        raise ValueError(f"approach {w_max:.4g} m reaches the foot of the hill "
                         f"(height {geometry.height:.4g} m)")
    if contact_radius is None:
        contact_radius = float(geometry.intersection_radius(np.array([max(w_max, 0.0)]))[0])
        if not contact_radius > 0:
            contact_radius = 0.1 * geometry.extent
    spec = mesh if mesh is not None else MeshSpec.for_hill(geometry, contact_radius, preset)
    hm = build_mesh(geometry, spec)
    cand = min(2.5 * contact_radius + slide, 0.95 * spec.half_width)
    model = HalfModel(geometry, hm, cand, volumetric=volumetric)
    sm = SlidingModel(model, material, friction, penalty_factor, preset["tolerance"],
                      preset["max_iterations"])
    t_mesh = time.perf_counter() - t_start
    say = progress or (lambda s: None)
    say(f"mesh: {hm.reference.t.shape[1]} tetrahedra, {model.ndofs} dofs "
        f"({len(model.free)} free), {model.cfacets.size} contact facets, {t_mesh:.2f} s")

    # --- time stepping: `march` with the steps of `SlidingMarch`
    run = SlidingMarch(sm, motion, friction, preset, stall_steps=stall_steps,
                        stall_fraction=stall_fraction, snapshots=snapshots,
                        contact_section=contact_section, say=say)
    march(run, run.caps[motion.segment(run.t)] / 2.0, max_steps)
    rows, t, u, w, state = run.rows, run.t, run.u, run.w, run.state
    stop_reason, critical = run.stop_reason, run.critical

    completed = t >= motion.end * (1 - 1e-12)
    if not stop_reason and not completed:
        stop_reason = f"max_steps ({max_steps}) reached at t = {t:.6g} s"
    snap = run.snap
    if "end" in run.snap_times and "end" not in snap:  # a run stopped early: its last state
        snap["end"] = (t, plane_snapshot(model, u, state, run.out_last["contact"]["tn"]
                                    if contact_section else None), {})
    total = time.perf_counter() - t_start
    head = dataset({name: np.array([r[name] for r in rows]) for name in OUTPUTS}, geometry,
                   material, accuracy, preset, "time step index")
    for name in OUTPUTS:     # forces and areas of the 3-D body, whatever the profile's flag
        units, long_name = VARIABLES[name]
        head[name].attrs.update(units=units, long_name=long_name)
    return _sliding_dataset(head, rows, model, sm, u, w, state, snap, dict(
        friction=describe(friction.resistance),
        slip_regularization=float(friction.slip_regularization),
        mesh=repr(spec),
        symmetry="half model y >= 0 (plane of symmetry y = 0 contains the sliding direction x)",
        elements=int(model.shape[0]), element_type="10-node tetrahedra (P2, isoparametric), "
        "4 quadrature points" + (", B-bar (element-mean volumetric strain)"
                                 if volumetric == "mean" else ""),
        dofs=int(model.ndofs), free_dofs=int(len(model.free)),
        tip_element_size=float(spec.tip_size), contact_facets=int(model.cfacets.size),
        contact_candidate_radius=float(model.contact_radius),
        penalty_factor=float(penalty_factor),
        critical_shear_factor=min(critical, default=math.inf),
        motion_times=np.asarray(motion.times, float), motion_normal=w_knots,
        motion_tangential=d_knots,
        steps=len(rows) - 1, total_step_cuts=int(sum(r["step_cuts"] for r in rows)),
        total_newton_iterations=int(sum(r["newton_iterations"] for r in rows)),
        steps_through_slip=int(sum(r["damped_solves"] > 0 for r in rows)),
        factorizations=int(sm.linear.factorizations), krylov_solves=int(sm.linear.krylov_solves),
        completed=int(completed), stop_reason=stop_reason,
        mesh_wall_time=t_mesh, total_wall_time=total))


def press_3d(geometry, material, approach, accuracy="standard", mesh: MeshSpec | None = None,
             contact_radius: float | None = None, penalty_factor: float = PENALTY_FACTOR_3D,
             progress=None) -> xr.Dataset:
    """The flat pressed onto the 3-D asperity without sliding or friction: `solve_sliding`
    with the flat moving only normally, w(t) through 0 and the approaches of `approach`
    (a number or increasing sequence [m]) at t = 1, 2, ... s, each segment in the
    preset's ``normal_steps`` steps, and a frictionless law (t_x = t_y = 0, report
    3.3.2).  The steps land on the knots (`step_grid`), so each approach is a row, and a
    snapshot ``approach i`` with the contact section (``contact_pressure`` at the contact
    nodes ``contact_x``, ``contact_y``: the contact's shape).

    Returns `solve_sliding`'s Dataset with ``normal_stiffness`` dF/dw [N/m] added: the
    derivative of the force history, second-order differences on the non-uniform steps
    (`numpy.gradient`), one-sided at the ends."""
    w = np.atleast_1d(np.asarray(approach, float))
    if w.ndim != 1 or not (np.all(np.isfinite(w)) and w[0] > 0 and np.all(np.diff(w) > 0)):
        raise ValueError(f"approach must be positive and increasing, got {approach!r}")
    times = tuple(float(t) for t in range(w.size + 1))
    motion = FlatMotion(times, (0.0,) + tuple(w), (0.0,) * (w.size + 1))
    scale = contact_radius if contact_radius is not None else float(
        geometry.intersection_radius(w[-1:])[0])
    ds = solve_sliding(geometry, material, motion, FrictionLaw(ShearResistance(), 1e-3 * scale),
                       accuracy=accuracy, mesh=mesh, contact_radius=contact_radius,
                       penalty_factor=penalty_factor, progress=progress, contact_section=True,
                       snapshots={f"approach {i}": t for i, t in enumerate(times[1:])})
    f, wd = ds["normal_force"].values, ds["normal_displacement"].values
    ds["normal_stiffness"] = ("step", np.gradient(f, wd), dict(
        units="N/m", long_name="normal contact stiffness dF/dw (differences of the force history)"))
    return ds


def _sliding_dataset(ds: xr.Dataset, rows, model: HalfModel, sm: SlidingModel, u, w, state,
                     snap, attrs):
    """The per-step Dataset `ds` with the symmetry-plane sections, the profile
    below the apex and the attributes."""
    # symmetry-plane section (Fig. 9.5)
    X = model.hm.mesh.doflocs[:, model.plane_nodes]
    names = list(snap)
    if names:
        ds = ds.assign_coords(snapshot=("snapshot", np.array(names, dtype=object),
                                        dict(units="1", long_name="instant of the section")))
        ds["snapshot_time"] = ("snapshot", np.array([snap[n][0] for n in names]),
                               dict(units="s", long_name="time of the section"))
        for key, var, units, ln in (("ux", "plane_ux", "m", "horizontal displacement u_x"),
                                    ("uz", "plane_uz", "m", "vertical displacement u_z"),
                                    ("ep", "plane_inelastic_strain", "1",
                                     "von Mises equivalent inelastic strain (element means "
                                     "averaged at the nodes)")):
            ds[var] = (("snapshot", "plane_node"), np.array([snap[n][1][key] for n in names]),
                       dict(units=units, long_name=f"{ln} on the symmetry plane y = 0"))
        if "tn" in snap[names[0]][1]:
            ds["contact_pressure"] = (("snapshot", "contact_node"),
                                      np.array([snap[n][1]["tn"] for n in names]), dict(
                units="Pa", long_name="normal pressure t_N at the contact node (penalty)"))
            for var, val, units, ln in (
                    ("contact_x", model.vX[0], "m", "x of the contact node (weighted, undeformed)"),
                    ("contact_y", model.vX[1], "m", "y of the contact node (weighted, undeformed)"),
                    ("contact_weight", model.vw, "m^2", "weight int phi_i ds of the contact node "
                     "(half model)")):
                ds[var] = ("contact_node", val, dict(units=units, long_name=ln))
            ds = ds.assign_coords(contact_node=("contact_node", np.arange(model.vw.size), dict(
                units="1", long_name="contact node (P2 node of a top facet)")))
    ds["plane_x"] = ("plane_node", X[0], dict(units="m", long_name="x of the node (undeformed)"))
    ds["plane_z"] = ("plane_node", X[2], dict(
        units="m", long_name="z of the node above the apex (undeformed)"))
    ds["plane_triangles"] = (("plane_triangle", "corner"), model.plane_triangles.T.astype(np.int32),
                             dict(units="1", long_name="node indices (into plane_node) of the "
                                  "linear sub-triangles of the 6-node faces on y = 0"))
    ds = ds.assign_coords(
        plane_node=("plane_node", np.arange(X.shape[1]),
                    dict(units="1", long_name="node on the symmetry plane")),
        plane_triangle=("plane_triangle", np.arange(model.plane_triangles.shape[1]),
                        dict(units="1", long_name="triangle on the symmetry plane")),
        corner=("corner", np.arange(3), dict(units="1", long_name="triangle corner")))
    # inelastic strain versus depth below the flat, under the apex
    a_max = max(r["contact_area"] for r in rows)
    a_ref = math.sqrt(a_max / math.pi) if a_max > 0 else model.contact_radius / 2.5
    ep = equivalent_strain(state.inelastic_strain)
    Ud = model.point_displacements(u)
    xd = model.x + Ud
    depth = -w - xd[2]
    nodes = model.hm.nodes_ref
    apex = int(np.argmin(np.sum(nodes**2, axis=0)))
    cx = float(model.hm.mesh.doflocs[0, apex] + u[model.dofmap[0, apex]])
    under = np.hypot(xd[0] - cx, xd[1]) <= a_ref
    edges = np.linspace(0.0, 3.0 * a_ref, 16)
    mids = 0.5 * (edges[1:] + edges[:-1])
    k = np.clip(np.searchsorted(edges, depth, side="right") - 1, -1, mids.size)
    prof = np.full(mids.size, np.nan)
    sel = under & (k >= 0) & (k < mids.size)
    if sel.any():
        np.fmax.at(prof, k[sel], ep[sel])
    ds = ds.assign_coords(depth=("depth", mids, dict(
        units="m", long_name="depth below the flat (bin centre)")))
    ds["inelastic_strain_below_apex"] = ("depth", prof, dict(
        units="1", long_name="largest equivalent inelastic strain at this depth within a_ref "
        "(horizontally) of the apex, end of the run"))
    attrs.update(largest_deformation(model, u, w, state, a_ref))
    for name in names:          # the same at the other sections (e.g. end of pressing)
        if name != "end":
            key = name.replace(" ", "_")
            for k, v in snap[name][2].items():
                if k.startswith(("largest_deformation", "reference_contact", "max_inelastic")) \
                        and not k.endswith("criterion"):
                    attrs[f"{key}_{k}"] = v
    attrs["apex_x_end"] = cx
    sliding = np.array([r["phase"] == "sliding" and r["contact_area"] > 0 for r in rows])
    if sliding.any():
        tau = np.array([r["mean_tangential_traction"] for r in rows])[sliding]
        attrs["mean_tangential_traction_sliding"] = float(tau.mean())
        attrs["mean_tangential_traction_sliding_method"] = (
            "mean over the sliding steps with contact of tangential force / contact area "
            "(report 9.2: about 64 MPa)")
    ds.attrs.update({k: v for k, v in attrs.items()})
    return ds
