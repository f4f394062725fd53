"""Guided demonstrations: one small JSON file per demo, checked here, served to the pages.

Each file in ``static/demos/`` describes one of seed 002's suggested experiments (P. Sällström,
USIP Report 99-05, "suggested use" of each setting and "Some further demonstrations"), or a
lab's: where it runs (a setting of the explorer or a lab), the state it loads, what to look
at, a question, the answer the page reveals on a button, optionally a second state that shows
the suggested change done ("Show me"), and ``expect``: bounds on numbers the page shows, which
``tests/app/test_demos_browser.py`` reads off the page in Chromium for every demo. The format,
for teachers, is described in ``docs/demos.md``.

:func:`load_demo` reads one file and raises one :class:`DemoError` naming the file and the
first thing wrong with it; :func:`load_demos` reads a folder (every file must be valid);
``GET /api/demos`` (:data:`router`) serves the folder's demos to the pages.
"""

from __future__ import annotations

import json
import math
import re
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from fastapi import APIRouter

from . import presets as _presets
from .choices import ADAPTATIONS, DISPLAYS, GAMUTS, NORMALISATIONS

#: Largest demo file read, bytes (a demo is a few hundred words and at most three spectra).
MAX_DEMO_BYTES = 32_768
#: Most demo files read from one folder.
MAX_DEMOS = 200
#: Longest text of ``look``, ``question``, ``answer`` and ``do``, characters.
MAX_TEXT = 1200
#: Where a demo can run: the explorer's five settings and the labs.
SETTINGS = {f"setting{n}": n for n in range(1, 6)}
LABS = ("thinfilm", "reflectance", "solid", "light")
#: Distributions per setting (the editors of the page, in order).
EDITORS = {1: 1, 2: 2, 3: 2, 4: 3, 5: 2}
#: Patches (and number cards) per setting: 4 adds the perfect white, 5 the light and the product.
PATCHES = {1: 1, 2: 2, 3: 2, 4: 3, 5: 4}
#: What a lab's state may set (the keys of the lab's URL hash) and, for numbers, their range.
LAB_KEYS: dict[str, dict[str, tuple[float, float] | None]] = {
    "thinfilm": {"film": None, "model": None, "light": None, "display": None,
                 "angle": (0.0, 80.0), "d": (0.0, 1500.0)},
    "reflectance": {"light": None, "step": None, "x": (0.0, 1.0), "y": (0.001, 1.0),
                    "Y": (0.5, 100.0)},
    "solid": {"light": None, "display": None, "second": None, "Y": (1.0, 99.0),
              "sample": (1.0, 14.0), "mismatch": (0.0, 1.0)},
    "light": {"kind": None, "name": None, "T": (1000.0, 25000.0), "display": None},
}
#: What ``expect`` may bound: per patch in the explorer, page-wide for ΔE00 and the labs.
PATCH_QUANTITIES = ("lambda_d", "purity", "L", "chroma", "Y", "x", "y")
PAGE_QUANTITIES = {"explorer": ("dE00",),
                   "thinfilm": ("Y", "thickness_nm"),
                   "reflectance": ("unconstrained_min", "unit_min", "unit_max", "max_Y"),
                   "solid": ("mismatch_dEab_max",), "light": ("Ra", "R9", "Rf", "Rg", "cct_K")}
_ID = re.compile(r"[a-z0-9][a-z0-9-]{0,47}")
_TEXT_KEYS = ("title", "look", "question", "answer")
_KEYS = {"id", "title", "where", "seed", "state", "then", "look", "question", "answer", "expect"}


class DemoError(ValueError):
    """A demo file that is not a valid demonstration (the message names the file and why)."""


#: Setting 5's modes (``state.mode``): filters in series, or two spotlights (issue 28 item 7).
MODES5 = ("series", "additive")


def _preset_keys(setting: int, editor: int, mode: str = "series") -> set[str]:
    """The keys (``"1"``-``"8"``) of the defaults an editor of a setting can start from."""
    tables: dict[int, list[Any]] = {
        1: _presets.SETTING1, 2: _presets.SETTING2_LEFT if editor == 0 else _presets.SETTING2_RIGHT,
        3: _presets.SETTING3,
        5: _presets.SETTING5_ADDITIVE if mode == "additive" else _presets.SETTING5,
        4: _presets.SETTING4_ILLUMINANTS if editor == 0 else _presets.SETTING4_SAMPLES}
    return {row[0] for row in tables[setting]}


