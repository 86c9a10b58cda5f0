"""``evaluate``: build the scene set and the tasks, skip what is recorded, run the rest, commit every row.

Backends: ``workers=0`` runs in this process (debugging, or a caller that wants no processes),
``workers>=1`` a local pool of that many processes (:mod:`.pool`), ``ray=ADDRESS`` Ray actors
(:mod:`.ray_backend`). All three run the same :class:`~l2p_bullet.evaluate.worker.Worker` on the same
tasks, so their rows are equal apart from timings.
"""

from __future__ import annotations

import numbers
import os
import sys
import time
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

from ..errors import EvaluationError, PlanError
from ..manners import registry as manner_registry
from ..options import check_options
from ..planning import resolve_planner
from ..plugins import registry
from .folder import check_out_folder
from .pool import run_pool
from .progressbar import ProgressBar
from .ray_backend import run_ray
from .results import ResultsStore, only_writer
from .scenes import (
    BYSTANDER_COLORS,
    MAX_SEED,
    SceneSpec,
    random_scenes,
    scene_file,
    study_scenes,
    with_bystanders,
)
from .tasks import KEEP, MODES, Task, make_tasks, skipped
from .worker import run_task

DEFAULT_SCENES = 10
MAX_WORKERS = 256
"""The most local worker processes (``--workers``): each holds its own PyBullet worlds and bundles, so far
more than the cores only costs memory. A Ray cluster's actors (``--ray ADDRESS``) are not limited here."""


@dataclass
class EvaluationConfig:
    """What to evaluate (stored in the results table: ``--resume`` runs exactly this again)."""

    actions: list[str] = field(default_factory=list)  # empty: the usable built-in actions (_tasks)
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
    chain_draw: str = "clause"  # how a chain is drawn: "clause" or "sentence" (evaluate/chains.py, DRAWS)
    arm: str = "panda"  # the arm that performs every run (l2p-bullet arms)
    manners: list[str] = field(default_factory=lambda: ["slide"])  # every run in each manner (l2p_bullet/manners)

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> EvaluationConfig:
        known = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in d.items() if k in known})

    def check(self) -> EvaluationConfig:
        """Refuse a setting out of range (one-line errors) before any folder is made: a typo must cost nothing."""
        for name, value in (("actions", self.actions), ("manners", self.manners)):
            if not isinstance(value, list) or not all(isinstance(v, str) and v.strip() for v in value):
                raise EvaluationError(f"--{name} must be a comma-separated list of names (got {value!r})")
        for name in ("scenes", "bystanders", "seed", "render_every", "budget", "chains"):
            value = getattr(self, name)
            if value is not None and (not isinstance(value, numbers.Integral) or isinstance(value, bool)):
                raise EvaluationError(f"--{name.replace('_', '-')} must be a whole number (got {str(value)[:20]!r})")
        if self.scenes is not None and self.scenes < 0:
            raise EvaluationError(f"--scenes must be 0 or more (got {self.scenes})")
        try:  # the same checks perform and plan make up front (an error row per task before)
            check_options(self.planner, self.seed, self.budget, self.threshold)
        except PlanError as e:
            raise EvaluationError(str(e)) from None
        if not 0 <= self.bystanders <= len(BYSTANDER_COLORS):
            raise EvaluationError(f"--bystanders must be 0 to {len(BYSTANDER_COLORS)} (got {self.bystanders})")
        last = self.seed + (DEFAULT_SCENES if self.scenes is None else max(self.scenes, 1)) - 1
        if not 0 <= self.seed <= MAX_SEED or (self.scene_file is None and not self.study and last > MAX_SEED):
            raise EvaluationError(f"--seed must be 0 to {MAX_SEED}, and so must the last scene's seed "
                                  f"(--seed + --scenes - 1; got --seed {self.seed})")
        if self.render_every < 0:
            raise EvaluationError(f"--render-every must be 0 (none) or more (got {self.render_every})")
        if self.mode not in MODES:
            raise EvaluationError(f'unknown mode "{self.mode}" (known: {", ".join(MODES)})')
        if self.keep not in KEEP:
            raise EvaluationError(f'unknown --keep "{self.keep}" (known: {", ".join(KEEP)})')
        if self.chains:
            check_chains(self.chains)
        from .chains import DRAWS

        if self.chain_draw not in DRAWS:
            raise EvaluationError(f'unknown --chain-draw "{self.chain_draw}" (known: {", ".join(DRAWS)})')
        return self

    def scene_set(self) -> list[SceneSpec]:
        sources = [self.scenes is not None, self.scene_file is not None, self.study]
        if sum(sources) > 1:
            raise EvaluationError("choose one scene set: --scenes N, --scene-file F or --study")
        if self.chains:
            if self.scene_file is not None or self.study:
                raise EvaluationError("--chains draws its own scenes of 3-5 blocks (--bystanders K: 2 + K blocks "
                                      "each): no --scene-file or --study")
            from .chains import chain_scenes

            return chain_scenes(DEFAULT_SCENES if self.scenes is None else self.scenes, self.seed,
                                blocks=2 + self.bystanders if self.bystanders else None)
        if self.scene_file is not None:
            specs = scene_file(self.scene_file, self.seed)
        elif self.study:
            specs = study_scenes(seed=self.seed)
        else:
            specs = random_scenes(DEFAULT_SCENES if self.scenes is None else self.scenes, self.seed)
        bad = next((s for s in specs if not 0 <= s.seed <= MAX_SEED), None)
        if bad is not None:  # a scene file's line numbers from --seed on, or the study's 75 starts
            raise EvaluationError(f"scene {bad.id} would plan with seed {bad.seed}: seeds are 0 to {MAX_SEED} "
                                  "(choose a smaller --seed)")
        return with_bystanders(specs, self.bystanders)


