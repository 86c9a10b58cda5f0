"""Plugin discovery through entry points: no imports at discovery, broken plugins reported, conflicts named.

Fake plugins are real installed distributions as far as importlib.metadata is concerned: a
``*.dist-info`` folder with METADATA and entry_points.txt in a temporary folder put on sys.path.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from click.testing import CliRunner
from plugin_fixtures import make_bundle, make_dist

from l2p_bullet.cli import main
from l2p_bullet.errors import PluginConflict, PluginError
from l2p_bullet.plugins import registry


@pytest.fixture
def plugins_dir(tmp_path, monkeypatch):
    """A site folder with one good plugin, one that explodes on import and several broken ones."""
    root = tmp_path / "site"
    make_bundle(root / "fk_good", "sideways", ["sideways", "off to the side of"])
    # Importing this module would raise: discovery must not import it.
    make_bundle(root / "fk_explodes", "upside", ["upside of"], init="raise RuntimeError('plugin bug: boom')\n")
    make_bundle(root / "fk_badtoml", "badtoml", [], manifest="phrases = [unterminated\n")
    make_bundle(root / "fk_untrained", "untrained", ["untrained to"], weights=False)
    make_bundle(root / "fk_nophrases", "nophrases", [], manifest='name = "nophrases"\nversion = "1"\n')
    # A plugin whose parent package would explode on import: locating the child must not run it.
    make_bundle(root / "fk_parent", "x", [], init="raise RuntimeError('parent imported')\n", weights=False,
                manifest="")
    make_bundle(root / "fk_parent" / "child", "nested", ["nested in"])
    make_dist(root, "fake-plugins", {
        "sideways": "fk_good", "upside": "fk_explodes", "badtoml": "fk_badtoml",
        "untrained": "fk_untrained", "nophrases": "fk_nophrases", "missing": "fk_not_there",
        "nested": "fk_parent.child",
    })
    monkeypatch.syspath_prepend(str(root))
    return root


def by_name(plugins):
    return {p.name: p for p in plugins}


def test_builtin_actions_are_found_through_the_entry_point_group():
    found = by_name(registry.discover())
    for name in ("closer", "away", "next-to", "past", "around"):
        assert found[name].package == "l2p-bullet"
        assert found[name].path is not None and found[name].path.name == name.replace("-", "_")


def test_discovery_reports_broken_plugins_without_importing(plugins_dir):
    found = by_name(registry.discover())
    assert not any(m.startswith("fk_") for m in sys.modules), "discovery imported plugin code"
    good = found["sideways"]
    assert good.ok and good.package == "fake-plugins" and good.package_version == "0.3"
    assert good.phrases == ("sideways", "off to the side of") and good.version == "1.2.0"
    assert good.metrics == {"final_progress": 0.91}
    assert found["nested"].ok and found["nested"].path == plugins_dir / "fk_parent" / "child"
    assert found["upside"].ok  # its bug only shows when it is loaded
    assert "not valid TOML" in found["badtoml"].error
    assert "no trained weights" in found["untrained"].error and "l2p-bullet train untrained" in found["untrained"].error
    assert '"phrases"' in found["nophrases"].error
    assert "fk_not_there is not installed" in found["missing"].error
    broken = {p.name for p in registry.broken()}
    assert {"badtoml", "untrained", "nophrases", "missing"} <= broken
    # The others still work: their phrases are in the table.
    table = registry.phrase_table()
    assert table["off to the side of"] == "sideways" and table["nested in"] == "nested"
    assert "untrained to" not in table


def test_load_reports_import_failure_with_name_and_package(plugins_dir):
    with pytest.raises(PluginError) as e:
        registry.load("upside")
    msg = str(e.value)
    assert '"upside"' in msg and "fake-plugins" in msg and "RuntimeError: plugin bug: boom" in msg


def test_load_of_broken_or_unknown_plugin_is_a_clear_error(plugins_dir):
    with pytest.raises(PluginError, match="cannot be used: no trained weights"):
        registry.load("untrained")
    with pytest.raises(PluginError, match='Did you mean "sideways"'):
        registry.load("sidewayz")


def test_duplicate_phrase_names_both_plugins(plugins_dir, tmp_path, monkeypatch):
    other = tmp_path / "other"
    make_bundle(other / "fk_rival", "rival", ["athwart", "sideways"])
    make_dist(other, "rival-plugin", {"rival": "fk_rival"})
    monkeypatch.syspath_prepend(str(other))
    # the contested phrase is blocked with an error naming both plugins; the others keep working
    table = registry.phrase_table()
    assert "sideways" not in table and table["athwart"] == "rival" and table["off to the side of"] == "sideways"
    e = registry.blocked_phrases()["sideways"]
    assert isinstance(e, PluginConflict) and e.claim == "sideways" and set(e.plugins) == {"rival", "sideways"}
    msg = str(e)
    assert '"sideways"' in msg and "fake-plugins" in msg and "rival-plugin" in msg and '"rival"' in msg


def test_two_plugins_of_one_name_are_both_broken(plugins_dir, tmp_path, monkeypatch):
    other = tmp_path / "other"
    make_bundle(other / "fk_twin", "sideways", ["twinned"])
    make_dist(other, "twin-plugin", {"sideways": "fk_twin"})
    monkeypatch.syspath_prepend(str(other))
    table = registry.phrase_table()
    assert "twinned" not in table and "sideways" not in table and table["nested in"] == "nested"
    twins = [p for p in registry.discover() if p.name == "sideways"]
    assert [p.package for p in twins] == ["fake-plugins", "twin-plugin"] and not any(p.ok for p in twins)
    assert all('both named "sideways" (packages fake-plugins 0.3 and twin-plugin 0.3)' in p.error for p in twins)
    blocked = registry.blocked_phrases()
    assert isinstance(blocked["twinned"], PluginError) and "both named" in str(blocked["twinned"])
    with pytest.raises(PluginConflict, match="both named"):
        registry.load("sideways")


def test_actions_command_lists_good_and_broken(plugins_dir):
    result = CliRunner().invoke(main, ["actions", "--json"])
    assert result.exit_code == 0, result.output
    rows = {r["name"]: r for r in json.loads(result.output)["actions"]}
    assert rows["sideways"]["ok"] and rows["sideways"]["phrases"] == ["sideways", "off to the side of"]
    assert rows["sideways"]["metrics"] == {"final_progress": 0.91} and rows["sideways"]["package"] == "fake-plugins"
    assert not rows["missing"]["ok"] and "not installed" in rows["missing"]["error"]
    text = CliRunner().invoke(main, ["actions"]).output
    assert "sideways" in text and "broken plugins" in text and "missing (package fake-plugins 0.3)" in text


def test_actions_check_loads_each_plugin(plugins_dir):
    pytest.importorskip("l2p_bullet.plugins.bundle")
    checked = CliRunner().invoke(main, ["actions", "--json", "--check"])
    rows = {r["name"]: r for r in json.loads(checked.output)["actions"]}
    assert not rows["upside"]["ok"] and "boom" in rows["upside"]["error"]
    text = CliRunner().invoke(main, ["actions", "--check"])  # the text ends with its verdict (issue 26)
    assert text.exit_code == 1 and text.stdout.strip().splitlines()[-1].endswith("plugins broken, 0 conflicts")


def test_actions_check_ends_with_all_ok():
    """With only the built-ins (the project's own environment), --check ends "all N action plugins OK" (N counts
    the actions, not the composites listed under them)."""
    from l2p_bullet.plugins import registry as reg

    r = CliRunner().invoke(main, ["actions", "--check"])
    n = len(reg.discover())
    assert r.exit_code == 0 and r.stdout.strip().splitlines()[-1].startswith(f"all {n} action plugins OK"), r.output


def test_new_action_scaffold_never_overwrites(tmp_path):
    out = tmp_path / "pkg"
    runner = CliRunner()
    r = runner.invoke(main, ["new-action", "left-of", "--phrase", "to the left of", "--out", str(out)])
    assert r.exit_code == 0, r.output
    assert (out / "pyproject.toml").read_text().count('left-of = "l2p_left_of"') == 1
    manifest = (out / "l2p_left_of" / "manifest.toml").read_text()
    assert 'phrases = ["to the left of"]' in manifest
    readme = (out / "README.md").read_text()
    assert "event_start_end" in readme and "l2p-bullet train left-of" in readme and "pip install" in readme
    again = runner.invoke(main, ["new-action", "left-of", "--phrase", "to the left of", "--out", str(out)])
    assert again.exit_code != 0 and "already exists" in again.output
    bad = runner.invoke(main, ["new-action", "Left Of", "--phrase", "x", "--out", str(tmp_path / "b")])
    assert bad.exit_code != 0 and "not a valid action name" in bad.output


def test_new_action_refuses_an_installed_phrase(plugins_dir, tmp_path):
    r = CliRunner().invoke(main, ["new-action", "lateral", "--phrase", "sideways", "--out", str(tmp_path / "p")])
    assert r.exit_code != 0 and 'already belongs to the installed action "sideways"' in r.output
    assert not (tmp_path / "p").exists()


def test_a_python_the_tests_start_sees_the_plugins_the_test_sees():
    """The CLI in a subprocess, the evaluate pool's spawned workers: they must list the same plugins as
    the test process (tests/conftest.py hides pre-installed plugins in both, or the rows disagree)."""
    code = "from l2p_bullet.plugins import registry; print(sorted(p.name for p in registry.discover()))"
    there = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert there.strip() == str(sorted(p.name for p in registry.discover()))


def test_a_manifest_is_parsed_once_until_its_bytes_change(tmp_path, monkeypatch):
    """Every sentence read asks discover() again (a composite's phrases, a broken one's), and parsing the installed
    manifests was half of reading one: an unchanged manifest is parsed once. Its bytes are read each time, so an
    edit shows at once (here one of the same length, in the same tick); a failure is never kept; and what one caller
    does to the manifest it got is not what the next one gets."""
    root = tmp_path / "site"  # module names of its own: other tests here import their fk_* modules
    make_bundle(root / "fk_once", "once", ["once", "off to the side of"])
    make_bundle(root / "fk_once_bad", "oncebad", [], manifest="phrases = [unterminated\n")
    make_dist(root, "fake-once", {"once": "fk_once", "oncebad": "fk_once_bad"})
    monkeypatch.syspath_prepend(str(root))
    parsed = []

    def counting(raw, error, label, **kw):
        parsed.append(label)
        return loads_toml(raw, error, label, **kw)

    loads_toml = registry.loads_toml
    monkeypatch.setattr(registry, "loads_toml", counting)
    registry._parsed.cache_clear()
    good, bad = str(root / "fk_once" / "manifest.toml"), str(root / "fk_once_bad" / "manifest.toml")
    first = by_name(registry.discover())
    assert parsed.count(good) == 1 and first["once"].phrases == ("once", "off to the side of")
    first["once"].manifest["phrases"].append("beside")  # a caller's own copy
    again = by_name(registry.discover())
    assert parsed.count(good) == 1 and again["once"].manifest["phrases"] == ["once", "off to the side of"]
    assert parsed.count(bad) == 2 and not again["oncebad"].ok  # an error is read again, as the file may be mended
    path = root / "fk_once" / "manifest.toml"
    path.write_text(path.read_text().replace('"once", "off to the side of"', '"once", "to the back of"'))
    edited = by_name(registry.discover())
    assert parsed.count(good) == 2 and edited["once"].phrases == ("once", "to the back of")
