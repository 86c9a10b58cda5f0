"""What ``replay`` executes: a demonstration, a scoring input or a plan, turned into a scene path.

Kept apart from the click command so that tests and the benchmark can use it without a CLI.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..actions import BUILTIN
from ..arms import PANDA, ArmSpec
from ..core.contracts import Plan, dumps_json, motion_from_dict, read_json
from ..core.runfolder import write_summary
from ..core.scene import Scene
from ..core.vocabulary import canonical_action
from ..data.demos import get_demo
from ..errors import PathError, SceneError
from ..language import manner_of_sentence
from .execute import check_waypoints, execute_path
from .retarget import retarget


@dataclass
class Source:
    """A path of ``mover`` in the scene frame, where it came from, and how it was fitted."""

    label: str
    mover: str
    anchor: str
    path: np.ndarray  # (N,3), scene frame
    action: str | None = None
    info: dict = field(default_factory=dict)
    manner: str = "slide"  # a plan's: what its sentence's verb asked for (a carried path crosses blocks)
    sentence: str | None = None  # a plan's sentence (trajectory.json's and summary.json's); None for a motion
    caption: str | None = None  # the video's caption when there is no sentence: a demonstration's action as said


def replay_scene(path_json: str | None, scene: Scene | None, scene_path: str | None = None,
                 mesh_dirs: tuple = ()) -> Scene:
    """The scene to replay on: a plan.json's recorded scene (``scene``, written by ``plan`` and
    ``perform``), checked against ``--scene`` when both are given; else ``--scene`` or the default.

    A plan's path is in its scene's frame and threads between its blocks: replayed on another scene it
    runs into them, or silently leaves a block out. So a mismatch is refused before any folder is made.
    """
    from ..core.scene import default_scene

    recorded = None
    if path_json is not None:
        from ..core.contracts import read_json

        data = read_json(path_json)
        if (scene is not None and isinstance(data, dict) and "path" in data
                and data.get("scene_sha256") == scene.digest()):
            # --scene is the very scene it records: replayed there, its meshes read from that file's folder (the
            # recorded scene names them by absolute path, outside the run folder: docs/perform.md, "Paths")
            return scene
        if isinstance(data, dict) and "path" in data and isinstance(data.get("scene"), dict):
            recorded = Scene.from_dict(data["scene"], source=f"{path_json} (its scene)",
                                       base=Path(path_json).resolve().parent,
                                       mesh_dirs=tuple(Path(d) for d in mesh_dirs)).validate()
    if recorded is None:
        return scene if scene is not None else default_scene()
    if scene is not None and scene.digest() != recorded.digest():
        raise PathError(f"{path_json} was planned on another scene than {scene_path or '--scene'} (its blocks "
                        "differ): leave out --scene to replay it on the scene it records")
    return recorded


def motion_source(path_json: str | None, demo: str | None, scene: Scene, mover: str, anchor: str) -> Source:
    """Read ``--demo ACTION:INDEX`` or a scoring input / plan.json into a :class:`Source`, its waypoints
    checked (finite, inside the workspace) before anything is densified or a run folder is made."""
    source = _motion_source(path_json, demo, scene, mover, anchor)
    check_waypoints(scene, source.mover, source.path)
    return source


def _motion_source(path_json: str | None, demo: str | None, scene: Scene, mover: str, anchor: str) -> Source:
    if demo is not None:
        action, sep, index = demo.partition(":")
        if not sep or not index.strip().lstrip("-").isdigit():
            raise PathError(f'--demo expects ACTION:INDEX, e.g. around:0 (got "{demo}")')
        d = get_demo(canonical_action(action), int(index))
        fit = retarget(d.event_mover, d.event_anchor, d.size, scene, mover, anchor)
        return Source(f"demonstration {d.id}", mover, anchor, fit.path, d.action,
                      {"source": {"demo": d.id, "frames": [d.start, d.end]}, "retarget": _fit_info(fit)},
                      caption=demo_caption(d.action, mover, anchor))

    data = read_json(path_json)
    if "path" in data:  # plan.json: already in the scene frame
        plan = Plan.from_dict(data, source=str(path_json))
        scene.get(plan.mover)
        sentence = data.get("sentence") if isinstance(data.get("sentence"), str) else None
        return Source(f"plan {path_json}", plan.mover, plan.anchor, plan.path, plan.action,
                      {"source": {"plan": str(path_json)}}, manner_of_sentence(sentence), sentence)

    m = motion_from_dict(data, source=str(path_json))
    mover, anchor = m.mover_name or mover, m.anchor_name or anchor
    fit = retarget(m.mover, m.anchor, m.size, scene, mover, anchor)
    return Source(f"motion {Path(path_json).name}", mover, anchor, fit.path, m.action,
                  {"source": {"motion": str(path_json)}, "retarget": _fit_info(fit)})


def demo_caption(action: str, mover: str, anchor: str) -> str:
    """What a replayed demonstration shows, said as its action's example sentence with these blocks ("move C
    around D"): the video's caption, where a performed run shows its sentence."""
    words = BUILTIN[action].sentence.split() if action in BUILTIN else ["move", "A", action, "B"]
    return " ".join([words[0], mover, *words[2:-1], anchor])


