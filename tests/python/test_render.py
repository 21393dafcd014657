# render() and snapshot() through OSMesa, with no display and no libGL in the process.
import os

import numpy as np
import pytest

import cablelab

pytestmark = pytest.mark.skipif(not cablelab.HAS_RENDERER, reason="a build without the UI")


def test_render_is_an_rgba_image_of_the_scene():
    w = cablelab.World.load("hand")
    img = cablelab.render(w, (320, 240))
    assert img.shape == (240, 320, 4) and img.dtype == np.uint8
    assert np.all(img[..., 3] == 255)
    background = np.median(img.reshape(-1, 4), axis=0)
    drawn = np.any(img != background, axis=2).mean()
    assert 0.01 < drawn < 0.9  # something is drawn, not everything


def test_render_follows_the_state():
    w = cablelab.World.load("pulley")
    a = cablelab.render(w, (200, 150))
    assert np.array_equal(a, cablelab.render(w, (200, 150)))  # deterministic
    w.run(2.0)
    assert not np.array_equal(a, cablelab.render(w, (200, 150)))


def test_snapshot_writes_the_rendered_png(tmp_path):
    import matplotlib.image
    w = cablelab.World.load("hexagon")
    path = tmp_path / "h.png"
    cablelab.snapshot(w, path, (160, 120))
    png = (matplotlib.image.imread(path) * 255).round().astype(np.uint8)
    assert np.array_equal(png, cablelab.render(w, (160, 120)))


def test_no_libgl_in_the_process():
    cablelab.render(cablelab.World.load("pulley"), (64, 64))
    with open("/proc/self/maps") as f:
        libs = {os.path.basename(line.split()[-1]) for line in f if ".so" in line}
    assert any(l.startswith("libOSMesa") for l in libs)
    assert not any(l.startswith("libGL.so") or l.startswith("libGLX") for l in libs), libs
