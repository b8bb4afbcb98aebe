"""Incremental reruns of the real workflow (issues 6, 13): shared sample keys, what a
changed setting reruns, what an upgrade of the code reruns (asperity.versions), a run
killed with SIGKILL and started again, and one failing sample under --keep-going.

Small variants of the report's scenes at `draft`, written into a copy of the
workflow:

- ``rr_sphere``: greenwood_williamson_fe (7.1) with a friction section: one FE sphere;
- ``rr_sphere_b``: the same asperities on another height grid (3 heights, not 2), with
  other homogenization and friction settings;
- ``rr_hill``: asperity_shape (7.2) with ``scaling: none``: one FE job per curvature (5).

One run of them (module fixture ``base``) is shared; the tests that edit a scene
run the workflow on to completion, so each leaves nothing pending for the next.
"""

from __future__ import annotations

import base64
import os
import re
import shutil
import signal
import subprocess
import time
from collections import Counter
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
import yaml

from asperity.io.netcdf import missing_attributes, read_dataset
from asperity.population.plan import job_keys

from .conftest import (REPO, SNAKEMAKE, assert_same_results, copy_workflow, nc_files,
                       planned_jobs, snakemake)

pytestmark = [pytest.mark.workflow, pytest.mark.slow]

HILL_CURVATURES = 5
RTOL = 1e-12  # two runs of the same jobs: the same numbers up to round-off (here bitwise)


def repo_scene(name: str) -> dict:
    scene = yaml.safe_load((REPO / "config" / "scenes" / f"{name}.yaml").read_text())
    for key in ("compare_with", "verification"):
        scene.pop(key, None)  # no comparison scenes: fewer jobs
    return scene


def sphere_scene(heights=2, cells=(400, 1), shear=10.0) -> dict:
    scene = repo_scene("greenwood_williamson_fe")
    scene["population"]["samples"]["height"] = heights
    scene["homogenization"]["cells"] = list(cells)
    scene["friction"] = {"junction_shear_strength": shear, "interlocking": "none"}  # kG/mm^2
    return scene


def hill_scene() -> dict:
    scene = repo_scene("asperity_shape")
    scene["population"]["samples"] = {"height": 2, "curvature": HILL_CURVATURES, "interference": 121}
    scene["asperity"]["scaling"] = "none"
    return scene


SCENES = {"rr_sphere": sphere_scene(), "rr_sphere_b": sphere_scene(heights=3, cells=(200, 1), shear=20.0),
          "rr_hill": hill_scene()}
CONFIG = ("--config", f"scenes=[{','.join(SCENES)}]", "accuracy=draft", "studies=False")
TARGETS = {"rr_sphere": "results/rr_sphere/friction.nc", "rr_sphere_b": "results/rr_sphere_b/friction.nc",
           "rr_hill": "results/rr_hill/interface.nc"}


def write_scene(workdir: Path, name: str, scene: dict) -> None:
    (workdir / "config" / "scenes" / f"{name}.yaml").write_text(yaml.safe_dump(scene))


def edit_scene(workdir: Path, name: str, edit) -> None:
    path = workdir / "config" / "scenes" / f"{name}.yaml"
    scene = yaml.safe_load(path.read_text())
    edit(scene)
    path.write_text(yaml.safe_dump(scene))


def executed_jobs(proc) -> dict[str, int]:
    """Rule -> number of jobs a (real) run finished.  Its first job table is printed
    before the plan checkpoint is evaluated, so it does not count the samples."""
    return dict(Counter(re.findall(r"Finished jobid: \d+ \(Rule: (\w+)\)", proc.stdout + proc.stderr)))


def plan_keys(workdir: Path, name: str) -> list[str]:
    return job_keys(read_dataset(workdir / "results" / name / "plan.nc"))


def sample_times(workdir: Path) -> dict[str, int]:
    return {p.name: p.stat().st_mtime_ns for p in (workdir / "results" / "samples").glob("*.nc")}


