"""Lazy, cached, read-only access to the CIE tables shipped in ``spectrocolor/data``."""

from __future__ import annotations

from functools import cache
from importlib import resources

import numpy as np


@cache
def load_table(relative_path: str) -> tuple[tuple[str, ...], np.ndarray]:
    """Column names and a read-only float array ``(rows, columns)`` of a shipped CSV table."""
    text = resources.files("spectrocolor").joinpath("data", relative_path).read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    header = tuple(cell.strip() for cell in lines[0].split(","))
    table = np.array([[float(cell) for cell in line.split(",")] for line in lines[1:]])
    table.setflags(write=False)
    return header, table
