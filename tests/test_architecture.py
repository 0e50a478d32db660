"""The package's shape: imports run one way (no import cycle anywhere in fickcam,
counting imports inside functions too; fickcam/diffusion's modules import only at their
top except the heavy optional libraries), the diffusion engine's sub-packages are layered
in the order of its data flow (each imports only itself and the stages below it), and its
functions stay short. Module boundaries follow concepts, not a line count."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "fickcam"
HEAVY = {"fipy", "matplotlib", "dask", "distributed"}  # may be imported inside functions
MAX_FUNCTION_LINES = 80


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _resolve(module: str, node: ast.ImportFrom, is_package: bool) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[:len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(tree, everywhere: bool):
    """The import statements of a module: all of them, or those at module level."""
    if everywhere:
        return [n for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))]
    return [n for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))]


def import_graph(everywhere_in: str = "fickcam.diffusion") -> dict[str, set[str]]:
    """module -> fickcam modules it imports (``from . import x`` counts as importing the
    submodule x when there is one): at module level, and inside functions too for the
    modules under ``everywhere_in``."""
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {name: set() for name in modules}
    for name, path in modules.items():
        tree = ast.parse(path.read_text())
        for node in _imports(tree, name.startswith(everywhere_in)):
            targets = []
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = _resolve(name, node, path.name == "__init__.py")
                targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base
                           for a in node.names]
            for target in targets:
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != name and target.startswith("fickcam"):
                    graph[name].add(target)
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Every strongly connected component with more than one module (Tarjan 1972)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in graph[node]:
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_the_import_graph_check_finds_a_cycle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


@pytest.mark.slow
def test_no_import_cycle_inside_fickcam():
    # every import counts, also those deferred inside functions: a cycle held apart by a
    # function-level import is still a cycle
    assert cycles(import_graph(everywhere_in="fickcam")) == []


def test_no_module_imports_its_own_package():
    graph = import_graph()
    upward = {name: sorted(t for t in targets if name.startswith(t + "."))
              for name, targets in graph.items()}
    assert {k: v for k, v in upward.items() if v} == {}


def _functions(tree):
    return [n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]


def test_diffusion_imports_at_module_top_except_heavy_libraries():
    late = []
    for path in sorted((PACKAGE / "diffusion").rglob("*.py")):
        for function in _functions(ast.parse(path.read_text())):
            for node in ast.walk(function):
                if isinstance(node, ast.Import):
                    names = [a.name for a in node.names]
                elif isinstance(node, ast.ImportFrom):
                    names = ["." * node.level + (node.module or "")]
                else:
                    continue
                late += [f"{path.name}:{node.lineno} {n}" for n in names
                         if n.split(".")[0] not in HEAVY]
    assert late == []


# The stages of fickcam/diffusion in the order of its data flow, lowest first: a module in
# one stage imports only modules of its own stage and of the stages before it. The package
# itself (``solve``, ``plan``: dispatch) sits on top of them all.
STAGES = ("problem", "accuracy", "forcing", "exact", "planform", "superposition", "operators",
          "stepping", "models", "nonfickian")
ENGINE = "fickcam.diffusion"


def stage_of(module: str) -> int:
    """Rank of a diffusion module's stage; the package's top-level modules rank above all."""
    parts = module.split(".")
    return STAGES.index(parts[2]) if len(parts) > 2 and parts[2] in STAGES else len(STAGES)


def upward_imports(graph: dict[str, set[str]]) -> list[tuple[str, str]]:
    """(module, target) pairs where a diffusion module imports a later stage."""
    return sorted((name, target) for name, targets in graph.items()
                  if name.startswith(ENGINE + ".") for target in targets
                  if target.startswith(ENGINE) and stage_of(target) > stage_of(name))


def test_the_layering_check_finds_an_upward_import():
    graph = {f"{ENGINE}.stepping.march": {f"{ENGINE}.models.plane", f"{ENGINE}.problem.results"},
             f"{ENGINE}.models.plane": {f"{ENGINE}.stepping.march"}}
    assert upward_imports(graph) == [(f"{ENGINE}.stepping.march", f"{ENGINE}.models.plane")]


def test_every_diffusion_module_lives_in_a_stage():
    loose = sorted(p.name for p in (PACKAGE / "diffusion").glob("*.py")
                   if p.stem not in ("__init__", "dispatch"))
    folders = sorted(p.name for p in (PACKAGE / "diffusion").iterdir()
                     if p.is_dir() and (p / "__init__.py").exists())
    assert loose == [] and folders == sorted(STAGES)


def test_diffusion_stages_import_only_the_stages_below_them():
    assert upward_imports(import_graph(everywhere_in="fickcam")) == []


def test_no_private_name_is_imported_across_modules():
    """A ``_name`` is its module's own: another module that needs it needs a public name."""
    private = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module != "__future__":
                private += [f"{path.relative_to(PACKAGE)}:{node.lineno} {a.name}"
                            for a in node.names
                            if a.name.startswith("_") and not a.name.endswith("__")]
    assert private == []


