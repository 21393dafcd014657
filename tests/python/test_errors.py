# Bad input raises cablelab.InputError naming the field; nothing crashes the interpreter.
import inspect
import json
import math

import numpy as np
import pytest

import cablelab


def message(fn, *args, **kwargs):
    with pytest.raises(cablelab.InputError) as e:
        fn(*args, **kwargs)
    assert isinstance(e.value, ValueError)
    return str(e.value)


def test_input_error_has_source_and_field():
    with pytest.raises(cablelab.InputError) as e:
        cablelab.World.from_dict({"bodies": [{"name": "b", "mass": -1.0,
                                              "shapes": [{"type": "circle", "radius": 1}]}]})
    assert e.value.source == "dict" and e.value.field == "bodies[0].mass"
    assert str(e.value).startswith("dict: bodies[0].mass: ")


@pytest.mark.parametrize("scene,field", [
    ({"bodies": [{"name": "b", "position": [math.nan, 0], "shapes": [{"type": "circle"}]}]}, "bodies[0].position[0]"),
    ({"bodies": [{"name": "b", "position": np.array([0.0, np.inf]), "shapes": [{"type": "circle"}]}]}, "bodies[0].position[1]"),
    ({"bodies": [{"name": "b", "shapes": [{"type": "circle"}], "colour": "red"}]}, "bodies[0]"),
    ({"bodies": {1, 2}}, "bodies"),
    ({"bodies": [{"name": 3}]}, "bodies[0].name"),
    ({"dt": 10**400}, "dt"),
])
def test_bad_dict_names_the_field(scene, field):
    assert field in message(cablelab.World.from_dict, scene)


def test_from_dict_accepts_numpy_values():
    w = cablelab.World.from_dict({"gravity": np.array([0.0, -1.0]), "dt": np.float64(0.01),
                                  "substeps": np.int64(2),
                                  "bodies": [{"name": "b", "position": np.zeros(2),
                                              "shapes": [{"type": "circle", "radius": 0.5}]}]})
    assert w.substeps == 2 and w.gravity == [0.0, -1.0]


@pytest.mark.parametrize("kwargs,field", [
    ({"dt": 0}, "dt"), ({"dt": -1e-3}, "dt"), ({"dt": 2}, "dt"), ({"dt": math.nan}, "dt"),
    ({"substeps": 0}, "substeps"), ({"substeps": 1001}, "substeps"), ({"substeps": 1.5}, "substeps"),
])
def test_bad_step_arguments(kwargs, field):
    w = cablelab.World.load("pulley")
    assert f"step: {field}: " in message(w.step, **kwargs)
    assert w.step_count == 0


def test_bad_run_arguments():
    w = cablelab.World.load("pulley")
    message(w.run)
    message(w.run, 1.0, steps=3)
    message(w.run, -1.0)
    message(w.run, steps=-1)
    message(w.run, 1e9, dt=1e-3)


@pytest.mark.parametrize("call", [
    lambda w: w.body_state(7),
    lambda w: w.body_state(-1),
    lambda w: w.body_state("nobody"),
    lambda w: w.set_body_state(0, [0, 0, 0]),
    lambda w: w.set_body_state(0, [0, 0, 0, 0, math.nan, 0]),
    lambda w: w.set_body_state(0, [1e30, 0, 0, 0, 0, 0]),
    lambda w: w.set_body_states(np.zeros((5, 6))),
    lambda w: w.apply_force(0, (math.inf, 0)),
    lambda w: w.apply_force(0, "up"),
    lambda w: w.cable_path(3),
    lambda w: w.set_servo_target("no_joint", 0.1),
    lambda w: w.set_servo_targets([1.0]),
    lambda w: w.set_cable_parameters("cable", stiffness=-1),
    lambda w: setattr(w, "gravity", (0, math.nan)),
])
def test_bad_world_calls_raise(call):
    w = cablelab.World.load("pulley")
    message(call, w)
    w.step()  # still usable


def test_a_servo_target_that_is_no_number_says_what_it_got():
    w = cablelab.World.load("winch")
    assert message(w.set_servo_target, 0, math.nan) == \
        "set_servo_target: target: must be finite and within +/-1e12 (got nan)"
    assert message(w.set_servo_targets, [math.inf]).endswith("targets[0]: must be finite (got inf)")


def test_unknown_scene_lists_the_builtins():
    text = message(cablelab.World.load, "no_such_scene")
    # The one style (docs/cli.md): SOURCE: FIELD: what is wrong (got VALUE).
    assert "pulley" in text and text.startswith("World.load: scene: no such built-in scene")
    assert text.endswith('(got "no_such_scene")')


