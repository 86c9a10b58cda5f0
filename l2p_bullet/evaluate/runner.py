"""``evaluate``: build the scene set and the tasks, skip what is recorded, run the rest, commit every row.

Backends: ``workers=0`` runs in this process (debugging, or a caller that wants no processes),
``workers>=1`` a local pool of that many processes (:mod:`.pool`), ``ray=ADDRESS`` Ray actors
(:mod:`.ray_backend`). All three run the same :class:`~l2p_bullet.evaluate.worker.Worker` on the same
tasks, so their rows are equal apart from timings.
"""

from __future__ import annotations

import os
import sys
import time
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

from ..errors import EvaluationError
from ..manners import registry as manner_registry
from ..planning import resolve_planner
from ..plugins import registry
from .pool import run_pool
from .progressbar import ProgressBar
from .ray_backend import run_ray
from .results import ResultsStore, only_writer
from .scenes import SceneSpec, random_scenes, scene_file, study_scenes, with_bystanders
from .tasks import Task, make_tasks, skipped
from .worker import run_task

DEFAULT_SCENES = 10


@dataclass
class EvaluationConfig:
    """What to evaluate (stored in the results table: ``--resume`` runs exactly this again)."""

    actions: list[str] = field(default_factory=list)  # empty: every usable installed action
    scenes: int | None = None  # N seeded random scenes (the default source: DEFAULT_SCENES)
    scene_file: str | None = None  # or a JSON-lines file of scenes
    study: bool = False  # or the original study's start configurations
    bystanders: int = 0
    seed: int = 0
    planner: str = "default"
    mode: str = "perform"  # or "plan"
    render_every: int = 0
    keep: str = "none"
    budget: int | None = None
    threshold: float | None = None
    chains: int = 0  # K > 0: one chain of K clauses per scene of 3-5 blocks (evaluate/chains.py)
    arm: str = "panda"  # the arm that performs every run (l2p-bullet arms)
    manners: list[str] = field(default_factory=lambda: ["slide"])  # every run in each manner (l2p_bullet/manners)

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> EvaluationConfig:
        known = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in d.items() if k in known})

    def scene_set(self) -> list[SceneSpec]:
        sources = [self.scenes is not None, self.scene_file is not None, self.study]
        if sum(sources) > 1:
            raise EvaluationError("choose one scene set: --scenes N, --scene-file F or --study")
        if self.chains:
            if self.scene_file is not None or self.study or self.bystanders:
                raise EvaluationError("--chains draws its own scenes of 3-5 blocks: no --scene-file, --study or "
                                      "--bystanders")
            from .chains import chain_scenes

            return chain_scenes(DEFAULT_SCENES if self.scenes is None else self.scenes, self.seed)
        if self.scene_file is not None:
            specs = scene_file(self.scene_file, self.seed)
        elif self.study:
            specs = study_scenes(seed=self.seed)
        else:
            specs = random_scenes(DEFAULT_SCENES if self.scenes is None else self.scenes, self.seed)
        return with_bystanders(specs, self.bystanders)


@dataclass
class EvaluationSummary:
    """What one call did: tasks in the evaluation, runs skipped as recorded, runs done now, time."""

    out_dir: Path
    total: int
    skipped: int
    ran: int = 0
    failed: int = 0
    errors: int = 0
    seconds: float = 0.0
    backend: str = "pool"
    workers: int = 1
    notes: dict[str, str] = field(default_factory=dict)  # action -> why runs of it were left out

    @property
    def runs_per_s(self) -> float:
        return self.ran / self.seconds if self.seconds > 0 else 0.0