@pytest.fixture(scope="module")
def base(tmp_path_factory):
    """rr_sphere and rr_hill run; their results copied aside; then rr_sphere_b's plan,
    a dry run of its friction.nc, and the run itself."""
    root = tmp_path_factory.mktemp("reruns")
    workdir = copy_workflow(root)
    for name, scene in SCENES.items():
        write_scene(workdir, name, scene)
    first = snakemake(workdir, TARGETS["rr_sphere"], TARGETS["rr_hill"], *CONFIG)
    reference = root / "reference"
    shutil.copytree(workdir / "results", reference)  # an uninterrupted run, before any edit
    snakemake(workdir, "results/rr_sphere_b/plan.nc", *CONFIG)
    second_dry = snakemake(workdir, "-n", TARGETS["rr_sphere_b"], *CONFIG)
    second = snakemake(workdir, TARGETS["rr_sphere_b"], *CONFIG)
    return SimpleNamespace(workdir=workdir, reference=reference, first=first,
                           second_dry=second_dry, second=second)


def test_shared_keys_one_job_per_distinct_asperity(base):
    """Two scenes needing the same asperity share its key and file, though their plans
    differ (2 or 3 heights: the job's interference range is the same): the second
    plans no `sample` job; the FE jobs run are the distinct keys of all plans."""
    w = base.workdir
    keys = {name: plan_keys(w, name) for name in SCENES}
    assert len(keys["rr_sphere"]) == 1 and keys["rr_sphere_b"] == keys["rr_sphere"]
    assert len(set(keys["rr_hill"])) == HILL_CURVATURES
    distinct = set().union(*keys.values())
    assert len(distinct) == 1 + HILL_CURVATURES
    # the first run made every distinct sample once; the second scene's made none
    assert executed_jobs(base.first)["sample"] == len(distinct)
    assert planned_jobs(base.second_dry) == {"asperities": 1, "interface": 1, "friction": 1}
    assert executed_jobs(base.second) == planned_jobs(base.second_dry)
    assert sorted(p.stem for p in finished_samples(w)) == sorted(distinct)
    # different plans, the same job spec (JSON) under the same key, the same asperity curve
    plans = [read_dataset(w / "results" / n / "plan.nc") for n in ("rr_sphere", "rr_sphere_b")]
    assert [p.sizes["height"] for p in plans] == [2, 3]
    assert len(set(plans[0]["spec"].values) | set(plans[1]["spec"].values)) == 1
    a, b = (read_dataset(w / "results" / n / "asperities.nc") for n in ("rr_sphere", "rr_sphere_b"))
    np.testing.assert_array_equal(a["force"].isel(height=0).values, b["force"].isel(height=-1).values)


def test_editing_a_rules_file_reruns_no_fe_job(base):
    """A comment added to any rules file changes no rule's recorded code: nothing
    reruns.  (A global `wildcard_constraints:` block in population.smk made Snakemake
    record a shifted source for rule `sample`, and every such edit reran every FE
    sample of every scene, which share one folder.)"""
    w = base.workdir
    for rules in ("population.smk", "figures.smk"):
        path = w / "workflow" / "rules" / rules
        text = path.read_text()
        try:
            path.write_text(text + "\n# an edit that changes no rule\n")
            assert planned_jobs(snakemake(w, "-n", *TARGETS.values(), *CONFIG)) == {}, rules
        finally:
            path.write_text(text)


# ------------------------------------------------------------------ upgrades


def upgraded(root: Path, *stages: str) -> dict:
    """The environment of a run with an upgraded asperity: a copy of the package whose
    `asperity.versions.VERSIONS` has each of `stages` one version higher, first on the
    Python path (the code itself is the same: only what the upgrade declares changes)."""
    package = root / "upgraded"
    shutil.rmtree(package, ignore_errors=True)
    shutil.copytree(REPO / "src" / "asperity", package / "asperity",
                    ignore=shutil.ignore_patterns("__pycache__"))
    path = package / "asperity" / "versions.py"
    text = path.read_text()
    for stage in stages:
        text, n = re.subn(rf'^(\s*"{re.escape(stage)}": )(\d+),$',
                          lambda m: f"{m.group(1)}{int(m.group(2)) + 1},", text, flags=re.M)
        assert n == 1, stage
    path.write_text(text)
    return {**os.environ, "PYTHONPATH": str(package)}


