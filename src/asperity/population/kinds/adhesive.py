"""The ``adhesive`` kind: elastic FE asperities with Lennard-Jones adhesion in the
pipeline: grid, job, gather, interface (report 3.3.3, 7.3, 9.1).

A scene turns adhesion on with the effect ``adhesion`` and a section

    adhesion: {work_of_adhesion: 1.0, spacing: 0.5, cutoff: 16}

``work_of_adhesion`` is dgamma of eq. 3.17 in J/m^2 (7.3: 1 J/m^2, DESIGN.md
errata), ``spacing`` the intermolecular distance d of eq. 3.16 in **nm**
whatever the scene's length unit (a molecular length: 0.3-0.5 nm reads
better than 0.0005 um), ``cutoff`` the separation s_c / d beyond which the
law is dropped (`asperity.fe.contact.adhesion`: 16 loses 0.5 % of the work, the
report's 4 loses 8.3 %).  The body must be elastic
(`asperity.fe.drivers.adhesive.solve_asperity_adhesive`).

What changes against an asperity without adhesion:

- **Grid** (`interference_grid`): the attraction of the law starts when the
  tip is at the cut-off separation s_c, i.e. at the interference
  w = d - s_c = -(cutoff - 1) d (`reach`), before contact.  The plan's
  grid gets gap levels from there to 0, spaced d / 8 out to 12 d (where
  the asperities jump in and out) and growing by 10 % per level farther
  out, joined to the usual geometric grid of w > 0.
- **Job** (`Adhesive.spec`, `Adhesive.solve`): one job per curvature (the response
  is shift invariant in height but not self-similar: d does not scale).  It approaches the
  flat from the cut-off to the top of the sample's range and retracts it
  until the asperity lets go, recording jumps and the pull-off force.  The
  law (dgamma, d, cutoff, SI) is in the spec, hence in the key.
- **Gather** (`Adhesive.gather`): both branches (dim ``branch``: approach, retract)
  on (height, curvature, interference) by `interpolate_adhesive` (jumps kept
  as jumps); force is negative where the asperity attracts, contact area 0
  where it does not touch; ``in_contact`` is 1 where the contact area is
  positive; ``elastic`` is 1 where it touches and the FE job's ``elastic``
  flag holds (von Mises below the yield stress everywhere), the flag of the
  nearer record of the branch (its interpolation at 1/2), and
  ``small_strain`` where it touches and the largest strain magnitude,
  interpolated, is below 8 % (report 7.3, Fig. 7.10: adhesion raises the
  stresses of a contact, so the share of elastic asperities is judged by the
  FE stresses, not by F/A); ``extrapolated`` flags grid points beyond the
  job's deepest level (the last tangent), as `asperity.population.gather.gather`.
  Per curvature: pull-off force, Tabor parameter, jump interferences, the DMT and JKR
  pull-off forces 2 pi R W_c and 3/2 pi R W_c, and the computed paths
  (Fig. 7.6) on (curvature, step).
- **Interface** (`Adhesive.interface`): the same integrator as every scene
  (`asperity.homogenize.interface_response`, eqs. 2.5-2.7) with
  ``reach``: an asperity of peak height z at separation h contributes
  X(z, kappa, w = z - h) for every w > -reach, not only w > 0; contacts
  are counted by ``in_contact``.  On retraction (from the smallest
  separation h_0) an asperity is on the retract branch if it jumped in,
  z - h_0 >= its jump-in interference, else still on the approach branch
  (each asperity caught at its own stage, as in 8.3).  The normal
  stiffness is -dp/dh of the homogenized pressure (the jumps of single
  asperities contribute to it, which an average of dF/dw would miss).
"""

from __future__ import annotations

import math
import time
from typing import Callable, Mapping

import numpy as np
import xarray as xr

from asperity.population.kinds.base import FiniteElementKind
from asperity.population.plan import geometric_levels
from asperity.population.plan import interference_grid as contact_grid
from asperity.scene import Adhesion, Material, build
from asperity.units import attrs

BRANCHES = ("approach", "retract")
#: gap levels of the grid: d * NEAR_STEP apart out to NEAR_RANGE d, growing by GROWTH beyond
NEAR_STEP = 0.125
NEAR_RANGE = 12.0
GROWTH = 0.1


