# Sensors (issue 39, item 2) against finite differences and analytic cases: the cable Jacobian and
# J-dot-v, servo torques, contact forces, per-span tensions round a capstan, posing by joint values.
import json
import math
import os

import numpy as np
import pytest

import cablelab

G = 9.81
SQUARE = os.path.join(os.path.dirname(__file__), "..", "data", "polygon_friction",
                      "good_polygon_friction_scene.json")


def swing_scene():
    """A rope from the world point (0, 0) to a point off the centre of a spinning, flying box
    (gravity off, so nothing but the given velocities)."""
    return {"name": "swing", "gravity": [0, 0], "dt": 0.01,
            "bodies": [{"name": "box", "position": [1.0, -1.2], "angle": 0.3,
                        "velocity": [0.8, 0.5], "angular_velocity": 1.5, "mass": 1.0,
                        "shapes": [{"type": "box", "half_size": [0.2, 0.1]}]}],
            "cables": [{"name": "rope", "start": {"body": "world", "point": [0, 0]},
                        "end": {"body": "box", "point": [0.2, 0.05]}, "stiffness": 100.0}]}


def worlds_in_motion():
    """(world, cable): a straight rope, a rope wrapping the moving hexagon, the tackle."""
    swing = cablelab.World.from_dict(swing_scene())
    hexagon = cablelab.World.load("hexagon")
    hexagon.run(steps=20)
    tackle = cablelab.World.load("tackle")
    tackle.run(steps=20)
    return [(swing, "rope"), (hexagon, 0), (tackle, 0)]


def lengths_at(w, cable, states):
    w.set_body_states(states)
    read = w.body_states()  # Box2D keeps floats: the pose it really holds
    return w.cable_lengths()[w.cable_names.index(cable) if isinstance(cable, str) else cable], read


@pytest.mark.parametrize("case", range(3))
def test_jacobian_is_the_derivative_of_the_length(case):
    w, cable = worlds_in_motion()[case]
    s0 = w.body_states()
    J = w.cable_jacobian(cable)
    assert J.shape == (len(w.body_names), 3)
    assert np.abs(J).max() > 0.1
    h = 1e-4
    checked = 0
    for b in range(len(w.body_names)):
        for k in range(3):
            if J[b, k] == 0:
                continue
            plus, minus = s0.copy(), s0.copy()
            plus[b, k] += h
            minus[b, k] -= h
            lp, qp = lengths_at(w, cable, plus)
            lm, qm = lengths_at(w, cable, minus)
            fd = (lp - lm) / (qp[b, k] - qm[b, k])
            assert fd == pytest.approx(J[b, k], abs=2e-4), (b, k)
            checked += 1
    assert checked >= 3
    w.set_body_states(s0)
    assert np.array_equal(w.cable_jacobian(cable), J)  # a pure function of the pose


def test_jdot_v_matches_the_analytic_value_on_a_straight_rope():
    w = cablelab.World.from_dict(swing_scene())
    x, y, th, vx, vy, om = w.body_state("box")
    r = np.array([0.2 * math.cos(th) - 0.05 * math.sin(th), 0.2 * math.sin(th) + 0.05 * math.cos(th)])
    p = np.array([x, y]) + r
    v = np.array([vx, vy]) + om * np.array([-r[1], r[0]])
    L = np.linalg.norm(p)
    u = p / L
    # d/dt (u . v_p) = (|v|^2 - (u.v)^2) / L + u . (d v_p / dt at constant body velocity)
    analytic = (v @ v - (u @ v) ** 2) / L + u @ (-om * om * r)
    assert w.cable_jdot_v("rope") == pytest.approx(analytic, rel=1e-6)


@pytest.mark.parametrize("case", range(3))
def test_jdot_v_is_the_rate_of_j_v_along_the_motion(case):
    w, cable = worlds_in_motion()[case]
    s0 = w.body_states()
    v = s0[:, 3:6]
    jdotv = w.cable_jdot_v(cable)

    def jv_at(t):
        s = s0.copy()
        s[:, 0:3] += t * v
        w.set_body_states(s)
        read = w.body_states()
        return float(np.sum(w.cable_jacobian(cable) * v)), read

    h = 1e-3
    (jp, sp), (jm, sm) = jv_at(h), jv_at(-h)
    moving = np.argmax(np.abs(v).sum(axis=1))
    k = np.argmax(np.abs(v[moving]))
    dt = (sp[moving, k] - sm[moving, k]) / v[moving, k]  # the time Box2D's floats really moved
    assert (jp - jm) / dt == pytest.approx(jdotv, rel=2e-3, abs=2e-4)