def _fit_info(fit) -> dict:
    return {"clamped_points": fit.clamped, "pushed_points": fit.pushed, "max_fix_m": round(fit.max_fix_m, 6),
            "points": len(fit.path)}


def run_replay(scene: Scene, source: Source, out_dir: Path | None, render, seed: int = 0, on_stage=None,
               arm: ArmSpec = PANDA):
    """Put the mover at the path's start (the motion defines where it begins) and execute the path with ``arm``."""
    start = scene.with_pose(source.mover, source.path[0])
    try:
        start.validate()
    except SceneError as e:
        raise PathError(f"the motion's start pose does not fit the scene: {e}") from None
    plan_file = None
    if out_dir is not None:
        plan_file = Path(out_dir) / "plan.json"
        plan = Plan(source.action or "replay", source.mover, source.anchor, start.get(source.mover).size,
                    start.get(source.anchor).pose, source.path[0], source.path, np.zeros(len(source.path)),
                    "replay", "replay", {"replay": source.info})
        doc = plan.to_dict() | {"progress": [None] * len(source.path)}  # no model scored a replay
        doc.update(scene=scene.to_dict(), scene_sha256=scene.digest())
        if source.sentence is not None:  # replayed again, it is still that sentence's motion (and manner)
            doc["sentence"] = source.sentence
        plan_file.write_text(dumps_json(doc, indent=1) + "\n")
    meta = {"action": source.action, "mover": source.mover, "anchor": source.anchor, "replay": source.info,
            "arm": arm.name}
    if source.sentence is not None:  # a plan's: the sentence it was planned for, as a chain's replay keeps its own
        meta["sentence"] = source.sentence
    elif source.caption is not None:
        meta["caption"] = source.caption
    if len(source.path) == 1:  # a plan that moves nothing (the relation already held): the world stands still
        from .execute import execution_summary
        from .still import stand_still

        ex = stand_still(start, source.mover, out_dir=out_dir, meta=meta, arm=arm, on_stage=on_stage)
        if out_dir is not None:
            ex.files["summary"] = Path(out_dir) / "summary.json"
            write_summary(ex.files["summary"], execution_summary(ex, meta, seed, None))
    else:
        ex = execute_path(start, source.mover, source.path, out_dir=out_dir, render=render, seed=seed, meta=meta,
                          on_stage=on_stage, arm=arm, manner=source.manner)
    if plan_file is not None:
        ex.files["plan"] = plan_file
        summary_file = ex.files.get("summary")
        if summary_file is not None and summary_file.exists():  # summary.json lists every file of the folder
            summary = read_json(summary_file)
            summary.setdefault("files", {})["plan"] = plan_file.name
            summary.setdefault("ok", True)  # a finished run says so, as perform's and a chain replay's do
            write_summary(summary_file, summary)
    return ex