def _text(value: object, what: str, limit: int = MAX_TEXT) -> str:
    if not isinstance(value, str) or not value.strip() or len(value) > limit:
        raise DemoError(f"{what} must be a non-empty text of at most {limit} characters")
    return value


def _number(value: object, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise DemoError(f"{what} must be a finite number")
    return float(value)


def _level(value: object, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 30:
        raise DemoError(f"{what} must be a whole level 0-30")
    return value


def _distribution(spec: object, setting: int, editor: int, what: str,
                  mode: str = "series") -> dict[str, Any]:
    """One editor's distribution: a default of the setting (``preset``), 31 ``levels`` or a
    ``constant``, with optional ``set`` ({"460": 9}: the level of single 10 nm bins) and ``name``."""
    if not isinstance(spec, dict):
        raise DemoError(f"{what} must be an object")
    extra = set(spec) - {"preset", "levels", "constant", "set", "name"}
    if extra:
        raise DemoError(f"{what} has unknown keys {sorted(extra)}")
    sources = [k for k in ("preset", "levels", "constant") if k in spec]
    if len(sources) != 1:
        raise DemoError(f"{what} needs exactly one of preset, levels, constant")
    if "preset" in spec and (not isinstance(spec["preset"], str)
                             or spec["preset"] not in _preset_keys(setting, editor, mode)):
        raise DemoError(f"{what}.preset must be one of {sorted(_preset_keys(setting, editor, mode))}"
                        f" (the keys of setting {setting}'s defaults for this distribution)")
    if "levels" in spec:
        levels = spec["levels"]
        if not isinstance(levels, list) or len(levels) != 31:
            raise DemoError(f"{what}.levels must be a list of 31 levels (400-700 nm, 10 nm)")
        for k, v in enumerate(levels):
            _level(v, f"{what}.levels[{k}]")
    if "constant" in spec:
        _level(spec["constant"], f"{what}.constant")
    bins = spec.get("set", {})
    if not isinstance(bins, dict) or len(bins) > 31:
        raise DemoError(f"{what}.set must be an object of at most 31 wavelengths")
    for nm, v in bins.items():
        if not (isinstance(nm, str) and nm.isdigit() and 400 <= int(nm) <= 700 and int(nm) % 10 == 0):
            raise DemoError(f"{what}.set: {nm!r} is not a wavelength 400-700 nm on the 10 nm grid")
        _level(v, f"{what}.set[{nm}]")
    if "name" in spec:
        _text(spec["name"], f"{what}.name", 60)
    return spec


def _state(state: object, where: str, what: str) -> dict[str, Any]:
    if not isinstance(state, dict):
        raise DemoError(f"{what} must be an object")
    if where in SETTINGS:
        n = SETTINGS[where]
        choices = {"display": DISPLAYS, "gamut": GAMUTS, "normalise": NORMALISATIONS,
                   "adaptation": ADAPTATIONS}
        extra = set(state) - {"distributions", *choices, *(("mode",) if n == 5 else ())}
        if extra:
            raise DemoError(f"{what} has unknown keys {sorted(extra)}")
        mode = state.get("mode", "series")
        if mode not in MODES5:  # compared as given: a list or number is refused too
            raise DemoError(f"{what}.mode must be one of {list(MODES5)} (setting 5: filters in "
                            f"series or two spotlights)")
        for key, allowed in choices.items():
            if key in state and (not isinstance(state[key], str) or state[key] not in allowed):
                raise DemoError(f"{what}.{key} must be one of {list(allowed)}")
        dists = state.get("distributions")
        if not isinstance(dists, list) or len(dists) != EDITORS[n]:
            raise DemoError(f"{what}.distributions must list {EDITORS[n]} distribution(s) for setting {n}")
        for i, d in enumerate(dists):
            _distribution(d, n, i, f"{what}.distributions[{i}]", mode)
        return state
    allowed_keys = LAB_KEYS[where]
    for key, value in state.items():
        if key not in allowed_keys:
            raise DemoError(f"{what}: {key!r} is not a setting of the {where} lab"
                            f" (accepted: {sorted(allowed_keys)})")
        bounds = allowed_keys[key]
        if bounds is None:
            _text(value, f"{what}.{key}", 60)
        elif not bounds[0] <= _number(value, f"{what}.{key}") <= bounds[1]:
            raise DemoError(f"{what}.{key} must lie in {bounds[0]:g}-{bounds[1]:g}")
    return state


def _expect(items: object, where: str, has_then: bool) -> list[dict[str, Any]]:
    if not isinstance(items, list) or not 1 <= len(items) <= 12:
        raise DemoError("expect must list 1-12 checks")
    page = "explorer" if where in SETTINGS else where
    count = PATCHES[SETTINGS[where]] if where in SETTINGS else 0
    for j, e in enumerate(items):
        what = f"expect[{j}]"
        if not isinstance(e, dict):
            raise DemoError(f"{what} must be an object")
        extra = set(e) - {"at", "quantity", "patch", "min", "max", "min_change", "max_change", "why"}
        if extra:
            raise DemoError(f"{what} has unknown keys {sorted(extra)}")
        at = e.get("at", "state")
        if at not in ("state", "then") or (at == "then" and not has_then):
            raise DemoError(f"{what}.at must be 'state'" + (" or 'then'" if has_then else " (the demo has no 'then')"))
        q = e.get("quantity")
        if not isinstance(q, str):
            q = None  # not a name: refused below with the accepted names
        per_patch = where in SETTINGS and q in PATCH_QUANTITIES
        if not per_patch and q not in PAGE_QUANTITIES[page]:
            raise DemoError(f"{what}.quantity must be one of "
                            f"{list(PATCH_QUANTITIES if where in SETTINGS else ()) + list(PAGE_QUANTITIES[page])}")
        if per_patch:
            p = e.get("patch")
            if isinstance(p, bool) or not isinstance(p, int) or not 0 <= p < count:
                raise DemoError(f"{what}.patch must be a patch index 0-{count - 1} of setting {SETTINGS[where]}")
        elif "patch" in e:
            raise DemoError(f"{what}: {q} belongs to the page, not to a patch")
        bounds = [k for k in ("min", "max", "min_change", "max_change") if k in e]
        if not bounds:
            raise DemoError(f"{what} needs at least one of min, max, min_change, max_change")
        for k in bounds:
            _number(e[k], f"{what}.{k}")
        if any(k.endswith("_change") for k in bounds) and at != "then":
            raise DemoError(f"{what}: min_change/max_change compare 'then' with 'state': set at to 'then'")
        if "why" in e:
            _text(e["why"], f"{what}.why", 300)
    return items


def validate_demo(data: object, name: str = "demo") -> dict[str, Any]:
    """Check one demo (the parsed JSON of its file) and return it.

    Parameters
    ----------
    data : object
        The parsed JSON.
    name : str
        The file's stem; a demo's ``id`` must equal it.

    Returns
    -------
    dict
        ``data`` itself, valid.

    Raises
    ------
    DemoError
        The first thing wrong, e.g. an unknown key, a missing text, a preset key the setting
        lacks, a level outside 0-30 or a check the page cannot read.

    Examples
    --------
    >>> demo = {"id": "grey", "title": "A grey", "where": "setting1",
    ...         "state": {"distributions": [{"constant": 15}]},
    ...         "look": "The patch.", "question": "Which colour?", "answer": "Grey.",
    ...         "expect": [{"quantity": "chroma", "patch": 0, "max": 1.5}]}
    >>> validate_demo(demo, "grey")["where"]
    'setting1'
    """
    if not isinstance(data, dict):
        raise DemoError("a demo must be a JSON object")
    extra = set(data) - _KEYS
    if extra:
        raise DemoError(f"unknown keys {sorted(extra)} (accepted: {sorted(_KEYS)})")
    if not isinstance(data.get("id"), str) or not _ID.fullmatch(data["id"]):
        raise DemoError("id must be 1-48 characters a-z, 0-9 and '-'")
    if data["id"] != name:
        raise DemoError(f"id {data['id']!r} must equal the file's name ({name!r})")
    where = data.get("where")
    if not isinstance(where, str) or (where not in SETTINGS and where not in LABS):
        raise DemoError(f"where must be one of {[*SETTINGS, *LABS]}")
    for key in _TEXT_KEYS:
        _text(data.get(key), key, 120 if key == "title" else MAX_TEXT)
    if "seed" in data:
        _text(data["seed"], "seed", 300)
    _state(data.get("state"), where, "state")
    then = data.get("then")
    if then is not None:
        if not isinstance(then, dict) or "do" not in then:
            raise DemoError("then must be an object with 'do' (what the change is) and 'state'")
        if set(then) - {"do", "state"}:
            raise DemoError(f"then has unknown keys {sorted(set(then) - {'do', 'state'})}")
        _text(then["do"], "then.do", 300)
        _state(then.get("state"), where, "then.state")
    _expect(data.get("expect"), where, then is not None)
    return data


def load_demo(path: str | Path) -> dict[str, Any]:
    """Read and check one demo file.

    Parameters
    ----------
    path : str or Path
        A ``.json`` file of at most :data:`MAX_DEMO_BYTES` bytes, UTF-8.

    Returns
    -------
    dict
        The demo (see :func:`validate_demo`).

    Raises
    ------
    DemoError
        One message naming the file and what is wrong: too large, not UTF-8 JSON, or not a
        valid demo.

    Examples
    --------
    >>> import json, pathlib, tempfile
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "bad.json").write_text(json.dumps({"id": "bad"}))
    >>> try:
    ...     load_demo(folder / "bad.json")
    ... except DemoError as exc:
    ...     print(str(exc)[:40])
    demo file bad.json: where must be one of
    """
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > MAX_DEMO_BYTES:
            raise DemoError(f"the file has {size} bytes; a demo has at most {MAX_DEMO_BYTES}")
        with path.open("rb") as f:
            raw = f.read(MAX_DEMO_BYTES + 1)
        if len(raw) > MAX_DEMO_BYTES:
            raise DemoError(f"the file has more than {MAX_DEMO_BYTES} bytes")
        try:
            data = json.loads(raw.decode("utf-8"), parse_constant=_no_constant)
        except (UnicodeDecodeError, ValueError, RecursionError) as exc:
            raise DemoError(f"not valid UTF-8 JSON ({str(exc).splitlines()[0][:120]})") from None
        return validate_demo(data, path.stem)
    except DemoError as exc:
        raise DemoError(f"demo file {path.name}: {exc}") from None
    except OSError as exc:
        raise DemoError(f"demo file {path.name}: cannot be read ({exc.strerror})") from None


def _no_constant(name: str) -> None:
    raise ValueError(f"{name} is not a number JSON allows")


def load_demos(folder: str | Path) -> list[dict[str, Any]]:
    """Every ``*.json`` demo of a folder, sorted by where and file name; one bad file raises.

    Parameters
    ----------
    folder : str or Path
        A folder of demo files (at most :data:`MAX_DEMOS`).

    Returns
    -------
    list of dict
        The demos.

    Raises
    ------
    DemoError
        The first bad file (its name and why), or too many files.

    Examples
    --------
    >>> len(load_demos(DEMO_FOLDER)) >= 7
    True
    """
    files = sorted(Path(folder).glob("*.json"))
    if len(files) > MAX_DEMOS:
        raise DemoError(f"{folder}: {len(files)} demo files; at most {MAX_DEMOS} are read")
    order = [*SETTINGS, *LABS]
    demos = [load_demo(f) for f in files]
    return sorted(demos, key=lambda d: (order.index(d["where"]), d["id"]))


#: The demos the app serves.
DEMO_FOLDER = Path(str(resources.files("spectrocolor.app") / "static" / "demos"))

router = APIRouter()


@lru_cache(maxsize=1)
def _served() -> list[dict[str, Any]]:
    return load_demos(DEMO_FOLDER)


@router.get("/api/demos")
def demos_route() -> dict[str, Any]:
    """All demos, as ``{"demos": [...]}`` (read and checked once per server)."""
    return {"demos": _served()}
