# Every bad argument of the Python API is refused in one style, the CLI's:
# "SOURCE: FIELD: what is wrong (got VALUE)" (engine/core/error.h), naming the value that was
# given, so that a student sees what they passed without a debugger. A wrong type is also a
# TypeError (cablelab.InputTypeError), a wrong value a ValueError.
import math
import re

import numpy as np
import pytest

import cablelab

ONE_LINE = re.compile(r"^[^:\n]+: [^:\n]+: .+ \(got .+\)$")

PULLEYS = (-0.2, 0.0, 0.2, 0.0)


def pulley():
    return cablelab.World.load("pulley")


def hand():
    return cablelab.World.load("hand")


# (call, expected exception, text that must name the value given inside "(got ...)")
CASES = {
    # World.load / from_dict
    "load_keyword_negative": (lambda: cablelab.World.load("pulley", m_left=-1), ValueError, "-1"),
    "load_keyword_text": (lambda: cablelab.World.load("pulley", m_left="heavy"), TypeError,
                          "a str"),
    "load_keyword_unknown": (lambda: cablelab.World.load("pulley", mass=2), ValueError,
                             "mass=2"),
    "load_unknown_scene": (lambda: cablelab.World.load("no_such_scene"), ValueError,
                           '"no_such_scene"'),
    "load_scene_not_text": (lambda: cablelab.World.load(3), TypeError, "an int"),
    "from_dict_list": (lambda: cablelab.World.from_dict([1, 2]), TypeError, "a list"),
    "from_dict_none": (lambda: cablelab.World.from_dict(None), TypeError, "None"),
    "from_dict_negative_mass": (
        lambda: cablelab.World.from_dict({"bodies": [{"name": "b", "mass": -1.5}]}), ValueError,
        "-1.5"),
    # step / run
    "step_dt_zero": (lambda: pulley().step(dt=0), ValueError, "got 0)"),
    "step_dt_big": (lambda: pulley().step(dt=2.5), ValueError, "got 2.5)"),
    "step_dt_text": (lambda: pulley().step(dt="fast"), TypeError, "a str"),
    "step_substeps_zero": (lambda: pulley().step(substeps=0), ValueError, "got 0)"),
    "step_substeps_float": (lambda: pulley().step(substeps=1.5), TypeError, "a float"),
    "run_time_negative": (lambda: pulley().run(time=-1), ValueError, "got -1)"),
    "run_time_nan": (lambda: pulley().run(time=math.nan), ValueError, "got nan)"),
    "run_time_text": (lambda: pulley().run(time="1 s"), TypeError, "a str"),
    "run_steps_negative": (lambda: pulley().run(steps=-3), ValueError, "got -3)"),
    "run_steps_float": (lambda: pulley().run(steps=2.5), TypeError, "a float"),
    "run_both": (lambda: pulley().run(1.0, steps=3), ValueError, "got both"),
    "run_neither": (lambda: pulley().run(), ValueError, "got neither"),
    "run_too_many_steps": (lambda: pulley().run(time=1e7, dt=1e-5), ValueError, "got 1e+07)"),
    # states
    "body_unknown_name": (lambda: pulley().set_body_state("nobody", [0] * 6), ValueError,
                          '"nobody"'),
    "body_index_range": (lambda: pulley().set_body_state(99, [0] * 6), ValueError, "got 99"),
    "body_index_float": (lambda: pulley().set_body_state(1.5, [0] * 6), TypeError, "a float"),
    "body_state_short": (lambda: pulley().set_body_state(0, [0, 0, 0]), ValueError,
                         "shape (3,)"),
    "body_states_shape": (lambda: pulley().set_body_states(np.zeros((3, 2))), ValueError,
                          "shape (3, 2)"),
    "body_states_out": (lambda: pulley().body_states(out=np.zeros((7, 6))), ValueError,
                        "shape (7, 6)"),
    "body_states_out_list": (lambda: pulley().body_states(out=[1.0]), TypeError, "a list"),
    "set_state_other_scene": (lambda: pulley().set_state(hand().get_state()), ValueError,
                              '"hand"'),
    "cable_unknown": (lambda: pulley().cable_jacobian("rope9"), ValueError, '"rope9"'),
    # pictures
    "render_size_small": (lambda: cablelab.render(pulley(), size=(8, 8)), ValueError,
                          "got (8, 8)"),
    "render_size_text": (lambda: cablelab.render(pulley(), size="big"), TypeError, "a str"),
    "render_view_text": (lambda: cablelab.render(pulley(), view="top"), ValueError, '"top"'),
    "render_view_key": (lambda: cablelab.render(pulley(), view={"centre": [0, 0], "height": 1}),
                        ValueError, '"centre"'),
    "render_view_keys_missing": (lambda: cablelab.render(pulley(), view={}), ValueError,
                                 "no keys"),
    "render_view_height": (lambda: cablelab.render(pulley(), view=((0, 0), -2)), ValueError,
                           "got -2)"),
    "snapshot_path": (lambda: cablelab.snapshot(pulley(), "/no/such/folder/x.png"), ValueError,
                      '"/no/such/folder/x.png"'),
    # rollouts
    "rollout_worlds_none": (lambda: cablelab.rollout(None, 3), TypeError, "None"),
    "rollout_worlds_item": (lambda: cablelab.rollout([pulley(), 5], 3), TypeError, "an int"),
    "rollout_worlds_empty": (lambda: cablelab.rollout([], 3), ValueError, "an empty list"),
    "rollout_steps": (lambda: cablelab.rollout([pulley()], -4), ValueError, "got -4)"),
    "rollout_threads": (lambda: cablelab.rollout([pulley()], 3, threads=0), ValueError, "got 0)"),
    "rollout_threads_text": (lambda: cablelab.rollout([pulley()], 3, threads="2"), TypeError,
                             "a str"),
    "rollout_controls": (lambda: cablelab.rollout([hand()], 3, controls=np.zeros((1, 2, 6))),
                         ValueError, "shape (1, 2, 6)"),
    # statics, wrap, fit, membrane tools
    "statics_array_shape": (lambda: cablelab.statics(np.zeros((2, 5))), ValueError,
                            "shape (2, 5)"),
    "statics_not_finite": (lambda: cablelab.statics(np.array([[0, 0, 1, 0, math.inf, 1.0]])),
                           ValueError, "got inf)"),
    "fit_pulleys": (lambda: cablelab.fit(np.zeros((4, 4)), [1, 2, 3]), ValueError, "shape (3,)"),
    "fit_data_shape": (lambda: cablelab.fit(np.zeros((5, 3)), PULLEYS), ValueError,
                       "shape (5, 3)"),
    "membrane_data_seed": (lambda: cablelab.membrane_data(100, 0.01, PULLEYS, seed=-1), ValueError,
                           "got -1)"),
    "membrane_data_grid": (lambda: cablelab.membrane_data(100, 0.01, PULLEYS, grid=(0, 3)),
                           ValueError, "got (0, 3)"),
    "membrane_data_k": (lambda: cablelab.membrane_data(-5, 0.01, PULLEYS), ValueError, "got -5)"),
    "membrane_data_depth": (lambda: cablelab.membrane_data(100, 0.01, PULLEYS, depth=(0, 0.3)),
                            ValueError, "got (0, 0.3)"),
    "membrane_model_points": (lambda: cablelab.membrane_model(PULLEYS, 100, 0.01, np.zeros(3)),
                              ValueError, "shape (3,)"),
    "membrane_pulleys_coincide": (lambda: cablelab.membrane_model((0, 0, 0, 0), 100, 0.01,
                                                                  np.zeros((1, 2))),
                                  ValueError, "(got 0,0,0,0)"),
    # hand tools
    "hand_model_negative": (lambda: cablelab.HandModel(k=-5), ValueError, "got -5)"),
    "hand_model_text": (lambda: cablelab.HandModel(k="stiff"), TypeError, "a str"),
    "hand_model_unknown": (lambda: cablelab.HandModel(stifness=3), ValueError, "stifness=3"),
    "grasp_options_int": (lambda: cablelab.GraspOptions(max_regrasps=1.5), TypeError, "a float"),
    "hand_grasp_world": (lambda: cablelab.HandGrasp(5), TypeError, "an int"),
    "hand_grasp_not_hand": (lambda: cablelab.HandGrasp(pulley()), ValueError, '"pulley"'),
    "hand_grasp_law": (lambda: cablelab.HandGrasp(hand()).step(law=3), TypeError, "an int"),
    "hand_joints_not_hand": (lambda: cablelab.hand_joints(pulley()), ValueError, '"pulley"'),
    "track_changes": (lambda: cablelab.track(target=(0.01, 0.0), time=1, changes=[(1.0,)]),
                      ValueError, "shape (1,)"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_bad_argument_is_named_with_the_value_given(name):
    call, kind, value = CASES[name]
    with pytest.raises(cablelab.InputError) as e:
        call()
    text = str(e.value)
    assert ONE_LINE.match(text), text
    assert isinstance(e.value, kind), (type(e.value).__mro__, text)
    # A wrong type is a TypeError too, a wrong value only a ValueError.
    assert isinstance(e.value, TypeError) == (kind is TypeError), text
    got = text[text.rindex("(got "):]
    assert value in got, text


def test_enough_bad_calls_are_covered():
    assert len(CASES) >= 30


def test_a_wrong_type_is_caught_as_either():
    with pytest.raises(TypeError):
        cablelab.World.load("pulley").step(dt="fast")
    with pytest.raises(ValueError):
        cablelab.World.load("pulley").step(dt="fast")
    assert issubclass(cablelab.InputTypeError, cablelab.InputError)
