"""The package layout: which layer may import which (docs/development.md, "Layout"), no import
cycle, no module over :data:`MAX_LINES` lines, and light imports.

Every module's imports are read with ``ast``: module level, inside functions (a lazy
import counts) and inside ``if TYPE_CHECKING:`` blocks (a type named for a hint only is
still an arrow between two files: the reader of one must read the other).
"""

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import REPO

PACKAGE = REPO / "sdc_cvx"

# layer -> the layers of ours it may import (besides itself); errors is open to all
RULES = {
    "errors": set(),
    "physics": set(),
    "inputs": {"physics"},
    "network": {"inputs", "physics"},
    "milp": set(),
    "solution": {"inputs", "physics", "report", "flight"},  # report, flight: inside plot(), fly()
    "planner": {"milp", "network", "inputs", "physics", "solution"},
    "report": {"inputs", "network", "physics"},  # a plan through report/plan_record.py
    "study": {"planner", "inputs", "milp", "report", "solution"},
    "flight": {"physics", "inputs", "solution", "report", "study"},
    "campaign": {"planner", "inputs", "milp", "network", "physics", "solution", "study", "report"},
    "gtoc9": {"flight", "inputs", "physics"},  # GTOC9's files, their validator, the search
    "cli": {
        "flight",
        "physics",
        "inputs",
        "network",
        "milp",
        "planner",
        "solution",
        "study",
        "report",
        "campaign",
        "gtoc9",
    },
    "__init__": {
        "flight",
        "physics",
        "inputs",
        "network",
        "milp",
        "planner",
        "solution",
        "study",
        "report",
        "campaign",
        "gtoc9",
    },
    "__main__": {"cli"},
}
"""The import rules of docs/development.md (the README's "Layout" section before)."""

THIRD_PARTY = {
    "physics": {"numpy"},
    "inputs": {"numpy", "pandas", "sgp4"},
    "network": {"numpy", "pandas"},
}
"""Layers restricted to a few third-party packages (besides the standard library)."""

CVXPY_LAYERS = {"milp", "planner", "campaign"}

MAX_LINES = 500
"""The longest a module of sdc_cvx may be (docs/development.md, the README's "Layout" before)."""


