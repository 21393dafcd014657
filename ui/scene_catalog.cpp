#include "ui/scene_catalog.h"

#include "engine/scenes/scene_registry.h"

namespace cablelab::ui {

std::vector<SceneEntry> builtinSceneList() {
  std::vector<SceneEntry> list;
  for (const auto& info : builtinScenes()) list.push_back({info.name, info.description});
  return list;
}

SceneDef loadScene(const std::string& nameOrPath) {
  return makeScene(nameOrPath, {});
}

std::string defaultSceneName() {
  const auto list = builtinSceneList();
  for (const auto& entry : list)
    if (entry.name == "hand") return entry.name;
  return list.empty() ? std::string("hand") : list.front().name;
}

}  // namespace cablelab::ui
