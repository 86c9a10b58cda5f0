"""An arm and a gripper described in separate files made one URDF (``l2p-bullet new-arm --gripper``).

A vendor describes its arm (a UR5e: links to ``tool0``) and a gripper maker its gripper (a Robotiq 2F-85: links
from its base), each with meshes beside it; a robot on a bench is both, bolted at the flange. :func:`compose`
writes that robot as one URDF into a folder of its own, so a plugin package can ship it:

- every mesh either file names (relative to its URDF, absolute, or ``package://PKG/...`` found in a folder named
  PKG above the URDF or on ``ROS_PACKAGE_PATH``) is copied beside the new URDF with the materials and textures
  an OBJ names, and named relative to it: the package works wherever pip puts it;
- the gripper's root link hangs from the arm's ``mount`` link (default ``tool0``, else the arm's last link) by
  a fixed joint at ``xyz``/``rpy`` in that link's frame;
- gripper links, joints and materials named like one of the arm's are renamed ``gripper_<name>`` (mimic
  references follow);
- what PyBullet does not read (``transmission``, ``gazebo``, elements and attributes of other namespaces such as
  drake's, which are not even bound in some vendors' files) is left out, and what it needs but a vendor left out
  (an ``<inertial>``'s ``<inertia>``) is supplied.

A file that cannot be composed (not a URDF, a gripper with no movable joint or two roots, a mount link the arm
lacks, a mesh that does not exist) is one :class:`~l2p_bullet.errors.PluginError` line.
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

from ..errors import PluginError

MOUNT_JOINT = "l2p_mount"
"""The fixed joint that bolts the gripper to the arm."""
_DROPPED = ("transmission", "gazebo")


def read_urdf(path: str | Path, role: str) -> ET.Element:
    """The ``<robot>`` element of ``path`` without the elements and attributes of other namespaces (a prefix left
    unbound, as ``drake:`` is in some vendors' files, would make the XML invalid); PluginError naming ``role``."""
    try:
        text = Path(path).read_text(encoding="utf-8", errors="replace")
    except OSError as e:
        raise PluginError(f"cannot read the {role} URDF {path}: {e.strerror or e}") from None
    text = re.sub(r"<(\w+):(\w+)\b[^>]*?/>", "", text)
    text = re.sub(r"<(\w+):(\w+)\b.*?</\1:\2\s*>", "", text, flags=re.S)
    text = re.sub(r"\s(?!xmlns:)\w+:\w+=\"[^\"]*\"", "", text)
    if "<!ENTITY" in text:
        raise PluginError(f"the {role} URDF {path} declares XML entities; a URDF never needs them")
    try:
        root = ET.fromstring(text.lstrip())
    except ET.ParseError as e:
        raise PluginError(f"the {role} URDF {path} is not valid XML ({e})") from None
    if root.tag != "robot":
        raise PluginError(f"the {role} URDF {path} is not a URDF: its root element is <{root.tag}>, not <robot>")
    for tag in _DROPPED:
        for el in root.findall(tag):
            root.remove(el)
    return root


def resolve_mesh(name: str, urdf: str | Path) -> Path:
    """The file a URDF's mesh ``filename`` means: ``package://PKG/rest`` is ``rest`` inside the nearest folder
    named PKG above the URDF (or on ``ROS_PACKAGE_PATH``), else the folder holding the URDF when PKG is its name
    (a description shipped alone); ``file://`` and absolute paths are themselves; others are relative to the URDF."""
    folder = Path(urdf).resolve().parent
    if name.startswith("file://"):
        return Path(name[len("file://"):])
    if name.startswith("package://"):
        pkg, _, rest = name[len("package://"):].partition("/")
        roots = [p for p in (folder, *folder.parents) if p.name == pkg]
        for entry in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
            if entry:
                roots += [Path(entry) / pkg, *(p for p in Path(entry).glob(f"*/{pkg}"))]
        for root in roots:
            if (root / rest).is_file():
                return root / rest
        return folder / pkg / rest if not (folder / rest).is_file() else folder / rest
    return Path(name) if os.path.isabs(name) else folder / name


def _companions(mesh: Path) -> list[str]:
    """Files an OBJ names beside it (its materials, and their textures), relative to its folder."""
    out: list[str] = []
    if mesh.suffix.lower() != ".obj":
        return out
    try:
        text = mesh.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return out
    for lib in re.findall(r"^\s*mtllib\s+(.+?)\s*$", text, flags=re.M):
        out.append(lib)
        try:
            mtl = (mesh.parent / lib).read_text(encoding="utf-8", errors="replace")
        except OSError:
            continue
        out += re.findall(r"^\s*map_\w+\s+(?:-\S+\s+\S+\s+)*(.+?)\s*$", mtl, flags=re.M)
    return out


def _copy_meshes(root: ET.Element, urdf: str | Path, dest: Path, sub: str) -> None:
    """Copy every mesh ``root`` names into ``dest/meshes/sub`` (one folder per source folder, so equal file names
    from different folders stay apart) and point the elements at the copies, relative to ``dest``."""
    missing = []
    for mesh in root.iter("mesh"):
        name = mesh.get("filename", "")
        src = resolve_mesh(name, urdf)
        if not src.is_file():
            missing += [name] if name not in missing else []
            continue
        tag = hashlib.sha256(str(src.parent.resolve()).encode()).hexdigest()[:8]
        folder = dest / "meshes" / sub / tag
        folder.mkdir(parents=True, exist_ok=True)
        for rel in [src.name, *_companions(src)]:
            s, d = src.parent / rel, folder / rel
            if s.is_file() and not d.exists() and d.resolve().is_relative_to(folder.resolve()):
                d.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(s, d)
        mesh.set("filename", os.path.relpath(folder / src.name, dest))
    if missing:
        raise PluginError(f"{urdf} names {len(missing)} mesh file(s) that do not exist (first: {missing[0]}); put "
                          "them where the URDF says")


def _complete_inertials(robot: ET.Element) -> None:
    """Give an ``<inertial>`` without ``<inertia>`` (a Schunk gripper's base has only a mass) a 3 cm solid
    sphere's, and one without ``<mass>`` 10 g: PyBullet refuses the whole file otherwise. A link without any
    (a frame such as ``tool0``, which ROS reads as massless) gets 1 g: PyBullet would give it 1 kg and a
    1 kg m^2 inertia, and print a warning on stdout that would corrupt ``--json`` output."""
    for link in robot.findall("link"):
        if link.find("inertial") is None:
            inertial = ET.SubElement(link, "inertial")
            ET.SubElement(inertial, "mass", value="0.001")
            ET.SubElement(inertial, "inertia", ixx="1e-07", ixy="0", ixz="0", iyy="1e-07", iyz="0", izz="1e-07")
    for inertial in robot.iter("inertial"):
        mass = inertial.find("mass")
        if mass is None:
            mass = ET.SubElement(inertial, "mass", value="0.01")
        if inertial.find("inertia") is None:
            try:
                m = float(mass.get("value", "0.01"))
            except ValueError:
                m = 0.01
            i = f"{0.4 * m * 0.03 ** 2:.3g}"
            ET.SubElement(inertial, "inertia", ixx=i, ixy="0", ixz="0", iyy=i, iyz="0", izz=i)


def _roots(robot: ET.Element) -> list[str]:
    children = {j.find("child").get("link") for j in robot.findall("joint") if j.find("child") is not None}
    return [link.get("name") for link in robot.findall("link") if link.get("name") not in children]


def last_link(robot: ET.Element) -> str:
    """``tool0`` when the arm has it (the ROS-Industrial flange frame grippers are mounted on), else the link at
    the end of the longest chain from the root."""
    names = [link.get("name") for link in robot.findall("link")]
    if "tool0" in names:
        return "tool0"
    parent = {j.find("child").get("link"): j.find("parent").get("link") for j in robot.findall("joint")}

    def depth(link: str) -> int:
        d = 0
        while link in parent and d <= len(names):
            link, d = parent[link], d + 1
        return d

    return max(names, key=depth)


def _rename(gripper: ET.Element, taken: set[str], kind: str) -> dict[str, str]:
    """Rename the gripper's ``kind`` elements named like one of ``taken``; returns old -> new names."""
    out = {}
    for el in gripper.findall(kind):
        name = el.get("name")
        if name and name in taken:
            new = f"gripper_{name}"
            while new in taken:
                new = f"gripper_{new}"
            out[name] = new
            el.set("name", new)
    return out


def compose(arm: str | Path, gripper: str | Path, dest: str | Path, name: str, mount: str | None = None,
            xyz: tuple[float, float, float] = (0.0, 0.0, 0.0),
            rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> Path:
    """Write ``dest/NAME.urdf``: the arm with the gripper bolted to ``mount`` (module docstring); returns its path."""
    dest = Path(dest)
    a, g = read_urdf(arm, "arm"), read_urdf(gripper, "gripper")
    links = {link.get("name") for link in a.findall("link")}
    mount = mount or last_link(a)
    if mount not in links:
        raise PluginError(f'the arm URDF {arm} has no link "{mount}" to mount the gripper on (--mount); its links: '
                          + ", ".join(sorted(n for n in links if n))[:300])
    roots = _roots(g)
    if len(roots) != 1:
        raise PluginError(f"the gripper URDF {gripper} cannot be composed: it has {len(roots)} root links "
                          f"({', '.join(roots)[:200]}), not one to bolt to the arm")
    moving = [j for j in g.findall("joint") if j.get("type") not in ("fixed", "floating", "planar")]
    if not moving:
        raise PluginError(f"the gripper URDF {gripper} cannot be composed: it has no movable joint (no fingers)")
    link_names = _rename(g, links, "link")
    joint_names = _rename(g, {j.get("name") for j in a.findall("joint")} | {MOUNT_JOINT}, "joint")
    _rename(g, {m.get("name") for m in a.findall("material")}, "material")
    for joint in g.findall("joint"):
        for tag in ("parent", "child"):
            el = joint.find(tag)
            if el is not None and el.get("link") in link_names:
                el.set("link", link_names[el.get("link")])
        mimic = joint.find("mimic")
        if mimic is not None and mimic.get("joint") in joint_names:
            mimic.set("joint", joint_names[mimic.get("joint")])
    _complete_inertials(a)
    _complete_inertials(g)
    dest.mkdir(parents=True, exist_ok=True)
    _copy_meshes(a, arm, dest, "arm")
    _copy_meshes(g, gripper, dest, "gripper")
    for el in list(g):
        if el.tag in ("link", "joint", "material"):
            a.append(el)
    root = link_names.get(roots[0], roots[0])
    joint = ET.SubElement(a, "joint", name=MOUNT_JOINT, type="fixed")
    ET.SubElement(joint, "parent", link=mount)
    ET.SubElement(joint, "child", link=root)
    ET.SubElement(joint, "origin", xyz=" ".join(f"{v:g}" for v in xyz), rpy=" ".join(f"{v:g}" for v in rpy))
    ET.indent(a)
    out = dest / f"{name}.urdf"
    note = f"{Path(arm).name} with {Path(gripper).name} on {mount}".replace("--", "-")
    out.write_text(f'<?xml version="1.0"?>\n<!-- made by l2p-bullet new-arm: {note} -->\n'
                   + ET.tostring(a, encoding="unicode") + "\n", encoding="utf-8")
    return out
