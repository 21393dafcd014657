# docs/scene.schema.json and docs/scene-format.md against the loader (engine/model/scene_json.cpp):
# every scene the loader accepts (assets/, examples/, tests/data/, the built-in scenes as to_dict
# writes them) passes the schema; every bad scene under tests/data/bad/ is rejected by the schema
# unless its fault is one the schema cannot express (listed below, and checked to stay so); on
# single-field changes of good scenes the schema and the loader agree; the docs and the schema
# name every field the loader reads.
import json
import math
import pathlib
import re

import pytest

import cablelab

jsonschema = pytest.importorskip("jsonschema")

ROOT = pathlib.Path(__file__).parents[2]
SCHEMA = json.loads((ROOT / "docs" / "scene.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)

# Bad scenes whose fault needs the whole scene or geometry (the loader's checks alone).
BEYOND_THE_SCHEMA = {
    "scene_box_too_small.json": "polygon area",
    "scene_coincident_cable_ends.json": "geometry",
    "scene_duplicate_body.json": "unique names",
    "scene_joint_unknown_body.json": "name references",
    "scene_limits_reversed.json": "lower <= upper",
    "scene_polygon_not_convex.json": "convexity",
    "scene_polygon_too_thin.json": "polygon area",
    "scene_unknown_cable_body.json": "name references",
}


def loader_accepts(scene):
    try:
        cablelab.World.from_dict(scene)
        return True
    except cablelab.InputError:
        return False


def schema_accepts(scene):
    return VALIDATOR.is_valid(scene)


def json_files():
    for folder in (ROOT / "assets", ROOT / "examples", ROOT / "tests" / "data"):
        for path in sorted(folder.rglob("*.json")):
            if "bad" not in path.parts:
                yield path


def test_the_schema_is_a_valid_draft_2020_12_schema():
    jsonschema.Draft202012Validator.check_schema(SCHEMA)


def test_every_scene_the_loader_accepts_passes_the_schema():
    scenes = 0
    for path in json_files():
        try:
            cablelab.World.load(str(path))
        except cablelab.InputError:
            continue  # statics, wrap and fit inputs live there too
        scenes += 1
        errors = [e.message for e in VALIDATOR.iter_errors(json.loads(path.read_text()))]
        assert not errors, (path, errors[:3])
    assert scenes >= 25  # assets/scenes and tests/data's scenes were all seen


def test_every_built_in_scene_as_saved_passes_the_schema():
    for name in [s["name"] for s in cablelab.scenes()]:
        for current in (False, True):
            d = cablelab.World.load(name).to_dict(current=current)
            assert schema_accepts(d), (name, next(VALIDATOR.iter_errors(d)).message)


def test_bad_scenes_are_rejected_by_the_schema_where_it_can_tell():
    bad = sorted((ROOT / "tests" / "data" / "bad").glob("scene_*.json"))
    assert len(bad) >= 25
    for path in bad:
        try:
            scene = json.loads(path.read_text())
        except json.JSONDecodeError:
            continue  # not JSON at all: no schema applies
        with pytest.raises(cablelab.InputError):
            cablelab.World.load(str(path))
        if path.name in BEYOND_THE_SCHEMA:
            assert schema_accepts(scene), f"{path.name} now caught by the schema: update the list"
        else:
            assert not schema_accepts(scene), path.name


def scene_file(relative):
    return json.loads((ROOT / relative).read_text())


def pulley(scene, kind):
    """The first pulley of this type in the scene."""
    return next(p for c in scene["cables"] for p in c.get("pulleys", [])
                if p.get("type", "point") == kind)


def body(s):
    return s["bodies"][-1]


def joint(s):
    return s["joints"][-1]


def nine_gon(s):
    body(s).update(shapes=[{"type": "polygon", "vertices": [
        [0.1 * math.cos(2 * math.pi * a / 9), 0.1 * math.sin(2 * math.pi * a / 9)]
        for a in range(9)]}])


WHEELS = "tests/data/wheels/good_wheels_scene.json"  # joints, a servo with speed, circle pulleys
CAPSTAN = "assets/scenes/capstan.json"  # a capstan wheel (mu) and a point pulley
HEXAGON = "assets/scenes/hexagon.json"  # a polygon pulley
CHANGES = {
    "unknown root key": (WHEELS, lambda s: s.update(gravitty=[0, -9.81])),
    "substeps 0": (WHEELS, lambda s: s.update(substeps=0)),
    "substeps 1000": (WHEELS, lambda s: s.update(substeps=1000)),
    "dt 1": (WHEELS, lambda s: s.update(dt=1)),
    "view height 0": (WHEELS, lambda s: s.update(view={"height": 0})),
    "view unknown key": (WHEELS, lambda s: s.update(view={"zoom": 2})),
    "body named world": (WHEELS, lambda s: body(s).update(name="world")),
    "static body with mass 0": (WHEELS, lambda s: body(s).update(type="static", mass=0)),
    "dynamic body with mass 0": (WHEELS, lambda s: body(s).update(mass=0)),
    "negative damping": (WHEELS, lambda s: body(s).update(linear_damping=-1)),
    "circle shape with vertices": (WHEELS, lambda s: body(s).update(
        shapes=[{"type": "circle", "radius": 0.1, "vertices": [[0, 0], [1, 0], [0, 1]]}])),
    "box shape with radius": (WHEELS, lambda s: body(s).update(
        shapes=[{"type": "box", "half_size": [0.1, 0.1], "radius": 0.1}])),
    "box shape turned": (WHEELS, lambda s: body(s).update(
        shapes=[{"type": "box", "half_size": [0.1, 0.2], "angle": 0.3, "center": [0, 0.1]}])),
    "polygon shape with 9 vertices": (WHEELS, nine_gon),
    "joint body_b world": (WHEELS, lambda s: joint(s).update(body_b="world")),
    "servo max_force 0": (WHEELS, lambda s: joint(s).update(servo={"max_force": 0})),
    "servo speed": (WHEELS, lambda s: joint(s).update(servo={"speed": 0.5, "kp": 100})),
    "servo unknown key": (WHEELS, lambda s: joint(s).update(servo={"ki": 1})),
    "joint with 3 limits": (WHEELS, lambda s: joint(s).update(limits=[0, 1, 2])),
    "joint limits": (WHEELS, lambda s: joint(s).update(limits=[-1, 1])),
    "anchor side without radius": (WHEELS, lambda s: s["cables"][0]["start"].update(side="left")),
    "anchor turns without radius": (WHEELS, lambda s: s["cables"][0]["start"].update(turns=2)),
    "drum": (WHEELS, lambda s: s["cables"][0]["start"].update(radius=0.05, side="right", turns=2)),
    "drum auto": (WHEELS, lambda s: s["cables"][0]["start"].update(radius=0.05, side="auto")),
    "point pulley with turns": (CAPSTAN, lambda s: pulley(s, "point").update(turns=1)),
    "point pulley with radius": (CAPSTAN, lambda s: pulley(s, "point").update(radius=1)),
    "point pulley auto": (CAPSTAN, lambda s: pulley(s, "point").update(side="auto")),
    "point pulley left": (CAPSTAN, lambda s: pulley(s, "point").update(side="left")),
    "point pulley without type": (CAPSTAN, lambda s: pulley(s, "point").pop("type")),
    "circle pulley without radius": (CAPSTAN, lambda s: pulley(s, "circle").pop("radius")),
    "circle pulley with vertices": (CAPSTAN, lambda s: pulley(s, "circle").update(
        vertices=[[0, 0], [1, 0], [0, 1]])),
    "circle pulley turns 2.25": (CAPSTAN, lambda s: pulley(s, "circle").update(turns=2.25)),
    "circle pulley turns with auto": (CAPSTAN, lambda s: pulley(s, "circle").update(
        side="auto")),
    "circle pulley mu 0 on auto": (CAPSTAN, lambda s: pulley(s, "circle").update(
        side="auto", mu=0, turns=0)),
    "circle pulley mu on auto": (CAPSTAN, lambda s: pulley(s, "circle").update(
        side="auto", turns=0)),
    "no_slip false with mu": (CAPSTAN, lambda s: pulley(s, "circle").update(no_slip=False)),
    "no_slip true with mu": (CAPSTAN, lambda s: pulley(s, "circle").update(no_slip=True)),
    "no_slip instead of mu": (CAPSTAN, lambda s: (pulley(s, "circle").pop("mu"),
                                                  pulley(s, "circle").update(no_slip=True))),
    "gripping wheel on an elastic cable": (CAPSTAN, lambda s: s["cables"][0].update(
        stiffness=100)),
    "free wheel on an elastic cable": (CAPSTAN, lambda s: (
        pulley(s, "circle").pop("mu"), s["cables"][0].update(stiffness=100))),
    "polygon pulley with radius": (HEXAGON, lambda s: pulley(s, "polygon").update(radius=1)),
    "polygon pulley with mu": (HEXAGON, lambda s: pulley(s, "polygon").update(mu=0.2)),
    "polygon pulley threaded": (HEXAGON, lambda s: pulley(s, "polygon").update(side="threaded")),
    "polygon pulley turns 1": (HEXAGON, lambda s: pulley(s, "polygon").update(turns=1)),
    "polygon pulley turns on auto": (HEXAGON, lambda s: pulley(s, "polygon").update(
        turns=1, side="auto")),
    "polygon pulley with 2 vertices": (HEXAGON, lambda s: pulley(s, "polygon").update(
        vertices=[[0, 0], [1, 0]])),
    "cable rest_length negative": (WHEELS, lambda s: s["cables"][0].update(rest_length=-1)),
    "cable unknown key": (WHEELS, lambda s: s["cables"][0].update(stifness=1)),
    "cable without end": (WHEELS, lambda s: s["cables"][0].pop("end")),
    "unknown pulley type": (CAPSTAN, lambda s: pulley(s, "point").update(type="disc")),
}


def test_the_schema_and_the_loader_agree_on_single_field_changes():
    """Each change made to a good scene: the schema's verdict is the loader's."""
    disagreements, verdicts = [], set()
    for what, (base, change) in CHANGES.items():
        scene = scene_file(base)
        assert loader_accepts(scene) and schema_accepts(scene), base
        change(scene)
        loader, schema = loader_accepts(scene), schema_accepts(scene)
        verdicts.add(loader)
        if loader != schema:
            disagreements.append(f"{what}: loader {loader}, schema {schema}")
    assert not disagreements, disagreements
    assert verdicts == {True, False}  # the changes cover both verdicts


def loader_field_names():
    """Every key scene_json.cpp reads: the first argument of the reader's accessors."""
    source = (ROOT / "engine" / "model" / "scene_json.cpp").read_text()
    accessors = "string|requiredString|number|integer|boolean|vec2|points|list|has|child|item"
    calls = rf'\b\w\.(?:{accessors})\("(\w+)"'
    return set(re.findall(calls, source))  # the writer uses j["..."], never these


def schema_field_names(node=SCHEMA):
    names = set()
    if isinstance(node, dict):
        names |= set(node.get("properties", {}))
        for value in node.values():
            names |= schema_field_names(value)
    elif isinstance(node, list):
        for value in node:
            names |= schema_field_names(value)
    return names


def test_the_docs_and_the_schema_name_every_field_the_loader_reads():
    fields = loader_field_names()
    # The loader's own words for the fields the issue names (a regex that found nothing would pass).
    assert {"radius", "turns", "no_slip", "mu", "speed", "half_size", "max_force"} <= fields
    assert len(fields) >= 40
    doc = (ROOT / "docs" / "scene-format.md").read_text()
    assert not [f for f in fields if not re.search(rf"`(\w+\.)*{f}`", doc)]  # `view.height`
    assert not sorted(fields - schema_field_names())
    # And nothing the loader does not read.
    assert not sorted(schema_field_names() - fields)