def modules_importing(library: str) -> list[str]:
    """The fickcam modules that import ``library`` anywhere (at the top or in a function)."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in _imports(ast.parse(path.read_text()), everywhere=True):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if node.level == 0 else [])
            if any(name == library or name.startswith(library + ".") for name in names):
                found.append(_module_name(path))
                break
    return found


def test_fipy_is_imported_in_one_backend_module():
    assert modules_importing("fipy") == ["fickcam.diffusion.operators.fipy_backend"]


def test_the_benchmarks_are_not_in_the_installed_package():
    """They read the repository's configs/ and tests/data/: they live in benchmarks/."""
    assert not list(PACKAGE.glob("bench*.py"))


# The geometries answer what the engine asks of them (``diffusion.problem.geometry``): no
# module switches on a geometry's class, except to refuse one it cannot take
GEOMETRY_CLASSES = {"Sheet", "Disc", "Bar", "CamPlate", "LinkBar"}
GEOMETRY_MODULE = PACKAGE / "diffusion" / "problem" / "geometry.py"


def _names_in(node) -> set[str]:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | {
        n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)}


def _refuses(node, parents) -> bool:
    """An ``if not isinstance(...)`` (or ``type(...) not in``) whose body raises."""
    parent = parents.get(node)
    while parent is not None and not isinstance(parent, ast.If):
        parent = parents.get(parent)
    return parent is not None and any(isinstance(s, ast.Raise) for s in parent.body) and (
        isinstance(parent.test, ast.UnaryOp) and isinstance(parent.test.op, ast.Not)
        or isinstance(parent.test, ast.Compare)
        and any(isinstance(op, ast.NotIn) for op in parent.test.ops))


