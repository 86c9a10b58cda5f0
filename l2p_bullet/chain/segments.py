"""Reading a chain run back: its segments (one per clause) as motions, for ``score``, ``export`` and ``review``.

A chain's trajectory.json holds one episode; its ``segments`` say which frames each clause covers and which
blocks it moved relative to which. A reader that scores, exports or shows one action at a time takes each
segment as a motion of its own (its mover, its anchors, its frames), so no clause is scored with another
clause's blocks.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..core.contracts import read_json, trajectory_poses
from ..errors import PathError
from ..progress.scoring import curve_from
from .clauses import MAX_CLAUSES


def segments_of(doc: dict, source: str = "trajectory.json") -> list[dict] | None:
    """The ``segments`` of a trajectory.json document, checked against its frames; None for a one-clause run."""
    segs = doc.get("segments")
    if segs is None:
        return None
    n = len(doc.get("frames") or [])
    names = set(doc.get("objects") or {})
    if not isinstance(segs, list) or not 1 <= len(segs) <= MAX_CLAUSES:  # a chain stops at MAX_CLAUSES clauses
        count = len(segs) if isinstance(segs, list) else type(segs).__name__
        raise PathError(f'{source}: "segments" must list 1 to {MAX_CLAUSES} clauses (got {count})')
    try:
        after = 0  # each clause's frames follow the previous clause's, from frame 0 on
        for s in segs:
            first, last = int(s["first_frame"]), int(s["last_frame"])
            if not 0 <= first <= last < n:
                raise ValueError(f"frames {first}..{last} of {n}")
            if first != after:
                raise ValueError(f"frames {first}..{last} do not follow the previous clause's (next frame {after})")
            after = last + 1
            if not first <= int(s.get("action_from", first)) <= last:
                raise ValueError(f"action_from {s['action_from']} outside frames {first}..{last}")
            for name in [s["mover"], *s["anchors"]]:
                if name not in names:
                    raise ValueError(f'unknown object "{str(name)[:40]}"')
    except (KeyError, TypeError, ValueError) as e:
        raise PathError(f"{source}: a malformed segment in \"segments\" ({type(e).__name__}: {str(e)[:80]})") from None
    return list(segs)


def segment_frames(doc: dict, seg: dict) -> list[dict]:
    return doc["frames"][int(seg["first_frame"]):int(seg["last_frame"]) + 1]


def action_start(seg: dict) -> int:
    """Where the segment's action proper starts, counted from its first frame (``action_from``: a clause that
    came near first; 0 for every other)."""
    return int(seg.get("action_from", seg["first_frame"])) - int(seg["first_frame"])


def score_segments(path: str | Path, model: Any) -> list[dict] | None:
    """``model``'s progress on each segment of the chain run at ``path`` (None when it is no chain run)."""
    try:
        doc = read_json(path)
    except PathError:
        return None
    segs = segments_of(doc, str(path)) if "frames" in doc else None
    if segs is None:
        return None
    out = []
    for s in segs:
        frames = segment_frames(doc, s)
        mover, anchors = s["mover"], list(s["anchors"])
        entry = {k: s[k] for k in ("clause", "text", "action", "mover", "anchors", "first_frame", "last_frame")}
        if len(anchors) != getattr(model, "anchors", 1):
            out.append(entry | {"progress": None, "final": None,
                                "skipped": f"the model reads {model.anchors} reference block(s), the clause names "
                                           f"{len(anchors)}"})
            continue
        more = [trajectory_poses(frames, a) for a in anchors[1:]]
        kw = {"more_anchors": more} if more else {}
        size = float(doc["objects"][mover]["size"])
        curve = curve_from(
            model, action_start(s), trajectory_poses(frames, mover), trajectory_poses(frames, anchors[0]), size, **kw
        )
        out.append(entry | {"progress": [round(float(v), 4) for v in curve], "final": round(float(curve[-1]), 4)})
    return out


def segment_docs(run: str | Path) -> list[dict] | None:
    """A chain run's trajectory.json cut into one trajectory.json-like document per segment (its frames,
    mover, anchor and sentence), or None for a one-clause run."""
    doc = read_json(Path(run) / "trajectory.json")  # bounded: a run folder from elsewhere may hold anything
    segs = segments_of(doc, f"{run}/trajectory.json")
    if segs is None:
        return None
    base = {k: v for k, v in doc.items() if k not in ("frames", "segments")}
    return [base | {"sentence": s.get("sentence") or s.get("text"), "action": s["action"], "mover": s["mover"],
                    "anchor": s["anchors"][0], "anchors": list(s["anchors"]), "frames": segment_frames(doc, s),
                    **({"action_from": action_start(s)} if "action_from" in s else {}),
                    "chain": {"sentence": doc.get("sentence"), "clause": s["clause"], "first_frame": s["first_frame"],
                              "last_frame": s["last_frame"]}}
            for s in segs]
