// Scene files: JSON <-> SceneDef. Loading validates every field and names it on error
// (InputError "file: bodies[2].mass: must be positive"); unknown keys are errors too, so a typo
// never silently falls back to a default. save -> load gives back the same SceneDef.
//
// Every field, its units and default: docs/scene-format.md (JSON Schema: docs/scene.schema.json).
// A scene written mid-run also has joints' "value", "time", "step_count" and a "history" (the scene
// as built and its inputs since) that World replays bit for bit (docs/scene-format.md).
// In brief (lengths m, masses kg, angles rad, every key but the lists optional):
// { "name": "...", "description": "...", "gravity": [0, -9.81], "dt": 0.0166, "substeps": 1,
//   "view": {"center": [0, 0], "height": 4},
//   "bodies": [{"name": "b", "type": "dynamic|static|kinematic", "position": [x, y], "angle": 0,
//               "velocity": [vx, vy], "angular_velocity": 0, "mass": 1, "inertia": 0,
//               "fixed_rotation": false, "linear_damping": 0, "angular_damping": 0,
//               "shapes": [{"type": "circle", "radius": r, "center": [x, y]},
//                          {"type": "box", "half_size": [hx, hy], "center": [x, y], "angle": 0},
//                          {"type": "polygon", "vertices": [[x, y], ...]}]}],
//              (shapes also take "friction", "restitution", "sensor")
//   "joints": [{"type": "revolute|prismatic|weld", "name": "j", "body_a": "world", "body_b": "b",
//               "anchor": [x, y], "axis": [1, 0], "limits": [lo, hi], "collide_connected": false,
//               "servo": {"kp": 500, "kd": 44.7, "target": 0, "max_force": 1e4}}],
//   "cables": [{"name": "c", "start": {"body": "world", "point": [x, y]}, "end": {...},
//               "pulleys": [{"type": "point", "body": "world", "point": [x, y],
//                            "side": "left|right|threaded"},
//                           {"type": "polygon", "body": "hex", "vertices": [[x, y], ...],
//                            "side": "left|right", "turns": 0, "mu": 0},
//                           {"type": "circle", "body": "wheel", "point": [x, y], "radius": r,
//                            "side": "left|right|auto", "turns": 0, "no_slip": false, "mu": 0}],
//               "rest_length": L, "stiffness": 0, "preload": 0, "damping": 0}] }
// Body-attached points are in the body frame; "world" points in the world frame. A box shape is
// stored as a polygon. rest_length omitted = the length at the initial pose. "mu" > 0 is capstan
// friction (docs/wheels.md): on a circle, holding while T_high <= T_low e^(mu theta); on a
// polygon, at each engaged corner with theta_i its turn (docs/polygon_friction.md); 0 = none.
// "no_slip" (circles only) and "mu" exclude each other; on a circle either needs a rigid cable
// (a polygon with "mu" also grips an elastic one: docs/polygon_friction.md "Elastic cables").
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "engine/model/scene.h"

namespace cablelab {

SceneDef sceneFromJson(const nlohmann::json& j, const std::string& source);
nlohmann::json sceneToJson(const SceneDef& scene);

/// A pulley's `type` in the scene file: "point", "polygon" or "circle".
const char* pulleyTypeName(PulleyDef::Kind kind);

/// Reads and validates a scene file; throws InputError (missing file, bad JSON, bad field).
SceneDef loadSceneFile(const std::string& path);
void saveSceneFile(const SceneDef& scene, const std::string& path);

}  // namespace cablelab
