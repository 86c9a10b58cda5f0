"""A chain's run folder: the one-clause files with the chain's fields added (contracts only grow).

- trajectory.json: the frames of the whole episode (every object's pose in each), ``segments`` (one per
  clause performed: clause index, text, action, mover, anchors, first and last frame); the top-level
  ``action``/``mover``/``anchor`` are the first clause's, for readers that know no segments.
- plan.json: the first clause's plan in the one-clause layout, and ``clauses``: every clause's plan as
  executed (re-planned from the real state) with the up-front ``forecast`` beside it.
- summary.json: ``chain`` (the chain's verdict: success, clauses completed, the first failure's reason),
  ``clauses`` (a verdict per clause), ``verdict``/``success`` the chain's; the one-clause fields that have a
  meaning for the whole chain (:func:`whole_chain`), and ``render`` as a one-clause run writes it.
- video: each image captioned with the clause being performed and its learned progress.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from ..core.contracts import dumps_json
from ..core.runfolder import write_summary
from ..embodiment.execute import render_info
from ..embodiment.record import versions
from ..pipeline import DISTURBED_M, scene_fields


def segments(result: Any) -> list[dict[str, Any]]:
    """trajectory.json's ``segments``: one per clause performed, in order."""
    out = []
    for r in result.results:
        c = r.clause.command
        out.append({"clause": r.clause.index, "text": r.clause.text, "sentence": c.sentence, "action": c.action,
                    "mover": c.mover, "anchor": c.anchor, "anchors": list(c.anchors),
                    "first_frame": r.first_frame, "last_frame": r.last_frame,
                    **({} if c.manner == "slide" else {"manner": c.manner}),  # only when not a slide
                    **({} if c.pace is None else {"pace": c.pace}),  # "slowly": its motions' limits scaled
                    **({} if c.extent is None else {"extent": c.extent}),
                    **({} if r.action_from is None else {"action_from": r.action_from})})  # came near first
    return out


def write_run(result: Any, steps: list, prims: Any, world: Any, settings: Any, seed: int, scene: Any,
              replay: dict | None = None) -> None:
    """trajectory.json, plan.json, images (when rendering) and summary.json of a chain run. ``replay`` (a
    replay of a chain's plan.json: where it came from): plan.json records the motions replayed, not plans, and
    both files get ``replay``, as a one-clause replay's (DESIGN.md section 4)."""
    out, rec = Path(result.out_dir), prims.recorder
    first = steps[0]
    cmd = first.clause.command
    meta: dict[str, Any] = {"sentence": result.sentence, "action": cmd.action, "mover": cmd.mover,
                            "anchor": cmd.anchor, "segments": segments(result)}
    if cmd.more_anchors:
        meta["anchors"] = list(cmd.anchors)
    if first.viewer is not None:
        meta["viewer"] = [float(v) for v in first.viewer]
    files = {"trajectory": out / "trajectory.json", "plan": out / "plan.json"}
    rec.write_trajectory(files["trajectory"], meta, world.sizes)
    _write_plans(files["plan"], result, steps, scene, replay)
    if rec.film is not None:
        files |= rec.write_images(out, settings.video, captions(result, rec))
    files["summary"] = out / "summary.json"
    result.files = files
    chain = result.verdict()
    summary = {
        "schema": 1, "ok": True, "sentence": result.sentence, "chain": chain,
        "clauses": [r.to_dict() for r in result.results],
        "not_run": [{"clause": s.clause.index, "text": s.clause.text} for s in steps[len(result.results):]],
        "verdict": {"success": chain["success"], "reason": chain["reason"]}, "success": chain["success"],
        "command": {"verb": cmd.verb, "mover": cmd.mover, "preposition": cmd.preposition, "action": cmd.action,
                    "anchor": cmd.anchor, "anchors": list(cmd.anchors)},
        "seed": seed, "arm": world.robot.spec.name, "simulated_s": round(world.time, 4),
        "displacements_m": bystanders(rec.frames, result),
        "execution": {"physics_steps": world.steps, "ik_solves": prims.ik_solves,
                      "rendered_frames": len(rec.images), "frames": len(rec.frames)},
        **whole_chain(result),
        "render": _render(settings, rec.film),
        "plugins": {s.bundle.name: {"version": s.bundle.version, "path": str(s.bundle.path)} for s in steps},
        **({} if replay is None else {"replay": replay}),
        "files": {k: v.name for k, v in files.items()},
        "versions": versions(),
    }
    write_summary(files["summary"], summary)