def rod_scene(mass=2.0, length=1.0):
    """A rod hinged to the world at its left end, held level by a servo against gravity."""
    return {"name": "rod", "gravity": [0, -G], "dt": 1 / 120, "substeps": 2,
            "bodies": [{"name": "rod", "position": [length / 2, 0], "mass": mass,
                        "shapes": [{"type": "box", "half_size": [length / 2, 0.02]}]}],
            "joints": [{"type": "revolute", "name": "hinge", "body_a": "world", "body_b": "rod",
                        "anchor": [0, 0],
                        "servo": {"kp": 3000, "kd": 150, "target": 0, "max_force": 1000}}]}


def test_a_servo_holding_a_rod_level_reports_m_g_l_over_2():
    w = cablelab.World.from_dict(rod_scene(mass=2.0, length=1.0))
    w.run(time=4.0)
    assert abs(w.joint_values()[0]) < 0.01  # level (kp holds it within m g l / 2 / kp)
    torque = w.joint_forces()[0]
    assert torque == pytest.approx(2.0 * G * 1.0 / 2, rel=1e-3)
    np.testing.assert_array_equal(w.joint_rates(), w.joint_speeds())


def test_joints_without_a_servo_report_no_force():
    scene = rod_scene()
    del scene["joints"][0]["servo"]
    w = cablelab.World.from_dict(scene)
    w.run(steps=10)
    assert w.joint_forces()[0] == 0.0


def test_contact_force_of_a_box_resting_on_the_floor_is_its_weight():
    scene = {"name": "rest", "gravity": [0, -G], "dt": 1 / 60,
             "bodies": [{"name": "floor", "type": "static", "position": [0, -0.5],
                         "shapes": [{"type": "box", "half_size": [3, 0.5]}]},
                        {"name": "box", "position": [0.3, 0.25], "mass": 2.0,
                         "shapes": [{"type": "box", "half_size": [0.25, 0.25]}]}]}
    w = cablelab.World.from_dict(scene)
    w.run(time=2.0)
    c = w.contact_forces()
    assert c["pairs"] == [("floor", "box")]
    assert c["bodies"].tolist() == [[0, 1]]
    np.testing.assert_allclose(c["force"][0], [0, 2.0 * G], atol=2e-3 * 2.0 * G)
    np.testing.assert_allclose(c["normal"][0], [0, 1], atol=1e-6)
    # Box2D's contact points lie within its polygon skin (b2_polygonRadius, 1 cm) of the faces.
    assert c["point"][0] == pytest.approx([0.3, 0.0], abs=0.012)


@pytest.mark.parametrize("m_load,slips", [(3.0, False), (6.0, True)])
def test_capstan_span_tensions(m_load, slips):
    w = cablelab.World.load("capstan", m_load=m_load)  # mu 0.3, 0.75 turns, m_hold 1
    w.run(time=1.0)
    t = w.cable_span_tensions("rope")
    assert t.shape == (2,)
    high, low = max(t), min(t)
    bound = math.exp(0.3 * 2 * math.pi * 0.75)
    if slips:
        assert high / low == pytest.approx(bound, rel=1e-3)
    else:
        assert (high, low) == pytest.approx((m_load * G, 1.0 * G), rel=1e-3)
    assert w.cable_tensions()[0] == pytest.approx(high, rel=1e-12)


@pytest.mark.parametrize("m_left,slides", [(1.5, False), (4.0, True)])
def test_square_corner_tensions(m_left, slides):
    """A rope over a fixed square's two top corners (90 degrees each), mu 0.2, 1 kg on the right:
    it holds while m_left <= e^(0.2 pi) = 1.87 kg; sliding, each corner's ratio is e^(0.2 pi / 2)."""
    with open(SQUARE) as f:
        scene = json.load(f)
    scene["bodies"][0]["mass"] = m_left
    w = cablelab.World.from_dict(scene)
    w.run(time=0.5)
    spans = w.cable_span_tensions("rope")
    corners = w.cable_corner_tensions("rope")
    assert spans.shape == (2,) and corners.shape == (2, 3)
    np.testing.assert_allclose(corners[:, 0], [math.pi / 2] * 2, atol=1e-6)
    assert corners[0, 1] == pytest.approx(spans[0], rel=1e-12)
    assert corners[1, 2] == pytest.approx(spans[1], rel=1e-12)
    assert corners[0, 2] == pytest.approx(corners[1, 1], rel=1e-12)
    ratios = corners[:, 1] / corners[:, 2]
    if slides:
        np.testing.assert_allclose(ratios, [math.exp(0.2 * math.pi / 2)] * 2, rtol=1e-6)
    else:
        assert tuple(spans) == pytest.approx((m_left * G, 1.0 * G), rel=1e-6)
        assert all(1 < r < math.exp(0.2 * math.pi / 2) for r in ratios)


