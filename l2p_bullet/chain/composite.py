"""Perform a composite: its learned recipe (recipe.py) turns "make a row of A, B, C, D and E" into a chain
of single actions ("move B next to A, then move C next to B, ...", l2p_bullet/chain), any length.

Recursion is the recipe's own: a row of n is a row of n-1 plus one more block, moved with the learned
action relative to the learned anchor (the previous block, or the first), on the far side (monotone),
at the learned spacing. Where on the ring of places that satisfy "next to" the block must end is the
row's business, not the action's: each clause gets a *target* (:class:`RowSlot`), slot k of the axis, which
the planner is given as a constraint (planning/target.py) while the learned progress model still scores
every candidate path. The slot is measured from where the blocks really are when the clause is planned
(each clause is re-planned from the simulated world): on the line through the block that stays, one
learned pitch beyond the previous block, so errors do not add up across or along the row.

The axis' direction is chosen at perform time (assumed free, see recipe.py): among the staying block's
four face directions (turned by the learned ``axis_offset_deg``), then the four diagonals, the first one
whose slots all lie in the arm's workspace, off every block that is not in the row, and not on a row
block that is still waiting for its turn; ties go to the one with most room to the workspace's edge.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..composite.bundle import read_recipe
from ..composite.recipe import Recipe, row_gaps
from ..core.contracts import read_json
from ..core.geometry import polygons_overlap
from ..core.runfolder import write_summary
from ..core.scene import GRIPPER_MARGIN, Scene
from ..errors import InfeasibleError, L2PError, LanguageError, PluginError
from ..language import parse_list, phrase_matches, phrase_tokens, strip_polite, tokens
from ..language.verbs import verb_heads
from ..pipeline import resolve
from ..plugins import registry
from .clause import MAX_CLAUSES, Clause, Group, named

GAP_OK = 0.35
LINE_OK = 0.25
"""A row: every consecutive gap at most GAP_OK sides, every centre within LINE_OK sides of the fitted line
(the row judge's criteria; ``row_verdict``)."""


@dataclass(frozen=True)
class RowSlot:
    """The place of the block that joins the row after ``previous``: on the line through block ``stay``
    along ``direction``, one ``pitch`` beyond where ``previous`` really is along it (so a block that ended
    a little short or long is followed at the learned spacing, and nobody leaves the line)."""

    stay: str
    previous: str
    direction: tuple[float, float]
    pitch: float  # metres between neighbouring centres
    aligned: bool

    def __call__(self, scene: Scene) -> np.ndarray:
        o, u = scene.get(self.stay), np.asarray(self.direction)
        along = (
            float((np.asarray(scene.get(self.previous).xy) - np.asarray(o.xy)) @ u)
            if self.previous != self.stay
            else 0.0
        )
        xy = np.asarray(o.xy, float) + (along + self.pitch) * u
        return np.array([xy[0], xy[1], o.yaw if self.aligned else math.atan2(u[1], u[0])])


def composite_phrases(plugins: list | None, installed: list | None = None) -> dict[str, str]:
    return {ph: p.name for p in registry.composites(plugins, installed) for ph in p.phrases}


def is_composite(sentence: str, plugins: list | None = None) -> bool:
    """Whether ``sentence`` starts (after polite words) with an installed composite's phrase (one that cannot be
    used too: the chain's path then says why, :func:`composite_clauses`)."""
    if not isinstance(sentence, str):
        return False
    low = tuple(w.lower() for w in strip_polite(tokens(sentence)))
    installed = registry.discover("composite")
    usable = composite_phrases(plugins, installed)
    if any(phrase_matches(low, t) for t, _, _ in phrase_tokens(usable)):
        return True
    return _broken_composite(sentence, plugins, usable, installed) is not None  # composite_clauses names it


def load_recipe(action: str, plugins: list | None) -> Recipe:
    info = next(p for p in registry.composites(plugins) if p.name == action)
    return read_recipe(info.path)


def composite_clauses(sentence: str, scene: Scene, plugins: list | None) -> list | None:
    """The chain's clauses for a composite sentence, each with its slot; None for any other sentence."""
    installed = registry.discover("composite")
    phrases = composite_phrases(plugins, installed)
    lc = parse_list(sentence, scene, phrases) if phrases else None
    if lc is None and phrases and isinstance(sentence, str) and ROW_LAST.search(sentence) \
            and sentence.split()[0].lower() not in verb_heads():  # "the glasses, the keys, the cup in a row"
        try:
            lc = parse_list(f"put {sentence}", scene, phrases)
        except L2PError:
            lc = None
    if lc is None:
        untaught = _broken_composite(sentence, plugins, phrases, installed)
        if untaught is not None:
            raise untaught
        return None
    if len(lc.objects) - 1 > MAX_CLAUSES:
        raise LanguageError(f'a row of {len(lc.objects)} blocks is {len(lc.objects) - 1} moves; a chain has at most '
                            f"{MAX_CLAUSES}")
    recipe = load_recipe(lc.action, plugins)
    action_phrase = _phrase_of(recipe.action, plugins)
    stay, movers = lc.objects[0], list(lc.objects[1:])
    size = scene.get(stay).size
    direction = choose_axis(scene, stay, movers, recipe)
    clauses = []
    group = Group(lc.action, lc.objects, lc.sentence)
    for k, m in enumerate(movers, start=1):
        anchor = stay if recipe.anchor == "first" or k == 1 else movers[k - 2]
        text = f"move {m} {action_phrase} {anchor}"
        try:
            cmd = resolve(text, scene, plugins)
        except L2PError as e:
            raise named(e, f'clause {k} ("{text}") of "{lc.sentence}"') from None
        slot = RowSlot(stay, stay if k == 1 else movers[k - 2], (float(direction[0]), float(direction[1])),
                       size * (1 + recipe.spacing), recipe.aligned)
        clauses.append(Clause(k, text, cmd, slot, group))
    return clauses


ROW_LAST = re.compile(r"\bin\s+(?:a|one)\s+(?:straight\s+)?(?:row|line)\b", re.IGNORECASE)
"""A list said with where it goes and no verb ("blade, pickups, sponge in a row please"): as "put ... in a row"."""


def _broken_composite(sentence: str, plugins: list | None, usable: dict[str, str],
                      installed: list) -> PluginError | None:
    """The error naming a composite that cannot be used (not taught yet, say) when ``sentence`` starts with one
    of its phrases that no usable plugin owns: as a broken single action's phrase is named
    (:func:`~l2p_bullet.plugins.registry.blocked_phrases`, the same rule), not "cannot find a preposition"."""
    pool = registry.composites(plugins, installed, usable=False)
    blocked = {ph: e for ph, e in registry.blocked_phrases(pool).items() if ph not in usable}
    if not blocked or not isinstance(sentence, str):
        return None
    low = tuple(w.lower() for w in strip_polite(tokens(sentence)))
    return next((blocked[ph] for t, _, ph in phrase_tokens({ph: ph for ph in blocked}) if phrase_matches(low, t)),
                None)


def _phrase_of(action: str, plugins: list | None) -> str:
    plugins = registry.discover() if plugins is None else plugins
    info = next((p for p in plugins if p.ok and p.kind == "action" and p.name == action and p.phrases), None)
    if info is None:
        raise InfeasibleError("plugin", f'the composite was learned with the action "{action}", which is not installed')
    return info.phrases[0]


def choose_axis(scene: Scene, stay: str, movers: list[str], recipe: Recipe) -> np.ndarray:
    """The row's direction (unit 2-vector) from the staying block (module docstring)."""
    base = scene.get(stay)
    size = base.size
    pitch = size * (1 + recipe.spacing)
    start = math.radians(recipe.axis_offset_deg) + base.yaw
    best, best_key = None, None
    for j, a in enumerate(
        [start + k * math.pi / 2 for k in range(4)] + [start + math.pi / 4 + k * math.pi / 2 for k in range(4)]
    ):
        u = np.array([math.cos(a), math.sin(a)])
        conflicts, room = 0, np.inf
        for k, m in enumerate(movers, start=1):
            xy = np.asarray(base.xy) + k * pitch * u
            yaw = base.yaw if recipe.aligned else a
            foot = scene.get(m).footprint(np.array([xy[0], xy[1], yaw]))
            room = min(room, float(scene.workspace.clearance(xy)[0]))  # to the disk's rim, or an arm's ring
            if not scene.table.contains(foot):
                conflicts += 100
            for o in scene.objects:
                if o.name in (m, stay) or not polygons_overlap(foot, o.footprint(), margin=GRIPPER_MARGIN):
                    continue
                if o.name not in movers:
                    conflicts += 100  # a block that is not in the row: it never leaves
                elif movers.index(o.name) + 1 > k:
                    conflicts += 1  # a row block whose turn comes after slot k is filled: still there
        key = (room < 0.25 * size, conflicts, j >= 4, -room)
        if best_key is None or key < best_key:
            best, best_key = u, key
    assert best is not None
    return best


def row_verdict(scene: Scene, names: list[str], displaced_m: dict[str, float] | None = None) -> dict[str, Any]:
    """Whether the blocks ``names`` (in order) form a row: gaps, offsets from the fitted line, knocks."""
    xy = np.array([scene.get(n).xy for n in names], float)
    sizes = np.array([scene.get(n).size for n in names], float)
    gaps, offsets, _ = row_gaps(xy, sizes)
    knocked = {k: v for k, v in (displaced_m or {}).items() if v > 0.001}
    ok = bool(np.all(gaps <= GAP_OK) and np.all(offsets <= LINE_OK) and not knocked)
    reason = ("a row" if ok else "not a row: " + "; ".join(
        s for s in (f"gap {gaps.max():.2f} > {GAP_OK} side" if np.any(gaps > GAP_OK) else "",
                    f"off the line by {offsets.max():.2f} > {LINE_OK} side" if np.any(offsets > LINE_OK) else "",
                    f"knocked {', '.join(sorted(knocked))}" if knocked else "") if s))
    return {"success": ok, "reason": reason, "gaps_sides": np.round(gaps, 4).tolist(),
            "offsets_sides": np.round(offsets, 4).tolist(), "max_gap_sides": round(float(gaps.max()), 4),
            "max_offset_sides": round(float(offsets.max()), 4), "knocked": knocked}


def judge_row(result: Any, steps: list, final: Scene, summary_path: Any) -> dict[str, Any]:
    """The row verdict of a composite's chain run (``final``: the world after the last clause), added to
    its summary.json as ``row`` (and to its verdict: a chain whose clauses all succeeded but whose blocks do
    not form a row failed). A block knocked (> 1 mm) by a clause that did not move it fails the row."""


    names = [steps[0].clause.target.stay] + [s.clause.command.mover for s in steps]
    knocked: dict[str, float] = {}
    for r in result.results:
        for k, v in r.displacements_m.items():
            knocked[k] = max(knocked.get(k, 0.0), float(v))
    row = row_verdict(final, names, knocked)
    result.row = row
    summary = read_json(summary_path)
    summary["row"] = row
    summary["success"] = result.success
    summary["chain"] = result.verdict()  # the chain's verdict with the row's (it kept "all N clauses done", success)
    summary["verdict"] = {"success": result.success, "reason": summary["chain"]["reason"]}
    write_summary(summary_path, summary)
    return row
