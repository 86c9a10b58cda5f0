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


def test_the_cpu_report_sums_each_group_and_hands_the_longest_out_first():
    import suite_cpu

    assert suite_cpu.two_workers({"a": 5.0, "b": 3.0, "c": 3.0, "d": 1.0}) == [6.0, 6.0]  # a+d, b+c
    assert suite_cpu.two_workers({"a": 9.0, "b": 1.0, "c": 1.0}) == [9.0, 2.0]  # the longest group bounds the time
    rows = [{"test": "t.py::x", "group": "t.py", "own_s": 1.0, "children_s": 2.0, "wall_s": 3.5, "worker": "gw0"},
            {"test": "t.py::y", "group": "t.py", "own_s": 0.5, "children_s": 0.0, "wall_s": 0.6, "worker": "gw0"},
            {"test": "u.py::z", "group": "ray", "own_s": 0.25, "children_s": 0.0, "wall_s": 0.3, "worker": "gw1"}]
    text = suite_cpu.report(rows)
    assert text.startswith("3 tests, 2 groups, 3.8 CPU s (1.8 in the workers, 2.0 in their subprocesses)")
    assert "two workers, longest group first: 3.5 + 0.2 CPU s" in text
    assert "    3.5     1.5     2.0     2  t.py" in text and "    3.0  t.py::x" in text
