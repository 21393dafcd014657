# One name per quantity (docs/python.md, "One name per quantity"): the hand scene's `--set` names
# are the Python names; the same values through World.load, HandModel and the CLI give the same
# simulation to the bit; the old Python names still work and warn; the docs' table is the code's.
import inspect
import math
import pickle
import re
import warnings

import numpy as np
import pytest

import cablelab
from cablelab import _keywords
from conftest import SOURCE_DIR, cli_json

# Every hand scene parameter, none at its default, so that a name mapped to the wrong field shows.
HAND_SETTINGS = {"k": 300.0, "damping": 400.0, "preload": 0.2, "box_mass": 2.0, "mu": 0.5,
                 "turn": 1}


def hand_scene_params():
    """{NAME: {default, description}} of the hand scene's `--set` parameters."""
    return {s["name"]: s for s in cablelab.scenes()}["hand"]["params"]


def stepped(world, steps=240):
    """The world's body states and cable tensions after `steps` steps with the fingers' servo
    targets moving every step (the same inputs for every world)."""
    q0 = world.servo_targets()
    states, tensions = [], []
    for i in range(steps):
        world.set_servo_targets(q0 + 0.05 * math.sin(0.05 * i))
        world.step()
        states.append(world.body_states())
        tensions.append(world.cable_tensions())
    return np.array(states), np.array(tensions)


def same_run(a, b):
    return all(np.array_equal(x, y) for x, y in zip(stepped(a), stepped(b)))


def test_the_scene_parameters_and_the_hand_model_build_the_same_hand_to_the_bit():
    assert set(HAND_SETTINGS) == set(hand_scene_params())  # every parameter of the scene
    loaded = cablelab.World.load("hand", **HAND_SETTINGS)
    built = cablelab.HandModel(**HAND_SETTINGS).world()
    assert loaded.to_dict() == built.to_dict()
    assert same_run(loaded, built)
    # Not vacuous: the settings change the run.
    assert not same_run(cablelab.World.load("hand", **HAND_SETTINGS), cablelab.World.load("hand"))


def test_the_defaults_are_the_scenes():
    model = cablelab.HandModel()
    for name, param in hand_scene_params().items():
        assert float(getattr(model, name)) == param["default"], name


def test_track_with_cli_set_equals_track_with_the_hand_model():
    settings = {"k": 300.0, "preload": 0.2, "mu": 0.5}
    cli = cli_json("track", "--target", "0.05,0.02", "--time", "2",
                   *[a for n, v in settings.items() for a in ("--set", f"{n}={v}")])
    py = cablelab.track(target=(0.05, 0.02), time=2, hand=cablelab.HandModel(**settings))
    default = cablelab.track(target=(0.05, 0.02), time=2)
    for key in ("final_error", "rms_error", "start_error", "grasp_time", "max_tension"):
        assert py[key] == cli[key], key
    assert py["rms_error"] != default["rms_error"]


def deprecation(match):
    return pytest.warns(DeprecationWarning, match=match)


def test_the_old_name_stiffness_warns_and_is_k():
    with deprecation(r"^HandModel: stiffness: deprecated, use k \(") as caught:
        old = cablelab.HandModel(stiffness=300.0)
    assert caught[0].filename == __file__  # points at the caller's line
    assert old.k == 300.0 and "stiffness" not in repr(old) and "k=300.0" in repr(old)
    assert same_run(old.world(), cablelab.HandModel(k=300.0).world())
    with deprecation("stiffness: deprecated, use k"):
        assert old.stiffness == 300.0
    with deprecation("stiffness: deprecated, use k"):
        old.stiffness = 200.0
    assert old.k == 200.0
    # A pickle made before the rename (its dict says stiffness) loads, warning.
    back = cablelab.HandModel.__new__(cablelab.HandModel)
    with deprecation("stiffness: deprecated, use k"):
        back.__setstate__({"stiffness": 250.0, "box_mass": 2.0})
    assert (back.k, back.box_mass) == (250.0, 2.0)
    assert "stiffness" not in pickle.loads(pickle.dumps(back)).__getstate__()
    with pytest.raises(cablelab.InputError) as error:
        cablelab.HandModel(k=300.0, stiffness=300.0)
    assert str(error.value) == "HandModel: stiffness: give k only (stiffness is its old name) (got both)"


