"""The five real instrument files of data/topographies/ (SOURCE.md): read with their units,
form removal, statistics; the same numbers as SurfaceTopography where both define them.

SurfaceTopography is another implementation of the readers and of least-squares form
removal: heights must agree to round-off (1e-12) once units are converted, and the rms
height after removing the plane (its detrend 'height') or the quadratic ('curvature')
to 1e-10.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from asperity import surface as S
from asperity.io.inputs import InputError
from asperity.io.topography import describe_file, read_measurement
from asperity.stages import surface as stage

DATA = Path(__file__).resolve().parents[1] / "data" / "topographies"

#: file, kind, unit given by the scene (only where the file has none), unit in the file,
#: shape (rows, columns), spacing in metres, share of undefined points
FILES = [
    ("hfm-1.hfm", "profile", None, "mm", (9600,), 0.5e-6, 0.0),
    ("xy-4.txt", "profile", "mm", None, (10001,), 0.995613e-3 / 10000, 0.0),
    ("frt-1.frt", "map", None, "m", (500, 500), 24e-6, 0.3058),
    ("di-3.di", "map", None, "nm", (256, 256), 10e-6 / 256, 0.0),
    ("mi-1.mi", "map", None, "um", (256, 256), 20e-6 / 256, 0.0),
]
SCALE = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}


@pytest.fixture(scope="module")
def surface_topography():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ImportWarning)
        import SurfaceTopography as ST
    return ST


@pytest.mark.parametrize("name, kind, unit, file_unit, shape, spacing, undefined", FILES,
                         ids=[f[0] for f in FILES])
def test_every_shared_file_is_read_with_its_units(surface_topography, name, kind, unit, file_unit,
                                                  shape, spacing, undefined):
    path = DATA / name
    info = describe_file(path)
    assert (info["kind"], info["unit"], info["points"]) == (kind, file_unit, shape)
    m = read_measurement(path, kind, unit=unit)
    assert m.heights.shape == shape
    assert m.dx == pytest.approx(spacing, rel=1e-9)
    if kind == "map":
        assert m.dy == pytest.approx(spacing, rel=1e-9)
    assert m.undefined_share == pytest.approx(undefined, abs=5e-5)
    assert np.isnan(m.heights[~m.defined]).all() and np.isfinite(m.heights[m.defined]).all()
    # the same numbers as SurfaceTopography's, in metres, maps transposed to z[y, x]
    reader = surface_topography.open_topography(str(path))
    topo = reader.topography(unit=unit) if unit else reader.topography()
    theirs = np.ma.getdata(topo.heights()) * SCALE[unit or file_unit]
    theirs = theirs.T if kind == "map" else theirs
    np.testing.assert_allclose(m.heights[m.defined], theirs[m.defined], rtol=1e-12, atol=0)
    np.testing.assert_array_equal(~m.defined, np.ma.getmaskarray(topo.heights()).T if kind == "map"
                                  else np.ma.getmaskarray(topo.heights()))
    assert any(f"length unit {unit or file_unit}" in note for note in m.notes)


@pytest.mark.parametrize("name, kind, unit, file_unit, shape, spacing, undefined", FILES,
                         ids=[f[0] for f in FILES])
def test_form_removal_of_every_shared_file_agrees_with_surface_topography(
        surface_topography, name, kind, unit, file_unit, shape, spacing, undefined):
    path = DATA / name
    m = read_measurement(path, kind, unit=unit)
    reader = surface_topography.open_topography(str(path))
    topo = reader.topography(unit=unit) if unit else reader.topography()
    for mode, form, degree in (("height", "tilt", None), ("curvature", "polynomial", 2)):
        detrended = topo.detrend(mode)
        theirs = (detrended.Rq() if kind == "profile" else detrended.Sq()) * SCALE[unit or file_unit]
        residual, _ = S.remove_form(m.heights, form, degree, m.defined)
        values = residual[m.defined]
        assert np.sqrt(np.mean((values - values.mean()) ** 2)) == pytest.approx(theirs, rel=1e-10), mode


#: rms height as read (mean removed) and after tilt removal, in metres, and what the
#: statistics must give: the tilt dwarfs the roughness on every file but xy-4
RMS = {"hfm-1.hfm": (9.0569e-7, 2.4534e-7), "xy-4.txt": (8.6418e-6, 7.7925e-6),
       "frt-1.frt": (4.9158e-6, 4.3960e-6), "di-3.di": (2.2643e-7, 3.5223e-8),
       "mi-1.mi": (3.3215e-8, 3.4340e-9)}
#: skewness and kurtosis after tilt removal (scipy's, checked in test_surface_spectra): none of
#: these real surfaces is Gaussian by the limits of asperity.surface.distribution
MOMENTS = {"hfm-1.hfm": (-2.2239, 8.5347), "xy-4.txt": (-3.8726, 18.837), "frt-1.frt": (-9.8491, 488.19),
           "di-3.di": (-0.3998, 5.6617), "mi-1.mi": (1.1946, 7.1585)}


@pytest.mark.parametrize("name, kind, unit, file_unit, shape, spacing, undefined", FILES,
                         ids=[f[0] for f in FILES])
def test_statistics_of_every_shared_file(name, kind, unit, file_unit, shape, spacing, undefined):
    """surface.nc of each file with tilt removal: rms before and after (SurfaceTopography's
    numbers, test above, 1e-4 as printed), the sampling sigma is the (n-1) deviation of the
    defined roughness, the undefined share, skewness and kurtosis (none is Gaussian), and
    for maps peaks that all lie on defined points."""
    m = read_measurement(DATA / name, kind, unit=unit)
    cfg = {kind: {"file": name}, "form": "tilt", "undefined": {"max_share": 0.5}}
    ds = stage.surface_from_data(m.heights, m.spacing, cfg, {"length": "um"}, defined=m.defined)
    before, after = RMS[name]
    assert float(ds["rms_height_raw"]) == pytest.approx(before, rel=1e-4)
    assert float(ds["rms_height"]) == pytest.approx(after, rel=1e-4)
    assert float(ds["undefined_share"]) == pytest.approx(undefined, abs=5e-5)
    residual, _ = S.remove_form(m.heights, "tilt", None, m.defined)
    sigma = np.std(residual[m.defined], ddof=1)
    got = ds["sigma"].sel(estimator="sampling") if kind == "profile" else ds["sigma"]
    assert float(got) == pytest.approx(sigma, rel=1e-12)
    assert (float(ds["skewness"]), float(ds["kurtosis"])) == pytest.approx(MOMENTS[name], rel=1e-4)
    assert ds.attrs["gaussian"].startswith("no: ")
    if kind == "map":
        assert ds.sizes["peak"] > 100
        assert m.defined[ds["row"].values, ds["column"].values].all()
        assert ds.attrs["axes"].startswith("z[i, j] = z(x = j dx, y = i dy)")
    else:
        for estimator in ("sampling", "counting", "spectral"):
            assert np.isfinite(float(ds["sigma_slope"].sel(estimator=estimator)))


def test_real_profile_with_a_filter():
    """hfm-1: the stylus profile's form beyond its tilt (a bend and the part's edge) goes with
    lambda_c = 250 um (ISO 4288 for Ra 0.02-0.1 um): the roughness rms drops from 0.245 um
    to 0.0141 um, and lambda_c / 2 = 250 points go at each end."""
    m = read_measurement(DATA / "hfm-1.hfm", "profile")
    cfg = {"profile": {"file": "hfm-1.hfm"}, "form": "tilt", "filter": {"lambda_c": 250.0}}
    ds = stage.surface_from_data(m.heights, m.spacing, cfg, {"length": "um"}, defined=m.defined)
    assert float(ds["rms_height"]) == pytest.approx(1.41365e-8, rel=1e-4)
    # what is left is spikes on a smooth band: dust or stylus jumps, no Gaussian surface
    assert (float(ds["skewness"]), float(ds["kurtosis"])) == pytest.approx((10.844, 218.62), rel=1e-4)
    assert ds.attrs["evaluation_region"] == "250:9350"
    assert int(ds["points"]) == 9100


def test_unitless_file_needs_the_scene_unit():
    with pytest.raises(InputError, match=r"xy-4.txt: the file states no length unit; give the unit of its "
                                         r"numbers in the scene as surface.profile.unit"):
        read_measurement(DATA / "xy-4.txt", "profile")


def test_the_optical_map_holds_points_its_instrument_did_not_mark():
    """frt-1.frt: its first row is 500 zeros, and 8 points stand above 200 um (up to 305 um)
    on a surface of median height 79 um: what its kurtosis of 488 after tilt removal shows."""
    m = read_measurement(DATA / "frt-1.frt", "map")
    z = np.where(m.defined, m.heights, np.nan)
    zeros = np.argwhere(z == 0.0)
    assert zeros.shape[0] == 500 and np.all(zeros[:, 0] == 0)
    assert np.count_nonzero(z > 200e-6) == 8
    assert np.nanmax(z) == pytest.approx(305.2e-6, rel=1e-4)
    assert np.nanmedian(z) == pytest.approx(79.16e-6, rel=1e-3)


def test_the_optical_maps_islands_are_its_unmarked_points(surface_topography):
    """frt-1.frt's points the instrument did not mark are islands (`surface.islands`): the
    500 zeros of the first row (rows 2 and 3 undefined) and 15 specks inside undefined
    areas, among them all 8 points above 200 um. Dropped (the scene default), the rms after
    tilt removal is SurfaceTopography's detrended Sq of the map with those points masked
    (1e-10), 0.710 um instead of 4.40 um, and the kurtosis falls from 488 to 22."""
    m = read_measurement(DATA / "frt-1.frt", "map")
    cut = S.islands(m.defined)
    assert np.count_nonzero(cut) == 515 and cut[0][m.defined[0]].all()
    assert np.all(cut[m.defined & (np.nan_to_num(m.heights) > 200e-6)])
    assert np.count_nonzero(cut[1:]) == 15
    kept = m.defined & ~cut
    cfg = {"map": {"file": "frt-1.frt"}, "form": "tilt",
           "undefined": {"max_share": 0.5, "islands": "drop"}}
    ds = stage.surface_from_data(m.heights, m.spacing, cfg, {"length": "um"}, defined=m.defined)
    assert int(ds["island_points"]) == 515
    topo = surface_topography.Topography(np.ma.masked_array(m.heights.T, ~kept.T),
                                         (500 * m.dx, 500 * m.dy), periodic=False)
    assert float(ds["rms_height"]) == pytest.approx(topo.detrend("height").Sq(), rel=1e-10)
    assert float(ds["rms_height"]) == pytest.approx(7.0999e-7, rel=1e-4)
    assert (float(ds["skewness"]), float(ds["kurtosis"])) == pytest.approx((-0.22386, 22.454), rel=1e-4)


def test_a_unit_or_spacing_in_the_scene_overrides_the_file_and_says_so():
    """di-3.di states nm: a scene that says um takes the same numbers in um (heights and
    positions 1000 times larger, to round-off 1e-15), a spacing in the scene replaces the
    file's, and the notes the surface log prints say both."""
    as_read = read_measurement(DATA / "di-3.di", "map")
    m = read_measurement(DATA / "di-3.di", "map", unit="um")
    np.testing.assert_allclose(m.heights, 1e3 * as_read.heights, rtol=1e-15, atol=0)
    assert (m.dx, m.dy) == (pytest.approx(1e3 * as_read.dx, rel=1e-15), pytest.approx(1e3 * as_read.dy, rel=1e-15))
    assert "length unit um from the scene (surface.map.unit) overrides the file's nm" in m.notes
    assert "length unit nm from the file" in as_read.notes
    spaced = read_measurement(DATA / "di-3.di", "map", spacing=5e-8)
    assert (spaced.dx, spaced.dy) == (5e-8, 5e-8)
    np.testing.assert_array_equal(spaced.heights, as_read.heights)
    assert "spacing 5e-08 m from the scene (surface.map.spacing) overrides the file's 3.90625e-08 m" in spaced.notes