@pytest.mark.parametrize("stages, expected", [
    # a non-FE stage: it and what reads its files, no plan, no sample
    (("friction",), {"friction": 2}),
    (("interface",), {"interface": 3, "friction": 2}),
    # the plan: every plan, then the gathers (a dry run cannot see past the checkpoint: the
    # samples of the new plans have the keys of the old, tests/test_plan_keys.py)
    (("plan",), {"plan": 3, "asperities": 3, "interface": 3, "friction": 2}),
    # one asperity kind: exactly its samples (all elastic here: the sphere shared by the
    # two sphere scenes, and the hill's five), and what reads them
    (("sample:elastic",), {"sample": 1 + HILL_CURVATURES, "asperities": 3, "interface": 3,
                           "friction": 2}),
    # a kind no scene of the run uses: nothing
    (("sample:inelastic", "sample:adhesive", "unloading"), {}),
], ids=["friction", "interface", "plan", "elastic-samples", "unused-kinds"])
def test_an_upgrade_reruns_exactly_the_stages_whose_version_changed(base, tmp_path, stages,
                                                                     expected):
    """A dry run with the package of an upgrade that bumps the versions of `stages`
    schedules those stages and what reads their files, nothing else."""
    env = upgraded(tmp_path, *stages)
    jobs = planned_jobs(snakemake(base.workdir, "-n", *TARGETS.values(), *CONFIG, env=env))
    assert jobs == expected, jobs


def test_a_changed_non_fe_script_reruns_no_sample(base):
    """A new version of a stage's script (the homogenization's) reruns that stage and
    what reads its file, never an FE sample."""
    w = base.workdir
    script = w / "workflow" / "scripts" / "interface.py"
    before = script.stat()
    try:
        os.utime(script, ns=(before.st_atime_ns, time.time_ns()))
        jobs = planned_jobs(snakemake(w, "-n", *TARGETS.values(), *CONFIG))
        assert jobs == {"interface": 3, "friction": 2}, jobs
    finally:
        os.utime(script, ns=(before.st_atime_ns, before.st_mtime_ns))


def test_homogenization_change_reruns_no_fe_job_and_changes_the_interface(base):
    """cells 200 -> 40 (Gauss cells over the heights): interface and friction rerun,
    no plan, no sample, no gather; the sample files are not touched; the pressure changes."""
    w = base.workdir
    before = read_dataset(w / "results" / "rr_sphere_b" / "interface.nc")
    times = sample_times(w)
    edit_scene(w, "rr_sphere_b", lambda s: s["homogenization"].update(cells=[40, 1]))
    assert planned_jobs(snakemake(w, "-n", *TARGETS.values(), *CONFIG)) == {"interface": 1, "friction": 1}
    run = snakemake(w, *TARGETS.values(), *CONFIG)
    assert executed_jobs(run) == {"interface": 1, "friction": 1}
    assert sample_times(w) == times
    after = read_dataset(w / "results" / "rr_sphere_b" / "interface.nc")
    p0, p1 = before["nominal_pressure"].values, after["nominal_pressure"].values
    np.testing.assert_array_equal(before["separation"].values, after["separation"].values)
    loaded = p0 > 0
    change = np.abs(p1[loaded] / p0[loaded] - 1)
    # a coarser quadrature of the same integral: changed, but by far less than the integral
    assert 1e-6 < change.max() < 0.05, change.max()


def test_friction_change_reruns_friction_only(base):
    """junction shear strength 20 -> 30 kG/mm^2: only friction.nc reruns, and its
    mu = tau_s A_c / F (no interlocking) scales by exactly 1.5 (1e-12)."""
    w = base.workdir
    path = w / "results" / "rr_sphere_b" / "friction.nc"
    before = read_dataset(path)
    times = sample_times(w)
    edit_scene(w, "rr_sphere_b", lambda s: s["friction"].update(junction_shear_strength=30.0))
    assert planned_jobs(snakemake(w, "-n", *TARGETS.values(), *CONFIG)) == {"friction": 1}
    snakemake(w, *TARGETS.values(), *CONFIG)
    after = read_dataset(path)
    assert sample_times(w) == times
    mu0, mu1 = before["mu"].values, after["mu"].values
    ok = np.isfinite(mu0) & (mu0 > 0)
    assert ok.sum() >= 10
    np.testing.assert_allclose(mu1[ok], 1.5 * mu0[ok], rtol=1e-12)
    tau0, tau1 = (float(ds["junction_shear_strength"]) for ds in (before, after))
    assert tau1 == pytest.approx(1.5 * tau0, rel=1e-15)


