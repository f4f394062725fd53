"""The command line speaks with the library's one voice: the same adaptation both ways."""

from __future__ import annotations

import csv

import pytest

from spectrocolor.cli import main


@pytest.mark.parametrize("illuminant", ["A", "D65", "FL11", "blackbody:3000"])
def test_recover_then_describe_gives_back_the_hex(tmp_path, capsys, illuminant):
    """`recover --hex` adapts sRGB's white to the illuminant's with Bradford, as `describe` adapts back."""
    out = tmp_path / "recovered.csv"
    assert main(["recover", "--hex", "4060a0", "c0a050", "--illuminant", illuminant, "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["describe", str(out), "--illuminant", illuminant, "--format", "csv"]) == 0
    rows = list(csv.DictReader(capsys.readouterr().out.splitlines()))
    assert [row["srgb"] for row in rows] == ["#4060a0", "#c0a050"]
