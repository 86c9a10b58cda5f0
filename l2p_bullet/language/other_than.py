"""An object described by what it is not: "the cube that isn't red", "the brown one that isn't the small one".

The description before "that isn't" names a group (language/pools.pool_of: what it describes); the words after
it name the ones left out, by colour or kind ("red") or as an object of the group ("the small one"). The one object
left is meant; where several are left it is asked, and where none is, it is no reading of this kind.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from ..core.scene import Scene
from ..errors import L2PError, LanguageError
from .pools import pool_of

OTHER_THAN = re.compile(r"^(?P<base>.+?)\s+(?:(?:that|which)\s+(?:isn't|isnt|is\s+not)|(?:that's|thats|which's)\s+not)"
                        r"\s+(?P<not>.+?)\s*$", re.IGNORECASE)


def other_than(text: str, scene: Scene, role: str, resolve: Callable[..., str]) -> str | None:
    """The one object of the group ``text`` names before "that isn't" that the words after it do not describe; None
    where ``text`` is not said so or the words after name none of the group (``resolve``: how one description is
    resolved, language/references.resolve_object)."""
    m = OTHER_THAN.match(text)
    if m is None:
        return None
    pool = pool_of(m.group("base"), scene)
    if len(pool) < 2:
        return None
    group = scene.only({o.name for o in pool})
    said = m.group("not").strip(" .!?")
    said = said if said.lower().startswith("the ") else f"the {said} one"
    left_out = {o.name for o in pool_of(said, group)}
    if not left_out or len(left_out) == len(pool):  # "the small one": a size, which pool_of does not read
        try:
            left_out = {resolve(said, group, role)}
        except L2PError:
            return None
    left = [o.name for o in pool if o.name not in left_out]
    if len(left) != 1:
        raise LanguageError(f'"{text}" fits {", ".join(left)}; name the one you mean')
    return left[0]
