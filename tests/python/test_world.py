# World from Python: stepping, state arrays, forces, servos, cables, dict round trips, threads.
import math
import threading
import time

import numpy as np
import pytest

import cablelab


def free_body_scene(n=1, gravity=(0.0, 0.0)):
    """n unit-mass discs in a row, no cables, no joints."""
    return {"name": "free", "gravity": list(gravity), "dt": 0.01, "substeps": 1,
            "bodies": [{"name": f"b{i}", "position": [3.0 * i, 0.0], "mass": 1.0,
                        "shapes": [{"type": "circle", "radius": 0.5}]} for i in range(n)]}


def test_module_is_the_build():
    assert "/python/cablelab/" in cablelab._core.__file__


def test_defaults_are_the_scenes_dt_and_substeps():
    a, b = cablelab.World.load("hand"), cablelab.World.load("hand")
    for _ in range(10):
        a.step()
        b.step(dt=a.dt, substeps=a.substeps)
    assert a.time == pytest.approx(10 * a.dt, rel=1e-12)
    assert np.array_equal(a.body_states(), b.body_states())
    assert a.step_count == 10


def test_run_equals_python_loop():
    a, b = cablelab.World.load("hexagon"), cablelab.World.load("hexagon")
    a.run(steps=50)
    for _ in range(50):
        b.step()
    assert np.array_equal(a.body_states(), b.body_states())
    assert a.run(time=0) is None


def test_body_states_layout_and_out_argument():
    w = cablelab.World.from_dict(free_body_scene(3))
    s = w.body_states()
    assert s.shape == (3, 6) and s.dtype == np.float64
    assert np.array_equal(s[:, 0], [0, 3, 6])
    out = np.full((3, 6), np.nan)
    assert w.body_states(out=out) is out
    assert np.array_equal(out, s)
    with pytest.raises(cablelab.InputError):
        w.body_states(out=np.zeros((2, 6)))


def test_set_body_state_round_trip_at_float_precision():
    w = cablelab.World.from_dict(free_body_scene(2))
    state = [1.25, -0.5, 0.3, 2.0, -1.0, 0.7]
    w.set_body_state("b1", state)
    assert np.array_equal(w.body_state(1), np.float32(state).astype(np.float64))  # Box2D keeps floats
    states = w.body_states()
    states[0, :2] = (-4.0, 2.0)
    w.set_body_states(states)
    assert np.array_equal(w.body_states(), states)


def test_free_flight_under_gravity_is_ballistic():
    w = cablelab.World.from_dict(free_body_scene(1, gravity=(0.0, -9.81)))
    w.set_body_state(0, [0, 0, 0, 1.0, 5.0, 0])
    w.run(steps=100)
    t = w.time
    x, y, _, vx, vy, _ = w.body_state(0)
    # a body nothing acts on but gravity flies by the trapezoid rule: the exact parabola (Box2D's
    # semi-implicit Euler alone would put y g h t / 2 = 0.05 m low)
    assert vy == pytest.approx(5.0 - 9.81 * t, abs=1e-5)
    assert y == pytest.approx(5.0 * t - 0.5 * 9.81 * t * t, abs=1e-4)
    assert x == pytest.approx(t, abs=1e-5)


def test_apply_force_lasts_one_step_and_makes_torque_off_centre():
    w = cablelab.World.from_dict(free_body_scene(1))
    w.apply_force(0, (2.0, 0.0))
    w.step()
    w.step()  # no force this time
    assert w.body_state(0)[3] == pytest.approx(2.0 * 0.01, rel=1e-6)  # F/m h, once
    w2 = cablelab.World.from_dict(free_body_scene(1))
    w2.apply_force("b0", (0.0, 1.0), point=(0.5, 0.0))
    w2.step()
    inertia = 0.5 * 1.0 * 0.5 ** 2  # disc
    assert w2.body_state(0)[5] == pytest.approx(0.5 * 1.0 / inertia * 0.01, rel=1e-5)


def test_pulley_conserves_length_and_energy():
    w = cablelab.World.load("pulley")
    l0, e0 = w.cable_lengths()[0], w.energy()
    rec = w.run(2.0, record=True)
    assert np.abs(rec["cables"][:, 0, 0] - l0).max() < 1e-3
    v = w.body_states()[:, 3:5]
    kinetic = 0.5 * (w.to_dict()["bodies"][0]["mass"] * v[0] @ v[0] + w.to_dict()["bodies"][1]["mass"] * v[1] @ v[1])
    assert kinetic > 10
    assert abs(w.energy() - e0) < 0.02 * kinetic  # first-order integrator: O(h) drift


