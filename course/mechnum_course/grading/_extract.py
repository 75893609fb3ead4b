"""The source of a student's functions, as text that defines them again in a fresh process.

The grader runs a notebook only to learn, for each exercise, the source of the function the
student defined: :func:`bundle` takes the function from the kernel's namespace and writes a
self-contained text, its ``def`` (or ``name = lambda ...``; or an ``import`` of a function of
the student's own module), the notebook's imports it uses, the helper functions it calls
(recursively) and the plain constants it reads. ``exec`` keeps the sources it is given where
:func:`bundle` finds them (:data:`PRELUDE`, run when the kernel starts). Whatever cannot be
carried over is said in words; a function that is not a function (a ``functools.partial``, a
callable object) is "not gradable: define it with def".

This module imports only the standard library: its source is sent to the student's kernel as
the notebook's last cell (:func:`cell`), and its output, one line of JSON after
:data:`MARK`, is only text, read by the grader, which never runs anything the notebook sends.
:func:`static` does the same from the notebook's cells alone, without running them, for a
notebook whose kernel did not finish.
"""

import ast
import builtins
import json  # noqa: F401 -- the last cell prints with it (cell)
import linecache
import sys
import textwrap
import types
from pathlib import Path

MARK = "MECHNUM-SOURCES "
MAX_ARRAY = 100_000
"""The largest array (entries) a function may read from the notebook's globals."""

PRELUDE = '''
import builtins as _b, linecache as _l, sys as _s
def _grader_keep(original_compile, original_exec, count=[0]):
    def keep(source):
        count[0] += 1
        name = f"<exec-{count[0]}>"
        _l.cache[name] = (len(source), None, source.splitlines(True), name)
        return name
    def compile(source, filename, *args, **kwargs):
        if isinstance(source, str) and filename == "<string>":
            filename = keep(source)
        return original_compile(source, filename, *args, **kwargs)
    def exec(source, globals=None, locals=None, /, **kwargs):
        frame = _s._getframe(1)
        if globals is None:
            globals, locals = frame.f_globals, frame.f_locals if locals is None else locals
        if isinstance(source, str):
            source = original_compile(source, keep(source), "exec")
        return original_exec(source, globals, locals, **kwargs)
    return compile, exec
_b.compile, _b.exec = _grader_keep(_b.compile, _b.exec)
del _grader_keep
'''
"""Run at the kernel's start: ``exec`` and ``compile`` keep the text of the code they run."""


class NotGradable(Exception):
    """A function the grader cannot carry over; the message says why and what to do."""


def _node(function):
    """The ``def`` or ``lambda`` node of a function, and its file's text."""
    code = function.__code__
    text = "".join(linecache.getlines(code.co_filename))
    if not text:
        raise NotGradable(f"the source of `{function.__name__}` cannot be found (it was made "
                          "by code the grader cannot read); define it with def in a cell")
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Lambda) and code.co_name == "<lambda>":
            if node.lineno == code.co_firstlineno:
                return node, text
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and \
                node.name == code.co_name:
            first = node.decorator_list[0].lineno if node.decorator_list else node.lineno
            if first == code.co_firstlineno:
                return node, text
    raise NotGradable(f"the source of `{function.__name__}` cannot be found; define it with "
                      "def in a cell")


def _is_students(function, folder):
    filename = function.__code__.co_filename
    return (filename.startswith("<") or "ipykernel_" in filename
            or (folder and str(Path(filename).resolve()).startswith(folder)))


def _imported(value, name):
    """``import`` text for a module or a library function or class, else None."""
    if isinstance(value, types.ModuleType):
        module = value.__name__
        return f"import {module}" if module == name else f"import {module} as {name}"
    module, qualname = getattr(value, "__module__", None), getattr(value, "__qualname__", "")
    if module and qualname and "." not in qualname and module in sys.modules and \
            getattr(sys.modules[module], qualname, None) is value:
        return f"from {module} import {qualname} as {name}"
    return None


def _constant(value, name):
    """Assignment text for a plain constant, else None."""
    if type(value) in (int, float, complex, str, bool, bytes, type(None)) or \
            type(value) in (tuple, list, dict):
        text = repr(value)
        try:
            if ast.literal_eval(text) == value:
                return f"{name} = {text}"
        except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError):
            return None
    numpy = sys.modules.get("numpy")
    if numpy is not None and type(value) is numpy.ndarray and value.dtype.kind in "biuf" \
            and value.size <= MAX_ARRAY:
        return (f"{name} = __import__('numpy').array({value.tolist()!r}, "
                f"dtype={str(value.dtype)!r})")
    return None


