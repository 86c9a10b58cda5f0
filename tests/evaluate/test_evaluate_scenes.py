"""Scene sets for ``l2p-bullet evaluate``: random, JSON-lines files (errors name the line), the study, bystanders."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from l2p_bullet.core.scene import default_scene, random_scene
from l2p_bullet.data.demos import load_graded_demos
from l2p_bullet.errors import EvaluationError, SceneError
from l2p_bullet.evaluate.scenes import (
    BYSTANDER_CLEARANCE,
    STUDY_BLOCK,
    random_scenes,
    scene_file,
    study_scenes,
    with_bystanders,
)


def test_random_scenes_are_the_benchmarks_seeds():
    specs = random_scenes(3, seed=5)
    assert [s.id for s in specs] == ["random/5", "random/6", "random/7"]
    assert [s.seed for s in specs] == [5, 6, 7]
    assert specs[1].scene.to_dict() == random_scene(6).to_dict()


def _line(**kw) -> str:
    return json.dumps(default_scene().to_dict() | kw)


def test_scene_file_reads_ids_roles_and_seeds(tmp_path):
    f = tmp_path / "s.jsonl"
    f.write_text("# two scenes\n" + _line(id="first", seed=42) + "\n\n" + _line(mover="B", anchor="A") + "\n")
    a, b = scene_file(f, seed=7)
    assert (a.id, a.seed, a.mover, a.anchor) == ("first", 42, "A", "B")
    assert (b.id, b.seed, b.mover, b.anchor) == ("s.jsonl/1", 8, "B", "A")


@pytest.mark.parametrize(
    "bad, words",
    [
        ("{not json", ["line 2", "not valid JSON"]),
        (
            json.dumps(
                {
                    "objects": [
                        {"name": "A", "color": "red", "size": 0.05, "xy": [0.9, 0]},
                        {"name": "B", "color": "green", "size": 0.05, "xy": [0, 0]},
                    ]
                }
            ),
            ["line 2", "off the table"],
        ),
        (_line(mover="Z"), ["line 2", '"Z"']),
        (_line(id="x"), ["line 2", 'id "x"', "line 1"]),
        (_line(seed="3"), ["line 2", "seed"]),
    ],
)
def test_scene_file_errors_name_the_line(tmp_path, bad, words):
    f = tmp_path / "s.jsonl"
    f.write_text(_line(id="x") + "\n" + bad + "\n")
    with pytest.raises(SceneError) as e:
        scene_file(f)
    for w in words:
        assert w in str(e.value)


def test_empty_or_missing_scene_file_is_an_error(tmp_path):
    (tmp_path / "empty.jsonl").write_text("\n# nothing\n")
    with pytest.raises(SceneError, match=r"empty\.jsonl has no scenes$"):
        scene_file(tmp_path / "empty.jsonl")
    with pytest.raises(SceneError, match=r"cannot read scene file .*missing\.jsonl"):
        scene_file(tmp_path / "missing.jsonl")


def test_study_scenes_keep_the_studys_geometry_in_block_units():
    specs = study_scenes()
    starts = {json.dumps(d["start_config"], sort_keys=True): d for d in load_graded_demos()}
    assert len(specs) == len(starts) == 75
    for spec in specs:
        d = next(d for d in load_graded_demos() if f"study/{d['id']}" == spec.id)
        m, a = d["start_config"][:2]
        want = math.hypot(m["x"] - a["x"], m["y"] - a["y"]) / STUDY_BLOCK
        A, B = spec.scene.get("A"), spec.scene.get("B")
        got = math.hypot(A.xy[0] - B.xy[0], A.xy[1] - B.xy[1]) / A.size
        assert got == pytest.approx(want, abs=1e-6)
        assert (A.yaw, B.yaw) == (m["theta"], a["theta"])


def test_bystanders_are_deterministic_and_keep_their_distance():
    a = with_bystanders(random_scenes(5), 3)
    b = with_bystanders(random_scenes(5), 3)
    assert [s.scene.to_dict() for s in a] == [s.scene.to_dict() for s in b]
    for spec in a:
        assert spec.id.endswith("+3by") and len(spec.scene.objects) == 5
        objs = spec.scene.objects
        for i, o in enumerate(objs[2:], start=2):
            d = min(np.hypot(o.xy[0] - p.xy[0], o.xy[1] - p.xy[1]) for j, p in enumerate(objs) if j != i)
            assert d >= BYSTANDER_CLEARANCE * o.size - 1e-9
    with pytest.raises(EvaluationError, match=r"at most 10 bystanders \(got 99\)"):
        with_bystanders(random_scenes(1), 99)
