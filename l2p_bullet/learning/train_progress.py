"""Train one action's progress ensemble, deterministically for a seed, on a couple of CPU cores.

Each ensemble member is a small LSTM trained with Adam on a per-frame, per-sequence-averaged squared
error plus an extra term on the frame where the event ends (the planner reads the final value). The
members differ only in their seed; averaging them is cheaper than tuning one model to be stable.
The held-out tests (split by capture session) live in ``research/heldout.py``.
The optimisation loop itself (a member, a fine-tuning) is in ``optimise.py``; ``train_net`` and ``fine_tune`` are
re-exported here.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..actions.spec import ActionSpec
from ..core.frames import Frame, declaration
from ..core.vocabulary import ACTIONS
from ..data.demos import UNTRUSTED, Demo, expand_files, load_demos
from ..errors import BundleError, DataError, L2PError, PluginError, UnknownActionError
from ..judge import RuleJudge
from ..plugins.bundle import MANIFEST, check_bundle_target, read_manifest, write_progress_bundle
from ..plugins.registry import action_spec, locate
from ..progress.config import ModelConfig
from ..progress.features import QSRConfig
from .augment import viewer_sides
from .feedback import FeedbackItem, load_feedback
from .feedback_targets import FeedbackConfig, feedback_sequences, judge_items, weigh
from .optimise import fine_tune, train_net
from .progress_net import ProgressModel, ProgressNet, ensemble_arrays
from .training_plan import SHIPPED, ProgressTrainConfig, TrainingPlan, extend, own_trusted, shipped_extension
from .trainset import DataConfig, TrainingSequence, build


@dataclass
class TrainResult:
    model: ProgressModel
    seconds: float
    n_sequences: int
    n_positive: int
    final_loss: float
    data_digest: str
    history: list[float] = field(default_factory=list)
    n_feedback: int = 0
    """Feedback sequences fine-tuned on (graded motions and their mirror images, blind negatives)."""


def data_digest(demos: dict[str, list[Demo]]) -> str:
    """sha256 over the demonstrations actually used (ids and poses), for the manifest."""
    h = hashlib.sha256()
    for action in sorted(demos):
        for d in demos[action]:
            h.update(d.id.encode())
            h.update(np.ascontiguousarray(d.mover, np.float64).tobytes())
            h.update(np.ascontiguousarray(d.anchor, np.float64).tobytes())
    return h.hexdigest()


def all_demos(files: dict[str, list] | None = None, sessions: set[str] | None = None,
              untrusted: bool = True) -> dict[str, list[Demo]]:
    """Every action's demonstrations (optionally only some capture sessions). ``untrusted`` False leaves out
    the shipped ones whose tracking is not trusted (:data:`data.demos.UNTRUSTED`): the grade-free suite never
    scores them; the shipped bundles are trained with them (leaving them out failed the planning check,
    docs/learning.md, "around's far corner"). A user's own files are taken as they are."""
    out = {}
    for a in ACTIONS:
        given = (files or {}).get(a)
        ds = load_demos(a, given)
        out[a] = [
            d
            for d in ds
            if (sessions is None or d.session in sessions) and (given or untrusted or d.id not in UNTRUSTED)
        ]
    return out


