"""The physical signature of a manner of motion (l2p_bullet/manners), checked on the executed frames.

The action's rule judge says whether the block went *where* the words say; this says whether it went
*how* the verb says, from trajectory.json's frames (the simulated world, not the plan):

- on-table (slide): the moved block stays within :data:`ON_TABLE_M` of resting on the table all along;
- lifted (carry): it rises at least :data:`LIFT_M` off the table and is set down again at the end (the
  1 mm rule for every other block, applied to every run, says it touched nothing on the way);
- no-grasp (push): no frame holds it (no constraint) and the fingers never open to close on it.
"""

from __future__ import annotations

import numpy as np

from .base import Verdict

ON_TABLE_M = 0.003
LIFT_M = 0.02
CLOSED_M = 0.001  # the fingers' gap (m) above which they count as opened


def signature_verdict(signature: str, frames: list[dict], mover: str, rest: float) -> Verdict:
    """Whether ``frames`` show ``signature`` for object ``mover``, whose reference point stands ``rest`` metres
    above the table when it rests on it (``SceneObject.rest``: a cube's half side, a box's or cylinder's half
    height, a mesh's centre of mass; a block's side is no height for a flat box or a tall cylinder)."""
    z = np.array([f["poses"][mover][2] for f in frames], float) - rest
    if signature == "on-table":
        worst = float(np.abs(z).max()) if len(z) else 0.0
        ok = worst <= ON_TABLE_M
        return Verdict(ok, 1.0 if ok else 0.0, f"stayed within {worst * 1000:.1f} mm of the table"
                       + ("" if ok else f" (more than {ON_TABLE_M * 1000:.0f} mm: not a slide)"), "manner")
    if signature == "lifted":
        top, end = (float(z.max()), float(abs(z[-1]))) if len(z) else (0.0, 0.0)
        ok = top >= LIFT_M and end <= ON_TABLE_M
        why = f"lifted {top * 100:.1f} cm, set down {end * 1000:.1f} mm off the table"
        if top < LIFT_M:
            why += f" (a carry lifts at least {LIFT_M * 100:.0f} cm)"
        elif end > ON_TABLE_M:
            why += " (not set down)"
        return Verdict(ok, 1.0 if ok else 0.0, why, "manner")
    if signature == "no-grasp":
        held = sum(1 for f in frames if f.get("grasped") == mover)
        opened = max((float((f.get("gripper") or {}).get("opening_m") or 0.0) for f in frames), default=0.0)
        ok = held == 0 and opened <= CLOSED_M
        why = "never grasped, fingers closed" if ok else (
            f"held in {held} frames" if held else f"the fingers opened {opened * 1000:.1f} mm")
        return Verdict(ok, 1.0 if ok else 0.0, why, "manner")
    raise ValueError(f"unknown manner signature {signature!r}")


def manner_verdict(verdict: dict, manner, frames: list[dict], mover: str, rest: float) -> dict:
    """The action's verdict with ``manner``'s (a MannerSpec) physical signature checked on the executed
    ``frames``. A slide's verdict gains nothing when its block stayed on the table (its files are as they
    were before manners)."""
    sig = signature_verdict(manner.signature, frames, mover, rest)
    if manner.name == "slide" and sig.success:
        return verdict
    return with_signature(verdict, manner.name, sig)


def with_signature(verdict: dict, manner: str, signature: Verdict) -> dict:
    """The action's verdict with the manner's: failed when the signature fails (``manner`` says which)."""
    out = verdict | {"manner": {"name": manner, **signature.to_dict()}}
    if not signature.success:
        out["success"] = False
        out["reason"] = f"{verdict.get('reason', '')}; but {manner}: {signature.reason}".lstrip("; ")
    return out
