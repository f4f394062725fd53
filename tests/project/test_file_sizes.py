"""Small rooms (issue 24, part 6): a source file over 500 lines states at its top why it is long.

A long file is allowed where splitting it would scatter one idea (one class, one registry, one
file format) over several modules; the reason must be written where a reader meets it, in the
module docstring, as a paragraph that starts ``Why this file is long:``. This test lists every
file over the limit that has no such paragraph, so a file that grows past it is noticed.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "src" / "spectrocolor"
LINE_LIMIT = 500
REASON = "Why this file is long:"


def long_files_without_a_reason() -> list[str]:
    """``path (lines)`` of each package module over :data:`LINE_LIMIT` lines whose docstring gives no reason."""
    missing = []
    for path in sorted(PACKAGE.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        lines = len(text.splitlines())
        if lines <= LINE_LIMIT:
            continue
        docstring = ast.get_docstring(ast.parse(text)) or ""
        reason = docstring.split(REASON, 1)[1].strip() if REASON in docstring else ""
        if len(reason) < 40:  # a reason is a sentence, not a placeholder
            missing.append(f"{path.relative_to(PACKAGE)} ({lines} lines)")
    return missing


def test_every_file_over_the_limit_says_why_it_is_long():
    missing = long_files_without_a_reason()
    assert not missing, (f"over {LINE_LIMIT} lines with no '{REASON} ...' paragraph in the module docstring "
                         f"(split the file, or state the reason): {missing}")


def test_the_check_sees_a_long_file_without_a_reason(tmp_path, monkeypatch):
    """The check itself can fail: a 600-line module with a plain docstring is reported."""
    package = tmp_path / "spectrocolor"
    package.mkdir()
    (package / "big.py").write_text('"""A module."""\n' + "x = 1\n" * 600, encoding="utf-8")
    (package / "fine.py").write_text(f'"""A module.\n\n{REASON} one class with its forty methods, '
                                     'split it and the class is scattered.\n"""\n' + "x = 1\n" * 600,
                                     encoding="utf-8")
    monkeypatch.setattr(__import__(__name__), "PACKAGE", package)
    assert long_files_without_a_reason() == ["big.py (601 lines)"]
