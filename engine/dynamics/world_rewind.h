// Rewind: a World as it was right after an earlier step, rebuilt the only bit-exact way there is
// (world_state.h): from its scene, replaying its history up to that step. The sandbox's timeline
// (ui/timeline.h) keeps the history of the run it rewinds and restores from it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/dynamics/world_history.h"
#include "engine/model/scene.h"

namespace cablelab {

class World;

/// The inputs of `inputs` up to and including its `steps`-th step: the history of the moment
/// right after that step (inputs recorded after it, before the next step, are left out).
/// Throws std::out_of_range when the history holds fewer steps.
std::vector<WorldInput> inputsThroughStep(const std::vector<WorldInput>& inputs, long steps);

/// A World built from `scene` with `inputs` replayed through its `steps`-th step (bit for bit the
/// World that took those inputs, at stepCount() == steps).
std::unique_ptr<World> rewoundWorld(const SceneDef& scene, const std::vector<WorldInput>& inputs,
                                    long steps, const std::string& source);

}  // namespace cablelab
