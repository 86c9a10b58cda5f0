"""A picture of a 2-D plan: the workspace, the other objects, the mover's footprints along its path, and
the learned progress per path point (plan.png next to plan.json, for a person to check a plan at a glance).

Drawn with Pillow rather than matplotlib: importing matplotlib took 1.1-1.5 s of every ``l2p-bullet plan``
process on the development machine, Pillow 0.1 s. The picture is drawn at twice its size and scaled
down, which smooths its edges.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..core.contracts import Plan
from ..core.scene import Scene, SceneObject

SCALE = 2  # drawn at twice the size, then scaled down (anti-aliasing)
SIZE = (900, 450)


def _rgb(o: SceneObject, alpha: float = 1.0) -> tuple[int, int, int, int]:
    r, g, b, _ = o.rgba
    return int(r * 255), int(g * 255), int(b * 255), int(alpha * 255)


def plot_plan(plan: Plan, scene: Scene, out: str | Path, footprints: int = 12) -> Path:
    """Write the plot to ``out`` (PNG) and return its path."""
    # lazy: Pillow only when a frame or plot is drawn
    from PIL import Image, ImageDraw, ImageFont

    w, h = SIZE[0] * SCALE, SIZE[1] * SCALE
    img = Image.new("RGBA", (w, h), (255, 255, 255, 255))
    layer = Image.new("RGBA", (w, h), (0, 0, 0, 0))  # translucent footprints, composited once
    draw, over = ImageDraw.Draw(img), ImageDraw.Draw(layer)
    font = ImageFont.load_default(size=13 * SCALE)
    small = ImageFont.load_default(size=11 * SCALE)

    # --- left: the table seen from above ---------------------------------------------------------------
    ws = scene.workspace
    r = ws.radius * 1.05
    box = (60 * SCALE, 40 * SCALE, 410 * SCALE, 390 * SCALE)  # square plot area (pixels)
    px_per_m = (box[2] - box[0]) / (2 * r)

    def to_px(xy: np.ndarray) -> list[tuple[float, float]]:
        xy = np.asarray(xy, float).reshape(-1, 2)
        x = box[0] + (xy[:, 0] - (ws.center[0] - r)) * px_per_m
        y = box[3] - (xy[:, 1] - (ws.center[1] - r)) * px_per_m
        return list(zip(x.tolist(), y.tolist(), strict=True))

    draw.rectangle(box, outline=(0, 0, 0, 255), width=SCALE)
    for arc in ws.outline(96):  # the disk's circle (97 points), or with an arm's reach ring the region's arcs
        pts = to_px(arc)
        for a, b in zip(pts[0::2], pts[1::2], strict=False):  # dashed
            draw.line([a, b], fill=(128, 128, 128, 255), width=SCALE)
    for o in scene.objects:
        if o.name == plan.mover:
            continue
        draw.polygon(to_px(o.footprint()), fill=_rgb(o, 0.9))
        (cx, cy), = to_px(o.xy)
        draw.text((cx, cy), o.name, fill=(255, 255, 255, 255), font=small, anchor="mm")
    mover = scene.get(plan.mover)
    path = np.asarray(plan.path)
    idx = np.unique(np.linspace(0, len(path) - 1, min(footprints, len(path))).round().astype(int))
    for k, i in enumerate(idx):
        alpha = 0.25 + 0.75 * k / max(len(idx) - 1, 1)
        last = k == len(idx) - 1
        over.polygon(to_px(mover.footprint(path[i])), fill=_rgb(mover, 0.5) if last else None,
                     outline=_rgb(mover, alpha), width=SCALE)
    img = Image.alpha_composite(img, layer)
    draw = ImageDraw.Draw(img)
    draw.line(to_px(path[:, :2]), fill=(0, 0, 0, 255), width=SCALE)
    way = np.asarray(plan.extra.get("waypoints", path[[0, -1]]), float)
    for x, y in to_px(way[:, :2]):
        draw.ellipse((x - 3 * SCALE, y - 3 * SCALE, x + 3 * SCALE, y + 3 * SCALE), fill=(0, 0, 0, 255))
    (sx, sy), = to_px(path[0, :2])
    draw.text((sx, sy - 10 * SCALE), plan.mover, fill=(0, 0, 0, 255), font=small, anchor="mm")
    title = f"{plan.extra.get('sentence') or f'{plan.mover} {plan.action} {plan.anchor}'} ({plan.planner})"
    draw.text(((box[0] + box[2]) / 2, 20 * SCALE), title, fill=(0, 0, 0, 255), font=font, anchor="mm")
    draw.text(((box[0] + box[2]) / 2, 425 * SCALE), "x (m)", fill=(0, 0, 0, 255), font=small, anchor="mm")
    draw.text((box[0] - 6 * SCALE, box[1] - 4 * SCALE), "y (m)", fill=(0, 0, 0, 255), font=small, anchor="rb")
    for t in (-0.2, 0.0, 0.2):
        (tx, ty), = to_px([t + ws.center[0], t + ws.center[1]])
        draw.text((tx, box[3] + 8 * SCALE), f"{t:+.1f}", fill=(60, 60, 60, 255), font=small, anchor="mt")
        draw.text((box[0] - 6 * SCALE, ty), f"{t:+.1f}", fill=(60, 60, 60, 255), font=small, anchor="rm")

    # --- right: learned progress along the path -------------------------------------------------------
    pbox = (500 * SCALE, 40 * SCALE, 880 * SCALE, 390 * SCALE)
    draw.rectangle(pbox, outline=(0, 0, 0, 255), width=SCALE)
    prog = np.asarray(plan.progress, float).reshape(-1)
    n = max(len(prog) - 1, 1)

    def p_px(i: np.ndarray, v: np.ndarray) -> list[tuple[float, float]]:
        x = pbox[0] + np.asarray(i, float) / n * (pbox[2] - pbox[0])
        y = pbox[3] - (np.asarray(v, float) + 0.02) / 1.04 * (pbox[3] - pbox[1])
        return list(zip(x.tolist(), y.tolist(), strict=True))

    threshold = float(plan.extra.get("threshold", 0.9))
    (x0, ty), (x1, _) = p_px([0, n], [threshold, threshold])
    for a in np.arange(x0, x1, 12 * SCALE):  # dotted
        draw.line([(a, ty), (min(a + 5 * SCALE, x1), ty)], fill=(128, 128, 128, 255), width=SCALE)
    draw.text((x1 - 4 * SCALE, ty + 4 * SCALE), "threshold", fill=(100, 100, 100, 255), font=small, anchor="ra")
    if len(prog) > 1:
        draw.line(p_px(np.arange(len(prog)), prog), fill=_rgb(mover), width=2 * SCALE)
    for v in (0.0, 0.5, 1.0):
        (_, vy), = p_px([0], [v])
        draw.text((pbox[0] - 6 * SCALE, vy), f"{v:.1f}", fill=(60, 60, 60, 255), font=small, anchor="rm")
    draw.text(((pbox[0] + pbox[2]) / 2, 20 * SCALE), f"stopped: {plan.stopped}", fill=(0, 0, 0, 255), font=font,
              anchor="mm")
    draw.text(((pbox[0] + pbox[2]) / 2, 425 * SCALE), f"path point (0-{len(prog) - 1})", fill=(0, 0, 0, 255),
              font=small, anchor="mm")
    draw.text((pbox[0] - 40 * SCALE, 30 * SCALE), "learned progress", fill=(0, 0, 0, 255), font=small, anchor="lm")

    out = Path(out)
    img.convert("RGB").resize(SIZE, Image.Resampling.LANCZOS).save(out, format="PNG", optimize=False)
    return out
