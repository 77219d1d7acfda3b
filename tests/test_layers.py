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
    "racketdyn.errors": 1,
    "racketdyn.numerics": 1,
    "racketdyn.racket": 1,
    "racketdyn.ball": 1,
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
# response objects do" -- the one upward import allowed, and only inside a method named plot
PLOT_METHODS = {"plot"}


def _imports(path: Path) -> tuple[set[str], set[str]]:
    """Racketdyn modules imported at module level and inside functions (but ``.plot()``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    top: set[str] = set()
    lazy: set[str] = set()

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            is_function = isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef)
            if is_function and child.name in PLOT_METHODS:
                continue
            inside = in_function or is_function
            names: list[str] = []
            if isinstance(child, ast.Import):
                names = [alias.name for alias in child.names]
            elif isinstance(child, ast.ImportFrom) and child.module and child.level == 0:
                names = [child.module]
            if isinstance(child, ast.If) and _is_type_checking(child.test):
                continue  # annotations only: never imported at run time
            for name in names:
                if name == "racketdyn" or name.startswith("racketdyn."):
                    (lazy if inside else top).add(name)
            visit(child, inside)

    visit(tree, False)
    return top, lazy


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


MODULES = {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


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


def test_computation_loads_no_presentation() -> None:
    code = (
        "import sys; import racketdyn.modal, racketdyn.impact, racketdyn.measurement, "
        "racketdyn.io, racketdyn.sweep; "
        "print(sorted(m for m in ('matplotlib', 'jinja2', 'racketdyn.plotting', "
        "'racketdyn.report') if m in sys.modules))"
    )
    loaded = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout.strip()
    assert loaded == "[]", f"importing the computation layer loaded {loaded}"
