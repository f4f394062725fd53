"""The rule that keeps the suite green on every x86-64 CPU and BLAS kernel (docs/robustness.md,
"Portable tests: the rule").

A float computed two different ways (another summation order, a BLAS kernel with other
accumulators, ``÷100`` before instead of after a product, a SIMD ``exp``) agrees with itself to
rounding, not bit for bit, and which way a CPU takes is not the test's to choose. So an exact
comparison in a test must be exact by construction on every CPU, and say why; everything else is
compared with a tolerance derived from the rounding (ulps × number of terms × size of the terms).

This module parses every ``tests/*.py`` and fails, listing ``file:line``, on

* a call of ``assert_array_equal``, ``assert_equal``, ``array_equal`` or ``array_equiv`` (as
  ``np.``, ``np.testing.``, ``npt.`` or imported bare) none of whose compared arguments is
  obviously non-float (a comparison, ``~mask``, ``np.isnan(...)`` and the like, ``.astype(int)``,
  a bitwise operation, an integer ``np.arange``);
* ``assert_allclose`` with ``rtol=0`` and ``atol=0`` (or no ``atol``), and ``pytest.approx`` with
  ``rel=0`` and ``abs=0``: exact comparisons in disguise;
* ``==`` or ``!=`` against a float literal (``x == 0.5``, ``v.tolist() == [1.0, 0.0]``);

unless the statement carries a comment ``# exact: <why this is bit-exact on every CPU>`` on one
of its lines or on the comment lines just above it. What is not caught (``a == b`` between two
computed floats, the text of formatted floats, which internal solver path a colour took) is for
review, by the same rule.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parents[1]
EXACT_CALLS = {"assert_array_equal", "assert_equal", "array_equal", "array_equiv"}
# functions whose result is boolean or integer whatever their input
NON_FLOAT_FUNCTIONS = {
    "isnan", "isfinite", "isinf", "isneginf", "isposinf", "signbit", "isin", "isclose",
    "logical_and", "logical_or", "logical_not", "logical_xor", "flatnonzero", "nonzero",
    "argwhere", "argsort", "argmax", "argmin", "searchsorted", "count_nonzero", "bincount",
    "len", "int", "bool", "ord",
}
INTEGER_TYPES = re.compile(r"^(u?int(8|16|32|64)?|bool_?|uintp|intp)$")
ANNOTATION = re.compile(r"#\s*exact:\s*\S.{8,}")
RULE = (
    "tests must not compare floats from two different computations bit for bit: summation "
    "order, BLAS kernel and SIMD width differ between CPUs (docs/robustness.md, 'Portable "
    "tests: the rule'). Fix each place by comparing with a tolerance derived from the "
    "rounding (ulps x number of terms x size of the terms; say so in a one-line comment), or, "
    "where the values are bit-exact by construction on every CPU (the same call on the same "
    "input, a copy, integer or boolean data, exact arithmetic on representable values), by "
    "annotating the statement with '# exact: <why>'."
)


def _type_name(node: ast.AST) -> str:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return node.attr
    return ""


def _called_name(node: ast.Call) -> str:
    return node.func.id if isinstance(node.func, ast.Name) else (
        node.func.attr if isinstance(node.func, ast.Attribute) else "")


def _integer_literal(node: ast.AST) -> bool:
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        node = node.operand
    return isinstance(node, ast.Constant) and type(node.value) in (int, bool)


def non_float(node: ast.AST) -> bool:
    """Whether an expression is boolean or integer by its form, whatever the values."""
    if isinstance(node, ast.Compare | ast.BoolOp):
        return True
    if isinstance(node, ast.UnaryOp):
        return isinstance(node.op, ast.Invert | ast.Not) or non_float(node.operand)
    if isinstance(node, ast.BinOp):
        if isinstance(node.op, ast.BitAnd | ast.BitOr | ast.BitXor | ast.LShift | ast.RShift):
            return True
        return False
    if isinstance(node, ast.Subscript):  # a part of a non-float array is non-float
        return non_float(node.value)
    if not isinstance(node, ast.Call):
        return False
    name = _called_name(node)
    if name in NON_FLOAT_FUNCTIONS:
        return True
    if name == "astype" and node.args:
        return bool(INTEGER_TYPES.match(_type_name(node.args[0])))
    if name == "arange":
        return all(_integer_literal(a) for a in node.args)
    if name == "where" and len(node.args) == 3:
        return all(_integer_literal(a) or non_float(a) for a in node.args[1:])
    for keyword in node.keywords:
        if keyword.arg == "dtype":
            return bool(INTEGER_TYPES.match(_type_name(keyword.value)))
    return False


def _zero(node: ast.AST | None) -> bool:
    return isinstance(node, ast.Constant) and node.value == 0 and type(node.value) in (int, float)


def _float_literal(node: ast.AST) -> bool:
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        node = node.operand
    if isinstance(node, ast.Constant):
        return type(node.value) is float
    if isinstance(node, ast.List | ast.Tuple):
        return any(_float_literal(e) for e in node.elts)
    return False


def findings(source: str) -> list[tuple[int, str]]:
    """``(line, what)`` for every unannotated exact float comparison in a module's source."""
    tree = ast.parse(source)
    comments: dict[int, str] = {}
    code_lines: set[int] = set()
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type == tokenize.COMMENT:
            comments[token.start[0]] = token.string
        elif token.type not in (tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT,
                                tokenize.ENDMARKER):
            code_lines.update(range(token.start[0], token.end[0] + 1))

    def annotated(statement: ast.stmt) -> bool:
        body = getattr(statement, "body", None)  # a compound statement: its header's lines
        last = body[0].lineno - 1 if isinstance(body, list) and body else statement.end_lineno
        lines = range(statement.lineno, max(last or statement.lineno, statement.lineno) + 1)
        if any(ANNOTATION.search(comments.get(n, "")) for n in lines):
            return True
        above = statement.lineno - 1
        while above in comments and above not in code_lines:  # the comment block just above
            if ANNOTATION.search(comments[above]):
                return True
            above -= 1
        return False

    exact_calls = set(EXACT_CALLS)  # and what a module imports them as
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            exact_calls.update(a.asname for a in node.names if a.name in EXACT_CALLS and a.asname)
    found = []

    def visit(node: ast.AST, statement: ast.stmt | None) -> None:
        if isinstance(node, ast.stmt):
            statement = node
        what = None
        if isinstance(node, ast.Call):
            name = _called_name(node)
            keywords = {k.arg: k.value for k in node.keywords}
            if name in exact_calls and not any(non_float(a) for a in node.args[:2]):
                what = f"{name}(...) of values not obviously integer or boolean"
            elif name == "assert_allclose" and _zero(keywords.get("rtol")) and (
                    "atol" not in keywords or _zero(keywords["atol"])):
                what = "assert_allclose(..., rtol=0, atol=0): an exact comparison"
            elif name == "approx" and _zero(keywords.get("rel")) and _zero(keywords.get("abs")):
                what = "pytest.approx(..., rel=0, abs=0): an exact comparison"
        elif isinstance(node, ast.Compare) and any(isinstance(op, ast.Eq | ast.NotEq) for op in node.ops):
            sides = [node.left, *node.comparators]
            approx = any(isinstance(s, ast.Call) and _called_name(s) == "approx" for s in sides)
            if not approx and any(_float_literal(side) for side in sides):
                what = "== or != against a float literal"
        if what and statement is not None and not annotated(statement):
            found.append((node.lineno, what))
        for child in ast.iter_child_nodes(node):
            visit(child, statement)

    visit(tree, None)
    return found


