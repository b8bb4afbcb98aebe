"""The summits of a Gaussian anisotropic surface (report 2.4.2) and the expectation over
them (2.5.2): the density against Nayak's isotropic one, a Monte Carlo of the field's
derivatives and the summits of a synthetic map; the route against a direct quadrature."""

import math

import numpy as np
import pytest

from asperity.homogenize.anisotropic import anisotropic_interface, elliptic_law, mean_curvature_law
from asperity.peaks import JointDensity
from asperity.peaks.anisotropic import AnisotropicDensity, curvature_tensor, principal_curvatures
from asperity.references.hertz import elliptic_hertz, hertz_response

M2, M4 = 0.3, 0.5  # profile moments of an isotropic field with sigma = 1 (alpha = m0 m4 / m2^2 = 5.6)
ISOTROPIC = dict(m00=1.0, m20=M2, m11=0.0, m02=M2, m40=M4, m31=0.0, m22=M4 / 3, m13=0.0, m04=M4)
# a strongly anisotropic field, its lay at about 10 degrees from x
ANISOTROPIC = dict(m00=1.0, m20=0.05, m11=0.01, m02=0.4, m40=0.01, m31=0.002, m22=0.02, m13=0.01, m04=0.3)


def test_principal_curvatures_invert_the_tensor():
    rng = np.random.default_rng(0)
    k1, k2 = np.sort(rng.uniform(0.1, 2.0, (2, 50)), axis=0)[::-1]
    alpha = rng.uniform(0, np.pi, 50)
    back = principal_curvatures(*curvature_tensor(k1, k2, alpha))
    np.testing.assert_allclose(back[0], k1, rtol=1e-13)
    np.testing.assert_allclose(back[1], k2, rtol=1e-12)
    np.testing.assert_allclose(np.cos(2 * back[2]), np.cos(2 * alpha), atol=1e-12)


def test_isotropic_moments_give_nayak():
    """Isotropic moments: the summit density is Nayak's m4 / (6 pi sqrt(3) m2), and the
    marginal over height and mean curvature (kappa_1 + kappa_2)/2 is the density of 2.4.1
    (integrated over the curvature difference by 64-point Gauss); both to 1e-8 (the
    truncation of the support)."""
    d = AnisotropicDensity(ISOTROPIC)
    assert d.summit_density == pytest.approx(M4 / (6 * math.pi * math.sqrt(3) * M2), rel=1e-8)
    nayak = JointDensity(1.0, math.sqrt(M2), math.sqrt(M4))
    x, w = np.polynomial.legendre.leggauss(64)
    for z, km in [(0.5, 0.2), (1.5, 0.4), (-0.5, 0.1), (2.5, 0.6)]:
        diff, wd = 0.5 * km * (x + 1), 0.5 * km * w  # kappa_1,2 = km +- diff: dk1 dk2 = 2 dkm ddiff
        marginal = 2 * (d.pdf_shape(z, km + diff, km - diff) * wd).sum()
        assert marginal == pytest.approx(nayak.pdf(z, km), rel=1e-8)


