# A scene written mid-run (issue 39, item 1): World.from_dict(w.to_dict(current=True)) continues bit
# for bit, joints included (docs/scene-format.md, "Scenes written mid-run"); without its history the
# scene still keeps the joint coordinates the servo targets refer to, time and step count.
import json
import math

import numpy as np
import pytest

import cablelab
from test_state import drive, fingerprint


def servo_moves(w, steps, start=0):
    """Time-varying servo targets (and forces, gravity) for `steps` steps from step `start`."""
    for k in range(start, start + steps):
        drive(w, k)


@pytest.mark.parametrize("scene", ["hand", "pulley", "hexagon", "winch"])
def test_a_fork_through_to_dict_current_steps_bit_for_bit(scene):
    w = cablelab.World.load(scene)
    servo_moves(w, 40)
    d = w.to_dict(current=True)
    forks = [cablelab.World.from_dict(d),
             cablelab.World.from_dict(json.loads(json.dumps(d)))]  # as a file would keep it
    for f in forks:
        assert fingerprint(f) == fingerprint(w)
        assert np.array_equal(f.joint_values(), w.joint_values())
        assert np.array_equal(f.servo_targets(), w.servo_targets())
        assert (f.time, f.step_count) == (w.time, 40)
    for k in range(40, 100):
        for x in [w] + forks:
            drive(x, k)
        for f in forks:
            assert fingerprint(f) == fingerprint(w), (scene, k)


def test_the_hand_after_a_second_of_servo_moves_continues_exactly():
    """The issue's case: joint values were re-zeroed at the present pose while the servo targets
    stayed absolute, so the box ended 6 cm off a second later."""
    w = cablelab.World.load("hand")
    steps = round(1.0 / w.dt)
    servo_moves(w, steps)
    assert np.abs(w.joint_values()).max() > 1e-3  # the joints moved: re-zeroing would show
    f = cablelab.World.from_dict(w.to_dict(current=True))
    assert np.array_equal(f.joint_values(), w.joint_values())
    servo_moves(w, steps, start=steps)
    servo_moves(f, steps, start=steps)
    assert np.array_equal(f.body_states(), w.body_states())


def test_without_its_history_the_scene_keeps_joints_time_and_steps():
    w = cablelab.World.load("hand")
    servo_moves(w, 60)
    d = w.to_dict(current=True)
    del d["history"]
    assert d["time"] == w.time and d["step_count"] == 60
    assert [j.get("value", 0.0) for j in d["joints"]] == list(w.joint_values())
    f = cablelab.World.from_dict(d)
    assert (f.time, f.step_count) == (w.time, 60)
    assert np.allclose(f.joint_values(), w.joint_values(), atol=2e-6, rtol=0)  # Box2D's floats
    assert np.array_equal(f.servo_targets(), w.servo_targets())
    # Box2D's contacts and the warm starts start afresh: close, not exact.
    servo_moves(w, 60, start=60)
    servo_moves(f, 60, start=60)
    assert np.allclose(f.body_states()[:, :2], w.body_states()[:, :2], atol=2e-3)


def test_a_scene_edited_after_it_was_written_is_refused():
    w = cablelab.World.load("hand")
    servo_moves(w, 10)
    d = w.to_dict(current=True)
    d["joints"][0]["value"] = 0.2
    with pytest.raises(cablelab.InputError, match=r"dict: history: does not lead to the "
                                                  r"scene's joints"):
        cablelab.World.from_dict(d)
    del d["history"]
    assert math.isclose(cablelab.World.from_dict(d).joint_values()[0], 0.2, abs_tol=1e-6)


def test_a_history_row_that_is_no_input_is_refused():
    w = cablelab.World.load("pulley")
    servo_moves(w, 3)
    d = w.to_dict(current=True)
    d["history"]["inputs"][0] = [99, 0, 1, 0, 0, 0, 0]
    with pytest.raises(cablelab.InputError, match=r"history.inputs\[0\]: is not a World input"):
        cablelab.World.from_dict(d)
    d["history"]["inputs"][0] = [0, 1]
    with pytest.raises(cablelab.InputError, match=r"history.inputs\[0\]: must be a list of 7"):
        cablelab.World.from_dict(d)
