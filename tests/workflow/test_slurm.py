"""The SLURM profile (profiles/slurm) on a real, one-node SLURM cluster
on localhost, against a local run; and what the profile declares."""

from __future__ import annotations

import glob
import math
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from tests.workflow.conftest import REPO, SNAKEMAKE, assert_same_results, copy_workflow, nc_files

PROFILE = REPO / "profiles" / "slurm"
CLUSTER = PROFILE / "localhost-cluster.sh"
SCENE = "greenwood_williamson_fe"  # statistics -> plan -> one FE sample -> interface, verification
TARGETS = [f"results/{SCENE}/{name}" for name in ("surface.nc", "interface.nc", "verification.nc")]
# what differs between two runs by nature: when a file was written, how long a job took
RTOL = 1e-12


def _rules() -> set[str]:
    text = "\n".join(p.read_text() for p in (REPO / "workflow" / "rules").glob("*.smk"))
    return set(re.findall(r"^(?:rule|checkpoint)\s+(\w+)\s*:", text, flags=re.M))


def _profile() -> dict:
    return yaml.safe_load((PROFILE / "config.yaml").read_text())


def test_profile_declares_runtime_and_memory_of_every_rule():
    profile = _profile()
    rules = _rules()
    assert rules, "no rule found in workflow/rules/*.smk"
    declared = profile["set-resources"]
    assert set(declared) == rules, (
        f"rules without resources in {PROFILE}/config.yaml: {sorted(rules - set(declared))}; "
        f"entries naming no rule: {sorted(set(declared) - rules)}"
    )
    for rule, res in declared.items():
        assert isinstance(res.get("runtime"), int) and res["runtime"] > 0, rule
        assert isinstance(res.get("mem_mb"), int) and res["mem_mb"] > 0, rule
    # the FE jobs get more than the default, and every rule of a group exists
    assert declared["sample"]["mem_mb"] > profile["default-resources"]["mem_mb"]
    assert declared["sample"]["runtime"] > profile["default-resources"]["runtime"]
    assert set(profile["groups"]) <= rules
    # asperities and interface depend on the plan checkpoint: grouping them
    # stalls Snakemake 9 (see the profile), so they must stay ungrouped
    assert not {"asperities", "interface", "sample"} & set(profile["groups"])


def _skip_reason() -> str | None:
    if os.geteuid() != 0:
        return "needs root: installs slurm-wlm and munge with apt-get and runs slurmd"
    if shutil.which("apt-get") is None:
        return "needs apt-get: installs Debian's slurm-wlm and munge"
    return None


def _run(args, env, check=True):
    proc = subprocess.run([str(a) for a in args], env=env, capture_output=True, text=True, timeout=300)
    if check and proc.returncode != 0:
        raise AssertionError(f"{' '.join(map(str, args))} failed:\n{proc.stdout}\n{proc.stderr}")
    return proc


def _alive(pid_file: Path) -> bool:
    try:
        os.kill(int(pid_file.read_text()), 0)
    except (OSError, ValueError):
        return False
    return True


@pytest.fixture
def cluster():
    """A running one-node cluster; stopped (daemons checked gone) afterwards."""
    reason = _skip_reason()
    if reason:
        pytest.skip(reason)
    # munged wants every directory above its socket searchable: not pytest's 0700 tmp_path
    state = Path(tempfile.mkdtemp(prefix="asperity-slurm-"))
    state.chmod(0o755)
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("SLURM_", "SBATCH_", "SRUN_", "ASPERITY_SLURM"))}
    env["ASPERITY_SLURM_DIR"] = str(state)
    _run([CLUSTER, "install"], env)
    try:
        _run([CLUSTER, "start"], env)
        yield env
    finally:
        _run([CLUSTER, "stop"], env, check=False)
        pid_files = [state / "slurmctld.pid", state / "slurmd.pid", state / "munge" / "munged.pid"]
        running = [p.name for p in pid_files if _alive(p)]
        shutil.rmtree(state, ignore_errors=True)
        assert not running, f"daemons left running: {running}"


@pytest.mark.slow
@pytest.mark.slurm
@pytest.mark.workflow
def test_slurm_profile_runs_a_scene_like_a_local_run(cluster, tmp_path):
    (tmp_path / "slurm").mkdir()
    (tmp_path / "local").mkdir()
    on_cluster = copy_workflow(tmp_path / "slurm")
    local = copy_workflow(tmp_path / "local")
    # draft: the comparison of the two runs does not depend on the preset
    config = ["--config", f"scenes=[{SCENE}]", "accuracy=draft"]
    # the reference, on one core beside the cluster's jobs
    local_proc = subprocess.Popen(
        [str(SNAKEMAKE), "--cores", "1", *TARGETS, *config], cwd=local,
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        proc = subprocess.run(
            [str(SNAKEMAKE), "--workflow-profile", "slurm", *TARGETS,
             # the localhost cluster: 2 CPUs, no accounting database (squeue
             # reports job states), jobs of seconds (ask every 10 s, not 40)
             "--cores", "1", "--slurm-status-command", "squeue",
             "--slurm-init-seconds-before-status-checks", "10",
             "--seconds-between-status-checks", "10", *config],
            cwd=on_cluster, env=cluster, capture_output=True, text=True, timeout=600)
        local_out = local_proc.communicate(timeout=600)[0]
    finally:
        if local_proc.poll() is None:
            local_proc.kill()
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out
    assert local_proc.returncode == 0, local_out

    # every job went through sbatch, as the profile groups them: one SLURM
    # job for the scene's statistics (surface, plan), one per FE sample, one
    # each for asperities and interface, one for the evaluation (verification)
    submitted = re.findall(r"submitted with SLURM jobid (\d+) \(log: (\S+)\)", out)
    kinds = sorted(Path(log).relative_to(on_cluster / ".snakemake" / "slurm_logs").parts[0]
                   for _, log in submitted)
    assert kinds == sorted(["group_statistics_plan_surface", "rule_sample", "rule_asperities",
                            "rule_interface", "group_evaluation_verification"]), out
    # and SLURM ran them to completion (finished jobs stay visible for MinJobAge)
    states = _run(["squeue", "--states=all", "--noheader", "--format=%i %T"], cluster).stdout
    state_of = dict(line.split() for line in states.splitlines())
    assert all(state_of.get(jobid) == "COMPLETED" for jobid, _ in submitted), states

    files = nc_files(local / "results" / SCENE)
    assert files and files == nc_files(on_cluster / "results" / SCENE)
    compared = assert_same_results(local / "results" / SCENE, on_cluster / "results" / SCENE, files, RTOL)
    assert compared > 1000  # the interface curves, the FE sample, the plan
