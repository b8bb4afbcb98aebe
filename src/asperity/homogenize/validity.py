"""Where a homogenized interface holds (DESIGN.md: Trust; report 2.5, 7.3, 7.4, 8.2).

The statistical route of report 2.5 adds up independent asperities whose
response was computed (or is Hertz's).  Each separation of an interface is
checked against the assumptions this rests on, with limits set in the scene
(``validity:``, config/schema.yaml, defaults and their sources in the docs,
guide/validity.md):

1. **Computed responses.**  The gather (`asperity.population.models.gather`)
   continues an FE curve beyond its last level in a straight line and flags
   those points ``extrapolated``.  ``extrapolated_load_fraction`` is the share
   of the nominal pressure those points carry, n E^(F x) / n E^(F) (eq. 2.7),
   beside ``extrapolated_fraction``, the share of contacting asperities.
2. **Elastic asperities below yield.**  ``yielded_fraction``: the share of
   contacting asperities beyond first yield (report 7.3, Figs. 7.10, 7.14).
   FE asperities that record it carry the ``elastic`` flag of their job (no
   inelastic strain, or von Mises below an elastic body's yield stress).
   Otherwise an asperity counts as yielded when its mean contact pressure
   F / A exceeds a limit: first yield of a Hertz contact, p0 = 1.5 F/A =
   1.60 Y (von Mises, nu = 0.3; Johnson, *Contact Mechanics*, 1985, 6.2),
   where the material has a yield stress, else the hardness H.  The limit
   applies to asperities modelled elastic; with the effect ``plasticity``
   the share is recorded, not limited.  The scene-wide summary is
   Greenwood & Williamson's plasticity index (1966; report 7.3 with the
   errata of DESIGN.md)::

       psi = (E' / H) sqrt(sigma_p / R),   E' = E / (1 - nu^2)

   with sigma_p the standard deviation of the peak heights and R = 1 / E(kappa)
   the radius of the mean peak curvature, both over the scene's peak
   density (`peak_statistics`).  GW: psi < 0.6 deforms elastically at all but
   extreme loads, psi > 1 plastically at the lightest.
3. **Small strain** (report 7.3: every strain below 8 %):
   ``large_strain_fraction`` = 1 - ``small_strain_fraction`` of FE asperities;
   recorded, not limited, where the jobs are in finite-strain kinematics
   (effect ``finite_strain``, `asperity.fe.discretization.kinematics`).
4. **Independent asperities.**  The expectation (2.5) sums asperities that do
   not feel each other.  ``contact_area_ratio`` grows with the load, and
   ``interaction`` is the mean contact radius over half the mean spacing of
   the contacts, 2 a_mean sqrt(N_c) (N_c contacts per unit area): 1 where
   neighbouring contacts of a square array would touch.  A neighbour's
   Boussinesq deflection at the spacing l is F / (pi E' l) = 2 rho / (3 pi)
   of a Hertz asperity's own interference (rho = interaction).

5. **Gaussian heights.**  The Nayak/Francis density (2.4.1) and Greenwood and
   Williamson's (7.1) assume Gaussian heights.  Where such a density is fed by
   a measured profile or map, its skewness and kurtosis are checked against the
   limits of `asperity.surface.distribution` (|Sk| <= 0.3, 2.5 <= Ku <= 4, where
   the light-load answer is off by a factor of two); outside them every
   separation with contact is not valid (``gaussian_heights``).  A map's own
   peaks (the sampled density) need no such assumption.
6. **What could not be checked is not valid.**  An elastic asperity's yield is
   judged by its contact pressure against a yield stress or hardness; with
   neither (no ``material.hardness`` or ``yield_stress``), every separation
   with contact is not valid (``unchecked_yield``): the result may hold, but
   nothing in the scene says so.  `valid_ranges` (and ``asperity show``) count
   these apart from the limits that fail.

A separation is ``valid`` where every limit holds; ``validity`` names the
first that fails (empty where valid).  A branch of unloading (8.3) starts
from the loading state at ``unloading_from``, each asperity on its own path:
it fails where that state fails, and where its own contact area does.

Hardness (`hardness_of`): the scene's ``material.hardness``; else Tabor's
H = 2.8 Y (*The Hardness of Metals*, 1951; Johnson 1985, 6.2: the mean
pressure of a fully plastic indentation is 2.8-3 Y) with the yield stress
Y of a J2 or elastic body; for Bodner-Partom, Y is the saturated uniaxial
flow stress at Z = Z1 (+ Z3 with directional hardening) and a strain rate
of 1e-3 1/s (`asperity.uniaxial.point.uniaxial_flow_stress`, the report's
flow law inverted).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np
import xarray as xr

from asperity.scene.materials import Material
from asperity.units import attrs

log = logging.getLogger("asperity")

__all__ = ["Limits", "Plasticity", "HARDNESS_OVER_YIELD", "FIRST_YIELD_P0", "REFERENCE_STRAIN_RATE",
           "hardness_of", "plasticity_of", "with_indicators", "peak_statistics", "plasticity_index",
           "assess", "valid_ranges", "warn_invalid"]

#: Tabor's constraint factor: hardness over the (representative) flow stress
HARDNESS_OVER_YIELD = 2.8
#: first yield of a Hertz contact (von Mises, nu = 0.3): peak pressure p0 over Y
FIRST_YIELD_P0 = 1.6
#: the strain rate at which a rate-dependent body's saturated flow stress gives its hardness [1/s]
REFERENCE_STRAIN_RATE = 1e-3

#: what a failing limit means and what the scene can change, appended to the warning
_INDEPENDENT = ("the contacts are no longer independent asperities (2.5): the boundary-element "
                "reference of the map (a scene's reference section) measures how far the route is")
REMEDIES = {
    "extrapolated_load_fraction": (
        "asperities pressed beyond their FE job's range (asperity.max_height_fraction of a hill, "
        "max_radius_fraction of a sphere, yield_multiple of an elliptic summit) carry that load, "
        "continued in a straight line (an anisotropic route's departure from Hertz: held); with the "
        "representative mapping, asperity.mapping: coupled presses a hill by at most its amplitude (2.5.1)"),
    "yielded_fraction": ("elastic asperities beyond first yield: asperity.model: fe with "
                         "effects: [plasticity]"),
    "large_strain_fraction": "strains of 8 % or more in small-strain FE jobs: add the effect finite_strain",
    "contact_area_ratio": _INDEPENDENT,
    "interaction": _INDEPENDENT,
    "plasticity_index": ("Greenwood and Williamson's plasticity index: plastic at the lightest loads "
                         "(asperity.model: fe with effects: [plasticity])"),
    "gaussian_heights": ("the Nayak and Greenwood-Williamson densities assume Gaussian heights: "
                         "use the map's own peaks (population.density: sampled) or a reference "
                         "scene's interacting or boundary-element route"),
    "unchecked_yield": ("nothing says whether the asperities yield: give material.hardness or "
                        "material.yield_stress"),
}
#: assumptions checked besides the indicators' limits (module text, 5-6)
ASSUMPTIONS = ("gaussian_heights", "unchecked_yield")
#: validity reasons that say a check could not be made, not that a limit failed
UNCHECKED = ("unchecked_yield",)

#: table variables this module adds before homogenizing, and what `assess` turns them into
EXTRAPOLATED_FORCE = "extrapolated_force"
YIELDED = "yielded"


@dataclass(frozen=True)
class Limits:
    """The scene's ``validity`` section: the largest value of each indicator that is
    still valid (`plasticity_index`: None, not limited)."""

    extrapolated_load_fraction: float
    yielded_fraction: float
    large_strain_fraction: float
    contact_area_ratio: float
    interaction: float
    plasticity_index: float | None
    #: the interacting route's own indicator (`asperity.stages.routes`), not used here
    merged_load_fraction: float = 0.5

    def __post_init__(self):
        for name in ("extrapolated_load_fraction", "yielded_fraction", "large_strain_fraction",
                     "contact_area_ratio"):
            v = getattr(self, name)
            if not 0.0 <= v <= 1.0:
                raise ValueError(f"validity.{name} must be a share in [0, 1], got {v!r}")
        if not self.interaction >= 0.0:
            raise ValueError(f"validity.interaction must be >= 0, got {self.interaction!r}")
        if self.plasticity_index is not None and not self.plasticity_index > 0.0:
            raise ValueError(f"validity.plasticity_index must be > 0, got {self.plasticity_index!r}")


@dataclass(frozen=True)
class Plasticity:
    """What the material says about yield, for the validity of an interface.

    plane_strain_modulus  E' = E / (1 - nu^2) [Pa]
    hardness, hardness_rule   H [Pa] (NaN: unknown) and where it comes from
    yield_pressure, yield_rule  the mean contact pressure F/A beyond which an
        asperity counts as yielded [Pa] (NaN: not by its pressure), and the rule
    by_flag  first yield is the FE jobs' ``elastic`` flag
    modelled  the asperities are inelastic (effect ``plasticity``): the yielded
        share is recorded, not limited
    finite_strain  their FE jobs are in finite-strain kinematics (effect
        ``finite_strain``): the large-strain share is recorded, not limited
    """

    plane_strain_modulus: float
    hardness: float
    hardness_rule: str
    yield_pressure: float
    yield_rule: str
    by_flag: bool
    modelled: bool
    finite_strain: bool = False


def hardness_of(material: Material) -> tuple[float, str]:
    """H [Pa] of a material (`asperity.scene.Material`) and its rule (module docstring).
    (NaN, reason) if the material has neither a hardness nor a yield stress nor a
    Bodner-Partom set."""
    if material.hardness is not None:
        return float(material.hardness), "given in the scene (material.hardness)"
    y = material.yield_stress
    if material.model == "bodner_partom":
        from asperity.scene.materials import build  # here: builds the body (imports asperity.fe)
        from asperity.uniaxial.point import uniaxial_flow_stress

        body = build(material, ["plasticity"])
        z_sat = body.Z1 + (body.Z3 if body.directional_hardening else 0.0)
        flow = uniaxial_flow_stress(body, REFERENCE_STRAIN_RATE, z_sat)
        return HARDNESS_OVER_YIELD * flow, (
            f"{HARDNESS_OVER_YIELD} x the saturated Bodner-Partom flow stress {flow / 1e6:.4g} MPa "
            f"(Z = {z_sat / 1e6:.4g} MPa, {REFERENCE_STRAIN_RATE:g} 1/s; Tabor)")
    if y is not None and math.isfinite(float(y)):
        return HARDNESS_OVER_YIELD * float(y), (
            f"{HARDNESS_OVER_YIELD} x the yield stress {float(y) / 1e6:.4g} MPa (Tabor)")
    return math.nan, "unknown: the material has no hardness, yield stress or Bodner-Partom set"


def plasticity_of(material: Material, effects, fe_flag: bool = False) -> Plasticity:
    """The `Plasticity` of a scene's material under its `effects`; `fe_flag`: the
    asperity table carries the FE jobs' ``elastic`` flag (then it judges first yield
    where the body has a yield stress)."""
    from asperity.references.hertz import plane_strain_modulus

    e_prime = float(plane_strain_modulus(material.youngs_modulus, material.poisson))
    h, rule = hardness_of(material)
    modelled = "plasticity" in set(effects)
    y = math.nan if material.yield_stress is None else float(material.yield_stress)
    by_flag = fe_flag and (modelled or math.isfinite(y))
    if by_flag:
        p_lim, p_rule = math.nan, "first yield of the FE job (the `elastic` flag of asperities.nc)"
    elif math.isfinite(y):
        p_lim = FIRST_YIELD_P0 / 1.5 * y
        p_rule = (f"first yield of a Hertz contact: p0 = 1.5 F/A above {FIRST_YIELD_P0} Y "
                  f"(Y = {y / 1e6:.4g} MPa)")
    elif math.isfinite(h):
        p_lim, p_rule = h, f"mean contact pressure F/A above the hardness {h / 1e6:.4g} MPa"
    else:
        p_lim, p_rule = math.nan, "not checked: " + rule
    return Plasticity(e_prime, h, rule, p_lim, p_rule, by_flag, modelled,
                      modelled and "finite_strain" in set(effects))


def with_indicators(asperities: xr.Dataset, plasticity: Plasticity | None) -> xr.Dataset:
    """The asperity table (dims height, curvature, interference[, branch]) with the
    variables whose expectations `assess` needs: the force of points beyond the FE
    range (force x ``extrapolated``) and, where the mean contact pressure judges
    yield, ``yielded`` (1 where in contact with F/A above the yield pressure)."""
    out = asperities.copy()
    if "extrapolated" in out and "force" in out:
        out[EXTRAPOLATED_FORCE] = (out["force"] * out["extrapolated"].astype(float)).assign_attrs(
            attrs(out["force"].attrs.get("units", "N"), "force of asperities beyond their FE range"))
    if plasticity is not None and math.isfinite(plasticity.yield_pressure) and "contact_area" in out:
        area, force = out["contact_area"], out["force"]
        flag = (area > 0) & (force > plasticity.yield_pressure * area)
        out[YIELDED] = flag.astype(float).assign_attrs(attrs("1", plasticity.yield_rule))
    return out


def peak_statistics(density, bounds=None, cells: int = 200) -> tuple[float, float]:
    """(sigma_p, R): the standard deviation of the peak heights [m] and the radius of the
    mean peak curvature, 1 / E(kappa) [m], over the peak density on `bounds` (eq. 2.7:
    Gauss cells; a map's peaks themselves; an anisotropic density's own quadrature, its
    kappa the mean curvature (kappa_1 + kappa_2) / 2)."""
    from asperity.homogenize.integrate import expectation
    from asperity.peaks import SampledDensity
    from asperity.peaks.anisotropic import AnisotropicDensity

    def moments(z, k):
        z, k = np.broadcast_arrays(z, k)
        return np.stack([z, z * z, k], axis=-1)

    if isinstance(density, AnisotropicDensity):
        mean, square, kappa = (density.expectation(fn) for fn in (
            lambda z, k1, k2: z, lambda z, k1, k2: z * z, lambda z, k1, k2: 0.5 * (k1 + k2)))
    elif isinstance(density, SampledDensity):
        mean, square, kappa = (float(v) for v in expectation(moments, density, rule="peaks").expectation)
    else:
        mean, square, kappa = (float(v) for v in expectation(moments, density, bounds, cells=(cells, cells),
                                                             rule="gauss").expectation)
    return math.sqrt(max(square - mean * mean, 0.0)), 1.0 / kappa


def plasticity_index(plane_strain_modulus: float, hardness: float, sigma_p: float,
                     radius: float) -> float:
    """Greenwood-Williamson's psi = (E'/H) sqrt(sigma_p / R) (1966; report 7.3, errata)."""
    return plane_strain_modulus / hardness * math.sqrt(sigma_p / radius)


def _share(out: xr.Dataset, name: str) -> xr.DataArray | None:
    """n E^(name) over the contact count (0 without contact), or None."""
    source = f"{name}_per_unit_area"
    if source not in out:
        return None
    return xr.where(out["contact_count"] > 0, out[source] / out["contact_count"], 0.0)


def _complement(out: xr.Dataset, name: str) -> xr.DataArray:
    """1 - a share of contacting asperities (0 without contact; round-off clipped)."""
    return xr.where(out["contact_count"] > 0, (1.0 - out[name]).clip(0.0, 1.0), 0.0)


#: indicator -> (units, long_name), in the order `assess` checks them
INDICATORS = {
    "extrapolated_load_fraction": ("1", "share of the nominal pressure carried by asperities beyond "
                                   "their FE job's largest interference (continued in a straight line)"),
    "yielded_fraction": ("1", "share of contacting asperities beyond first yield"),
    "large_strain_fraction": ("1", "share of contacting asperities with a strain magnitude of 8 % or "
                              "more, outside small-strain theory (report 7.3)"),
    "contact_area_ratio": ("1", "real contact area per unit nominal area"),
    "interaction": ("1", "mean contact radius over half the mean spacing of contacts, "
                    "2 a_mean sqrt(contact_count): 1 where neighbouring contacts touch"),
}


def assess(interface: xr.Dataset, plasticity: Plasticity | None, peaks: tuple[float, float],
           limits: Limits, heights: tuple[float, float] | None = None) -> xr.Dataset:
    """`interface` with its validity (module docstring): the indicators, ``hardness``
    and ``plasticity_index`` (scalars), ``valid`` and ``validity`` on (branch,)
    separation; a log warning and the attribute ``validity_warning`` where a
    separation fails.  `interface` is the homogenization of a table made by
    `with_indicators`; `peaks` the (sigma_p, R) of `peak_statistics`; `heights`
    the (skewness, kurtosis) of the measured heights where the density assumes
    them Gaussian (None: not assumed, or not measured)."""
    out = interface.copy()
    p = out["nominal_pressure"]
    if f"{EXTRAPOLATED_FORCE}_per_unit_area" in out:
        share = out[f"{EXTRAPOLATED_FORCE}_per_unit_area"] / p.where(p > 0)
        out["extrapolated_load_fraction"] = xr.where(p > 0, share, 0.0).where(p.notnull())
    yielded = _share(out, YIELDED)
    if yielded is None and plasticity is not None and plasticity.by_flag and "elastic_fraction" in out:
        yielded = _complement(out, "elastic_fraction")
    if yielded is not None:
        out["yielded_fraction"] = yielded.where(out["contact_count"].notnull())
    if "small_strain_fraction" in out:
        out["large_strain_fraction"] = _complement(out, "small_strain_fraction")
    radius = _share(out, "contact_radius")
    if radius is not None:
        n = out["contact_count"]
        out["interaction"] = 2.0 * radius * np.sqrt(n.where(n > 0, 0.0))
    helpers = [name for v in (EXTRAPOLATED_FORCE, YIELDED) for name in (f"raw_{v}", f"{v}_per_unit_area")]
    out = out.drop_vars([name for name in helpers if name in out])
    for name, (units, long_name) in INDICATORS.items():
        if name in out and name != "contact_area_ratio":
            if name == "yielded_fraction" and plasticity is not None:
                long_name = f"{long_name}: {plasticity.yield_rule}"
            out[name] = out[name].assign_attrs(attrs(units, long_name))

    sigma_p, radius_p = peaks
    h = plasticity.hardness if plasticity is not None else math.nan
    psi = plasticity_index(plasticity.plane_strain_modulus, h, sigma_p, radius_p) \
        if plasticity is not None else math.nan
    out["hardness"] = ((), h, attrs("Pa", "hardness H: " + (plasticity.hardness_rule if plasticity
                                                             else "unknown: no material")))
    out["plasticity_index"] = ((), psi, {
        **attrs("1", "Greenwood-Williamson plasticity index psi = (E'/H) sqrt(sigma_p/R), "
                "E' = E/(1-nu^2); psi < 0.6 elastic, > 1 plastic at the lightest loads (GW 1966)"),
        "peak_height_deviation": sigma_p, "peak_radius": radius_p,
        "peak_radius_rule": "1 / E(kappa) over the peak density",
        "plane_strain_modulus": plasticity.plane_strain_modulus if plasticity else math.nan})

    checks = _checks(out, plasticity, psi, limits)
    valid, why = _judge(out, checks)
    valid, why = _assumed(out, valid, why, plasticity, heights)
    if "branch" in out.dims and "unloading" in out["branch"].values and "unloading_from" in out.attrs:
        valid, why = _inherit(out, valid, why)
    dims = out["nominal_pressure"].dims
    out["valid"] = (dims, valid, {
        **attrs("1", "every validity limit holds at this separation (asperity.homogenize.validity)"),
        **{f"limit_{k}": v for k, v in _limit_attrs(limits).items()},
        "not_checked": "; ".join(_unchecked(out, plasticity, limits)) or "none"})
    out["validity"] = (dims, why.astype(object), attrs(
        "1", "the first validity limit that fails at this separation (empty where valid)"))
    warning = warn_invalid(out, "interface")
    if warning:
        out.attrs["validity_warning"] = warning
    return out


def _assumed(out: xr.Dataset, valid: np.ndarray, why: np.ndarray, plasticity: Plasticity | None,
             heights: tuple[float, float] | None) -> tuple[np.ndarray, np.ndarray]:
    """Separations with contact fail where the density's Gaussian heights are not the
    surface's, and where an elastic asperity's yield cannot be judged (module text, 5-6)."""
    from asperity.surface.distribution import gaussianity

    dims = out["nominal_pressure"].dims
    contact = (out["nominal_pressure"].transpose(*dims).values > 0)
    reasons = []
    if heights is not None:
        gaussian, text = gaussianity(*heights)
        if not gaussian:
            reasons.append(f"gaussian_heights: {text}")
    if (plasticity is not None and not plasticity.modelled and not plasticity.by_flag
            and not math.isfinite(plasticity.yield_pressure)):
        reasons.append("unchecked_yield: no hardness or yield stress in the scene's material")
    for reason in reasons:
        new = contact & valid
        why[new] = reason
        valid = valid & ~contact
    return valid, why


def _limit_attrs(limits: Limits) -> dict[str, float]:
    out = {k: float(getattr(limits, k)) for k in INDICATORS}
    if limits.plasticity_index is not None:
        out["plasticity_index"] = float(limits.plasticity_index)
    return out


def _checks(out: xr.Dataset, plasticity: Plasticity | None, psi: float, limits: Limits):
    """(name, values (array or scalar), limit) in the order they are reported."""
    elastic = plasticity is not None and not plasticity.modelled
    checks = []
    if elastic and limits.plasticity_index is not None and math.isfinite(psi):
        checks.append(("plasticity_index", psi, limits.plasticity_index))
    recorded = _recorded_only(plasticity)
    for name in INDICATORS:
        if name in out and name not in recorded:
            checks.append((name, out[name], getattr(limits, name)))
    return checks


def _recorded_only(plasticity: Plasticity | None) -> set[str]:
    """Indicators the asperities model themselves: recorded, not limited. Yield where
    they are inelastic (or nothing says whether they are), large strain where their
    FE jobs are in finite strain."""
    out = set()
    if plasticity is None or plasticity.modelled:
        out.add("yielded_fraction")
    if plasticity is not None and plasticity.finite_strain:
        out.add("large_strain_fraction")
    return out


def _unchecked(out: xr.Dataset, plasticity: Plasticity | None, limits: Limits) -> list[str]:
    notes = []
    if "yielded_fraction" not in out:
        notes.append("yield: " + (plasticity.yield_rule if plasticity else "no material"))
    elif plasticity.modelled:
        notes.append("yield: the asperities are inelastic (yielded_fraction recorded, not limited)")
    if limits.plasticity_index is None:
        notes.append("plasticity_index: no limit set (validity.plasticity_index)")
    if plasticity is not None and plasticity.finite_strain and "large_strain_fraction" in out:
        notes.append("large_strain_fraction: finite-strain FE asperities (effect finite_strain; "
                     "recorded, not limited)")
    for name, why in (("extrapolated_load_fraction", "no extrapolated responses (analytic asperities)"),
                      ("large_strain_fraction", "no strain record (elastic or analytic asperities)"),
                      ("interaction", "no contact radius")):
        if name not in out:
            notes.append(f"{name}: {why}")
    return notes


def _judge(out: xr.Dataset, checks) -> tuple[np.ndarray, np.ndarray]:
    """valid and the first failing reason on the interface's (branch, separation)."""
    shape = out["nominal_pressure"].shape
    dims = out["nominal_pressure"].dims
    valid = np.ones(shape, bool)
    why = np.full(shape, "", dtype=object)
    for name, values, limit in checks:
        if isinstance(values, xr.DataArray):
            v = values.transpose(*dims).values
        else:
            v = np.full(shape, float(values))
        with np.errstate(invalid="ignore"):
            fails = v > limit  # NaN (not defined there) does not fail
        new = fails & valid
        for idx in zip(*np.nonzero(new)):
            why[idx] = f"{name} {v[idx]:.3g} > {limit:.3g}"
        valid &= ~fails
    return valid, why


