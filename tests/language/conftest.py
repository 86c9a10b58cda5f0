"""The installed action plugins, for every sentence test in this folder (read once per module, as a user's
``perform`` reads them once per sentence)."""

from __future__ import annotations

import pytest

from l2p_bullet.plugins import registry


@pytest.fixture(scope="module")
def plugins():
    return registry.discover()
