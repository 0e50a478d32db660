"""Formulas on the module pages of the API reference are math that Sphinx renders
(``.. math::`` or ``:math:``), never ASCII set apart in an indented quote block."""
from __future__ import annotations

import ast
import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "fickcam"


def quoted_formulas(doc: str) -> list[str]:
    """Lines of a docstring indented as a quote block (4 spaces or more, outside a literal
    block or directive opened by ``::``) that hold an equation."""
    found, block = [], None  # block: the indent of the line that opened a ``::`` block
    for line in doc.splitlines():
        indent = len(line) - len(line.lstrip())
        if not line.strip():
            continue
        if block is not None and indent > block:
            continue
        block = indent if line.rstrip().endswith("::") else None
        if indent >= 4 and re.search(r"\s=\s", line):
            found.append(line.strip())
    return found


def test_no_module_docstring_sets_an_ascii_formula_apart():
    offenders = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        doc = ast.get_docstring(ast.parse(path.read_text()))
        lines = quoted_formulas(doc or "")
        if lines:
            offenders[str(path.relative_to(PACKAGE.parent))] = lines
    assert not offenders, offenders


def test_the_check_sees_a_quoted_formula_and_not_a_math_block():
    assert quoted_formulas("Text:\n\n    F = m a\n\nmore") == ["F = m a"]
    assert quoted_formulas("Text:\n\n.. math::\n\n    F = m a\n") == []
    assert quoted_formulas("An example::\n\n    x = 1\n") == []
