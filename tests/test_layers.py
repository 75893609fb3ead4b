"""The package's shape (issue 22; ARCHITECTURE.md): three layers, no import loop, no private name
crossing its subpackage, and the mechanism protocol's signatures.

The imports are read from the source (``ast``), every ``import`` statement of a module, also one
inside a function: a loop through a deferred import is still a loop in the design.
"""

import ast
import importlib
import inspect
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "pkg" / "mechnum"
MECHANISMS = ("hacksaw", "finger", "elastica", "prr3", "rfr2", "pfr3", "actuator")
SHARED = ("_validate",)  # the package's own input checks, for every module


def module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imports(name):
    """``[(module imported, [names taken from it])]`` of module ``name``, relative imports
    resolved, only modules of mechnum."""
    path = MODULES[name]
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join([*package.split(".")[:len(package.split(".")) - node.level + 1],
                                 *([base] if base else [])])
            for alias in node.names:  # `from mechnum.x import y` may import a module y
                sub = f"{base}.{alias.name}"
                found.append((sub, []) if sub in MODULES else (base, [alias.name]))
        elif isinstance(node, ast.Import):
            found += [(alias.name, []) for alias in node.names]
    return [(m, names) for m, names in found if m in MODULES]


def subpackage(name):
    """The subpackage of mechnum that owns module ``name`` (``mechnum.rods``, ...)."""
    return ".".join(name.split(".")[:2])


def layer(name):
    parts = name.split(".")
    if parts[1:2] == ["exercises"]:  # the chapters' exercises, above the mechanisms: their
        return "exercises"           # public cases are the chapters' mechanisms
    return (parts[2] if len(parts) > 2 else "") if parts[1:2] == ["mechanisms"] else ""


def test_no_import_loop():
    graph = {name: {m for m, _ in imports(name) if m != name} for name in MODULES}
    state = {}

    def visit(name, path):
        if state.get(name) == "open":
            pytest.fail(f"import loop: {' -> '.join(path[path.index(name):] + [name])}")
        if state.get(name) != "done":
            state[name] = "open"
            for other in sorted(graph[name]):
                # a package's __init__ importing its own modules is how it exports them
                if not other.startswith(name + "."):
                    visit(other, path + [name])
            state[name] = "done"

    for name in MODULES:
        visit(name, [])


@pytest.mark.parametrize("name", MODULES)
def test_layers_and_private_names(name):
    mine = layer(name)
    for other, names in imports(name):
        theirs = layer(other)
        if mine == "exercises":
            pass  # the top layer imports any
        elif not mine:
            assert not theirs, f"{name} (methods layer) imports the mechanism {other}"
        else:
            assert theirs in ("", mine, "thesis", "_assembly"), \
                f"{name} imports another mechanism: {other}"
        # a private name is its subpackage's: mechnum.rods's internals are the rods' own,
        # mechnum.mechanisms._assembly the mechanisms' (each mechanism imports no other)
        private_module = [p for p in other.split(".")[1:] if p.startswith("_")
                          and p not in SHARED]
        crossing = subpackage(other) != subpackage(name)
        assert not (crossing and private_module), f"{name} imports the private module {other}"
        private = [n for n in names if n.startswith("_") and n not in SHARED]
        assert not (crossing and private), f"{name} imports {private} from {other}"


@pytest.mark.parametrize("mechanism", MECHANISMS)
def test_the_mechanism_protocol(mechanism):
    """``draw(ax, mech, state, *, artists=None, ...)``, and the verbs take the mechanism first."""
    module = importlib.import_module(f"mechnum.mechanisms.{mechanism}")
    draw = inspect.signature(module.draw).parameters
    assert list(draw)[:3] == ["ax", "mech", "state"], mechanism
    assert draw["artists"].kind is inspect.Parameter.KEYWORD_ONLY
    assert draw["artists"].default is None
    verbs = [v for v in ("forward", "inverse", "singular_points", "workspace", "atlas")
             if hasattr(module, v)]
    for verb in verbs:
        assert list(inspect.signature(getattr(module, verb)).parameters)[0] == "mech", verb
