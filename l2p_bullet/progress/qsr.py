"""The feature space of a progress model: :class:`QSRConfig` (what a manifest's ``[features]`` records) and the
names of the columns it gives, in order (:func:`feature_names`), with the columns a manifest's declarations
append:
- ``frame = "viewer"``: the mover's offset from the anchor as a viewer sees it (:data:`VIEWER_NAMES`);
- ``anchors = 2``: the mover's place relative to the segment between the two anchors (:data:`TWO_ANCHOR_NAMES`).

Apart from the computation (``features.py``) and the resampling (``resample.py``), which both read it, because
it is a declaration, not a computation: a bundle's manifest records it and its validation checks it
(plugins/bundle.py, plugins/validate.py) without computing a column. ``features.py`` re-exports these names,
where every caller reads them.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

from ..core.frames import RELATIVE, parse_anchors, parse_frame


@dataclass(frozen=True)
class QSRConfig:
    """Feature parameters. Every length is in blocks (units of the block side), angles in radians."""

    spacing: float = 0.25
    """Arc-length distance between resampled frames (DESIGN.md section 5: 0.25 beat time sampling)."""
    cd_sectors: int = 8
    """Cardinal-direction sectors around the anchor (8: the compass rose N, NE, E, ...)."""
    qdc_edges: tuple[float, ...] = (1.5, 3.0, 5.0)
    """QDC bins on the centre distance: touching/adjacent < 1.5 <= near < 3 <= far < 5 <= very far."""
    moving_eps: float = 0.02
    """A block moving less than this per resampled frame is static (MV and QTC's 0)."""
    max_distance: float = 12.0
    """Distances are clipped here before scaling (the network sees bounded inputs)."""
    frame: str = RELATIVE
    """Where the relation is seen from (``core/frames.py``): "relative", or "viewer[:name]" for the
    viewer-frame columns."""
    anchors: int = 1
    """Reference objects: 2 appends the columns of the mover relative to the segment between them."""

    def to_dict(self) -> dict:
        d = asdict(self)
        d["qdc_edges"] = list(self.qdc_edges)
        # Left out at their defaults: a relative one-anchor manifest reads exactly as it did before
        # frames and second anchors existed.
        if self.frame == RELATIVE:
            d.pop("frame")
        if self.anchors == 1:
            d.pop("anchors")
        return d

    @classmethod
    def from_dict(cls, d: dict) -> QSRConfig:
        known = {f.name for f in fields(cls)}
        kw = {k: v for k, v in d.items() if k in known}
        if "qdc_edges" in kw:
            kw["qdc_edges"] = tuple(float(v) for v in kw["qdc_edges"])
        if "frame" in kw:
            kw["frame"] = parse_frame(kw["frame"]).name
        if "anchors" in kw:
            kw["anchors"] = parse_anchors(kw["anchors"])
        return cls(**kw)

    @property
    def viewer(self) -> bool:
        """Whether the features need a viewpoint (a viewer frame)."""
        return self.frame != RELATIVE

    @property
    def n_features(self) -> int:
        return len(feature_names(self))


def feature_names(cfg: QSRConfig = QSRConfig()) -> list[str]:
    """Names of the feature columns, in order (written to the manifest so a bundle documents itself)."""
    names = ["dist", "log_dist", "gap", "dist_change_from_start", "log_dist_ratio", "bearing_cos",
             "bearing_sin", "swept", "swept_abs", "face_alignment", "rot_cos", "rot_sin",
             "path_length", "displacement", "first_frame"]
    names += [f"cd_{i}" for i in range(cfg.cd_sectors)]
    names += [f"qdc_{i}" for i in range(len(cfg.qdc_edges) + 1)]
    names += ["mv_mover", "mv_anchor", "qtc_k_mover", "qtc_k_anchor", "qtc_l_mover", "qtc_l_anchor"]
    names += ["d_dist", "d_swept", "d_rot", "cd_changed", "qdc_changed", "qtc_changed"]
    if cfg.viewer:
        names += VIEWER_NAMES
    if cfg.anchors == 2:
        names += TWO_ANCHOR_NAMES
    return names


VIEWER_NAMES = ["view_lateral", "view_depth", "view_cos", "view_sin", "d_view_lateral", "d_view_depth"]
"""Viewer-frame columns: the mover's offset from the anchor seen from the viewpoint (lateral > 0 is the
viewer's left, depth > 0 behind the anchor), its bearing from the line of sight, and their changes."""

TWO_ANCHOR_NAMES = ["seg_t", "seg_lateral", "seg_dist", "mid_dist", "dist2", "gap2", "anchor_sep", "d_seg_dist"]
"""Two-anchor columns: where the mover projects on the segment from anchor 1 (0) to anchor 2 (1), how far
it is from that line, from the segment and from its midpoint, its distance and gap to anchor 2, how far
apart the anchors are, and the change of the distance to the segment."""

