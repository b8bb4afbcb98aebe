"""A sliding asperity's force histories between presets (asperity.studies.sliding_accuracy),
on hand-made histories whose differences are known in closed form."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from asperity.studies.sliding_accuracy import history_difference, sliding_accuracy

T_PRESS, T_END = 1800.0, 4000.0


def _run(preset: str, times: np.ndarray, scale: float = 1.0, shift: float = 0.0) -> xr.Dataset:
    """F_N = scale t / T_PRESS while pressing, then scale (1 + shift); F_T = 0 while pressing,
    then 0.5 scale (1 - exp(-(t - T_PRESS) / 200)) + shift."""
    fn = np.where(times <= T_PRESS, scale * times / T_PRESS, scale * (1.0 + shift))
    ft = np.where(times <= T_PRESS, 0.0, 0.5 * scale * (1 - np.exp(-(times - T_PRESS) / 200.0)) + shift)
    return xr.Dataset({"time": ("step", times), "normal_force": ("step", fn), "tangential_force": ("step", ft)},
                      attrs={"accuracy": preset, "motion_times": np.array([0.0, T_PRESS, T_END]),
                             "dofs": {"draft": 100, "standard": 400}[preset], "total_wall_time": 1.0,
                             "completed": 1, "scene": f"s@{preset}"})


def test_shared_step_times_are_compared_without_interpolation():
    """The coarser run's times all among the finer one's: d = |shift| / (1 + shift) exactly."""
    fine_t = np.linspace(0.0, T_END, 41)
    coarse, fine = _run("draft", fine_t[::2]), _run("standard", fine_t, shift=0.02)
    d, shared = history_difference((coarse["time"], coarse["normal_force"]),
                                   (fine["time"], fine["normal_force"]), (T_PRESS, np.inf))
    assert shared and d == pytest.approx(0.02 / 1.02, rel=1e-12)


def test_other_times_interpolate_the_finer_history():
    """Off the finer grid the finer (linear while pressing) history is interpolated: the
    same ramp differs by 0 to round-off; a 1 % steeper one by 1 % of the ramp at the
    coarser run's last pressing step t_c, over the finer ramp's top: 0.01 t_c / T / 1.01."""
    coarse_t = np.linspace(0.0, T_END, 23)
    fine_t = np.linspace(0.0, T_END, 41)
    t_c = coarse_t[coarse_t <= T_PRESS][-1]
    for scale, expected in ((1.0, 0.0), (1.01, 0.01 * t_c / T_PRESS / 1.01)):
        d, shared = history_difference((coarse_t, _run("draft", coarse_t)["normal_force"].values),
                                       (fine_t, _run("standard", fine_t, scale=scale)["normal_force"].values),
                                       (0.0, T_PRESS))
        assert not shared and d == pytest.approx(expected, abs=1e-12)


def test_the_study_compares_each_preset_with_the_next_finer():
    """Pressing identical, sliding F_N shifted 2 %, F_T shifted by 0.02 of the F_T plateau's
    0.5: d as in closed form; F_T while pressing not compared (zero by symmetry)."""
    fine_t = np.linspace(0.0, T_END, 41)
    ds = sliding_accuracy({"draft": _run("draft", fine_t[::2]), "standard": _run("standard", fine_t, shift=0.02)},
                          ["draft", "standard"])
    d = ds["difference"].sel(pair="draft vs standard")
    assert float(d.sel(force="normal_force", phase="pressing")) == 0.0
    assert float(d.sel(force="normal_force", phase="sliding")) == pytest.approx(0.02 / 1.02, rel=1e-12)
    peak = 0.5 * (1 - np.exp(-(T_END - T_PRESS) / 200.0)) + 0.02
    assert float(d.sel(force="tangential_force", phase="sliding")) == pytest.approx(0.02 / peak, rel=1e-12)
    assert np.isnan(float(d.sel(force="tangential_force", phase="pressing")))
    assert ds["dofs"].values.tolist() == [100, 400] and ds.attrs["sliding_scene"] == "s"


def test_a_run_at_another_preset_is_refused():
    t = np.linspace(0.0, T_END, 11)
    with pytest.raises(ValueError, match="computed at accuracy 'draft'"):
        sliding_accuracy({"draft": _run("draft", t), "standard": _run("draft", t)}, ["draft", "standard"])
