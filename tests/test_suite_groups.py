"""The suite's units of work under pytest-xdist's ``--dist loadgroup`` (``make test``): a module is one unit, so
its module-scoped fixtures are made once, on one worker (tests/conftest.py)."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

HERE = Path(__file__).resolve().parent


def _conftest(config):
    """tests/conftest.py as pytest loaded it (``import conftest`` may find another folder's conftest)."""
    return next(p for p in config.pluginmanager.get_plugins()
                if Path(getattr(p, "__file__", "") or "/").resolve() == HERE / "conftest.py")


def test_a_node_id_ends_with_the_group_xdist_splits_on(request):
    from xdist.scheduler.loadgroup import LoadGroupScheduling

    if not hasattr(request.node, "_id"):
        pytest.skip("a pytest whose node ids are strings: xdist's own suffix groups the tests there")
    node_id = type(request.node._id)
    for plain in (str(request.node.nodeid).split("@")[0], "tests/x/test_y.py::test_z[a-b@c]"):
        item = SimpleNamespace(_id=node_id.parse(plain))
        _conftest(request.config)._name_the_group(item, "tests/elsewhere.py")
        assert str(item._id) == f"{plain}@tests/elsewhere.py"
        assert LoadGroupScheduling._split_scope(None, str(item._id)) == "tests/elsewhere.py"
        assert (item._id.path, item._id.names, item._id.params) == (lambda p: (p.path, p.names, p.params))(
            node_id.parse(plain))


def test_under_loadgroup_this_module_is_one_unit_of_work(request):
    if not getattr(request.config.option, "loadgroup", False):
        pytest.skip("only under pytest-xdist's --dist loadgroup (make test)")
    assert request.node.nodeid.endswith("@tests/test_suite_groups.py")
