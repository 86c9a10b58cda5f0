"""What a worker does with a task: perform (or plan) it, judge it by every installed action, return a row.

A :class:`Worker` lives as long as its process (a pool worker or a Ray actor) and keeps what is
expensive to make: the discovered plugins, the loaded bundles with their numpy progress models
(``registry.load`` and ``Bundle.progress_model`` cache them per process), one judge per action, and its
PyBullet worlds (one without visuals, one with, made on first use). No run sees another's state: a
planner is made per run, and ``execute_path`` resets the world to the run's scene before it starts
(``World.reset``: a reused world records byte for byte what a new one would, tests/embodiment/test_sim_world.py).
A run that fails inside the simulator leaves its world behind: the next run gets a new one.

The automatic confusion matrix is computed here, where the executed trajectory is in memory: every
installed action's judge reads it (``judge_for``: the built-ins' rules; a plugin without rules falls
back to its progress model) and every installed progress model scores it (``final``).
"""

from __future__ import annotations

import json
import os
import shutil
import socket
import tempfile
import time
import traceback
from pathlib import Path
from typing import Any

import numpy as np

from ..chain import perform_chain
from ..core.contracts import trajectory_poses
from ..core.scene import Scene
from ..embodiment.sim.world import World
from ..errors import L2PError
from ..judge import judge_context, judge_for
from ..judge.footprints import gap as footprint_gap
from ..judge.footprints import outlines_of
from ..pipeline import judged_plan, prepare
from ..plugins import registry
from .tasks import Task

TIMING_FIELDS = ("plan_s", "execute_s", "total_s", "wall_s", "timings", "worker", "finished_at")
"""Row fields that depend on the machine and the moment, not on the task (left out when comparing runs)."""


def empty_row(task: Task) -> dict[str, Any]:
    """A row with the task's fields filled and every result field empty (an error row until filled)."""
    return {
        "run_id": task.run_id,
        "idx": task.index,
        "scene_id": task.scene_id,
        "scene_source": task.scene_source,
        "seed": task.seed,
        "sentence": task.sentence,
        "action": task.action,
        "planner": task.planner,
        "manner": getattr(task, "manner", "slide"),
        "planner_used": None,
        "mode": task.mode,
        "success": None,
        "score": None,
        "reason": None,
        "judge": None,
        "final_progress": None,
        "planned_progress": None,
        "max_deviation_m": None,
        "anchor_displacement_m": None,
        "final_error_m": None,
        "final_gap_blocks": None,
        "stopped": None,
        "plan_steps": None,
        "judged": None,
        "scored": None,
        "timings": None,
        "plan_s": None,
        "execute_s": None,
        "total_s": None,
        "wall_s": None,
        "worker": None,
        "run_dir": None,
        "error": None,
        "error_type": None,
        "finished_at": None,
        "completed": None,
        "redraws": None,
        "clauses": None,
    }


def error_row(task: Task, error_type: str, message: str) -> dict[str, Any]:
    """The row of a run that failed outside the worker's control (the worker process died, Ray lost it)."""
    row = empty_row(task)
    row.update(success=0, error=message, error_type=error_type, finished_at=time.time())
    return row


