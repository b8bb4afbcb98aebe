"""Undefined points in profiles and maps (asperity.surface.missing, .statistics, .maps).

The statistics of a record with undefined points must be those of its defined part,
computed directly: derivatives only where the stencil is defined, peaks only where the
neighbourhood is, densities per defined length or area.
"""

from __future__ import annotations

import numpy as np
import pytest

from asperity import surface as S

ORDER = 8
P = ORDER // 2


def gaussian_map(n=64, seed=3):
    return S.gaussian_map(n, 1.0, 1.0, 5.0, seed)


def test_map_with_undefined_rows_equals_the_defined_submap():
    """A band of undefined rows at the top: every statistic equals that of the rows below,
    the map that is left (1e-12: the same numbers, summed in another order)."""
    z = gaussian_map(72)
    defined = np.ones(z.shape, bool)
    defined[60:] = False
    masked = np.where(defined, z, np.nan)
    got = S.map_statistics(masked, 1.0, 1.5, defined=defined)
    ref = S.map_statistics(z[:60], 1.0, 1.5)
    for name in ref.data_vars:
        if name in ("points_y", "points_defined"):
            continue
        assert float(got[name]) == pytest.approx(float(ref[name]), rel=1e-12, abs=1e-300), name
    assert int(got["points_defined"]) == 60 * 72
    peaks, ref_peaks = S.map_peaks(masked, 1.0, 1.5, defined=defined), S.map_peaks(z[:60], 1.0, 1.5)
    np.testing.assert_array_equal(peaks["row"], ref_peaks["row"])
    np.testing.assert_allclose(peaks["curvature"], ref_peaks["curvature"], rtol=1e-12)


def direct_statistics(z, defined, dx, dy):
    """Sampling statistics of the defined part of a map, point by point (loops: a reference)."""
    a, b = S.stencil(ORDER)
    ny, nx = z.shape
    out = {"height": [z[i, j] for i in range(ny) for j in range(nx) if defined[i, j]],
           "slope_x": [], "curvature_x": [], "slope_y": [], "curvature_y": []}
    for i in range(ny):
        for j in range(P, nx - P):
            if defined[i, j - P : j + P + 1].all():
                row = z[i, j - P : j + P + 1]
                out["slope_x"].append(sum(a[k - 1] * (row[P + k] - row[P - k]) for k in range(1, P + 1)) / dx)
                out["curvature_x"].append((b[0] * row[P] + sum(b[k] * (row[P + k] + row[P - k])
                                                              for k in range(1, P + 1))) / dx**2)
    for j in range(nx):
        for i in range(P, ny - P):
            if defined[i - P : i + P + 1, j].all():
                col = z[i - P : i + P + 1, j]
                out["slope_y"].append(sum(a[k - 1] * (col[P + k] - col[P - k]) for k in range(1, P + 1)) / dy)
                out["curvature_y"].append((b[0] * col[P] + sum(b[k] * (col[P + k] + col[P - k])
                                                              for k in range(1, P + 1))) / dy**2)
    return {k: np.array(v) for k, v in out.items()}


def test_map_with_a_block_of_undefined_points_equals_the_direct_statistics_of_its_defined_part():
    z = gaussian_map(48, seed=9)
    defined = np.ones(z.shape, bool)
    defined[15:27, 20:31] = False  # a block inside
    defined[40, 5] = False  # and a lone bad pixel
    dx, dy = 1.0, 0.8
    got = S.map_statistics(np.where(defined, z, np.nan), dx, dy, defined=defined)
    ref = direct_statistics(z, defined, dx, dy)
    # 1e-12: the same sums in another order
    assert float(got["mean_height"]) == pytest.approx(ref["height"].mean(), rel=1e-12, abs=1e-15)
    assert float(got["sigma"]) == pytest.approx(np.std(ref["height"], ddof=1), rel=1e-12)
    for axis in ("x", "y"):
        for what in ("slope", "curvature"):
            values = ref[f"{what}_{axis}"]
            assert float(got[f"sigma_{what}_{axis}"]) == pytest.approx(np.std(values, ddof=1), rel=1e-12)
            assert float(got[f"mean_{what}_{axis}"]) == pytest.approx(values.mean(), rel=1e-9, abs=1e-14)
    # the density is per tested area: the points whose eight neighbours are defined
    tested = sum(defined[i - 1 : i + 2, j - 1 : j + 2].all()
                 for i in range(1, 47) for j in range(1, 47))
    assert float(got["tested_area"]) == pytest.approx(tested * dx * dy, rel=1e-15)
    assert float(got["peak_density"]) == pytest.approx(int(got["peak_count"]) / (tested * dx * dy), rel=1e-15)