def train_action(action: str, demos: dict[str, list[Demo]], *, seed: int = 0,
                 qsr_cfg: QSRConfig | None = None, data_cfg: DataConfig | None = None,
                 cfg: ProgressTrainConfig | None = None, tick: Callable[[], None] | None = None,
                 feedback: Sequence[FeedbackItem] = (), feedback_cfg: FeedbackConfig | None = None,
                 base: Sequence[ProgressNet] | None = None,
                 on_stage: Callable[[str], None] | None = None,
                 extend: Callable[[list[TrainingSequence]], list[TrainingSequence]] | None = None) -> TrainResult:
    """Build the training set and train the ensemble; ``tick`` is called once per member-epoch,
    ``on_stage`` with a line when the (validated) set starts being built and when it is built (the
    command prints them; its progress bar's clock starts at the second).

    With ``feedback`` (graded motions of any action; those of ``action`` are used), the ensemble trained
    on the demonstrations is then fine-tuned on them (:func:`fine_tune`, ``feedback_cfg``). ``base``
    skips the training on the demonstrations and fine-tunes these nets instead (cross-validation and
    ``improve`` reuse one such ensemble for many fine-tunings). ``extend`` adds to the built training set
    (a plan of :mod:`l2p_bullet.learning.training_plan`; the shipped set is unchanged before it).
    """
    qsr_cfg, data_cfg, cfg = qsr_cfg or QSRConfig(), data_cfg or DataConfig(), cfg or ProgressTrainConfig()
    if not demos.get(action):
        raise DataError(f'no demonstrations of "{action}" to learn from: the session files hold no events '
                        "(event_start_end is empty)")
    fcfg = feedback_cfg or FeedbackConfig()
    t0 = time.perf_counter()
    if on_stage:
        on_stage("building the training set")
    seqs = build(action, demos, qsr_cfg, data_cfg, seed=seed)
    if extend is not None:
        seqs = extend(seqs)
    if on_stage:
        on_stage(f"{len(seqs)} sequences")
    nets, last = list(base or []), []
    for i in range(0 if base else cfg.ensemble):
        net, hist = train_net(seqs, qsr_cfg.n_features, cfg, seed * 1000 + i, tick)
        nets.append(net)
        last.append(hist[-1])
    fb = feedback_sequences(action, feedback, qsr_cfg, data_cfg, fcfg)
    if fb:
        weigh(seqs, fb, fcfg.weight)
        nets = fine_tune(nets, seqs, fb, fcfg, cfg, seed=seed, tick=tick)
    mcfg = ModelConfig(n_features=qsr_cfg.n_features, hidden=cfg.hidden, ensemble=len(nets), levels=cfg.levels)
    return TrainResult(
        model=ProgressModel.from_nets(nets, mcfg, qsr_cfg),
        seconds=time.perf_counter() - t0,
        n_sequences=len(seqs),
        n_positive=sum(s.positive for s in seqs),
        final_loss=float(np.mean(last)) if last else float("nan"),
        data_digest=data_digest(demos),
        history=last,
        n_feedback=len(fb),
    )


def training_section(result: TrainResult, cfg: ProgressTrainConfig, seed: int, command: str,
                     data_cfg: DataConfig | None = None, own: list[Demo] | None = None,
                     qsr_cfg: QSRConfig | None = None) -> dict:
    """The manifest's ``[training]``: how to reproduce the weights and what data went in (for a
    viewer-frame action also on which sides its demonstrations end, which decides its negatives)."""
    section = {"command": command, "seed": seed, "data_digest": result.data_digest,
               "n_sequences": result.n_sequences, "n_positive": result.n_positive,
               "seconds": round(result.seconds, 1), **cfg.to_dict(), "data": (data_cfg or DataConfig()).to_dict()}
    if qsr_cfg is not None and qsr_cfg.viewer and own:
        lateral, depth = viewer_sides(own)
        section["viewer_sides"] = {"lateral": lateral, "depth": depth}
    return section


def declared(name: str, folder: Path | None) -> tuple[Frame, int]:
    """The frame and number of anchors a plugin action declares: in the manifest in ``folder`` (the one
    being trained), else in the installed plugin's; the defaults without either."""

    if folder is None or not (folder / MANIFEST).is_file():
        try:
            folder = locate(name)[1]
        except L2PError:
            return Frame(), 1
    try:
        return declaration(read_manifest(folder))
    except BundleError as e:
        raise BundleError(f"{folder / MANIFEST}: {e}") from None


def declared_spec(name: str) -> ActionSpec | None:
    """What the plugin action ``name`` declares about itself (its module's ``ACTION``), when it is installed
    and declares one: its training options shape its training set (``DataConfig.with_action``)."""
    try:
        return action_spec(name)
    except UnknownActionError:  # a plugin still being authored, not installed yet
        return None


def training_target(action: str, out: Path | None, demo_files: Sequence[str]) -> tuple[str, bool]:
    """(action name, is it a plugin action still being authored) for ``l2p-bullet train ACTION``.

    An installed action (built-in or plugin) or a bundle folder resolves as everywhere else. A plugin
    action (``l2p-bullet new-action``) is trained before its package is installed, so it is recognised
    by the manifest the scaffold put in ``out``, which must name it, and it needs the author's demos.
    """

    try:
        name = locate(action)[0]
    except (BundleError, PluginError):
        if out is None or not (out / MANIFEST).is_file() or str(read_manifest(out).get("name", "")) != action:
            raise
        name = action
    manifest = read_manifest(out) if out is not None and (out / MANIFEST).is_file() else {}
    if manifest.get("kind") == "composite":
        # a composite's bundle holds a recipe learned from whole rows, never a progress model: training one
        # into it left a plugin that `actions` listed as usable and whose every sentence was refused
        project = out.parent if (out.parent / "pyproject.toml").is_file() else "<its project folder>"
        raise BundleError(f'{out} holds the composite action "{name}", which is not trained on demonstration '
                          f"files: record rows and learn its recipe with l2p-bullet teach {name} --plugin {project}")
    plugin = name not in ACTIONS
    if plugin and not demo_files:
        raise BundleError(f'the plugin action "{name}" has no shipped demonstrations: give yours with '
                          "--demos FILE (capture-session .npz, see the plugin's README)")
    return name, plugin