class Worker:
    """Runs tasks one after another in one process; see the module docstring for what it keeps."""

    def __init__(self) -> None:
        self.plugins = registry.discover()
        self.ident = f"{socket.gethostname()}:{os.getpid()}"
        self._judges: dict[str, Any] | None = None
        self._scratch: Path | None = None
        self._worlds: dict[Any, Any] = {}  # visuals (and the arm's name, for an arm other than the Panda) -> World

    # --- per process, built once ---------------------------------------------------------------
    def judges(self) -> dict[str, tuple[Any, Any]]:
        """action -> (judge, progress model) for every usable installed action."""
        if self._judges is None:
            self._judges = {}
            for info in self.plugins:
                if not info.ok:
                    continue
                bundle = registry.load(info.name, self.plugins)
                self._judges[info.name] = (judge_for(bundle), bundle.progress_model())
        return self._judges

    def scratch(self) -> Path:
        """A folder for the run folders nobody asked to keep (emptied after each run)."""
        if self._scratch is None:  # removed when the process exits (TemporaryDirectory's finalizer)
            self._tmp = tempfile.TemporaryDirectory(prefix="l2p-evaluate-")
            self._scratch = Path(self._tmp.name)
        return self._scratch

    def world(self, scene: Any, visuals: bool, arm: str = "panda") -> Any:
        """This process's world (with or without the arm's visuals), made on first use."""
        key = visuals if arm == "panda" else (visuals, arm)
        if key not in self._worlds:
            from ..plugins import arms as arm_plugins

            self._worlds[key] = World(scene, arm=arm_plugins.get(arm), visuals=visuals)
        return self._worlds[key]

    def drop_world(self, visuals: Any, arm: str = "panda") -> None:
        """Close and forget a world a failed run may have left in an unknown state."""
        w = self._worlds.pop(visuals if arm == "panda" else (visuals, arm), None)
        if w is not None:
            w.close()

    def close(self) -> None:
        for key in list(self._worlds):
            w = self._worlds.pop(key)
            w.close()
        if self._scratch is not None:
            self._tmp.cleanup()
            self._scratch = None

    # --- one task ------------------------------------------------------------------------------
    def run(self, task: Task) -> dict[str, Any]:
        """The task's row; an L2PError (or a bug) in the run becomes the row's error, never an exception."""
        t0 = time.perf_counter()
        row = empty_row(task)
        try:
            if task.mode == "plan":
                self._plan(task, row)
            elif task.mode == "chain":
                from .chains import run_chain

                run_chain(self, task, row)
            else:
                self._perform(task, row)
        except L2PError as e:
            row.update(success=0, error=str(e), error_type=type(e).__name__)
        except Exception as e:  # a bug on one scene must not end the evaluation: record it
            tb = traceback.format_exc(limit=-3).strip().splitlines()
            row.update(success=0, error=f"{type(e).__name__}: {e} [{' | '.join(tb[-3:])}]", error_type="bug")
        row.update(wall_s=time.perf_counter() - t0, worker=self.ident, finished_at=time.time())
        return row

    def _perform(self, task: Task, row: dict) -> None:
        keep_always = task.render or task.keep == "all"
        out = (
            Path(task.run_dir) if (task.run_dir and (keep_always or task.keep == "failed")) else self.scratch() / "run"
        )
        scene = Scene.from_dict(task.scene, source=task.scene_id)
        try:
            world = self.world(scene.validate(), visuals=task.render, arm=task.arm)
            try:
                r = perform_chain(task.sentence, scene, task.options(out), plugins=self.plugins, world=world)
            except BaseException:
                self.drop_world(task.render, task.arm)
                raise
            traj = json.loads((r.out_dir / "trajectory.json").read_text())
            frames = traj["frames"]
            mover, anchor = trajectory_poses(frames, task.mover), trajectory_poses(frames, task.anchor)
            more = [trajectory_poses(frames, a) for a in task.more_anchors]
            size = scene.get(task.mover).size
            row.update(
                planner_used=r.plan.planner, success=int(r.success), score=r.verdict.get("score"),
                reason=r.verdict.get("reason"), judge=r.verdict.get("judge"), final_progress=r.final_progress,
                planned_progress=r.planned_progress, max_deviation_m=r.max_deviation_m,
                anchor_displacement_m=r.anchor_displacement_m, final_error_m=r.final_error_m,
                stopped=r.plan.stopped, plan_steps=r.plan.extra.get("steps"),
                plan_s=r.timings.get("plan"), execute_s=r.timings.get("execute"), total_s=r.timings.get("total"),
                timings={k: round(v, 5) for k, v in r.timings.items()},
            )
            self._confusion(row, mover, anchor, size, more,
                            outlines_of([scene.get(o) for o in (task.mover, task.anchor, *task.more_anchors)]))
            kept = keep_always or (task.keep == "failed" and not r.success)
        except BaseException:
            kept = task.keep in ("failed", "all") or task.render
            raise
        finally:
            if out.exists() and not kept:
                shutil.rmtree(out, ignore_errors=True)
            elif out.exists():
                row["run_dir"] = str(out)

    def _plan(self, task: Task, row: dict) -> None:
        scene = Scene.from_dict(task.scene, source=task.scene_id)
        p = prepare(task.sentence, scene, task.options(), plugins=self.plugins)  # refused up front, as by plan
        t = time.perf_counter()
        plan, v = judged_plan(p, time_limit=task.time_limit)
        plan_s = time.perf_counter() - t
        row.update(planner_used=plan.planner, success=int(bool(v["success"])), score=v.get("score"),
                   reason=v.get("reason"), judge=v.get("judge"), final_progress=plan.extra.get("final_progress"),
                   planned_progress=plan.extra.get("final_progress"), stopped=plan.stopped,
                   plan_steps=plan.extra.get("steps"), plan_s=plan_s, total_s=plan_s,
                   timings={"plan": round(plan_s, 5), "total": round(plan_s, 5)})
        anchor = np.repeat(np.asarray(plan.anchor_pose, float)[None], len(plan.path), axis=0)
        more = [np.repeat(np.asarray(q, float)[None], len(plan.path), axis=0)
                for q in ([] if plan.more_anchor_poses is None else plan.more_anchor_poses)]
        self._confusion(row, np.asarray(plan.path, float), anchor, plan.size, more,
                        outlines_of([scene.get(o) for o in (task.mover, task.anchor, *task.more_anchors)]))
        if task.keep == "all" and task.run_dir:
            out = Path(task.run_dir)
            out.mkdir(parents=True, exist_ok=True)
            plan.extra["verdict"] = v
            plan.save(out / "plan.json")
            row["run_dir"] = str(out)

    def _confusion(self, row: dict, mover: np.ndarray, anchor: np.ndarray, size: float,
                   more: list[np.ndarray] | None = None, outlines: list[np.ndarray] | None = None) -> None:
        """Every installed action's verdict and learned progress on this motion; the final gap to the anchor.

        ``more``: the tracks of the run's further reference blocks (a two-anchor run's C). An action
        judges the run when it reads as many reference blocks as the run has, or one (the first anchor):
        "between" cannot judge a one-anchor motion, but every one-anchor action can judge a "between" run.
        ``outlines``: the objects' real footprints where one is not a cube (judge/footprints.py), else None.
        """
        more = more or []
        judged, scored = {}, {}
        for name, (judge, model) in self.judges().items():
            need = getattr(model, "anchors", 1)
            if need != 1 and need != 1 + len(more):
                continue
            extra = more[: need - 1]
            kw = {"more_anchors": extra} if extra else {}
            shapes = None if outlines is None else outlines[: 1 + need]
            if shapes is not None and getattr(model, "reads_outlines", False):
                kw["outlines"] = shapes
            progress = float(model.final(mover, anchor, size, **kw))
            v = judge.judge(mover, anchor, size, final_progress=progress,
                            **judge_context([anchor, *extra], None, judge=judge, outlines=shapes))
            judged[name] = {"success": bool(v.success), "score": round(float(v.score), 6)}
            scored[name] = round(progress, 6)
        rel = np.r_[(mover[-1, :2] - anchor[-1, :2]) / size, mover[-1, 2]]
        row.update(judged=judged, scored=scored,
                   final_gap_blocks=round(footprint_gap(rel, np.array([0.0, 0.0, anchor[-1, 2]]), size, outlines), 6))


_WORKER: Worker | None = None


def run_task(task: Task | dict) -> dict[str, Any]:
    """Run one task in this process's worker (made on first use and kept)."""
    global _WORKER
    if _WORKER is None:
        _WORKER = Worker()
    return _WORKER.run(task if isinstance(task, Task) else Task(**task))
