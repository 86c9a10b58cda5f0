"""Gymnasium environments: ``l2p_bullet/Plan2D-v0`` (the 2-D planning problem) and ``l2p_bullet/Arm-v0``
(the same with the Panda in PyBullet executing every move). See docs/envs.md.

Importing this module registers both (idempotent). Gymnasium 0.26-0.29 do it on their own import
through the ``gymnasium.envs`` entry point (pyproject.toml); Gymnasium 1.x dropped that plugin loader,
so there name the module in the id or import it first::

    gymnasium.make("l2p_bullet.envs:l2p_bullet/Plan2D-v0", action="around")
    # or
    import l2p_bullet.envs
    gymnasium.make("l2p_bullet/Plan2D-v0", action="around")
"""

from __future__ import annotations

ENVS: dict[str, str] = {
    "l2p_bullet/Plan2D-v0": "l2p_bullet.envs.plan2d:Plan2DEnv",
    "l2p_bullet/Arm-v0": "l2p_bullet.envs.arm:ArmEnv",
}


def register_envs() -> None:
    """Register the environments with Gymnasium (the ``gymnasium.envs`` entry point's target)."""
    # lazy: gymnasium only for the environments
    import gymnasium

    for env_id, entry_point in ENVS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(id=env_id, entry_point=entry_point)


register_envs()
