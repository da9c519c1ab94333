"""The layering of the package (docs/architecture.md), checked on the source of every module.

Layers, lowest first: utilities -> core and the sample shapes (datasets) ->
domains (planar, mesh, volume) -> routing (``_dispatch``, ``api``) -> uses of
axes (compare, metrics, gis) -> entry points (the ``cli`` package, one module
per command, and the package namespace). A module may import its
own layer and the layers below; the three domains never import one
another; module-level imports form no cycle. The few imports made inside a
function that reach a higher layer are listed in ``UPWARD`` with their reason:
a new one fails this test until it is written down there and in the doc.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"

#: Layer of each top-level part of the package.
LAYERS = {
    "errors": 0, "_version": 0, "_typing": 0, "_jit": 0, "_optional": 0, "_progress": 0, "_help": 0,
    "core": 1, "datasets": 1,
    "planar": 2, "mesh": 2, "volume": 2,
    "_dispatch": 3, "api": 3,
    "compare": 4, "metrics": 4, "gis": 4,
    "cli": 5, "_entry": 5, "__main__": 5, "": 5,
}
DOMAINS = {"planar", "mesh", "volume"}
#: Modules that sit above their folder's layer: none (each command is a module of ``cli``).
OWN_LAYER: dict[str, int] = {}

#: Function-level imports into a higher layer, with the reason they are there.
UPWARD = {
    ("medialaxis.core.result", "medialaxis._dispatch"):
        "MedialAxis.prune re-prunes with the function of the domain that made the axis, "
        "which only the dispatcher knows (imported when prune is called)",
}


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted((SRC / "medialaxis").rglob("*.py")):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def _imports(path: Path, name: str) -> list[tuple[str, bool]]:
    """(imported module, at module level) for every import of medialaxis in a file."""
    tree = ast.parse(path.read_text(), str(path))
    top = set(map(id, tree.body))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([module] if module else []))
            targets = [module] if module != "medialaxis" else [f"medialaxis.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        else:
            continue
        for target in targets:
            if target == "medialaxis" or target.startswith("medialaxis."):
                found.append((target, id(node) in top))
    return found


def _part(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def _layer(module: str) -> int:
    if module in OWN_LAYER:
        return OWN_LAYER[module]
    return LAYERS[_part(module)]


MODULES = _modules()
IMPORTS = {name: _imports(path, name) for name, path in MODULES.items()}


def test_every_part_has_a_layer():
    assert {_part(m) for m in MODULES} <= set(LAYERS), "add new parts of the package to LAYERS and the doc"


def test_the_domains_never_import_one_another():
    bad = [(m, t) for m, imports in IMPORTS.items() for t, _ in imports
           if _part(m) in DOMAINS and _part(t) in DOMAINS and _part(t) != _part(m)]
    assert not bad


def test_no_import_reaches_a_higher_layer_unless_written_down():
    bad = []
    for module, imports in IMPORTS.items():
        for target, at_top in imports:
            target_module = target if target in MODULES else target.rpartition(".")[0]
            if _layer(target_module) <= _layer(module):
                continue
            if not at_top and (module, target_module) in UPWARD:
                continue
            bad.append((module, target, "module level" if at_top else "in a function"))
    assert not bad, "imports into a higher layer (see docs/architecture.md):\n" + "\n".join(map(str, bad))


def test_the_written_down_exceptions_are_still_needed():
    used = {(m, t if t in MODULES else t.rpartition(".")[0]) for m, imports in IMPORTS.items() for t, top in imports
            if not top}
    assert set(UPWARD) <= used


def test_module_level_imports_form_no_cycle():
    graph = {m: {t if t in MODULES else t.rpartition(".")[0] for t, top in imports if top} - {m}
             for m, imports in IMPORTS.items()}
    # a package imports its own submodules to re-export them: the package and its children are one node
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w.startswith(v + ".") or v.startswith(w + "."):
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    assert not cycles


@pytest.mark.parametrize("name", sorted(MODULES))
def test_modules_stay_small(name):
    """Modules over ~400 lines hold more than one stage (docs/architecture.md); split them along their seams."""
    lines = len(MODULES[name].read_text().splitlines())
    assert lines <= LINE_LIMIT.get(name, 420), f"{name}: {lines} lines"


#: Modules allowed over the limit, with their size (they may shrink, not grow): none today.
LINE_LIMIT: dict[str, int] = {}


#: Most modules a folder of the package may hold (docs/architecture.md, "Size").
MAX_MODULES_PER_FOLDER = 20


def test_no_folder_holds_more_than_twenty_modules():
    counts: dict[str, int] = {}
    for path in MODULES.values():
        if path.name != "__init__.py":
            folder = str(path.parent.relative_to(SRC))
            counts[folder] = counts.get(folder, 0) + 1
    crowded = {folder: n for folder, n in counts.items() if n > MAX_MODULES_PER_FOLDER}
    assert not crowded, f"split these folders into subpackages by stage: {crowded}"
