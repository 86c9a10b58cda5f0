"""Train an action's move policy by REINFORCE in the 2-D simulator and store it in the action's bundle.

Episodes start from random two-block scenes (``scene.random_scene`` with seeds from 10 000 on, so the
benchmark's scenes 0-49 are never trained on). At each step the Gaussian policy proposes a move, the
2-D simulator accepts or rejects it (a rejected move leaves the mover where it was and costs a small
penalty), and the reward is the increase of the action's **learned** progress: the returns therefore
sum to the final progress gained, which is what the planner maximises. An episode ends early once
progress passes ``done_at``. All episodes of a step are scored in one forward pass.

    l2p-bullet train-policy around [--iterations 300] [--episodes 48] [--out DIR | --bundle DIR [--force]]
"""

from __future__ import annotations

import shlex
import shutil
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch

from ..core.folders import check_writable
from ..core.frames import declaration
from ..core.scene import random_scene
from ..core.threads import torch_threads
from ..errors import BundleError, L2PError
from ..planning.policy import FEATURE_RADIUS, FEATURES, policy_features, to_poses
from ..planning.problem import FRAME_STEP
from ..planning.world2d import World2D, segment_frames
from ..plugins.bundle import (
    POLICY_FILE,
    PROGRESS_FILE,
    load_bundle,
    read_manifest,
    write_weights,
)
from .adam import Adam
from .policy_net import GaussianPolicy
from .progress_net import ProgressModel

BEST_WINDOW = 10
"""Iterations averaged when choosing which weights to keep (see :func:`train_policy`)."""


@dataclass(frozen=True)
class PolicyTrainConfig:
    iterations: int = 300
    episodes: int = 48
    horizon: int = 8
    lr: float = 3e-3
    entropy: float = 1e-3
    reject_penalty: float = 0.02
    done_at: float = 0.95
    seed: int = 0
    size: float = 0.05


def rollout(net: GaussianPolicy, model, seeds: list[int], cfg: PolicyTrainConfig):
    """Run one batch of episodes; returns log-probs (H,B) and rewards (H,B) as tensors, and final progress."""
    worlds = [World2D(random_scene(s, cfg.size), "A") for s in seeds]
    anchors = np.stack([w.scene.get("B").pose for w in worlds])
    centres = np.stack([w.center for w in worlds])
    frames = [w.mover.pose[None].copy() for w in worlds]
    progress = np.asarray(model.final_batch(frames, [a[None] for a in anchors], cfg.size), float)
    moves = np.zeros(len(seeds))
    active = np.ones(len(seeds), bool)
    logps, rewards = [], []
    for _ in range(cfg.horizon):
        feats, hand = policy_features(frames, anchors, cfg.size, progress, moves, centres, FEATURE_RADIUS)
        x = torch.from_numpy(feats)
        dist = net.distribution(x)
        act = dist.sample()
        logps.append(dist.log_prob(act).sum(-1) * torch.from_numpy(active.astype(np.float32)))
        poses = np.stack([f[-1] for f in frames])
        ends = to_poses(act.numpy().astype(float), poses, anchors, cfg.size, hand)
        reward = np.zeros(len(seeds))
        moved = []
        for i, w in enumerate(worlds):
            if not active[i]:
                continue
            if w.moves_free(poses[i], ends[i][None])[0]:
                frames[i] = np.vstack([frames[i], segment_frames(poses[i], ends[i], FRAME_STEP * cfg.size)])
                moves[i] += 1
                moved.append(i)
            else:
                reward[i] = -cfg.reject_penalty
        if moved:
            new = np.asarray(model.final_batch([frames[i] for i in moved],
                                               [np.repeat(anchors[i][None], len(frames[i]), 0) for i in moved],
                                               cfg.size), float)
            reward[moved] = new - progress[moved]
            progress[moved] = new
        rewards.append(torch.from_numpy(reward.astype(np.float32)))
        active &= progress < cfg.done_at
        if not active.any():
            break
    return torch.stack(logps), torch.stack(rewards), progress


Tick = Callable[[float], None]
"""Called after every iteration with its mean final progress (the command's progress bar)."""


def train_policy(model, cfg: PolicyTrainConfig = PolicyTrainConfig(), log=print,
                 tick: Tick | None = None) -> tuple[GaussianPolicy, list[float], int]:
    """REINFORCE with a per-step mean baseline.

    Returns the policy, the mean final progress per iteration and the iteration whose weights are
    returned: the last of the best ``BEST_WINDOW`` consecutive iterations by mean final progress (each
    iteration's episodes are fresh random scenes, so that mean is an unbiased estimate of the policy
    a few steps earlier). REINFORCE can collapse late: with a re-trained past model, the last
    iterations reached 0.42 after 0.8 earlier on, and the planner's success fell from 100 % to 42 %.
    """
    with torch_threads(1):  # small batches: a second thread only adds contention on a shared machine
        return _train_policy(model, cfg, log, tick)