@pytest.mark.slow
def test_the_quadrature_has_converged():
    """The default quadrature against one half again as fine in every direction (cells
    and orientations), on a field whose curvature variances differ thirtyfold: the summit
    density to 1e-6, the elliptic route's pressure and area to 1e-5 at separations of
    0.5 and 2 sigma and to 1e-4 at 3.5 sigma, where a thousandth of the summits touch
    (measured: 2e-7; 5e-7 and 3e-6; 4e-5)."""
    coarse = AnisotropicDensity(ANISOTROPIC)
    fine = AnisotropicDensity(ANISOTROPIC, cells=tuple(3 * c // 2 for c in coarse.cells),
                              orientations=3 * coarse.orientations // 2)
    assert coarse.summit_density == pytest.approx(fine.summit_density, rel=1e-6)
    h = np.array([0.5, 2.0, 3.5])
    a, b = (anisotropic_interface(d, elliptic_law(1.0), h) for d in (coarse, fine))
    for name in ("nominal_pressure", "contact_area_ratio"):
        rel = np.abs(a[name].values / b[name].values - 1.0)
        np.testing.assert_array_less(rel, [1e-5, 1e-5, 1e-4])


def _monte_carlo(moments, n=2_000_000, seed=1):
    """Heights and curvature tensors of the Gaussian field at points, each weighted by
    det K where K is positive definite (Kac-Rice: the summits' density)."""
    d = AnisotropicDensity(moments)
    v = np.random.default_rng(seed).multivariate_normal(np.zeros(4), d.covariance, size=n)
    det = v[:, 1] * v[:, 3] - v[:, 2] ** 2
    weight = np.where((det > 0) & (v[:, 1] > 0), det, 0.0)
    return d, v, weight


def test_density_and_moments_against_monte_carlo():
    """2 million points of the field's (z, Kxx, Kxy, Kyy): the summit density
    p_grad(0) E[det K; K > 0], the summits' mean height and principal curvatures, and the
    distribution of their orientation in six bins, each within 4 standard errors of the
    Monte Carlo."""
    d, v, w = _monte_carlo(ANISOTROPIC)
    pg = 1 / (2 * np.pi * np.sqrt(np.linalg.det(d.slope_covariance)))
    assert abs(d.summit_density - pg * w.mean()) < 4 * pg * w.std() / np.sqrt(w.size)
    k1, k2, alpha = principal_curvatures(v[:, 1], v[:, 2], v[:, 3])
    p = w / w.sum()
    n_eff = w.sum() ** 2 / (w * w).sum()
    for values, fn in ((v[:, 0], lambda z, a, b: z), (k1, lambda z, a, b: a), (k2, lambda z, a, b: b)):
        mean = (p * values).sum()
        error = np.sqrt((p * (values - mean) ** 2).sum() / n_eff)
        assert abs(d.expectation(fn) - mean) < 4 * error
    edges = np.linspace(0, np.pi, 7)
    share = np.histogram(alpha, edges, weights=p)[0]
    x, wx = np.polynomial.legendre.leggauss(16)
    theory = np.array([(0.5 * (b - a) * wx * d.orientation_pdf(0.5 * (b - a) * x + 0.5 * (a + b))).sum()
                       for a, b in zip(edges[:-1], edges[1:])])
    assert theory.sum() == pytest.approx(1.0, abs=1e-6)
    np.testing.assert_array_less(np.abs(theory - share), 4 * np.sqrt(share * (1 - share) / n_eff) + 1e-4)


def test_summits_of_a_synthetic_anisotropic_map():
    """A 1024^2 Gaussian map, correlation lengths 12 and 48 points (a lay along x): its
    summits by the eight-neighbour rule, with finite-difference curvatures, against the
    density of its own derivative moments: the summit density within 3 Poisson
    deviations, the mean principal curvatures within 3 standard errors plus 3 % (the
    differences' truncation at 12 points per correlation length), and the share of
    summits whose larger curvature lies across the lay (alpha within 45 degrees of y)
    within 3 binomial deviations."""
    from asperity.surface import map_peaks, map_statistics
    from asperity.surface.synthetic import gaussian_map

    z = gaussian_map(1024, 1.0, 1.0, 12.0, 5, aspect=4.0)
    stats = map_statistics(z, 1.0, 1.0)
    d = AnisotropicDensity({k: float(stats[k]) for k in ISOTROPIC}, mean_height=float(stats["mean_height"]))
    peaks = map_peaks(z, 1.0, 1.0)
    n = peaks.sizes["peak"]
    assert n > 300
    expected = d.summit_density * float(stats["tested_area"])
    assert abs(n - expected) < 3 * math.sqrt(expected)
    k1, k2, alpha = principal_curvatures(-peaks["z_xx"].values, -peaks["z_xy"].values, -peaks["z_yy"].values)
    keep = k2 > 0  # pixel maxima that are summits of the differences' quadratic
    for values, fn in ((k1[keep], lambda z, a, b: a), (k2[keep], lambda z, a, b: b)):
        theory = d.expectation(fn)
        assert abs(values.mean() - theory) < 3 * values.std() / math.sqrt(values.size) + 0.03 * theory
    across = np.abs(alpha[keep] - np.pi / 2) < np.pi / 4
    a = np.linspace(np.pi / 4, 3 * np.pi / 4, 65)
    share = np.trapezoid(d.orientation_pdf(a), a)
    assert abs(across.mean() - share) < 3 * math.sqrt(share * (1 - share) / keep.sum())
    assert share > 0.9  # the summits are elongated along the lay


def test_elliptic_law_is_elliptic_hertz():
    """The self-similar form c(t) of the route's law against elliptic Hertz itself (1e-12)."""
    rng = np.random.default_rng(2)
    w, k1, t = rng.uniform(0.01, 1.0, (3, 40))
    force, area, stiffness, radius = elliptic_law(3.0)(w, k1, t)
    ref = elliptic_hertz(w, k1, t * k1, 3.0)
    np.testing.assert_allclose(force, ref["force"], rtol=1e-12)
    np.testing.assert_allclose(area, ref["contact_area"], rtol=1e-12)
    np.testing.assert_allclose(stiffness, ref["stiffness"], rtol=1e-12)
    np.testing.assert_allclose(radius, np.sqrt(ref["semi_axis_a"] * ref["semi_axis_b"]), rtol=1e-12)
    sphere = mean_curvature_law(3.0)(w, k1, t)
    hertz = hertz_response(w, k1 * (1 + t) / 2, 1.0, 0.0)  # E = 1, nu = 0: E* = 1; force x 3
    np.testing.assert_allclose(sphere[0], 3.0 * hertz["force"], rtol=1e-12)
    np.testing.assert_allclose(sphere[1], hertz["contact_area"], rtol=1e-12)


def test_isotropic_route_against_a_direct_quadrature():
    """Isotropic moments and spheres of the mean curvature: the route's pressure, area and
    contact count are Nayak's density times Hertz, integrated directly over height and
    mean curvature (Gauss, 400 x 400 points), to 1e-5."""
    d = AnisotropicDensity(ISOTROPIC)
    h = np.array([0.5, 1.5, 3.0])
    out = anisotropic_interface(d, mean_curvature_law(1.0), h)
    nayak = JointDensity(1.0, math.sqrt(M2), math.sqrt(M4))
    x, w = np.polynomial.legendre.leggauss(400)
    for i, hk in enumerate(h):
        z, wz = 0.5 * (7.0 - hk) * (x + 1) + hk, 0.5 * (7.0 - hk) * w
        k, wk = 2.5 * (x + 1), 2.5 * w
        f = nayak.pdf(z[:, None], k[None, :]) * wz[:, None] * wk[None, :] * d.summit_density
        hz = hertz_response(z[:, None] - hk, k[None, :], 1.0, 0.0)
        assert out["nominal_pressure"].values[i] == pytest.approx((hz["force"] * f).sum(), rel=1e-5)
        assert out["contact_area_ratio"].values[i] == pytest.approx((hz["contact_area"] * f).sum(), rel=1e-5)
        assert out["contact_count"].values[i] == pytest.approx(f.sum(), rel=1e-5)


def test_moments_of_no_gaussian_field_are_refused():
    bad = {**ANISOTROPIC, "m40": 1e-6}
    with pytest.raises(ValueError, match="not positive definite"):
        AnisotropicDensity(bad)
    with pytest.raises(ValueError, match="m13"):
        AnisotropicDensity({k: v for k, v in ANISOTROPIC.items() if k != "m13"})


def test_gaussian_map_with_an_aspect_has_the_directional_moments():
    """A map of autocorrelation exp(-(x / (a l))^2 - (y / l)^2) has m20 = 2 sigma^2 / (a l)^2,
    m02 = 2 sigma^2 / l^2 and m11 = 0 (the second derivatives of the autocorrelation at
    zero, report 2.3.2): on 1024^2 points, l = 12, a = 4, about 1,800 correlation areas,
    so the sampling spread of a slope variance is about 3 %; bound 10 % (m11 within 10 %
    of sqrt(m20 m02))."""
    from asperity.surface import map_statistics
    from asperity.surface.synthetic import gaussian_map

    stats = map_statistics(gaussian_map(1024, 1.0, 1.0, 12.0, 5, aspect=4.0), 1.0, 1.0)
    assert float(stats["m20"]) == pytest.approx(2.0 / 48.0**2, rel=0.1)
    assert float(stats["m02"]) == pytest.approx(2.0 / 12.0**2, rel=0.1)
    assert abs(float(stats["m11"])) < 0.1 * math.sqrt(float(stats["m20"] * stats["m02"]))


def test_the_anisotropic_route_writes_the_contract_and_its_validity():
    """route.kind anisotropic on a map's moments (asperity.stages.routes): the interface
    contract with units, the elliptic law by default, a pressure falling with the
    separation, equal to the route called directly (1e-12), the validity of independent
    asperities (yield checked against the aluminum's hardness) and a one-line error for a
    law the route does not have."""
    from asperity.stages import routes
    from asperity.surface import map_statistics
    from asperity.surface.synthetic import gaussian_map
    from tests.references.test_routes import ALUMINUM, UNITS, VALIDITY, _homogenization, route

    z = gaussian_map(256, 1.25e-6, 1e-6, 10e-6, 4, aspect=4.0)
    surface_ds = map_statistics(z, 1.25e-6, 1.25e-6)
    ds = routes.route_interface(z, 1.25e-6, 1.25e-6, surface_ds, route(kind="anisotropic"), ALUMINUM,
                                _homogenization(), UNITS, VALIDITY)
    for name, (unit, _) in routes.CONTRACT.items():
        assert ds[name].attrs["units"] == unit and ds[name].attrs["long_name"], name
    assert ds.attrs["route"] == "anisotropic" and ds.attrs["law"] == "elliptic"
    p = ds["nominal_pressure"].values
    assert np.all(np.diff(p) < 0)
    direct = anisotropic_interface(AnisotropicDensity.from_surface(surface_ds),
                                   elliptic_law(ds.attrs["contact_modulus"]), ds["separation"].values)
    np.testing.assert_allclose(p, direct["nominal_pressure"].values, rtol=1e-12)
    # elastic summits of curvature radius ~ l^2 / sigma = 100 um pressed by ~1 um carry a
    # mean Hertz pressure ~ 4 E* sqrt(w / R) / (3 pi) ~ 3 GPa, ten times the aluminum's
    # yield pressure: (nearly) every contact has yielded, and no separation is valid
    assert np.all(ds["yielded_fraction"].values > 0.9)
    assert not ds["valid"].values.any()
    assert all(str(v).startswith("yielded_fraction") for v in ds["validity"].values)
    with pytest.raises(ValueError, match="route.law of the anisotropic route"):
        routes.route_interface(z, 1.25e-6, 1.25e-6, surface_ds, route(kind="anisotropic", law="shape"),
                               ALUMINUM, _homogenization(), UNITS, VALIDITY)


def test_the_anisotropic_route_on_a_measured_map():
    """The AFM map di-3.di, prepared as afm_reference prepares it (tilt removed, the lateral
    scale `auto`): the route runs on the moments of a user's map, its pressure and area
    finite and falling with the separation, and it is not called valid anywhere: the map's
    heights are not Gaussian (kurtosis 5), which the density assumes (an elastic body
    without a yield stress, so that yield is not the first limit to fail)."""
    from pathlib import Path

    from asperity.io.topography import read_measurement
    from asperity.stages import routes
    from asperity.stages.surface import surface_from_data
    from tests.references.test_routes import BARE, UNITS, VALIDITY, _homogenization, route
    from tests.scene_defaults import filled_scene

    path = Path(__file__).resolve().parents[1] / "data" / "topographies" / "di-3.di"
    scene = filled_scene({"surface": {"form": "tilt", "scale": "auto", "map": {"file": str(path)}},
                          "material": {"youngs_modulus": 1.0, "poisson": 0.3}})
    m = read_measurement(path, "map")
    surface_ds = surface_from_data(m.heights, (m.dx, m.dy), scene["surface"], UNITS, defined=m.defined)
    z = np.zeros((8, 8))  # the route reads the moments, not the heights
    ds = routes.route_interface(z, m.dx, m.dy, surface_ds, route(kind="anisotropic"), BARE,
                                _homogenization(1.5, 3.0, 6), UNITS, VALIDITY)
    p, a = ds["nominal_pressure"].values, ds["contact_area_ratio"].values
    assert np.all(np.isfinite(p)) and np.all(np.diff(p) < 0) and np.all(np.diff(a) < 0)
    assert not ds["valid"].values.any()
    assert all(str(v).startswith("gaussian_heights") for v in ds["validity"].values), ds["validity"].values


def test_the_peak_pressure_curvature_gives_the_ellipses_peak_pressure():
    """The sphere of `peak_pressure_curvature` has, at every interference, the Hertz peak
    pressure p0 = 3 F / (2 pi a b) of the elliptic contact (1e-10); for t = 1 it is the
    ellipse's own curvature (1e-12)."""
    from asperity.homogenize.anisotropic import peak_pressure_curvature

    w = np.geomspace(1e-4, 1e-1, 5)
    for t in (1.0, 0.5, 0.25, 0.1):
        e = elliptic_hertz(w, 2.0, 2.0 * t, 1.0)
        p0 = 3 * e["force"] / (2 * math.pi * e["semi_axis_a"] * e["semi_axis_b"])
        k = float(peak_pressure_curvature(np.array(2.0), np.array(t)))
        s = hertz_response(w, k, 1.0, 0.0)
        np.testing.assert_allclose(3 * s["force"] / (2 * s["contact_area"]), p0, rtol=1e-10)
    assert float(peak_pressure_curvature(np.array(2.0), np.array(1.0))) == pytest.approx(2.0, rel=1e-12)


def test_the_anisotropic_fe_law_is_elliptic_hertz_with_the_spheres_departure():
    """route.law fe of the anisotropic route: a table of exact Hertz spheres gives the
    elliptic route (the table's linear interpolation, 1e-3); a sphere whose force is
    Hertz's / (1 + 300 w kappa) (a departure of w/R alone) divides each summit's force by
    1 + 300 w kappa_p, kappa_p its peak-pressure curvature, on Hertz's area (against a
    direct quadrature, 1e-3), its stiffness by the product rule (central differences of the
    pressure, 2e-3); past the sphere's computed reach the ratio is held and marked; without
    asperities the route says what it needs."""
    import xarray as xr
    import yaml

    from asperity.homogenize.anisotropic import peak_pressure_curvature, with_departure
    from asperity.homogenize.asperity_laws import hertz_law
    from asperity.stages import routes
    from asperity.surface import map_statistics
    from asperity.surface.synthetic import gaussian_map
    from tests.references.test_routes import ALUMINUM, UNITS, VALIDITY, _homogenization, route

    z = gaussian_map(256, 1.25e-6, 1e-6, 10e-6, 4, aspect=4.0)
    surface_ds = map_statistics(z, 1.25e-6, 1.25e-6)
    modulus, _ = routes.contact_modulus_and_hardness(ALUMINUM, UNITS)
    sigma = float(z.std())
    curvature = np.geomspace(1e3, 1e6, 31)
    grid = np.concatenate([[0.0], np.geomspace(1e-5, 6.0, 400) * sigma])
    index = np.repeat(np.arange(curvature.size), grid.size)
    force, area = (v.reshape(curvature.size, grid.size)
                   for v in hertz_law(modulus, curvature)(np.tile(grid, curvature.size), index)[:2])

    def table(ratio, extrapolated=None):
        data = {"force": (("curvature", "interference"), ratio * force),
                "contact_area": (("curvature", "interference"), area + 0.0 * ratio)}
        if extrapolated is not None:
            data["extrapolated"] = (("curvature", "interference"),
                                    np.broadcast_to(extrapolated, force.shape).astype(np.int8))
        config = yaml.safe_dump({"asperity": {"model": "fe", "geometry": "sphere"}})
        return xr.Dataset(data, coords={"curvature": curvature, "interference": grid},
                          attrs={"config": config}).expand_dims(height=[0.0])

    def interface(asperities=None, law="fe"):
        return routes.route_interface(z, 1.25e-6, 1.25e-6, surface_ds, route(kind="anisotropic", law=law),
                                      ALUMINUM, _homogenization(), UNITS, VALIDITY, asperities=asperities)

    elliptic = interface(law="elliptic")
    hertz_table = interface(table(1.0))
    for name in ("nominal_pressure", "contact_area_ratio", "normal_stiffness"):
        np.testing.assert_allclose(hertz_table[name].values, elliptic[name].values, rtol=1e-3)
    assert hertz_table.attrs["law"] == "fe"

    c = 300.0
    soft = table(1.0 / (1.0 + c * grid[None, :] * curvature[:, None]))
    got = interface(soft)
    density = AnisotropicDensity.from_surface(surface_ds)
    base = elliptic_law(modulus)

    def exact(w, k1, t):
        f, a, s, r = base(w, k1, t)
        d = 1.0 + c * np.maximum(w, 0.0) * peak_pressure_curvature(k1, t)
        return f / d, a, None, r

    h = got["separation"].values
    direct = anisotropic_interface(density, lambda w, k1, t: exact(w, k1, t)[:2] + (0 * w, 0 * w), h)
    np.testing.assert_allclose(got["nominal_pressure"].values, direct["nominal_pressure"].values, rtol=1e-3)
    np.testing.assert_allclose(got["contact_area_ratio"].values, elliptic["contact_area_ratio"].values,
                               rtol=1e-3)
    dh = 1e-4 * sigma
    fd = -(anisotropic_interface(density, with_departure(base, routes.sphere_departure(soft, modulus)),
                                 h + dh)["nominal_pressure"].values
           - anisotropic_interface(density, with_departure(base, routes.sphere_departure(soft, modulus)),
                                   h - dh)["nominal_pressure"].values) / (2 * dh)
    np.testing.assert_allclose(got["normal_stiffness"].values, fd, rtol=2e-3)
    # computed only to w kappa = 1e-3: the ratio there, 1 / (1 + 0.3), is held past it
    reach = grid[None, :] * curvature[:, None] > 1e-3
    held = routes.sphere_departure(table(np.where(reach, 0.1, 1.0 / (1.0 + c * grid[None, :]
                                                                   * curvature[:, None])), reach), modulus)
    rf, _, _, beyond = held(np.array([1e-4, 5e-3, 1e-1]), 1.0)  # the grid's last computed level, within 1e-3 of it
    np.testing.assert_allclose(rf, [1 / 1.03, 1 / 1.3, 1 / 1.3], rtol=1e-3)
    np.testing.assert_array_equal(beyond, [False, True, True])
    with pytest.raises(ValueError, match="route.law fe needs the scene's finite element asperities"):
        interface(law="fe")
