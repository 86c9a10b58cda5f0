"""The installed plugins, for every sentence test in this folder: read once per module, as a user's ``perform``
reads them once per sentence.

Reading a sentence also asks :func:`registry.discover` for the installed composites, once per sentence
(``plugins/once.py``: the scan of every distribution's entry points and the manifests, about 7 ms), the largest share
of the CPU of the corpus tests' thousands of sentences. No test in this folder installs or hides a plugin, so each
module reads them once here (:func:`_installed_read_once`); the discovery per sentence runs unchanged in the rest of
the suite (chain/, cli/, plugins/), where plugins are installed and broken between reads.
"""

from __future__ import annotations

import sys

import pytest

from l2p_bullet.plugins import registry


@pytest.fixture(scope="module", autouse=True)
def _installed_read_once():
    real, kept = registry.discover, {}

    def discover(kind: str = "action") -> list:
        key = (kind, tuple(sys.path))  # a folder put on the path could hold a plugin: read anew then
        if key not in kept:
            kept[key] = real(kind)
        return list(kept[key])

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(registry, "discover", discover)
        yield


@pytest.fixture(scope="module")
def plugins(_installed_read_once):
    return registry.discover()
