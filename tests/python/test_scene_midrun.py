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


def spool_and_weight(kind, side, speed):
    """A servo spool winding a weight 6 m below through an eyelet: a square polygon spool the rope
    is tied to (0.25 turns authored) or a round drum end (0.5 turns authored)."""
    x = 0.3 if side == "left" else -0.3
    if kind == "polygon":
        start = {"body": "spool", "point": [-0.05, -0.05]}
        pulleys = [{"type": "polygon", "body": "spool", "side": side, "turns": 0.25}]
    else:
        start = {"body": "spool", "radius": 0.05, "side": side, "turns": 0.5}
        pulleys = []
    pulleys.append({"type": "point", "point": [x, 0.0], "side": "threaded"})
    return {"bodies": [{"name": "spool", "mass": 0.5, "shapes": [
                           {"type": "box", "half_size": [0.05, 0.05], "sensor": True}]},
                       {"name": "weight", "position": [x, -6.0],
                        "shapes": [{"type": "circle", "radius": 0.04}]}],
            "joints": [{"type": "revolute", "name": "axle", "body_b": "spool",
                        "servo": {"kp": 0.0, "kd": 50.0, "max_force": 1e4, "speed": speed}}],
            "cables": [{"name": "rope", "start": start, "end": {"body": "weight"},
                        "pulleys": pulleys}]}


@pytest.mark.parametrize("kind", ["polygon", "circle"])
@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("turns", [0.3, 2, 5, 11])
def test_without_its_history_the_scene_keeps_the_turns_wound_since(kind, side, turns):
    """The turns written are the ones wound now, not the authored ones: built from 0.25 authored
    turns the rope started 4.4 m short of its rest length after 11 turns and the weight fell."""
    speed = 6.0 if side == "left" else -6.0  # the way that winds
    w = cablelab.World.from_dict(spool_and_weight(kind, side, speed))
    w.run(time=turns * 2 * math.pi / speed * np.sign(speed))
    d = w.to_dict(current=True)
    del d["history"]
    written = d["cables"][0]["pulleys"][0] if kind == "polygon" else d["cables"][0]["start"]
    authored = 0.25 if kind == "polygon" else 0.5
    assert written["turns"] > authored + turns - 0.5  # about the turns the servo wound on
    f = cablelab.World.from_dict(d)
    rest = w.cable_parameters(0)["rest_length"]
    assert f.cable_parameters(0)["rest_length"] == rest
    # Poses go through Box2D's floats: the lengths agree to their rounding. A drum's came back
    # 5 mm short (its last step's turn, 0.1 rad at 6 rad/s and 60 Hz, r = 5 cm): the turns
    # written were the last re-selection's, before the step's end.
    assert abs(f.cable_lengths()[0] - w.cable_lengths()[0]) < 1e-6
    for _ in range(round(1.0 / w.dt)):
        w.step()
        f.step()
    assert abs(f.cable_lengths()[0] - w.cable_lengths()[0]) < 1e-4
    assert f.cable_tensions()[0] > 0  # the weight hangs on the rope, not falling slack


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("paid", [0.4, 1.5, 2.9])
def test_a_drum_paying_out_is_rebuilt_at_its_length(side, paid):
    """A round drum wound 3 turns that pays `paid` turns out: the turns written are the ones left
    at the step's end, so the rebuilt rope has the running one's length."""
    speed = -4.0 if side == "left" else 4.0  # the way that pays out
    d0 = spool_and_weight("circle", side, speed)
    d0["cables"][0]["start"]["turns"] = 3.0
    w = cablelab.World.from_dict(d0)
    w.run(time=paid * 2 * math.pi / abs(speed))
    d = w.to_dict(current=True)
    del d["history"]
    assert abs(d["cables"][0]["start"]["turns"] - (3.0 - paid)) < 0.1
    f = cablelab.World.from_dict(d)
    assert abs(f.cable_lengths()[0] - w.cable_lengths()[0]) < 1e-6
