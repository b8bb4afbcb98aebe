"""What the interface, single-asperity and map figures show, asserted on the figures'
artists (not pixels), from small synthetic files shaped like the pipeline's:

- interface.nc: a Greenwood-Williamson population of Hertz asperities homogenized
  (asperity.homogenize) with its validity, written and read back with the scene's
  config (material in MPa) as the pipeline writes it;
- asperities.nc: elastic "FE" asperities (Hertz times 1 + 0.05 w / w_max, so that
  the two curves differ) with an FE scene's config;
- surface.nc of a map: a synthetic Gaussian map through the surface stage.

Every figure is drawn and no text may reach beyond the figure (1 pixel of slack).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.text import Text

from asperity import homogenize
from asperity import surface as S
from asperity.homogenize import validity
from asperity.io.netcdf import read_dataset, write_dataset
from asperity.peaks import FixedCurvatureDensity
from asperity.plots.surface import MAX_PEAK_MARKERS
from asperity.population.plan import interference_grid
from asperity.references.hertz import hertz_asperities, hertz_response
from asperity.scene import Material
from asperity.stages import figures
from asperity.stages import surface as surface_stage

SIGMA_P = 1e-7  # m
CURVATURE = 1e3  # 1/m
E_MPA, NU, YIELD_MPA = 7.0e4, 0.33, 280.0  # aluminium-like
UNITS = {"length": "um", "pressure": "MPa"}
MATERIAL = {"model": "elastic", "youngs_modulus": E_MPA, "poisson": NU, "yield_stress": YIELD_MPA}
BOUNDS = (-8 * SIGMA_P, 8 * SIGMA_P, CURVATURE, CURVATURE)
LIMITS = dict(extrapolated_load_fraction=0.02, yielded_fraction=0.5, large_strain_fraction=0.1,
              contact_area_ratio=0.1, interaction=0.3, plasticity_index=None)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def interface(tmp_path_factory):
    """interface.nc of a GW population of Hertz asperities, yielding at small separations."""
    material = Material("elastic", youngs_modulus=E_MPA * 1e6, poisson=NU, yield_stress=YIELD_MPA * 1e6)
    plasticity = validity.plasticity_of(material, [])
    density = FixedCurvatureDensity(SIGMA_P, CURVATURE)
    table = validity.with_indicators(
        hertz_asperities([0.0], [CURVATURE], interference_grid(16 * SIGMA_P, 2001), E_MPA * 1e6, NU),
        plasticity)
    out = homogenize.interface_response(table, density, np.linspace(-1.0, 3.0, 17) * SIGMA_P,
                                        bounds=BOUNDS, cells=(400, 1), rule="gauss", peak_density=1e9)
    out = validity.assess(out, plasticity, validity.peak_statistics(density, BOUNDS),
                          validity.Limits(**LIMITS))
    path = tmp_path_factory.mktemp("interface") / "interface.nc"
    write_dataset(out, path, scene="s", title="homogenized interface",
                  config={"units": UNITS, "material": MATERIAL, "effects": []})
    return read_dataset(path)


@pytest.fixture(scope="module")
def asperities(tmp_path_factory):
    """asperities.nc of elastic FE asperities at three curvatures (Hertz, 5 % stiffer at w_max)."""
    w = interference_grid(2e-6, 60)
    ds = hertz_asperities([0.0], [5e3, 1e4, 2e4], w, E_MPA * 1e6, NU)
    bias = 1.0 + 0.05 * w / w[-1]
    for name in ("force", "contact_area"):
        ds[name] = ds[name] * bias
    ds["extrapolated"] = (("height", "curvature", "interference"), np.zeros(ds["force"].shape, bool),
                          {"units": "1", "long_name": "extrapolated"})
    ds.attrs.update(max_kink_force=0.01, max_kink_contact_area=0.02)
    path = tmp_path_factory.mktemp("asperities") / "asperities.nc"
    write_dataset(ds, path, scene="s", title="asperity responses",
                  config={"units": UNITS, "material": MATERIAL, "effects": [],
                          "asperity": {"model": "fe", "geometry": "paraboloid"}})
    return read_dataset(path)


@pytest.fixture(scope="module")
def surface_map():
    """surface.nc of a 160 x 160 Gaussian map (1 um spacing, correlation length 3 um) with a
    few tall spikes."""
    z = S.gaussian_map(160, 1.0, 1.0, 3.0, 3) * 1e-6
    z[5, 7], z[90, 100], z[60, 20] = 40e-6, 55e-6, -50e-6  # spikes that would set a min-max scale
    return surface_stage.surface_from_data(z, (1e-6, 1e-6), {"map": {"file": "g.npy"}, "form": "tilt"},
                                           UNITS, defined=np.ones(z.shape, bool))


def outside_texts(fig) -> list[str]:
    """Visible, non-empty texts whose drawn extent leaves the figure (1 px slack), and
    axes whose drawn tick labels do; after two draws (the constrained layout runs at
    each and may move once the tick labels it measured change)."""
    fig.canvas.draw()
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    bad = []

    def out(ext):
        return (ext.x0 < box.x0 - 1 or ext.y0 < box.y0 - 1 or ext.x1 > box.x1 + 1
                or ext.y1 > box.y1 + 1)

    ticks = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            ticks.update(id(t) for t in axis.get_ticklabels(which="both"))
            drawn = axis.get_tightbbox(renderer) if ax.get_visible() and ax.axison else None
            if drawn is not None and out(drawn):
                bad.append(f"ticks or label of {axis.axis_name} axis of {ax.get_title()!r}")
    for t in fig.findobj(Text):
        if id(t) in ticks or not t.get_visible() or not t.get_text().strip():
            continue
        if out(t.get_window_extent(renderer)):
            bad.append(t.get_text())
    return bad


def test_interface_figure_has_the_stiffness_and_names_the_material(interface):
    fig = figures.interface_figure(interface, UNITS)
    axes = [ax for ax in fig.axes if "stiffness" in ax.get_ylabel()]
    assert len(axes) == 1
    ax = axes[0]
    assert ax.get_ylabel() == "normal stiffness -dp/dh [MPa/um]"
    line = ax.get_lines()[0]
    # MPa/um = 1e6 Pa / 1e-6 m = 1e12 Pa/m; round-off only
    np.testing.assert_allclose(line.get_xdata(), interface["separation"].values / 1e-6, rtol=1e-12)
    np.testing.assert_allclose(line.get_ydata(), interface["normal_stiffness"].values / 1e12,
                               rtol=1e-12, atol=0)
    assert float(interface["normal_stiffness"].max()) > 0  # the panel is not empty
    title = fig._suptitle.get_text()
    assert "E = 70000 MPa" in title and "ν = 0.33" in title and "yield stress 280 MPa" in title
    # the hardness validity used: 2.8 Y (Tabor), in the file's `hardness`
    assert f"hardness H = {2.8 * YIELD_MPA:.4g} MPa" in title
    # the invalid separations (yielded at small separations) are shaded on the stiffness panel too
    valid = interface["valid"].values
    assert valid.any() and not valid.all()
    assert len(ax.patches) == len(fig.axes[0].patches) >= 1
    assert outside_texts(fig) == []


def test_asperities_figure_draws_hertz_beside_each_fe_curve(asperities):
    fig = figures.asperities_figure(asperities, UNITS)
    force_ax, area_ax = fig.axes[:2]
    for ax, name in ((force_ax, "force"), (area_ax, "contact_area")):
        hertz = [line for line in ax.get_lines() if line.get_gid() == "hertz"]
        fe = [line for line in ax.get_lines() if line.get_gid() != "hertz"]
        assert len(hertz) == len(fe) == 3
        for h_line, fe_line, kappa in zip(hertz, fe, asperities["curvature"].values):
            assert h_line.get_linestyle() == "--" and h_line.get_color() == "k"
            w = np.asarray(h_line.get_xdata()) * 1e-6
            np.testing.assert_array_equal(h_line.get_xdata(), fe_line.get_xdata())
            # E from the config in MPa, to SI: the closed form to round-off
            ref = hertz_response(w, kappa, E_MPA * 1e6, NU)[name] / (1e-12 if name == "contact_area" else 1.0)
            np.testing.assert_allclose(h_line.get_ydata(), ref, rtol=1e-12)
            # and the FE curve is the one 5 % off at its end, not the Hertz curve again
            assert fe_line.get_ydata()[-1] / h_line.get_ydata()[-1] == pytest.approx(1.05, rel=1e-9)
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert sum(label.startswith("Hertz") for label in labels) == 1
    # the third panel: FE over Hertz, here 1 + 0.05 w / w_max by construction (round-off)
    ratio_ax = fig.axes[2]
    assert ratio_ax.get_ylabel() == "FE / Hertz [1]"
    ratios = [line for line in ratio_ax.get_lines() if len(line.get_xdata()) > 2]
    assert len(ratios) == 2 * 3  # force and area at each curvature
    w = asperities["interference"].values
    for line in ratios:
        np.testing.assert_allclose(line.get_ydata(), (1 + 0.05 * w / w[-1])[w > 0], rtol=1e-12)
    assert "E = 70000 MPa" in fig._suptitle.get_text()
    assert outside_texts(fig) == []


def test_no_hertz_curve_for_hertz_or_inelastic_asperities(asperities):
    import yaml

    for change in ({"asperity": {"model": "hertz"}}, {"effects": ["plasticity"]}):
        ds = asperities.copy()
        cfg = {**yaml.safe_load(ds.attrs["config"]), **change}
        ds.attrs["config"] = yaml.safe_dump(cfg)
        fig = figures.asperities_figure(ds, UNITS)
        assert not [line for line in fig.axes[0].get_lines() if line.get_gid() == "hertz"]


def test_map_figure_robust_colours_and_thinned_peaks(surface_map):
    fig = figures.surface_figure("map", surface_map, UNITS)
    rough = [ax for ax in fig.axes if ax.get_title().startswith("roughness")][0]
    image = rough.get_images()[0]
    r = surface_map["roughness_height"].values.ravel() / 1e-6
    p1, p99 = np.percentile(r, [1, 99])
    half = max(abs(p1 - r.mean()), abs(p99 - r.mean()))
    assert image.get_clim() == pytest.approx((r.mean() - half, r.mean() + half), rel=1e-12, abs=1e-12)
    assert half < 0.2 * (r.max() - r.min())  # the spikes do not set the scale
    peaks = surface_map.sizes["peak"]
    assert peaks > MAX_PEAK_MARKERS  # the map has more peaks than are marked
    (marks,) = rough.get_lines()
    assert len(marks.get_xdata()) == MAX_PEAK_MARKERS and marks.get_markerfacecolor() == "none"
    # the highest ones
    lowest_shown = np.sort(surface_map["height"].values)[-MAX_PEAK_MARKERS]
    shown = np.isin(surface_map["x"].values / 1e-6 + 1j * (surface_map["y"].values / 1e-6),
                    np.asarray(marks.get_xdata()) + 1j * np.asarray(marks.get_ydata()))
    assert shown.sum() == MAX_PEAK_MARKERS
    assert surface_map["height"].values[shown].min() == lowest_shown
    # the sampled peak density over the 0.5-99.5th percentiles keeps its normalization by
    # all peaks: its integral is the share of peaks drawn (round-off)
    dens = [ax for ax in fig.axes if ax.get_xlabel().startswith("peak height")][0]
    mesh = dens.collections[0]
    z_p, kappa = surface_map["height"].values / 1e-6, surface_map["curvature"].values * 1e-6
    (z0, z1), (k0, k1) = np.percentile(z_p, [0.5, 99.5]), np.percentile(kappa, [0.5, 99.5])
    share = np.mean((z_p >= z0) & (z_p <= z1) & (kappa >= k0) & (kappa <= k1))
    cell = (z1 - z0) / 20 * (k1 - k0) / 20
    assert float(np.sum(mesh.get_array())) * cell == pytest.approx(share, rel=1e-12)
    assert dens.get_xlim() == pytest.approx((z0, z1), rel=1e-12)
    bars = [ax for ax in fig.axes if ax.get_ylabel() == "roughness height [um]"]
    assert len(bars) == 1  # the colour bar, labelled with its unit
    assert outside_texts(fig) == []


def test_profile_surface_figure_fits(surface_map):
    """The profile figure too (its roughness and estimator panels): nothing outside."""
    rng = np.random.default_rng(3)
    z = np.cumsum(rng.standard_normal(4000)) * 1e-8 + np.linspace(0, 5e-6, 4000)
    ds = surface_stage.surface_from_data(z, 1e-6, {"profile": {"file": "p.npy"}, "form": "tilt"},
                                         UNITS, defined=np.ones(z.shape, bool))
    fig = figures.surface_figure("profile", ds, UNITS)
    assert outside_texts(fig) == []


def test_outside_texts_sees_a_clipped_title():
    """The check itself: a title far wider than its figure, not fitted, is reported."""
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.set_title("a title that is much too long for a figure three inches wide " * 2)
    assert outside_texts(fig) != []


def test_friction_and_laws_figures_fit():
    """The friction and laws figures of a Greenwood-Williamson interface (report 7.1's
    surface), with measured and report values in the legend: nothing outside."""
    from asperity import friction, laws
    from asperity.plots.friction import friction_figure, laws_figure
    from asperity.references.greenwood_williamson import gw_interface
    from asperity.scene import Friction, Laws, Units
    from tests.scene_defaults import filled

    units = Units.from_section(UNITS)
    gw = gw_interface(np.linspace(0.0, 3.0, 31) * 7.07106e-7, 0.1414e-3, 7.07106e-7, 300e6,
                      321.7335 * 9.80665e6, 0.3)
    surface = surface_stage.surface_from_statistics(filled("surface", {"statistics": {
        "sigma": 4.91, "sigma_slope": 0.16, "sigma_curvature": 0.0227, "peak_density": 0.000508}}), UNITS)
    section = {"junction_shear_strength": 150.0, "interlocking": "rms_slope",
               "measured": [{"label": "a measurement with a long label", "value": 0.2,
                             "nominal_pressure": 0.1}],
               "report": {"shear": 0.093, "interlocking": 0.16, "total": 0.253, "nominal_pressure": 2.19,
                          "source": "9.1, Fig. 9.3"}}
    ds = friction.friction_dataset(gw, surface, Friction.from_section(filled("friction", section), units),
                                   None)
    assert outside_texts(friction_figure(ds, pressure_unit="MPa", length_unit="um")) == []
    p = np.sort(gw["nominal_pressure"].values) / 1e6
    law_section = {"residual": "log", "pressure_range": [float(p[5]), float(p[25])],
                   "report": {"units": {"length": "um", "pressure": "N/cm^2"}, "source": "10, Fig. 10.1",
                              "oden_martins": {"c": 15.2, "g": 0.0, "m": 2.25}}}
    fitted = laws.laws_dataset(gw, Laws.from_section(filled("laws", law_section), units))
    assert outside_texts(laws_figure(fitted, "MPa", "um")) == []


def test_fit_shrinks_a_title_a_little_too_wide_and_wraps_a_long_one():
    """`fit`: a title up to 1/0.85 times its axes' width keeps its words and gets a smaller
    font; a longer one is wrapped at word boundaries; both then lie inside their axes'
    width (1 px)."""
    from asperity.plots.layout import fit, subplots

    fig, (a, b) = subplots(1, 2, figsize=(6, 2.5))
    a.set_title("x" * 10)
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    width = a.get_window_extent(renderer).width
    per_char = a.title.get_window_extent(renderer).width / 10
    short = "x" * int(1.1 * width / per_char)  # about 10 % too wide
    long = " ".join(["word"] * int(3 * width / per_char / 5))
    a.set_title(short)
    b.set_title(long)
    size = a.title.get_fontsize()
    fit(fig)
    fig.canvas.draw()
    assert a.title.get_text() == short and 0.85 * size <= a.title.get_fontsize() < size
    assert "\n" in b.title.get_text() and b.title.get_text().replace("\n", " ") == long
    for ax in (a, b):
        assert ax.title.get_window_extent(renderer).width <= ax.get_window_extent(renderer).width + 1
