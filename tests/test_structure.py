"""The design rules the code base keeps (docs/architecture.md): the package's layers, each importing only
the layers below it (imports inside functions included), the closed form nothing of the simulation; at most 10
modules directly in ``pounding/``; no import cycle; no module over 500 lines; every compiled (numba) function calls compiled functions of its
own file only, so that numba's on-disk cache, which does not see an edit to a callee in another file, cannot
go stale; the fast path of ``pounding estimate`` imports no plotting or dashboard library."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("pounding", "dashboard")


def _modules() -> dict[str, Path]:
    modules = {}
    for package in PACKAGES:
        for path in (ROOT / package).rglob("*.py"):
            parts = path.relative_to(ROOT).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            modules[name] = path
    return modules


def _imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """Every module of the project that ``name`` imports, at module level or inside a function."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            candidates = [target] + [f"{target}.{alias.name}" for alias in node.names]
        elif isinstance(node, ast.Import):
            candidates = [alias.name for alias in node.names]
        else:
            continue
        found.update(c for c in candidates if c in modules and c != name)
    return found


LAYERS = (
    ("pounding", "pounding.presets"),  # the package-wide basics: the modules directly in pounding/, the presets
    ("pounding.random_vibration", "pounding.mechanics"),
    ("pounding.hazard",),
    ("pounding.case",),
    ("pounding.closed_form", "pounding.simulation"),
    ("pounding.studies", "pounding.export"),
    ("pounding.report",),
    ("pounding.cli",),
    ("pounding.__main__",),
    ("dashboard",),
)
"""The layers, lowest first. A module imports from its own package, and from the layers below its own; packages
that share a layer are independent of each other (the closed form and the simulation above all)."""


def _package(module: str) -> str:
    """The entry of :data:`LAYERS` that ``module`` belongs to."""
    if module.count(".") == 1 and module != "pounding.__main__" and (ROOT / "pounding" / f"{module.split('.')[1]}.py").is_file():
        return "pounding"
    entries = [entry for layer in LAYERS for entry in layer[1 if layer[0] == "pounding" else 0:]
               if module == entry or module.startswith(entry + ".")]
    return max(entries, key=len) if entries else ("pounding" if module == "pounding" else "")


def _rank(package: str) -> int:
    return next(i for i, layer in enumerate(LAYERS) if package in layer)


def test_every_module_belongs_to_a_layer():
    assert all(_package(name) for name in _modules())


@pytest.mark.parametrize("name", sorted(_modules()))
def test_no_module_imports_from_a_layer_above_or_beside_its_own(name):
    modules = _modules()
    own = _package(name)
    wrong = sorted(target for target in _imports(name, modules[name], modules)
                   if _package(target) != own and _rank(_package(target)) >= _rank(own))
    assert wrong == [], f"{name} ({own}) imports {wrong}"


def test_the_closed_form_imports_nothing_from_the_simulation():
    modules = _modules()
    found = {name: sorted(t for t in _imports(name, path, modules) if t.startswith("pounding.simulation"))
             for name, path in modules.items() if name.startswith("pounding.closed_form")}
    assert len(found) > 10 and not any(found.values()), found


def test_the_package_root_holds_at_most_10_modules():
    files = sorted(p.name for p in (ROOT / "pounding").glob("*.py"))
    assert "__init__.py" in files and len(files) <= 10, files


def test_the_layer_rule_catches_an_upward_import(tmp_path):
    """The rule itself: an import of the simulation from the closed form, or of the command line from the
    mechanics, is found (inside a function too)."""
    source = "def f():\n    from pounding.simulation.monte_carlo import simulate\n    import pounding.cli.commands\n"
    path = tmp_path / "probe.py"
    path.write_text(source)
    modules = {**_modules(), "pounding.mechanics.probe": path}
    found = _imports("pounding.mechanics.probe", path, modules)
    assert {"pounding.simulation.monte_carlo", "pounding.cli.commands"} <= found
    assert all(_rank(_package(t)) > _rank("pounding.mechanics") for t in found)


