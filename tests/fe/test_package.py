"""`asperity.fe` exports every geometry, material and driver; its modules share
only public names; its packages hold one concern each; the whole package keeps to a
newcomer's budgets of lines."""

import ast
import importlib
import inspect
import pkgutil
from pathlib import Path

import asperity.fe as fe
from asperity.fe.discretization.geometry import Profile
from asperity.fe.materials.elastic import IsotropicElasticity

FE = Path(fe.__file__).parent


#: the packages of `asperity.fe` by concern, and the modules left at its top
PACKAGES = {"materials", "discretization", "contact", "solvers", "drivers"}
TOP = {"__init__", "presets", "errors", "outputs", "analytic"}


def _modules():
    return [importlib.import_module(m.name)
            for m in pkgutil.walk_packages([str(FE)], prefix="asperity.fe.") if not m.ispkg]


def test_the_package_is_laid_out_by_concern():
    assert {p.name for p in FE.iterdir() if (p / "__init__.py").is_file()} == PACKAGES
    assert {p.stem for p in FE.glob("*.py")} == TOP
    for package in PACKAGES:
        assert importlib.import_module(f"asperity.fe.{package}").__doc__, package


def test_every_geometry_material_and_driver_is_exported():
    wanted = set()
    for mod in _modules():
        for name, obj in vars(mod).items():
            if getattr(obj, "__module__", None) != mod.__name__ or name.startswith("_"):
                continue
            if inspect.isclass(obj) and issubclass(obj, (Profile, IsotropicElasticity)):
                wanted.add(name)
            # drivers: solve_* returning a Dataset
            if inspect.isfunction(obj) and name.startswith("solve_") and \
                    "Dataset" in str(inspect.signature(obj).return_annotation):
                wanted.add(name)
    # the laws of the surface: adhesion and friction
    wanted |= {"LennardJones", "FrictionLaw", "ShearResistance"}
    assert {"Paraboloid", "BodnerPartom", "J2Plasticity", "solve_asperity",
            "solve_asperity_history", "solve_asperity_adhesive", "solve_sliding"} <= wanted
    missing = wanted - set(fe.__all__)
    assert not missing, sorted(missing)
    for name in fe.__all__:
        assert getattr(fe, name) is not None


def test_no_module_imports_a_private_name_of_another():
    offenders = []
    for path in sorted(FE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and (
                    node.level >= 1 or (node.module or "").startswith("asperity.fe")):
                offenders += [f"{path.relative_to(FE)}: {a.name}" for a in node.names
                              if a.name.startswith("_")]
    assert not offenders, offenders


#: a newcomer's budgets: the lines of a module, and of a function without its docstring
MODULE_LINES, FUNCTION_LINES = 600, 120


def _function_lines(node) -> int:
    """Lines of a function from its ``def`` to its end, its docstring left out."""
    lines = node.end_lineno - node.lineno + 1
    first = node.body[0]
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) \
            and isinstance(first.value.value, str):
        lines -= first.end_lineno - first.lineno + 1
    return lines


def test_modules_and_functions_keep_to_their_budgets():
    """Every module of the package, `asperity.fe` and the rest."""
    over = []
    for path in sorted(FE.parent.rglob("*.py")):
        text = path.read_text()
        name = path.relative_to(FE.parent)
        if text.count("\n") > MODULE_LINES:
            over.append(f"{name}: {text.count(chr(10))} lines > {MODULE_LINES}")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and \
                    _function_lines(node) > FUNCTION_LINES:
                over.append(f"{name}: {node.name} has {_function_lines(node)} lines "
                            f"> {FUNCTION_LINES}")
    assert not over, "\n".join(over)


#: calls that solve a linear system
LINEAR_SOLVES = {"solve", "spsolve", "splu", "lu_solve", "cho_solve", "lstsq", "factorized"}


def _converges(node) -> bool:
    """An ``if`` that leaves its loop (break or return) on a comparison with a tolerance."""
    if not isinstance(node, ast.If) or not any(
            isinstance(m, (ast.Name, ast.Attribute))
            and "tol" in (m.id if isinstance(m, ast.Name) else m.attr).lower()
            for c in ast.walk(node.test) if isinstance(c, ast.Compare) for m in ast.walk(c)):
        return False
    return any(isinstance(b, (ast.Break, ast.Return)) for s in node.body for b in ast.walk(s))


def _newton_loops(source: str) -> list[int]:
    """Lines of the loops of `source` that iterate Newton: a loop that solves a
    linear system and leaves when a residual is within a tolerance."""
    found = []
    for loop in ast.walk(ast.parse(source)):
        if not isinstance(loop, (ast.For, ast.While)):
            continue
        calls = {n.func.attr if isinstance(n.func, ast.Attribute) else getattr(n.func, "id", "")
                 for n in ast.walk(loop) if isinstance(n, ast.Call)}
        if calls & LINEAR_SOLVES and any(_converges(n) for n in ast.walk(loop)):
            found.append(loop.lineno)
    return found


def test_newton_is_iterated_only_in_solvers():
    # the detector sees a Newton loop written out
    assert _newton_loops(
        "for it in range(20):\n"
        "    r = residual(x)\n"
        "    if norm(r) <= tol:\n"
        "        break\n"
        "    x = x - np.linalg.solve(tangent(x), r)\n") == [1]
    # a loop of linear solves, or of time steps with a predictor solve, is not Newton
    assert _newton_loops("for k in range(3):\n    y = np.linalg.solve(A, b[k])\n") == []
    assert _newton_loops("while t < end:\n    x = x + np.linalg.solve(D, f)\n"
                         "    if error > tol:\n        continue\n    t += h\n") == []
    outside = [p for p in sorted(FE.rglob("*.py")) if "solvers" not in p.relative_to(FE).parts]
    outside += sorted((FE.parent / "uniaxial").rglob("*.py"))  # a material point's mixed control
    offenders = [f"{p.relative_to(FE.parent)}:{line}" for p in outside
                 for line in _newton_loops(p.read_text())]
    assert not offenders, offenders
