"""The modules of `asperity` import one another without a cycle (DESIGN.md, layout).

Every import counts, the ones inside a function too: an import moved into a function
hides a cycle from the interpreter, not from a reader.  A package's ``__init__``
importing its own modules to re-export them is not a dependency of theirs and is
left out.
"""

import ast
import graphlib
import subprocess
import sys
from pathlib import Path

import pytest

import asperity

SRC = Path(asperity.__file__).parent.parent


def _modules() -> dict[str, tuple[Path, bool]]:
    """Dotted name -> (file, is a package) of every module under src/asperity."""
    out = {}
    for path in (SRC / "asperity").rglob("*.py"):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        package = parts[-1] == "__init__"
        out[".".join(parts[:-1] if package else parts)] = (path, package)
    return out


def import_graph() -> dict[str, set[str]]:
    """Module -> the asperity modules it imports (anywhere in its text)."""
    modules = _modules()
    graph = {}
    for name, (path, package) in modules.items():
        here = name if package else name.rpartition(".")[0]
        wanted = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                wanted |= {alias.name for alias in node.names}
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    parent = here.split(".")[: len(here.split(".")) - node.level + 1]
                    base = ".".join(parent + ([node.module] if node.module else []))
                # `from package import module` names the module; `from module import f`, the module
                wanted |= {f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base
                           for a in node.names}
        targets = set()
        for target in wanted:
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target and target != name and not (package and target.startswith(name + ".")):
                targets.add(target)
        graph[name] = targets
    return graph


def test_the_graph_sees_every_module_and_function_level_imports():
    graph = import_graph()
    assert len(graph) > 100
    # asperity.population.geometry imports the finite element package inside a function
    assert "asperity.fe" in graph["asperity.population.geometry"]
    assert "asperity.population.plan" in graph["asperity.population.gather"]


def test_no_import_cycle():
    try:
        tuple(graphlib.TopologicalSorter(import_graph()).static_order())
    except graphlib.CycleError as err:
        pytest.fail("import cycle: " + " -> ".join(err.args[1]))


#: the stages whose every job draws (their modules may import matplotlib at the top)
DRAWING_STAGES = {"figures", "accuracy", "studies"}


def test_data_jobs_start_without_matplotlib():
    """A stage that computes data imports the plots in its figure functions only: a job
    that writes a netCDF file starts without matplotlib (about 0.4 s a process)."""
    stages = sorted(p.stem for p in (SRC / "asperity" / "stages").glob("*.py")
                    if p.stem != "__init__" and p.stem not in DRAWING_STAGES)
    assert {"friction", "population", "reference", "routes", "surface"} <= set(stages)
    code = ("import sys\n" + "".join(f"import asperity.stages.{s}\n" for s in stages)
            + "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]", out.stdout
