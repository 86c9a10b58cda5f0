"""Every command function is named one way (``<name>_cmd``), whatever its click name."""

from __future__ import annotations

import importlib
import pkgutil

import l2p_bullet.commands


def test_every_command_function_is_named_cmd():
    names = {}
    for info in pkgutil.iter_modules(l2p_bullet.commands.__path__, "l2p_bullet.commands."):
        module = importlib.import_module(info.name)
        for command in getattr(module, "COMMANDS", []):
            names[command.name] = command.callback.__name__
    assert {"perform", "plan", "replay", "train", "improve", "score", "recognize"} <= set(names)
    bad = {k: v for k, v in names.items() if not v.endswith("_cmd")}
    assert not bad, f"command functions not named <name>_cmd: {bad}"
