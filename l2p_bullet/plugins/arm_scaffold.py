"""``l2p-bullet new-arm``: write a ready-to-install arm plugin package for a user's URDF.

Like ``new-action`` (plugins/scaffold.py): a pyproject declaring the entry point in ``l2p_bullet.arms``, a module
whose ``ARM`` is the :class:`~l2p_bullet.arms.ArmSpec` that ``embodiment.arm_guess`` read and
measured from the URDF (every field written out, to be read and corrected by the author), and a README. Plain
text from templates: no network, no build step. The URDF stays where it is: a path inside pybullet_data is
written relative to it (portable), any other path absolutely (move the description into the package and point
``URDF`` at it to ship it).
"""

from __future__ import annotations

import os
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

from .. import __version__
from ..core.folders import check_writable
from ..embodiment import arm_guess
from ..embodiment.sim.arms import portable_path
from ..embodiment.sim.urdf_check import MAX_URDF_BYTES
from ..embodiment.sim.urdf_check import check_urdf as sim_check_urdf
from ..errors import PluginError, sizes
from . import arms as arm_plugins

DESCRIPTION = "description"
"""The folder inside a package made with ``--gripper`` that holds the composed URDF and its meshes."""
ARM_NAME = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")


@dataclass(frozen=True)
class ArmScaffold:
    """What :func:`scaffold_arm` wrote."""

    root: Path
    module: str
    dist_name: str
    spec: object  # the ArmSpec written into the module
    files: list[Path]


