"""Shared test fixtures and switches."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
SEEDS = REPO.parent / "shared" / "seeds"
ARTIFACTS = REPO / "artifacts"
CHROMIUM = Path("/usr/bin/chromium")


@pytest.fixture(scope="session")
def artifacts_dir() -> Path:
    """Folder for pictures and screenshots the tests write for a person to look at."""
    ARTIFACTS.mkdir(exist_ok=True)
    return ARTIFACTS


@pytest.fixture(scope="session")
def base_url():
    """The explorer's server on a free loopback port, for every browser test of the session."""
    from appbrowser import serve

    with serve() as url:
        yield url


@pytest.fixture(scope="session")
def browser():
    """One headless Debian Chromium shared by the browser tests (each test opens its own pages)."""
    from appbrowser import chromium

    with chromium() as b:
        yield b


@pytest.hookimpl(tryfirst=True)  # before -m deselects: the slow mark must be there
def pytest_collection_modifyitems(config, items):
    """Browser and cluster tests are slow (``-m "not slow"`` leaves them out); browser tests need
    Debian's Chromium: skip them loudly here, fail in CI."""
    for item in items:
        if "browser" in item.keywords or "cluster" in item.keywords:
            item.add_marker(pytest.mark.slow)
    if CHROMIUM.exists():
        return
    if os.environ.get("SPECTROCOLOR_REQUIRE_BROWSER"):
        raise pytest.UsageError(
            f"{CHROMIUM} is missing but SPECTROCOLOR_REQUIRE_BROWSER is set: install it with `apt-get install chromium`"
        )
    skip = pytest.mark.skip(
        reason=f"BROWSER TESTS SKIPPED: {CHROMIUM} not found; `apt-get install chromium` to run them"
    )
    for item in items:
        if "browser" in item.keywords:
            item.add_marker(skip)
