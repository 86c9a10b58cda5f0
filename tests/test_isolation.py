"""The suite passes whatever else is installed and from any directory (issue 26, item 1; arm and manner plugins
since 2026-11-28).

A user who followed docs/perform.md's plugin tutorial has ``l2p-left-of`` ("to the left of") and
``l2p-between`` installed next to l2p-bullet. This runs a representative part of the suite in a fresh
pytest with two such plugins on the path (installed-looking distributions, tests/plugin_fixtures.py: a
trained left-of and an untrained between) and from an unrelated working directory: the plugin tests
(registry, bundles, the hostile-plugin matrix with its own "left-of", a subprocess seeing what the test
sees) and parsing. The conftest hides the pre-installed plugins from every test and every Python the
tests start (tests/hide_plugins.py) and says so in the header.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from plugin_fixtures import copy_builtin_as_plugin, make_bundle, make_dist

TESTS = Path(__file__).resolve().parent
SUBSET = ["plugins/test_registry.py", "plugins/test_bundle.py", "cli/test_language.py",
          "manners/test_manners.py::test_the_builtins_register_through_the_entry_point_group",
          "manners/test_manners.py::test_manners_lists_every_manner_with_its_verbs_and_package",
          "embodiment/test_arms.py::test_the_built_in_arms_register_through_the_entry_point_group",
          "embodiment/test_arms.py::test_arms_lists_the_three_arms_as_json",
          "plugins/test_hostile_plugins.py::test_an_untrained_plugin_owning_the_phrase_is_named",
          "plugins/test_hostile_plugins.py::test_a_plugin_claiming_a_builtin_phrase_blocks_only_that_phrase"]


@pytest.mark.slow
def test_the_suite_ignores_installed_plugins_and_the_working_directory(tmp_path):
    site, cwd = tmp_path / "site", tmp_path / "elsewhere"
    cwd.mkdir()
    # the tutorial's module and distribution names: l2p_left_of in l2p-left-of, trained (a built-in's weights)
    copy_builtin_as_plugin(site, "next-to", "left-of", ["to the left of"], dist="l2p-left-of", module="l2p_left_of")
    make_bundle(site / "l2p_between", "between", ["between"], weights=False)
    make_dist(site, "l2p-between", {"between": "l2p_between"})
    # a manner plugin ("roll") and an arm plugin whose module is gone: the manners and arms listings must not
    # see them in the tests either
    (site / "l2p_roll").mkdir()
    (site / "l2p_roll" / "__init__.py").write_text(
        "from l2p_bullet.manners.spec import MannerSpec\n"
        "MANNER = MannerSpec(name='roll', verbs=('roll',), motion='slide', signature='on-table')\n")
    info = site / "l2p_roll-0.3.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: l2p-roll\nVersion: 0.3\n")
    (info / "entry_points.txt").write_text("[l2p_bullet.manners]\nroll = l2p_roll\n"
                                           "[l2p_bullet.arms]\nur5 = l2p_ur5_gone:ARM\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(site), os.environ.get("PYTHONPATH", "")])}
    seen = subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "actions", "--json"], cwd=cwd, env=env,
                          capture_output=True, text=True, check=True).stdout
    assert '"left-of"' in seen and '"between"' in seen  # the plugins are really installed for l2p-bullet
    manners = subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "manners", "--json"], cwd=cwd, env=env,
                             capture_output=True, text=True).stdout
    assert '"roll"' in manners
    r = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider",
                        *[str(TESTS / t) for t in SUBSET]], cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-2000:]
    assert ("hidden from the tests: between (l2p-between), left-of (l2p-left-of), roll (l2p-roll), ur5 (l2p-roll)"
            in r.stdout), r.stdout[:1000]
    assert " passed" in r.stdout and "failed" not in r.stdout
    assert not any(cwd.iterdir()), sorted(p.name for p in cwd.iterdir())  # nothing written where it ran


@pytest.mark.slow
def test_the_plugin_tests_venv_hides_a_plugin_installed_in_the_users_environment(tmp_path):
    """The same with "left-of" installed in the environment itself (its site-packages, as pip puts it), which
    tests/plugins/test_plugin_install.py layers its throw-away environment on: that environment saw the
    user's plugin and `new-action left-of` refused the name, erroring 4 tests."""
    import sysconfig

    user = tmp_path / "user-env"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(user)], check=True)
    site = next((user / "lib").glob("python3*/site-packages"))
    (site / "zz_host_env.pth").write_text(f"import site; site.addsitedir({sysconfig.get_paths()['purelib']!r})\n")
    copy_builtin_as_plugin(site, "next-to", "left-of", ["to the left of"], dist="l2p-left-of", module="l2p_left_of")
    python = user / "bin" / "python"
    seen = subprocess.run([str(python), "-m", "l2p_bullet.cli", "actions", "--json"], capture_output=True, text=True,
                          check=True, cwd=tmp_path).stdout
    assert '"left-of"' in seen  # installed for l2p-bullet in that environment
    test = TESTS / "plugins" / "test_plugin_install.py::test_the_tutorials_names_are_free_in_the_test_environment"
    r = subprocess.run([str(python), "-m", "pytest", "-p", "no:cacheprovider", str(test)], cwd=tmp_path,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and "1 passed" in r.stdout, r.stdout[-3000:] + r.stderr[-2000:]
