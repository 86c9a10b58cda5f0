"""Benchmark the plugin path for viewer-frame and two-anchor prepositions, as docs/perform.md walks it.

    .venv/bin/python benchmarks/bench_prepositions.py                      # default training (5 x 30)
    .venv/bin/python benchmarks/bench_prepositions.py --ensemble 2 --epochs 12 --scenes 10
    .venv/bin/python benchmarks/bench_prepositions.py --scenes 1 --ensemble 1 --epochs 4 --events 4   # smoke run

For "to the left of", "to the right of" (``frame = "viewer"``) and "between" (``anchors = 2``): scaffold
the plugin, write the generated demonstrations (``learning.synthetic``, 2 sessions x 16 events, seed 0;
``--events`` sets the events per session: fewer make a smaller training set, for a smoke run),
train it with ``l2p-bullet train``'s code, then ``perform`` (executed by the arm, no rendering) on the
test's scenes (seeds 0..N-1: ``random_scene`` / ``random_between_scene``) and on held-out scenes no
choice was made on (seeds 1000..1000+N-1). The freshly trained folder is used directly
(``registry.local``), not installed. Prints per action and scene set:

- "side": the block ends on the asked side of the anchor as the robot sees it (the half-plane of the
  line of sight through B; the installed-plugin test's measure); "rules": the plugin's rule judge
  (left-of: within 45 degrees of straight left, at most 4 blocks away, not overlapping; between: on the
  segment, off the line by at most half a block, touching neither) on the executed trajectory;
- final progress (the action's own model on the executed trajectory), the anchors' largest motion;
- discrimination: the left-of model's final progress on the executed right-of runs and on generated
  right-of demonstrations (a session of another seed), and on its own held-out demonstrations;
- training seconds and mean plan / execute seconds.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

PLUGINS = {  # action: (phrase, frame, anchors, rules, sentence)
    "left-of": ("to the left of", "viewer", 1, "left-of", "move A to the left of B"),
    "right-of": ("to the right of", "viewer", 1, "right-of", "move A to the right of B"),
    "between": ("between", "relative", 2, "between", "put A between B and C"),
}


def build(root: Path, name: str, ensemble: int | None, epochs: int | None, events: int = 16) -> tuple[Path, float]:
    """Scaffold, generate demonstrations and train one plugin; its bundle folder and training seconds."""
    import dataclasses

    from l2p_bullet.learning.synthetic import write_sessions
    from l2p_bullet.learning.train_progress import ProgressTrainConfig, train_bundle
    from l2p_bullet.plugins.scaffold import scaffold

    phrase, frame, anchors, rules, _ = PLUGINS[name]
    s = scaffold(name, [phrase], root / f"l2p-{name}", frame=frame, anchors=anchors, judge=rules)
    files = write_sessions(s.root / "demos", name, sessions=2, events=events, seed=0)
    cfg = ProgressTrainConfig()
    cfg = dataclasses.replace(cfg, ensemble=ensemble or cfg.ensemble, epochs=epochs or cfg.epochs)
    t = time.perf_counter()
    train_bundle(name, s.package_dir, demo_files=[str(f) for f in files], cfg=cfg, force=True)
    return s.package_dir, time.perf_counter() - t


def run(name: str, folder: Path, seeds: list[int], out: Path, score_with=None) -> list[dict]:
    from l2p_bullet.core.contracts import load_motion
    from l2p_bullet.core.frames import VIEWPOINTS, viewer_offset
    from l2p_bullet.core.scene import random_between_scene, random_scene
    from l2p_bullet.pipeline import perform
    from l2p_bullet.plugins import registry

    plugins = [*registry.discover(), registry.local(name, folder)]
    three = PLUGINS[name][2] == 2
    rows = []
    for seed in seeds:
        scene = random_between_scene(seed) if three else random_scene(seed)
        r = perform(PLUGINS[name][4], scene, out_dir=out / f"{name}-{seed}", seed=seed, render=False,
                    plugins=plugins)
        m = load_motion(out / f"{name}-{seed}" / "trajectory.json")
        lat, _ = viewer_offset(m.mover[-1, :2], m.anchor[-1, :2], np.array(VIEWPOINTS["robot"]))
        row = {
            "rules": r.success,
            "lateral": lat,
            "final": r.final_progress,
            "moved_mm": 1000 * r.anchor_displacement_m,
            "plan": r.timings["plan"],
            "execute": r.timings["execute"],
        }
        if score_with is not None:
            row["other"] = float(score_with.final(m.mover, m.anchor, m.size))
        rows.append(row)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=30)
    ap.add_argument("--ensemble", type=int, default=None)
    ap.add_argument("--epochs", type=int, default=None)
    ap.add_argument("--events", type=int, default=16, help="generated demonstrations per session (2 sessions)")
    args = ap.parse_args()
    from l2p_bullet.data.demos import load_demos
    from l2p_bullet.learning.synthetic import write_sessions
    from l2p_bullet.plugins.bundle import load_bundle

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        folders, train_s = {}, {}
        for name in PLUGINS:
            folders[name], train_s[name] = build(root, name, args.ensemble, args.epochs, args.events)
        left_model = load_bundle(folders["left-of"]).progress_model()
        sets = {f"test seeds 0-{args.scenes - 1}": list(range(args.scenes)),
                f"held-out seeds 1000-{999 + args.scenes}": list(range(1000, 1000 + args.scenes))}
        print("\n| action | scenes | side | rules | final progress | anchors moved mm (max) | plan s | execute s "
              "| train s |\n|---|---|---:|---:|---:|---:|---:|---:|---:|")
        scored: list[float] = []
        for name, folder in folders.items():
            for label, seeds in sets.items():
                rows = run(name, folder, seeds, root / "runs", left_model if name == "right-of" else None)
                want = {"left-of": 1, "right-of": -1}.get(name)
                side = "" if want is None else f"{np.mean([r['lateral'] * want > 0 for r in rows]):.0%}"
                print(f"| {name} | {label} | {side} | {np.mean([r['rules'] for r in rows]):.0%} | "
                      f"{np.mean([r['final'] for r in rows]):.2f} | {max(r['moved_mm'] for r in rows):.2f} | "
                      f"{np.mean([r['plan'] for r in rows]):.2f} | {np.mean([r['execute'] for r in rows]):.2f} | "
                      f"{train_s[name]:.0f} |", flush=True)
                if name == "right-of":
                    scored += [r["other"] for r in rows]
        print("\nDiscrimination (the left-of model's final progress):")
        print(f"- on the executed right-of runs: mean {np.mean(scored):.3f}, max {np.max(scored):.3f}")
        for kind in ("right-of", "left-of"):
            demos = load_demos(kind, write_sessions(root / f"held-{kind}", kind, sessions=1, events=args.events,
                                                    seed=7))
            f = [left_model.final(d.mover[: d.end + 1], d.anchor[: d.end + 1], d.size, viewer=d.viewer) for d in demos]
            print(f"- on {len(f)} generated {kind} demonstrations of another seed: mean {np.mean(f):.3f}, "
                  f"min {np.min(f):.3f}, max {np.max(f):.3f}")


if __name__ == "__main__":
    main()
