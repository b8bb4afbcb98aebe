"""The lateral scale of the asperities against what it changes: summit density and
curvature, the boundary elements' resolution, and the routes' error against them.

    python benchmarks/scale_study.py [--maps synthetic di-3 mi-1] [--scales 0 4 5 8 12 16]

For each map (tilt removed) and each scale lambda_s = s max(dx, dy) (s = 0: the pixel's
eight-neighbour peaks, unfiltered), the way the pipeline prepares it
(`asperity.stages.surface`): the map low-passed at lambda_s, its summits found and fitted
there (`asperity.surface.summits`); then, on separations 0.5 ... 3 sigma of the prepared
map, the elastic boundary elements, the interacting route with each asperity law and
Persson's theory (`asperity.stages.routes`), with each route's pressure error at equal
separation and area error at equal pressure.  Aluminum (E = 70 GPa, nu = 0.33).

Writes benchmarks/results/scale-study.json (``--out``), which docs/generate.py draws and
tabulates.
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # run as a script: `benchmarks` importable
from benchmarks.routes import _commit  # noqa: E402
from benchmarks.scenes import OUT  # noqa: E402
from benchmarks.workflow_copy import REPO  # noqa: E402

MAPS = {"synthetic": None, "di-3": "data/topographies/di-3.di", "mi-1": "data/topographies/mi-1.mi"}
SEPARATIONS = np.linspace(0.5, 3.0, 11)
MODULUS = 70e9 / (1 - 0.33**2)


def read(name: str):
    from asperity.io.topography import read_measurement
    from asperity.surface.form import remove_form
    from asperity.surface.synthetic import gaussian_map

    if MAPS[name] is None:  # the map of deterministic_reference
        return gaussian_map(512, 1.25e-6, 1e-6, 20e-6, 11), 1.25e-6, 1.25e-6
    data = read_measurement(REPO / MAPS[name], "map")
    z, _ = remove_form(data.heights, "tilt", defined=data.defined)
    return z, *data.spacing


def _errors(p, a, p_ref, a_ref):
    from asperity.stages.reference import _interp_log

    with np.errstate(divide="ignore", invalid="ignore"):
        return (np.where(p_ref > 0, p / p_ref - 1, np.nan),
                np.where(a_ref > 0, _interp_log(p_ref, p, a) / a_ref - 1, np.nan))


def one(z0, dx: float, dy: float, factor: float) -> dict:
    from asperity.references import persson
    from asperity.references.boundary_element import solve_map
    from asperity.homogenize.interacting import interacting_interface
    from asperity.stages.routes import INTERACTING_ACCEPT, INTERACTING_TOLERANCE, LAWS, asperity_law
    from asperity.surface.maps import map_peaks
    from asperity.surface.summits import lowpass_map, map_summits

    scale = factor * max(dx, dy)
    if factor > 0:
        z = lowpass_map(z0, dx, dy, scale)
        peaks = map_summits(z0, dx, dy, scale).rename(summit="peak")
    else:
        z = np.array(z0, dtype=float)
        peaks = map_peaks(z, dx, dy)
    peaks = peaks.isel(peak=np.flatnonzero(peaks["curvature"].values > 0))  # as the route does
    z = z - np.nanmean(z)
    sigma = float(np.nanstd(z))
    h = SEPARATIONS * sigma
    ny, nx = z.shape
    t0 = time.process_time()
    bem = solve_map(z, dx, dy, h, MODULUS)
    out = {"factor": factor, "scale_m": scale, "sigma_m": sigma, "summits": int(peaks.sizes["peak"]),
           "summit_density_per_m2": peaks.sizes["peak"] / (nx * dx * ny * dy),
           "mean_curvature_per_m": float(peaks["curvature"].mean()),
           "bem_area_ratio": bem["contact_area_ratio"].values.tolist(),
           "cells_per_patch": np.nan_to_num(bem["cells_per_patch"].values, nan=0.0).tolist(),
           "bem_cpu_s": time.process_time() - t0, "routes": {}}
    p_ref, a_ref = bem["nominal_pressure"].values, bem["contact_area_ratio"].values
    for law in (law for law in LAWS if law != "fe"):  # fe needs a scene's finite element table
        try:
            ds = interacting_interface(peaks["x"].values, peaks["y"].values, peaks["height"].values,
                                       peaks["curvature"].values, h, MODULUS, (nx * dx, ny * dy),
                                       law=asperity_law(law, z, dx, dy, peaks, MODULUS),
                                       tolerance=INTERACTING_TOLERANCE, accept=INTERACTING_ACCEPT)
        except (RuntimeError, ValueError) as err:
            out["routes"][f"interacting_{law}"] = {"error": str(err)}
            continue
        pe, ae = _errors(ds["nominal_pressure"].values, ds["contact_area_ratio"].values, p_ref, a_ref)
        out["routes"][f"interacting_{law}"] = {"pressure_error": pe.tolist(), "area_error": ae.tolist()}
    q, C = persson.isotropic_spectrum(z, dx, dy)
    ds = persson.persson_interface(q, C, MODULUS, h)
    pe, ae = _errors(ds["nominal_pressure"].values, ds["contact_area_ratio"].values, p_ref, a_ref)
    out["routes"]["persson"] = {"pressure_error": pe.tolist(), "area_error": ae.tolist()}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--maps", nargs="+", default=list(MAPS), choices=list(MAPS))
    ap.add_argument("--scales", nargs="+", type=float, default=[0, 4, 5, 8, 12, 16],
                    help="lambda_s in grid steps (0: the pixel)")
    ap.add_argument("--out", type=Path, default=OUT / "scale-study.json", help="JSON file")
    args = ap.parse_args(argv)
    result = {"date": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "commit": _commit(),
              "machine": {"platform": platform.platform(), "python": platform.python_version()},
              "separation_sigma": SEPARATIONS.tolist(), "maps": {}}
    for name in args.maps:
        z, dx, dy = read(name)
        result["maps"][name] = [one(z, dx, dy, s) for s in args.scales]
        for row in result["maps"][name]:
            shape = row["routes"].get("interacting_shape", {})
            worst = (np.nanmax(np.abs(shape["pressure_error"])) if "pressure_error" in shape else np.nan)
            print(f"{name} {row['factor']:g} steps: {row['summits']} summits, largest |p error| of "
                  f"interacting_shape {100 * worst:.0f} %", flush=True)
    path = args.out.resolve()
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=1) + "\n")
    print(f"written {path.relative_to(REPO) if path.is_relative_to(REPO) else path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
