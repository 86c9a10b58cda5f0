"""Hide the plugins (actions, arms, manners) that were installed before the tests started (tests/conftest.py).

The conftest lists them (entry point, distribution and where it lies) in ``L2P_TESTS_HIDDEN_PLUGINS``
and copies this file as ``sitecustomize.py`` into a folder it puts first on ``PYTHONPATH``, so every
Python the tests start (``l2p-bullet`` in a subprocess, the evaluate pool's spawned workers, Ray's
workers) hides them as the test process does. Plugins a test installs itself (a temporary site folder,
tests/plugin_fixtures.py) lie elsewhere and stay visible.
"""

from __future__ import annotations

import json
import os
from importlib import metadata

GROUPS = ("l2p_bullet.actions", "l2p_bullet.arms", "l2p_bullet.manners")
"""Every entry-point group l2p-bullet discovers plugins in: a user's arm or manner plugin changes what the
tests' listings see as much as an action plugin does."""
VARIABLE = "L2P_TESTS_HIDDEN_PLUGINS"
SITE_PREFIX = "l2p-tests-site-"
"""How the conftest's folder holding this file as sitecustomize.py is named: a test that starts a Python with
an environment of its own keeps that folder on its PYTHONPATH (tests/plugins/test_plugin_install.py)."""


def dist_name(ep: metadata.EntryPoint) -> str:
    dist = getattr(ep, "dist", None)
    return "" if dist is None else str(dist.metadata["Name"] or "").lower().replace("_", "-")


def key(ep: metadata.EntryPoint) -> tuple[str, str, str, str, str]:
    """An installed entry point: its name, value, distribution, where that distribution lies, and its group."""
    dist = getattr(ep, "dist", None)
    return ep.name, ep.value, dist_name(ep), "" if dist is None else str(dist.locate_file("")), ep.group


def hidden() -> set[tuple[str, ...]]:
    return {tuple(k) for k in json.loads(os.environ.get(VARIABLE) or "[]")}


def install() -> None:
    """Make ``importlib.metadata.entry_points`` leave out the hidden plugins. Installed once per process;
    the list is read from the environment at every call, so a nested test run can add to it."""
    if not hidden() or getattr(metadata.entry_points, "hides_plugins", False):
        return
    everything = metadata.entry_points

    def entry_points(**params):
        found = everything(**params)
        if params.get("group") not in GROUPS:
            return found
        keys = hidden()
        return metadata.EntryPoints(ep for ep in found if key(ep) not in keys)

    entry_points.hides_plugins = True
    metadata.entry_points = entry_points


if __name__ == "sitecustomize":
    install()
