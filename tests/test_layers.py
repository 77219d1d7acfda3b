"""The house's layers (docs/develop.md, "Layers"): each imports only those below it, no circles.

Read from the source with :mod:`ast`, so the test sees every import, also those inside
functions, without running any of them.
"""

from __future__ import annotations

import ast
import graphlib
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "racketdyn"

# module prefix -> layer; the longest matching prefix wins (docs/develop.md, "Layers")
LAYERS: dict[str, int] = {
    "racketdyn.__about__": 1,
    "racketdyn._display": 1,
    "racketdyn._grammar": 1,
    "racketdyn.errors": 1,
    "racketdyn.plausibility": 1,
    "racketdyn.numerics": 1,
    "racketdyn.racket": 1,
    "racketdyn.ball": 1,
    "racketdyn.hand": 1,
    "racketdyn.modal.model": 1,
    "racketdyn.measurement.records": 1,
    "racketdyn.data": 1,
    "racketdyn.contact": 2,  # builds laws from a racket (and its files) and a ball
    "racketdyn.io": 2,
    "racketdyn.measurement": 2,
    "racketdyn.modal": 2,
    "racketdyn.racket_modal": 2,
    "racketdyn.impact": 2,
    "racketdyn.rig": 2,
    "racketdyn.sweep": 2,
    "racketdyn.testing": 2,  # test oracles (known modes) for users' tests; core nouns only
    "racketdyn.workflows": 3,
    "racketdyn.plotting": 4,
    "racketdyn.report": 4,
    "racketdyn.cli": 5,
}
LAYER_NAMES = {1: "core", 2: "computation", 3: "workflows", 4: "presentation", 5: "CLI"}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _layer(module: str) -> int | None:
    best = ""
    for prefix in LAYERS:
        if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > len(best):
            best = prefix
    return LAYERS[best] if best else None


# STYLE.md: "A `.plot()` on a result object may import presentation lazily, as python-control's
# response objects do" -- the one upward import allowed: presentation, inside a method `plot`
PLOT_METHODS = {"plot"}
PRESENTATION = ("racketdyn.plotting", "racketdyn.report")


def _imports(path: Path, package: str | None = None) -> tuple[set[str], set[str]]:
    """Racketdyn modules imported at module level and inside functions.

    Seen: ``import racketdyn.x``, ``from racketdyn.x import y`` (and ``racketdyn.x.y`` when ``y``
    is a module), ``from racketdyn import x``, relative imports, and
    ``importlib.import_module("racketdyn.x")`` with a literal name.  Not counted: imports under
    ``if TYPE_CHECKING:`` (never run) and of presentation inside a ``plot`` method.
    """
    tree = ast.parse(path.read_text(encoding="utf-8"))
    if package is None:
        package = _module_name(path)
        if path.name != "__init__.py":
            package = package.rpartition(".")[0]
    top: set[str] = set()
    lazy: set[str] = set()

    def targets(node: ast.AST) -> list[str]:
        if isinstance(node, ast.Import):
            return [alias.name for alias in node.names]
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            submodules = [f"{module}.{alias.name}" for alias in node.names]
            found = [name for name in submodules if name in MODULES]
            if len(found) < len(submodules):  # names defined in the module itself
                found.append(module)
            return found
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Attribute | ast.Name)
            and getattr(node.func, "attr", getattr(node.func, "id", "")) == "import_module"
            and node.args
            and isinstance(node.args[0], ast.Constant)
            and isinstance(node.args[0].value, str)
        ):
            return [node.args[0].value]
        return []

    def visit(node: ast.AST, in_function: bool, in_plot: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child.test):
                continue  # annotations only: never imported at run time
            is_function = isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef)
            plot = in_plot or (is_function and child.name in PLOT_METHODS)
            inside = in_function or is_function
            for name in targets(child):
                if not (name == "racketdyn" or name.startswith("racketdyn.")):
                    continue
                if plot and name.startswith(PRESENTATION):
                    continue
                (lazy if inside else top).add(name)
            visit(child, inside, plot)

    visit(tree, False, False)
    return top, lazy


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


