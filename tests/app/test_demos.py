"""The demo files (issue 28, item 2): every file in the app's demo folder is a valid demo, the
server serves them, and each kind of mistake a teacher can make in a file gets one clear
:class:`DemoError` naming the file and the mistake (never a traceback from deep inside)."""

from __future__ import annotations

import copy
import json

import pytest
from fastapi.testclient import TestClient

from spectrocolor.app import demos as D
from spectrocolor.app.server import create_app

FILES = sorted(D.DEMO_FOLDER.glob("*.json"))
# the seed's suggestions the issue asks for (seed 002; thin films and the reflectance lab)
REQUIRED = {"straw-short-waves": "setting1", "notch-540": "setting3", "three-line-match": "setting2",
            "metamers-under-a": "setting4", "filters-in-series": "setting5",
            "soap-film-thinning": "thinfilm", "smoothest-reflectance": "reflectance"}


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_every_demo_file_is_valid(path):
    demo = D.load_demo(path)
    assert demo["id"] == path.stem
    assert "?" in demo["question"]  # it asks something, as the panel says


def test_the_issues_demos_are_there():
    found = {d["id"]: d["where"] for d in D.load_demos(D.DEMO_FOLDER)}
    assert {k: found.get(k) for k in REQUIRED} == REQUIRED


def test_the_server_serves_the_demos():
    with TestClient(create_app(), base_url="http://127.0.0.1") as c:
        r = c.get("/api/demos")
    assert r.status_code == 200
    assert [d["id"] for d in r.json()["demos"]] == [d["id"] for d in D.load_demos(D.DEMO_FOLDER)]


GOOD = json.loads((D.DEMO_FOLDER / "straw-short-waves.json").read_text(encoding="utf-8"))


def _with(change):
    demo = copy.deepcopy(GOOD)
    change(demo)
    return demo


MISTAKES = [
    (lambda d: d.pop("question"), "question must be a non-empty text"),
    (lambda d: d.update(colour="red"), "unknown keys ['colour']"),
    (lambda d: d.update(where="setting6"), "where must be one of"),
    (lambda d: d.update(id="Straw"), "id must be"),
    (lambda d: d["state"]["distributions"][0].update(preset="9"), "preset must be one of"),
    (lambda d: d["state"]["distributions"].append({"constant": 3}), "must list 1 distribution"),
    (lambda d: d["state"]["distributions"][0].update(set={"405": 3}), "not a wavelength"),
    (lambda d: d["state"]["distributions"][0].update(set={"400": 31}), "whole level 0-30"),
    (lambda d: d["state"].update(normalise="brightest"), "normalise must be one of"),
    (lambda d: d["expect"][0].update(quantity="hue"), "quantity must be one of"),
    (lambda d: d["expect"][0].update(patch=3), "patch must be a patch index 0-0"),
    (lambda d: d["expect"][0].update(at="state", min_change=1), "set at to 'then'"),
    (lambda d: d["expect"][0].update(max="0.5"), "finite number"),
    (lambda d: d.pop("then"), "the demo has no 'then'"),
    (lambda d: d["then"].pop("do"), "then must be an object with 'do'"),
]


@pytest.mark.parametrize(("change", "message"), MISTAKES, ids=[m for _, m in MISTAKES])
def test_each_mistake_gets_one_clear_error(tmp_path, change, message):
    path = tmp_path / "straw-short-waves.json"
    path.write_text(json.dumps(_with(change)), encoding="utf-8")
    with pytest.raises(D.DemoError) as err:
        D.load_demo(path)
    assert str(err.value).startswith("demo file straw-short-waves.json: ")
    assert message in str(err.value)


def test_a_file_named_otherwise_than_its_id_is_refused(tmp_path):
    path = tmp_path / "other.json"
    path.write_text(json.dumps(GOOD), encoding="utf-8")
    with pytest.raises(D.DemoError, match="must equal the file's name"):
        D.load_demo(path)


def test_a_large_or_broken_file_is_refused_before_parsing(tmp_path):
    big = tmp_path / "big.json"
    big.write_bytes(b" " * (D.MAX_DEMO_BYTES + 1))
    with pytest.raises(D.DemoError, match="at most 32768"):
        D.load_demo(big)
    broken = tmp_path / "broken.json"
    broken.write_bytes(b"\xff{")
    with pytest.raises(D.DemoError, match="not valid UTF-8 JSON"):
        D.load_demo(broken)
    nan = tmp_path / "nan.json"
    nan.write_text('{"id": NaN}', encoding="utf-8")
    with pytest.raises(D.DemoError, match="not valid UTF-8 JSON"):
        D.load_demo(nan)


def test_a_folder_with_one_bad_file_names_it(tmp_path):
    (tmp_path / "straw-short-waves.json").write_text(json.dumps(GOOD), encoding="utf-8")
    (tmp_path / "zz.json").write_text("[]", encoding="utf-8")
    with pytest.raises(D.DemoError, match="demo file zz.json: a demo must be a JSON object"):
        D.load_demos(tmp_path)
