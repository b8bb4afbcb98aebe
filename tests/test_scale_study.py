"""The lateral-scale study (asperity.stages.studies.scale_study_dataset) on a measured map."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from asperity.scene.files import read_scene
from asperity.stages import studies
from tests.scene_defaults import filled_scene

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def study():
    scene = filled_scene(read_scene(REPO / "config" / "scenes" / "afm_reference.yaml"))
    cfg = {part: scene[part] for part in ("surface", "units", "material")}
    ds = studies.scale_study_dataset({"afm_reference": str(REPO / scene["surface"]["map"]["file"])},
                                     {"afm_reference": cfg}, {"scales": [0, 8], "separations": [1.0, 2.5, 4]})
    return ds.sel(scene="afm_reference"), cfg


def _map(cfg):
    from asperity.io.topography import read_measurement
    from asperity.stages.surface import prepared_roughness, reading

    surface = {k: v for k, v in cfg["surface"].items() if k != "scale"}
    data = read_measurement(REPO / cfg["surface"]["map"]["file"], **reading(surface, cfg["units"]))
    return prepared_roughness(data.heights, data.spacing, surface, cfg["units"]), *data.spacing


def test_summits_at_each_scale_are_those_the_surface_stage_finds(study):
    """At 8 grid steps the summits of `map_summits` at lambda_s = 8 max(dx, dy), those of
    positive curvature; at 0 the pixel's eight-neighbour peaks of the unfiltered map."""
    from asperity.surface.maps import map_peaks
    from asperity.surface.summits import map_summits

    ds, cfg = study
    z, dx, dy = _map(cfg)
    summits = map_summits(z, dx, dy, 8 * max(dx, dy))
    assert int(ds["summits"].sel(factor=8)) == int((summits["curvature"].values > 0).sum())
    assert float(ds["scale"].sel(factor=8)) == 8 * max(dx, dy)
    pixel = map_peaks(z, dx, dy)
    assert int(ds["summits"].sel(factor=0)) == int((pixel["curvature"].values > 0).sum())
    assert float(ds["summits"].sel(factor=0)) > 3 * float(ds["summits"].sel(factor=8))  # the pixel's many peaks


def test_persson_errors_against_the_boundary_elements_of_the_same_prepared_map(study):
    """Persson's errors at 8 grid steps recomputed from the low-passed map: its sigma sets
    the separations, the elastic boundary elements are the reference (1e-9)."""
    from asperity.references import persson
    from asperity.references.boundary_element import solve_map
    from asperity.stages.routes import contact_modulus_and_hardness
    from asperity.surface.summits import lowpass_map

    ds, cfg = study
    z0, dx, dy = _map(cfg)
    z = lowpass_map(z0, dx, dy, 8 * max(dx, dy))
    z = z - z.mean()
    h = np.linspace(1.0, 2.5, 4) * z.std()
    modulus = contact_modulus_and_hardness(cfg["material"], cfg["units"])[0]
    bem = solve_map(z, dx, dy, h, modulus)
    q, C = persson.isotropic_spectrum(z, dx, dy)
    p = persson.persson_interface(q, C, modulus, h)["nominal_pressure"].values
    expected = p / bem["nominal_pressure"].values - 1
    got = ds["pressure_error"].sel(factor=8, route="persson").values
    np.testing.assert_allclose(got, expected, rtol=1e-9)
    np.testing.assert_allclose(ds["bem_area_ratio"].sel(factor=8), bem["contact_area_ratio"], rtol=1e-12)
    for route in ds["route"].values:  # every route ran at both scales
        assert np.isfinite(ds["pressure_error"].sel(route=route)).all(), route
