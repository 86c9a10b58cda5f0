"""Fixtures shared by several test modules. Only one definition of a session fixture may exist: the
headless Chromium is started once per test session (Playwright's sync API runs one instance per thread),
for the review app's and the teach page's browser tests alike.

The suite must not depend on what else is installed (issue 26: a user who followed the plugin tutorial
had ``l2p-left-of`` and ``l2p-between`` in the environment, and two tests failed). Action plugins that
were installed before the suite started, other than l2p-bullet's own built-ins, are hidden from the
registry in every test (``pytest_report_header`` names them); the plugins a test installs itself in a
temporary site folder (tests/plugin_fixtures.py) stay visible. tests/test_isolation.py runs part of the
suite with such a plugin on the path and from another directory.
"""

from __future__ import annotations

import os
from importlib import metadata

import pytest
from review_fixtures import CHROMIUM, CHROMIUM_FLAGS

GROUP = "l2p_bullet.actions"


def _dist_name(ep: metadata.EntryPoint) -> str:
    dist = getattr(ep, "dist", None)
    return "" if dist is None else str(dist.metadata["Name"] or "").lower().replace("_", "-")


def _key(ep: metadata.EntryPoint) -> tuple[str, str, str, str]:
    """An installed entry point: its name, value, distribution and where that distribution lies."""
    dist = getattr(ep, "dist", None)
    return ep.name, ep.value, _dist_name(ep), "" if dist is None else str(dist.locate_file(""))


FOREIGN = frozenset(_key(ep) for ep in metadata.entry_points(group=GROUP) if _dist_name(ep) != "l2p-bullet")
"""Action plugins installed in the environment before the tests started (not l2p-bullet's built-ins)."""


def pytest_report_header(config) -> str | None:
    if FOREIGN:
        names = ", ".join(sorted(f"{name} ({dist})" for name, _, dist, _ in FOREIGN))
        return f"installed action plugins hidden from the tests: {names}"
    return None


@pytest.fixture(autouse=True)
def _installed_plugins_hidden(monkeypatch):
    """The registry sees the built-ins and what the test itself installs, never the user's own plugins."""
    if not FOREIGN:
        return
    everything = metadata.entry_points

    def entry_points(**params):
        found = everything(**params)
        if params.get("group") != GROUP:
            return found
        return metadata.EntryPoints(ep for ep in found if _key(ep) not in FOREIGN)

    monkeypatch.setattr(metadata, "entry_points", entry_points)


@pytest.fixture(scope="session")
def chromium():
    """Headless Debian Chromium through Playwright. CI (CI=true) must have it: there it fails, never skips."""
    if not os.path.exists(CHROMIUM):
        message = f"{CHROMIUM} is missing (apt-get install -y chromium; .ci/run installs it)"
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail(message)
        pytest.skip(message)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_FLAGS, headless=True)
        yield browser
        browser.close()
