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


def lifted_scene(x=0.0):
    """One box 3 m up and no "view" (the scene's view is then 4 m high at the origin)."""
    return {"name": "lifted", "gravity": [0, 0],
            "bodies": [{"name": "box", "position": [x, 3.0], "mass": 1.0,
                        "shapes": [{"type": "box", "half_size": [0.3, 0.3]}]}]}


def test_render_fits_a_scene_without_a_view_and_takes_a_camera():
    here = cablelab.World.from_dict(lifted_scene())
    gone = cablelab.World.from_dict(lifted_scene(x=500.0))  # the box far out of every view
    size = (160, 120)
    # The scene's own view (y -2..2) misses the box: the same picture as with no box near
    # (below the top strip, where the renderer writes its notes).
    assert np.array_equal(cablelab.render(here, size, view="scene")[24:],
                          cablelab.render(gone, size, view="scene")[24:])
    # The default fit takes it in; so does a camera on it, given either way.
    fitted = cablelab.render(here, size)
    assert not np.array_equal(fitted, cablelab.render(here, size, view="scene"))
    on_box = cablelab.render(here, size, view=((0.0, 3.0), 2.0))
    assert np.array_equal(on_box, cablelab.render(here, size, view={"center": [0, 3], "height": 2}))
    assert not np.array_equal(on_box, cablelab.render(gone, size, view=((0.0, 3.0), 2.0)))
    # The box (0.6 m wide, 60 px/m: 18 px either side) fills the middle of the picture and no
    # more (its name is written below and to the right of it).
    changed = np.any(on_box != cablelab.render(gone, size, view=((0.0, 3.0), 2.0)), axis=2)
    for row, col in [(60, 80), (60, 65), (45, 80), (60, 95)]:
        assert changed[row, col], (row, col)
    for row, col in [(60, 55), (35, 80), (60, 40)]:
        assert not changed[row, col], (row, col)
    with pytest.raises(cablelab.InputError, match="render: view.height: must be positive"):
        cablelab.render(here, size, view=((0, 0), -1))
