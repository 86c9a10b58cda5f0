"""The trainer reads a training plan, a plan never calls the trainer: no import circle among learning/'s modules,
function-level imports included (one hidden inside a function is a circle all the same)."""

from __future__ import annotations

import ast
from pathlib import Path

import l2p_bullet.learning

LEARNING = Path(l2p_bullet.learning.__file__).parent


def _edges(folder: Path) -> dict[str, set[str]]:
    """Module -> the modules of the same folder it imports, anywhere in its body (``from .x import``,
    ``from . import x``)."""
    mods = {p.stem for p in folder.glob("*.py")}
    out = {}
    for p in folder.glob("*.py"):
        found = set()
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                found |= {node.module.split(".")[0]} if node.module else {a.name for a in node.names}
        out[p.stem] = found & mods
    return out


def circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """One import circle through each module that lies on one."""
    found = []
    for start in sorted(edges):
        stack, seen = [(start, [start])], set()
        while stack:
            node, path = stack.pop()
            if start in edges[node]:
                found.append([*path, start])
                break
            for nxt in sorted(edges[node] - seen):
                seen.add(nxt)
                stack.append((nxt, [*path, nxt]))
    return found


def test_no_import_circle_among_the_learning_modules():
    assert not circles(_edges(LEARNING)), circles(_edges(LEARNING))
    assert "training_plan" in _edges(LEARNING)["train_progress"]  # the trainer reads the plan ...
    assert "train_progress" not in _edges(LEARNING)["training_plan"]  # ... and the plan never the trainer


def test_the_scan_sees_a_circle_hidden_in_a_function(tmp_path):
    (tmp_path / "plan.py").write_text("from .trainer import train\n")
    (tmp_path / "trainer.py").write_text("def train():\n    from .plan import SHIPPED\n    return SHIPPED\n")
    assert circles(_edges(tmp_path)) == [["plan", "trainer", "plan"], ["trainer", "plan", "trainer"]]