@pytest.mark.slow
def test_no_test_compares_floats_of_different_computations_bit_for_bit():
    problems = []
    for path in sorted(TESTS.rglob("*.py")):
        for line, what in findings(path.read_text(encoding="utf-8")):
            problems.append(f"{path.relative_to(TESTS.parent).as_posix()}:{line}: {what}")
    assert not problems, f"{len(problems)} unmarked exact comparison(s):\n  " + "\n  ".join(problems) + (
        f"\n\n{RULE}")


@pytest.mark.parametrize("source", [
    "np.testing.assert_array_equal(a @ w, b @ w)\n",
    "assert_array_equal(x, y)\n",
    "assert np.array_equal(table.node_XYZ100, rho @ table.weights)\n",
    "npt.assert_equal(a.sum(), 3.0)\n",
    "np.testing.assert_allclose(a, b, rtol=0, atol=0)\n",
    "np.testing.assert_allclose(a, b, rtol=0)\n",
    "assert x == pytest.approx(y, rel=0, abs=0)\n",
    "assert mu.tolist() == [0.2, -0.2, 0.0]\n",
    "assert value != 1.5\n",
    "# a comment that says nothing\nnp.testing.assert_array_equal(a, b)\n",
    "np.testing.assert_array_equal(a, b)  # exact:\n",
    "np.testing.assert_array_equal(a, b)\n# exact: the comment of the next statement does not count\n",
    "np.testing.assert_array_equal(a.astype(float), b)\n",
    "np.testing.assert_array_equal(np.arange(0.0, 3.0), b)\n",
    "from numpy.testing import assert_array_equal as same\nsame(a, b)\n",
])
def test_the_check_sees_exact_float_comparisons(source):
    assert findings(source), source


@pytest.mark.parametrize("source", [
    "np.testing.assert_array_equal(a, b)  # exact: the same call on the same input\n",
    "# exact: copies of one array, no arithmetic\nnp.testing.assert_array_equal(a, b)\n",
    "# exact: integer codes\n# (read back from the PNG)\nnp.testing.assert_array_equal(\n    a,\n    b)\n",
    "np.testing.assert_array_equal(\n    a,  # exact: uint8 codes read back\n    b)\n",
    "np.testing.assert_array_equal(np.isnan(a), np.isnan(b))\n",
    "np.testing.assert_array_equal(~mask, b)\n",
    "np.testing.assert_array_equal(a > 1, b)\n",
    "np.testing.assert_array_equal(data[:, 6:].astype(int), codes)\n",
    "np.testing.assert_array_equal(x.astype(np.uint8), y)\n",
    "np.testing.assert_array_equal(codes >> 8, y)\n",
    "np.testing.assert_array_equal(t.ticks, np.arange(99, 1000, 100))\n",
    "np.testing.assert_array_equal(a[..., 3], np.where(m, 0, 255))\n",
    "assert not np.array_equal(np.isnan(a), m)\n",
    "np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)\n",
    "np.testing.assert_allclose(a, b, atol=0)\n",
    "assert x == pytest.approx(0.5)\n",
    "assert codes == [0, 0, 0]\n",
    "assert n == 3\n",
])
def test_the_check_accepts_what_is_exact_by_construction_or_annotated(source):
    assert findings(source) == [], source
