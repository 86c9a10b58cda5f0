"""Fixtures shared by several test modules. Only one definition of a session fixture may exist: the
headless Chromium is started once per test session (Playwright's sync API runs one instance per thread),
for the review app's and the teach page's browser tests alike.

The suite must not depend on what else is installed (issue 26: a user who followed the plugin tutorial
had ``l2p-left-of`` and ``l2p-between`` in the environment, and two tests failed). Plugins (actions, arms,
manners) that were installed before the suite started, other than l2p-bullet's own built-ins, are hidden
from the registries in the tests and in every Python they start (tests/hide_plugins.py; ``pytest_report_header``
names them); the plugins a test installs itself in a temporary site folder (tests/plugin_fixtures.py)
stay visible. tests/test_isolation.py runs part of the suite with such plugins on the path and from
another directory.
"""

from __future__ import annotations

import atexit
import dataclasses
import json
import os
import shutil
import tempfile
from importlib import metadata
from pathlib import Path

import hide_plugins
import pytest
from review_fixtures import CHROMIUM, CHROMIUM_FLAGS

FOREIGN = frozenset(hide_plugins.key(ep) for group in hide_plugins.GROUPS for ep in metadata.entry_points(group=group)
                    if hide_plugins.dist_name(ep) != "l2p-bullet")
"""Plugins (actions, arms, manners) installed in the environment before the tests started (not l2p-bullet's
built-ins)."""

BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
"""One BLAS / OpenMP thread in the tests and in every Python they start, unless the person running them chose:
the suite runs a pytest-xdist worker per core, and numpy's OpenBLAS, which scores the planner's moves with the
progress LSTMs in ``perform``, spins a second thread per process on those small products (a planned small mover
by a tall anchor: 6.0 CPU s with it, 2.0 without, on the 2-core machine). Set here, before numpy is imported,
so the xdist workers and the subprocesses inherit it; results do not depend on it (test_determinism_audit.py
compares runs across thread counts)."""
for _name in BLAS_THREADS:
    os.environ.setdefault(_name, "1")

if FOREIGN:
    _site = Path(tempfile.mkdtemp(prefix=hide_plugins.SITE_PREFIX))
    atexit.register(shutil.rmtree, _site, True)
    shutil.copy(hide_plugins.__file__, _site / "sitecustomize.py")
    os.environ[hide_plugins.VARIABLE] = json.dumps(sorted(FOREIGN | hide_plugins.hidden()))
    os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (str(_site), os.environ.get("PYTHONPATH")) if p)
    hide_plugins.install()


def pytest_report_header(config) -> str | None:
    if FOREIGN:
        names = ", ".join(sorted(f"{name} ({dist})" for name, _, dist, _, _ in FOREIGN))
        return f"installed plugins hidden from the tests: {names}"
    return None


def pytest_configure(config) -> None:
    if getattr(config.option, "dist", "no") == "loadgroup":
        # the modules are ordered here, longest first (pytest_collection_modifyitems); xdist's own reorder
        # (by number of tests) would put a module of many quick tests before one of a few long ones
        config.option.loadscopereorder = False


SLOW_S, QUICK_S = 10.0, 0.3
"""Seconds a slow test and another test take, as the suite's durations have them on the 2-core machine (a
slow test takes 2 s or more, most 5-20 s; most quick ones a few tenths): only their ratio orders the groups."""


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items) -> None:
    """Under pytest-xdist with ``--dist loadgroup`` (``make test``), each module is one unit of work, so
    its module-scoped fixtures (a perform, a trained plugin, a virtual environment) are made once, on one
    worker; a test's own ``xdist_group`` mark groups tests across modules instead (the Ray tests, which
    must not start two clusters at once). The longest groups go first, so that the last unit handed out is a
    short one and the workers finish together: a group's length is guessed from its tests, SLOW_S for each
    slow one (``slow(SECONDS)`` for one that takes far longer) and QUICK_S for each other (a module of a
    hundred quick tests outlasts one of a single slow one; xdist hands a worker its next unit while its last
    two tests still run)."""
    if not getattr(config.option, "loadgroup", False):  # what an xdist worker is told of --dist loadgroup
        return
    group = {}
    for item in items:
        mark = item.get_closest_marker("xdist_group")
        if mark is None:
            group[item] = item.nodeid.split("::")[0]
            item.add_marker(pytest.mark.xdist_group(group[item]))
        else:
            group[item] = str(mark.args[0] if mark.args else mark.kwargs.get("name", "default"))
        _name_the_group(item, group[item])
    length: dict[str, float] = {}
    for item in items:
        slow = item.get_closest_marker("slow")
        guess = QUICK_S if slow is None else float(slow.args[0]) if slow.args else SLOW_S
        length[group[item]] = length.get(group[item], 0.0) + guess
    items.sort(key=lambda item: -length[group[item]])


def _name_the_group(item, name: str) -> None:
    """End the item's node id with ``@name``, the suffix by which pytest-xdist's scheduler knows a group. xdist
    writes it to ``item._nodeid``, which pytest 9.2 no longer reads (a node's id is its structured ``_id``): without
    this every test would be a unit of its own, a module's tests spread over both workers, and its module-scoped
    fixtures (a trained plugin, a perform) made on each. Where ``_id`` is not pytest's structured id, xdist's own
    suffix works and nothing is done here."""
    node_id = getattr(item, "_id", None)
    if node_id is None or not dataclasses.is_dataclass(node_id) or not hasattr(node_id, "_str_cache"):
        return
    grouped = dataclasses.replace(node_id)  # the same path, names and parameters; only its text gains the suffix
    object.__setattr__(grouped, "_str_cache", f"{node_id}@{name}")
    item._id = grouped


@pytest.fixture(scope="session")
def chromium_session():
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


@pytest.fixture
def chromium(chromium_session):
    """The session's Chromium for one test; the pages the test opened are closed after it. A page left open
    keeps drawing (the review app's 3-D view, a video) in Chromium's software GPU process, a quarter of a
    core for the rest of the session on the 2-core machine."""
    yield chromium_session
    for context in chromium_session.contexts:
        context.close()
