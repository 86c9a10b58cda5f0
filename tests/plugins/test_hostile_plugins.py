"""Hostile and broken action plugins, as a matrix (issue 15): each one is reported by ``actions --check``
(exit 1), makes ``perform`` of its own phrase a one-line error naming it (exit 2, no run folder left
behind), and leaves every other action working.

Each plugin is a copy of a real built-in bundle (real weights) installed as a distribution on a
temporary sys.path entry (tests/plugin_fixtures.py), then damaged the way the issue describes. Digests
are recomputed after damaging a weights file, so the damage itself is what load must catch.
"""

from __future__ import annotations

import hashlib
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w
from click.testing import CliRunner
from plugin_fixtures import copy_builtin_as_plugin, make_bundle, make_dist
from safetensors.numpy import load as st_load
from safetensors.numpy import save as st_save

from l2p_bullet.cli import main
from l2p_bullet.core.scene import default_scene
from l2p_bullet.errors import FailedToLoadPlugin, PluginConflict
from l2p_bullet.pipeline import resolve
from l2p_bullet.plugins import registry
from l2p_bullet.plugins.bundle import MANIFEST


def _no_constant(name: str) -> None:
    raise AssertionError(f"{name} in JSON output")


def _manifest(folder: Path) -> dict:
    return tomllib.loads((folder / MANIFEST).read_text())


def _write_manifest(folder: Path, man: dict) -> None:
    (folder / MANIFEST).write_text(tomli_w.dumps(man))


def _rewrite_weights(folder: Path, filename: str, data: bytes) -> None:
    """Replace a weights file and record its real digest: only the content is wrong."""
    (folder / filename).write_bytes(data)
    man = _manifest(folder)
    man["weights"][filename] = {"sha256": hashlib.sha256(data).hexdigest(), "bytes": len(data)}
    _write_manifest(folder, man)


def _edit(folder: Path, fn) -> None:
    man = _manifest(folder)
    fn(man)
    _write_manifest(folder, man)


def _append(folder: Path, text: str) -> None:
    with (folder / MANIFEST).open("a") as f:
        f.write(text)


def _tensors(folder: Path, filename: str) -> dict[str, np.ndarray]:
    return dict(st_load((folder / filename).read_bytes()))


def truncated_policy(f: Path) -> None:
    _rewrite_weights(f, "policy.safetensors", (f / "policy.safetensors").read_bytes()[:500])


def wrong_shaped_policy(f: Path) -> None:
    t = _tensors(f, "policy.safetensors")
    t["body.2.weight"] = np.ascontiguousarray(t["body.2.weight"][:, :10])
    _rewrite_weights(f, "policy.safetensors", st_save(t))


def nan_progress_weights(f: Path) -> None:
    t = _tensors(f, "progress.safetensors")
    t["m0.head.bias"] = np.array([np.nan], np.float32)
    _rewrite_weights(f, "progress.safetensors", st_save(t))


def inf_policy_weights(f: Path) -> None:
    t = _tensors(f, "policy.safetensors")
    t["mean.bias"] = np.array([np.inf, 0, 0], np.float32)
    _rewrite_weights(f, "policy.safetensors", st_save(t))


def weights_outside_the_bundle(f: Path) -> None:
    outside = f.parent / "outside.safetensors"
    outside.write_bytes((f / "policy.safetensors").read_bytes())
    digest = hashlib.sha256(outside.read_bytes()).hexdigest()
    _edit(f, lambda m: m["weights"].update({str(outside): {"sha256": digest}}))


def weights_with_dotdot(f: Path) -> None:
    (f.parent / "up.safetensors").write_bytes((f / "policy.safetensors").read_bytes())
    digest = hashlib.sha256((f.parent / "up.safetensors").read_bytes()).hexdigest()
    _edit(f, lambda m: m["weights"].update({"../up.safetensors": {"sha256": digest}}))


