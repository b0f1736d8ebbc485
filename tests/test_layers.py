"""The package's import graph: no cycles, and no module imports from a layer above it.

Layers, bottom first: models and the shared errors; glsl and the model sources; render,
plots and presets; the command line; the features (app, grading, web, measured, ...).
Lazy imports inside functions count too: they are still dependencies.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "lab"

LAYERS = {  # module -> layer; a feature package's modules default to the top layer
    "lab": 0,
    "lab.errors": 0,
    "lab.geometry": 0,
    "lab.resources": 0,
    "lab.constants": 0,
    "lab.gl": 0,
    "lab.models": 0,
    "lab.reference": 0,
    "lab.bootstrap": 0,
    "lab.plotscale": 0,
    "lab.describe": 0,
    "lab.describe_views": 0,
    "lab.nonfinite": 0,
    "lab.measured": 0,
    "lab.measured.sh": 0,
    "lab.glsl": 1,
    "lab.brdf_explorer": 1,
    "lab.sources": 1,
    "lab.measured.merl": 1,
    "lab.measured.model": 1,
    "lab.render": 2,
    "lab.views": 2,
    "lab.plots": 2,
    "lab.presets": 2,
    "lab.figures": 2,
    "lab.diagrams": 2,
    "lab.bench": 2,
    "lab.measured.tabulate": 2,
    "lab.ibl": 2,
    "lab.ibl.environments": 2,
    "lab.ibl.integrator": 2,
    "lab.ibl.furnace": 2,
    "lab.ibl.chisquare": 2,
    "lab.ibl.bench": 2,
    "lab.ibl.figures": 2,
    "lab.ibl.convergence": 2,
    "lab.ibl.png": 2,
    "lab.ibl.sobol": 2,
    "lab.ibl.table": 2,
    "lab.cli": 3,
}
TOP = 4
LAYER_NAMES = ["models", "glsl/sources", "render", "cli", "features"]


def module_files() -> dict[str, Path]:
    modules = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        modules[name] = path
    return modules


def import_graph() -> dict[str, set[str]]:
    modules = module_files()
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        deps = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("lab"):
                for alias in node.names:
                    child = f"{node.module}.{alias.name}"
                    deps.add(child if child in modules else node.module)
            elif isinstance(node, ast.Import):
                deps.update(a.name for a in node.names if a.name.startswith("lab"))
        graph[name] = {d for d in deps if d in modules and d != name}
    return graph


def layer(module: str) -> int:
    if module in LAYERS:
        return LAYERS[module]
    if module.startswith("lab.views."):
        return LAYERS["lab.views"]  # a view's module: what it computes and plots
    if module.count(".") >= 2 or module == "lab.__main__":
        return TOP  # a module of a feature package (lab.app.window, lab.grading.cli, ...)
    raise AssertionError(
        f"{module} has no layer: add it to LAYERS in tests/test_layers.py "
        "(or put it in a feature package)"
    )


def test_no_module_imports_from_a_layer_above() -> None:
    graph = import_graph()
    upward = [
        f"{src} ({LAYER_NAMES[layer(src)]}) imports {dst} ({LAYER_NAMES[layer(dst)]})"
        for src, deps in sorted(graph.items())
        for dst in sorted(deps)
        if layer(dst) > layer(src)
    ]
    assert not upward, "imports that run up the layers:\n" + "\n".join(upward)


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle as a list of modules, or None (depth-first search)."""
    state: dict[str, int] = {}  # 1 on the current path, 2 finished
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for dep in sorted(graph[node]):
            if state.get(dep) == 1:
                return path[path.index(dep) :] + [dep]
            if dep not in state and (cycle := visit(dep)):
                return cycle
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state and (cycle := visit(node)):
            return cycle
    return None


def test_no_import_cycles() -> None:
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_the_checks_can_fail() -> None:
    """The cycle finder finds a planted cycle, and an upward import is caught."""
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None
    assert layer("lab.app.window") > layer("lab.cli") > layer("lab.render") > layer("lab.models")