# --- the law ------------------------------------------------------------------------------
def law(adhesion: Adhesion | Mapping[str, float]):
    """`asperity.fe.LennardJones` of the law (an `Adhesion`, or a job spec's ``adhesion``)."""
    from asperity.fe import LennardJones

    if isinstance(adhesion, Adhesion):
        adhesion = adhesion.spec()
    return LennardJones(float(adhesion["dgamma"]), float(adhesion["d"]), float(adhesion["cutoff"]))


def reach(adhesion: Adhesion) -> float:
    """Largest gap -w [m] at which the law acts: the tip at the cut-off separation,
    w = d - s_c (the first level of `asperity.fe.drivers.adhesive_trace.adhesive_path`).
    """
    lj = law(adhesion)
    return float(lj.range - lj.d)


def interference_grid(largest: float, count: int, adhesion: Adhesion) -> np.ndarray:
    """Gap levels from -`reach` up to 0, then the plan's geometric grid of w > 0.

    The gap levels are d / 8 apart out to 12 d, where the asperities jump
    into and out of contact (a jump-off lies within (2 mu + 4) d of contact,
    mu the Tabor parameter, the end of the solver's retraction), and grow
    by 10 % per level beyond (the attraction decays as (d / s)^2): 120
    levels for the default cut-off of 16.  The homogenization interpolates
    linearly in w, so a jump between two levels is integrated with an error
    of at most its height times half the spacing, d / 16.
    """
    d = float(adhesion.d)
    lo = reach(adhesion)
    h0 = NEAR_STEP * d
    w_near = min(NEAR_RANGE * d, lo)  # uniform steps up to here, geometric beyond
    near = np.linspace(0.0, w_near, int(math.ceil(w_near / h0 * (1 - 1e-12))) + 1)[1:]
    far = np.empty(0)
    if lo > w_near:
        m = int(math.ceil(math.log(lo / w_near) / math.log1p(GROWTH) * (1 - 1e-12)))
        far = geometric_levels(w_near, lo, m + 1)[1:]
        far[-1] = lo
    gaps = np.concatenate([near, far])
    return np.concatenate([-gaps[::-1], contact_grid(largest, count)])


# --- an adhesive sample on the plan's grid ------------------------------------------------
def on_levels(reference: xr.Dataset, other: xr.Dataset, name: str, clearance: float):
    """Two adhesive samples' `name` on the reference's requested levels, branch by
    branch, away from its jumps (farther than `clearance` [m] from its jump-in and
    jump-off): a (reference, other) pair of arrays per branch (`interpolate_adhesive`).
    Compares two discretizations of one asperity (tests, `benchmarks/adhesion_cost.py`)."""
    for which in ("approach", "retract"):
        keep = reference.requested.values & (reference.branch.values == which)
        w = reference.interference.values[keep]
        w = w[(np.abs(w - reference.attrs["jump_in_interference"]) > clearance)
              & (np.abs(w - reference.attrs["jump_off_interference"]) > clearance)]
        yield (interpolate_adhesive(reference, w, which)[name],
               interpolate_adhesive(other, w, which)[name])


