"""Fuzz what issue 26 item 3 added: declaration parsing, the ``declared`` conditions, the
``recover --xyz-scale`` option and ``/api/import``'s ``content_base64`` and ``observer`` fields.

Every outcome is a result or one clear error (one line, naming the argument): never a traceback,
never a 500."""

from __future__ import annotations

import base64
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from spectrocolor import Spectrum, cli
from spectrocolor.app.server import create_app
from spectrocolor.errors import ColorimetryError
from spectrocolor.io.conditions import choose_conditions, declared_conditions, parse_declaration

CORPUS = Path(__file__).parents[1] / "data" / "io"
SETTINGS = settings(max_examples=60, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
KEYS = st.sampled_from(["MEASUREMENT_SOURCE", "WEIGHTING_FUNCTION", "ILLUMINANT", "ILLUMINATION_NAME",
                        "ILLUMINATION", "OBSERVER", "MEASUREMENT_GEOMETRY", "GEOMETRY", "ORIGINATOR"])
PIECES = st.sampled_from(["Illumination=", "ObserverAngle=", "D50", "D65", "A", "F11", "blackbody:1e9", "D:1",
                          "2", "10", "°", "º", "degree", "ILLUMINANT,", "OBSERVER,", ";", ",", " ", "\t", "=",
                          "1931", "1964", "0/45", "nan", "x" * 60])
VALUES = st.lists(PIECES, max_size=12).map("".join) | st.text(max_size=80)


@SETTINGS
@given(st.dictionaries(KEYS, VALUES, max_size=6))
def test_any_keywords_give_a_bounded_declaration(keywords):
    found = parse_declaration(keywords)
    assert set(found) <= {"declared_illuminant", "declared_observer", "declared_geometry", "declared_by",
                          "declared_unknown"}
    assert all(isinstance(v, str) and len(v) <= 300 + 80 * 6 for v in found.values())
    spectrum = Spectrum([400.0, 700.0], [0.2, 0.4], metadata=found)
    light, viewer, note = choose_conditions(spectrum)  # what a reader declares is always usable
    assert "\n" not in note and (light, viewer) != (None, None)


@SETTINGS
@given(illuminant=st.text(max_size=20) | st.sampled_from(["declared", "D50", "none"]),
       observer=st.text(max_size=20) | st.sampled_from(["declared", "1964", "2deg"]),
       metadata=st.dictionaries(st.sampled_from(["declared_illuminant", "declared_observer"]),
                                st.text(max_size=20) | st.sampled_from(["D50", "CIE 1964 10°"]), max_size=2))
def test_choose_conditions_answers_or_names_the_argument(illuminant, observer, metadata):
    spectrum = Spectrum([400.0, 700.0], [0.2, 0.4], metadata=metadata)
    try:
        light, viewer, note = choose_conditions(spectrum, illuminant, observer)
    except ColorimetryError as exc:  # a bad name, given or in hand-made metadata: one line
        assert "\n" not in str(exc) and str(exc).split(":")[0] in ("illuminant", "observer"), str(exc)
        return
    assert "\n" not in note and bool(declared_conditions(spectrum)) >= bool(note)


def _cli(argv, capsys) -> tuple[int, str]:
    try:
        code = cli.main([str(a) for a in argv])
    except SystemExit as exc:  # argparse's refusal: one error line
        code = exc.code
    out, err = capsys.readouterr()
    assert "Traceback" not in err + out
    assert code in (0, 1, 2), (code, err)
    if code == 2:
        assert len([line for line in err.splitlines() if "error:" in line]) == 1, err
    return code, err


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(xyz=st.lists(st.floats(allow_nan=True, allow_infinity=True, width=32) | st.floats(0, 1.5), min_size=3,
                    max_size=3),
       scale=st.none() | st.sampled_from(["1", "100", "7", "nan", "-1", "1e309", "", "0x1"]))
def test_recover_xyz_scale(tmp_path_factory, capsys, xyz, scale):
    out = tmp_path_factory.mktemp("recover") / "r.csv"
    argv = ["recover", "--xyz", *(repr(v) for v in xyz), "--range", "400", "700", "20", "--out", out]
    code, err = _cli(argv + ([] if scale is None else ["--xyz-scale", scale]), capsys)
    if scale is None and all(abs(v) <= 1 for v in xyz):
        assert code == 2 and "--xyz-scale" in err
    if scale not in (None, "1", "100"):
        assert code == 2 and "--xyz-scale" in err


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(illuminant=st.none() | st.text(max_size=12) | st.sampled_from(["declared", "D50", "none"]),
       observer=st.none() | st.text(max_size=12) | st.sampled_from(["declared", "1964"]),
       name=st.sampled_from(["colorport_d65_10_cp1252.cgats", "eci_weighting_d50_2.cgats", "wide.csv"]))
def test_xyz_conditions_options(capsys, illuminant, observer, name):
    argv = ["xyz", CORPUS / name, "--format", "csv"]
    argv += [] if illuminant is None else [f"--illuminant={illuminant}"]
    argv += [] if observer is None else [f"--observer={observer}"]
    code, err = _cli(argv, capsys)
    notes = [line for line in err.splitlines() if "declares" in line]
    assert len(notes) <= 1 and (code == 0 or not notes)


CLIENT = TestClient(create_app(), base_url="http://127.0.0.1")


@pytest.fixture(scope="module", autouse=True)
def _close_client():
    with CLIENT:
        yield


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.binary(max_size=2000) | st.sampled_from([(CORPUS / "colorport_latin1.cgats").read_bytes(),
                                                         (CORPUS / "utf16le_bom.tsv").read_bytes()]),
       raw=st.none() | st.text(max_size=40),
       observer=st.none() | st.text(max_size=12) | st.sampled_from(["1931", "1964", "2015-10"]))
def test_import_content_base64_and_observer(data, raw, observer):
    body: dict = {"filename": "f.cgats", "content_base64": base64.b64encode(data).decode() if raw is None else raw,
                  "scale": "unit"}
    if observer is not None:
        body["observer"] = observer
    r = CLIENT.post("/api/import", json=body)
    assert r.status_code in (200, 422, 429), r.text
    answer = r.json()
    if r.status_code == 200:
        assert "\n" not in answer["note"] and "encoding" in answer["metadata"]
    else:
        assert "\n" not in answer["error"] and len(answer["error"]) < 600, answer