def test_peaks_never_touch_an_undefined_point():
    """Every peak's eight neighbours, and the whole stencil of its curvature (fd_order + 1
    points square), are defined; no peak is lost that the full map has where its
    neighbourhood is defined."""
    z = gaussian_map(128, seed=11)
    rng = np.random.default_rng(4)
    defined = rng.random(z.shape) > 0.02  # 2 % scattered bad pixels
    defined[30:50, 40:70] = False
    peaks = S.map_peaks(np.where(defined, z, np.nan), 1.0, 1.0, defined=defined)
    assert peaks.sizes["peak"] > 20
    for i, j, order in zip(peaks["row"].values, peaks["column"].values, peaks["fd_order"].values):
        p = order // 2
        assert defined[i - p : i + p + 1, j - p : j + p + 1].all(), (i, j, order)
    full = S.map_peaks(z, 1.0, 1.0)
    keep = [defined[i - 1 : i + 2, j - 1 : j + 2].all() for i, j in zip(full["row"].values, full["column"].values)]
    np.testing.assert_array_equal(np.sort(peaks["row"].values * 1000 + peaks["column"].values),
                                  np.sort(full["row"].values[keep] * 1000 + full["column"].values[keep]))
    # a peak with the whole order-8 stencil defined has the same curvature as in the full map
    whole = peaks["fd_order"].values == ORDER
    assert whole.sum() > 5
    rows = {(r, c): k for r, c, k in zip(full["row"].values, full["column"].values, full["curvature"].values)}
    for r, c, k in zip(peaks["row"].values[whole], peaks["column"].values[whole], peaks["curvature"].values[whole]):
        assert k == pytest.approx(rows[(r, c)], rel=1e-12)


def test_profile_with_gaps_equals_its_segments_computed_directly():
    """Sampling: the defined heights' std and the std of the derivatives of each segment,
    pooled; counting: crossings of the mean within segments, per defined length; spectral:
    the longest segment alone (1e-12 each)."""
    C, k, e = S.quasirandom_series(n=12, seed=2, period=200.0, k_range=(0.2, 1.5))
    dx = 0.25
    z = S.evaluate_series(np.arange(3000) * dx, C, k, e)
    defined = np.ones(z.size, bool)
    defined[700:760] = False
    defined[2000:2003] = False
    ds = S.profile_statistics(np.where(defined, z, np.nan), dx, defined=defined)
    segments = [z[:700], z[760:2000], z[2003:]]
    slopes = np.concatenate([S.derivatives(seg, dx)[0] for seg in segments])
    curvs = np.concatenate([S.derivatives(seg, dx)[1] for seg in segments])
    samp = ds.sel(estimator="sampling")
    assert float(samp["sigma"]) == pytest.approx(np.std(z[defined], ddof=1), rel=1e-12)
    assert float(samp["sigma_slope"]) == pytest.approx(np.std(slopes, ddof=1), rel=1e-12)
    assert float(samp["sigma_curvature"]) == pytest.approx(np.std(curvs, ddof=1), rel=1e-12)
    assert int(ds["points_defined"]) == defined.sum()
    mean = z[defined].mean()
    crossings, span = 0, 0.0
    for seg in segments:
        d = seg - mean
        idx = np.flatnonzero(np.signbit(d[:-1]) != np.signbit(d[1:]))
        pos = idx + d[idx] / (d[idx] - d[idx + 1])
        crossings += pos.size - 1
        span += pos[-1] - pos[0]
    count = ds.sel(estimator="counting")
    assert float(count["zero_density"]) == pytest.approx(crossings / span / dx, rel=1e-12)
    longest = S.profile_statistics(z[760:2000], dx, estimators=("spectral",))
    assert float(ds["sigma_slope"].sel(estimator="spectral")) == pytest.approx(
        float(longest["sigma_slope"].sel(estimator="spectral")), rel=1e-12)
    assert "760 to 1999" in ds.attrs["spectral_record"]


def test_all_undefined_and_non_finite_defined_points_are_errors():
    z = np.ones((20, 20))
    with pytest.raises(ValueError, match="every point of the map is undefined"):
        S.map_statistics(z, 1.0, 1.0, defined=np.zeros(z.shape, bool))
    bad = z.copy()
    bad[3, 4] = np.inf
    with pytest.raises(ValueError, match=r"\(row 3, column 4\)"):
        S.map_statistics(bad, 1.0, 1.0, defined=np.ones(z.shape, bool))