def evaluate(config: EvaluationConfig | None, out_dir: str | Path, *, workers: int | None = None,
             ray: str | None = None, resume: bool = False, retry_errors: bool = False, progressbar: bool = True,
             plugins: list | None = None) -> EvaluationSummary:
    """Run (or continue, ``resume``) the evaluation ``config`` into ``out_dir``; every row committed as it arrives.

    With ``resume`` the stored settings are used (``config`` may be None; if given it must be the
    same); recorded runs are skipped, those that ended in an error too unless ``retry_errors``.
    KeyboardInterrupt stops the workers and propagates; every row already recorded stays.
    """
    out = Path(out_dir)
    if workers is None:  # the cores here; on a Ray cluster, every CPU it has (0)
        workers = 0 if ray and ray != "local" else (os.cpu_count() or 1)
    if workers < 0:
        raise EvaluationError(f"--workers must be 0 or more (got {workers})")
    if config is not None:
        from ..embodiment import arm_plugins

        arm_plugins.get(config.arm)  # an unknown arm is refused before the folder is made
    if not resume and (out / "results.sqlite").exists():
        raise EvaluationError(f"{out} already holds an evaluation: pass --resume to continue it, or choose another --out")
    with only_writer(out), ResultsStore(out) as store:
        stored = store.get_meta("config")
        if not resume and stored is not None:  # another fresh start got here first (we waited for its lock)
            raise EvaluationError(f"{out} already holds an evaluation: pass --resume to continue it, or choose "
                                  "another --out")
        if resume and stored is None:
            raise EvaluationError(f"{out} holds no evaluation to resume (no results.sqlite with settings)")
        if stored is not None:  # settings added since the evaluation was stored have their defaults
            stored = {**EvaluationConfig().to_dict(), **stored}
        if resume:
            if config is not None and config.to_dict() != stored:
                diff = sorted(k for k, v in config.to_dict().items() if stored.get(k) != v)
                raise EvaluationError(f"--resume runs the stored evaluation again, but these settings differ: "
                                      f"{', '.join(diff)} (choose another --out for a new evaluation)")
            config = EvaluationConfig.from_dict(stored)
        config = config or EvaluationConfig()
        plugins = registry.discover() if plugins is None else plugins
        actions = config.actions or [p.name for p in plugins if p.ok]
        if not actions:
            raise EvaluationError("no usable action plugin is installed (see: l2p-bullet actions)")

        resolve_planner(config.planner)  # a typo fails before anything runs
        scenes = config.scene_set()
        notes: dict[str, str] = {}
        if config.chains:
            from .chains import make_chain_tasks

            if config.mode == "plan":
                raise EvaluationError("--chains performs its chains: no --plan-only")
            tasks = make_chain_tasks(scenes, config.chains, actions, planner=config.planner,
                                     render_every=config.render_every, keep=config.keep, out_dir=str(out),
                                     plugins=plugins, budget=config.budget, threshold=config.threshold,
                                     arm=config.arm)
        else:
            notes = skipped(scenes, actions, plugins)
            tasks = make_tasks(scenes, actions, planner=config.planner, mode=config.mode,
                               render_every=config.render_every, keep=config.keep, out_dir=str(out), plugins=plugins,
                               budget=config.budget, threshold=config.threshold, arm=config.arm,
                               manners=manner_registry.check_names(list(config.manners or ["slide"])))
            if not tasks and notes:
                raise EvaluationError("nothing to run: " + "; ".join(notes.values()))
        if progressbar:
            for note in notes.values():
                sys.stderr.write(f"note: {note}\n")
        if not resume:
            store.set_meta("config", config.to_dict())
        store.set_meta("tasks_total", len(tasks))
        done = store.recorded(with_errors=not retry_errors)
        todo = [t for t in tasks if t.run_id not in done]
        backend = "ray" if ray else ("pool" if workers >= 1 else "inline")
        summary = EvaluationSummary(out, len(tasks), len(tasks) - len(todo), backend=backend, workers=workers,
                                    notes=notes)
        bar = ProgressBar(len(todo), summary.skipped, enabled=progressbar)

        def on_row(row: dict) -> None:
            store.add(row)
            bar.update(row)
            summary.ran += 1
            summary.errors += row.get("error") is not None
            summary.failed += row.get("error") is None and not row.get("success")

        t0 = time.perf_counter()
        try:
            run_tasks(todo, workers=workers, ray=ray, on_row=on_row)
        finally:
            summary.seconds = time.perf_counter() - t0
            bar.close()
    return summary


def run_tasks(tasks: list[Task], *, workers: int, ray: str | None, on_row) -> None:
    """Dispatch ``tasks`` to the chosen backend (see the module docstring)."""
    if ray:
        run_ray(tasks, ray, workers, on_row)
    elif workers >= 1:
        run_pool(tasks, workers, on_row)
    else:
        for t in tasks:
            on_row(run_task(t))


def load_rows(out_dir: str | Path) -> list[dict]:
    """Every recorded row of the evaluation in ``out_dir`` (EvaluationError if there is none)."""
    out = Path(out_dir)
    if not (out / "results.sqlite").exists():
        raise EvaluationError(f"{out} holds no evaluation (no results.sqlite)")
    with ResultsStore(out) as store:
        return store.rows()