def _train_policy(model, cfg: PolicyTrainConfig, log, tick: Tick | None) -> tuple[GaussianPolicy, list[float], int]:
    torch.manual_seed(cfg.seed)
    rng = np.random.default_rng(cfg.seed)
    net = GaussianPolicy()
    opt = Adam(net.parameters(), lr=cfg.lr)
    history: list[float] = []
    best, best_it, best_state = -np.inf, cfg.iterations - 1, None
    t0 = time.perf_counter()
    for it in range(cfg.iterations):
        seeds = [int(s) for s in rng.integers(10_000, 1_000_000, cfg.episodes)]
        logp, rew, final = rollout(net, model, seeds, cfg)
        returns = torch.flip(torch.cumsum(torch.flip(rew, [0]), 0), [0])
        adv = returns - returns.mean(1, keepdim=True)
        adv = adv / (adv.std() + 1e-6)
        with torch.no_grad():
            _, log_std = net(torch.zeros(1, net.body[0].in_features))
        loss = -(logp * adv).sum(0).mean() - cfg.entropy * log_std.sum()
        opt.zero_grad()
        loss.backward()
        torch.nn.utils.clip_grad_norm_(net.parameters(), 1.0)
        opt.step()
        history.append(float(final.mean()))
        if len(history) >= BEST_WINDOW and np.mean(history[-BEST_WINDOW:]) > best:
            best, best_it = float(np.mean(history[-BEST_WINDOW:])), it
            best_state = {k: v.detach().clone() for k, v in net.state_dict().items()}
        if tick:
            tick(history[-1])
        if log and (it % 10 == 0 or it == cfg.iterations - 1):
            log(f"iter {it:4d}  final progress {history[-1]:.3f}  ({time.perf_counter() - t0:.0f} s)")
    if best_state is not None:
        net.load_state_dict(best_state)
    net.eval()
    return net, history, best_it


