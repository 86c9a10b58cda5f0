"""The caption strip under a video frame: the sentence and the learned progress (the paper's Fig. 7).

A run's video is watched outside the review app too (a file browser, a slide): the strip makes it say
what was asked and how far the action's learned progress model thinks it got, frame by frame. It is
drawn *under* the rendered image, never over it, so no pixel of the scene is hidden, and only on the
video: ``frames/*.png`` stay the raw renders (the review app's blind mode shows those, because the
strip names the action; the determinism tests compare them).

Pure function of its inputs (Pillow's built-in font, no system fonts), so videos stay reproducible.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

MACRO_BLOCK = 8
"""Video encoders want frame sides divisible by this; the strip's height makes the total fit."""

BACKGROUND = (24, 24, 24)
TEXT = (240, 240, 240)
BAR_BACK = (70, 70, 70)
BAR_FILL = (80, 190, 110)


@lru_cache(maxsize=8)
def _font(size: int):
    # lazy: Pillow only when a frame or plot is drawn
    from PIL import ImageFont

    return ImageFont.load_default(size=size)


def strip_height(height: int) -> int:
    """Height of the strip under an image ``height`` pixels high: about a fifth, total a multiple of 8."""
    h = max(28, round(height * 0.2))
    return h + (-(height + h)) % MACRO_BLOCK


MIN_FONT = 8
"""Smallest caption font (pixels): still legible in a 320-pixel-wide video."""


def _fit(draw, text: str, font, width: int) -> str:
    """``text``, shortened with an ellipsis until it fits ``width`` pixels."""
    if draw.textlength(text, font=font) <= width:
        return text
    while text and draw.textlength(text + "...", font=font) > width:
        text = text[:-1]
    return text + "..."


def _two_lines(draw, text: str, font, width: int) -> list[str] | None:
    """``text`` broken at a space into two lines that each fit ``width`` pixels, or None."""
    words = text.split()
    for k in range(len(words) - 1, 0, -1):  # the longest first line that fits
        first, second = " ".join(words[:k]), " ".join(words[k:])
        if draw.textlength(first, font=font) <= width:
            return [first, second] if draw.textlength(second, font=font) <= width else None
    return None


def caption_lines(draw, text: str, width: int, height: int, size: int) -> tuple[list[str], object]:
    """The sentence's lines and font, in ``width`` x ``height`` pixels: one line at the strip's ``size``
    if it fits, else one line at a smaller size (down to :data:`MIN_FONT`), else two lines at the largest
    size that fits them; an ellipsis only when even two lines of the smallest font cannot hold it.
    (A polite sentence, "Please slide the red block around the green one.", needs two lines at 320 px.)"""
    for s in range(size, MIN_FONT - 1, -1):
        font = _font(s)
        if draw.textlength(text, font=font) <= width:
            return [text], font
    for s in range(min(size, (height - 1) // 2 - 1), MIN_FONT - 1, -1):
        font = _font(s)
        lines = _two_lines(draw, text, font, width)
        if lines:
            return lines, font
    font = _font(MIN_FONT)
    return [_fit(draw, text, font, width)], font


def overlay(image: np.ndarray, sentence: str | None, progress: float | None) -> np.ndarray:
    """``image`` (H, W, 3) uint8 with a strip under it: ``sentence`` and a bar for ``progress`` in [0, 1].

    ``progress`` None (no model scored the run) writes "progress n/a" and no bar. Returns a new
    (H + strip_height(H), W, 3) uint8 array; ``image`` is not modified.
    """
    # lazy: Pillow only when a frame or plot is drawn
    from PIL import Image, ImageDraw

    img = np.asarray(image)
    if img.ndim != 3 or img.shape[2] < 3:
        raise ValueError(f"expected an (H, W, 3) image, got shape {img.shape}")
    h, w = img.shape[:2]
    sh = strip_height(h)
    strip = Image.new("RGB", (w, sh), BACKGROUND)
    draw = ImageDraw.Draw(strip)
    pad = max(3, sh // 10)
    font = _font(max(9, (sh - 3 * pad) // 2))
    line = int(getattr(font, "size", 11)) + 1
    y = pad + line + pad // 2
    lines, cfont = caption_lines(draw, sentence or "", w - 2 * pad, y - pad, int(getattr(font, "size", 11)))
    step = int(getattr(cfont, "size", 11)) + 1
    for i, text in enumerate(lines):
        draw.text((pad, pad + i * step), text, fill=TEXT, font=cfont)
    if progress is None or not np.isfinite(progress):
        draw.text((pad, y), "progress n/a", fill=TEXT, font=font)
    else:
        p = float(np.clip(progress, 0.0, 1.0))
        label = f"{p:.2f}"
        lw = int(draw.textlength("0.00", font=font)) + pad
        x0, x1, y1 = pad, w - pad - lw, min(sh - pad, y + line)
        draw.rectangle((x0, y, x1, y1), fill=BAR_BACK)
        if p > 0:
            draw.rectangle((x0, y, x0 + round((x1 - x0) * p), y1), fill=BAR_FILL)
        draw.text((x1 + pad, y), label, fill=TEXT, font=font)
    return np.concatenate([img[:, :, :3].astype(np.uint8), np.asarray(strip, dtype=np.uint8)], axis=0)


def panel_caption(image: np.ndarray, text: str) -> np.ndarray:
    """``image`` with a one-line caption strip under it (a contact sheet's panel: its time, its clause);
    the text shrinks, then wraps, to fit (caption_lines). Returns a new array; ``image`` is not modified."""
    from PIL import Image, ImageDraw

    img = np.asarray(image)[:, :, :3].astype(np.uint8)
    h, w = img.shape[:2]
    sh = max(18, round(h * 0.1))
    strip = Image.new("RGB", (w, sh), BACKGROUND)
    draw = ImageDraw.Draw(strip)
    pad = max(2, sh // 8)
    lines, font = caption_lines(draw, text, w - 2 * pad, sh - 2 * pad, max(MIN_FONT, sh - 2 * pad - 2))
    step = int(getattr(font, "size", 11)) + 1
    top = max(0, (sh - step * len(lines)) // 2)
    for i, line in enumerate(lines):
        draw.text((pad, top + i * step), line, fill=TEXT, font=font)
    return np.concatenate([img, np.asarray(strip, dtype=np.uint8)], axis=0)


def progress_at(times: list[float], frame_times: np.ndarray, frame_progress: list[float | None]) -> list[float | None]:
    """The progress shown at each image time: that of the last trajectory frame at or before it."""
    if not len(frame_times):
        return [None] * len(times)
    idx = np.clip(np.searchsorted(frame_times, np.asarray(times, float) + 1e-6, side="right") - 1,
                  0, len(frame_times) - 1)
    return [frame_progress[i] for i in idx]
