"""The numbers of the README's subsection "In a scene: `smooth_aluminum_adhesion`":
the adhesive scene (report 7.3, 9.1) beside its elastic twin.

Reads a results tree made by the pipeline (default ``results/``), e.g. after

    snakemake --cores 2 --config 'scenes=[smooth_aluminum_adhesion]' studies=False

(which makes the twin, smooth_aluminum_elastic, too), and prints:

- per curvature sample: tip radius, Tabor parameter, pull-off against JKR's
  3/2 pi R W_c and against 2 pi R W_c, jump-in and jump-off interference, and from its
  FE job (``samples/<key>.nc``) the least and the largest von Mises stress while in
  contact against the yield stress, and the largest strain while in contact;
- the FE cost: jobs and CPU seconds (``asperities.nc``);
- the share of the peaks above 1 and 2 sigma whose curvature lies outside the scene's
  samples (Nayak's joint density of the surface's statistics, on a fine grid): the
  homogenization gives them the response of the nearest sample;
- the interface: the largest attraction before contact on approach, the pull-off
  pressure on retraction, the pressure at 1 sigma with and without adhesion;
- friction: mu at 1 sigma and at the lightest positive load, the twin's range;
- the share of contacting asperities still elastic (Fig. 7.10) on each branch and the
  twin's, and the separations where the interface is valid.

With a second tree (``--against DIR``, e.g. ``results/smooth_aluminum_adhesion@standard``
made by ``snakemake ... results/smooth_aluminum_adhesion@standard/interface.nc``), also
how far the two agree: pressure and contact area at 1 to 2 sigma, pull-off ratios.

Writes benchmarks/results/adhesion-scene.json.

    python benchmarks/adhesion_numbers.py [results] [--against results/smooth_aluminum_adhesion@standard]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from asperity import peaks
from asperity.io.netcdf import read_dataset
from asperity.population.density import height_scale, population_stat

SCENE, TWIN = "smooth_aluminum_adhesion", "smooth_aluminum_elastic"
OUT = Path(__file__).with_name("results") / "adhesion-scene.json"


def in_contact(sample: xr.Dataset) -> dict:
    """The least and largest von Mises stress [MPa] and the largest strain of a job's
    steps in contact."""
    touching = sample["contact_area"].values > 0
    vm = sample["max_von_mises"].values[touching]
    return dict(von_mises_in_contact_MPa=[float(vm.min() / 1e6), float(vm.max() / 1e6)],
                largest_strain_in_contact=float(sample["max_equivalent_strain"].values[touching].max()))


def scene_numbers(folder: Path) -> dict:
    asp = read_dataset(folder / "asperities.nc")
    plan = read_dataset(folder / "plan.nc")
    keys = {float(k): str(plan["key"].values[np.flatnonzero(plan["sample_curvature"].values == k)[0]])
            for k in asp["curvature"].values}
    samples = folder.parent / "samples"
    interface = read_dataset(folder / "interface.nc")
    surface = read_dataset(folder / "surface.nc")
    friction = read_dataset(folder / "friction.nc")
    pull = asp["pull_off_force"].values
    # pull_off_force_dmt is 2 pi R W_c
    tips = [dict(tip_radius_um=float(1e6 / k), tabor_parameter=float(mu),
                 pull_off_over_jkr=float(p / jkr), pull_off_over_2_pi_R_W=float(p / dmt),
                 jump_in_interference_nm=float(wi * 1e9), jump_off_interference_nm=float(wo * 1e9),
                 **in_contact(read_dataset(samples / f"{keys[float(k)]}.nc")))
            for k, mu, p, jkr, dmt, wi, wo in zip(
                asp["curvature"].values, asp["tabor_parameter"].values, pull,
                asp["pull_off_force_jkr"].values, asp["pull_off_force_dmt"].values,
                asp["jump_in_interference"].values, asp["jump_off_interference"].values)]
    s = height_scale(surface)
    p = friction["nominal_pressure"].values
    sep, mu = friction["separation"].values, friction["mu"].values
    lightest = int(np.nanargmax(np.where(p > 0, sep, np.nan)))
    return dict(
        fe_jobs=int(asp.attrs["fe_jobs"]), fe_cpu_time_s=float(asp.attrs["fe_cpu_time"]),
        tips=tips,
        peaks_outside_samples=outside_samples(surface, asp["curvature"].values),
        largest_attraction_approach_Pa=float(interface.attrs["largest_attraction_approach"]),
        pull_off_pressure_Pa=float(interface.attrs["pull_off_pressure"]),
        pressure_at_1_sigma_Pa=float(interface.sel(branch="approach")["nominal_pressure"]
                                     .interp(separation=s)),
        mu_at_1_sigma=float(np.interp(s, sep, mu)),
        mu_at_lightest_positive_load=float(mu[lightest]),
        lightest_positive_load_Pa=float(p[lightest]),
        elastic_fraction_range={b: [float(x.min()), float(x.max())] for b, x in (
            (b, interface["elastic_fraction"].sel(branch=b).where(
                interface["contact_count"].sel(branch=b) > 0, drop=True))
            for b in interface["branch"].values)},
        valid_separations_over_sigma={b: (interface["separation"].where(
            interface["valid"].sel(branch=b), drop=True).values[[0, -1]] / s).tolist()
            for b in interface["branch"].values},
        yield_stress_MPa=json.loads(str(plan["spec"].values[0]))["material"]["yield_stress"] / 1e6,
    )


def outside_samples(surface: xr.Dataset, curvatures: np.ndarray) -> dict:
    """Share of the peaks above 1 and 2 sigma flatter than the flattest sample and
    steeper than the steepest (the surface's given statistics, Nayak's density)."""
    stats = {v: population_stat(surface, v) for v in ("sigma", "sigma_slope", "sigma_curvature")}
    density = peaks.JointDensity(**stats)
    s = stats["sigma"]
    z = np.linspace(-6 * s, 8 * s, 1401)
    k = np.linspace(0.0, 15 * stats["sigma_curvature"], 25001)[1:]
    Z, K = np.meshgrid(z, k, indexing="ij")
    P = density.pdf(Z, K)
    out = {}
    for n in (1, 2):
        above = Z > n * s
        total = P[above].sum()
        out[f"flatter_above_{n}_sigma"] = float(P[above & (K < curvatures.min())].sum() / total)
        out[f"steeper_above_{n}_sigma"] = float(P[above & (K > curvatures.max())].sum() / total)
    return out


def twin_numbers(folder: Path) -> dict:
    interface = read_dataset(folder / "interface.nc")
    friction = read_dataset(folder / "friction.nc")
    s = height_scale(read_dataset(folder / "surface.nc"))
    return dict(pressure_at_1_sigma_Pa=float(interface["nominal_pressure"].interp(separation=s)),
                mu_range=[float(np.nanmin(friction["mu"])), float(np.nanmax(friction["mu"]))],
                elastic_fraction_range=[float(interface["elastic_fraction"].min()),
                                        float(interface["elastic_fraction"].max())])


def agreement(a: Path, b: Path) -> dict:
    """How far tree ``b`` is from tree ``a``: approach pressure and contact area at 1 to 2
    sigma (largest relative difference), pull-off ratios (largest relative difference)."""
    ia, ib = read_dataset(a / "interface.nc"), read_dataset(b / "interface.nc")
    aa, ab = read_dataset(a / "asperities.nc"), read_dataset(b / "asperities.nc")
    s = height_scale(read_dataset(a / "surface.nc"))
    h = np.linspace(1.0, 2.0, 11) * s
    out = {}
    for var in ("nominal_pressure", "contact_area_ratio"):
        x = ia.sel(branch="approach")[var].interp(separation=h).values
        y = ib.sel(branch="approach")[var].interp(separation=h).values
        out[f"{var}_1_to_2_sigma_largest_relative_difference"] = float(np.max(np.abs(y / x - 1)))
    pa, pb = aa["pull_off_force"], ab["pull_off_force"]
    out["pull_off_largest_relative_difference"] = float(np.max(np.abs(pb.values / pa.values - 1)))
    out["pull_off_relative_difference"] = dict(zip((f"{1e6 / k:.3g} um" for k in pa["curvature"].values),
                                                   (pb.values / pa.values - 1).tolist()))
    out["fe_cpu_time_s"] = [float(aa.attrs["fe_cpu_time"]), float(ab.attrs["fe_cpu_time"])]
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="?", type=Path, default=Path("results"))
    ap.add_argument("--against", type=Path, help="a second tree of the scene (e.g. at standard)")
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args(argv)
    record = dict(scene=scene_numbers(args.results / SCENE), twin=twin_numbers(args.results / TWIN))
    if args.against is not None:
        record["against"] = dict(folder=str(args.against),
                                 **agreement(args.results / SCENE, args.against))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(record, indent=1) + "\n")
    print(json.dumps(record, indent=1))
    print(f"written: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
