"""Scene sets for an evaluation: seeded random scenes, a JSON-lines file, the original study's starts, bystanders.

Every scene of a set has a stable id (the results table's key together with the action, so ``--resume``
finds what was already run), a mover and an anchor, and the seed its runs plan with:

- ``random``: :func:`~l2p_bullet.core.scene.random_scene` for seeds S..S+N-1 (what the benchmarks use);
  a run on ``random/17`` plans with seed 17, exactly as ``bench_perform.py`` did.
- ``file``: one scene per line of a JSON-lines file, each a scene file's object (DESIGN.md section 4)
  with optional ``"id"``, ``"mover"``, ``"anchor"`` (default: the first two objects) and ``"seed"``
  (default: the first seed plus the line's index). Errors name the file and the line.
- ``study``: the start configurations of the 90 graded 2-D demonstrations (75 distinct ones), see
  :func:`study_scenes` for how the study's table is put on ours.
- bystanders: any set with K more blocks placed at random (seeded by the scene's seed) at least
  :data:`BYSTANDER_CLEARANCE` block sizes from every other block: obstacles the planner must go round.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..core.bounded import read_bounded
from ..core.contracts import MAX_JSON_BYTES, MAX_SEED
from ..core.scene import COLORS, Scene, SceneObject, random_scene
from ..core.workspace import START_RADIUS
from ..data.demos import load_graded_demos
from ..errors import EvaluationError, L2PError, SceneError

STUDY_BLOCK = 0.15
"""Side of the blocks in the original study's 2-D simulator (metres; its table spans +-1.2 m)."""

BYSTANDER_CLEARANCE = 2.0
"""Least centre distance (in block sizes of the larger block) between a bystander and any other block."""

BYSTANDER_COLORS = ("blue", "yellow", "orange", "purple", "cyan", "pink", "brown", "gray", "white", "black")


@dataclass(frozen=True)
class SceneSpec:
    """One scene of a set: ``id`` is stable across runs of the same set (the results table's key)."""

    id: str
    scene: Scene
    seed: int
    mover: str = "A"
    anchor: str = "B"
    source: str = "random"


def random_scenes(n: int, seed: int = 0, size: float = 0.05) -> list[SceneSpec]:
    """``n`` seeded random two-block scenes, seeds ``seed`` .. ``seed + n - 1``."""
    if n < 0:
        raise EvaluationError(f"--scenes must be 0 or more (got {n})")
    return [SceneSpec(f"random/{s}", random_scene(s, size), s) for s in range(seed, seed + n)]