def test_there_is_no_import_cycle():
    modules = _modules()
    graph = {name: _imports(name, path, modules) for name, path in modules.items()}
    # A cycle through a package and its own submodule (pounding -> pounding.x -> pounding) is not one here.
    state: dict[str, int] = {}
    cycles = []

    def visit(node: str, trail: list[str]) -> None:
        state[node] = 1
        for target in sorted(graph[node]):
            if state.get(target) == 1:
                cycle = trail[trail.index(target):] + [target]
                if not all(c == cycle[0] or c.startswith(cycle[0] + ".") or cycle[0].startswith(c + ".") for c in cycle):
                    cycles.append(" -> ".join(cycle))
            elif target not in state:
                visit(target, trail + [target])
        state[node] = 2

    for name in sorted(graph):
        if name not in state:
            visit(name, [name])
    assert cycles == []


@pytest.mark.parametrize("name", sorted(_modules()))
def test_no_module_is_over_500_lines(name):
    assert len(_modules()[name].read_text().splitlines()) <= 500


def _compiled_functions(path: Path) -> dict[str, ast.FunctionDef]:
    out = {}
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.FunctionDef) and any(
            (isinstance(d, ast.Call) and getattr(d.func, "id", "") == "njit") or getattr(d, "id", "") == "njit"
            for d in node.decorator_list
        ):
            out[node.name] = node
    return out


def test_every_compiled_call_tree_lives_in_one_file():
    compiled = {name: path for path in _modules().values() for name in _compiled_functions(path)}
    crossing = []
    for path in _modules().values():
        for name, function in _compiled_functions(path).items():
            for node in ast.walk(function):
                if isinstance(node, ast.Call):
                    callee = node.func.id if isinstance(node.func, ast.Name) else getattr(node.func, "attr", "")
                    if callee in compiled and compiled[callee] != path:
                        crossing.append(f"{path.name}:{name} calls {compiled[callee].name}:{callee}")
    assert crossing == []


