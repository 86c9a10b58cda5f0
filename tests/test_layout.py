"""The package boundaries that keep commands fast and dependencies contained, checked on the source.

- torch lives in ``learning/`` only: the modules that train (or validate) networks. Nothing outside
  ``learning/`` imports torch, and nothing outside ``learning/`` and ``commands/`` (whose bodies call the
  trainers) imports those modules, so ``perform``, ``plan``, ``score`` and the review app never load it.
- pybullet lives in ``embodiment/sim/`` only.
Checked statically (every import statement, also inside functions) and at run time (a fresh interpreter
imports every other module and must not have loaded torch).
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

import l2p_bullet

PKG = Path(l2p_bullet.__file__).parent


def _modules() -> dict[str, Path]:
    out = {}
    for f in sorted(PKG.rglob("*.py")):
        parts = list(f.relative_to(PKG.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = f
    return out


def _imports(name: str, path: Path) -> set[str]:
    """Absolute names of every module the file imports (relative imports resolved)."""
    pkg = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
                base = ".".join(up + ([base] if base else []))
            found.add(base)
            found |= {f"{base}.{a.name}" for a in node.names}
    return found


MODULES = _modules()
IMPORTS = {n: _imports(n, p) for n, p in MODULES.items()}


def _torch_modules() -> set[str]:
    """Modules that import torch, or (at module level or not) a module that does: a fixed point."""
    found = {n for n, imps in IMPORTS.items() if any(i == "torch" or i.startswith("torch.") for i in imps)}
    while True:
        more = {n for n, imps in IMPORTS.items() if n not in found and imps & found
                and not n.startswith("l2p_bullet.commands.")}  # commands import trainers inside their bodies
        if not more:
            return found
        found |= more


TORCH_MODULES = _torch_modules()


def test_torch_is_imported_only_in_learning():
    outside = sorted(n for n in TORCH_MODULES if not n.startswith("l2p_bullet.learning."))
    assert not outside, f"modules outside learning/ that import torch: {outside}"
    assert TORCH_MODULES, "the learning code trains in torch: the scan found no torch import at all"


def test_only_learning_and_commands_reach_the_torch_modules():
    bad = sorted((n, i) for n, imps in IMPORTS.items() for i in imps if i in TORCH_MODULES
                 and not n.startswith(("l2p_bullet.learning.", "l2p_bullet.commands.")))
    assert not bad, f"torch-free modules importing a torch module of learning/: {bad}"


def test_pybullet_is_imported_only_in_embodiment_sim():
    bad = sorted(n for n, imps in IMPORTS.items() if any(i.split(".")[0] in ("pybullet", "pybullet_data",
                 "pybullet_utils") for i in imps) and not n.startswith("l2p_bullet.embodiment.sim."))
    assert not bad, f"modules outside embodiment/sim/ that import pybullet: {bad}"


def test_every_torch_free_module_imports_without_torch():
    names = sorted(n for n in MODULES if n not in TORCH_MODULES and ".actions." not in n)
    code = ("import importlib, sys\n"
            f"for n in {names!r}:\n    importlib.import_module(n)\n"
            "loaded = sorted(m for m in sys.modules if m == 'torch' or m.startswith('torch.'))\n"
            "assert not loaded, loaded[:5]\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-2000:]


# The one place that checks the fences at run time: the paths users run that must stay torch-free (and,
# before the arm, pybullet-free; load_grades also web-free), run in a fresh interpreter in the order a
# module would be loaded. The static checks above see every import statement; this catches what they
# cannot (a dynamic import, a dependency that imports torch itself).
RUNTIME_CHECK = """
import sys, tempfile
from pathlib import Path

def loaded(*names):
    return sorted(m for m in sys.modules if m.split('.')[0] in names)

from l2p_bullet.review.store import Store, load_grades
from l2p_bullet.review.original import import_original
db = Path(tempfile.mkdtemp()) / 'r.sqlite'
import_original(Store(db))
assert len(load_grades(db)) == 180
heavy = loaded('torch', 'fastapi', 'uvicorn', 'matplotlib', 'pybullet')
assert not heavy, 'load_grades: ' + str(heavy[:5])