def test_material_change_reruns_exactly_the_affected_fe_jobs(base):
    """E of rr_hill 65 -> 70 GPa: its plan reruns, then exactly its five FE jobs (new
    keys, none of the old) and its gather; nothing of the sphere scenes."""
    w = base.workdir
    old = {name: plan_keys(w, name) for name in SCENES}
    edit_scene(w, "rr_hill", lambda s: s["material"].update(youngs_modulus=70000.0))
    assert executed_jobs(snakemake(w, "results/rr_hill/plan.nc", *CONFIG)) == {"plan": 1}
    new = plan_keys(w, "rr_hill")
    assert len(set(new)) == HILL_CURVATURES and not set(new) & set().union(*old.values())
    assert plan_keys(w, "rr_sphere") == old["rr_sphere"]
    jobs = planned_jobs(snakemake(w, "-n", *TARGETS.values(), *CONFIG))
    assert jobs == {"sample": HILL_CURVATURES, "asperities": 1, "interface": 1}, jobs


# ------------------------------------------------------------------ SIGKILL


def registered(workdir: Path) -> list[str]:
    """Sample files whose job Snakemake has recorded as finished (its incomplete marker,
    set when the job starts, is removed once the output is registered)."""
    marks = workdir / ".snakemake" / "incomplete"
    return [p.stem for p in finished_samples(workdir)
            if not (marks / base64.urlsafe_b64encode(f"results/samples/{p.name}".encode()).decode()).exists()]


def finished_samples(workdir: Path) -> list[Path]:
    """The sample files under their own names (a temporary file of a write is hidden: .<name>.*.tmp.nc)."""
    return [p for p in (workdir / "results" / "samples").glob("*.nc") if not p.name.startswith(".")]


