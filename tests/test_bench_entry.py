"""`make bench CASE=...`: one entry point for every benchmark (benchmarks/run.py)."""

import re
import subprocess
from pathlib import Path

from benchmarks import run

ROOT = Path(__file__).resolve().parents[1]


def test_every_case_names_a_script_that_takes_its_default_arguments():
    for case, (script, default, _) in run.STUDIES.items():
        path = ROOT / "benchmarks" / script
        assert path.is_file(), case
        # every default option is one the script's argument parser defines
        text = path.read_text()
        for option in (a for a in default if a.startswith("--")):
            assert re.search(rf"add_argument\(\s*['\"]{option}['\"]", text), (case, option)


def test_an_unknown_case_is_a_one_line_error_naming_the_key(capsys):
    assert run.run_case("no-such-case", []) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "CASE" in err and "no-such-case" in err


def test_make_bench_lists_its_cases():
    out = subprocess.run(["make", "-s", "bench", "CASE=list"], cwd=ROOT, capture_output=True,
                         text=True, check=True).stdout
    assert {line.split()[0] for line in out.splitlines()} == {"kernels", *run.STUDIES}
