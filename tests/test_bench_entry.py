"""`make bench CASE=...`: one entry point for every benchmark (benchmarks/run.py)."""

import inspect
import re
import subprocess
from pathlib import Path

from benchmarks import run

ROOT = Path(__file__).resolve().parents[1]


def _options_of_the_parser(script: str, arguments: list[str]) -> list[str]:
    """The options of `arguments` that the script's argument parser does not define."""
    text = (ROOT / "benchmarks" / script).read_text()
    return [option for option in (a for a in arguments if a.startswith("--"))
            if not re.search(rf"add_argument\(\s*['\"]{option}['\"]", text)]


def test_every_case_names_a_script_that_takes_its_default_arguments():
    for case, study in run.STUDIES.items():
        assert (ROOT / "benchmarks" / study.script).is_file(), case
        # every default option is one the script's argument parser defines
        assert _options_of_the_parser(study.script, study.default) == [], case


def test_every_case_has_a_short_form_that_writes_under_benchmarks_out_or_a_reason():
    """The short form (`make bench CASE=short`, what CI runs) runs each study with its short
    arguments: options its parser defines, every path under benchmarks/out/ (the commands
    run from the repository), its JSON under benchmarks/out/short/, never benchmarks/results/
    (tracked: the docs' verification page is made from it).  A case without them says why."""
    for case, study in run.STUDIES.items():
        if study.short is None:
            assert run.SHORT_SKIPPED.get(case, "").strip(), case
            continue
        assert case not in run.SHORT_SKIPPED, case
        assert _options_of_the_parser(study.script, study.short) == [], case
        assert not any("benchmarks/results" in a for a in study.short), case
        paths = [a for a in study.short if "/" in a]
        assert all(a.startswith("benchmarks/out/") for a in paths), (case, paths)
        assert all((ROOT / a).resolve().is_relative_to(ROOT / "benchmarks" / "out") for a in paths), case
        out = study.short[study.short.index("--out") + 1]
        assert out.startswith("benchmarks/out/short/"), case
    assert set(run.SHORT_SKIPPED) <= set(run.STUDIES)


def test_every_kernel_has_a_small_case():
    for name, fn, _ in run.CASES:
        assert inspect.signature(fn).parameters["small"].default is False, name


def test_an_unknown_case_is_a_one_line_error_naming_the_key(capsys):
    assert run.run_case("no-such-case", []) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "CASE" in err and "no-such-case" in err


def test_make_bench_lists_its_cases():
    out = subprocess.run(["make", "-s", "bench", "CASE=list"], cwd=ROOT, capture_output=True,
                         text=True, check=True).stdout
    assert {line.split()[0] for line in out.splitlines()} == {"kernels", *run.STUDIES, "short"}