CASES = {
    "truncated policy": (truncated_policy, "policy.safetensors"),
    "wrong-shaped policy": (wrong_shaped_policy, "body.2.weight"),
    "NaN progress weights": (nan_progress_weights, "NaN"),
    "infinite policy weights": (inf_policy_weights, "NaN or infinite"),
    "features no longer match the model": (lambda f: _edit(f, lambda m: m["features"].update(cd_sectors=4)),
                                           "[features] names"),
    "spacing = wide": (lambda f: _edit(f, lambda m: m["features"].update(spacing="wide")), "spacing"),
    "policy threshold = high": (lambda f: _edit(f, lambda m: m["policy"].update(threshold="high")), "threshold"),
    "policy planner unknown": (lambda f: _edit(f, lambda m: m["policy"].update(planner="astar")), "planner"),
    "weights as a string": (lambda f: _edit(f, lambda m: m.update(weights="progress.safetensors")), "[weights]"),
    "ensemble = 0": (lambda f: _edit(f, lambda m: m["model"].update(ensemble=0)), "ensemble"),
    "hidden = -3": (lambda f: _edit(f, lambda m: m["model"].update(hidden=-3)), "hidden"),
    "schema = true": (lambda f: _edit(f, lambda m: m.update(schema=True)), "schema"),
    "absolute weight path": (weights_outside_the_bundle, "plain file name"),
    "weight path with ..": (weights_with_dotdot, "plain file name"),
    "judge threshold = high": (lambda f: _edit(f, lambda m: m.update(judge={"threshold": "high"})), "judge"),
    "import calls sys.exit(7)": (lambda f: (f / "__init__.py").write_text("import sys\nsys.exit(7)\n"),
                                 "sys.exit(7)"),
    "import raises a BaseException": (
        lambda f: (f / "__init__.py").write_text("class Boom(BaseException):\n    pass\nraise Boom('bang')\n"),
        "Boom: bang"),
    "untrained (no weights)": (lambda f: (f / "progress.safetensors").unlink(), "no trained weights"),
    "manifest is not TOML": (lambda f: (f / MANIFEST).write_text('phrases = ["athwart"\n'), None),
    # by structure, not by field (issue 27.2): each one used to be a RecursionError in every command
    "500 nested arrays": (lambda f: _append(f, "deep = " + "[" * 500 + "]" * 500 + "\n"), "nests"),
    "500 nested inline tables": (lambda f: _append(f, "deep = " + "{a = " * 500 + "1" + "}" * 500 + "\n"), "nests"),
    "a table 300 dotted keys deep": (lambda f: _append(f, "[" + ".".join(["t"] * 300) + "]\nk = 1\n"), "nests"),
    "a 1 MiB manifest": (lambda f: _append(f, "# " + "x" * (1 << 20) + "\n"), "larger than"),
}

UNREADABLE = {"manifest is not TOML", "500 nested arrays", "500 nested inline tables", "a table 300 dotted keys deep",
              "a 1 MiB manifest"}
"""Cases whose manifest cannot be read at all (so the plugin's phrase is not known either)."""


@pytest.fixture
def site(tmp_path, monkeypatch) -> Path:
    root = tmp_path / "site"
    root.mkdir()
    monkeypatch.syspath_prepend(str(root))
    return root


def one_line_error(result) -> str:
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), result.output
    return lines[0]


@pytest.mark.parametrize("case", list(CASES))
def test_a_broken_plugin_is_reported_named_and_harmless(site, tmp_path, case):
    damage, reason = CASES[case]
    name = "hostile-" + hashlib.sha1(case.encode()).hexdigest()[:6].translate(str.maketrans("0123456789", "ghijklmnop"))
    phrase = "athwart"
    folder = copy_builtin_as_plugin(site, "past", name, [phrase], dist="l2p-hostile")
    damage(folder)

    checked = CliRunner().invoke(main, ["actions", "--check", "--json"])
    assert checked.exit_code == 1, checked.output
    rows = {r["name"]: r for r in json.loads(checked.output)["actions"]}
    assert not rows[name]["ok"] and (reason is None or reason in rows[name]["error"]), rows[name]
    assert all(rows[a]["ok"] for a in ("closer", "away", "next-to", "past", "around"))
    json.loads(checked.output, parse_constant=_no_constant)  # strict JSON: no NaN/Infinity literals

    out = tmp_path / "run"
    line = one_line_error(CliRunner().invoke(main, ["perform", f"move A {phrase} B", "--no-render", "-q",
                                                    "--out", str(out)]))
    assert name in line, line
    if case not in UNREADABLE:  # a manifest that cannot be read declares no phrase: only then is it "unknown"
        assert "not a preposition" not in line, line
    assert not out.exists(), "a broken plugin left a run folder behind"

    # every other action still parses, loads and plans
    ok = CliRunner().invoke(main, ["plan", "move A around B", "--out", str(tmp_path / "plan")])
    assert ok.exit_code == 0, ok.output


def test_a_plugin_claiming_a_builtin_phrase_blocks_only_that_phrase(site, tmp_path):
    copy_builtin_as_plugin(site, "around", "athwart", ["athwart", "past"], dist="l2p-squatter")
    with pytest.raises(PluginConflict) as e:
        resolve("move A past B", default_scene())
    assert e.value.claim == "past" and set(e.value.plugins) == {"past", "athwart"}
    assert resolve("move A athwart B", default_scene()).action == "athwart"  # its other phrase is its own
    r = CliRunner().invoke(main, ["actions", "--check"])
    assert r.exit_code == 1 and 'the phrase "past" is claimed by several' in r.output
    line = one_line_error(CliRunner().invoke(main, ["perform", "move A past B", "--no-render", "-q",
                                                    "--out", str(tmp_path / "x")]))
    assert "l2p-squatter" in line and "l2p-bullet" in line
    r = CliRunner().invoke(main, ["perform", "move A next to B", "--no-render", "-q", "--out", str(tmp_path / "y")])
    assert r.exit_code == 0, r.output


