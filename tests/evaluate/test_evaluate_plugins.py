"""``evaluate`` with an installed two-anchor plugin (issue 26, item 2).

The plugin is made as docs/perform.md says (``new-action between --phrase between --anchors 2``,
generated demonstrations, ``train``) and put on ``sys.path`` as an installed distribution. Before the
fix, evaluate asked it "move A between B" on every scene: 100 % errors, the reason only in SQLite, and
an empty row drawn as 0 %.
"""

from __future__ import annotations

import pytest
from plugin_fixtures import trained_plugin

from l2p_bullet.evaluate import worker
from l2p_bullet.evaluate.report import report_text
from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows
from l2p_bullet.plugins import registry

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def between_site(tmp_path_factory):
    return trained_plugin(tmp_path_factory.mktemp("between"), "between", "between", ["--anchors", "2"])


@pytest.fixture
def with_between(between_site, monkeypatch):
    monkeypatch.syspath_prepend(str(between_site))
    monkeypatch.setattr(worker, "_WORKER", None)  # a worker made before the install would not see it
    registry._LOADED.clear()
    yield registry.discover()
    registry._LOADED.clear()


def test_two_anchor_action_is_skipped_with_a_reason_on_two_block_scenes(with_between, tmp_path, capsys):
    assert registry.find("between", with_between).ok
    s = evaluate(EvaluationConfig(actions=["between", "closer"], scenes=2), tmp_path / "e", workers=0,
                 plugins=with_between)
    rows = load_rows(tmp_path / "e")
    assert {r["action"] for r in rows} == {"closer"} and s.total == 2
    assert "between" in s.notes and "--bystanders 1" in s.notes["between"]
    assert 'note: "between" names 2 reference blocks: skipped on 2 of 2 scenes' in capsys.readouterr().err


def test_two_anchor_action_runs_on_scenes_with_a_third_block(with_between, tmp_path):
    evaluate(EvaluationConfig(actions=["between", "closer"], scenes=2, bystanders=1), tmp_path / "e", workers=0,
             plugins=with_between, progressbar=False)
    rows = load_rows(tmp_path / "e")
    btw = [r for r in rows if r["action"] == "between"]
    assert len(btw) == 2 and all(r["sentence"] == "move A between B and C" for r in btw)
    assert not any("reference" in (r["error"] or "") for r in btw), [r["error"] for r in btw]
    performed = [r for r in btw if r["error"] is None]
    for r in performed:  # the run is judged by its own (two-anchor) action and by the one-anchor ones
        assert "between" in r["judged"] and "closer" in r["judged"]
    closer = [r for r in rows if r["action"] == "closer" and r["error"] is None]
    assert closer and all("between" not in r["judged"] for r in closer)  # no second anchor in the sentence
    text = report_text(rows)
    matrix = text.split("judge-based confusion")[1].split("\n\n")[0].splitlines()
    end = matrix[1].index("between") + len("between")
    closer_line = next(line for line in matrix if line.startswith("closer"))
    assert closer_line[end - 4:end].strip() == "", matrix  # between's cell in closer's row: blank, not 0
    if len(performed) < len(btw):
        assert "errors (runs x reason" in text

