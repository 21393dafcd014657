# cablelab.HandGrasp: the engine's grasp sequence stepped from Python. With the built-in
# controller, or a Python law that is the same controller, it is `track` to the bit; a law that
# opens the fingers loses the box, and the sequence notices and re-grasps.
import numpy as np
import pytest

import cablelab

TARGET = (0.2, 0.1)
START = (-0.1, 0.1)


def run_grasp(seconds, law=None, target=TARGET, **kw):
    hand = cablelab.HandModel()
    world = hand.world()
    g = cablelab.HandGrasp(world, hand, **kw)
    g.begin(START)
    box = world.body_names.index(cablelab.HAND_BOX)
    path = [world.body_state(box)[:2]]
    for _ in range(round(seconds / world.dt)):
        g.step(target, law)
        path.append(world.body_state(box)[:2])
    return g, np.array(path)


def test_grasp_with_the_controller_is_track_to_the_bit():
    g, path = run_grasp(4)
    r = cablelab.track(target=TARGET, start=START, time=4)
    assert np.array_equal(path, r["box"])
    assert g.grasp_time == r["grasp_time"] and g.held == r["grasp_held"]
    assert g.events == r["events"]
    assert g.phase == "control" and g.controlling and g.updates > 0


def test_python_law_equal_to_the_controller_is_track_to_the_bit():
    controller = cablelab.HandController()
    calls = []

    def law(q, box, commanded):
        calls.append(1)
        return controller.update(q, box, TARGET, commanded)

    g, path = run_grasp(4, law=law, target=None)
    r = cablelab.track(target=TARGET, start=START, time=4)
    assert np.array_equal(path, r["box"])
    assert len(calls) == g.updates > 0
    period = cablelab.ControllerParams().period
    assert g.updates == pytest.approx((4 - g.control_start) / period, abs=1)


def test_pid_controller_params_are_the_tracks():
    g, path = run_grasp(3, controller=cablelab.ControllerParams(ki=cablelab.PID_KI))
    assert np.array_equal(path, cablelab.track(target=TARGET, start=START, time=3, pid=True)["box"])


def test_a_law_that_opens_the_fingers_loses_the_box_and_regrasps():
    hand = cablelab.HandModel()
    options = cablelab.GraspOptions(max_regrasps=1)

    def open_up(q, box, commanded):
        return hand.open_pose() - commanded  # swing the fingers apart in one update

    g, path = run_grasp(6, law=open_up, target=None, options=options)
    what = [e["what"] for e in g.events]
    assert what[0] == "grasp closed"
    assert any("membrane" in w for w in what) and "re-grasp" in what
    assert g.losses >= 1 and not g.held
    # the law runs again after the re-grasp, so the box is lost again: one re-grasp, then it gives up
    assert g.phase == "failed" and what[-1] == "gave up"
    assert np.all(np.isfinite(path))


def test_hold_without_target_or_law_keeps_the_commanded_joints():
    g, _ = run_grasp(3, target=None)
    assert g.phase == "control" and g.updates == 0
    before = g.commanded.copy()
    g.step()
    assert np.array_equal(g.commanded, before)
    assert np.abs(g.joints() - before).max() < 0.02  # the servos hold the pinch


def test_bad_world_start_and_law():
    with pytest.raises(cablelab.InputError, match=r"^HandGrasp: world: is not the hand scene"):
        cablelab.HandGrasp(cablelab.World.load("pulley"))
    with pytest.raises(cablelab.InputError, match=r"^HandGrasp: world: must be a cablelab.World"):
        cablelab.HandGrasp(3)
    world = cablelab.HandModel().world()
    g = cablelab.HandGrasp(world)
    with pytest.raises(cablelab.InputError, match=r"^HandGrasp.begin: start: the fingers cannot pinch the box there \(got 9,9\)"):
        g.begin((9, 9))
    with pytest.raises(cablelab.InputError, match=r"^HandGrasp: law: must be a function"):
        g.step(law=3)
    with pytest.raises(cablelab.InputError, match=r"^GraspOptions: open: no such field"):
        cablelab.GraspOptions(open=1)
    g.begin_pinched()
    for _ in range(60):  # past the settle time, so that updates are due
        g.step()

    def wrong_shape(q, box, commanded):
        return [0.0] * 5

    with pytest.raises(cablelab.InputError, match=r"^law: q: must be 6 numbers"):
        for _ in range(5):  # an update is due every 0.053 s, every third or fourth step
            g.step(law=wrong_shape)

    def failing(q, box, commanded):
        raise ZeroDivisionError("from the law")

    with pytest.raises(ZeroDivisionError, match="from the law"):
        g.step(law=failing)  # the update the failed one left due
    updates = g.updates
    g.step(law=lambda q, box, commanded: np.zeros(6))  # the failed update is retried
    assert g.updates == updates + 1


def test_grasp_keeps_its_world_alive():
    g = cablelab.HandGrasp(cablelab.HandModel().world())
    g.begin(START)
    for _ in range(10):
        g.step(TARGET)
    assert g.world.time == pytest.approx(10 * g.world.dt)


def test_controller_status_follows_the_reference_to_the_target():
    g, path = run_grasp(6)
    s = g.controller.status()
    # the reference has come to rest on the target, and the box model is close to the box
    assert np.array_equal(s["reference"], TARGET)
    assert np.linalg.norm(s["expected"] - path[-1]) < 0.02
    assert s["joints_at_limit"] == 0 and not s["rate_limited"]
