"""``perform``: a sentence in, a recorded robot action out. The stages of DESIGN.md, in order.

    parse      sentence -> Command, against the phrases of the installed plugins (registry, language)
    load       the one plugin the command needs -> Bundle, and its progress model (scored in numpy:
               perform never imports torch, see progress_numpy.py)
    plan       planners.plan -> Plan (2-D path of the mover), saved as plan.json
    execute    execute.execute_path: the arm performs the path in PyBullet; trajectory.json gets the
               progress model's value per frame, so a run can be read without the model
    evaluate   the project's rule-based judge on the *executed* trajectory (what the simulator did,
               not what was planned): a plan that the arm cannot follow must not count as success

Each stage is timed; the timings, the verdict and the final progress are merged into summary.json.
The cheap checks (sentence, plugin, run folder) run before the expensive ones so that a typo costs
milliseconds, not a planning run.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .core.scene import Scene
from .errors import L2PError, PluginError
from .language import Command, parse

StageFn = Callable[[str], None]


@dataclass
class PerformResult:
    """What one ``perform`` did; ``to_dict`` is what ``perform --json`` prints."""

    command: Command
    out_dir: Path
    plan: Any  # paths.Plan
    verdict: dict[str, Any]  # {"success", "score", "reason", "judge"}
    final_progress: float | None  # the progress model on the executed trajectory's last frame
    planned_progress: float  # the progress model at the plan's end
    max_deviation_m: float  # block vs planned path during execution
    anchor_displacement_m: float
    final_error_m: float  # mover's final position vs the plan's goal
    timings: dict[str, float]
    files: dict[str, Path] = field(default_factory=dict)

    @property
    def success(self) -> bool:
        return bool(self.verdict.get("success"))

    def to_dict(self) -> dict[str, Any]:
        c = self.command
        return {
            "sentence": c.sentence, "verb": c.verb, "mover": c.mover, "preposition": c.preposition,
            "action": c.action, "anchor": c.anchor, "out_dir": str(self.out_dir),
            "verdict": self.verdict, "final_progress": _round(self.final_progress),
            "planned_progress": _round(self.planned_progress), "planner": self.plan.planner,
            "stopped": self.plan.stopped, "max_deviation_m": _round(self.max_deviation_m),
            "anchor_displacement_m": _round(self.anchor_displacement_m),
            "final_error_m": _round(self.final_error_m),
            "timings": {k: round(v, 4) for k, v in self.timings.items()},
            "files": {k: str(v) for k, v in self.files.items()},
        }


def _round(v: float | None) -> float | None:
    return None if v is None else round(float(v), 6)


class _Clock:
    """Times the stages and tells the caller when each starts (for progress on stderr)."""

    def __init__(self, on_stage: StageFn | None):
        self.on_stage = on_stage
        self.timings: dict[str, float] = {}
        self.stage = ""
        self.t0 = time.perf_counter()

    def start(self, stage: str, message: str | None = None) -> float:
        self.stage = stage
        if self.on_stage is not None and message:
            self.on_stage(message)
        return time.perf_counter()

    def stop(self, stage: str, t: float) -> None:
        self.timings[stage] = self.timings.get(stage, 0.0) + time.perf_counter() - t


class _ModelOnce:
    """A bundle whose progress model is built once per process and weights digest.

    The planner and the recorder both need the model; building it twice would read and check the
    weights twice, and a benchmark performing many sentences would rebuild it every time. With
    ``inference="numpy"`` (the default) the model is :class:`NumpyProgressModel`, the same network
    evaluated without torch: importing torch alone would take half of perform's time budget.
    """

    _cache: dict[tuple[str, str, str], Any] = {}

    def __init__(self, bundle: Any, inference: str = "numpy"):
        if inference not in ("numpy", "torch"):
            raise ValueError(f"inference must be numpy or torch, not {inference!r}")
        self._bundle, self._inference = bundle, inference

    def __getattr__(self, name: str) -> Any:
        return getattr(self._bundle, name)

    def progress_model(self) -> Any:
        weights = self._bundle.manifest.get("weights", {}).get("progress.safetensors", {})
        key = (str(self._bundle.path), str(weights.get("sha256", "")), self._inference)
        if key not in self._cache:
            if self._inference == "numpy" and self._bundle.manifest.get("model", {}).get("arch", "lstm") == "lstm":
                from .progress.model import NumpyProgressModel

                self._cache[key] = NumpyProgressModel.from_bundle(self._bundle)
            else:
                self._cache[key] = self._bundle.progress_model()
        return self._cache[key]


def resolve(sentence: str, scene: Scene, plugins: list | None = None) -> Command:
    """Parse ``sentence`` against the installed plugins' phrases (no plugin is imported)."""
    from .plugins import registry

    plugins = registry.discover() if plugins is None else plugins
    table = registry.phrase_table(plugins)
    if not table and plugins:
        bad = registry.broken(plugins)
        raise PluginError(f"none of the {len(plugins)} installed action plugins can be used (first: "
                          f"{bad[0].label()}: {bad[0].error}); see: l2p-bullet actions")
    return parse(sentence, scene, table)


