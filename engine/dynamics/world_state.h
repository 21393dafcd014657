// WorldState: everything a World's next step depends on, to fork a World (rollouts, MPC) or send
// it to another process. Box2D 2.4 keeps contact caches, warm-start impulses and its broad-phase
// tree where they cannot be copied, and the cable solver keeps warm starts and wrap-selection
// caches; a World rebuilt from poses alone steps differently in the last bits. So the state is the
// scene plus the World's input history (world_history.h), and restoring it rebuilds the World and
// replays the history: bit for bit the same, at the cost of the steps replayed (docs/python.md).
// The poses and joint values captured with it are for reading only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"

namespace cablelab {

struct WorldState {
  SceneDef scene;                  ///< the scene the World was built from
  std::string source;              ///< names it in errors
  std::vector<WorldInput> inputs;  ///< the history, oldest first
  // Read-only copies taken with the state (restoring does not read them).
  double time = 0;                   ///< s
  long steps = 0;                    ///< World::stepCount()
  std::vector<BodyState> bodies;     ///< per body
  std::vector<double> jointValues;   ///< per joint (rad or m)
  std::vector<double> servoTargets;  ///< per joint (rad or m)
};

/// The state of `world` now.
WorldState captureState(const World& world, const std::string& source);

/// A World in `state`: built from its scene, with its history replayed. Throws InputError for an
/// input that names no body, cable or joint of the scene (a state edited by hand).
std::unique_ptr<World> restoreWorld(const WorldState& state);

/// The scene with `world`'s state now in place of the initial one: poses, velocities, joint
/// coordinates (JointDef::value) and anchors, servo targets, cable parameters, gravity, time
/// and step count, and the history (the scene as built and the inputs since) from which
/// World(scene) rebuilds `world` bit for bit (Python's World.to_dict(current=True)).
SceneDef sceneNow(const World& world);

/// For World's constructor, given a scene with a history: replays the history on `world` (built
/// from history->origin), then checks that it led to the state `written` gives; InputError
/// (source, "history") if not (the scene was edited after it was written).
void resumeHistory(World& world, const SceneDef& written, const std::string& source);

/// The history as rows (kind, index, count, four values) and back; fromRows throws InputError
/// (source, "history.inputs[i]") for a row that is no input.
std::vector<std::array<double, 7>> inputRows(const std::vector<WorldInput>& inputs);
std::vector<WorldInput> inputsFromRows(const std::vector<std::array<double, 7>>& rows,
                                       const std::string& source,
                                       const std::string& field = "history.inputs");

/// Replays `inputs` on `world` in order (each as the World method it records).
void replayInputs(World& world, const std::vector<WorldInput>& inputs, const std::string& source);

}  // namespace cablelab
