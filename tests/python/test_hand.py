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
    m = cablelab.HandModel(k=300.0, box_mass=2.0)
    assert (m.k, m.box_mass) == (300.0, 2.0)
    assert cablelab.HandModel().k != 300.0
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