def test_a_plugin_named_like_a_builtin_is_broken_and_the_builtin_kept(site, tmp_path):
    """The one rule for names of every plugin kind: a plugin cannot take a built-in's name. It is listed as
    broken naming its package, its own phrases are refused with that reason, and the built-in keeps working
    (an action plugin named "around" used to make "move A around B" ambiguous)."""
    copy_builtin_as_plugin(site, "past", "around", ["circling"], dist="l2p-twin")
    assert resolve("move A around B", default_scene()).action == "around"
    with pytest.raises(FailedToLoadPlugin) as e:
        resolve("move A circling B", default_scene())
    assert e.value.name == "around" and e.value.package == "l2p-twin" and "built-in" in e.value.reason
    rows = [
        r
        for r in json.loads(CliRunner().invoke(main, ["actions", "--json"]).output)["actions"]
        if r["name"] == "around"
    ]
    assert [(r["package"], r["ok"]) for r in rows] == [("l2p-bullet", True), ("l2p-twin", False)], rows
    assert (
        'the name "around" is the built-in action\'s' in rows[1]["error"] and "uninstall l2p-twin" in rows[1]["error"]
    )
    assert resolve("move A past B", default_scene()).action == "past"
    assert CliRunner().invoke(main, ["plan", "move A around B", "--out", str(tmp_path / "p")]).exit_code == 0


def test_an_untrained_plugin_owning_the_phrase_is_named(site):
    make_bundle(site / "l2p_left_of", "left-of", ["to the left of"], weights=False)
    make_dist(site, "l2p-left-of", {"left-of": "l2p_left_of"})
    with pytest.raises(FailedToLoadPlugin) as e:
        resolve("move A to the left of B", default_scene())
    assert e.value.name == "left-of" and e.value.package == "l2p-left-of" and "no trained weights" in e.value.reason


def test_an_untaught_composite_owning_the_phrase_is_named(site, tmp_path):
    """A composite installed before it was taught: its phrase was "cannot find a preposition in ..."."""
    import shutil

    from l2p_bullet.chain.clauses import resolve_clauses
    from l2p_bullet.core.scene import load_scene
    from l2p_bullet.plugins.scaffold import scaffold

    made = scaffold("row2", ["queue up"], tmp_path / "l2p-row2", kind="composite")
    shutil.copytree(made.package_dir, site / made.package_dir.name)
    make_dist(site, "l2p-row2", {"row2": made.package_dir.name})
    scene = load_scene(Path(__file__).resolve().parents[2] / "examples" / "four_blocks.json")
    with pytest.raises(FailedToLoadPlugin) as e:
        resolve_clauses("Please queue up A, B and C", scene, registry.discover())
    assert e.value.name == "row2" and e.value.package == "l2p-row2" and "recipe.json missing" in e.value.reason
    assert [c.command.action for c in resolve_clauses("make a row of A, B and C", scene, registry.discover())] == [
        "next-to", "next-to"]  # the built-in composite is untouched
    r = CliRunner().invoke(main, ["plan", "queue up A, B and C", "--scene",
                                  str(Path(__file__).resolve().parents[2] / "examples" / "four_blocks.json"),
                                  "--no-plot", "--out", str(tmp_path / "p")])
    assert 'action plugin "row2" (package l2p-row2) cannot be used' in one_line_error(r)


def test_ctrl_c_during_a_plugin_import_still_stops_the_program(site):
    folder = copy_builtin_as_plugin(site, "past", "stopper", ["stopping at"], dist="l2p-stopper")
    (folder / "__init__.py").write_text("raise KeyboardInterrupt\n")
    with pytest.raises(KeyboardInterrupt):
        registry.load("stopper")


def test_nan_metrics_never_reach_json(site):
    copy_builtin_as_plugin(site, "past", "nanny", ["nanning"], dist="l2p-nan",
                           metrics={"final_progress": math.nan, "loss": math.inf})
    r = CliRunner().invoke(main, ["actions", "--json"])
    assert r.exit_code == 0
    rows = {x["name"]: x for x in json.loads(r.output, parse_constant=_no_constant)["actions"]}
    assert rows["nanny"]["metrics"]["final_progress"] is None
