"""Arms as data, below planning: what an arm is (:class:`ArmSpec`, the built-in specs), the room its hand
takes beside a block and the range of its wrist (``reach``), and the workspace it gets (``fit``).

Plain numpy and the scene, as robosuite keeps its robot models apart from the simulator: planning, the
up-front checks and the embodiment read one model, and nothing here loads a simulator (measuring an arm in
PyBullet is ``embodiment/arm_measure.py``; finding the installed arms is ``plugins/arms.py``)."""

from .builtin import KUKA_IIWA, PANDA, XARM6
from .fit import fit_scene, fit_workspace
from .spec import ArmSpec, problems

__all__ = ["KUKA_IIWA", "PANDA", "XARM6", "ArmSpec", "fit_scene", "fit_workspace", "problems"]