def test_cable_paths_are_wraps_plus_anchors():
    w = cablelab.World.load("hexagon")
    w.run(1.0)
    for i, path in enumerate(w.cable_paths()):
        assert path.shape == (int(w.cable_wraps()[i]) + 2, 2)
        length = np.linalg.norm(np.diff(path, axis=0), axis=1).sum()
        assert length == pytest.approx(w.cable_lengths()[i], rel=1e-12)
    assert np.array_equal(w.cable_path("cable" if "cable" in w.cable_names else 0), w.cable_paths()[0])
    assert np.array_equal(w.wrap_points(0), w.cable_paths()[0][1:-1])


def test_cable_parameters_are_live():
    w = cablelab.World.load("pulley")  # one rigid cable
    w.run(0.5)
    before = w.cable_parameters("cable")
    assert before["stiffness"] == 0 and w.cable_tensions()[0] > 0
    rest = before["rest_length"] + 0.5
    w.set_cable_parameters("cable", rest_length=rest)  # 0.5 m of slack: both bodies fall freely
    assert w.cable_parameters("cable") == dict(before, rest_length=rest)
    w.run(0.1)
    assert w.cable_tensions()[0] == 0 and w.cable_lengths()[0] < rest
    w.run(1.0)  # taut again at the new rest length
    assert w.cable_tensions()[0] > 0
    assert w.cable_lengths()[0] == pytest.approx(rest, abs=1e-3)
    with pytest.raises(cablelab.InputError):
        w.set_cable_parameters("cable", rest_length=-1)
    assert w.cable_parameters("cable")["rest_length"] == rest


def test_a_rope_hauled_into_its_pulley_pays_out():
    # A kinematic hook hauls a 10 kg load up to a pulley at 5 m/s and keeps going: the load stays
    # there, the rope pays out what the hook hauls (its rest length follows) and the World says so.
    box = [{"type": "box", "half_size": [0.05, 0.05], "sensor": True}]
    w = cablelab.World.from_dict({
        "name": "haul", "dt": 1 / 60,
        "bodies": [{"name": "hook", "type": "kinematic", "position": [-1, -0.5], "velocity": [-5, 0],
                    "shapes": box},
                   {"name": "load", "position": [1.5, -2], "mass": 10, "fixed_rotation": True,
                    "shapes": box}],
        "cables": [{"name": "rope", "start": {"body": "hook", "point": [0, 0]},
                    "end": {"body": "load", "point": [0, 0]},
                    "pulleys": [{"type": "point", "body": "world", "point": [1.5, 0],
                                 "side": "threaded"}]}]})
    length0 = w.cable_lengths()[0]
    w.run(2.0)
    assert w.body_states()[1, 1] == pytest.approx(-0.01, abs=2e-3)  # held 1 cm under the pulley
    assert w.cable_tensions()[0] == pytest.approx(98.1, rel=1e-3)
    paid = w.cable_paid_out()[0]
    assert paid == pytest.approx(w.cable_lengths()[0] - length0, abs=1e-4)
    assert w.cable_parameters("rope")["rest_length"] == pytest.approx(length0 + paid, abs=1e-9)
    assert any("'rope': pays out" in m for m in w.warnings)


def test_a_point_pulley_on_the_wrong_side_is_said_at_load():
    # The route goes over the point (side left); "right" left it out of the path with no word.
    def scene(side):
        return {"bodies": [{"name": "a", "position": [-1, -1]}, {"name": "b", "position": [1, -1]}],
                "cables": [{"name": "rope", "start": {"body": "a"}, "end": {"body": "b"},
                            "pulleys": [{"type": "point", "point": [0, 1], "side": side}]}]}
    wrong = cablelab.World.from_dict(scene("right"))
    assert wrong.warnings == [
        "cable 'rope': pulley 0 (a point on 'world') is left out: from the point before it to the "
        "one after, the rope passes to its left, not its right as \"side\": \"right\" says, so it "
        "runs straight past it (2 m away) and does not use it until the rope reaches it "
        "(\"side\": \"left\" takes it from the start)"]
    assert cablelab.World.from_dict(scene("left")).warnings == []
    for name in ["membrane", "pulley", "tackle", "ballast", "hexagon", "winch", "wheel"]:
        assert cablelab.World.load(name).warnings == [], name