def _inherit(out: xr.Dataset, valid: np.ndarray, why: np.ndarray):
    """The unloading branch fails where the loading state it turns from fails."""
    dims = list(out["nominal_pressure"].dims)
    b, s = dims.index("branch"), dims.index("separation")
    branches = list(out["branch"].values)
    i_load, i_unl = branches.index("loading"), branches.index("unloading")
    h = out["separation"].values
    turn = int(np.argmin(np.abs(h - float(out.attrs["unloading_from"]))))
    v = np.moveaxis(valid, (b, s), (0, 1)).copy()
    w = np.moveaxis(why, (b, s), (0, 1)).copy()
    if not v[i_load, turn]:
        unloads = np.isfinite(out["nominal_pressure"].sel(branch="unloading").values)
        reason = f"unloads from a state that fails: {w[i_load, turn]}"
        w[i_unl] = np.where(unloads & v[i_unl], reason, w[i_unl])
        v[i_unl] &= ~unloads
    return np.moveaxis(v, (0, 1), (b, s)), np.moveaxis(w, (0, 1), (b, s))


def valid_ranges(ds: xr.Dataset) -> list[str]:
    """One line per branch: the valid separations and the first failure (for
    `asperity show` and the log)."""
    if "valid" not in ds or "separation" not in ds.dims:
        return []
    lines = []
    branches = ds["branch"].values if "branch" in ds["valid"].dims else [None]
    for branch in branches:
        one = ds if branch is None else ds.sel(branch=branch)
        h = one["separation"].values
        defined = np.isfinite(one["nominal_pressure"].values)
        ok = one["valid"].values.astype(bool) & defined
        label = "" if branch is None else f" ({branch})"
        if ok[defined].all():
            lines.append(f"valid{label}: every separation, {h[defined].min():.4g} .. "
                         f"{h[defined].max():.4g} m" if defined.any() else f"valid{label}: no data")
            continue
        if ok.any():
            text = f"valid{label}: {ok.sum()} of {_count(defined.sum())}, " + ", ".join(
                f"{a:.4g} .. {b:.4g} m" for a, b in _runs(h, ok))
        else:
            text = f"valid{label}: none of {_count(defined.sum())}"
        reasons = {}
        for hk, why, good, d in zip(h, one["validity"].values, ok, defined):
            if d and not good:
                reasons.setdefault(_kind(why), []).append((hk, str(why)))
        for kind, items in reasons.items():
            verb = "not checked" if kind in UNCHECKED else "fails"
            text += (f"; {kind} {verb} at {_count(len(items))} ({items[0][0]:.4g} .. "
                     f"{items[-1][0]:.4g} m), e.g. {items[0][1]}")
        lines.append(text)
    return lines


