"""Fixtures shared by several test modules. Only one definition of a session fixture may exist: the
headless Chromium is started once per test session (Playwright's sync API runs one instance per thread),
for the review app's and the teach page's browser tests alike."""

from __future__ import annotations

import os

import pytest
from review_fixtures import CHROMIUM, CHROMIUM_FLAGS


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