MODULES = {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def test_the_import_reader_sees_every_form(tmp_path: Path) -> None:
    """The forms a review found the first reader missed (issue 11)."""
    source = tmp_path / "probe.py"
    source.write_text(
        "import importlib\n"
        "from racketdyn import plotting\n"
        "from ..report import page\n"
        "from . import grid\n"
        "def f():\n"
        "    importlib.import_module('racketdyn.cli')\n"
        "class Result:\n"
        "    def plot(self):\n"
        "        from racketdyn.plotting import primitives\n"
        "        from racketdyn.workflows import run\n",
        encoding="utf-8",
    )
    top, lazy = _imports(source, package="racketdyn.impact")
    assert top == {"racketdyn.plotting", "racketdyn.report.page", "racketdyn.impact.grid"}
    assert lazy == {"racketdyn.cli", "racketdyn.workflows.run"}


def test_every_module_has_a_layer() -> None:
    unplaced = [module for module in MODULES if module != "racketdyn" and _layer(module) is None]
    assert not unplaced, f"give these modules a layer in tests/test_layers.py: {unplaced}"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m != "racketdyn"))
def test_imports_only_go_down(module: str) -> None:
    own = _layer(module)
    assert own is not None
    top, lazy = _imports(MODULES[module])
    upward = sorted(
        f"{name} ({LAYER_NAMES[layer]})"
        for name in top | lazy
        if (layer := _layer(name)) is not None and layer > own
    )
    assert not upward, f"{module} ({LAYER_NAMES[own]}) imports a higher layer: {upward}"


@pytest.mark.slow
def test_no_import_circle() -> None:
    graph: dict[str, set[str]] = {}
    for module, path in MODULES.items():
        top, lazy = _imports(path)
        graph[module] = {name for name in top | lazy if name in MODULES and name != module}
    try:
        graphlib.TopologicalSorter(graph).prepare()
    except graphlib.CycleError as error:
        pytest.fail(f"import circle: {' -> '.join(error.args[1])}")


def test_modal_core_knows_no_racket() -> None:
    """The modal package works on any structure: no racket nouns, no racket layer."""
    offenders = []
    for module, path in MODULES.items():
        if not module.startswith("racketdyn.modal"):
            continue
        top, lazy = _imports(path)
        offenders += [
            f"{module} -> {name}"
            for name in top | lazy
            if name.startswith(("racketdyn.racket_modal", "racketdyn.impact", "racketdyn.rig"))
            or name == "racketdyn.racket"
        ]
    assert not offenders, offenders


@pytest.mark.slow
def test_computation_loads_no_presentation() -> None:
    code = (
        "import sys; import racketdyn.modal, racketdyn.impact, racketdyn.measurement, "
        "racketdyn.io, racketdyn.sweep, racketdyn.racket_modal, racketdyn.rig, racketdyn.contact, "
        "racketdyn.workflows; "
        "print(sorted(m for m in ('matplotlib', 'jinja2', 'racketdyn.plotting', "
        "'racketdyn.report') if m in sys.modules))"
    )
    loaded = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.strip()
    assert loaded == "[]", f"importing the computation layer loaded {loaded}"


# --- issue 23: the presentation layer draws, it never runs the physics ------------------------
COMPUTING = (
    "racketdyn.impact",
    "racketdyn.rig",
    "racketdyn.measurement",
    "racketdyn.workflows",
    "racketdyn.modal",
    "racketdyn.racket_modal",
    "racketdyn.sweep",
)
"""Packages whose computations plotting/ and report/ must not call (their types and constants
they may import: a figure draws what the step computed, docs/develop.md "Layers"); the modal
ones since the identified shapes' figures (Figs 4–6, AutoMAC) draw what identify evaluated,
the sweep since its summary figures draw the curves the sweep computed."""
STILL_EVALUATING: dict[str, str] = {}
"""Presentation modules that still evaluate a modal model, and why: the debt, in one place."""
PURE_HELPERS = {
    "racketdyn.impact.result.shown_speed_index",  # which of the run's speeds a table shows
    "racketdyn.impact.result.invalidate_table",  # NaN in the flagged rows of a table read back
    "racketdyn.impact.result.is_valid",  # which rows of a table hold numbers (ok or filled)
    "racketdyn.impact.result.extreme_row",  # the valid row of a headline's highest/lowest value
    "racketdyn.impact.result.model_note",  # "(transient model)" after a filled row's number
    # the approach energy ½ μ V² of a row's own masses and speeds: the one definition the 30 %
    # rule and the report's vibration share use (arithmetic on the file's numbers, no model)
    "racketdyn.impact.approximate.approach_energy",
    "racketdyn.workflows.run.sha256",  # a file's hash, for the provenance table
    "racketdyn.workflows.run.write_pending",  # the step's computed data into its files
    "racketdyn.workflows.shape_figures.is_racket_model",  # whether modes have racket names
}
MODAL = ("racketdyn.modal", "racketdyn.racket_modal")
EVALUATING = ("mode_shapes_at", "modal_constants", "synthesise", "frf_at")
"""Methods of a modal model that evaluate it: presentation never calls them."""
"""Functions of those packages that compute no model: allowed in presentation."""