def interpolate_adhesive(ds: xr.Dataset, grid, branch: str = "approach",
                         names=("force", "contact_area", "contact_radius")) -> dict:
    """An adhesive sample's curves on an interference grid, for one branch.

    The log-log interpolation of `asperity.population.gather` assumes positive
    curves growing from w = 0; an adhesive sample has negative forces,
    negative interferences (attraction before touching) and jumps, and two
    branches.  Here the records of `branch` ('approach', or 'retract' with
    the turning point) are taken in order of interference and split at the
    jumps into continuous pieces; each piece is interpolated by a monotone
    cubic (PCHIP) in (w, X); a grid point between the state before a jump
    and the one after (min_step * d apart) is interpolated linearly
    between them, so the jump stays a jump.  Below the branch's smallest
    interference the value is the first record's if that record is out of
    the adhesive range (force below 1e-6 of the largest: zero everywhere
    below), else NaN; above
    its largest, the last tangent, flagged.  Returns {name: values} and
    ``extrapolated`` (bool, beyond the largest interference).
    """
    from scipy.interpolate import PchipInterpolator

    from asperity.fe.drivers.adhesive_trace import retract_indices

    grid = np.asarray(grid, dtype=float)
    b = ds["branch"].values.astype(str)
    idx = np.nonzero(b == "approach")[0] if branch == "approach" else retract_indices(b)
    if branch not in ("approach", "retract") or idx.size == 0:
        raise ValueError(f"the sample has no {branch!r} records")
    w = ds["interference"].values[idx]
    jump = ds["jump"].values[idx].astype(bool)
    jump[0] = False
    if branch == "retract":  # path order is decreasing w
        idx, w, jump = idx[::-1], w[::-1], np.concatenate(([False], jump[1:][::-1]))
    # jump[k]: a discontinuity between sorted records k - 1 and k
    if np.any(np.diff(w) < 0):
        raise ValueError(f"the {branch} records are not monotonic in the interference")
    starts = np.concatenate(([0], np.nonzero(jump)[0]))
    stops = np.concatenate((np.nonzero(jump)[0], [len(w)]))
    forces = ds["force"].values[idx]
    first_out = (ds["contact_area"].values[idx[0]] == 0
                 and abs(forces[0]) <= 1e-6 * np.max(np.abs(forces)))
    extrap = grid > w[-1]
    out = {}
    for name in names:
        x = ds[name].values[idx].astype(float)
        y = np.interp(grid, w, x)  # linear: across a jump's gap
        for lo, hi in zip(starts, stops):
            ws, xs = w[lo:hi], x[lo:hi]
            keep = np.concatenate(([True], np.diff(ws) > 0))
            ws, xs = ws[keep], xs[keep]
            inside = (grid >= ws[0]) & (grid <= ws[-1])
            if ws.size >= 2 and inside.any():
                y[inside] = PchipInterpolator(ws, xs)(grid[inside])
        y[grid < w[0]] = x[0] if first_out else np.nan
        if len(w) > 1 and w[-1] > w[-2]:
            slope = (x[-1] - x[-2]) / (w[-1] - w[-2])
            y[extrap] = x[-1] + slope * (grid[extrap] - w[-1])
        out[name] = y
    out["extrapolated"] = extrap
    return out


# --- the gather ---------------------------------------------------------------------------
GATHERED = {
    "force": ("N", "normal force on the asperity, compressive positive (adhesion negative)"),
    "contact_area": ("m^2", "real contact area (0 where the asperity does not touch)"),
    "contact_radius": ("m", "contact radius (0 where the asperity does not touch)"),
    "in_contact": ("1", "1 where the asperity touches the flat (contact area > 0)"),
    "elastic": ("1", "1 where the asperity touches the flat and is still elastic: von Mises "
                     "stress below the yield stress everywhere (the FE job's flag; report 7.3, "
                     "Fig. 7.10)"),
    "small_strain": ("1", "1 where the asperity touches the flat and every strain magnitude is "
                          "below 8 % (report 7.3)"),
}
#: per curvature, as `asperity.fe.drivers.adhesive.stack_runs` gives them
PER_CURVATURE = ("pull_off_force", "pull_off_interference", "tabor_parameter",
                 "jump_in_interference", "jump_off_interference")
PATH = {"interference": "path_interference", "force": "path_force",
        "contact_area": "path_contact_area", "branch": "path_branch", "jump": "path_jump",
        "valid": "path_valid"}