def _gone(pgid: int, timeout: float = 10.0) -> bool:
    """Whether no process of the group is left (zombies reaped) within `timeout`."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            os.killpg(pgid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.05)
    return False


def test_sigkill_mid_run_then_restart_gives_the_uninterrupted_results(base, tmp_path):
    """rr_hill started, SIGKILLed (the whole process group) once some but not all of
    its five samples exist; every netCDF left opens and is complete; after
    `snakemake --unlock` the run with the default profile (--rerun-incomplete) keeps
    the finished samples and ends with results identical to the uninterrupted run."""
    w = copy_workflow(tmp_path)
    write_scene(w, "rr_hill", SCENES["rr_hill"])
    config = ("--config", "scenes=[rr_hill]", "accuracy=draft", "studies=False")
    proc = subprocess.Popen([str(SNAKEMAKE), "--cores", "2", TARGETS["rr_hill"], *config], cwd=w,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + 300
        while not registered(w) and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.02)
        os.killpg(proc.pid, signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait()
    kept = registered(w)  # at the kill (one more may have been registered since the check)
    assert _gone(proc.pid), "a process of the killed run survived"
    done = sorted(p.stem for p in finished_samples(w))
    assert 1 <= len(kept) <= len(done) < HILL_CURVATURES, (kept, done)
    assert not (w / "results" / "rr_hill" / "asperities.nc").exists()
    # what the killed run left: complete files under their own names, partial ones
    # (if the kill hit a write) only under hidden temporary names no rule reads
    for path in (w / "results").rglob("*.nc"):
        if path.name.startswith("."):
            assert path.name.endswith(".tmp.nc"), path
            continue
        ds = read_dataset(path)
        assert missing_attributes(ds) == [] and ds.attrs["history"], path
        assert (path.stat().st_mode & 0o777) == 0o666 & ~_umask(), path

    # the lock of the killed run stays until --unlock (Snakemake 9 cannot tell it is stale)
    locked = snakemake(w, TARGETS["rr_hill"], *config, check=False)
    assert locked.returncode != 0 and "--unlock" in locked.stdout + locked.stderr
    snakemake(w, "--unlock", *config)
    resumed = snakemake(w, TARGETS["rr_hill"], *config)  # the default profile, found by Snakemake
    # samples Snakemake had registered as finished are kept; one it had not (killed between
    # the file's rename and Snakemake's bookkeeping) is complete too, but is rerun: --rerun-incomplete
    assert HILL_CURVATURES - len(done) <= executed_jobs(resumed)["sample"] <= HILL_CURVATURES - len(kept)

    # the resumed run rewrote what the kill interrupted, and removed the temporary files
    assert not list((w / "results").rglob("*.tmp*"))
    names = sorted(str(p.relative_to(w / "results")) for p in (w / "results").rglob("*.nc"))
    keys = plan_keys(w, "rr_hill")
    assert names == sorted([f"rr_hill/{n}.nc" for n in ("asperities", "interface", "plan", "surface")]
                           + [f"samples/{k}.nc" for k in keys])
    assert assert_same_results(w / "results", base.reference, names) > 5000


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


# --------------------------------------------------------------- keep-going


def failing_scene() -> dict:
    """Three steep elastic cosine hills (width/height 3, nearly incompressible),
    each pressed to 99.9 % of its height or to the top of the grid (10 um),
    whichever is less: the largest curvature (0.35 1/um, 6.3 um high) is pressed
    to its foot and bulges past the edge of its top surface (ContactZoneError);
    the others (44 and 11 um high) stop at 23 % and 91 % and are solved."""
    scene = repo_scene("asperity_shape")
    scene["title"] = "three steep hills, the smallest pressed to its foot"
    scene["population"] = {"density": "nayak", "height_range": [-5.0, 5.0], "curvature_range": [0.05, 0.35],
                           "samples": {"height": 2, "curvature": 3, "interference": 61}}
    scene["asperity"] = {"model": "fe", "geometry": "cosine", "width_to_height": 3.0,
                         "max_height_fraction": 0.999, "scaling": "none"}
    scene["material"] = {"youngs_modulus": 65000.0, "poisson": 0.4999}
    return scene


def test_keep_going_one_failed_sample(tmp_path):
    """With --keep-going the failing sample leaves a record naming it and its step, the
    other samples are written, the gather fails naming the failed sample (no interface
    over a hole), and a second scene of the same run completes."""
    w = copy_workflow(tmp_path)
    write_scene(w, "rr_fail", failing_scene())
    hertz = repo_scene("asperity_shape_hertz")
    hertz["population"]["samples"]["interference"] = 61
    write_scene(w, "rr_hertz", hertz)
    config = ("--config", "scenes=[rr_fail,rr_hertz]", "accuracy=draft", "studies=False")
    proc = snakemake(w, "--keep-going", "results/rr_fail/interface.nc", "results/rr_hertz/interface.nc",
                     *config, check=False)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0, out
    plan = read_dataset(w / "results" / "rr_fail" / "plan.nc")
    keys = job_keys(plan)
    assert len(keys) == 3
    records = {k: read_dataset(w / "results" / "samples" / f"{k}.nc") for k in keys}
    failed = [k for k, ds in records.items() if ds.attrs["status"] == "failed"]
    assert len(failed) == 1, {k: ds.attrs["status"] for k, ds in records.items()}
    bad = records[failed[0]]
    assert bad.attrs["curvature"] == pytest.approx(0.35e6, rel=1e-12)  # the smallest hill
    error = bad.attrs["error"]
    assert f"sample {failed[0]}" in error and "at step" in error and "outer edge" in error, error
    for k, ds in records.items():
        if k not in failed:
            assert ds.attrs["status"] == "ok" and ds.sizes["step"] >= 40 and float(ds["force"].max()) > 0
    # the gather names what is missing instead of homogenizing over the hole
    message = f"1 of 3 samples missing from the gather; not homogenizing over a hole: {error}"
    assert message in (w / "results" / "rr_fail" / "logs" / "asperities.log").read_text()
    assert message in out
    assert not (w / "results" / "rr_fail" / "asperities.nc").exists()
    assert not (w / "results" / "rr_fail" / "interface.nc").exists()
    # the other scene of the run completed
    interface = read_dataset(w / "results" / "rr_hertz" / "interface.nc")
    assert float(interface["nominal_pressure"].max()) > 0


def test_write_leaves_no_stale_temporary_and_honours_the_umask(tmp_path):
    """A write removes what a killed write of the same file left (hidden temporaries),
    not those of other files, and gives the file the user's usual permissions."""
    from asperity.io.netcdf import write_dataset

    ds = xr.Dataset({"x": ("i", np.arange(3.0), {"units": "m", "long_name": "x"})},
                    coords={"i": ("i", np.arange(3), {"units": "1", "long_name": "index"})})
    stale = tmp_path / ".a.nc.k1ll3d.tmp.nc"
    other = tmp_path / ".b.nc.k1ll3d.tmp.nc"
    stale.write_bytes(b"CDF half")
    other.write_bytes(b"CDF half")
    path = write_dataset(ds, tmp_path / "a.nc", scene="s", title="t")
    assert not stale.exists() and other.exists()
    assert (path.stat().st_mode & 0o777) == 0o666 & ~_umask()
    np.testing.assert_array_equal(read_dataset(path)["x"].values, [0.0, 1.0, 2.0])
