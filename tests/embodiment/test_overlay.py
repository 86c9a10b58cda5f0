"""The video's caption strip: the sentence and the learned progress under the frame (embodiment/overlay.py)."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.embodiment.overlay import BAR_FILL, overlay, progress_at, strip_height


def _frame(h: int = 120, w: int = 160) -> np.ndarray:
    rng = np.random.default_rng(0)
    return rng.integers(0, 255, (h, w, 3), dtype=np.uint8)


def _filled(img: np.ndarray, h: int) -> int:
    return int(np.all(img[h:] == np.array(BAR_FILL, np.uint8), axis=-1).sum())


@pytest.mark.parametrize("shape", [(120, 160), (240, 320), (360, 480), (101, 64)])
def test_the_strip_goes_under_the_frame_and_keeps_every_pixel(shape):
    img = _frame(*shape)
    before = img.copy()
    out = overlay(img, "move A around B", 0.5)
    assert out.shape == (shape[0] + strip_height(shape[0]), shape[1], 3) and out.dtype == np.uint8
    assert out.shape[0] % 8 == 0  # video encoders want it
    assert np.array_equal(out[: shape[0]], before) and np.array_equal(img, before)


def test_the_bar_grows_with_progress_and_the_strip_is_deterministic():
    img, h = _frame(), 120
    fills = [_filled(overlay(img, "move A past B", p), h) for p in (0.0, 0.25, 0.5, 1.0)]
    assert fills[0] == 0 and fills[1] < fills[2] < fills[3]
    assert fills[2] == pytest.approx(fills[3] / 2, rel=0.1)
    assert np.array_equal(overlay(img, "x", 0.3), overlay(img, "x", 0.3))
    assert _filled(overlay(img, "move A past B", None), h) == 0  # no model: "progress n/a", no bar
    assert not np.array_equal(overlay(img, "move A past B", 0.3), overlay(img, "move A around B", 0.3))
    long = overlay(img, "a very long sentence " * 20, 2.0)  # clipped to the width, progress clamped
    assert long.shape == overlay(img, "move A past B", 1.0).shape  # the strip does not grow with the text
    assert _filled(long, h) == fills[3]  # a progress of 2.0 draws the full bar, no more


def test_progress_shown_is_that_of_the_last_frame_at_or_before_the_image():
    t = np.array([0.0, 1 / 30, 2 / 30, 3 / 30])
    assert progress_at([0.0, 0.1, 0.05, 5.0], t, [None, 0.1, 0.2, 0.3]) == [None, 0.3, 0.1, 0.3]
    assert progress_at([0.0], np.array([]), []) == [None]


@pytest.mark.parametrize("sentence", ["Please slide the red block around the green one.",
                                      "Please put the red block between the green block and the blue one."])
def test_a_long_sentence_is_shown_whole(sentence):
    """Issue 26: the strip cut long sentences ("Please slide the red block around the gre..."): a
    sentence that differs only in its last word drew the same strip. It shrinks or wraps now."""
    from PIL import Image, ImageDraw

    from l2p_bullet.embodiment.overlay import MIN_FONT, caption_lines

    img, h = _frame(240, 320), 240
    other = sentence.rsplit(" ", 1)[0] + " box."
    assert not np.array_equal(overlay(img, sentence, 0.5)[h:], overlay(img, other, 0.5)[h:])
    draw = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    lines, font = caption_lines(draw, sentence, 300, 21, 18)
    assert " ".join(lines) == sentence and font.size >= MIN_FONT and len(lines) <= 2
    assert all(draw.textlength(t, font=font) <= 300 for t in lines) and len(lines) * (font.size + 1) <= 21
    short, font = caption_lines(draw, "move A past B", 300, 21, 18)
    assert short == ["move A past B"] and font.size == 18  # a short one keeps the strip's size
