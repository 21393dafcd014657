// Scene catalog: the one place the UI reaches the engine's scene registry.
//
// Needs: engine/scenes/scene_registry.h (built-in scenes) and engine/model/scene_json.h (scene
// files). The sandbox menu, `cablelab snapshot` and the golden-image tests all list and load scenes
// through these two functions, so they always agree with `cablelab scenes`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab::ui {

struct SceneEntry {
  std::string name;
  std::string description;
};

/// One `--set` parameter of a built-in scene, for the Scene panel's sliders.
struct SceneParameter {
  std::string name;
  double value = 0;         ///< the scene's default
  std::string description;  ///< with units
  double lo = 0, hi = 1;    ///< slider range (the registry's range of allowed values within it)
  bool logarithmic = false;
};

/// The parameters of built-in scene `name` (empty for files and unknown names).
std::vector<SceneParameter> sceneParameters(const std::string& name);

/// Scene JSON files bundled with the project (assets/scenes/*.json), sorted by path; empty
/// when the assets directory cannot be found.
std::vector<std::string> bundledSceneFiles();

/// Every built-in scene, in the registry's order.
std::vector<SceneEntry> builtinSceneList();
/// Whether `name` names a built-in scene (not a file).
bool isBuiltinScene(const std::string& name);

/// A built-in scene by name, or a scene JSON file by path; throws InputError naming the
/// file or scene on failure.
SceneDef loadScene(const std::string& nameOrPath);
/// A built-in scene with `--set` overrides (name, value); throws InputError as makeScene.
SceneDef loadScene(const std::string& name,
                   const std::vector<std::pair<std::string, double>>& overrides);

/// The scene the sandbox opens with no argument: "hand" if it exists, else the first one.
std::string defaultSceneName();

}  // namespace cablelab::ui