def arm_scene():
    """Two links hinged end to end from the world, then a slider on the second: a tree."""
    link = lambda name, x: {"name": name, "position": [x, 0], "mass": 1.0,
                            "shapes": [{"type": "box", "half_size": [0.5, 0.05]}]}
    return {"name": "arm", "gravity": [0, 0],
            "bodies": [link("upper", 0.5), link("fore", 1.5), link("slider", 2.5)],
            "joints": [{"type": "revolute", "name": "shoulder", "body_a": "world",
                        "body_b": "upper", "anchor": [0, 0]},
                       {"type": "revolute", "name": "elbow", "body_a": "upper",
                        "body_b": "fore", "anchor": [1, 0]},
                       {"type": "prismatic", "name": "slide", "body_a": "fore",
                        "body_b": "slider", "anchor": [2, 0], "axis": [1, 0]}]}


def test_set_joint_values_poses_a_tree_of_joints():
    w = cablelab.World.from_dict(arm_scene())
    q = [0.4, -0.9, 0.25]
    w.set_joint_values(q)
    np.testing.assert_allclose(w.joint_values(), q, atol=1e-6)
    np.testing.assert_allclose(w.servo_targets(), q)
    a1, a2 = 0.4, 0.4 - 0.9
    elbow = np.array([math.cos(a1), math.sin(a1)])
    slider = elbow + (1.5 + 0.25) * np.array([math.cos(a2), math.sin(a2)])
    np.testing.assert_allclose(w.body_state("slider")[:3], [*slider, a2], atol=1e-6)
    assert not np.any(w.body_states()[:, 3:])


def test_set_joint_values_on_the_hand_is_place_hand():
    q = [0.2, 0.1, -0.3, -0.1, 0.05, 0.2]
    a, b = cablelab.World.load("hand"), cablelab.World.load("hand")
    names = list(a.joint_names)
    values = np.zeros(len(names))
    for name, v in zip(cablelab.HAND_JOINT_NAMES, q):
        values[names.index(name)] = v
    a.set_joint_values(values)
    cablelab.place_hand(b, q)
    np.testing.assert_allclose(a.body_states(), b.body_states(), atol=1e-6)
    np.testing.assert_allclose(a.servo_targets(), b.servo_targets())
    # set_joint_values also brings the membranes to the new pose at once (place_hand leaves
    # them until the next step): here the paddles opened off the box, so they run straight.
    b.set_body_states(b.body_states())
    np.testing.assert_allclose(a.cable_lengths(), b.cable_lengths(), atol=1e-6)


def test_set_joint_values_refuses_a_wrong_count():
    w = cablelab.World.from_dict(arm_scene())
    with pytest.raises(cablelab.InputError, match="set_joint_values: values"):
        w.set_joint_values([0.1])


def test_set_body_states_updates_the_cables_at_once():
    w = cablelab.World.load("pulley")
    s = w.body_states()
    before = w.cable_lengths()[0]
    s[0, 1] += 1.0  # the left box 1 m up: its rope 1 m shorter
    w.set_body_states(s)
    assert w.cable_lengths()[0] == pytest.approx(before - 1.0, abs=1e-5)
    assert w.cable_path(0)[0][1] == pytest.approx(s[0, 1] + 2.0, abs=1e-5)


def test_a_circle_pulley_is_on_the_path_by_its_centre_and_the_rope_leaves_along_a_tangent():
    # cable_path()'s docstring: a circle's wrap point is its centre. A bob let go from rest on a
    # rope over a 5 cm peg pulls along the tangent: its tension is m g . e for the tangent's e,
    # not for the direction to the centre (off by asin(r / l), 3.7 deg here).
    c, r, m = np.array([0.0, -0.4]), 0.05, 1.3
    bob = np.array([0.7174, -0.6967])
    w = cablelab.World.from_dict({
        "dt": 1 / 240, "substeps": 4,
        "bodies": [{"name": "bob", "position": bob.tolist(), "mass": m,
                    "shapes": [{"type": "circle", "radius": 0.03}]}],
        "cables": [{"name": "rope", "start": {"point": [0, 0]}, "end": {"body": "bob"},
                    "pulleys": [{"type": "circle", "point": c.tolist(), "radius": r,
                                 "side": "right"}]}]})
    path = w.cable_path(0)
    assert path.shape == (3, 2) and np.allclose(path[1], c, atol=1e-12)
    assert np.allclose(w.wrap_points(0), [c], atol=1e-12)
    d = bob - c
    dist = np.linalg.norm(d)
    along = d / dist
    # the tangent from the bob: the direction to the centre turned by asin(r / dist), on the side
    # the rope passes (right: the peg on the rope's left, the rope turning anticlockwise round it)
    a = -math.asin(r / dist)
    e = np.array([along[0] * math.cos(a) + along[1] * math.sin(a),
                  -along[0] * math.sin(a) + along[1] * math.cos(a)])
    w.step()
    t = w.cable_tensions()[0]
    assert t == pytest.approx(m * G * -e[1], rel=2e-3)
    assert abs(t - m * G * -along[1]) > 0.1 * t  # the centre's direction misses it by 19%
