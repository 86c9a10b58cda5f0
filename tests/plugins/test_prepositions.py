"""Viewer-frame and two-anchor prepositions, piece by piece (the installed-plugin test runs them whole):
declarations, sentences with two anchors, features, judges, run-folder fields, the demos format, the
training set's mirror images, and that relative one-anchor actions are untouched."""

from __future__ import annotations

import json

import numpy as np
import pytest

from l2p_bullet.core.contracts import Plan, load_motion
from l2p_bullet.core.frames import VIEWPOINTS, declaration, parse_anchors, parse_frame, viewer_offset
from l2p_bullet.core.scene import Scene, default_scene, random_between_scene
from l2p_bullet.data.demos import load_demos, load_session, save_session
from l2p_bullet.errors import (
    BundleError,
    DataError,
    LanguageError,
    PlanError,
    PluginError,
    UnknownObjectError,
)
from l2p_bullet.judge.rules import rule_verdict
from l2p_bullet.language import Command, parse
from l2p_bullet.learning.augment import reflect, viewer_sides
from l2p_bullet.learning.synthetic import write_sessions
from l2p_bullet.progress.features import QSRConfig, feature_names, motion_features

ROBOT = np.array(VIEWPOINTS["robot"])


# --- declarations ---------------------------------------------------------------------------------
def test_frame_and_anchor_declarations():
    assert parse_frame(None).relative and parse_frame("relative").name == "relative"
    assert parse_frame("viewer").name == "viewer" and np.allclose(parse_frame("viewer").viewpoint_xy(), ROBOT)
    assert parse_frame("viewer:robot").name == "viewer" and parse_frame("Viewer:Camera").name == "viewer:camera"
    assert declaration({}) == (parse_frame("relative"), 1)
    assert parse_anchors(2) == 2
    for bad in ("viewr", "viewer:moon", 3):
        with pytest.raises(BundleError):
            parse_frame(bad)
    for bad in (0, 3, "2", True):
        with pytest.raises(BundleError):
            parse_anchors(bad)


def test_the_camera_viewpoint_is_where_the_video_camera_stands():
    from l2p_bullet.embodiment.sim.camera import CAMERAS

    assert VIEWPOINTS["camera"] == CAMERAS["robot"].eye[:2]


def test_viewer_offset_left_is_the_robots_left():
    b = np.zeros(2)
    assert viewer_offset(np.array([0.0, 0.1]), b, ROBOT)[0] > 0  # +y: the robot's left
    lat, dep = viewer_offset(np.array([0.1, 0.0]), b, ROBOT)
    assert abs(lat) < 1e-12 and dep > 0  # +x: behind B, seen from the robot


# --- sentences ------------------------------------------------------------------------------------
PHRASES = {"between": "between", "next to": "next-to", "to the left of": "left-of"}
ANCHORS = {"between": 2}


@pytest.fixture
def three() -> Scene:
    return random_between_scene(0)


def test_two_anchor_sentences(three):
    cmd = parse("Please put the red block between B and the blue one.", three, PHRASES, ANCHORS)
    assert (cmd.mover, cmd.action, cmd.anchor, cmd.anchors, cmd.more_anchors) == ("A", "between", "B", ("B", "C"),
                                                                                ("C",))
    assert parse("move A next to C", three, PHRASES, ANCHORS).anchors == ("C",)  # one-anchor actions as ever
    assert Command("move", "A", "around", "around", "B").anchors == ("B",)


@pytest.mark.parametrize("sentence, error", [
    ("move A between B", LanguageError),  # one reference block
    ("move A between B and B", LanguageError),  # the same block twice
    ("move A between A and C", LanguageError),  # the mover as an anchor
    ("move A between B and the purple block", UnknownObjectError),
    ("move A between B and Cc", UnknownObjectError),
    ("move A betwen B and C", LanguageError),
])
def test_two_anchor_errors(three, sentence, error):
    with pytest.raises(error) as e:
        parse(sentence, three, PHRASES, ANCHORS)
    assert type(e.value) is error


def test_two_anchor_typos_get_a_suggestion(three):
    with pytest.raises(LanguageError) as e:
        parse("move A betwen B and C", three, PHRASES, ANCHORS)
    assert '"betwen"' in str(e.value) and 'Did you mean "between"' in str(e.value)
    with pytest.raises(UnknownObjectError) as e:
        parse("move A between B and Cc", three, PHRASES, ANCHORS)
    assert 'Did you mean "C"' in str(e.value)