def _runtime_imports(path: Path, package: str) -> list[tuple[str, str, int]]:
    """``(module, name, line)`` of every racketdyn import run at run time (not under
    ``if TYPE_CHECKING:``); ``name`` is ``""`` for ``import racketdyn.x``."""
    found: list[tuple[str, str, int]] = []

    def visit(node: ast.AST) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and _is_type_checking(child.test):
                continue
            if isinstance(child, ast.Import):
                found.extend((alias.name, "", child.lineno) for alias in child.names)
            elif isinstance(child, ast.ImportFrom):
                module = child.module or ""
                if child.level:
                    base = package.split(".")
                    module = ".".join(base[: len(base) - child.level + 1] + [module] * bool(module))
                found.extend((module, alias.name, child.lineno) for alias in child.names)
            visit(child)

    visit(ast.parse(path.read_text(encoding="utf-8")))
    return [(m, n, line) for m, n, line in found if m == "racketdyn" or m.startswith("racketdyn.")]


def _computations_imported(path: Path, package: str) -> list[str]:
    """The computations of :data:`COMPUTING` a module imports at run time: functions (not in
    :data:`PURE_HELPERS`) and whole modules (a module reaches every computation in it)."""
    import importlib
    import inspect

    offenders = []
    for module, name, line in _runtime_imports(path, package):
        target = f"{module}.{name}" if name else module
        if not target.startswith(COMPUTING) or target in PURE_HELPERS:
            continue
        if not name or target in MODULES:
            offenders.append(f"line {line}: module {target}")
            continue
        value = getattr(importlib.import_module(module), name)
        if inspect.isroutine(value) or inspect.ismodule(value):
            offenders.append(f"line {line}: {target}")
    return offenders


def test_the_computation_reader_sees_the_physics(tmp_path: Path) -> None:
    source = tmp_path / "probe.py"
    source.write_text(
        "from typing import TYPE_CHECKING\n"
        "from racketdyn.impact import predict\n"
        "from racketdyn.impact.result import ImpactResult, STATUS_OK, shown_speed_index\n"
        "from racketdyn.workflows.figure_data import PaperFigures\n"
        "import racketdyn.rig\n"
        "if TYPE_CHECKING:\n"
        "    from racketdyn.impact.transient import predict_transient\n"
        "def draw():\n"
        "    from racketdyn.impact.swing import predict_swing\n"
        "    from racketdyn.workflows.predict import run_predict\n"
        "    from ..impact.comparison import simulate_histories\n",
        encoding="utf-8",
    )
    assert _computations_imported(source, "racketdyn.plotting") == [
        "line 2: racketdyn.impact.predict",
        "line 5: module racketdyn.rig",
        "line 9: racketdyn.impact.swing.predict_swing",
        "line 10: racketdyn.workflows.predict.run_predict",
        "line 11: racketdyn.impact.comparison.simulate_histories",
    ]


@pytest.mark.parametrize(
    "module", sorted(m for m in MODULES if m.startswith(("racketdyn.plotting", "racketdyn.report")))
)
def test_presentation_runs_no_physics(module: str) -> None:
    """Issue 23: a figure or the report draws what its step computed; it never calls ``predict``,
    ``predict_transient``, ``predict_swing``, the rig, the measurement chain or a workflow."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    offenders = _computations_imported(path, package)
    if module in STILL_EVALUATING:
        offenders = [o for o in offenders if not o.split()[-1].startswith(MODAL)]
    assert not offenders, f"{module} imports computations: {offenders}"
    calls = [] if module in STILL_EVALUATING else _evaluations_called(path)
    assert not calls, f"{module} evaluates a modal model: {calls}"


def _evaluations_called(path: Path) -> list[str]:
    """``line N: .method`` for each call of an :data:`EVALUATING` method in a module."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return [
        f"line {node.lineno}: .{node.func.attr}"
        for node in ast.walk(tree)
        if isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and node.func.attr in EVALUATING
    ]


def test_the_evaluation_reader_sees_a_model_evaluated(tmp_path: Path) -> None:
    source = tmp_path / "probe.py"
    source.write_text(
        "def draw(model, points):\n"
        "    shape = model.mode_shapes_at(points)\n"
        "    return shape, model.mode_shapes\n",
        encoding="utf-8",
    )
    assert _evaluations_called(source) == ["line 2: .mode_shapes_at"]
    assert _computations_imported(source, "racketdyn.plotting") == []
    source.write_text("from racketdyn.modal.residues import mac\n", encoding="utf-8")
    assert _computations_imported(source, "racketdyn.plotting") == [
        "line 1: racketdyn.modal.residues.mac"
    ]
