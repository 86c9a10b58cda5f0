"""The built-in actions: one subpackage each, holding its bundle (manifest.toml and weights) and its
:class:`~l2p_bullet.actions.spec.ActionSpec` (``ACTION``): the same shape a plugin's module has.

``BUILTIN`` lists them in the order every table uses (closer, away, next-to, past, around).
"""

from __future__ import annotations

from .around import ACTION as AROUND
from .away import ACTION as AWAY
from .closer import ACTION as CLOSER
from .next_to import ACTION as NEXT_TO
from .past import ACTION as PAST
from .spec import ActionSpec, Bound, LeadIn, Planning, Touching, Training, Violation

BUILTIN: dict[str, ActionSpec] = {a.name: a for a in (CLOSER, AWAY, NEXT_TO, PAST, AROUND)}
"""Canonical name -> spec of every built-in action."""

__all__ = ["BUILTIN", "ActionSpec", "Bound", "LeadIn", "Planning", "Touching", "Training", "Violation"]
