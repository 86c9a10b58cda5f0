"""What ``perform`` and ``plan`` hand back and write: :class:`PerformResult` and :class:`PlanResult` (their
``to_dict`` is what ``--json`` prints, their ``text`` what the command prints), the verdict's disturbance rule
(:func:`disturbance_verdict`: a run that knocks the anchor or a bystander about is no success) and a performed
run's summary.json (:func:`perform_summary`). The stages that make them are in the package's ``__init__``."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core.contracts import Plan
from ..language import Command

DISTURBED_M = 0.001
"""A block other than the mover that moved more than this (m) during the run makes the verdict a failure."""


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
    displacements_m: dict[str, float] = field(default_factory=dict)  # every block but the mover: how far it moved
    grasp: dict[str, Any] = field(default_factory=dict)  # the grasp's yaw offset and angle (execute.py)
    planned_verdict: dict[str, Any] = field(default_factory=dict)  # the judge on the plan, before the arm moved

    @property
    def success(self) -> bool:
        return bool(self.verdict.get("success"))

    def to_dict(self) -> dict[str, Any]:
        c = self.command
        return {
            "sentence": c.sentence, "verb": c.verb, "mover": c.mover, "preposition": c.preposition,
            "action": c.action, "anchor": c.anchor, "anchors": list(c.anchors), "out_dir": str(self.out_dir),
            "verdict": self.verdict, "final_progress": _round(self.final_progress),
            "planned_progress": _round(self.planned_progress), "planner": self.plan.planner,
            "stopped": self.plan.stopped, "max_deviation_m": _round(self.max_deviation_m),
            "anchor_displacement_m": _round(self.anchor_displacement_m),
            "final_error_m": _round(self.final_error_m),
            "timings": {k: round(v, 4) for k, v in self.timings.items()},
            "files": {k: str(v) for k, v in self.files.items()},
            "displacements_m": {k: _round(v) for k, v in self.displacements_m.items()},
            "disturbed": sorted(k for k, v in self.displacements_m.items() if v > DISTURBED_M),
            "grasp": self.grasp,
            **({} if c.manner == "slide" else {"manner": c.manner}),  # a slide's output names no manner
            **({"manner_why": c.manner_why} if c.manner_why else {}),  # not the verb's own manner: why
            **({} if c.pace is None else {"pace": c.pace}),  # the sentence's "slowly", "gently"
            **({} if c.extent is None else {"extent": c.extent}),  # "far away", "a bit closer"
            # the relation held where the mover stood: nothing moved (planning/already.py)
            **({"already": self.plan.extra["already"]} if "already" in self.plan.extra else {}),
        }

    def text(self) -> list[str]:
        """What ``perform`` prints: the verdict, the numbers that explain it, where the run went."""
        c, v = self.command, self.verdict
        fp = "n/a" if self.final_progress is None else f"{self.final_progress:.2f}"
        video = self.files.get("video")
        how = "" if c.manner == "slide" else f"{c.manner}, "  # the manner it was performed and judged in
        if c.manner_why:  # "move" whose slide the other objects left no way: carried over them
            how = f"{c.manner} over the other objects in the way, "
        return [f'{c.mover} {c.preposition} {" and ".join(c.anchors)}: {how}action "{c.action}", '
                f'{"success" if self.success else "FAILED"} ({v.get("reason", "")})',
                f"final progress {fp} (planned {self.planned_progress:.2f}), "
                f"block within {self.max_deviation_m * 1000:.1f} mm of the plan, "
                f"{moved_text(self.displacements_m, c.anchors)}, {self.timings.get('total', 0):.1f} s",
                f"run folder: {self.out_dir}" + (f"\nvideo: {video}" if video else " (no video: --no-render)")]


def _round(v: float | None) -> float | None:
    return None if v is None else round(float(v), 6)


def moved_text(displacements_m: dict[str, float], anchors: tuple[str, ...] | list[str]) -> str:
    """How far the anchor(s) and, apart, the furthest-moved bystander moved in a run ("anchor moved 0.1 mm,
    bystander C moved 2.0 mm"): each figure named as whose it is, never one object's shift as another's."""
    anchors = [a for a in anchors if a in displacements_m]
    parts = []
    if anchors:
        word = "anchor" if len(anchors) == 1 else "anchors"
        parts.append(f"{word} moved {max(displacements_m[a] for a in anchors) * 1000:.1f} mm")
    others = {k: v for k, v in displacements_m.items() if k not in anchors}
    if others:
        name = max(others, key=others.get)
        parts.append(f"bystander {name} moved {others[name] * 1000:.1f} mm")
    return ", ".join(parts) or "no other object"


def disturbance_verdict(verdict: dict[str, Any], displacements_m: dict[str, float], anchor: str) -> dict[str, Any]:
    """The judge's verdict, failed when the arm moved the anchor or a bystander more than DISTURBED_M: the
    action is not done if the arm knocked its surroundings about (``disturbed_m`` lists who, how far)."""
    moved = {k: round(float(v), 6) for k, v in displacements_m.items() if v > DISTURBED_M}
    if not moved:
        return verdict
    who = ", ".join(f'{"the anchor " if k == anchor else ""}{k} by {v * 1000:.0f} mm'
                    for k, v in sorted(moved.items(), key=lambda kv: -kv[1]))
    return verdict | {"success": False, "disturbed_m": moved,
                      "reason": f"{verdict.get('reason', '')}; but the arm moved {who}".lstrip("; ")}


@dataclass
class PlanResult:
    """What ``plan`` did: the command, the plan (with its verdict in ``plan.extra``) and where it went."""

    command: Command
    plan: Plan
    verdict: dict[str, Any]
    out_dir: Path

    def to_dict(self) -> dict[str, Any]:
        """What ``l2p-bullet plan`` prints."""
        x = self.plan.extra
        return {"out": str(self.out_dir), "action": self.command.action, "planner": self.plan.planner,
                "stopped": self.plan.stopped, "final_progress": x["final_progress"], "steps": x["steps"],
                "seconds": x["seconds"], "success": self.verdict["success"], "reason": self.verdict["reason"]}

    def text(self) -> list[str]:
        """What ``plan`` prints, in ``perform``'s style."""
        d, cmd = self.to_dict(), self.command
        plot = self.out_dir / "plan.png"
        return [f'{cmd.mover} {cmd.preposition} {" and ".join(cmd.anchors)}: action "{cmd.action}", '
                f'{"success" if d["success"] else "FAILED"} on the plan ({d["reason"]})',
                f"final progress {d['final_progress']:.2f}, {d['steps']} steps of the {d['planner']} planner "
                f"(stopped: {d['stopped']}), {d['seconds']:.2f} s",
                f"plan folder: {self.out_dir}" + (f"\nplot: {plot}" if plot.exists() else " (no plot: --no-plot)")]


def perform_summary(summary: dict, r: PerformResult, bundle: Any, seed: int) -> dict:
    """summary.json of a performed run: the execution's summary (``execute.execution_summary``) with
    perform's fields added (contracts only grow)."""
    d = r.to_dict()
    timings = summary.get("timings_s") if isinstance(summary.get("timings_s"), dict) else {}
    files = summary.get("files") if isinstance(summary.get("files"), dict) else {}
    summary.update(
        {
            "schema": summary.get("schema", 1),
            "ok": True,
            "sentence": d["sentence"],
            "command": {
                k: d[k]
                for k in ("verb", "mover", "preposition", "action", "anchor", "anchors", "pace", "extent")
                if k in d
            },
            "verdict": d["verdict"],
            "success": r.success,
            "final_progress": d["final_progress"],
            "planned_progress": d["planned_progress"],
            "planner": d["planner"],
            "stopped": d["stopped"],
            "seed": seed,
            "final_error_m": d["final_error_m"],
            "max_deviation_m": d["max_deviation_m"],
            "anchor_displacement_m": d["anchor_displacement_m"],
            "displacements_m": d["displacements_m"],
            "disturbed": d["disturbed"],
            "grasp": d["grasp"],
            "grasp_angle_deg": r.plan.extra.get("grasp_angle_deg"),
            "plugin": {"name": bundle.name, "version": bundle.version, "path": str(bundle.path)},
            # execute's sub-stages (check, setup, reach, engage, move, disengage, record) and perform's stages
            # "evaluate": the judge stage's older name, still written for readers (contracts only grow)
            "timings_s": {
                **timings,
                **d["timings"],
                **({"evaluate": d["timings"]["judge"]} if "judge" in d["timings"] else {}),
            },
            "files": {**files, "plan": "plan.json"},
        }
    )
    if "already" in d:  # an added field, only where the relation already held (planning/already.py)
        summary["already"] = d["already"]
    return summary
