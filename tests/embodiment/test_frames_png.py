"""The frames' PNGs: lossless, readable by Pillow and imageio, the size a flat rendered frame deserves."""

from __future__ import annotations

import io

import numpy as np
from PIL import Image

from l2p_bullet.embodiment.render import png_bytes, write_pngs


def test_a_frame_png_holds_the_image_exactly(tmp_path):
    import imageio.v2 as imageio

    rng = np.random.default_rng(0)
    noisy = rng.integers(0, 256, (37, 48, 3), dtype=np.uint8)
    rgba = np.dstack([noisy, np.full((37, 48), 7, np.uint8)])  # a renderer's RGBA: the alpha is dropped
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(png_bytes(noisy)))), noisy)
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(png_bytes(rgba)))), noisy)
    write_pngs(tmp_path, 5, [noisy, noisy[::-1]])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["0005.png", "0006.png"]
    assert np.array_equal(imageio.imread(tmp_path / "0006.png"), noisy[::-1])


def test_a_flat_frame_compresses_well():
    flat = np.zeros((480, 640, 3), np.uint8)
    flat[:240] = (170, 170, 200)  # sky and table, as a rendered frame mostly is
    flat[240:] = (160, 130, 100)
    assert len(png_bytes(flat)) < 10_000  # raw: 921,600 bytes
