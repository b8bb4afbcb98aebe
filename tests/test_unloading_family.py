"""The blended unloading family in the pipeline (report 8.3): family_table and
the per-asperity unloading responses that the interface homogenizes."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from asperity import unloading
from asperity.population.plan import interference_grid

RHO = 0.8   # residual interference / maximum interference of the exact family
C = 2.0e6   # F = C w^1.5 on loading


def exact_path(w_max, n=60):
    """An exact family: residual RHO w_max, F = F_max s^1.5, A = A_max s, s = (w - w_r)/(w_max - w_r)."""
    w_r = RHO * w_max
    w = np.linspace(w_max, w_r, n)
    s = (w - w_r) / (w_max - w_r)
    return w, C * w_max**1.5 * s**1.5, np.pi * 1e-5 * w_max * s


def gathered(levels, check=None):
    """What asperity.population.gather.gather writes: loading curves and computed paths."""
    grid = interference_grid(1e-6, 241)
    all_levels = sorted(list(levels) + ([check] if check else []))
    n = 60
    W = np.full((1, len(all_levels), n), np.nan)
    F, A = W.copy(), W.copy()
    for j, lv in enumerate(all_levels):
        W[0, j], F[0, j], A[0, j] = exact_path(lv, n)
    left = np.array([[lv == check for lv in all_levels]])
    d3, d2 = ("curvature", "unloading_level", "point"), ("curvature", "unloading_level")
    return xr.Dataset({
        "force": (("height", "curvature", "interference"), (C * grid**1.5)[None, None, :]),
        "contact_area": (("height", "curvature", "interference"), (np.pi * 1e-5 * grid)[None, None, :]),
        "unloading_interference": (d3, W), "unloading_force": (d3, F), "unloading_contact_area": (d3, A),
        "maximum_interference": (d2, np.array([all_levels])),
        "residual_interference": (d2, RHO * np.array([all_levels])),
        "left_out": (d2, left),
    }, coords={"height": [0.0], "curvature": [1e5], "interference": grid,
               "unloading_level": np.arange(len(all_levels)), "point": np.arange(n)})


def test_family_reproduces_computed_paths_and_measures_the_left_out_one():
    levels = np.geomspace(0.05, 1.0, 4) * 0.5e-6
    check = float(np.sqrt(levels[1] * levels[2]))
    table = unloading.family_table(gathered(levels, check))
    # the residual interference is linear in w_max here: the blend's end points are exact
    wm = table["maximum_interference"].values
    inside = (wm >= levels[0]) & (wm <= levels[-1])
    np.testing.assert_allclose(table["residual_interference"].values[0, inside], RHO * wm[inside], rtol=1e-9)
    # every blended path starts on the loading curve and ends at zero force (to the 3e-7 of
    # the monotone cubic through the loading grid at the computed levels, which are off-grid)
    np.testing.assert_allclose(table["path_force"].values[0, inside, -1], C * wm[inside] ** 1.5, rtol=1e-6)
    assert np.all(table["path_force"].values[0, inside, 0] == 0.0)
    # the left-out path: the blend of its neighbours is within 1 % of its peak force
    err = float(table["check_force_error"][0])
    assert 0.0 < err < 0.01, err
    assert float(table["check_residual_error"][0]) < 1e-9
    assert float(table["corner_mismatch"][0]) < 1e-6  # paths start on the loading curve
    # below the smallest level: back along the loading curve (reversible)
    below = np.flatnonzero(wm < levels[0])[-1]
    w, f = table["path_interference"].values[0, below], table["path_force"].values[0, below]
    np.testing.assert_allclose(f, C * w**1.5, rtol=1e-2, atol=1e-12 * f.max())


def test_each_asperity_unloads_from_its_own_maximum_interference():
    levels = np.geomspace(0.05, 1.0, 4) * 0.5e-6
    table = unloading.family_table(gathered(levels))
    heights = np.linspace(0.1e-6, 0.5e-6, 9)  # w_max inside the computed levels
    h0 = 0.05e-6
    # at the separation of the reversal every asperity is at its maximum interference
    back = unloading.unloading_asperities(table, heights, h0, h0)
    np.testing.assert_allclose(back["force"].values[:, 0, 0], C * (heights - h0) ** 1.5, rtol=2e-3)
    # lifted by d, the asperity of maximum interference w_max follows the exact path
    d = 0.02e-6
    back = unloading.unloading_asperities(table, heights, h0, h0 + d)
    w_max = heights - h0
    s = np.clip((w_max - d - RHO * w_max) / ((1 - RHO) * w_max), 0.0, 1.0)
    expected = C * w_max**1.5 * s**1.5
    np.testing.assert_allclose(back["force"].values[:, 0, 0], expected, atol=0.02 * expected.max())
    np.testing.assert_array_equal(back["in_contact"].values[:, 0, 0], (back["force"].values[:, 0, 0] > 0))
    # lifted beyond every rebound: nothing touches
    back = unloading.unloading_asperities(table, heights, h0, h0 + 0.3e-6)
    assert not back["force"].values.any()
