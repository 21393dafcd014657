// The `hand` scene's parameters as a HandModel, for the commands that run the hand under its
// controller (`track`, `reach`) and take the scene's --set like `run hand`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/hand/hand_model.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {

/// Every parameter of `scene`, defaults filled in and --set overrides applied; throws InputError
/// for an unknown parameter or a value out of its range (as makeScene()).
SceneParams sceneParams(const SceneInfo& scene,
                        const std::vector<std::pair<std::string, double>>& overrides);

/// The hand of the `hand` scene with its parameters (k, damping, preload, box_mass, turn, mu) and
/// the --set overrides; throws InputError as makeScene() does.
HandModel handModelWithSettings(const std::vector<std::pair<std::string, double>>& overrides);

}  // namespace cablelab