def train_bundle(action: str, out: Path | None, *, demo_files: Sequence[str] = (), seed: int = 0,
                 cfg: ProgressTrainConfig | None = None, force: bool = False,
                 tick: Callable[[], None] | None = None, feedback: Sequence[str] = (),
                 feedback_judge: str | None = None, judge_scenes: int = 30,
                 feedback_cfg: FeedbackConfig | None = None,
                 log: Callable[[str], None] | None = None,
                 on_stage: Callable[[str], None] | None = None) -> tuple[Path, TrainResult]:
    """``l2p-bullet train``: train ``action``'s progress ensemble and write it into a bundle folder.

    The default folder is ``runs/bundles/<action>``. An existing trained bundle is only replaced with
    ``force``; a scaffolded plugin's manifest without weights is a template to fill, not a bundle to
    protect. Built-in actions train on the shipped demonstrations (or ``demo_files``); a plugin action on
    its author's files, with the built-in actions' demonstrations as negatives and no random negatives
    (no rule says a random motion is not the new action).

    ``feedback`` sources ("original" or review exports, :func:`feedback.load_feedback`) and
    ``feedback_judge`` ("rules": plans of the installed bundle on ``judge_scenes`` scenes graded by the
    rule judge, :func:`feedback_targets.judge_items`) fine-tune the ensemble after the demonstrations; reviewed
    runs that cannot be used (changed trajectory, missing folder) are reported through ``log``.
    """

    demo_files = [str(f) for f in expand_files(list(demo_files))]
    name, plugin = training_target(action, out, demo_files)
    out = out if out is not None else Path("runs") / "bundles" / name
    check_bundle_target(out, name, force)  # someone's folder, another action's bundle, unwritable: before training
    cfg = cfg or ProgressTrainConfig()
    fcfg = feedback_cfg or FeedbackConfig()
    items, n_skipped = _feedback_items(name, feedback, log)
    qsr_cfg = QSRConfig()
    if plugin:
        demos = {**all_demos(), name: load_demos(name, list(demo_files))}
        spec = declared_spec(name)  # its training options and extras (a built-in's are looked up)
        data_cfg = DataConfig(random_negatives=0).with_action(spec)
        frame, anchors = declared(name, out)
        qsr_cfg = QSRConfig(frame=frame.name, anchors=anchors)
    else:
        demos = all_demos({name: list(demo_files)} if demo_files else None)
        data_cfg, spec = DataConfig(), None
    if demo_files and not demos[name]:
        raise DataError(f"the demonstration files ({', '.join(str(f) for f in demo_files)[:200]}) hold no events "
                        f'of "{name}" (event_start_end is empty): nothing to learn, no bundle written')
    if not plugin and not demo_files:  # the shipped demonstrations: the plan may leave untrusted ones out
        demos = own_trusted(SHIPPED, name, demos)
    result = train_action(name, demos, seed=seed, cfg=cfg, data_cfg=data_cfg, qsr_cfg=qsr_cfg, tick=tick,
                          on_stage=on_stage,
                          extend=shipped_extension(name, demos, qsr_cfg, data_cfg, seed, spec))
    if feedback_judge:  # the demonstration-trained model plans, the judge grades its plans
        if feedback_judge != "rules":
            raise DataError(f'unknown feedback judge "{feedback_judge}" (known: rules)')
        items += judge_items(name, result.model, range(JUDGE_SEEDS, JUDGE_SEEDS + judge_scenes), RuleJudge(name),
                             log=log)
    if items:
        tuned = train_action(name, demos, seed=seed, cfg=cfg, data_cfg=data_cfg, qsr_cfg=qsr_cfg, tick=tick,
                             feedback=items, feedback_cfg=fcfg, base=result.model.nets,
                             extend=shipped_extension(name, demos, qsr_cfg, data_cfg, seed, spec))
        result = dataclasses.replace(tuned, seconds=result.seconds + tuned.seconds, final_loss=result.final_loss,
                                     history=result.history)
    arrays = ensemble_arrays(result.model.nets)
    if not (np.isfinite(result.final_loss) and all(np.all(np.isfinite(a)) for a in arrays.values())):
        raise DataError(f'training "{name}" diverged (the loss or a weight is not a number); no bundle written')
    default = ProgressTrainConfig()
    cmd = (f"l2p-bullet train {name} --seed {seed}" + "".join(f" --demos {f}" for f in demo_files)
           + (f" --ensemble {cfg.ensemble}" if cfg.ensemble != default.ensemble else "")
           + (f" --epochs {cfg.epochs}" if cfg.epochs != default.epochs else "")
           + "".join(f" --feedback {f}" for f in feedback)
           + (f" --feedback-judge {feedback_judge} --judge-scenes {judge_scenes}" if feedback_judge else ""))
    training = training_section(result, cfg, seed, cmd, data_cfg, demos[name], qsr_cfg)
    training["recipe"] = {"name": SHIPPED.name, **SHIPPED.extras_dict()}
    if feedback or feedback_judge:
        training["feedback"] = {"sources": list(feedback), "judge": feedback_judge or "",
                                "judge_scenes": judge_scenes if feedback_judge else 0,
                                "n_items": sum(it.action == name for it in items), "n_sequences": result.n_feedback,
                                "skipped_runs": n_skipped, "digest": feedback_digest(items), **fcfg.to_dict()}
    write_progress_bundle(out, name, arrays, result.model.model_cfg, result.model.qsr_cfg, training=training,
                          metrics={"train_loss": round(result.final_loss, 6)})
    return out, result