def gather(plan: xr.Dataset, samples: Mapping[str, xr.Dataset]) -> xr.Dataset:
    """Adhesive samples onto (branch, height, curvature, interference) (module docstring)."""
    from asperity.fe.drivers.adhesive import stack_runs
    from asperity.population.gather import (SMALL_STRAIN_LIMIT, fe_cost, samples_by_key,
                                            strain_magnitude)

    by_key = samples_by_key(plan, samples)
    heights, curvatures = plan["height"].values, plan["curvature"].values
    grid = plan["interference"].values
    pk, keys = plan["sample_curvature"].values, plan["key"].values
    runs = [by_key[str(keys[np.flatnonzero(pk == k)[0]])] for k in curvatures]
    names = ("force", "contact_area", "contact_radius", "elastic", "strain")
    shape = (len(BRANCHES), curvatures.size, grid.size)
    tables = {name: np.empty(shape) for name in names}
    beyond = np.empty(shape, bool)
    for j, ds in enumerate(runs):  # one FE job per curvature, each vectorized over the grid
        ds = ds.assign(strain=strain_magnitude(ds))
        for b, branch in enumerate(BRANCHES):
            c = interpolate_adhesive(ds, grid, branch, names)
            for name in names:
                tables[name][b, j] = c[name]
            beyond[b, j] = c["extrapolated"]
    touching = tables["contact_area"] > 0
    tables["in_contact"] = touching.astype(float)
    tables["elastic"] = (touching & (tables["elastic"] >= 0.5)).astype(float)
    tables["small_strain"] = (touching & (tables.pop("strain") < SMALL_STRAIN_LIMIT)).astype(float)
    bad = [n for n, v in tables.items() if not np.isfinite(v).all()]
    if bad:
        raise ValueError(f"adhesive gather: NaN in {', '.join(bad)} (a sample does not cover "
                         f"the grid from {grid[0]:.6g} m)")
    dims = ("branch", "height", "curvature", "interference")
    full = (len(BRANCHES), heights.size, curvatures.size, grid.size)

    def over_heights(a):  # shift invariant: every height has its curvature's curve
        return np.broadcast_to(a[:, None], full)

    out = xr.Dataset(
        {name: (dims, over_heights(tables[name]), attrs(*GATHERED[name])) for name in GATHERED},
        coords={
            "branch": ("branch", list(BRANCHES), attrs(
                "1", "approach of the flat, or its retraction (report 7.3, Fig. 7.6)")),
            "height": ("height", heights, attrs("m", "asperity peak height")),
            "curvature": ("curvature", curvatures, attrs("1/m", "tip curvature")),
            "interference": ("interference", grid, attrs(
                "m", "interference (negative: gap before first touch)")),
        })
    out["extrapolated"] = (dims, over_heights(beyond), attrs(
        "1", "beyond the largest interference the FE job computed (continued with its last "
        "tangent)"))
    paths = stack_runs(runs, "curvature", curvatures, attrs("1/m", "tip curvature"))
    for name in PER_CURVATURE:
        out[name] = ("curvature", paths[name].values, dict(paths[name].attrs))
    W = float(runs[0].attrs["work_of_adhesion"])
    radius = np.array([float(r.attrs["tip_radius"]) for r in runs])
    out["pull_off_force_dmt"] = ("curvature", 2 * np.pi * radius * W,
                                 attrs("N", "DMT pull-off 2 pi R W_c (rigid sphere, Derjaguin)"))
    out["pull_off_force_jkr"] = ("curvature", 1.5 * np.pi * radius * W,
                                 attrs("N", "JKR pull-off 3/2 pi R W_c"))
    for src, dst in PATH.items():
        var = paths[src]
        out[dst] = (("curvature", "step"), var.values,
                    attrs(var.attrs["units"], f"computed path: {var.attrs['long_name']}"))
    out = out.assign_coords(step=("step", paths["step"].values, attrs("1", "path step index")))
    adh = runs[0].attrs
    out.attrs.update(
        reach=-float(grid[0]), adhesion=str(adh.get("adhesion", "")),
        work_of_adhesion=W, **fe_cost(runs),
        sign_convention="force compressive positive; adhesion (attraction) negative")
    return out


# --- the interface ------------------------------------------------------------------------
def retract_table(asperities: xr.Dataset, h_turn: float) -> xr.Dataset:
    """The retract branch of every asperity after the flat came to separation `h_turn`.

    An asperity of peak height z was pressed to w = z - h_turn; if it got there
    past its jump-in interference it is on the retract branch (the contact
    hangs on, JKR-like), otherwise it never touched and retracts along its
    approach branch.  A curvature without jumps has one branch: retract.
    """
    app = asperities.sel(branch="approach", drop=True)
    ret = asperities.sel(branch="retract", drop=True)
    w_in = asperities["jump_in_interference"].fillna(-np.inf)
    jumped = (asperities["height"] - h_turn) >= w_in  # (height, curvature)
    out = ret.copy()
    for name, var in ret.data_vars.items():
        if "interference" in var.dims:
            out[name] = xr.where(jumped, var, app[name]).transpose(*var.dims).assign_attrs(var.attrs)
    return out