# --- features -------------------------------------------------------------------------------------
def _turn(poses: np.ndarray, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    xy = poses[..., :2] @ np.array([[c, s], [-s, c]])
    return np.concatenate([xy, poses[..., 2:] + angle], axis=-1)


def test_feature_columns_follow_the_declaration():
    base = feature_names(QSRConfig())
    assert feature_names(QSRConfig(frame="viewer"))[: len(base)] == base
    assert len(feature_names(QSRConfig(frame="viewer", anchors=2))) == len(base) + 6 + 8
    assert QSRConfig().to_dict().keys() == QSRConfig(frame="relative", anchors=1).to_dict().keys()
    assert "frame" not in QSRConfig().to_dict() and "anchors" not in QSRConfig().to_dict()
    cfg = QSRConfig(frame="viewer:camera", anchors=2)
    assert QSRConfig.from_dict(cfg.to_dict()) == cfg


def test_viewer_columns_know_left_from_right_and_relative_columns_do_not():
    size = 0.05
    anchor = np.array([0.0, 0.0, 0.0])
    left = np.column_stack([np.linspace(0.1, 0.0, 20), np.linspace(-0.1, 0.08, 20), np.zeros(20)])
    right = left * [1, -1, 1]  # its mirror image: ends on the robot's right
    cfg = QSRConfig(frame="viewer")
    n = len(feature_names())
    fl, _ = motion_features(left, anchor, size, cfg, viewer=ROBOT)
    fr, _ = motion_features(right, anchor, size, cfg, viewer=ROBOT)
    col = feature_names(cfg).index("view_lateral")
    assert fl[-1, col] > 0 > fr[-1, col]
    assert np.allclose(fl[:, :n], motion_features(left, anchor, size)[0])  # the relative columns as before
    # Turning the scene with the viewer changes nothing; turning it under a fixed viewer does.
    turned, anchor_t = _turn(left, 0.7), _turn(anchor[None], 0.7)[0]
    ft, _ = motion_features(turned, anchor_t, size, cfg, viewer=_turn(np.r_[ROBOT, 0.0][None], 0.7)[0, :2])
    assert np.allclose(ft, fl, atol=1e-5)
    fixed, _ = motion_features(turned, anchor_t, size, cfg, viewer=ROBOT)
    assert not np.allclose(fixed[:, n:], fl[:, n:], atol=1e-3)


def test_two_anchor_columns_see_the_segment():
    size = 0.05
    scene = random_between_scene(1)
    b, c = scene.get("B").pose, scene.get("C").pose
    a = scene.get("A").pose
    mid = np.r_[(b[:2] + c[:2]) / 2, a[2]]
    path = np.linspace(a, mid, 30)
    cfg = QSRConfig(anchors=2)
    f, _ = motion_features(path, b, size, cfg, more_anchors=[c])
    names = feature_names(cfg)
    assert f[-1, names.index("seg_t")] == pytest.approx(0.5, abs=1e-6)
    assert f[-1, names.index("seg_dist")] == pytest.approx(0.0, abs=1e-6)
    assert f[0, names.index("seg_dist")] > 0.2
    with pytest.raises(ValueError, match="two-anchor features need the second anchor's poses"):
        motion_features(path, b, size, cfg)  # the second anchor is required (not numpy's broadcasting error)


# --- judges ---------------------------------------------------------------------------------------
def test_between_rule():
    b, c = np.array([0.0, 0.0, 0.0]), np.array([0.2, 0.0, 0.0])
    go = lambda end: np.linspace([0.1, 0.15, 0.0], end, 20)  # noqa: E731
    assert rule_verdict("between", go([0.1, 0.0, 0.0]), b, 0.05, anchors=[b, c]).success
    assert not rule_verdict("between", go([0.1, 0.04, 0.0]), b, 0.05, anchors=[b, c]).success  # off the line
    assert not rule_verdict("between", go([0.26, 0.0, 0.0]), b, 0.05, anchors=[b, c]).success  # beyond C
    near_b = rule_verdict("between", go([0.05, 0.0, 0.0]), b, 0.05, anchors=[b, c])
    assert not near_b.success and "touching" in near_b.reason
    with pytest.raises(ValueError, match=r'the rule "between" needs the two reference objects \(anchors=\[B, C\]\)'):
        rule_verdict("between", go([0.1, 0.0, 0.0]), b, 0.05)


def test_viewer_rules_as_the_robot_sees_it():
    b = np.zeros(3)
    to = lambda end: np.linspace([0.15, 0.15, 0.0], end, 20)  # noqa: E731
    assert rule_verdict("left-of", to([0.0, 0.08, 0.0]), b, 0.05).success  # +y is the robot's left
    assert not rule_verdict("left-of", to([0.0, -0.08, 0.0]), b, 0.05).success
    assert rule_verdict("right-of", to([0.0, -0.08, 0.0]), b, 0.05).success
    assert rule_verdict("in-front-of", to([-0.08, 0.0, 0.0]), b, 0.05).success  # towards the robot
    assert rule_verdict("behind", to([0.08, 0.0, 0.0]), b, 0.05).success
    assert not rule_verdict("left-of", to([0.0, 0.3, 0.0]), b, 0.05).success  # 6 blocks: not near it
    # seen from the camera (front right of the table, looking back), left is elsewhere
    cam = np.array(VIEWPOINTS["camera"])
    assert rule_verdict("left-of", to([0.0, 0.08, 0.0]), b, 0.05).success != rule_verdict(
        "left-of", to([0.0, 0.08, 0.0]), b, 0.05, viewer=cam).success


# --- run-folder fields ----------------------------------------------------------------------------
def test_plan_json_has_anchors_only_for_two_anchor_actions(tmp_path):
    common = dict(action="x", mover="A", anchor="B", size=0.05, anchor_pose=np.zeros(3), start=np.zeros(3),
                  path=np.zeros((2, 3)), progress=np.zeros(2), planner="mixed", stopped="budget")
    one = Plan(**common).to_dict()
    assert "anchors" not in one and "anchor_poses" not in one and "viewer" not in one
    two = Plan(**common, more_anchors=["C"], more_anchor_poses=np.ones((1, 3)), viewer=ROBOT)
    d = two.to_dict()
    assert d["anchors"] == ["B", "C"] and d["anchor_poses"] == [[0.0] * 3, [1.0] * 3] and d["viewer"] == [-0.53, 0]
    back = Plan.from_dict(json.loads(json.dumps(d)))
    assert back.anchors == ["B", "C"] and np.allclose(back.more_anchor_poses, 1) and np.allclose(back.viewer, ROBOT)
    (tmp_path / "plan.json").write_text(json.dumps(d))
    m = load_motion(tmp_path / "plan.json")
    assert len(m.more_anchors) == 1 and m.more_anchors[0].shape == (2, 3) and np.allclose(m.viewer, ROBOT)


def test_scoring_input_with_a_second_anchor(tmp_path):
    p = tmp_path / "m.json"
    p.write_text(json.dumps({"size": 0.05, "mover": [[0, 0, 0], [0.1, 0, 0]], "anchor": [[0.2, 0, 0]],
                             "more_anchors": [[[0.3, 0.1, 0]]], "viewer": [-0.5, 0]}))
    m = load_motion(p)
    assert m.more_anchors[0].shape == (2, 3) and np.allclose(m.viewer, [-0.5, 0])


# --- the demos format -----------------------------------------------------------------------------
def test_synthetic_sessions_load_with_their_viewer_and_anchors(tmp_path):
    (left,) = write_sessions(tmp_path / "l", "left-of", sessions=1, events=4)
    ds = load_demos("left-of", [left])
    assert len(ds) == 4 and all(d.viewer is not None and not d.more_anchors for d in ds)
    assert viewer_sides(ds) == (1, 0)  # they end on the viewer's left, in front and behind
    (btw,) = write_sessions(tmp_path / "b", "between", sessions=1, events=3)
    ds = load_demos("between", [btw])
    assert all(len(d.more_anchors) == 1 and d.viewer is None for d in ds)


def test_bad_optional_arrays_are_refused(tmp_path):
    tracks = [np.zeros((10, 3)), np.ones((10, 3)), np.full((10, 3), 2.0)]
    with pytest.raises(DataError, match=r'a\.npz: with "more_poses", each event\'s reference blocks must be given in '
                                        '"event_anchors"'):  # three blocks need event_anchors
        save_session(tmp_path / "a.npz", tracks, [[1, 5]], [0])
    with pytest.raises(DataError, match=r"b\.npz: event 0 names block 0 as mover and anchors \[0, 2\]"):  # the mover
        save_session(tmp_path / "b.npz", tracks, [[1, 5]], [0], anchors=[[0, 2]])  # as its own anchor
    with pytest.raises(DataError, match=r'c\.npz: "event_anchors" names a block beyond the two tracks'):
        save_session(tmp_path / "c.npz", tracks[:2], [[1, 5]], [0], anchors=[[2]])  # a block that does not exist
    assert not list(tmp_path.iterdir())  # nothing invalid is left on disk
    ok = save_session(tmp_path / "d.npz", tracks, [[1, 5]], [2], anchors=[[0, 1]], viewer=[1.0, 2.0])
    arrays = load_session(ok)
    assert arrays["more_poses"].shape == (1, 10, 3) and arrays["viewer_xy"].tolist() == [1.0, 2.0]


# --- the training set -----------------------------------------------------------------------------
def test_reflections_in_the_viewer_frame():
    poses = np.array([[1.0, 2.0, 0.3]])
    back = reflect(reflect(poses, np.zeros(2), 0.4), np.zeros(2), 0.4)
    assert np.allclose(back, poses)
    assert np.allclose(reflect(poses, np.zeros(2), 0.0)[0, :2], [1.0, -2.0])


def test_viewer_training_set_has_no_positive_right_of_motions(tmp_path):
    from l2p_bullet.learning.augment import Context, mirrored_copies
    from l2p_bullet.learning.trainset import DataConfig, build

    files = write_sessions(tmp_path, "left-of", sessions=1, events=6)
    own = load_demos("left-of", files)
    seqs = build("left-of", {"left-of": own}, QSRConfig(frame="viewer"), DataConfig(random_negatives=0,
                                                                                     static_negatives=4))
    col = feature_names(QSRConfig(frame="viewer")).index("view_lateral")
    pos_ends = [s.x[s.end, col] for s in seqs if s.positive]
    assert min(pos_ends) > 0  # every positive ends on the viewer's left: nothing was mirrored into a positive
    d = own[0]
    kinds = [
        p for *_, p in mirrored_copies(d, d.mover, d.anchor, Context((), d.viewer), QSRConfig(frame="viewer"), (1, 0))
    ]
    assert kinds == [True, False, True, False]  # itself; left<->right: no; front<->behind: yes; both: no


def test_relative_actions_still_mirror(tmp_path):
    from l2p_bullet.learning.augment import mirrored_copies

    d = load_demos("around")[0]
    kinds = [p for *_, p in mirrored_copies(d, d.mover, d.anchor, None, QSRConfig(), None)]
    assert kinds == [True, True]


def test_scaffold_declares_the_frame_anchors_and_judge(tmp_path):
    import tomllib

    from l2p_bullet.plugins.scaffold import scaffold

    s = scaffold("between", ["between"], tmp_path / "b", anchors=2, judge="between")
    man = tomllib.loads((s.package_dir / "manifest.toml").read_text())
    assert (man["frame"], man["anchors"], man["judge"]["rules"]) == ("relative", 2, "between")
    assert "move A between B and C" in (s.root / "README.md").read_text()
    with pytest.raises(PluginError, match=r'the rules "next-to" read 1 reference object\(s\); this action takes 2'):
        scaffold("beside2", ["aside"], tmp_path / "c", anchors=2, judge="next-to")  # a one-anchor rule, two anchors
    with pytest.raises(PluginError, match=r'unknown frame "sideways" \(known: relative, viewer'):
        scaffold("left2", ["leftish"], tmp_path / "d", frame="sideways")
    assert not (tmp_path / "c").exists() and not (tmp_path / "d").exists()  # refused before anything is written


def test_a_description_with_quotes_backslashes_and_lines_is_kept_in_a_valid_manifest(tmp_path):
    """new-action --description wrote the text between quotes as it was: a backslash or a newline broke the
    manifest (and a double quote became a single one)."""
    import tomllib

    from l2p_bullet.plugins.scaffold import scaffold

    text = 'Put it "under" C:\\tables\nsecond line, café'
    s = scaffold("under", ["under"], tmp_path / "u", description=text)
    assert tomllib.loads((s.package_dir / "manifest.toml").read_text())["description"] == text
    plain = scaffold("over", ["over"], tmp_path / "o")  # the default reads as before
    assert 'description = "Slide a block over another block."' in (plain.package_dir / "manifest.toml").read_text()


@pytest.mark.parametrize("frame", ["viewer", "viewer:camera", "relative"])
def test_the_scaffolds_example_script_writes_what_its_frame_needs(tmp_path, monkeypatch, frame):
    """Issue 26: for a viewer-frame plugin the README's example script wrote no viewer_xy, and training
    refused its files. The script is run as the README gives it."""
    import re
    import runpy

    from l2p_bullet.data.demos import DEMO_BLOCK_SIZE
    from l2p_bullet.plugins.scaffold import scaffold

    s = scaffold("leftish", ["leftwards of"], tmp_path / "p", frame=frame)
    script = re.search(r"```python\n(.*?)```", (s.root / "README.md").read_text(), re.S).group(1)
    (s.root / "write_demos.py").write_text(script)
    monkeypatch.chdir(s.root)
    runpy.run_path("write_demos.py")
    arrays = load_session(s.root / "demos" / "leftish_Session1.npz")
    want = parse_frame(frame).viewpoint_xy()
    if want is None:
        assert "viewer_xy" not in arrays
    else:
        assert np.allclose(arrays["viewer_xy"], want / 0.05 * DEMO_BLOCK_SIZE, atol=0.01)
    demos = load_demos("leftish", sorted((s.root / "demos").glob("*.npz")))
    assert demos and all((d.viewer is None) == (want is None) for d in demos)


def test_a_changed_declaration_needs_retraining(tmp_path):
    import shutil

    from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle

    folder = tmp_path / "b"
    shutil.copytree(builtin_bundle_dir("closer"), folder)
    (folder / "manifest.toml").write_text((folder / "manifest.toml").read_text().replace(
        'description = "', 'frame = "viewer"\ndescription = "'))
    with pytest.raises(BundleError) as e:
        load_bundle(folder)
    assert "re-train" in str(e.value)


def test_default_scene_actions_have_no_anchors_field(tmp_path):
    from l2p_bullet.pipeline import perform

    r = perform("move A next to B", default_scene(), out_dir=tmp_path / "r", render=False)
    traj = json.loads((tmp_path / "r" / "trajectory.json").read_text())
    assert "anchors" not in traj and "viewer" not in traj and r.to_dict()["anchors"] == ["B"]
    assert "anchors" not in json.loads((tmp_path / "r" / "plan.json").read_text())


def test_two_anchor_planning_leaves_both_anchors_untouched():
    from l2p_bullet.planning import plan
    from l2p_bullet.planning.world2d import World2D

    class Between:
        """A stand-in two-anchor model: progress is the between rule's score."""

        anchors, viewpoint = 2, None

        def final_batch(self, movers, anchors, size, *, more_anchors=None, viewer=None):
            return np.array([rule_verdict("between", m, anchors, size, anchors=[anchors, more_anchors[0]]).score
                             for m in movers])

        def curve(self, mover, anchor, size, *, more_anchors=None, viewer=None):
            return self.final_batch([mover[: i + 1] for i in range(len(mover))], anchor, size,
                                    more_anchors=more_anchors)

    class FakeBundle:
        name, manifest = "between", {"policy": {"planner": "discrete"}}

        def progress_model(self):
            return Between()

    scene = random_between_scene(2)
    p = plan(scene, "A", ["B", "C"], FakeBundle(), budget=10)
    assert p.anchors == ["B", "C"] and np.allclose(p.more_anchor_poses[0], scene.get("C").pose)
    assert World2D(scene, "A").path_free(np.array(p.extra["waypoints"]))
    assert rule_verdict(
        "between", p.path, p.anchor_pose, p.size, anchors=[p.anchor_pose, p.more_anchor_poses[0]]
    ).success
    with pytest.raises(PlanError, match=r'the action "between" takes 2 reference object\(s\), not 1 \(B\)'):
        plan(scene, "A", "B", FakeBundle())  # the model reads two anchors



def test_train_takes_a_folder_of_demonstrations(tmp_path):
    from l2p_bullet.data.demos import expand_files

    files = write_sessions(tmp_path / "d", "left-of", sessions=2, events=2)
    assert expand_files([tmp_path / "d"]) == sorted(files)
    assert expand_files([files[0]]) == [files[0]]
    (tmp_path / "empty").mkdir()
    with pytest.raises(DataError, match=r"no demonstration files \(\.npz\) in the folder .*empty"):
        expand_files([tmp_path / "empty"])


def test_new_action_and_teach_on_the_command_line(tmp_path, monkeypatch):
    from click.testing import CliRunner

    from l2p_bullet.cli import main

    monkeypatch.chdir(tmp_path)
    r = CliRunner().invoke(main, ["new-action", "between", "--phrase", "between", "--anchors", "2",
                                  "--judge", "between"])
    assert r.exit_code == 0, r.output
    assert "pip install ./l2p-between" in r.output and 'perform "move A between B and C"' in r.output
    r = CliRunner().invoke(main, ["new-action", "left2", "--phrase", "leftish", "--judge", "nowhere"])
    assert r.exit_code == 2 and r.output.startswith("error:")
    r = CliRunner().invoke(main, ["teach", "left-of"])  # not scaffolded here
    assert r.exit_code == 2 and r.output.startswith("error:") and "new-action left-of" in r.output


def _random_bundle(folder, name: str, phrases: list[str], qsr: QSRConfig) -> None:
    """A loadable bundle with random weights of the right shapes (for plumbing tests; nothing learned)."""
    from l2p_bullet.plugins.bundle import write_progress_bundle
    from l2p_bullet.progress.config import ModelConfig, expected_shapes

    mcfg = ModelConfig(n_features=len(feature_names(qsr)), hidden=4, ensemble=1)
    rng = np.random.default_rng(0)
    arrays = {k: rng.normal(0, 0.1, shape).astype(np.float32) for k, shape in expected_shapes(mcfg).items()}
    folder.mkdir(parents=True)
    (folder / "__init__.py").write_text("")
    (folder / "manifest.toml").write_text(
        f'schema = 1\nname = "{name}"\nversion = "0.1.0"\nphrases = {json.dumps(phrases)}\n'
    )
    write_progress_bundle(folder, name, arrays, mcfg, qsr, training={}, metrics={})


def test_evaluation_and_the_report_live_with_two_anchor_and_viewer_plugins(tmp_path, monkeypatch):
    """Installed next to the built-ins, a between and a left-of plugin must not break the evaluation's
    confusion matrix (every installed action judges every motion) nor the review report."""
    from plugin_fixtures import make_dist

    from l2p_bullet.evaluate.worker import Worker
    from l2p_bullet.plugins import registry
    from l2p_bullet.review.report import _Motions

    site = tmp_path / "site"
    _random_bundle(site / "l2p_test_between", "between-test", ["midway between"], QSRConfig(anchors=2))
    _random_bundle(site / "l2p_test_leftof", "leftof-test", ["leftwards of"], QSRConfig(frame="viewer"))
    make_dist(site, "l2p-test-prepositions", {"between-test": "l2p_test_between", "leftof-test": "l2p_test_leftof"})
    monkeypatch.syspath_prepend(str(site))
    registry._LOADED.clear()
    try:
        w = Worker()
        assert {"between-test", "leftof-test"} <= {p.name for p in w.plugins if p.ok}
        row: dict = {}
        mover = np.linspace([0.1, 0.1, 0.0], [0.0, 0.08, 0.0], 20)
        w._confusion(row, mover, np.repeat(np.zeros((1, 3)), 20, 0), 0.05)
        assert "leftof-test" in row["judged"] and "between-test" not in row["judged"]
        # a two-anchor run in the review report: scored with both anchors
        from l2p_bullet.pipeline import perform

        scene = random_between_scene(0)
        out = tmp_path / "run"
        perform("move A midway between B and C", scene, out_dir=out, render=False, budget=2, plugins=w.plugins)
        row = type("Row", (), {"source": "app", "run_path": str(out), "demo_id": None})()
        motions = _Motions()
        final, score = motions.scores("between-test", motions.motion(row))
        assert final is not None and score is not None and not motions.notes
    finally:
        registry._LOADED.clear()