@pytest.mark.parametrize("name, kind", [("mi-1.mi", "map"), ("hfm-1.hfm", "profile")])
def test_a_surface_that_is_not_gaussian_says_so_in_the_log_the_file_and_the_figure(name, kind, caplog):
    """Skewness and kurtosis beyond the limits of asperity.surface.distribution (|Sk| <= 0.3,
    Ku 2.5 ... 4, the README says why): a warning in the job's log, the attribute `gaussian`
    and a red note over the figure, each with the numbers and the limits."""
    import logging

    from asperity.stages import figures

    m = read_measurement(DATA / name, kind)
    with caplog.at_level(logging.WARNING, logger="asperity"):
        ds = stage.surface_from_data(m.heights, m.spacing, {kind: {"file": name}, "form": "tilt"},
                                     {"length": "um"}, defined=m.defined)
    sk, ku = MOMENTS[name]
    verdict = f"skewness {sk:.2f} beyond +-0.3; kurtosis {ku:.2f} outside 2.5 ... 4"
    assert ds.attrs["gaussian"] == f"no: {verdict}"
    assert ds.attrs["gaussian_limits"] == "|skewness| <= 0.3, kurtosis 2.5 ... 4"
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert any(w.startswith(f"the heights are not Gaussian ({verdict})") for w in warnings), warnings
    fig = figures.surface_figure(kind, ds, {"length": "um"})
    note = fig._suptitle
    assert note is not None and note.get_text().startswith(f"heights not Gaussian ({verdict}; limits "
                                                           f"|skewness| <= 0.3, kurtosis 2.5 ... 4)")


def test_a_gaussian_map_gets_no_warning_and_no_note(caplog):
    """A synthetic Gaussian map (skewness 0.008, kurtosis 2.72 after tilt removal): within the
    limits, so no warning, `gaussian: yes`, and no note on the figure."""
    import logging

    from asperity.stages import figures

    z = S.gaussian_map(128, 1.0, 1.0, 6.0, 3) * 1e-6
    with caplog.at_level(logging.WARNING, logger="asperity"):
        ds = stage.surface_from_data(z, (1e-6, 1e-6), {"map": {"file": "g.npy"}, "form": "tilt"},
                                     {"length": "um"}, defined=np.ones(z.shape, bool))
    assert abs(float(ds["skewness"])) < 0.3 and 2.5 < float(ds["kurtosis"]) < 4
    assert ds.attrs["gaussian"] == "yes"
    assert not [r for r in caplog.records if "Gaussian" in r.getMessage()]
    assert figures.surface_figure("map", ds, {"length": "um"})._suptitle is None