def trajectory_motion(frames: list[dict], mover: str, anchor: str) -> tuple[np.ndarray, np.ndarray]:
    """(T,3) ``[x, y, yaw]`` of mover and anchor from trajectory.json frames."""
    m = np.array([[f["poses"][mover][0], f["poses"][mover][1], f["poses"][mover][3]] for f in frames], float)
    a = np.array([[f["poses"][anchor][0], f["poses"][anchor][1], f["poses"][anchor][3]] for f in frames], float)
    return m, a


def judge(action: str, mover: np.ndarray, anchor: np.ndarray, size: float,
          final_progress: float | None, threshold: float = 0.5) -> dict[str, Any]:
    """The verdict: the rule-based evaluator for the built-in actions.

    A plugin action has no rules in this project, so its only judge is its own progress model; the
    verdict says so ("judge": "progress-model") rather than pretending to be independent.
    """
    from .learning.demos import ACTIONS

    if action in ACTIONS:
        from .judge.rules import evaluate

        v = evaluate(action, mover, anchor, size)
        return {"success": bool(v.success), "score": round(float(v.score), 4), "reason": v.reason, "judge": "rules"}
    fp = 0.0 if final_progress is None else float(final_progress)
    return {"success": fp >= threshold, "score": round(fp, 4), "judge": "progress-model",
            "reason": f"no rule-based judge for the plugin action {action}; its own progress model gives "
                      f"{fp:.2f} at the end (success at {threshold:.2f} or more)"}


def perform(sentence: str, scene: Scene, *, out_dir: str | Path | None = None, planner: str = "default",
            seed: int = 0, render: bool = True, force: bool = False, budget: int | None = None,
            threshold: float | None = None, on_stage: StageFn | None = None,
            plugins: list | None = None, render_settings: Any = None, inference: str = "numpy") -> PerformResult:
    """Parse, plan, execute, record and judge ``sentence`` in ``scene``; write the run folder.

    Raises an :class:`L2PError` subclass for anything a user can get wrong (sentence, plugin, run
    folder, unreachable plan); the run folder, once created, gets a summary.json naming the stage that
    failed, so a failed run is still explained on disk.
    """
    from .core.runfolder import prepare_run_folder
    from .plugins import registry

    clock = _Clock(on_stage)
    t = clock.start("parse")
    scene.validate()
    plugins = registry.discover() if plugins is None else plugins
    cmd = resolve(sentence, scene, plugins)
    clock.stop("parse", t)

    out = prepare_run_folder(out_dir, force=force, prefix="perform")
    try:
        t = clock.start("load", f'loading the plugin "{cmd.action}" and its progress model')
        bundle = _ModelOnce(registry.load(cmd.action, plugins), inference)
        model = bundle.progress_model()
        clock.stop("load", t)
        return _run(cmd, scene, bundle, model, out, clock, planner=planner, seed=seed, render=render,
                    budget=budget, threshold=threshold, render_settings=render_settings)
    except L2PError as e:
        _write_json(out / "summary.json", {
            "schema": 1, "sentence": cmd.sentence, "action": cmd.action, "ok": False,
            "failed_stage": clock.stage, "error": str(e), "timings_s": clock.timings,
        })
        raise