def by_branch(asperities: xr.Dataset, separations: np.ndarray,
              homogenized: Callable[..., xr.Dataset]) -> xr.Dataset:
    """The interface on dim ``branch`` (approach, retract from the smallest separation).

    `homogenized(table, reach=..., contact=...)` is the pipeline's homogenization of
    one (height, curvature, interference) table over `separations` (`asperity.stages.homogenize`).
    """
    grid_dims = {"height", "curvature", "interference"}
    r = float(asperities.attrs["reach"])
    h_turn = float(np.min(separations))
    tables = {"approach": asperities.sel(branch="approach", drop=True),
              "retract": retract_table(asperities, h_turn)}
    parts = []
    for name in BRANCHES:
        t = tables[name]
        t = t[[v for v in t.data_vars if set(t[v].dims) == grid_dims]]
        parts.append(homogenized(t, reach=r, contact="in_contact"))
    out = xr.concat(parts, dim="branch", data_vars="all", coords="minimal", compat="override")
    out["density_integral"] = out["density_integral"].isel(branch=0, drop=True)
    out = out.assign_coords(branch=("branch", list(BRANCHES), attrs(
        "1", "approach of the flat, or its retraction from the smallest separation (7.3)")))
    h = out["separation"].values
    p = out["nominal_pressure"].transpose("branch", "separation").values
    out["normal_stiffness"] = (("branch", "separation"), -np.gradient(p, h, axis=1), attrs(
        "Pa/m", "normal stiffness -dp/dh of the homogenized pressure"))
    retract_p = p[1]
    out.attrs.update(
        reach=r, retract_from=h_turn,
        pull_off_pressure=float(max(-retract_p.min(), 0.0)),
        pull_off_separation=float(h[np.argmin(retract_p)]),
        largest_attraction_approach=float(max(-p[0].min(), 0.0)),
        sign_convention="pressure compressive positive; net attraction negative")
    return out


# --- the kind -----------------------------------------------------------------------------
class Adhesive(FiniteElementKind):
    name = "adhesive"

    def check(self, asperity, material, effects):
        if "plasticity" in effects:
            raise ValueError("effect `adhesion` needs an elastic body (no `plasticity`): "
                             "the adhesive solver is elastic (asperity.fe.drivers.adhesive)")
        super().check(asperity, material, effects)

    def grid(self, base, largest, count, adhesion):
        """The attraction acts before contact: gap levels too (`interference_grid`)."""
        return interference_grid(largest, count, adhesion)

    def spec(self, planning, height, curvature, level):
        """Geometry, range and body (`FiniteElementKind.base_spec`) and the law in SI;
        the path is the solver's own, no level count."""
        spec = self.base_spec(planning, height, curvature)
        spec["adhesion"] = planning.adhesion.spec()
        return spec

    def solve(self, spec, key):
        """Approach from the cut-off to the top of the range and retraction until the
        asperity lets go (`solve_asperity_adhesive`)."""
        from asperity import fe
        from asperity.population.geometry import spec_geometry

        curvature = float(spec["curvature"])
        geometry = spec_geometry(spec)
        material = build(Material.from_spec(spec["material"]), spec["effects"])
        top = float(spec["range"][1])
        cpu = time.process_time()
        try:
            ds = fe.solve_asperity_adhesive(geometry, material, law(spec["adhesion"]), w_max=top,
                                            accuracy=spec["accuracy"], label=key,
                                            progress=self.progress(key))
        except (fe.ConvergenceError, fe.ContactZoneError) as err:
            raise self.failed(key, curvature, err, ", adhesive") from err
        return self.record(ds, spec, key, geometry, math.nan, time.process_time() - cpu)

    def gather(self, plan, samples):
        return gather(plan, samples)

    def plan_attrs(self, planning):
        a = planning.adhesion
        return {"adhesion": f"Lennard-Jones dgamma = {a.dgamma:g} J/m^2, d = {a.d:g} m, "
                            f"cut-off {a.cutoff:g} d",
                "reach": reach(a)}

    def interface(self, asperities, separations, homogenized):
        return by_branch(asperities, separations, homogenized)


ADHESIVE = Adhesive()
