# cablelab.rollout steps N Worlds on a thread pool: each World must give exactly what a serial
# `set_servo_targets(c); step()` loop gives (bit for bit), whatever the thread count.
import numpy as np
import pytest

import cablelab

WORLDS, STEPS = 4, 150


def hand_controls(world, worlds=WORLDS, steps=STEPS):
    """(worlds, steps, joints) servo targets: the hand's own targets plus a different slow wave
    per world, so that the worlds move apart."""
    base = np.asarray(world.servo_targets())
    t = np.arange(steps) * 0.01
    amplitude = 0.02 * (1 + np.arange(worlds))[:, None, None]
    return base + amplitude * np.sin(3 * t)[None, :, None] * np.ones(len(base))


def serial_recording(worlds, controls):
    bodies, tensions, times = [], [], []
    for i, w in enumerate(worlds):
        b, c, t = [], [], []
        for s in range(controls.shape[1]):
            w.set_servo_targets(controls[i, s])
            w.step()
            b.append(w.body_states())
            c.append(w.cable_tensions())
            t.append(w.time)
        bodies.append(b), tensions.append(c), times.append(t)
    return np.array(bodies), np.array(tensions), np.array(times)


@pytest.fixture(scope="module")
def hand():
    return cablelab.World.load("hand")


def test_rollout_equals_serial_stepping_bit_for_bit(hand):
    controls = hand_controls(hand)
    parallel = [hand.copy() for _ in range(WORLDS)]
    serial = [hand.copy() for _ in range(WORLDS)]
    rec = cablelab.rollout(parallel, STEPS, controls=controls, threads=2)
    bodies, tensions, times = serial_recording(serial, controls)
    assert rec["bodies"].shape == (WORLDS, STEPS, len(hand.body_names), 6)
    assert np.array_equal(rec["bodies"], bodies)
    assert np.array_equal(rec["cables"][..., 1], tensions)
    assert np.array_equal(rec["t"], times)
    # The worlds were stepped in place, and they really differ from each other.
    for p, s in zip(parallel, serial):
        assert np.array_equal(p.body_states(), s.body_states())
    assert not np.array_equal(rec["bodies"][0, -1], rec["bodies"][3, -1])


def test_one_and_two_threads_give_identical_arrays(hand):
    controls = hand_controls(hand)
    one = cablelab.rollout([hand.copy() for _ in range(WORLDS)], STEPS, controls, threads=1)
    two = cablelab.rollout([hand.copy() for _ in range(WORLDS)], STEPS, controls, threads=2)
    for key in ("t", "bodies", "cables", "joints"):
        assert np.array_equal(one[key], two[key]), key


def test_a_callable_policy_sees_the_states_and_matches_the_table(hand):
    controls = hand_controls(hand, steps=40)
    seen = []

    def policy(step, bodies):
        seen.append(bodies.copy())
        return controls[:, step]

    by_table = cablelab.rollout([hand.copy() for _ in range(WORLDS)], 40, controls)
    by_policy = cablelab.rollout([hand.copy() for _ in range(WORLDS)], 40, policy)
    assert np.array_equal(by_table["bodies"], by_policy["bodies"])
    # The policy got the states before each step: step k's are the recording's row k - 1.
    assert np.array_equal(seen[5], by_policy["bodies"][:, 4])


def test_without_controls_the_targets_stay(hand):
    worlds = [hand.copy() for _ in range(2)]
    alone = hand.copy()
    rec = cablelab.rollout(worlds, 30)
    for _ in range(30):
        alone.step()
    assert np.array_equal(rec["bodies"][1, -1], alone.body_states())


def test_bad_input_names_the_argument(hand):
    w = hand.copy()
    with pytest.raises(cablelab.InputError, match=r"rollout: worlds\[1\]: the same World"):
        cablelab.rollout([w, w], 3)
    with pytest.raises(cablelab.InputError, match=r"rollout: controls: must be an array of shape "
                                                  r"\(worlds, steps, joints\) = \(1, 3, 6\)"):
        cablelab.rollout([w], 3, controls=np.zeros((1, 3, 5)))
    with pytest.raises(cablelab.InputError, match=r"rollout: threads: must be 1..1024 \(got 0\)"):
        cablelab.rollout([w], 3, threads=0)
    with pytest.raises(cablelab.InputError, match=r"rollout: worlds\[1\]: has other numbers"):
        cablelab.rollout([w, cablelab.World.load("pulley")], 3)
    assert w.time == 0  # nothing was stepped