def _run(cmd: Command, scene: Scene, bundle: Any, model: Any, out: Path, clock: _Clock, *, planner: str,
         seed: int, render: bool, budget: int | None, threshold: float | None, render_settings: Any) -> PerformResult:
    from . import planning
    from .embodiment import execute

    size = scene.get(cmd.mover).size
    t = clock.start("plan", f"planning with the {planner} planner")
    plan = planning.plan(scene, cmd.mover, cmd.anchor, bundle, planner=planner, seed=seed, budget=budget,
                         threshold=threshold)
    clock.stop("plan", t)
    plan.extra.setdefault("sentence", cmd.sentence)
    plan.save(out / "plan.json")

    def progress_fn(mover: np.ndarray, anchor: np.ndarray) -> np.ndarray:
        return np.asarray(model.curve(mover, anchor, size), float).reshape(-1)

    meta = {"sentence": cmd.sentence, "action": cmd.action, "anchor": cmd.anchor, "mover": cmd.mover}
    t = clock.start("execute", "executing with the arm" + ("" if render else " (no rendering)"))
    kwargs: dict[str, Any] = {"render": None}
    if render:
        kwargs = {} if render_settings is None else {"render": render_settings}
    stage_cb = (lambda s: clock.on_stage(f"  execute: {s}")) if clock.on_stage else None
    ex = execute.execute_path(scene, cmd.mover, plan.path, out_dir=out, seed=seed, progress_fn=progress_fn,
                              meta=meta, on_stage=stage_cb, **kwargs)
    clock.stop("execute", t)

    t = clock.start("evaluate")
    mover, anchor = trajectory_motion(ex.frames, cmd.mover, cmd.anchor)
    prog = [f.get("progress") for f in ex.frames]
    final_progress = float(prog[-1]) if prog and prog[-1] is not None else None
    verdict = judge(cmd.action, mover, anchor, size, final_progress)
    final_error = float(np.hypot(*(mover[-1, :2] - plan.path[-1, :2])))
    clock.stop("evaluate", t)
    clock.timings["total"] = time.perf_counter() - clock.t0

    result = PerformResult(
        command=cmd, out_dir=out, plan=plan, verdict=verdict, final_progress=final_progress,
        planned_progress=float(plan.progress[-1]) if len(plan.progress) else float("nan"),
        max_deviation_m=float(ex.max_deviation_m), anchor_displacement_m=float(ex.anchor_displacement_m),
        final_error_m=final_error, timings=dict(clock.timings),
        files={"plan": out / "plan.json", **{k: Path(v) for k, v in ex.files.items()}},
    )
    _merge_summary(out / "summary.json", result, bundle, ex, seed)
    return result


def _merge_summary(path: Path, r: PerformResult, bundle: Any, ex: Any, seed: int) -> None:
    """Add perform's fields to the summary.json the recorder wrote (contracts only grow)."""
    try:
        summary = json.loads(path.read_text()) if path.exists() else {}
    except (OSError, json.JSONDecodeError):
        summary = {}
    d = r.to_dict()
    timings = summary.get("timings_s") if isinstance(summary.get("timings_s"), dict) else {}
    files = summary.get("files") if isinstance(summary.get("files"), dict) else {}
    summary.update({
        "schema": summary.get("schema", 1), "ok": True, "sentence": d["sentence"],
        "command": {k: d[k] for k in ("verb", "mover", "preposition", "action", "anchor")},
        "verdict": d["verdict"], "success": r.success, "final_progress": d["final_progress"],
        "planned_progress": d["planned_progress"], "planner": d["planner"], "stopped": d["stopped"],
        "seed": seed, "final_error_m": d["final_error_m"],
        "max_deviation_m": d["max_deviation_m"], "anchor_displacement_m": d["anchor_displacement_m"],
        "plugin": {"name": bundle.name, "version": bundle.version, "path": str(bundle.path)},
        # execute's sub-stages (check, setup, reach, engage, move, disengage, record) and perform's stages
        "timings_s": {**timings, **d["timings"]},
        "files": {**files, "plan": "plan.json"},
    })
    _write_json(path, summary)


def _write_json(path: Path, data: dict) -> None:
    path.write_text(json.dumps(data, indent=1, default=_json_default) + "\n")


def _json_default(o: object) -> object:
    if isinstance(o, Path):
        return str(o)
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")