def test_a_winch_says_when_its_weight_reaches_the_drum_before_it_stalls():
    w = cablelab.World.load("winch", r=0.2)  # 3.4 m at 0.4 m/s: there at 8.5 s
    w.run(time=8.0)
    assert w.warnings == []
    w.run(time=1.0)
    assert len(w.warnings) == 1
    assert w.warnings[0].startswith("cable 'cable': the weight 'weight' reached the drum 'drum' "
                                    "at t = 8.5")


def test_run_record_has_the_joints():
    a, b = cablelab.World.load("hand"), cablelab.World.load("hand")
    rec = a.run(steps=20, record=True)
    b.run(steps=20)
    assert rec["joints"].shape == (21, len(a.joint_names), 2)
    assert np.array_equal(rec["joints"][-1, :, 0], b.joint_values())
    assert np.array_equal(rec["joints"][-1, :, 1], b.joint_speeds())
    assert rec["joint_names"] == a.joint_names


def test_hand_joints_and_servo_targets():
    w = cablelab.World.load("hand")
    assert w.joint_names[:6] == list(cablelab.HAND_JOINT_NAMES)
    assert np.abs(w.joint_values()[:6]).max() < 1e-6  # the pinch pose is q = 0
    target = w.servo_targets()
    target[1] = 0.1  # top slide, m
    w.set_servo_targets(target)
    w.run(1.0)
    assert w.servo_targets()[1] == 0.1
    assert w.joint_values()[1] == pytest.approx(0.1, abs=0.02)
    w.set_servo_target("top_slide", 0.0)
    assert w.servo_targets()[1] == 0.0


def test_to_dict_round_trip_gives_the_same_trajectory():
    a = cablelab.World.load("hand")
    b = cablelab.World.from_dict(a.to_dict())
    a.run(steps=30)
    b.run(steps=30)
    assert np.array_equal(a.body_states(), b.body_states())


def test_to_dict_current_continues_from_the_present_state():
    a = cablelab.World.load("pulley")
    a.run(0.5)
    b = cablelab.World.from_dict(a.to_dict(current=True))
    assert np.allclose(b.body_states(), a.body_states(), atol=1e-6)
    a.run(0.5)
    b.run(0.5)
    assert np.allclose(b.body_states(), a.body_states(), atol=1e-3)


def test_gravity_is_assignable():
    w = cablelab.World.from_dict(free_body_scene(1))
    w.gravity = (0.0, -2.0)
    assert w.gravity == [0.0, -2.0]
    w.step()
    assert w.body_state(0)[4] == pytest.approx(-0.02, rel=1e-6)


def test_scenes_lists_every_builtin_scene():
    names = [s["name"] for s in cablelab.scenes()]
    assert {"ballast", "hand", "hexagon", "membrane", "pulley"} <= set(names)
    for s in cablelab.scenes():
        cablelab.World.load(s["name"], **{k: v["default"] for k, v in s["params"].items()})


def test_run_releases_the_gil():
    w = cablelab.World.load("hand")
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.perf_counter()
    w.run(steps=6000)
    elapsed = time.perf_counter() - start
    stop.set()
    t.join()
    assert elapsed > 0.05
    assert len(ticks) > 10  # the other thread ran while run() was in C++


def test_a_world_busy_in_run_refuses_other_threads():
    w = cablelab.World.load("hand")
    errors = []
    started = threading.Event()

    def poke():
        started.wait()
        for _ in range(2000):
            try:
                w.body_states()
            except RuntimeError as e:
                errors.append(str(e))
                return
            time.sleep(0.0005)

    t = threading.Thread(target=poke)
    t.start()
    started.set()
    w.run(steps=20000)
    t.join()
    assert errors and "another thread" in errors[0]


def test_ctrl_c_interrupts_a_long_run():
    import os
    import signal
    w = cablelab.World.load("pulley")
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        w.run(steps=10**8)
    timer.join()
    assert time.perf_counter() - start < 30
    assert 0 < w.step_count < 10**8
    w.step()  # the World is usable afterwards
