"""A URDF's structure checked before PyBullet reads it: PyBullet crashes the whole process (exit 139, no
Python error to catch) on a URDF with two root links, and on one of a few hundred thousand chained links
after printing a warning per link. :func:`check_urdf` reads the file bounded and refuses, in one line:
more than :data:`MAX_URDF_BYTES`, XML that does not parse or declares entities, a root element other than
``<robot>``, more than :data:`MAX_URDF_LINKS` links, a joint naming a link that does not exist, a link that
is the child of two joints, not exactly one root link, or links the root does not reach (a cycle).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from functools import lru_cache

from ...core.bounded import read_bounded
from ...errors import PluginError

MAX_URDF_BYTES = 16 * 2**20
"""A robot's URDF is tens of kilobytes (the Panda's: 12 KB); 16 MiB leaves room for inline meshes' names."""
MAX_URDF_LINKS = 512
"""Links in one URDF (a humanoid has about 60; the arms this toolkit drives, 10-15)."""


def check_urdf(path: str) -> None:
    """Refuse (``PluginError``, one line) a URDF that PyBullet would crash on or choke on (module docstring);
    checked once per file version (path, size, modification time)."""
    try:
        st = os.stat(path)
    except OSError:
        return  # PyBullet says "cannot load" for a missing file: no crash to prevent
    _check(os.path.abspath(path), st.st_size, st.st_mtime_ns)


@lru_cache(maxsize=64)
def _check(path: str, size: int, mtime_ns: int) -> None:
    name = os.path.basename(path)
    raw = read_bounded(path, MAX_URDF_BYTES, PluginError, f"URDF {name}")
    if b"<!ENTITY" in raw:
        raise PluginError(f"URDF {name} declares XML entities; a URDF never needs them")
    try:
        root = ET.fromstring(raw.lstrip())  # PyBullet reads a file with blank lines before "<?xml"
    except ET.ParseError as e:
        raise PluginError(f"URDF {name} is not valid XML ({e})") from None
    if root.tag != "robot":
        raise PluginError(f"URDF {name}: its root element is <{str(root.tag)[:40]}>, not <robot>")
    links = [link.get("name") for link in root.findall("link")]
    if any(not n for n in links):
        raise PluginError(f"URDF {name}: a link without a name")
    if len(set(links)) != len(links):
        twice = next(n for n in links if links.count(n) > 1)
        raise PluginError(f'URDF {name}: two links are named "{twice[:60]}"')
    if len(links) > MAX_URDF_LINKS:
        raise PluginError(f"URDF {name} has {len(links):,} links; a robot this toolkit drives has at most "
                          f"{MAX_URDF_LINKS}")
    if not links:
        raise PluginError(f"URDF {name} has no link")
    known = set(links)
    children: dict[str, list[str]] = {}
    parent_of: dict[str, str] = {}
    for joint in root.findall("joint"):
        p, c = joint.find("parent"), joint.find("child")
        parent, child = (None if e is None else e.get("link") for e in (p, c))
        jname = str(joint.get("name"))[:60]
        for end, link in (("parent", parent), ("child", child)):
            if link not in known:
                raise PluginError(f'URDF {name}: joint "{jname}" names the {end} link "{str(link)[:60]}", which '
                                  "is not a link of the file")
        if child in parent_of:
            raise PluginError(f'URDF {name}: link "{child[:60]}" is the child of two joints')
        parent_of[child] = parent
        children.setdefault(parent, []).append(child)
    roots = [link for link in links if link not in parent_of]
    if len(roots) != 1:
        said = ", ".join(f'"{r[:40]}"' for r in roots[:3]) + (" ..." if len(roots) > 3 else "")
        raise PluginError(f"URDF {name} has {len(roots)} root links ({said or 'every link is a child'}); a robot "
                          "has exactly one, every other link the child of a joint")
    reached, todo = {roots[0]}, [roots[0]]
    while todo:
        for c in children.get(todo.pop(), []):
            if c not in reached:
                reached.add(c)
                todo.append(c)
    if len(reached) != len(known):
        lost = sorted(known - reached)[0]
        raise PluginError(f'URDF {name}: link "{lost[:60]}" is not reached from the root link "{roots[0][:60]}" '
                          "(its joints form a cycle)")