def geometry_switches(source: str) -> list[int]:
    """Lines of ``isinstance(x, <geometry class>)`` and ``type(x) is/in <geometry class>``
    that do not refuse a type."""
    tree = ast.parse(source)
    parents = {child: node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "isinstance":
            checked = _names_in(node.args[1]) if len(node.args) > 1 else set()
        elif isinstance(node, ast.Compare) and isinstance(node.left, ast.Call) and getattr(
                node.left.func, "id", "") == "type":
            checked = set().union(*(_names_in(c) for c in node.comparators))
        else:
            continue
        if checked & GEOMETRY_CLASSES and not _refuses(node, parents):
            found.append(node.lineno)
    return found


def test_the_geometry_switch_check_finds_a_switch():
    assert geometry_switches("if isinstance(g, (Sheet, Disc)):\n    x = 1\n") == [1]
    assert geometry_switches("y = 2 if type(g) is Bar else 3\n") == [1]
    assert geometry_switches("if not isinstance(g, Bar):\n    raise TypeError('no')\n") == []
    assert geometry_switches("if isinstance(g, dict):\n    x = 1\n") == []


def test_no_module_switches_on_a_geometry_class():
    switches = [f"{path.relative_to(PACKAGE)}:{line}"
                for path in sorted(PACKAGE.rglob("*.py")) if path != GEOMETRY_MODULE
                for line in geometry_switches(path.read_text())]
    assert switches == []


#: the two mechanism responses, being split where the mechanisms become objects: this set
#: only shrinks (empty it when they are)
def test_functions_stay_short_everywhere():
    long_functions = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for function in _functions(ast.parse(path.read_text())):
            length = function.end_lineno - function.lineno + 1
            if length > MAX_FUNCTION_LINES:
                long_functions.append((str(path.relative_to(PACKAGE)), function.name, length))
    assert long_functions == []


# An import inside a function is there to keep a heavy dependency off the start-up path,
# and says so in a comment on the line or just above its group of imports; every other
# import is at the top of its module
def late_imports_without_a_reason(source: str) -> list[int]:
    """Lines of imports inside functions with no comment on them or above their group."""
    lines = source.split("\n")
    found = []
    for function in _functions(ast.parse(source)):
        for node in ast.walk(function):
            if not isinstance(node, (ast.Import, ast.ImportFrom)):
                continue
            above = node.lineno - 2
            while above >= 0 and lines[above].strip().startswith(("from ", "import ")):
                above -= 1
            if "#" not in lines[node.lineno - 1] and not (
                    above >= 0 and lines[above].strip().startswith("#")):
                found.append(node.lineno)
    return found


def test_the_late_import_check_finds_one_without_a_reason():
    assert late_imports_without_a_reason("def f():\n    import json\n    return json\n") == [2]
    assert late_imports_without_a_reason(
        "def f():\n    # deferred: heavy\n    import a\n    import b\n    return a, b\n") == []


def test_imports_inside_functions_say_why():
    late = [f"{path.relative_to(PACKAGE)}:{line}" for path in sorted(PACKAGE.rglob("*.py"))
            for line in late_imports_without_a_reason(path.read_text())]
    assert late == []


# The package's stages in the order they depend on each other, lowest first: a module
# imports only its own stage and the stages before it (imports inside functions count).
# The scene reads the domains' specs (``*.spec``, the mechanism registry, the diffusion
# model names and accuracy check) but no implementation of them (below).
LAYERS = (
    ("errors", "_version", "extras", "messages", "files", "schema", "quantities", "drawing"),  # foundations
    ("diffusion",),
    ("materials",),
    ("climate",),
    ("mechanisms", "cam", "linkage", "elastic"),
    ("scene",),
    ("results",),
    ("simulation",),
    ("compensation", "sweep", "fit", "plotting"),
    ("cli",),
    ("fickcam",),  # the package's own __init__: the public functions
)
#: what the scene may read of later stages: their specs, and the mechanism registry (the
#: protocol and the table of mechanism types; the implementations live in cam/ and linkage/)
SCENE_READS = ("fickcam.cam.spec", "fickcam.linkage.spec", "fickcam.materials",
               "fickcam.mechanisms", "fickcam.diffusion.accuracy.budget",
               "fickcam.diffusion.problem.definition")


def layer_of(module: str) -> int:
    stage = module.split(".")[1] if "." in module else "fickcam"
    return next(i for i, layer in enumerate(LAYERS) if stage in layer)


def against_the_flow(graph: dict[str, set[str]]) -> set[tuple[str, str]]:
    """(stage, stage) pairs where a module imports a later stage."""
    found = set()
    for name, targets in graph.items():
        for target in targets:
            if layer_of(target) > layer_of(name):
                found.add((name.split(".")[1] if "." in name else "fickcam",
                           target.split(".")[1] if "." in target else "fickcam"))
    return found


def test_the_flow_check_finds_an_import_against_it():
    assert against_the_flow({"fickcam.diffusion.x": {"fickcam.cli.main"},
                             "fickcam.cli.main": {"fickcam.diffusion.x"}}) == {("diffusion", "cli")}


def test_every_stage_has_its_place():
    stages = {p.stem if p.is_file() else p.name for p in PACKAGE.iterdir()
              if p.suffix == ".py" or (p / "__init__.py").exists()} - {"__init__"}
    placed = set().union(*LAYERS)
    assert stages - placed == set()


def test_imports_follow_the_flow():
    found = against_the_flow(import_graph(everywhere_in="fickcam"))
    assert found == set()


def test_the_scene_reads_no_implementation_of_the_later_stages():
    graph = import_graph(everywhere_in="fickcam")
    later = [(name, target) for name, targets in graph.items()
             if name.startswith("fickcam.scene.load") for target in targets
             if layer_of(target) > layer_of("fickcam.scene.load.x") or target.split(".")[1] in (
                 "diffusion", "cam", "linkage", "elastic", "materials", "mechanisms")]
    assert [(n, t) for n, t in later if not t.startswith(SCENE_READS)] == []