def layer_of(module: str) -> str:
    """``sdc_cvx.inputs.formats.tle`` -> ``inputs``; ``sdc_cvx`` -> ``__init__``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def module_name(path: Path) -> str:
    relative = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(relative.parts)
    if parts[-1] == "__init__" and len(parts) > 1:
        parts.pop()
    return ".".join(parts)


def is_module(name: str) -> bool:
    """Whether ``name`` (``sdc_cvx.report.plots``) is a module or package of ours."""
    if name.split(".")[0] != PACKAGE.name:
        return False
    path = PACKAGE.parent.joinpath(*name.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def imports(path: Path) -> set[str]:
    """Absolute names of the modules ``path`` imports (relative imports resolved), wherever
    the import stands (module level, a function, ``if TYPE_CHECKING:``).

    ``from a.b import c`` imports the module ``a.b.c`` when there is one (``from . import
    x``), else the module ``a.b`` (its name ``c``).
    """
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()

    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            for alias in node.names:
                submodule = f"{target}.{alias.name}"
                found.add(submodule if is_module(submodule) else target)
    return found


MODULES = sorted(PACKAGE.rglob("*.py"))


def import_graph() -> dict[str, set[str]]:
    """Each module of sdc_cvx -> the modules of sdc_cvx it imports (see :func:`imports`).

    An import of ``a.b.c`` is an edge to ``a.b.c`` alone: its parent packages run first
    but stand for themselves, so a package ``__init__`` that gathers its own submodules
    (``cli/__init__.py``) is no cycle, unless one of them imports it back, which is an
    edge here.
    """
    names = {module_name(path): path for path in MODULES}
    return {
        name: {other for other in imports(path) if other in names and other != name}
        for name, path in names.items()
    }


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The circles of ``graph``: its strongly connected components of more than one node
    (Tarjan's algorithm), each sorted, in sorted order.  A node in none is in no cycle."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for successor in sorted(graph[node]):
            if successor not in index:
                visit(successor)
                low[node] = min(low[node], low[successor])
            elif successor in stack:
                low[node] = min(low[node], index[successor])
        if low[node] == index[node]:  # node is the root of its component
            component = []
            while not component or component[-1] != node:
                component.append(stack.pop())
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(found)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_imports_follow_the_layers(path):
    name = module_name(path)
    layer = layer_of(name)
    assert layer in RULES, f"{name}: layer {layer!r} has no rule in docs/development.md's Layout"
    allowed = RULES[layer] | {layer, "errors"}
    ours = {m for m in imports(path) if m == "sdc_cvx" or m.startswith("sdc_cvx.")}
    wrong = sorted(m for m in ours if layer_of(m) not in allowed)
    assert not wrong, f"{name} ({layer}) may not import {wrong}; allowed: {sorted(allowed)}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_third_party_imports(path):
    name = module_name(path)
    layer = layer_of(name)
    others = {m.split(".")[0] for m in imports(path)} - {"sdc_cvx"}
    others -= set(sys.stdlib_module_names) | {"__future__"}
    if layer in THIRD_PARTY:
        assert others <= THIRD_PARTY[layer], f"{name} imports {sorted(others)}"
    if layer not in CVXPY_LAYERS:
        assert "cvxpy" not in others, f"{name}: cvxpy only in {sorted(CVXPY_LAYERS)}"
    if layer == "errors":
        assert not others


def test_solution_loads_matplotlib_only_to_draw():
    """``solution`` -> ``report`` is the one direction (``report`` reads a plan through
    the protocols of ``report/plan_record.py``): ``Solution.save`` writes through the run
    folder's module, and ``Solution.plot`` imports the figures, and matplotlib, when it is
    called."""
    code = "import sys, sdc_cvx.solution\nassert 'matplotlib' not in sys.modules\n"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_no_import_circle_between_files():
    """No file of sdc_cvx leads back to itself by its imports, lazy and ``TYPE_CHECKING``
    ones included (:func:`imports`): the files read in an order, each after those it uses.

    The convention for packages (:func:`import_graph`): an arrow goes to the module an
    import names, never to the packages above it.  ``from . import x`` and ``from .x
    import y`` in a submodule are arrows to the sibling ``x``, not to the package's
    ``__init__.py``; ``from .. import errors`` is an arrow to ``sdc_cvx/errors.py``; only a
    name that is no module (``from sdc_cvx import solve``) is an arrow to the package's
    ``__init__.py``.  So an ``__init__.py`` that re-exports its submodules is in no circle,
    unless one of them imports a name from it.
    """
    found = circles(import_graph())
    graph = import_graph()
    lines = [
        f"  {', '.join(circle)}:\n"
        + "\n".join(f"    {name} -> {', '.join(sorted(graph[name] & set(circle)))}"
                    for name in circle)
        for circle in found
    ]  # fmt: skip
    assert not found, f"{len(found)} import circle(s) between files:\n" + "\n".join(lines)


def test_circles_are_the_strongly_connected_components():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set(), "e": {"a", "f"}, "f": {"e"}}
    assert circles(graph) == [["a", "b", "c"], ["e", "f"]]
    assert circles({"a": {"b"}, "b": {"c"}, "c": set()}) == []


def test_imports_count_the_type_checking_blocks():
    """``cli/reading.py`` imports ``pandas`` and the catalog's module for its hints only."""
    found = imports(PACKAGE / "cli" / "reading.py")
    assert {"pandas", "sdc_cvx.inputs.catalog"} <= found


def test_imports_name_the_submodule_a_from_import_takes():
    assert "sdc_cvx.inputs.formats.csv" in imports(PACKAGE / "inputs" / "formats" / "__init__.py")
    cli = imports(PACKAGE / "cli" / "__init__.py")
    assert "sdc_cvx.cli.run" in cli and "sdc_cvx.cli" not in cli


def test_no_module_over_the_line_limit():
    lengths = {module_name(path): len(path.read_text(encoding="utf-8").splitlines())
               for path in MODULES}  # fmt: skip
    over = {name: lines for name, lines in lengths.items() if lines > MAX_LINES}
    assert not over, f"over {MAX_LINES} lines, split them: {over}"


PLANNER = PACKAGE / "planner"
PAPER = PLANNER / "paper"


