"""What a newcomer met on a first afternoon: the verdict line that does not say a carry was a carry, an
installed plugin that silently changed what ``evaluate`` runs, and replayed demonstrations without a caption.
(The plugin tests in a user's environment: tests/test_isolation.py; a refused export that blocked its retry:
tests/test_hostile_inputs.py.)
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from types import SimpleNamespace

from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.scene import default_scene
from l2p_bullet.evaluate.runner import EvaluationConfig, _tasks
from l2p_bullet.plugins import registry


def _result(manner: str, why: str | None = None) -> SimpleNamespace:
    command = SimpleNamespace(mover="A", preposition="next to", anchors=("B",), action="next-to", manner=manner,
                              manner_why=why)
    from l2p_bullet.pipeline import PerformResult

    r = SimpleNamespace(command=command, verdict={"reason": "the rules hold"}, final_progress=0.97, success=True,
                        planned_progress=0.98, max_deviation_m=0.001, anchor_displacement_m=0.0,
                        timings={"total": 1.0}, files={}, out_dir=Path("runs/x"), displacements_m={"B": 0.0})
    r.text = lambda: PerformResult.text(r)  # perform prints what the result says of itself
    return r


def test_the_verdict_line_names_a_carry(monkeypatch):
    """"A next to B: action next-to" was all a carry said: the manner it was performed (and judged) in is named."""
    import l2p_bullet.chain as chain

    for manner, said, why in (("carry", 'A next to B: carry, action "next-to", success', None),
                              ("slide", 'A next to B: action "next-to", success', None),
                              ("carry", 'A next to B: carry over the other objects in the way, action "next-to"',
                               "carried over the other objects, which leave a slide no move at all (...)")):
        monkeypatch.setattr(chain, "perform_chain", lambda *a, _m=manner, _w=why, **k: _result(_m, _w))
        r = CliRunner().invoke(main, ["perform", f"{manner} A next to B", "--no-render", "-q"])
        assert r.exit_code == 0, r.output
        assert r.output.splitlines()[0].startswith(said), r.output


def _with_extra() -> list:
    """The installed actions and a user's "left-of" (a built-in's bundle under another package's name)."""
    plugins = registry.discover()
    next_to = registry.find("next-to", plugins)
    return plugins + [dataclasses.replace(next_to, name="left-of", package="l2p-left-of", package_version="0.3")]


def test_evaluate_runs_the_built_in_actions_and_names_an_installed_one(tmp_path):
    """Installing a plugin silently changed evaluate's default action set (and the chain benchmark's clauses):
    the published tables were no longer reproduced without --actions."""
    plugins = _with_extra()
    builtin = sorted(p.name for p in registry.discover() if p.ok)
    tasks, notes = _tasks(EvaluationConfig(scenes=2).check(), tmp_path, plugins)
    assert sorted({t.action for t in tasks}) == builtin
    assert "left-of" in notes and "--actions" in notes["left-of"] and "not in the default set" in notes["left-of"]
    chains, notes = _tasks(EvaluationConfig(scenes=2, chains=2).check(), tmp_path, plugins)
    assert "left-of" not in chains[0].chain_actions and "left-of" in notes
    named, notes = _tasks(EvaluationConfig(scenes=1, actions=["left-of", "closer"]).check(), tmp_path, plugins)
    assert sorted({t.action for t in named}) == ["closer", "left-of"] and not notes


def test_a_replayed_demonstration_is_captioned_with_its_sentence(tmp_path):
    """Replayed demonstrations showed only "progress n/a" under the video."""
    from l2p_bullet.embodiment import execute
    from l2p_bullet.embodiment.replay import motion_source

    source = motion_source(None, "around:0", default_scene(), "A", "B")
    assert source.caption == "move A around B" and source.sentence is None
    got = {}

    class Recorder:
        film = object()

        def write_trajectory(self, path, meta, sizes):
            got["trajectory_sentence"] = meta.get("sentence")

        def write_images(self, out, video, sentence):
            got["caption"] = sentence
            return {}

    execute._write_files(Recorder(), tmp_path, {"caption": source.caption}, {}, SimpleNamespace(video="mp4"))
    assert got == {"trajectory_sentence": None, "caption": "move A around B"}  # trajectory.json as before
    execute._write_files(Recorder(), tmp_path, {"sentence": "carry A past B", "manner": "carry"}, {},
                         SimpleNamespace(video="mp4"))
    assert got["caption"] == "carry: carry A past B"