def bundle(namespace, name, folder=""):
    """The text that defines ``name`` of ``namespace`` again; raises :class:`NotGradable`."""
    function = namespace.get(name)
    if function is None:
        raise KeyError(name)
    lines, defs, notes, seen = [], {}, [], set()

    def visit(function, alias):
        if not isinstance(function, types.FunctionType):
            text = _imported(function, alias)
            if text is None:
                raise NotGradable(f"`{alias}` is a {type(function).__name__}, not a function; "
                                  "define it with def")
            lines.append(text)
            return
        if not _is_students(function, folder):
            text = _imported(function, alias)
            if text is None:
                raise NotGradable(f"`{alias}` comes from {function.__module__}, which the "
                                  "grader cannot import; define it with def")
            lines.append(text)
            return
        if function.__code__.co_freevars:
            raise NotGradable(f"`{alias}` is made inside another function (it uses "
                              f"{', '.join(function.__code__.co_freevars)} of it); define it "
                              "with def at the top of a cell")
        node, text = _node(function)
        if getattr(node, "decorator_list", None):
            raise NotGradable(f"`{alias}` is decorated; define it with a plain def")
        source = textwrap.dedent(ast.get_source_segment(text, node, padded=True))
        if isinstance(node, ast.Lambda):
            source = f"{alias} = {source.strip()}"
        elif node.name != alias:
            source += f"\n{alias} = {node.name}"
        key = (id(function), alias)
        if key in seen:
            return
        seen.add(key)
        defs[alias] = source
        used = {n.id for n in ast.walk(node) if isinstance(n, ast.Name)}
        for other in sorted(used):
            if other in defs or other == alias or other not in function.__globals__:
                continue
            value = function.__globals__[other]
            if isinstance(value, types.FunctionType) and _is_students(value, folder):
                visit(value, other)
                continue
            if hasattr(builtins, other):  # IPython's own open, say: the builtin serves
                continue
            if isinstance(value, type) or callable(value):
                text = _imported(value, other)
            else:
                text = _imported(value, other) or _constant(value, other)
            if text:
                lines.append(text)
            else:
                notes.append(f"`{other}` (a {type(value).__name__}) is not carried over")

    visit(function, name)
    body = "\n".join(dict.fromkeys(lines)) + "\n\n" + "\n\n".join(
        defs[k] for k in reversed(list(defs))) + "\n"
    return body, notes


def extract(namespace, names, folder=""):
    """``{name: {"source": text, "notes": [...]} or {"error": why}}`` for each name."""
    found = {}
    for name in names:
        try:
            source, notes = bundle(namespace, name, folder)
            found[name] = {"source": source, "notes": notes}
        except KeyError:
            found[name] = {"error": "missing"}
        except NotGradable as error:
            found[name] = {"error": f"not gradable: {error}"}
        except Exception as error:  # noqa: BLE001 -- whatever a hostile namespace does
            found[name] = {"error": f"not gradable: {type(error).__name__}: {error}"}
    return found


def cell(names, folder):
    """The notebook's last cell: this module run in a namespace of its own (a student's name
    is never overwritten), then one line of JSON after :data:`MARK`."""
    source = Path(__file__).read_text(encoding="utf-8")
    return (f"_mechnum_grader = {{'__name__': 'mechnum_grader'}}\n"
            f"exec({source!r}, _mechnum_grader)\n"
            f"print(_mechnum_grader['MARK'] + _mechnum_grader['json'].dumps("
            f"_mechnum_grader['extract'](globals(), {list(names)!r}, {str(folder)!r})))\n")


def static(cells, names):
    """The same from the code cells' text alone, without running them: the top-level ``def``
    of each name, with every top-level import and ``def`` of the notebook (a fallback for a
    notebook whose kernel did not finish)."""
    imports, defs = [], {}
    for text in cells:
        try:
            tree = ast.parse(text)
        except SyntaxError:
            continue
        for node in tree.body:
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                imports.append(ast.get_source_segment(text, node))
            elif isinstance(node, ast.FunctionDef) and not node.decorator_list:
                defs[node.name] = ast.get_source_segment(text, node)
    found = {}
    for name in names:
        if name not in defs:
            found[name] = {"error": "missing"}
            continue
        body = "\n".join(dict.fromkeys(imports)) + "\n\n" + "\n\n".join(
            source for other, source in defs.items() if other != name)
        found[name] = {"source": body + "\n\n" + defs[name] + "\n",
                       "notes": ["graded from the notebook's text: its kernel did not finish"]}
    return found


def _imports(cells):
    """``{name: import statement}`` of the top-level imports of the code cells' text."""
    found = {}
    for text in cells:
        try:
            tree = ast.parse(text)
        except SyntaxError:
            continue
        for node in tree.body:
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                for alias in node.names:
                    name = (alias.asname or alias.name).split(".")[0]
                    found[name] = ast.get_source_segment(text, node)
    return found


def with_imports(source, cells):
    """``source`` with the notebook's import statements of the names it uses but does not
    bind (an import the kernel could not run, such as the instructors' package, is still
    tried, and refused, where the function runs)."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return source
    bound = set(dir(builtins))
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            bound.add(node.name)
            bound.update(a.arg for a in ast.walk(node.args) if isinstance(a, ast.arg))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            bound.update((a.asname or a.name).split(".")[0] for a in node.names)
        elif isinstance(node, ast.Name) and not isinstance(node.ctx, ast.Load):
            bound.add(node.id)
    used = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and
            isinstance(n.ctx, ast.Load)} - bound
    imports = _imports(cells)
    extra = list(dict.fromkeys(imports[name] for name in sorted(used) if name in imports))
    return "\n".join(extra + [source])

