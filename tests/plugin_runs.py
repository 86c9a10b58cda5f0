"""Perform an installed plugin action on seeded scenes, as the installed-plugin test measures it.

Run with the Python of the environment the plugin is installed in (the project's own environment does
not see it)::

    python plugin_runs.py SENTENCE SCENES OUT_DIR [--three] [--score-with ACTION]

For seeds 0 .. SCENES-1: ``pipeline.perform`` on ``random_scene(seed)`` (``random_between_scene`` with
``--three``), executed by the arm without rendering, and one JSON line per scene on stdout: the verdict,
the final progress, where A ended relative to B as seen from the robot (blocks), how far any other block
moved, the trajectory's ``anchors``, and (``--score-with``) the final progress another installed action's
model gives the executed trajectory.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from l2p_bullet.core.contracts import load_motion
from l2p_bullet.core.frames import VIEWPOINTS, viewer_offset
from l2p_bullet.core.scene import random_between_scene, random_scene
from l2p_bullet.pipeline import perform
from l2p_bullet.plugins import registry


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("sentence")
    ap.add_argument("scenes", type=int)
    ap.add_argument("out", type=Path)
    ap.add_argument("--three", action="store_true")
    ap.add_argument("--score-with", default=None)
    args = ap.parse_args()
    other = registry.load(args.score_with).progress_model() if args.score_with else None
    for seed in range(args.scenes):
        scene = random_between_scene(seed) if args.three else random_scene(seed)
        out = args.out / f"scene{seed:02d}"
        r = perform(args.sentence, scene, out_dir=out, seed=seed, render=False)
        traj = json.loads((out / "trajectory.json").read_text())
        motion = load_motion(out / "trajectory.json")
        size = scene.get("A").size
        lat, dep = viewer_offset(motion.mover[-1, :2], motion.anchor[-1, :2], np.array(VIEWPOINTS["robot"]))
        row = {"seed": seed, "success": r.success, "verdict": r.verdict, "final_progress": r.final_progress,
               "lateral": float(lat) / size, "depth": float(dep) / size,
               "others_moved_mm": 1000 * r.anchor_displacement_m, "anchors": traj.get("anchors"),
               "seconds": r.timings["total"]}
        if other is not None:
            row["other_model"] = float(other.final(motion.mover, motion.anchor, motion.size))
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    sys.exit(main())
