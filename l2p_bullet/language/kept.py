"""Answers kept for the scene they were read against, so that one sentence's many readings ask each question once.

Reading one sentence resolves the same words against the same scene many times: each reading the clause reader
tries (a comma's, an "and"'s, the mended sentence's, the lenient one's) and each span a reader tries ("the red",
"the red cube", ...) asks the object resolver again, and its answer depends on nothing but the words, what the
caller passes with them (a role, a context) and the scene's objects. A scene may change between two questions (a
test or a chain's clause moves an object, a group is read among some objects only), its objects do not: a
:class:`~l2p_bullet.core.scene.SceneObject` is frozen, and a moved one is a new object. So the objects themselves,
by identity, with the table and workspace beside them, key what was read among them; each kept answer holds the
objects it was read among, so no other object can take their ids while it is kept.

A refusal is kept too and raised as a fresh copy each time (its type, message and attributes; a new traceback),
as reading the words again would raise a new one.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any

from ..core.scene import Scene
from ..errors import L2PError, copied


class SceneMemo:
    """The last ``size`` answers of one pure reader of a scene, each kept by (question, the scene's objects)."""

    def __init__(self, size: int) -> None:
        self.size = size
        self._kept: OrderedDict[tuple, tuple[tuple, Any, L2PError | None]] = OrderedDict()

    def clear(self) -> None:
        self._kept.clear()

    def ask(self, question: Hashable, scene: Scene, read: Callable[[], Any]) -> Any:
        """``read()``'s answer to ``question`` among ``scene``'s objects: kept from the last time it was asked
        among the same objects, else read now and kept. A refusal (an :class:`L2PError`) is kept and raised anew;
        any other exception is a bug and is never kept. A question that cannot be hashed is read each time."""
        try:
            held = (scene.table, scene.workspace, *scene.objects)
            key = (question, *map(id, held))
            kept = self._kept.get(key)
        except (AttributeError, TypeError):  # not a Scene, or an unhashable question (a list for a tuple, say)
            return read()
        if kept is not None:
            self._kept.move_to_end(key)
            _, answer, refusal = kept
            if refusal is not None:
                raise copied(refusal)
            return answer
        try:
            answer = read()
        except L2PError as e:
            self._keep(key, (held, None, copied(e)))  # a copy: the raised one's traceback holds every frame
            raise
        self._keep(key, (held, answer, None))
        return answer

    def _keep(self, key: tuple, entry: tuple) -> None:
        self._kept[key] = entry
        if len(self._kept) > self.size:
            self._kept.popitem(last=False)

