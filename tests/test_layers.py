"""The package's layers: imports flow one way (no circle, lazy imports included), the mechanics
import nothing above them, and no module uses another's private names or matplotlib's."""

import ast
import functools
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "dccss"


def module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


@functools.cache
def imports(name):
    """(imported module, names taken from it) for every import statement of module ``name``, at any depth."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out += [(alias.name, ()) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            names = tuple(alias.name for alias in node.names)
            submodules = [f"{target}.{n}" for n in names if f"{target}.{n}" in MODULES]
            out += [(m, ()) for m in submodules] + [(target, tuple(n for n in names if f"{target}.{n}" not in MODULES))]
        elif (isinstance(node, ast.Call) and getattr(node.func, "attr", getattr(node.func, "id", "")) == "import_module"
              and node.args and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
            out.append((node.args[0].value, ()))  # importlib.import_module("dccss...."): an import all the same
    return tuple(out)


@functools.cache
def internal_graph():
    return {name: {target for target, _ in imports(name) if target in MODULES and target != name} for name in MODULES}


def test_the_import_graph_has_no_circle():
    graph = internal_graph()
    # a package's __init__ importing its own modules is not a layer: leave those edges out
    graph = {m: {t for t in ts if not (MODULES[m].name == "__init__.py" and t.startswith(m + "."))}
             for m, ts in graph.items()}
    state, cycles = {}, []

    def visit(node, path):
        state[node] = "open"
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                cycles.append(path[path.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
    assert not cycles, " ; ".join(" -> ".join(c) for c in cycles)


@pytest.mark.parametrize("name", [m for m in MODULES if m.startswith("dccss.mechanics")])
def test_the_mechanics_import_nothing_above_them(name):
    above = sorted(t for t in internal_graph()[name] if not t.startswith("dccss.mechanics"))
    assert not above, f"{name} imports {above}"


@pytest.mark.parametrize("name", list(MODULES))
def test_no_private_name_is_imported_across_modules(name):
    private = [(target, n) for target, names in imports(name) for n in names
               if n.startswith("_") and not n.startswith("__") and target != name]
    assert not private, f"{name} imports private names {private}"
    source = MODULES[name].read_text(encoding="utf-8")
    tree = ast.parse(source)
    aliases = {alias.asname or alias.name.rpartition(".")[2] for node in ast.walk(tree)
               if isinstance(node, (ast.Import, ast.ImportFrom)) for alias in node.names
               if f"{getattr(node, 'module', '') or ''}.{alias.name}".strip(".") in MODULES
               or any(m.endswith("." + alias.name) for m in MODULES)}
    used = sorted({f"{node.value.id}.{node.attr}" for node in ast.walk(tree)
                   if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                   and node.value.id in aliases and node.attr.startswith("_") and not node.attr.startswith("__")})
    assert not used, f"{name} uses private names of other modules: {used}"


@pytest.mark.parametrize("name", list(MODULES))
def test_no_private_matplotlib_module_is_used(name):
    private = sorted({target for target, names in imports(name) if target.startswith("matplotlib") and (
        any(part.startswith("_") for part in target.split(".")) or any(n.startswith("_") for n in names))})
    assert not private, f"{name} imports {private}"