def whole_chain(result: Any) -> dict[str, Any]:
    """summary.json's one-clause fields that mean something for a whole chain (readers that know no
    ``clauses`` find them where a one-clause run has them): ``action``/``mover``/
    ``anchor`` the first clause's (as trajectory.json's), ``max_deviation_m`` the largest of the clauses',
    ``anchor_displacement_m`` the largest displacement of a block by a clause that did not move it, and
    ``disturbed`` the blocks a clause that did not move them moved more than 1 mm. Per-clause values (progress,
    final error, grasp) stay in ``clauses`` only: one number for the chain would mislead."""
    first = result.clauses[0].command
    moved = [(k, v) for r in result.results for k, v in r.displacements_m.items() if v is not None]
    deviations = [r.max_deviation_m for r in result.results if r.max_deviation_m is not None]
    return {"action": first.action, "mover": first.mover, "anchor": first.anchor,
            "max_deviation_m": round(float(max(deviations)), 6) if deviations else None,
            "anchor_displacement_m": round(float(max(v for _, v in moved)), 6) if moved else None,
            "disturbed": sorted({k for k, v in moved if v > DISTURBED_M})}


def _render(settings: Any, film: Any) -> dict[str, Any] | None:
    """summary.json's ``render``: a one-clause run's (the renderer the film could start, its camera and
    workers) when frames were drawn; the settings asked for otherwise."""
    if film is not None:
        return render_info(settings, film)
    return None if settings is None else {"width": settings.width, "height": settings.height, "fps": settings.fps,
                                          "renderer": settings.renderer}


def merge_timings(path: Path, timings: dict[str, float]) -> None:
    """Add the chain's stage timings to summary.json once the clock has stopped."""
    summary = json.loads(path.read_text())
    summary["timings_s"] = {k: round(v, 4) for k, v in timings.items()}
    write_summary(path, summary)


def bystanders(frames: list[dict], result: Any) -> dict[str, float]:
    """Over the whole episode, how far each block that no clause moved got from where it started."""
    movers = {r.clause.command.mover for r in result.results}
    out = {}
    for name in frames[0]["poses"] if frames else {}:
        if name not in movers:
            xy = np.array([f["poses"][name][:2] for f in frames], float)
            out[name] = round(float(np.hypot(*(xy - xy[0]).T).max()), 6)
    return out


def captions(result: Any, rec: Any) -> list[str]:
    """Each rendered image's caption: the clause whose frames it falls in ("2/3 slide C past A")."""
    n = len(result.clauses)
    times = np.array([f["t"] for f in rec.frames], float)
    bounds = [(times[r.first_frame], r) for r in result.results]
    out = []
    for t in rec.image_times:
        current = bounds[0][1] if bounds else None
        for start, r in bounds:
            if t + 1e-6 >= start:
                current = r
        out.append("" if current is None else f"{current.clause.index}/{n}: {current.clause.command.sentence}")
    return out


def _write_plans(path: Path, result: Any, steps: list, scene: Any, replay: dict | None = None) -> None:
    """plan.json: the first clause's plan as a one-clause run writes it, plus every clause's plan and
    ``chain`` (the sentence and the scene it started from: ``replay`` needs both). A replay's (``replay`` given)
    records the motions it replayed: ``planner`` and ``stopped`` "replay", ``progress`` null, as a one-clause
    replay's plan.json."""
    mark = (lambda d: d) if replay is None else _replayed
    clauses = []
    for s, r in zip(steps, result.results, strict=False):
        executed = mark(r.plan.to_dict()) if r.plan is not None else None
        clauses.append({"clause": s.clause.index, "text": s.clause.text, "plan": executed,
                        "forecast": mark(s.forecast.to_dict())})
    head = result.results[0].plan if result.results and result.results[0].plan is not None else steps[0].forecast
    # scene, scene_sha256: the first clause's, as a one-clause run's
    doc = mark(head.to_dict()) | scene_fields(scene) | {
        "clauses": clauses, "chain": {"sentence": result.sentence, "scene": scene.to_dict()},
        **({} if replay is None else {"replay": replay})}
    path.write_text(dumps_json(doc, indent=1) + "\n")


def _replayed(plan: dict) -> dict:
    """A plan's dict as a replay records it (embodiment/replay.py does the same for one clause): the motion,
    not a plan, so no planner stopped it and no model scored it here."""
    return plan | {"planner": "replay", "stopped": "replay", "progress": [None] * len(plan.get("path") or [])}
