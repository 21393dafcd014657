// Scene catalog: the one place the UI reaches the engine's scene registry.
//
// Needs: engine/scenes/scene_registry.h (built-in scenes) and engine/model/scene_json.h (scene files).
// The sandbox menu, `cablelab snapshot` and the golden-image tests all list and load scenes
// through these two functions, so they always agree with `cablelab scenes`.
#pragma once

#include <string>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab::ui {

struct SceneEntry {
  std::string name;
  std::string description;
};

/// Every built-in scene, in the registry's order.
std::vector<SceneEntry> builtinSceneList();

/// A built-in scene by name, or a scene JSON file by path; throws InputError naming the
/// file or scene on failure.
SceneDef loadScene(const std::string& nameOrPath);

/// The scene the sandbox opens with no argument: "hand" if it exists, else the first one.
std::string defaultSceneName();

}  // namespace cablelab::ui