def _kind(why) -> str:
    """The limit a `validity` reason names (its first word), or the unloading's inherited failure."""
    if str(why).startswith("unloads"):
        return "unloading from a failing state"
    return str(why).split(" ")[0].rstrip(":")


def _count(n) -> str:
    return f"{int(n)} separation{'' if n == 1 else 's'}"


def _runs(h: np.ndarray, ok: np.ndarray) -> list[tuple[float, float]]:
    """Contiguous runs of `ok` along the separations `h` as (first, last) separations."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ok.astype(int), [0]])))
    return [(float(h[a]), float(h[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


def warn_invalid(ds: xr.Dataset, what: str) -> str:
    """Log a warning naming the separations of `ds` (with ``valid``, ``validity``)
    outside the model's validity and why, and for each failing limit what it means
    and what the scene can change (`REMEDIES`); returns the text ('' if all valid)."""
    if bool(np.all(ds["valid"].values | ~np.isfinite(ds["nominal_pressure"].values))):
        return ""
    text = f"{what} outside the model's validity: " + " | ".join(
        line for line in valid_ranges(ds) if ": every separation" not in line)
    kinds = dict.fromkeys(_kind(why) for why in np.ravel(ds["validity"].values) if why)
    hints: dict[str, list[str]] = {}  # one hint, the limits it explains
    for kind in kinds:
        if kind in REMEDIES:
            hints.setdefault(REMEDIES[kind], []).append(kind)
    if hints:
        text += ". What it means: " + "; ".join(f"{', '.join(names)}: {hint}"
                                                for hint, names in hints.items())
    log.warning("%s", text)
    return text