def scaffold_arm(name: str, urdf: str, out: str | Path | None = None, *, tool_link: str | None = None,
                 fingers: list[str] | None = None, gripper: str | None = None, mount: str | None = None,
                 mount_xyz: tuple[float, float, float] = (0.0, 0.0, 0.0),
                 mount_rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> ArmScaffold:
    """Guess and measure the arm in ``urdf`` (``arm_guess.guess``) and write its plugin project into ``out``
    (default ``./l2p-arm-NAME``). Never overwrites; an installed arm of the same name is refused up front.

    With ``gripper``, the arm and the gripper (separate URDFs) are first composed into one URDF inside the package
    (``embodiment.arm_compose``: the gripper bolted to ``mount`` at ``mount_xyz``/``mount_rpy``, every mesh copied
    beside it), which the package ships: it works wherever pip installs it."""
    if not ARM_NAME.match(name):
        raise PluginError(f'"{name}" is not a valid arm name: use lower-case letters and digits joined by hyphens, '
                          'e.g. "my-ur5"')
    if name in arm_plugins.names():
        raise PluginError(f'an arm named "{name}" is already installed (l2p-bullet arms); choose another name')
    module = "l2p_arm_" + name.replace("-", "_")
    dist = "l2p-arm-" + name
    root = Path(out) if out is not None else Path(dist)
    if root.exists() or root.is_symlink():
        raise PluginError(f"{root} already exists; choose another --out (new-arm never overwrites)")
    check_writable(root, "--out", PluginError)
    pkg = root / module
    source = os.path.basename(urdf)
    if gripper is not None:
        from ..embodiment.arm_compose import compose

        source = f"{source} with {os.path.basename(gripper)}"
        for path, role in ((urdf, "arm"), (gripper, "gripper")):
            if not os.path.isfile(path):
                raise PluginError(f"the {role} URDF {path}: no such file")
        try:
            urdf = str(compose(urdf, gripper, pkg / DESCRIPTION, name, mount, mount_xyz, mount_rpy))
        except BaseException:
            shutil.rmtree(root, ignore_errors=True)
            raise
    try:
        check_urdf(urdf)
        spec = arm_guess.guess(name, urdf, tool_link=tool_link, fingers=fingers)
    except Exception as e:  # pybullet.error (imported only in embodiment/sim/): XML it still cannot load
        if gripper is not None:
            shutil.rmtree(root, ignore_errors=True)  # what compose wrote: nothing of a refused arm is left
            if isinstance(e, PluginError):  # named by the files the user gave, not by the removed composition
                raise PluginError(str(e).replace(urdf, f"{source} (composed)")) from None
        if type(e).__module__ != "pybullet":
            raise
        raise PluginError(f"{urdf}: pybullet cannot load this URDF ({e}); its own message, printed above, "
                          "says why") from None
    pkg.mkdir(parents=True, exist_ok=gripper is not None)
    texts = {
        root / "pyproject.toml": _PYPROJECT.format(name=name, module=module, dist=dist, version=__version__)
        + (_PACKAGE_DATA.format(module=module, folder=DESCRIPTION) if gripper is not None else ""),
        pkg / "__init__.py": (_INIT_SHIPPED if gripper is not None else _INIT).format(
            name=name,
            src=_docstring_text(source),
            urdf=_urdf_expr(spec.urdf) if gripper is None else repr(f"{DESCRIPTION}/{name}.urdf"),
            spec=arm_guess.spec_source(spec),
        ),
        root / "README.md": _README.format(
            name=name,
            dist=dist,
            module=module,
            root=root.name,
            urdf=spec.urdf if gripper is None else source,
            near=spec.reach[0],
            far=spec.reach[1],
            mount=spec.mount[0],
            opening=spec.gripper_opening * 100,
            joints=len(spec.arm_joints),
        ),
    }
    for path, text in texts.items():
        path.write_text(text, encoding="utf-8")
    return ArmScaffold(root, module, dist, spec, sorted(texts))


def check_urdf(urdf: str) -> None:
    """A one-line ``PluginError`` for a file that is not a URDF (not XML, or its root is not ``<robot>``),
    said before pybullet tries it: pybullet only prints "Cannot load URDF file" and raises its own error."""
    import xml.etree.ElementTree as ET

    if not urdf.lower().endswith(".urdf") or not os.path.isfile(urdf):
        return  # arm_guess.guess says what is wrong with the name or a missing file
    try:
        if os.path.getsize(urdf) > MAX_URDF_BYTES:
            have, most = sizes(os.path.getsize(urdf), MAX_URDF_BYTES)
            raise PluginError(f"{urdf} is {have}, more than the {most} of a URDF new-arm reads")
        root = ET.parse(urdf).getroot()
    except ET.ParseError as e:
        raise PluginError(f"{urdf} is not a URDF: it is not valid XML ({e})") from None
    except OSError as e:
        raise PluginError(f"cannot read {urdf}: {e.strerror or e}") from None
    if root.tag != "robot":
        raise PluginError(f"{urdf} is not a URDF: its root element is <{root.tag}>, not <robot>")
    sim_check_urdf(urdf)  # one root link, links in bounds: what PyBullet would otherwise crash on


def _docstring_text(text: str) -> str:
    """``text`` (the URDF's file name) as it may stand in the module's docstring: a name holding ``\"\"\"``
    would close the docstring and make the rest of the name code that runs when the plugin is imported,
    and a backslash could make the module a SyntaxError; such characters become ``_``."""
    return re.sub(r"[^\w .,+()-]", "_", text)


def _urdf_expr(path: str) -> str:
    """The Python expression of the URDF's path: relative to pybullet_data when it lies inside it."""
    return repr(portable_path(path))


_PYPROJECT = """\
[build-system]
requires = ["setuptools>=68", "wheel"]
build-backend = "setuptools.build_meta"

[project]
name = "{dist}"
version = "0.1.0"
description = "l2p-bullet arm plugin: {name}"
requires-python = ">=3.11"
dependencies = ["l2p-bullet>={version}"]

# This line is the whole plugin mechanism: l2p-bullet finds arms in this entry-point group. The value names
# the ArmSpec (module:attribute).
[project.entry-points."l2p_bullet.arms"]
{name} = "{module}:ARM"

[tool.setuptools]
packages = ["{module}"]
"""

_INIT = '''"""Arm plugin "{name}" for l2p-bullet, made by `l2p-bullet new-arm` from {src}.

Every field was read from the URDF or measured on it (l2p_bullet/embodiment/arm_guess.py says how): check them,
correct what was guessed wrong, and run `l2p-bullet arms --check` after any change.
"""

from l2p_bullet.arms import ArmSpec

URDF = {urdf}

ARM = {spec}
'''

_PACKAGE_DATA = """
# The composed URDF and its meshes ship inside the package.
[tool.setuptools.package-data]
{module} = ["{folder}/*.urdf", "{folder}/meshes/**/*"]
"""

_INIT_SHIPPED = '''"""Arm plugin "{name}" for l2p-bullet, made by `l2p-bullet new-arm` from {src}.

The arm and its gripper are one URDF in the folder beside this module, with their meshes. Every field was read
from it or measured on it (l2p_bullet/embodiment/arm_guess.py says how): check them, correct what was guessed
wrong, and run `l2p-bullet arms --check` after any change.
"""

import os

from l2p_bullet.arms import ArmSpec

URDF = os.path.join(os.path.dirname(os.path.abspath(__file__)), {urdf})

ARM = {spec}
'''

_README = """\
# {dist}: the arm "{name}" for l2p-bullet

Made by `l2p-bullet new-arm` from `{urdf}`: {joints} arm joints, a gripper that opens {opening:.1f} cm, reaching
the table pointing down {near:.2f}-{far:.2f} m from its base (mounted {mount:.3f} m along x, facing +x).

    {root}/
      pyproject.toml      declares the entry point  [project.entry-points."l2p_bullet.arms"]  {name} = "{module}:ARM"
      {module}/__init__.py  ARM = ArmSpec(...): every field read or measured; correct what is wrong, and set
                          payload (kg) to your arm's rated payload: a URDF does not say it (1 kg until then)

Install it (a path: never the bare name, which would fetch a stranger's package), check it, use it:

    pip install ./{root}
    l2p-bullet arms --check
    l2p-bullet perform "move A around B" --arm {name}
"""
