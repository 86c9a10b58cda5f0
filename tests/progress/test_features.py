"""QSR features: the invariances the models rely on, and the relations on hand-made cases."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from l2p_bullet.progress.features import (
    QSRConfig,
    feature_names,
    motion_features,
    resample,
    resample_batch,
)

NAMES = feature_names()
COL = {n: i for i, n in enumerate(NAMES)}


def _motion(seed: int, n: int = 40, size: float = 0.15) -> tuple[np.ndarray, np.ndarray]:
    """A smooth random mover path around an anchor that drifts a little (metres, blocks of ``size``)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 1, n)[:, None]
    start = rng.uniform(-4, 4, 2) * size
    while np.linalg.norm(start) < 1.5 * size:
        start = rng.uniform(-4, 4, 2) * size
    ctrl = rng.normal(0, 3 * size, (2, 2))
    xy = start + t * ctrl[0] + t**2 * ctrl[1]
    theta = rng.uniform(0, 1.5) + t[:, 0] * rng.normal(0, 0.5)
    mover = np.column_stack([xy, theta])
    anchor = np.column_stack([t * rng.normal(0, 0.2 * size, 2), 0.3 + t[:, 0] * 0.05])
    return mover, anchor


def _transform(poses: np.ndarray, angle: float, shift: np.ndarray, scale: float = 1.0) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    xy = poses[:, :2] @ np.array([[c, s], [-s, c]]) * scale + shift
    return np.column_stack([xy, poses[:, 2] + angle])


def _close_except_boundaries(f1: np.ndarray, f2: np.ndarray) -> None:
    """Continuous columns match tightly; a one-hot may flip only where its value sits on a bin edge,
    which floating-point rounding makes ambiguous: allow at most 2 flipped frames."""
    assert f1.shape == f2.shape
    cont = [COL[n] for n in NAMES if not n.startswith(("cd_", "qdc_", "qtc_", "mv_")) and "changed" not in n]
    np.testing.assert_allclose(f1[:, cont], f2[:, cont], atol=1e-4)
    disc = [i for i in range(len(NAMES)) if i not in cont]
    flipped = np.any(np.abs(f1[:, disc] - f2[:, disc]) > 1e-6, axis=1).sum()
    assert flipped <= 2


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), angle=st.floats(-np.pi, np.pi),
       dx=st.floats(-5, 5), dy=st.floats(-5, 5))
def test_invariant_to_moving_and_rotating_the_scene(seed, angle, dx, dy):
    mover, anchor = _motion(seed)
    f1, _ = motion_features(mover, anchor, 0.15)
    shift = np.array([dx, dy])
    f2, _ = motion_features(_transform(mover, angle, shift), _transform(anchor, angle, shift), 0.15)
    _close_except_boundaries(f1, f2)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), scale=st.floats(0.1, 10.0))
def test_invariant_to_scaling_scene_and_block_size_together(seed, scale):
    mover, anchor = _motion(seed)
    f1, r1 = motion_features(mover, anchor, 0.15)
    f2, r2 = motion_features(_transform(mover, 0.0, np.zeros(2), scale), _transform(anchor, 0.0, np.zeros(2), scale),
                             0.15 * scale)
    assert len(r1.arc) == len(r2.arc)
    _close_except_boundaries(f1, f2)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000), cut=st.floats(0.2, 0.9))
def test_a_prefix_resamples_to_the_same_frames(seed, cut):
    """The planner's candidates extend one path: their shared prefix must give identical frames."""
    mover, anchor = _motion(seed)
    k = max(2, int(cut * len(mover)))
    full, pre = resample_batch([mover, mover[:k]], [anchor, anchor[:k]], 0.15)
    n = len(pre.arc) - 1  # the prefix's last frame is its own end point, off the grid
    np.testing.assert_allclose(pre.mover[:n], full.mover[:n], atol=1e-9)
    np.testing.assert_allclose(pre.arc[:n], full.arc[:n])


def test_resampling_spacing_and_end_point():
    mover = np.array([[0.0, 0, 0], [0.15, 0, 0], [0.15, 0.15 * 1.1, 0]])
    rs = resample(mover, np.array([1.0, 1.0, 0.0]), 0.15)
    assert np.allclose(np.diff(rs.arc)[:-1], 0.25)
    assert np.isclose(rs.arc[-1], 2.1)
    np.testing.assert_allclose(rs.mover[-1, :2], [1.0, 1.1])


def test_standing_still_is_one_frame():
    mover = np.repeat([[0.3, 0.0, 0.1]], 50, axis=0)
    rs = resample(mover, np.zeros(3), 0.15)
    assert len(rs.arc) == 1