def test_complete_neighbourhood_against_brute_force():
    rng = np.random.default_rng(7)
    defined = rng.random((23, 31)) > 0.05
    for half in (1, 2, 4):
        got = S.complete_neighbourhood(defined, half)
        for i in range(23):
            for j in range(31):
                inside = half <= i < 23 - half and half <= j < 31 - half
                expected = inside and defined[i - half : i + half + 1, j - half : j + half + 1].all()
                assert got[i, j] == expected, (half, i, j)


def test_harmonic_fill_is_discrete_harmonic_and_agrees_with_surface_topography():
    """The filled heights satisfy the five-point Laplace equation at every filled point
    (1e-10 of the height range), and equal SurfaceTopography's harmonic in-fill of the
    same masked map (1e-9 relative: two sparse direct solves)."""
    import SurfaceTopography as ST

    z = gaussian_map(60, seed=5)
    rng = np.random.default_rng(8)
    defined = rng.random(z.shape) > 0.15
    defined[10:25, 30:50] = False
    filled = S.harmonic_fill(np.where(defined, z, 0.0), defined)
    np.testing.assert_array_equal(filled[defined], z[defined])
    ii, jj = np.nonzero(~defined)
    for i, j in zip(ii, jj):
        nb = [(i + di, j + dj) for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
              if 0 <= i + di < 60 and 0 <= j + dj < 60]
        assert abs(sum(filled[a, b] for a, b in nb) - len(nb) * filled[i, j]) < 1e-10 * np.ptp(z)
    topo = ST.Topography(np.ma.masked_array(z.T, ~defined.T), (60.0, 60.0), periodic=False)
    theirs = topo.interpolate_undefined_data("harmonic").heights().T
    np.testing.assert_allclose(filled, theirs, rtol=1e-9, atol=1e-12)
    profile = np.array([1.0, 2.0, 0.0, 0.0, 0.0, 6.0, 7.0, 0.0])
    mask = np.array([True, True, False, False, False, True, True, False])
    np.testing.assert_allclose(S.harmonic_fill(profile, mask), [1, 2, 3, 4, 5, 6, 7, 7], rtol=1e-12)


def test_the_scene_limits_the_share_of_undefined_points_and_can_fill_them():
    """Above surface.undefined.max_share the stage stops, naming the key; fill: harmonic fills
    first (the statistics then see every point, the PSD no longer needs its own fill)."""
    from asperity.stages.surface import surface_from_data

    z = gaussian_map(64, seed=4) * 1e-6
    defined = np.ones(z.shape, bool)
    defined[:20] = False  # 31 % undefined
    masked = np.where(defined, z, np.nan)
    strict = {"map": {"file": "m.npy"}, "form": "tilt", "undefined": {"max_share": 0.25}}
    with pytest.raises(ValueError, match=r"31.2 % of the points are undefined, more than the scene allows "
                                         r"\(key surface.undefined.max_share = 0.25\)"):
        surface_from_data(masked, (1e-6, 1e-6), strict, {"length": "um"}, defined=defined)
    kept = surface_from_data(masked, (1e-6, 1e-6), {**strict, "undefined": {"max_share": 0.5}},
                             {"length": "um"}, defined=defined)
    assert float(kept["undefined_share"]) == pytest.approx(0.3125, rel=1e-12)
    assert int(kept["points_defined"]) == 44 * 64 and int(kept["filled_points"]) == 0
    assert "filled harmonically for the spectrum only" in kept.attrs["psd_note"]
    filled = surface_from_data(masked, (1e-6, 1e-6), {**strict, "undefined": {"max_share": 0.5, "fill": "harmonic"}},
                               {"length": "um"}, defined=defined)
    assert int(filled["filled_points"]) == 20 * 64 and int(filled["points_defined"]) == 64 * 64
    assert filled.attrs["undefined_fill"] == "harmonic" and "psd_note" not in filled.attrs


def _islands_brute_force(defined):
    """Regions by flood fill over the four (map) or two (profile) neighbours; a region is
    kept when one of its points has every neighbour of its 3 x 3 square (or pair) inside
    the record and defined."""
    d = np.atleast_2d(defined)
    ny, nx = d.shape
    step = [(0, 1), (0, -1)] if np.ndim(defined) == 1 else [(1, 0), (-1, 0), (0, 1), (0, -1)]
    di = (0,) if np.ndim(defined) == 1 else (-1, 0, 1)
    out = np.zeros(d.shape, bool)
    seen = np.zeros(d.shape, bool)
    for i0 in range(ny):
        for j0 in range(nx):
            if not d[i0, j0] or seen[i0, j0]:
                continue
            region, stack = [], [(i0, j0)]
            seen[i0, j0] = True
            while stack:
                i, j = stack.pop()
                region.append((i, j))
                for a, b in step:
                    p, q = i + a, j + b
                    if 0 <= p < ny and 0 <= q < nx and d[p, q] and not seen[p, q]:
                        seen[p, q] = True
                        stack.append((p, q))
            interior = any(all(0 <= i + a < ny and 0 <= j + b < nx and d[i + a, j + b]
                               for a in di for b in (-1, 0, 1)) for i, j in region)
            if not interior:
                for i, j in region:
                    out[i, j] = True
    return out.reshape(np.shape(defined))


