"""Every test that asserts a tolerance says why that tolerance (CONTRIBUTING: a tolerance is a
claim about round-off, truncation or a method's own test, and a reader must be able to check it).

A tolerance assertion is an ``assert_allclose``/``allclose``/``isclose``/``approx`` with a non-zero
``rtol``/``atol``/``rel``/``abs`` (or with numpy's or pytest's defaults), or an ``assert`` that
compares with a number below 1e-2 (``abs(x - y) < 1e-12``). It says why when a comment stands on
one of its lines or on one of the three lines above it. The files still to be swept are listed in
:data:`UNSWEPT` with the number of their assertions that give no reason: that number may only go
down (a file swept leaves the list).
"""

import ast
import io
import tokenize
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
UNSWEPT = {  # file: assertions without a reason, at most
    "test_actuator.py": 32, "test_exercises.py": 13, "test_finger.py": 27, "test_hacksaw.py": 31,
    "test_pfr3.py": 25, "test_prr3.py": 28, "test_rfr2.py": 20, "test_rods.py": 43,
}
CLOSE = {"assert_allclose", "allclose", "isclose", "approx", "assert_array_almost_equal"}
TOLERANCES = {"rtol", "atol", "rel", "abs"}


def _small(node):
    return (isinstance(node, ast.Constant) and isinstance(node.value, float)
            and 0 < abs(node.value) < 1e-2)


def _is_tolerance(node):
    if isinstance(node, ast.Call):
        name = getattr(node.func, "attr", getattr(node.func, "id", ""))
        if name not in CLOSE:
            return False
        given = [k.value for k in node.keywords if k.arg in TOLERANCES]
        if not given:  # numpy's or pytest's default tolerance is a tolerance too
            return name != "assert_allclose"
        return any(isinstance(n, ast.Constant) and isinstance(n.value, (int, float))
                   and n.value != 0 for v in given for n in ast.walk(v))
    if isinstance(node, ast.Assert):
        return any(isinstance(c, ast.Compare) and any(
            isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE)) for op in c.ops)
            and any(_small(n) for n in ast.walk(c)) for c in ast.walk(node.test))
    return False


def unexplained(path):
    """The first lines of the tolerance assertions of ``path`` that give no reason."""
    text = path.read_text(encoding="utf-8")
    comments = {t.start[0] for t in tokenize.generate_tokens(io.StringIO(text).readline)
                if t.type == tokenize.COMMENT}
    tree = ast.parse(text)
    statements = [s for s in ast.walk(tree) if isinstance(s, (ast.Assert, ast.Expr, ast.Assign))]
    found = set()
    for node in filter(_is_tolerance, ast.walk(tree)):
        holder = min((s for s in statements if s.lineno <= node.lineno
                      and s.end_lineno >= node.end_lineno),
                     key=lambda s: s.end_lineno - s.lineno, default=None)
        if holder is None:  # a tolerance in a return or a call's argument: not an assertion
            continue
        lines = range(max(holder.lineno - 3, 1), holder.end_lineno + 1)
        if not comments.intersection(lines):
            found.add(holder.lineno)
    return sorted(found)


@pytest.mark.parametrize("name", sorted(p.name for p in TESTS.glob("test_*.py")))
def test_every_tolerance_says_why(name):
    missing = unexplained(TESTS / name)
    allowed = UNSWEPT.get(name, 0)
    assert len(missing) <= allowed, (
        f"{name}: {len(missing)} tolerance assertions without a reason (a comment on their lines "
        f"or the three above), at most {allowed} allowed; lines {missing}")


def test_the_list_of_unswept_files_only_shrinks():
    # a file that has been swept (or gone) leaves UNSWEPT, so that its count cannot grow back
    for name, allowed in UNSWEPT.items():
        path = TESTS / name
        assert path.exists() and len(unexplained(path)) == allowed, (
            f"{name}: {len(unexplained(path)) if path.exists() else 'no file'} now, {allowed} "
            "listed: lower the count, or remove the file from UNSWEPT")
