"""The packaging conventions a Python user relies on.

- ``python -m orccad_app`` is the ``orccad`` command, and ``--version`` reads the one version
  source (``orccad_app.__version__``, which pyproject reads too);
- the package is marked typed (``py.typed``);
- every third-party package that the core or a built-in plugin imports is declared in
  pyproject's dependencies, or in an extra for an optional feature imported lazily (an
  undeclared import works here only by accident, because some other dependency happens to
  pull it in).
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
import tomllib
from importlib.metadata import packages_distributions
from pathlib import Path

import orccad_app

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
#: Modules whose distribution installs them where importlib.metadata cannot map them back
#: (cmeel wheels put ``pinocchio`` under ``cmeel.prefix``).
DISTRIBUTION_OF = {"pinocchio": "pin"}
FEATURE_EXTRAS = ("cluster", "report", "lsp")
FIRST_PARTY = {"orccad_app", "orccad_control", "orccad_arm3dof", "orccad_observers", "orccad_auv"}


def _requirement_name(requirement: str) -> str:
    return re.split(r"[\s\[<>=!~;]", requirement, maxsplit=1)[0].lower().replace("_", "-")


def _imported_top_level(folder: Path) -> set[str]:
    names: set[str] = set()
    for path in folder.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
    return names


def test_python_dash_m_runs_the_command_and_reports_the_single_version():
    result = subprocess.run([sys.executable, "-m", "orccad_app", "--version"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == f"orccad {orccad_app.__version__}"
    assert "version" in PYPROJECT["project"]["dynamic"]
    assert "version" not in PYPROJECT["project"]
    assert PYPROJECT["tool"]["hatch"]["version"]["path"] == "orccad_app/__init__.py"


def test_the_package_is_marked_typed():
    assert (Path(orccad_app.__file__).parent / "py.typed").is_file()


def _declared() -> set[str]:
    """Distributions named in the dependencies or an extra; ``dask[distributed]`` also
    declares ``distributed`` (an extra of a requirement named after the package it adds)."""
    project = PYPROJECT["project"]
    requirements = list(project["dependencies"])
    for extra in project.get("optional-dependencies", {}).values():
        requirements += extra
    names = {_requirement_name(r) for r in requirements}
    for requirement in requirements:
        extras = re.search(r"\[([^\]]*)\]", requirement)
        if extras:
            names |= {e.strip().lower() for e in extras.group(1).split(",")}
    return names


def test_every_imported_third_party_package_is_declared():
    declared = _declared()
    # a feature extra's packages are imported lazily by that feature, which says how to
    # install them when they are missing (orccad campaign --cluster, --report)
    extras = PYPROJECT["project"]["optional-dependencies"]
    declared |= {_requirement_name(r) for name in FEATURE_EXTRAS for r in extras[name]}
    folders = [ROOT / "orccad_app"] + [ROOT / "plugins" / name for name in FIRST_PARTY
                                       if (ROOT / "plugins" / name).is_dir()]
    imported = set().union(*(_imported_top_level(folder) for folder in folders))
    third_party = imported - FIRST_PARTY - set(sys.stdlib_module_names)
    distributions = packages_distributions()
    undeclared = {}
    for module in sorted(third_party):
        found = distributions.get(module) or [DISTRIBUTION_OF.get(module, module)]
        names = {d.lower().replace("_", "-") for d in found}
        if not names & declared:
            undeclared[module] = sorted(names)
    assert not undeclared, f"imported but not declared in pyproject: {undeclared}"


def _children_of_orccad_app(package: Path = ROOT / "orccad_app") -> set[str]:
    names = {p.stem for p in package.glob("*.py")} | {
        p.name for p in package.iterdir() if (p / "__init__.py").is_file()}
    return names - {"__init__"}


def _contract(contract_id: str) -> dict:
    contracts = PYPROJECT["tool"]["importlinter"]["contracts"]
    return next(c for c in contracts if c["id"] == contract_id)


def test_the_import_contracts_name_every_part_of_the_core():
    """A new sub-package or module of orccad_app must be placed in the import contracts,
    or it would escape them silently."""
    children = _children_of_orccad_app()
    layered = set()
    for layer in _contract("layers")["layers"]:
        layered |= {name.strip().strip("()") for name in re.split(r"[|:]", layer)}
    assert children - layered == set(), "not in any layer of the 'layers' contract"
    core = {m.removeprefix("orccad_app.")
            for m in _contract("core-without-textual")["source_modules"]}
    missing = children - core - {"tui", "__main__"}
    assert not missing, f"missing from core-without-textual's source_modules: {sorted(missing)}"
    without_pygls = {m.removeprefix("orccad_app.")
                     for m in _contract("core-without-pygls")["source_modules"]}
    missing = children - without_pygls - {"lsp", "__main__"}
    assert not missing, f"missing from core-without-pygls's source_modules: {sorted(missing)}"
    forbidden = {m.removeprefix("orccad_app.")
                 for m in _contract("plugins-through-the-api")["forbidden_modules"]}
    missing = children - forbidden - {"plugin_api", "__main__"}
    assert not missing, f"missing from plugins-through-the-api's forbidden_modules: {sorted(missing)}"


def test_the_sil_packages_are_each_in_a_layer_by_job():
    """orccad_app/sil is split by job (generate, build, controller, lockstep, realtime, runs):
    a new module or package there must take its place in the 'sil-by-job' layers, so that
    generating C never imports running it."""
    children = _children_of_orccad_app(ROOT / "orccad_app" / "sil")
    layered = set()
    for layer in _contract("sil-by-job")["layers"]:
        layered |= {name.strip() for name in layer.split("|")}
    assert children - layered == set(), "not in any layer of the 'sil-by-job' contract"
    assert children == layered, "a layer of 'sil-by-job' names nothing"


def test_every_test_marked_slow_exists():
    """tests/slow.py names tests by file and function: a renamed test must be renamed there."""
    from tests.slow import SLOW
    for node in sorted(SLOW):
        path, function = node.split("::")
        assert f"def {function}(" in (ROOT / path).read_text(encoding="utf-8"), node


def test_no_package_imports_another_packages_private_names():
    """A name with a leading underscore is its package's own: another package of orccad_app
    (or a built-in plugin) that needs it asks for a public one (issue 36: codegen imported
    reactive's ``_divide``)."""
    found = []
    for path in sorted([*(ROOT / "orccad_app").rglob("*.py"), *(ROOT / "plugins").rglob("*.py")]):
        relative = path.relative_to(ROOT)
        own = relative.parts[1] if relative.parts[0] == "orccad_app" else relative.parts[0]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not (isinstance(node, ast.ImportFrom) and node.module
                    and node.module.startswith("orccad_app.")):
                continue
            other = node.module.split(".")[1]
            found += [f"{relative}:{node.lineno}: {node.module}.{alias.name}"
                      for alias in node.names if alias.name.startswith("_") and other != own]
    assert not found, "\n".join(found)
