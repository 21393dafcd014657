// The one list of built-in scenes: it feeds `cablelab scenes`, `run`, `snapshot`, the sandbox
// menu and the test that steps every scene. Each scene is built from named parameters (--set).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab {

struct SceneParam {
  enum class Range { Positive, NonNegative, Any };
  std::string name;
  double value;             ///< default
  std::string description;  ///< with units
  Range range = Range::Positive;
};

using SceneParams = std::map<std::string, double>;

struct SceneInfo {
  std::string name;
  std::string description;
  std::vector<SceneParam> params;
  std::function<SceneDef(const SceneParams&)> build;  ///< gets every param, defaults filled in
};

/// Built-in scenes in menu order.
const std::vector<SceneInfo>& builtinScenes();
const SceneInfo* findBuiltinScene(const std::string& name);

/// A built-in name or a scene file path, with --set overrides ("name", value).
/// Throws InputError for an unknown scene or parameter, or a bad file.
SceneDef makeScene(const std::string& nameOrPath,
                   const std::vector<std::pair<std::string, double>>& overrides = {});

/// Parses "NAME=VALUE" (for --set); throws InputError naming the argument.
std::pair<std::string, double> parseSetting(const std::string& text);

// Builders, one file each (scene_<name>.cpp).
SceneDef makeBallastScene(const SceneParams& p);
SceneDef makeHandScene(const SceneParams& p);
SceneDef makeHexagonScene(const SceneParams& p);
SceneDef makeMembraneScene(const SceneParams& p);
SceneDef makePulleyScene(const SceneParams& p);
SceneDef makeWheelScene(const SceneParams& p);
SceneDef makeCapstanScene(const SceneParams& p);
SceneDef makeWinchScene(const SceneParams& p);
SceneDef makeTackleScene(const SceneParams& p);

}  // namespace cablelab