def policy_settings(cfg: PolicyTrainConfig, history: list[float], seconds: float, best_it: int) -> dict:
    """The manifest's ``[policy]`` section describing the trained policy.

    ``final_progress_first`` / ``_last`` are means over the first and last ``window`` iterations
    (``BEST_WINDOW``, fewer in a short run so that the two never overlap: with 2 iterations
    overlapping windows would give the same mean, which would disagree with the last iteration's line).
    """
    w = max(1, min(BEST_WINDOW, len(history) // 2))
    return {
        "file": "policy.safetensors",
        "kind": "gaussian-mlp",
        "features": FEATURES,
        "training": asdict(cfg) | {"seconds": round(seconds, 1),
                                   "window": w,
                                   "final_progress_first": round(float(np.mean(history[:w])), 4),
                                   "final_progress_last": round(float(np.mean(history[-w:])), 4),
                                   "kept_iteration": best_it,
                                   "final_progress_kept": round(float(np.mean(
                                       history[max(0, best_it + 1 - BEST_WINDOW):best_it + 1])), 4)},
    }


def policy_folder(action: str, bundle_dir: str | None, out_dir: str | None, force: bool) -> tuple[Path, bool]:
    """Where ``train-policy`` writes, and whether that is a fresh copy: ``--bundle DIR`` in place (refused
    inside the installed l2p-bullet package or an installed plugin's bundle without ``force``), else a
    copy of ACTION's bundle in ``out_dir`` (default ``runs/train-policy-<timestamp>``), which must not
    exist. The default never touches an installed bundle: in an editable install that is the
    repository's committed files. A copy interrupted half-way is removed: a partial bundle
    would block the same ``--out`` next time."""
    from ..plugins import registry

    if bundle_dir is not None:
        if out_dir is not None:
            raise BundleError("give --bundle (train in place) or --out (a new copy), not both")
        folder = Path(bundle_dir)
        if not force and installed(folder):
            raise BundleError(f"{folder} is a bundle of an installed package: pass --force to replace its policy, "
                              "or leave out --bundle to train a copy in a new folder")
        _check_bundle_action(folder, action)  # a past policy in the around bundle would plan "around" wrong
        check_writable(folder, "--bundle", BundleError)  # before minutes of training, not after
        return folder, False
    _, source = registry.locate(action)
    folder = Path(out_dir) if out_dir else Path("runs") / f"train-policy-{time.strftime('%Y%m%d-%H%M%S')}"
    if folder.exists() or folder.is_symlink():
        raise BundleError(f"{folder} already exists: choose another --out (or train in it with --bundle {folder})")
    check_writable(folder, "--out", BundleError)
    folder.parent.mkdir(parents=True, exist_ok=True)
    try:
        shutil.copytree(source, folder, ignore=shutil.ignore_patterns("__pycache__"))
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    return folder, True


def train_policy_into(action: str, bundle_dir: str | None, out_dir: str | None, force: bool,
                      cfg: PolicyTrainConfig = PolicyTrainConfig(), log=print,
                      tick: Tick | None = None) -> tuple[Path, bool, dict]:
    """``train-policy``: train in :func:`policy_folder`'s folder; returns it, whether it is a fresh copy,
    and the new ``[policy]`` section.

    The copy is made before the minutes of training. If training fails or is interrupted (Ctrl-C) before
    the policy is written, the copy this run made is removed: left behind, it held the untrained bundle,
    byte for byte, looked finished, and made the same command fail ("already exists"). In place
    (``--bundle``) nothing is written before the end, so the bundle is left as it was. A Ctrl-C gets a
    note saying so (the CLI prints it after "interrupted").
    """
    folder, copied = policy_folder(action, bundle_dir, out_dir, force)
    try:
        settings = train_policy_bundle(folder, cfg, log, tick)
    except BaseException as e:
        if copied:
            shutil.rmtree(folder, ignore_errors=True)
        if isinstance(e, KeyboardInterrupt):
            e.add_note("nothing was written" if copied else f"the bundle in {folder} is unchanged")
        raise
    return folder, copied, settings


def policy_command(action: str, folder: Path) -> str | None:
    """The ``train-policy`` command that trains the policy of the bundle in ``folder`` in place (with
    ``--force`` where that bundle is installed), or None for an action no policy is trained for (a
    viewer-frame or two-anchor one plans without one): the next step after ``train``."""
    frame, anchors = declaration(read_manifest(folder))
    if not frame.relative or anchors != 1:
        return None
    return shlex.join(["l2p-bullet", "train-policy", action, "--bundle", str(folder)]
                      + (["--force"] if installed(folder) else []))


def _check_bundle_action(folder: Path, action: str) -> None:
    """Refuse a ``--bundle`` whose manifest names another action than ACTION (``BundleError``)."""
    from ..core.vocabulary import normalize_name
    from ..plugins import registry

    try:
        name = registry.locate(action)[0]
    except L2PError:  # a plugin action still being authored (not installed): its own name
        name = action
    found = str(read_manifest(folder).get("name", ""))
    if normalize_name(found) != normalize_name(name):
        raise BundleError(f'{folder} is the bundle of the action "{found}", not of "{name}": give the bundle '
                          f'folder of "{name}" as --bundle (or "{found}" as ACTION)')


def installed(folder: Path) -> bool:
    """Is ``folder`` inside the installed l2p-bullet package, or an installed plugin's bundle folder?"""
    from .. import __file__ as package_init
    from ..plugins import registry

    here = folder.resolve()
    roots = [Path(package_init).resolve().parent] + [p.path.resolve() for p in registry.discover() if p.path]
    return any(here == r or r in here.parents for r in roots)


def train_policy_bundle(folder: Path, cfg: PolicyTrainConfig = PolicyTrainConfig(), log=print,
                        tick: Tick | None = None) -> dict:
    """Train the move policy of the bundle in ``folder`` against its progress model and store it there.

    Returns the manifest's new ``[policy]`` section. The bundle's own planner choices (``planner``,
    ``threshold``) are kept; ``progress_sha256`` records which progress model the policy learned to
    please, so a re-trained model marks it stale (see :func:`l2p_bullet.planning.plan`).
    """
    bundle = load_bundle(folder)
    frame, anchors = declaration(bundle.manifest)
    if not frame.relative or anchors != 1:
        # The policy sees the mover in the anchor's polar frame and mirrors it to the side with more room:
        # it cannot know the viewer's left from right, nor a second anchor. Such actions plan without one.
        raise BundleError(f'"{bundle.name}" declares frame = "{frame.name}", anchors = {anchors}: move policies are '
                          "trained for relative one-anchor actions only; the default planner plans this action "
                          "without one")
    t0 = time.perf_counter()
    net, history, best_it = train_policy(ProgressModel.from_bundle(bundle), cfg, log, tick)
    settings = policy_settings(cfg, history, time.perf_counter() - t0, best_it)
    settings |= {k: v for k, v in bundle.manifest.get("policy", {}).items() if k in ("planner", "threshold")}
    settings["progress_sha256"] = bundle.manifest["weights"][PROGRESS_FILE]["sha256"]
    arrays = {k: v.detach().contiguous().numpy() for k, v in net.state_dict().items()}
    write_weights(folder, POLICY_FILE, arrays, "policy", settings)
    return settings