def train_plan(plan: TrainingPlan, action: str, demos: dict[str, list[Demo]], seed: int = 0,
               tick: Callable[[], None] | None = None) -> TrainResult:
    """``plan``'s ensemble for ``action``: :func:`train_action` (members seeded ``seed * 1000 + i``) on
    ``training_plan.training_set`` (of the shipped ``demos``: ``own_trusted`` applies)."""
    q = QSRConfig()
    demos = own_trusted(plan, action, demos)
    return train_action(action, demos, seed=seed, qsr_cfg=q, data_cfg=plan.data, cfg=plan.train, tick=tick,
                        extend=functools.partial(extend, plan, action, demos, q, seed))


JUDGE_SEEDS = 5000
"""First scene seed of the automatic feedback (``--feedback-judge``): benchmarks use 0-99, ``improve``
1000-4999, REINFORCE 10 000 and up."""


def _feedback_items(
    name: str, sources: Sequence[str], log: Callable[[str], None] | None
) -> tuple[list[FeedbackItem], int]:
    """The graded motions of ``sources`` for ``train_bundle``, and how many reviewed runs were left out."""
    items, skipped = load_feedback(sources)
    for s in skipped:
        if log:
            log(f"warning: left out reviewed run {s.id} ({s.path or 'no path'}): {s.reason}")
    if sources and not any(it.action == name for it in items) and log:
        log(f'warning: the feedback has no graded motion of "{name}"')
    return items, len(skipped)


def feedback_digest(items: Sequence[FeedbackItem]) -> str:
    """sha256 over the feedback used (ids, actions, grades, labels and poses), for the manifest."""
    h = hashlib.sha256()
    for it in items:
        h.update(f"{it.id}|{it.action}|{it.grades}|{it.labels}".encode())
        h.update(np.ascontiguousarray(it.mover, np.float64).tobytes())
    return h.hexdigest()


@dataclass(frozen=True)
class BundleTrainer:
    """:func:`train_bundle` with fixed settings, handed to code outside ``learning/`` that must not import
    torch itself (the teach page gets one from its command, which may)."""

    cfg: ProgressTrainConfig = field(default_factory=ProgressTrainConfig)

    @property
    def ticks(self) -> int:
        """How many times a training calls ``tick`` (once per member-epoch)."""
        return self.cfg.ensemble * self.cfg.epochs

    def __call__(self, action: str, out: Path, demo_files: Sequence[str], seed: int = 0,
                 tick: Callable[[], None] | None = None) -> tuple[Path, TrainResult]:
        return train_bundle(action, out, demo_files=demo_files, seed=seed, cfg=self.cfg, force=True, tick=tick)