def test_bad_scene_parameter_values():
    assert "must be positive" in message(cablelab.World.load, "pulley", m_left=-1)
    assert "must be a number" in message(cablelab.World.load, "pulley", m_left="heavy")
    assert "must be finite" in message(cablelab.World.load, "pulley", m_left=math.inf)


@pytest.mark.parametrize("args,kwargs", [
    ([[]], {}),
    ([[{"a": [0, 0], "b": [1, 0], "k": -1, "L": 1}]], {}),
    ([[{"a": [0, 0], "b": [1, 0], "k": 1, "L": 1}]], {"solver": "magic"}),
    ([np.array([[0, 0, 1, 0, 1, np.nan]])], {}),
    ([np.zeros((2, 5))], {}),
    ([[{"a": [0, 0], "b": [1, 0], "k": 1, "L": 1}]], {"p0": [0, math.nan]}),
    (["/no/such/file.json"], {}),
])
def test_bad_statics(args, kwargs):
    message(cablelab.statics, *args, **kwargs)


def test_bad_wrap_fit_and_membrane():
    square = [[-1, -1], [1, -1], [1, 1], [-1, 1]]
    message(cablelab.wrap, [0, 0], [3, 0], square, "left")  # A inside the polygon
    message(cablelab.wrap, [-3, 0], [3, 0], square, "up")
    message(cablelab.wrap, [-3, 0], [3, 0], [[0, 0], [1, 1]], "left")
    message(cablelab.fit, np.zeros((5, 3)), (-0.2, 0, 0.2, 0))
    message(cablelab.fit, np.array([[0, -0.1, np.nan, 90]] * 5), (-0.2, 0, 0.2, 0))
    message(cablelab.fit, "/no/such.csv", (-0.2, 0, 0.2, 0))
    message(cablelab.fit, np.zeros((5, 4)), (0, 0, 0, 0))
    message(cablelab.membrane_data, 10, 0.1, (-0.2, 0, 0.2, 0), grid=(0, 3))
    message(cablelab.membrane_model, (-0.2, 0, 0.2, 0), 10, 0.1, np.array([[0.0, 0.0]]))


def test_bad_hand_calls():
    message(cablelab.track, target=(1, 1), ramp=(1, 1, 2))
    message(cablelab.track, ramp=(1, 1, 0))
    message(cablelab.track, target=(1e3, 0))
    message(cablelab.track, time=-1)
    message(cablelab.reach, grid=0)
    message(cablelab.hand_joints, cablelab.World.load("pulley"))
    message(cablelab.HandModel, stifness=3)
    message(cablelab.HandController().predict, [0, 0, 0])


def test_bad_render_calls(tmp_path):
    w = cablelab.World.load("pulley")
    message(cablelab.render, w, (8, 8))
    message(cablelab.render, w, (100.5, 100))
    message(cablelab.snapshot, w, tmp_path / "no_dir" / "x.png", (64, 64))


def test_simulation_error_is_a_runtime_error():
    assert issubclass(cablelab.SimulationError, RuntimeError)
    assert issubclass(cablelab.InputError, ValueError)


def mutations(scene, rng, count):
    """Copies of scene with one leaf replaced by a bad or odd value, or one key removed."""
    leaves = []

    def walk(node, path):
        items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else []
        for k, v in items:
            leaves.append(path + [k])
            walk(v, path + [k])

    walk(scene, [])
    odd = [math.nan, -1.0, 0.0, 1e300, -1e300, 1e-300, "x", None, [], {}, [1.0], True, 10**20]
    for _ in range(count):
        d = json.loads(json.dumps(scene))
        path = leaves[rng.integers(len(leaves))]
        parent = d
        for k in path[:-1]:
            parent = parent[k]
        if rng.random() < 0.2 and isinstance(parent, dict):
            del parent[path[-1]]
        else:
            parent[path[-1]] = odd[rng.integers(len(odd))]
        yield d


@pytest.mark.parametrize("scene", ["hand", "hexagon", "pulley", "membrane", "ballast"])
def test_mutated_scenes_load_or_raise_input_error(scene):
    rng = np.random.default_rng(15)
    base = cablelab.World.load(scene).to_dict()
    loaded = refused = 0
    for d in mutations(base, rng, 60):
        try:
            w = cablelab.World.from_dict(d)
        except cablelab.InputError:
            refused += 1
            continue
        loaded += 1
        try:
            w.run(steps=5)
        except cablelab.SimulationError:
            continue
        assert np.isfinite(w.body_states()).all()  # a run that succeeds never gives NaN
    assert refused > 0 and loaded + refused == 60


