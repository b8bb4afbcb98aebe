"""`asperity.fe` exports every geometry, material and driver; its modules share
only public names; its packages hold one concern each."""

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
