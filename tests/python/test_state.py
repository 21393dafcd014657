# World state you can fork (issue 39, item 1): get_state / set_state / copy / pickle keep a World
# bit for bit, and the value classes pickle (ProcessPoolExecutor over HandModel).
import concurrent.futures
import copy
import math
import pickle

import numpy as np
import pytest

import cablelab


def drive(w, k):
    """One step with inputs that change every step: servo targets, a force, now and then a
    gravity change (the same k gives the same inputs to every world)."""
    if w.joint_names:
        w.set_servo_targets([0.05 * math.sin(0.1 * k + j) for j in range(len(w.joint_names))])
    w.apply_force(len(w.body_names) - 1, [0.5 * math.cos(0.3 * k), 0.2 * math.sin(0.2 * k)])
    if k % 25 == 0:
        w.gravity = [0.01 * math.sin(k), -9.81]
    w.step()


def fingerprint(w):
    """Every number a user reads after a step, as raw bytes."""
    parts = [w.body_states(), w.cable_tensions(), w.cable_lengths(), w.joint_values(),
             w.joint_speeds(), np.array([w.time, w.step_count])]
    return b"".join(np.ascontiguousarray(p, dtype=np.float64).tobytes() for p in parts)


@pytest.mark.parametrize("scene", ["hand", "pulley", "hexagon"])
def test_forks_step_bit_for_bit_as_the_original(scene):
    w = cablelab.World.load(scene)
    for k in range(30):
        drive(w, k)
    state = w.get_state()
    assert state.time == w.time and state.step_count == w.step_count == 30
    assert np.array_equal(state.body_states, w.body_states())
    forks = [w.copy(), copy.deepcopy(w), pickle.loads(pickle.dumps(w)),
             cablelab.World.from_state(state), cablelab.World.from_state(pickle.loads(pickle.dumps(state)))]
    for f in forks:
        assert fingerprint(f) == fingerprint(w)
    for k in range(30, 90):
        for x in [w] + forks:
            drive(x, k)
        for i, f in enumerate(forks):
            assert fingerprint(f) == fingerprint(w), (scene, i, k)
    # set_state goes back: from there the same inputs give the same trajectory again.
    after = fingerprint(w)
    w.set_state(state)
    assert w.time == state.time and w.step_count == 30
    for k in range(30, 90):
        drive(w, k)
    assert fingerprint(w) == after


def test_a_fork_is_independent():
    w = cablelab.World.load("pulley")
    w.run(steps=10)
    f = w.copy()
    f.set_body_state("left", [0, 0, 0, 0, 0, 0])
    f.run(steps=5)
    assert w.step_count == 10 and f.step_count == 15
    assert not np.array_equal(w.body_state("left"), f.body_state("left"))


def test_set_state_of_another_scene_is_refused():
    w = cablelab.World.load("pulley")
    with pytest.raises(cablelab.InputError, match="set_state: state: is of another scene"):
        w.set_state(cablelab.World.load("hexagon").get_state())


def test_value_classes_pickle_and_copy():
    values = [cablelab.HandModel(k=300.0, lower=[-0.5] * 6),
              cablelab.ControllerParams(kp=0.2, ki=1.0),
              cablelab.GraspOptions(close_time=2.0, max_regrasps=4)]
    for v in values:
        for back in (pickle.loads(pickle.dumps(v)), copy.copy(v), copy.deepcopy(v)):
            assert type(back) is type(v) and repr(back) == repr(v)
    assert pickle.loads(pickle.dumps(values[0])).k == 300.0
    assert list(pickle.loads(pickle.dumps(values[0])).lower) == [-0.5] * 6


def box_after(model):
    """The hand built from `model` after 30 steps: the box's x, y (a worker's task)."""
    w = model.world()
    w.run(steps=30)
    return tuple(w.body_state(cablelab.HAND_BOX)[:2])


def test_process_pool_over_hand_models():
    models = [cablelab.HandModel(k=k) for k in (100.0, 200.0)]
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as pool:
        remote = list(pool.map(box_after, models))
    assert remote == [box_after(m) for m in models]  # the same doubles in another process