def test_an_estimate_imports_no_plotting_library():
    code = ("import io, contextlib, sys\nfrom pounding.cli.commands import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    main(['estimate', 'section5-T2-0.4', '--json'])\n"
            "print(sorted(m for m in ('bokeh', 'holoviews', 'panel', 'matplotlib', 'dask', 'pandas') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.strip() == "[]"


def test_listing_the_cases_loads_no_numerical_library():
    """``pounding cases`` (and the parser every command builds) stays light: the simulation, numba and scipy
    load when a command computes, not when the command line starts."""
    code = ("import io, contextlib, sys\nfrom pounding.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    main(['cases'])\n"
            "print(sorted(m for m in ('numba', 'scipy', 'pounding.simulation', 'dask', 'bokeh') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert out.stdout.strip() == "[]"


def test_every_data_file_of_the_package_is_in_the_wheel():
    """pyproject's package data covers every file under pounding/ that is not Python (presets, the accuracy
    data), so that a non-editable install has them."""
    import fnmatch
    import tomllib

    patterns = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["pounding"]
    package = ROOT / "pounding"
    data = [p.relative_to(package).as_posix() for p in package.rglob("*")
            if p.is_file() and p.suffix not in (".py", ".pyc", ".nbi", ".nbc") and "__pycache__" not in p.parts]
    assert data and all(any(fnmatch.fnmatch(name, pattern) for pattern in patterns) for name in data)




ENTRY_POINTS = {"main"}
"""``main`` is the entry point of each runnable module (the command line, the dashboard's server, an exported
OpenSeesPy model): one per program, not a concept defined twice."""


def _public_definitions(path: Path) -> list[str]:
    """The public functions, classes and upper-case constants a module defines at its top level."""
    names = []
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.append(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names += [t.id for t in targets if isinstance(t, ast.Name) and t.id.isupper()]
    return [n for n in names if not n.startswith("_") and n not in ENTRY_POINTS]


def _defined_twice(modules: dict[str, Path]) -> dict[str, list[str]]:
    where: dict[str, list[str]] = {}
    for name, path in sorted(modules.items()):
        for definition in _public_definitions(path):
            where.setdefault(definition, []).append(name)
    return {definition: places for definition, places in where.items() if len(places) > 1}


def test_no_public_name_is_defined_in_two_modules():
    """One name per concept: a public function, class or constant is defined once; the others import it."""
    assert _defined_twice(_modules()) == {}


def test_the_duplicate_finder_finds_a_duplicate(tmp_path):
    (tmp_path / "a.py").write_text("LIMIT = 20\ndef expected_peak():\n    pass\n")
    (tmp_path / "b.py").write_text("LIMIT = 10\nclass Other:\n    pass\ndef expected_peak():\n    pass\n")
    found = _defined_twice({"a": tmp_path / "a.py", "b": tmp_path / "b.py"})
    assert found == {"LIMIT": ["a", "b"], "expected_peak": ["a", "b"]}


# --- the library names its own arguments; only the command line names flags (issue 30) ----------------------

FLAGS_ALLOWED = ("pounding/cli/", "pounding/export/opensees_script.py")  # the command line; a script with its own argparse


def _flags(path: Path) -> list[str]:
    """Every string constant of ``path`` (an f-string's literal parts included) that starts with ``--`` and a
    letter: a command-line flag, as ``raise ArgumentError("--records", ...)`` or ``f"--seed {seed}"`` would write."""
    import re

    return [f"{path.name}:{node.lineno}: {node.value!r}" for node in ast.walk(ast.parse(path.read_text()))
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and re.match(r"--[A-Za-z]", node.value)]


def test_the_library_names_no_command_line_flag():
    found = [flag for path in sorted((ROOT / "pounding").rglob("*.py"))
             if not path.relative_to(ROOT).as_posix().startswith(FLAGS_ALLOWED) for flag in _flags(path)]
    assert found == []


def test_the_flag_scan_finds_a_flag_named_by_the_library(tmp_path):
    planted = tmp_path / "planted.py"
    planted.write_text('from pounding.errors import ArgumentError\n\n\ndef check(records, seed):\n'
                       '    if records < 1:\n        raise ArgumentError("--records", "must be >= 1")\n'
                       '    return f"--seed {seed}", "give --records at most that", "-- a dash", "---"\n')
    assert _flags(planted) == ["planted.py:6: '--records'", "planted.py:7: '--seed '"]


_MEASURED_RANGE = re.compile(r"[-+]\d[\d,.]* ?% to [-+]?\d[\d,.]* ?%")
"""A measured range of errors written out (``-19 % to +13 %``): such figures belong in pounding/data/accuracy.json."""


def _measured_ranges(path: Path) -> list[str]:
    """The string constants and f-string parts of ``path`` (docstrings aside) that write out a measured range."""
    tree = ast.parse(path.read_text())
    docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                  if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                  and node.body and isinstance(node.body[0], ast.Expr) and isinstance(node.body[0].value, ast.Constant)}
    for body in [tree.body] + [n.body for n in ast.walk(tree) if isinstance(n, ast.ClassDef)]:
        docstrings |= {id(b.value) for a, b in zip(body, body[1:]) if isinstance(a, (ast.Assign, ast.AnnAssign))
                       and isinstance(b, ast.Expr) and isinstance(b.value, ast.Constant)}  # attribute docstrings
    return [node.value for node in ast.walk(tree) if isinstance(node, ast.Constant) and isinstance(node.value, str)
            and id(node) not in docstrings and _MEASURED_RANGE.search(node.value)]


def test_measured_accuracy_comes_from_the_data_file_only():
    """What users read of the measured accuracy is read from pounding/data/accuracy.json, never typed into code."""
    found = {name: ranges for name, path in _modules().items() if (ranges := _measured_ranges(path))}
    assert found == {}


def test_the_accuracy_scan_finds_a_typed_range(tmp_path):
    planted = tmp_path / "planted.py"
    planted.write_text('"""Docstrings may cite -19 % to +13 %."""\nWARNING = "it was -19 % to +13 % off"\n'
                       'def f(x):\n    return f"measured +34 % to +630 % off, {x}"\n')
    assert _measured_ranges(planted) == ["it was -19 % to +13 % off", "measured +34 % to +630 % off, "]