def test_relations_on_hand_made_motions():
    cfg = QSRConfig()
    # straight towards the anchor from 6 blocks to 2 blocks
    mover = np.column_stack([np.linspace(6, 2, 30), np.zeros(30), np.zeros(30)])
    f, _ = motion_features(mover, np.zeros(3), 1.0, cfg)
    assert np.allclose(f[1:, COL["qtc_k_mover"]], -1)  # moving towards
    assert np.allclose(f[:, COL["qtc_k_anchor"]], 0)  # anchor static
    assert np.allclose(f[1:, COL["mv_mover"]], 1) and np.allclose(f[:, COL["mv_anchor"]], 0)
    assert f[0, COL["qdc_3"]] == 1 and f[-1, COL["qdc_1"]] == 1  # very far -> near
    assert f[:, [COL[f"cd_{i}"] for i in range(8)]].argmax(axis=1).max() == 0  # never changes side
    assert np.isclose(f[-1, COL["dist"]] * 5, 2.0)
    # half a circle around it: swept angle pi, ends on the opposite side (cd_4), moving sideways
    a = np.linspace(0, np.pi, 60)
    mover = np.column_stack([3 * np.cos(a), 3 * np.sin(a), np.zeros(60)])
    f, _ = motion_features(mover, np.zeros(3), 1.0, cfg)
    assert np.isclose(f[-1, COL["swept"]], 1.0, atol=1e-6)
    assert f[-1, [COL[f"cd_{i}"] for i in range(8)]].argmax() == 4
    assert np.all(f[1:, COL["qtc_l_mover"]] != 0) and np.allclose(f[1:, COL["qtc_k_mover"]], 0)
    # touching face to face: the gap is 0
    f, _ = motion_features(np.array([[1.0, 0, 0], [1.0, 0, 0]]), np.zeros(3), 1.0, cfg)
    assert np.isclose(f[-1, COL["gap"]], 0.0) and np.isclose(f[-1, COL["face_alignment"]], 1.0)


def test_config_round_trip_and_names():
    cfg = QSRConfig(spacing=0.5, qdc_edges=(1.0, 2.0))
    assert QSRConfig.from_dict(cfg.to_dict()) == cfg
    assert cfg.n_features == len(feature_names(cfg))
    f, _ = motion_features(np.array([[3.0, 0, 0], [0, 3.0, 0]]), np.zeros(3), 1.0, cfg)
    assert f.shape[1] == cfg.n_features and f.dtype == np.float32


def test_a_cube_s_features_are_the_unit_square_s_bit_for_bit():
    """Without outlines (every object a cube) the gap column is the unit squares' formula the bundles were
    trained on, exactly; a cube's own square given as an outline measures the same gap."""
    mover, anchor = _motion(5, size=0.05)
    f, rs = motion_features(mover, anchor, 0.05)
    d = rs.mover[:, :2] - rs.anchor[:, :2]
    r = np.linalg.norm(d, axis=1)
    bearing = np.arctan2(d[:, 1], d[:, 0])

    def half(phi):
        return 0.5 / np.maximum(np.abs(np.cos(phi)), np.abs(np.sin(phi)))

    gap = r - half(bearing - rs.anchor[:, 2]) - half(bearing + np.pi - rs.mover[:, 2])
    assert np.array_equal(f[:, COL["gap"]], (np.clip(gap, -1.0, 12.0) / 5.0).astype(np.float32))
    square = np.array([[-0.025, -0.025], [0.025, -0.025], [0.025, 0.025], [-0.025, 0.025]])
    g, _ = motion_features(mover, anchor, 0.05, outlines=[square, square])
    assert np.allclose(g, f, atol=1e-6)


def test_the_gap_to_a_2_to_1_box_is_to_its_real_outline():
    """A 4 cm cube coming at a 12 x 6 cm box: the gap column reads the box's long face, then its end."""
    from l2p_bullet.core.scene import SceneObject, shaped
    from l2p_bullet.judge.footprints import outlines_of

    cube, box = SceneObject("A", "red", 0.04, (0.0, 0.1)), shaped("B", "green", (0.0, 0.0), dims=(0.12, 0.06, 0.04))
    outlines = outlines_of([cube, box])
    towards_face = np.column_stack([np.zeros(20), np.linspace(0.2, 0.065, 20), np.zeros(20)])
    f, _ = motion_features(towards_face, box.pose, 0.04, outlines=outlines)
    assert np.isclose(f[-1, COL["gap"]] * 5, 0.015 / 0.04, atol=1e-6)  # 1.5 cm from the long face
    square, _ = motion_features(towards_face, box.pose, 0.04)
    assert np.isclose(square[-1, COL["gap"]] * 5, 0.025 / 0.04, atol=1e-6)  # a 4 cm square at its centre
    towards_end = towards_face[:, [1, 0, 2]]
    f, _ = motion_features(towards_end, box.pose, 0.04, outlines=outlines)
    assert np.isclose(f[-1, COL["gap"]] * 5, -0.015 / 0.04, atol=1e-6)  # 1.5 cm into its end: overlapping


@pytest.mark.slow
def test_the_planner_gives_the_model_the_footprints_only_where_an_object_is_not_a_cube(monkeypatch):
    from l2p_bullet import planning
    from l2p_bullet.core.scene import Scene, SceneObject, shaped
    from l2p_bullet.plugins import registry
    from l2p_bullet.progress.scoring import ScoringMixin

    seen = []
    real = ScoringMixin.final_batch

    def spy(self, movers, anchors, size, **kw):
        seen.append(kw.get("outlines"))
        return real(self, movers, anchors, size, **kw)

    monkeypatch.setattr(ScoringMixin, "final_batch", spy)
    bundle = registry.load("next-to")
    assert not bundle.progress_model().reads_outlines  # the built-in bundles were trained on squares
    monkeypatch.setattr(ScoringMixin, "reads_outlines", True)  # a model trained on outlines declares it
    cube = SceneObject("A", "red", 0.04, (-0.1, 0.0))
    box = Scene([cube, shaped("B", "green", (0.0, 0.1), dims=(0.12, 0.06, 0.04))]).validate()
    planning.plan(box, "A", "B", bundle, budget=2)
    assert seen and all(o is not None and len(o) == 2 and np.ptp(o[1][:, 0]) == pytest.approx(0.12) for o in seen)
    seen.clear()
    cubes = Scene([cube, SceneObject("B", "green", 0.06, (0.0, 0.1))]).validate()
    planning.plan(cubes, "A", "B", bundle, budget=2)
    assert seen and all(o is None for o in seen)