def test_keyword_errors_name_the_keyword_in_python_words():
    text = message(cablelab.World.load, "pulley", m1=2.0)
    assert text == ("World.load: m1: no such keyword for scene 'pulley' (known: m_left, m_right, "
                    "L) (got m1=2.0)")
    text = message(cablelab.World.load, "pulley", m_left=-1)
    assert text == "World.load: m_left: must be positive (got -1)"
    for t in (text, message(cablelab.World.load, "no_such_scene"),
              message(cablelab.track, target=(1, 2, 3))):
        assert "--" not in t and "command line" not in t
    assert cablelab.World.load("pulley", m_left=2.0).to_dict()["bodies"][0]["mass"] == 2.0


def test_a_keyword_that_breaks_a_built_in_scene_is_named():
    # The scene's own field (joints[0].servo.speed) is quoted, the keyword is the field.
    text = message(cablelab.World.load, "winch", omega=1e308)
    assert text == ("World.load: omega: makes scene winch invalid (joints[0].servo.speed: must be "
                    "within +/-1e12 (got 1e+308)) (got \"omega=1e+308\")")
    assert "scene 'winch'" not in text


def test_a_polygon_pulley_on_a_body_without_a_polygon_says_so():
    scene = {"bodies": [{"name": "drum", "shapes": [{"type": "circle"}]},
                        {"name": "w", "position": [0.5, -1]}],
             "cables": [{"name": "c", "start": {"point": [-0.5, 1]}, "end": {"body": "w"},
                         "pulleys": [{"type": "polygon", "body": "drum"}]}]}
    assert message(cablelab.World.from_dict, scene) == (
        'dict: cables[0].pulleys[0].vertices: is required: body "drum" has no polygon or box '
        "shape to take them from (got nothing)")
    scene["bodies"][0]["shapes"] = [{"type": "box"}]  # a box is a polygon: it wraps
    cablelab.World.from_dict(scene).run(steps=3)


def test_a_scene_file_takes_no_keywords(tmp_path):
    path = tmp_path / "s.json"
    path.write_text(json.dumps(cablelab.World.load("pulley").to_dict()))
    assert message(cablelab.World.load, path, m_left=2.0).startswith(
        "World.load: m_left: a scene file takes no keywords")


def test_value_classes_check_each_field_when_given():
    assert message(cablelab.HandModel, k=-5) == "HandModel: k: must be positive (got -5)"
    h = cablelab.HandModel()
    with pytest.raises(cablelab.InputError, match=r"^HandModel: box_mass: must be positive"):
        h.box_mass = 0.0
    assert h.box_mass == cablelab.HandModel().box_mass  # unchanged
    with pytest.raises(cablelab.InputError, match=r"^HandModel: lower\[2\]: must be finite"):
        h.lower = [0, 0, math.nan, 0, 0, 0]
    text = message(cablelab.HandModel, stifness=3)
    assert text.startswith("HandModel: stifness: no such field (known: ") and ", k, " in text
    assert message(cablelab.ControllerParams, period=0) == \
        "ControllerParams: period: must be positive (got 0)"
    assert "must be an integer" in message(cablelab.GraspOptions, max_regrasps=1.5)
    assert "must be >= 0" in message(cablelab.GraspOptions, stop_time=-0.1)


def test_a_misspelt_keyword_is_named_with_the_known_ones():
    """pybind11 alone answers "incompatible function arguments" with the whole signature."""
    w = cablelab.World.load("hand")
    cases = [(lambda: w.step(dtt=0.1), "World.step: dtt: no such keyword (known: dt, substeps)"),
             (lambda: w.set_servo_targets(targts=[0.0] * 6),
              "World.set_servo_targets: targts: no such keyword (known: targets)"),
             (lambda: cablelab.World.from_dict({}, sorce="x"),
              "World.from_dict: sorce: no such keyword (known: scene, source)"),
             (lambda: cablelab.rollout([w], 3, thread=2),
              "rollout: thread: no such keyword (known: worlds, steps, controls, threads)")]
    for call, message in cases:
        with pytest.raises(TypeError) as error:
            call()
        assert str(error.value) == message
    # Right keywords still work, and the signatures stay visible.
    w.step(dt=0.01, substeps=2)
    assert w.step_count == 1 and list(inspect.signature(cablelab.World.step).parameters) == [
        "self", "dt", "substeps"]