def test_islands_are_the_regions_without_an_interior_point():
    """Against a flood fill on random masks (maps with 40-70 % defined, where islands of
    every shape occur, and profiles), and by hand: a speck, a 2 x 2 block and a line one
    point wide are islands; a 3 x 3 block is kept whole; a speck touching a region only at
    a corner is apart from it."""
    rng = np.random.default_rng(11)
    for p in (0.4, 0.55, 0.7):
        defined = rng.random((37, 29)) < p
        np.testing.assert_array_equal(S.islands(defined), _islands_brute_force(defined))
        line = rng.random(400) < p
        np.testing.assert_array_equal(S.islands(line), _islands_brute_force(line))
    m = np.zeros((12, 14), bool)
    m[1, 1] = True                      # speck
    m[1:3, 4:6] = True                  # 2 x 2
    m[5, 1:13] = True                   # one point wide
    m[8:11, 8:11] = True                # 3 x 3: one interior point
    m[7, 7] = True                      # a corner away from the 3 x 3
    expected = m.copy()
    expected[8:11, 8:11] = False
    np.testing.assert_array_equal(S.islands(m), expected)
    run = np.array([1, 0, 1, 1, 0, 1, 1, 1, 0, 0, 1, 1, 1, 1], bool)
    np.testing.assert_array_equal(S.islands(run), [1, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0])
    assert not S.islands(np.ones((5, 5), bool)).any()


def test_the_scene_drops_islands_before_the_form_fit():
    """A map with an undefined band holding specks 100 times its rms high and a one-point
    line of zeros: with surface.undefined.islands: drop every statistic equals that of the
    map with those points marked undefined by hand (1e-12), and the count is recorded; kept,
    they dominate the rms (about 4 times). A map that is all islands is an error naming the key."""
    from asperity.stages.surface import surface_from_data

    z = gaussian_map(64, seed=6) * 1e-6
    rms = float(np.std(z))
    defined = np.ones(z.shape, bool)
    defined[20:40] = False
    specks = [(25, 10), (25, 40), (33, 22), (36, 50)]
    for i, j in specks:
        defined[i, j] = True
        z[i, j] = 100 * rms * (1 if j % 2 else -1)
    defined[30, 5:60] = True
    z[30, 5:60] = 0.0
    cfg = {"map": {"file": "m.npy"}, "form": "tilt", "undefined": {"max_share": 0.5}}
    units = {"length": "um"}
    dropped = surface_from_data(np.where(defined, z, np.nan), (1e-6, 1e-6),
                                {**cfg, "undefined": {"max_share": 0.5, "islands": "drop"}}, units,
                                defined=defined)
    by_hand = defined.copy()
    by_hand[20:40] = False
    direct = surface_from_data(np.where(by_hand, z, np.nan), (1e-6, 1e-6), cfg, units, defined=by_hand)
    assert int(dropped["island_points"]) == len(specks) + 55 and int(direct["island_points"]) == 0
    assert dropped.attrs["undefined_islands"] == "drop"
    assert float(dropped["undefined_share"]) == pytest.approx(1 - defined.mean(), rel=1e-12)
    for name in ("rms_height", "sigma", "sigma_slope", "sigma_curvature", "skewness", "kurtosis",
                 "peak_density"):
        assert float(dropped[name]) == pytest.approx(float(direct[name]), rel=1e-12), name
    np.testing.assert_array_equal(dropped["height"].values, direct["height"].values)
    kept = surface_from_data(np.where(defined, z, np.nan), (1e-6, 1e-6), cfg, units, defined=defined)
    # four specks of 100 rms among about 2 700 points add sqrt(4e4 / 2700) = 3.8 rms
    assert float(kept["rms_height"]) > 3.5 * float(direct["rms_height"])
    specks_only = np.zeros(z.shape, bool)
    specks_only[::2, ::2] = True
    with pytest.raises(ValueError, match=r"every one lies in an island \(key surface.undefined.islands"):
        surface_from_data(np.where(specks_only, z, np.nan), (1e-6, 1e-6),
                          {**cfg, "undefined": {"max_share": 0.9, "islands": "drop"}}, units,
                          defined=specks_only)