from l2p_bullet.plugins import registry
from l2p_bullet.language import parse
from l2p_bullet.core.scene import default_scene
table = registry.phrase_table()
assert table['around'] == 'around', table
cmd = parse('move A around B', default_scene(), table)
bundle = registry.load(cmd.action)
from l2p_bullet.planning import PLANNERS, plan
for name in sorted(set(PLANNERS) - {'default'}):
    plan(default_scene(), 'A', 'B', bundle, planner=name, budget=3)
assert not loaded('torch', 'pybullet'), 'parse and plan: ' + str(loaded('torch', 'pybullet')[:5])

from l2p_bullet.pipeline import perform
r = perform('move A next to B', default_scene(), out_dir=Path(tempfile.mkdtemp()) / 'run', render=False)
assert r.verdict['success'], r.verdict
assert not loaded('torch'), 'perform: ' + str(loaded('torch')[:5])
"""


@pytest.mark.slow
def test_the_torch_free_paths_run_without_torch(tmp_path):
    """load_grades (also without the web stack and pybullet), plugin discovery, parse, every planner (the
    REINFORCE policy too) without pybullet, and a whole perform, in one fresh interpreter: none loads torch."""
    r = subprocess.run([sys.executable, "-c", RUNTIME_CHECK], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]


# --- floors: which room may import which ------------------------------------------------------------
FLOORS: tuple[tuple[str, ...], ...] = (
    ("l2p_bullet", "errors"),  # the package (its version) and the error classes every room raises
    ("plugins.finder",),  # the one plugin finder: every kind's entry points, one record, one rule for names
    ("actions", "manners"),  # what each built-in action is (ActionSpec, next to its bundle) and each manner of
    # motion (MannerSpec, its verbs, through the entry points l2p_bullet.manners): pure declarations
    ("core",),  # scene, geometry, vocabulary, file contracts (incl. a bundle's file names), run folders
    ("data",),  # the shipped demonstrations, people's grades, and their readers
    ("arms",),  # arms as data (ArmSpec, the built-in specs), the hand and wrist model, the workspace an arm gets
    ("progress", "judge", "language"),  # features + numpy model; verdicts and rule judges; sentence parsing
    ("embodiment", "planning"),  # the arm in the simulator (motion, execution, recording, sim/: pybullet) and
    # 2-D planning beside it: planning reads the arm's model from arms/, never the simulator
    ("plugins",),  # registries of every plugin kind, bundles, scaffolds, validation: the shape of a plugin
    ("options",),  # RunOptions: what a run is asked to do, checked once at the front door, handed down whole
    ("pipeline", "recognition"),  # perform and plan: the stages in order; recognising an action in a motion
    ("learning", "composite"),  # training (torch), feedback, agreement (improve performs through the pipeline);
    # composite actions' recipes learned from recognised demonstrations, and their bundles
    ("chain",),  # chains of clauses performed in one episode (through the pipeline's stages); a composite's
    # sentence expanded into a chain (chain/composite.py)
    ("evaluate", "envs", "web"),  # the batch runner, the Gymnasium environments, the shared web plumbing
    ("export", "review", "teach"),  # exports of evaluations, the review app, the teach page
    ("commands",),  # click commands: parse options, call one function
    ("cli",),  # the front door
    ("launch",),  # the l2p-bullet program's start-up (a quiet early Ctrl-C), then the front door
    ("__main__",),  # python -m l2p_bullet: the program
)
"""The floors, lowest first (docs/DESIGN.md, "Floors"). A module may import its own room and the rooms of
lower floors only: never a higher floor (a climb) nor another room on its own floor, so no two rooms can
import each other. A room is a subpackage of l2p_bullet or a top-level module, or a module named in
:data:`SUBROOMS`; a new one gets a floor here."""

SUBROOMS = ("plugins.finder",)
"""Modules that are rooms of their own inside a subpackage: the plugin finder lives with the plugin registries
(plugins/), but every floor that finds plugins (the manners' verbs, read when parsing) must reach it; its
package's ``__init__`` imports nothing."""

FLOOR_OF = {room: i for i, rooms in enumerate(FLOORS) for room in rooms}


def _room(module: str) -> str:
    inner = module.split(".", 1)[1] if "." in module else ""
    for sub in SUBROOMS:
        if inner == sub or inner.startswith(sub + "."):
            return sub
    parts = module.split(".")
    return "l2p_bullet" if len(parts) == 1 else parts[1]


def _internal_target(name: str) -> str | None:
    """The l2p_bullet module an imported name belongs to (``from .. import __version__`` -> l2p_bullet)."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def _room_imports() -> list[tuple[str, str, str, str]]:
    """(importing module, imported module, its room, the imported room) for every cross-room import."""
    out = set()
    for n, imps in IMPORTS.items():
        for i in imps:
            t = _internal_target(i) if i.startswith("l2p_bullet") else None
            if t is not None and _room(t) != _room(n):
                out.add((n, t, _room(n), _room(t)))
    return sorted(out)


def test_every_room_has_a_floor():
    rooms = {_room(n) for n in MODULES}
    missing = sorted(rooms - set(FLOOR_OF))
    assert not missing, f"rooms without a floor in tests/test_layout.py FLOORS (and docs/DESIGN.md): {missing}"
    assert not set(FLOOR_OF) - rooms, f"FLOORS names rooms that do not exist: {sorted(set(FLOOR_OF) - rooms)}"


def test_no_import_climbs_a_floor():
    bad = [f"{n} imports {t}: {a} (floor {FLOOR_OF[a]}) may not import {b} (floor {FLOOR_OF[b]})"
           + ("" if FLOOR_OF[b] > FLOOR_OF[a] else ", a room on its own floor")
           for n, t, a, b in _room_imports() if FLOOR_OF.get(b, -1) >= FLOOR_OF.get(a, -1)]
    assert not bad, "imports that climb (move the shared code down a floor):\n  " + "\n  ".join(bad)


def test_no_import_circle_between_rooms():
    edges: dict[str, set[str]] = {}
    for _, _, a, b in _room_imports():
        edges.setdefault(a, set()).add(b)

    def path(src: str, dst: str, seen: set[str]) -> list[str] | None:
        for nxt in sorted(edges.get(src, ())):
            if nxt == dst:
                return [src, dst]
            if nxt not in seen:
                seen.add(nxt)
                rest = path(nxt, dst, seen)
                if rest:
                    return [src, *rest]
        return None

    circles = {" -> ".join(p) for a in sorted(edges) if (p := path(a, a, set()))}
    assert not circles, f"import circles between rooms: {sorted(circles)}"


def test_nothing_in_the_package_imports_research():
    """research/ holds the experiments that did not ship (docs/learning.md, "What moved where"): the product
    never depends on them, so they can change or go without touching a command."""
    bad = sorted((n, i) for n, imps in IMPORTS.items() for i in imps if i == "research" or i.startswith("research."))
    assert not bad, f"modules of l2p_bullet importing research/: {bad}"


def test_planning_reads_the_arm_from_arms_never_from_the_simulator():
    """Planning and the up-front checks read the arm's model (ArmSpec, hand, wrist) from ``arms/``; the arm in
    PyBullet (``embodiment/``) sits on planning's floor, so an import of it from planning is a failure here."""
    assert FLOOR_OF["planning"] == FLOOR_OF["embodiment"] > FLOOR_OF["arms"]
    bad = sorted((n, t) for n, t, a, b in _room_imports() if a == "planning" and b == "embodiment")
    assert not bad, f"planning imports the simulator's room: {bad}"


def test_plugins_are_found_in_one_module():
    """Every kind of plugin (actions, composites, arms, manners) is found by one finder: one record, one
    error, one rule for names."""
    found = sorted(n for n, p in MODULES.items() if "metadata.entry_points(" in p.read_text())
    assert found == ["l2p_bullet.plugins.finder"], found


def test_no_import_circle_between_modules():
    """No module reaches itself through imports, function-level ones included (a lazy import inside a function
    hides a circle from Python, not from a reader)."""
    edges = {n: {i for i in imps if i in MODULES and i != n} for n, imps in IMPORTS.items()}
    for n in list(edges):  # "from .pkg import mod" names the package too: a package's own modules are not a circle
        edges[n] = {i for i in edges[n] if not n.startswith(i + ".")}
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    assert not found, f"import circles between modules: {found}"
