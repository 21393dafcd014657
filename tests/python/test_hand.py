# The hand from Python: joints, placement, the controller's statics model and its Jacobian.
import numpy as np
import pytest

import cablelab


def test_place_hand_then_read_the_joints():
    model = cablelab.HandModel()
    w = model.world()
    q = model.open_pose()
    cablelab.place_hand(w, q, model)
    assert np.abs(cablelab.hand_joints(w) - q).max() < 1e-5  # Box2D float poses
    assert np.array_equal(w.servo_targets()[:6], q)


def test_model_fields_and_keyword_construction():
    m = cablelab.HandModel(stiffness=300.0, box_mass=2.0)
    assert (m.stiffness, m.box_mass) == (300.0, 2.0)
    assert cablelab.HandModel().stiffness != 300.0
    assert len(m.lower) == 6 and all(lo < hi for lo, hi in zip(m.lower, m.upper))
    assert np.array_equal(m.clamp([10] * 6), m.upper)


def test_predict_jacobian_matches_finite_differences():
    c = cablelab.HandController()
    q = np.array([0.05, 0.02, -0.05, -0.04, 0.01, 0.04])  # paddles face-on (valid)
    p = c.predict(q)
    assert p["valid"]
    h = 1e-6
    fd = np.zeros((2, 6))
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = h
        fd[:, j] = (c.predict(q + dq, p["box"])["box"] - c.predict(q - dq, p["box"])["box"]) / (2 * h)
    assert np.abs(fd - p["jacobian"]).max() < 1e-5 * max(1.0, np.abs(fd).max())


def test_update_moves_the_prediction_towards_the_target():
    c = cablelab.HandController()
    q = np.zeros(6)
    box = c.predict(q)["box"]
    target = box + (0.05, 0.03)
    dq = c.update(q, box, target, q)
    moved = c.predict(q + dq, box)["box"]
    assert np.linalg.norm(moved - target) < np.linalg.norm(box - target)


def test_track_releases_the_gil_and_reports_samples():
    r = cablelab.track(target=(0.05, 0.05), time=2)
    assert r["grasp_time"] > 0
    assert r["box"].shape == (r["t"].shape[0], 2)
    assert np.all(np.diff(r["t"]) > 0)


def test_reach_small_grid_is_consistent():
    r = cablelab.reach(grid=6, threads=1)
    assert r["points"] == 36
    cell = np.prod((np.array(r["upper"]) - r["lower"]) / 6)
    assert r["fingertip_area"] == pytest.approx(len(r["fingertip_points"]) * cell, rel=1e-9)
    assert r["ratio"] == pytest.approx(r["object_area"] / r["fingertip_area"], rel=1e-12)
