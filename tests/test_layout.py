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