def scene_file(path: str | Path, seed: int = 0) -> list[SceneSpec]:
    """Scenes from a JSON-lines file (blank lines and lines starting with # are skipped)."""
    p = Path(path)
    raw = read_bounded(p, MAX_JSON_BYTES, SceneError, f"scene file {p}")  # bounded: a link to /dev/zero never ends
    try:
        lines = raw.decode("utf-8").splitlines()
    except UnicodeDecodeError as e:
        raise SceneError(f"scene file {p} is not UTF-8 text (byte {e.start})") from None
    out: list[SceneSpec] = []
    seen: dict[str, int] = {}
    for n, line in enumerate(lines, start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        where = f"{p} line {n}"
        try:
            data = json.loads(text)
        except json.JSONDecodeError as e:
            raise SceneError(f"{where} is not valid JSON (column {e.colno}: {e.msg})") from None
        except (ValueError, RecursionError) as e:  # nested past the recursion limit, an integer of 5,000 digits
            raise SceneError(f"{where} is not valid JSON ({type(e).__name__}: {str(e)[:80]})") from None
        if not isinstance(data, dict):
            raise SceneError(f'{where}: expected a JSON object with an "objects" list')
        scene = Scene.from_dict(data, source=where, base=Path(p).resolve().parent)  # meshes beside the file
        try:
            scene.validate()
        except SceneError as e:
            raise SceneError(f"{where}: {e}") from None
        names = scene.names
        if len(names) < 2:
            raise SceneError(f"{where}: a scene needs at least two objects (a mover and an anchor)")
        mover, anchor = str(data.get("mover", names[0])), str(data.get("anchor", names[1]))
        for role, name in (("mover", mover), ("anchor", anchor)):
            if name not in names:
                raise SceneError(f'{where}: the {role} "{name}" is not one of the objects ({", ".join(names)})')
        if mover == anchor:
            raise SceneError(f'{where}: the mover and the anchor are the same object "{mover}"')
        run_seed = data.get("seed", seed + len(out))  # a default past MAX_SEED: EvaluationConfig.scene_set
        if "seed" in data and (not isinstance(run_seed, int) or isinstance(run_seed, bool)
                               or not 0 <= run_seed <= MAX_SEED):
            raise SceneError(f'{where}: "seed" must be an integer from 0 to {MAX_SEED} (got {run_seed!r})')
        sid = data.get("id", f"{p.name}/{len(out)}")
        if isinstance(sid, bool) or not isinstance(sid, str | int) or not str(sid).strip():
            raise SceneError(f'{where}: "id" must be a non-empty string (got {json.dumps(sid)}); it names the '
                             "scene in the results table")
        sid = str(sid)
        if sid in seen:
            raise SceneError(f'{where}: the id "{sid}" was already used on line {seen[sid]}')
        seen[sid] = n
        out.append(SceneSpec(sid, scene, run_seed, mover, anchor, "file"))
    if not out:
        raise SceneError(f"{p} has no scenes")
    return out


def study_scenes(size: float = 0.05, seed: int = 0) -> list[SceneSpec]:
    """The distinct start configurations of the graded 2-D demonstrations, on our table.

    The study's blocks are 0.15 m squares on a +-1.2 m table; ours are ``size`` (5 cm) in a disk of
    0.25 m (``START_RADIUS``; the planning disk is larger). Everything is expressed in block sizes first: the study's
    table centre becomes ours and every
    position is multiplied by ``size / 0.15`` (so the distance between the blocks, in block sizes, and
    both yaws are exactly the study's). Where that puts a block outside our workspace (the study's table
    is 16 blocks wide, our workspace 10), the whole configuration is translated, never scaled or turned,
    towards the centre until both blocks are half a block inside the workspace's edge. Block 0 (the
    study's mover) is A, red; block 1 (its static block) is B, green.
    """
    k = size / STUDY_BLOCK
    out: list[SceneSpec] = []
    seen: set[str] = set()
    for d in load_graded_demos():
        key = json.dumps(d["start_config"], sort_keys=True)
        if key in seen:
            continue
        seen.add(key)
        (m, a) = d["start_config"][:2]
        xy = np.array([[m["x"], m["y"]], [a["x"], a["y"]]]) * k
        xy = _fit_into_disk(xy, START_RADIUS - size / 2)
        scene = Scene([SceneObject("A", "red", size, (float(xy[0, 0]), float(xy[0, 1])), float(m["theta"])),
                       SceneObject("B", "green", size, (float(xy[1, 0]), float(xy[1, 1])), float(a["theta"]))])
        try:
            scene.validate()
        except SceneError as e:  # pragma: no cover - every shipped start fits (tests/evaluate/test_evaluate_scenes.py)
            raise EvaluationError(f"study start {d['id']} does not fit our table: {e}") from None
        out.append(SceneSpec(f"study/{d['id']}", scene, seed + len(out), source="study"))
    return out


def _fit_into_disk(xy: np.ndarray, radius: float) -> np.ndarray:
    """Translate points (K,2) towards the origin until all lie within ``radius`` (if they can)."""
    xy = xy.copy()
    for _ in range(20):
        r = np.hypot(xy[:, 0], xy[:, 1])
        far = int(np.argmax(r))
        if r[far] <= radius + 1e-12:
            break
        xy -= xy[far] / r[far] * (r[far] - radius + 1e-6)
    return xy


def with_bystanders(specs: list[SceneSpec], k: int) -> list[SceneSpec]:
    """Each scene with ``k`` more blocks (C, D, ...), placed at random from the scene's seed."""
    if k <= 0:
        return specs
    if k > len(BYSTANDER_COLORS):
        raise EvaluationError(f"at most {len(BYSTANDER_COLORS)} bystanders (got {k})")
    return [replace(s, id=f"{s.id}+{k}by", scene=add_bystanders(s.scene, k, s.seed), source=s.source + "+bystanders")
            for s in specs]


def add_bystanders(scene: Scene, k: int, seed: int) -> Scene:
    """``scene`` with ``k`` more blocks of the mover's size placed at random, deterministic for ``seed``."""
    rng = np.random.default_rng([seed, k, 1013])
    size = scene.objects[0].size
    used = {o.color for o in scene.objects}
    colors = [c for c in BYSTANDER_COLORS if c not in used and c in COLORS]
    names = [chr(ord("C") + i) for i in range(26) if chr(ord("C") + i) not in scene.names]
    objects = list(scene.objects)
    ws = scene.workspace.starts()  # drawn where they were before the planning disk grew (START_RADIUS)
    for i in range(k):
        for _ in range(2000):
            r, a = (ws.radius - size / 2) * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
            xy = (ws.center[0] + r * math.cos(a), ws.center[1] + r * math.sin(a))
            if ws.ring is not None and not ws.contains(np.array(xy), size / 2)[0]:
                continue  # an arm's reach ring: drawn in the disk, kept when inside the ring too (rejection)
            if all(math.hypot(xy[0] - o.xy[0], xy[1] - o.xy[1]) >= BYSTANDER_CLEARANCE * max(size, o.size)
                   for o in objects):
                objects.append(SceneObject(names[i], colors[i], size, xy, float(rng.uniform(0, math.pi / 2))))
                break
        else:
            raise EvaluationError(f"no room for {k} bystanders in this scene (placed {i})")
    try:
        return Scene(objects, scene.table, scene.workspace).validate()
    except L2PError as e:  # pragma: no cover - the clearance rules make this impossible
        raise EvaluationError(f"bystanders do not fit: {e}") from None
