"""A picture of a 2-D plan: the workspace, the other objects, the mover's footprints along its path, and
the learned progress per path point (plan.png next to plan.json, for a person to check a plan at a glance)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..core.contracts import Plan
from ..core.scene import COLORS, Scene


def plot_plan(plan: Plan, scene: Scene, out: str | Path, footprints: int = 12) -> Path:
    """Write the plot to ``out`` (PNG) and return its path. Headless (Agg backend)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon

    mover = scene.get(plan.mover)
    fig, (ax, axp) = plt.subplots(1, 2, figsize=(10, 4.8), gridspec_kw={"width_ratios": [1.1, 1]})
    ws = scene.workspace
    ax.add_patch(Circle(ws.center, ws.radius, fill=False, ls="--", color="0.5", label="workspace"))
    for o in scene.objects:
        if o.name == plan.mover:
            continue
        ax.add_patch(Polygon(o.footprint(), closed=True, color=COLORS.get(o.color, (0.5, 0.5, 0.5, 1))[:3],
                             alpha=0.9, label=o.name if o.name == plan.anchor else None))
        ax.annotate(o.name, o.xy, ha="center", va="center", color="white", fontsize=9, weight="bold")
    path = np.asarray(plan.path)
    rgb = COLORS.get(mover.color, (0.5, 0.5, 0.5, 1))[:3]
    idx = np.unique(np.linspace(0, len(path) - 1, min(footprints, len(path))).round().astype(int))
    for k, i in enumerate(idx):
        ax.add_patch(Polygon(mover.footprint(path[i]), closed=True, fill=k == len(idx) - 1, color=rgb,
                             alpha=0.25 + 0.75 * k / max(len(idx) - 1, 1), lw=1))
    ax.plot(path[:, 0], path[:, 1], "-", color="k", lw=1)
    way = np.asarray(plan.extra.get("waypoints", path[[0, -1]]), float)
    ax.plot(way[:, 0], way[:, 1], "o", ms=3, color="k")
    ax.annotate(plan.mover, path[0, :2], ha="center", va="center", fontsize=9, weight="bold")
    r = ws.radius * 1.05
    ax.set(xlim=(ws.center[0] - r, ws.center[0] + r), ylim=(ws.center[1] - r, ws.center[1] + r),
           aspect="equal", xlabel="x (m)", ylabel="y (m)",
           title=f"{plan.extra.get('sentence') or f'{plan.mover} {plan.action} {plan.anchor}'} ({plan.planner})")
    axp.plot(np.arange(len(plan.progress)), plan.progress, "-", color=rgb)
    axp.axhline(float(plan.extra.get("threshold", 0.9)), ls=":", color="0.5", label="threshold")
    axp.set(ylim=(-0.02, 1.02), xlabel="path point", ylabel="learned progress",
            title=f"stopped: {plan.stopped}")
    axp.legend(loc="lower right")
    fig.tight_layout()
    out = Path(out)
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return out