def test_renamed_keywords_warn_and_reach_the_new_ones():
    hand, gains = cablelab.HandModel(k=300.0), cablelab.ControllerParams(kp=0.2)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        old = cablelab.HandController(model=hand, params=gains)
    assert [(w.category, str(w.message).split(" (")[0]) for w in caught] == [
        (DeprecationWarning, "HandController: model: deprecated, use hand"),
        (DeprecationWarning, "HandController: params: deprecated, use controller")]
    q = hand.open_pose() * 0.1

    def update(controller):  # one outer-loop update: depends on the hand and on the gains
        return controller.update(q, [0.0, 0.0], [0.02, 0.01], q)
    new = update(cablelab.HandController(hand=hand, controller=gains))
    assert np.array_equal(update(old), new)
    assert not np.array_equal(new, update(cablelab.HandController(controller=gains)))
    assert not np.array_equal(new, update(cablelab.HandController(hand=hand)))
    a, b = hand.world(), hand.world()
    with deprecation(r"^place_hand: model: deprecated, use hand") as caught:
        cablelab.place_hand(a, hand.open_pose(), model=hand)
    assert caught[0].filename == __file__
    cablelab.place_hand(b, hand.open_pose(), hand=hand)
    assert same_run(a, b)
    with pytest.raises(TypeError, match=r"^place_hand: model: give hand only"):
        cablelab.place_hand(a, hand.open_pose(), model=hand, hand=hand)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the new names warn about nothing
        cablelab.HandController(hand=hand, controller=gains)
        cablelab.HandModel(k=1.0).world()


@pytest.mark.parametrize("call, text", [
    (lambda: cablelab.HandController(hnd=cablelab.HandModel()),
     "HandController: hnd: no such keyword (known: hand, controller)"),
    (lambda: cablelab.place_hand(cablelab.World.load("hand"), [0] * 6, modl=None),
     "place_hand: modl: no such keyword (known: world, q, hand)"),
    (lambda: cablelab.HandGrasp(cablelab.World.load("hand"), hnd=None),
     "HandGrasp: hnd: no such keyword (known: world, hand, controller, options)"),
])
def test_a_misspelt_keyword_names_itself_and_the_known_ones(call, text):
    with pytest.raises(TypeError) as error:
        call()
    assert str(error.value) == text


@pytest.mark.parametrize("cls, field, value, text", [
    (cablelab.HandModel, "stiffness", -5, "HandModel: stiffness: must be positive (got -5)"),
    (cablelab.HandModel, "k", -5, "HandModel: k: must be positive (got -5)"),
    (cablelab.HandModel, "k", math.nan, "HandModel: k: must be finite (got nan)"),
    (cablelab.HandModel, "damping", -1, "HandModel: damping: must be >= 0 (got -1)"),
    (cablelab.HandModel, "preload", -0.1, "HandModel: preload: must be >= 0 (got -0.1)"),
    (cablelab.HandModel, "box_mass", 0, "HandModel: box_mass: must be positive (got 0)"),
    (cablelab.HandModel, "mu", -0.5, "HandModel: mu: must be >= 0 (got -0.5)"),
    (cablelab.HandModel, "turn", 2,
     "HandModel: turn: must be True or False (or the scene's 1 or 0) (got 2)"),
    (cablelab.HandModel, "turn", "yes",
     "HandModel: turn: must be True or False (or the scene's 1 or 0) (got \"'yes'\")"),
    (cablelab.HandModel, "turn", None,
     "HandModel: turn: must be True or False (or the scene's 1 or 0) (got \"None\")"),
    (cablelab.HandModel, "link_mass", "1", "HandModel: link_mass: must be a number (got a str)"),
    (cablelab.HandModel, "k", 1j, "HandModel: k: must be a number (got \"1j\")"),
    (cablelab.HandModel, "k", np.array([1.0, 2.0]),
     "HandModel: k: must be a number (got \"array([1., 2.])\")"),
    (cablelab.HandModel, "lower", [0.0] * 5, "HandModel: lower: must be 6 numbers (got shape (5,))"),
    (cablelab.ControllerParams, "period", 0, "ControllerParams: period: must be positive (got 0)"),
    (cablelab.ControllerParams, "kp", -0.1, "ControllerParams: kp: must be >= 0 (got -0.1)"),
    (cablelab.GraspOptions, "max_regrasps", -1, "GraspOptions: max_regrasps: must be >= 0 (got -1)"),
    (cablelab.GraspOptions, "max_regrasps", 2**70,
     "GraspOptions: max_regrasps: is too large (got 1180591620717411303424)"),
    (cablelab.GraspOptions, "close_time", 0, "GraspOptions: close_time: must be positive (got 0)"),
])
def test_a_bad_value_raises_at_once_in_one_line(cls, field, value, text):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError) as error:
            cls(**{field: value})
        assert isinstance(error.value, cablelab.InputError)
        assert str(error.value) == text and "\n" not in text
        obj = cls()
        with pytest.raises(cablelab.InputError) as error:
            setattr(obj, field, value)
        assert str(error.value) == text
    assert repr(obj) == repr(cls())  # unchanged


