"""The Snakemake conventions the workflow keeps (issue 13): `snakemake --lint` finds
nothing, `snakefmt` would change nothing, every report figure has labels, the default
profile is found the documented way, and every rule depends on the version of the code
that computes it (asperity.versions)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from asperity.population.kinds import KINDS
from asperity.versions import VERSIONS

from .conftest import REPO, SNAKEMAKE, copy_workflow, snakemake

RULES = REPO / "workflow" / "rules"
SNAKEFMT = Path(sys.executable).with_name("snakefmt")


def rule_blocks() -> dict[str, str]:
    """Rule (or checkpoint) name -> its text, from the Snakefile and workflow/rules/*.smk."""
    blocks = {}
    for path in [REPO / "Snakefile", *sorted(RULES.glob("*.smk"))]:
        parts = re.split(r"(?m)^(?=(?:rule|checkpoint) \w+:)", path.read_text())
        for part in parts:
            m = re.match(r"(?:rule|checkpoint) (\w+):", part)
            if m:
                blocks[m.group(1)] = part
    return blocks


def test_snakefmt_would_change_nothing():
    proc = subprocess.run([str(SNAKEFMT), "--check", "Snakefile", "workflow/"], cwd=REPO,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr


@pytest.mark.slow
@pytest.mark.workflow
def test_lint_finds_nothing():
    proc = subprocess.run([str(SNAKEMAKE), "--lint"], cwd=REPO, capture_output=True, text=True,
                          timeout=300)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out
    assert "Lints for" not in out and "Congratulations" in out, out


def test_rules_files_hold_rules_only_and_every_rule_its_environment():
    """Functions live in common.smk (the lint's 'mixed rules and functions'); every rule
    with a script names the software environment of workflow/envs/."""
    for path in RULES.glob("*.smk"):
        if path.name != "common.smk":
            assert not re.search(r"(?m)^def ", path.read_text()), f"{path.name}: a function"
    env = re.search(r'^ENV = "(.+)"$', (RULES / "common.smk").read_text(), flags=re.M)
    assert env and (RULES / env.group(1)).resolve().is_file()
    for name, block in rule_blocks().items():
        if "script:" in block:
            assert re.search(r"conda:\s+ENV", block), f"rule {name}: no conda environment"


def test_every_report_figure_has_labels():
    """report(..., labels={...}) on every figure: the report's table shows its columns
    (the scene and what the figure is, or the study)."""
    calls = [b for b in rule_blocks().values() if "report(" in b]
    assert len(calls) >= 10
    for block in calls:
        for call in re.findall(r"report\((.*?)\n\s*\)", block, flags=re.S):
            labels = re.search(r"labels=\{(.*)\}", call, flags=re.S)
            assert labels and '"figure":' in labels.group(1), call
            assert ('"scene": "{scene}"' in labels.group(1)) == ("{scene}" in call.split(",")[0]), call
    assert re.search(r'^report: "workflow/report/workflow.rst"$', (REPO / "Snakefile").read_text(),
                     flags=re.M)
    assert (REPO / "workflow" / "report" / "workflow.rst").is_file()


def test_every_rule_depends_on_the_version_of_its_code():
    """params: version=code_version("<the rule>") (the sample's: its kind's), and the
    table of versions names the rules and kinds that exist, no other."""
    blocks = rule_blocks()
    for name, block in blocks.items():
        if "script:" not in block:
            continue
        expected = "version=sample_code_version," if name == "sample" else \
            f'version=code_version("{name}"),'
        assert expected in block, f"rule {name}: no {expected}"
    stages = {name for name, block in blocks.items() if "script:" in block} - {"sample"}
    assert set(VERSIONS) == stages | {f"sample:{kind}" for kind in KINDS}


@pytest.mark.slow
@pytest.mark.workflow
def test_snakemake_finds_the_default_profile(tmp_path):
    """`snakemake --cores 2` reads profiles/default/ without being asked (Snakemake 9
    looks for profiles/default beside the Snakefile); its settings apply."""
    workdir = copy_workflow(tmp_path)
    proc = snakemake(workdir, "-n", "--config", "scenes=[profile_cosine]", "studies=False")
    out = proc.stdout + proc.stderr
    assert "Using workflow specific profile profiles/default" in out, out
    none = snakemake(workdir, "-n", "--workflow-profile", "none", "--config",
                     "scenes=[profile_cosine]", "studies=False")
    assert "profiles/default" not in none.stdout + none.stderr


def test_every_script_calls_the_stages_module_of_its_rules_file_and_io_only():
    """The chain workflow/rules/X.smk -> workflow/scripts/*.py -> asperity.stages.X: a
    script imports the standard library, `asperity.io` and the one stages module named
    after its rules file, nothing else of the package."""
    import ast

    scripts = 0
    for path in sorted(RULES.glob("*.smk")):
        stage = path.stem
        for script in re.findall(r'script:\s+"\.\./scripts/(\w+\.py)"', path.read_text()):
            scripts += 1
            tree = ast.parse((REPO / "workflow" / "scripts" / script).read_text())
            for node in ast.walk(tree):
                if isinstance(node, ast.Import):
                    names = [(a.name, None) for a in node.names]
                elif isinstance(node, ast.ImportFrom):
                    names = [(node.module, a.name) for a in node.names]
                else:
                    continue
                for module, name in names:
                    top = module.split(".")[0]
                    where = f"{path.name} -> {script}: {module}{'.' + name if name else ''}"
                    if top != "asperity":
                        assert top in sys.stdlib_module_names, where
                    elif module == "asperity.stages":
                        assert name == stage, where
                    else:
                        assert module.startswith("asperity.io.") or module == f"asperity.stages.{stage}", where
    assert scripts >= 30


def test_every_module_says_what_it_holds():
    """The documentation's module map (docs/reference/modules.md, generated by
    docs/generate.py) is each module of src/asperity with the first line of its docstring:
    every module must have one."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("docs_generate", REPO / "docs" / "generate.py")
    generate = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generate)
    summaries = generate.module_summaries()
    root = REPO / "src" / "asperity"
    assert len(summaries) == sum(1 for _ in root.rglob("*.py"))
    missing = [name for name, line in summaries.items() if not line]
    assert not missing, f"modules without a docstring: {missing}"
    page = generate.modules_page()
    assert all(f"| `{name}` |" in page for name in summaries)


def test_the_verification_page_keeps_a_section_until_its_benchmark_writes_it_again(
        tmp_path, monkeypatch):
    """docs/generate.py: the benchmark outputs are not tracked, the sections they wrote
    are (docs/verification/sections/). Without its output a section is kept as it was;
    with it, renewed from it; never measured, it says so."""
    import importlib.util
    import json

    spec = importlib.util.spec_from_file_location("docs_generate", REPO / "docs" / "generate.py")
    generate = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generate)
    results, sections = tmp_path / "results", tmp_path / "sections"
    results.mkdir()
    monkeypatch.setattr(generate, "RESULTS", results)
    monkeypatch.setattr(generate, "SECTIONS", sections)
    page = generate.verification_page()  # nothing measured
    assert "surface-speed.md: not measured yet" in page
    speed = {"map": {"points": [4, 5], "undefined_share": 0.25},
             "times": {"form removal": {"cpu_s": 1.5, "wall_s": 1.75}},
             "date": "2026-12-07", "commit": "abcdef0123"}
    (results / "surface-speed.json").write_text(json.dumps(speed))
    page = generate.verification_page()
    assert "| form removal | 1.5 | 1.75 |" in page and "commit abcdef0" in page
    (results / "surface-speed.json").unlink()  # a clean clone: the section written is kept
    assert generate.verification_page() == page
    assert "| form removal | 1.5 | 1.75 |" in (sections / "surface-speed.md").read_text()
    # every tracked section of the repository is one the page is assembled from
    tracked = {p.name for p in (REPO / "docs" / "verification" / "sections").glob("*.md")}
    assert tracked == {e[0] for e in generate.VERIFICATION_SECTIONS if not isinstance(e, str)}