def test_the_certified_side_does_not_import_the_paper_room():
    """The default method reads without the paper's: outside ``planner/paper/``, only
    ``api.py`` (which dispatches to both methods) imports it, lazily or not."""
    dispatchers = {PLANNER / "api.py", PLANNER / "__init__.py"}
    for path in sorted(set(PLANNER.rglob("*.py")) - set(PAPER.rglob("*.py")) - dispatchers):
        paper = {m for m in imports(path) if m.startswith("sdc_cvx.planner.paper")}
        assert not paper, f"{module_name(path)} imports {sorted(paper)}"


def test_the_planner_modules_import_one_another_without_a_cycle():
    """Lazy imports included: a cycle would make the modules' order of reading circular."""
    names = {module_name(path): path for path in PLANNER.rglob("*.py")}
    graph = {name: imports(path) & set(names) - {name} for name, path in names.items()}
    done, open_ = set(), []

    def visit(name):
        assert name not in open_, f"import cycle: {' -> '.join([*open_, name])}"
        if name in done:
            return
        open_.append(name)
        for other in sorted(graph[name]):
            visit(other)
        open_.pop()
        done.add(name)

    for name in sorted(graph):
        visit(name)


def test_errors_import_nothing_of_ours():
    ours = {m for m in imports(PACKAGE / "errors.py") if m.startswith("sdc_cvx")}
    assert not ours


@pytest.mark.parametrize(
    "module", ["sdc_cvx.inputs.formats", "sdc_cvx.physics.plan", "sdc_cvx.study.runner"]
)
@pytest.mark.slow
def test_a_module_imports_alone(module):
    """No import cycle: each of these works as the first import of a fresh interpreter."""
    subprocess.run([sys.executable, "-c", f"import {module}"], check=True)


@pytest.mark.slow
def test_import_sdc_cvx_is_light():
    """``import sdc_cvx`` (and the CLI module, for ``--help``) load neither CVXPY nor
    matplotlib nor pandas; the public names still resolve when used."""
    code = (
        "import sys, sdc_cvx, sdc_cvx.cli\n"
        "heavy = [m for m in ('cvxpy', 'matplotlib', 'pandas') if m in sys.modules]\n"
        "assert not heavy, heavy\n"
        "from sdc_cvx import Catalog, solve, sweep, CatalogError, SequentialSettings\n"
        "assert callable(solve) and callable(sweep) and SequentialSettings().max_iterations\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.slow
def test_the_default_run_needs_no_cvxpy_when_labels_solve_the_relaxations(tmp_path):
    """``python -m sdc_cvx run`` on the paper case (README's first command, here with n = 3
    for the suite's time: the same code paths): the certified
    search solves every relaxation by labels, so neither the run nor the check of its
    backend imports CVXPY (1-2 s of import, issue 21's end-to-end goal); the paper's
    method, a MILP every iteration, does."""
    probe = (
        "import atexit, runpy, sys\n"
        "atexit.register(lambda: print('cvxpy' in sys.modules, file=sys.stderr))\n"
        "sys.argv = ['sdc_cvx', *sys.argv[1:]]\n"
        "runpy.run_module('sdc_cvx', run_name='__main__')\n"
    )
    loaded = {}
    for method in ("certified", "paper"):
        done = subprocess.run(
            [sys.executable, "-c", probe, "run", "--method", method, "--n", "3", "--json",
             "--quiet", "--out", str(tmp_path / method)],
            capture_output=True, text=True, timeout=300,
        )  # fmt: skip
        assert done.returncode == 0, done.stderr
        assert json.loads(done.stdout)["status"] == "optimal" or method == "paper"
        loaded[method] = done.stderr.strip().splitlines()[-1]
    assert loaded == {"certified": "False", "paper": "True"}


def test_old_import_paths_still_work():
    import sdc_cvx
    from sdc_cvx import errors

    for name in sdc_cvx.__all__:
        assert getattr(sdc_cvx, name) is not None
    assert sdc_cvx.CatalogError is errors.CatalogError
    assert issubclass(sdc_cvx.MissionInfeasible, RuntimeError)
    assert issubclass(sdc_cvx.CatalogError, ValueError)
    with pytest.raises(AttributeError):
        sdc_cvx.no_such_name  # noqa: B018
