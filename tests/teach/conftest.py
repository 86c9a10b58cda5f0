"""The teach tests' shared fixture: a composite plugin's teach app, for every module that posts rows to it."""

from __future__ import annotations

import pytest
from teach_fixtures import Rows


@pytest.fixture
def rows(tmp_path):
    """A composite plugin's teach app (:class:`Rows`), stopped after the test."""
    r = Rows(tmp_path)
    yield r
    r.server.stop()