def check_chains(k: int) -> None:
    """``--chains K``: 1 to MAX_CHAIN clauses (0 is no option: leave --chains out for single runs)."""
    from .chains import MAX_CHAIN

    if not 1 <= k <= MAX_CHAIN:
        raise EvaluationError(f"--chains must be 1 to {MAX_CHAIN} clauses (got {k})")


def check_workers(workers: int | None, ray: str | None) -> int:
    """The number of workers to start (None: the cores here; on a Ray cluster, every CPU it has: 0)."""
    if workers is None:
        return 0 if ray and ray != "local" else (os.cpu_count() or 1)
    if workers < 0:
        raise EvaluationError(f"--workers must be 0 or more (got {workers})")
    if workers > MAX_WORKERS and not (ray and ray != "local"):
        raise EvaluationError(f"--workers must be at most {MAX_WORKERS} on this machine (got {workers}); "
                              "each worker holds its own simulator")
    return workers


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
    if config is not None and not isinstance(config, EvaluationConfig):
        raise EvaluationError(f"the settings must be an EvaluationConfig (got {type(config).__name__}); from a "
                              "dict: EvaluationConfig.from_dict(d)")
    workers = check_workers(workers, ray)
    if config is not None:
        config.check()
        from ..plugins import arms as arm_plugins

        arm_plugins.get(config.arm)  # an unknown arm is refused before the folder is made
    # Everything that can fail on the settings fails here, before the folder or its table is made
    # (a failed start must not leave a folder that neither a new start nor --resume accepts).
    stored = check_out_folder(out, resume=resume)
    if resume:
        config = _resumed(config, stored)
    config = (config or EvaluationConfig()).check()
    plugins = registry.discover() if plugins is None else plugins
    tasks, notes = _tasks(config, out, plugins)
    with only_writer(out), ResultsStore(out) as store:
        now = store.get_meta("config")
        if not resume and now is not None:  # another fresh start got here first (we waited for its lock)
            raise EvaluationError(f"{out} already holds an evaluation: pass --resume to continue it, or choose "
                                  "another --out")
        if resume and now != stored:
            raise EvaluationError(f"the evaluation in {out} changed while this --resume started; run it again")
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
        bar.advance(0)  # a first "0/N runs" line at once: the first run (workers starting, rendering) takes seconds

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


def _resumed(config: EvaluationConfig | None, stored: dict | None) -> EvaluationConfig:
    """The stored settings (those added since it was stored at their defaults); ``config``, if given, must match."""
    stored = {**EvaluationConfig().to_dict(), **(stored or {})}
    if config is not None and config.to_dict() != stored:
        diff = sorted(k for k, v in config.to_dict().items() if stored.get(k) != v)
        raise EvaluationError(f"--resume runs the stored evaluation again, but these settings differ: "
                              f"{', '.join(diff)} (choose another --out for a new evaluation)")
    return EvaluationConfig.from_dict(stored)


BUILTIN_PACKAGE = "l2p-bullet"
"""The distribution of the built-in actions: what ``evaluate`` runs unless ``--actions`` says otherwise."""


def _tasks(config: EvaluationConfig, out: Path, plugins: list) -> tuple[list[Task], dict[str, str]]:
    """The evaluation's tasks, and why runs of some actions are left out (action -> note)."""
    # the built-in actions by default, whatever else is installed: the published tables stay reproducible
    # without --actions, and an installed plugin is named (it is evaluated when --actions names it)
    actions = config.actions or [p.name for p in plugins if p.ok and p.package == BUILTIN_PACKAGE]
    extras = [] if config.actions else [p.name for p in plugins if p.ok and p.package != BUILTIN_PACKAGE]
    if not actions:
        actions, extras = extras, []  # no built-in action is usable here: the installed ones, as before
    if not actions:
        raise EvaluationError("no usable action plugin is installed (see: l2p-bullet actions)")
    extra_notes = {name: f'the installed action "{name}" is not in the default set (the built-in actions); '
                         f"evaluate it with --actions {','.join(actions + extras)}" for name in extras}
    resolve_planner(config.planner)  # a typo fails before anything runs
    scenes = config.scene_set()
    if config.chains:
        from .chains import make_chain_tasks

        if config.mode == "plan":
            raise EvaluationError("--chains performs its chains: no --plan-only")
        return make_chain_tasks(scenes, config.chains, actions, planner=config.planner,
                                render_every=config.render_every, keep=config.keep, out_dir=str(out),
                                plugins=plugins, budget=config.budget, threshold=config.threshold,
                                arm=config.arm, draw=config.chain_draw), extra_notes
    notes = extra_notes | skipped(scenes, actions, plugins)
    tasks = make_tasks(scenes, actions, planner=config.planner, mode=config.mode,
                       render_every=config.render_every, keep=config.keep, out_dir=str(out), plugins=plugins,
                       budget=config.budget, threshold=config.threshold, arm=config.arm,
                       manners=manner_registry.check_names(list(config.manners or ["slide"])))
    if not tasks and notes:
        raise EvaluationError("nothing to run: " + "; ".join(notes.values()))
    return tasks, notes


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