def test_turn_takes_true_false_and_the_scenes_one_and_zero():
    for value, turn in ((True, True), (1, True), (1.0, True), (np.bool_(True), True),
                        (False, False), (0, False)):
        assert cablelab.HandModel(turn=value).turn is turn, value


def test_a_shared_parameter_is_checked_alike_through_both_apis():
    for name, bad in (("k", -5), ("damping", -1), ("preload", -0.1), ("box_mass", 0), ("mu", -1)):
        with pytest.raises(cablelab.InputError) as scene:
            cablelab.World.load("hand", **{name: bad})
        with pytest.raises(cablelab.InputError) as model:
            cablelab.HandModel(**{name: bad})
        assert (scene.value.field, model.value.field) == (name, name)
        assert str(scene.value).split(": ", 2)[2] == str(model.value).split(": ", 2)[2]
    with pytest.raises(cablelab.InputError) as scene:  # refused by the scene's builder
        cablelab.World.load("hand", turn=2)
    assert str(scene.value) == "World.load: turn: must be 0 or 1 (got 2)"


# --- the docs' table -------------------------------------------------------------------------

def names_table():
    """The rows of docs/python.md's "One name per quantity" table: (quantity, set, python, old),
    each cell the list of its `code` spans."""
    text = (SOURCE_DIR / "docs" / "python.md").read_text()
    section = text.split("## One name per quantity", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("| ")][1:]
    cells = [[re.findall(r"`([^`]+)`", c) for c in row.strip().strip("|").split("|")]
             for row in rows]
    assert rows and all(len(c) == 4 for c in cells), rows
    return cells


def keywords_of(name):
    obj = getattr(cablelab, name)
    if inspect.isclass(obj):
        return _keywords._doc_keywords(obj.__doc__, name)
    return _keywords._keywords(obj)


def test_the_docs_table_of_names_is_the_codes():
    scene = hand_scene_params()
    model = cablelab.HandModel()
    fields = set(re.findall(r"(\w+)=", repr(model)))
    listed_sets, listed_fields, listed_keywords = set(), {}, {}
    for _, set_names, python, old in names_table():
        if set_names:  # a hand scene parameter: the same name as a HandModel field
            (name,) = set_names
            assert python == [f"HandModel.{name}"] and name in scene and name in fields, name
            listed_sets.add(name)
            for o in old:
                listed_fields[o.split(".")[1]] = name
        else:  # a keyword: `new=` of the callables listed, `old=` of some of them
            new = python[0].rstrip("=")
            for where in python[1:]:
                assert new in keywords_of(where), (new, where)
            for where in old[1:]:
                listed_keywords.setdefault(where, {})[old[0].rstrip("=")] = new
    assert listed_sets == set(scene)
    assert listed_fields == cablelab.HandModel._renamed
    assert listed_keywords == _keywords.RENAMED
