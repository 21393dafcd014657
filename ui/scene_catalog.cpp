#include "ui/scene_catalog.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

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

SceneDef loadScene(const std::string& name,
                   const std::vector<std::pair<std::string, double>>& overrides) {
  return makeScene(name, overrides);
}

bool isBuiltinScene(const std::string& name) {
  return findBuiltinScene(name) != nullptr;
}

std::vector<SceneParameter> sceneParameters(const std::string& name) {
  std::vector<SceneParameter> list;
  const SceneInfo* info = findBuiltinScene(name);
  if (!info) return list;
  for (const SceneParam& p : info->params) {
    SceneParameter q{p.name, p.value, p.description};
    const double a = std::abs(p.value);
    switch (p.range) {
      case SceneParam::Range::Positive:  // a factor of 10 either way, on a log scale
        q.lo = a > 0 ? a / 10 : 1e-3;
        q.hi = a > 0 ? a * 10 : 1;
        q.logarithmic = true;
        break;
      case SceneParam::Range::NonNegative:
        q.lo = 0;
        q.hi = a > 0 ? 5 * a : 1;
        break;
      case SceneParam::Range::Any:
        q.hi = a > 0 ? 5 * a : 1;
        q.lo = -q.hi;
        break;
    }
    list.push_back(q);
  }
  return list;
}

std::vector<std::string> bundledSceneFiles() {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  // The source tree's assets (a build tree knows it), else assets/ next to the working dir.
  std::vector<fs::path> roots = {fs::path("assets/scenes")};
#ifdef CABLELAB_ASSETS_DIR
  roots.insert(roots.begin(), fs::path(CABLELAB_ASSETS_DIR) / "scenes");
#endif
  for (const fs::path& root : roots) {
    std::error_code error;
    if (!fs::is_directory(root, error)) continue;
    for (const auto& entry : fs::directory_iterator(root, error))
      if (entry.path().extension() == ".json") files.push_back(entry.path().string());
    if (!files.empty()) break;
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string defaultSceneName() {
  const auto list = builtinSceneList();
  for (const auto& entry : list)
    if (entry.name == "hand") return entry.name;
  return list.empty() ? std::string("hand") : list.front().name;
}

}  // namespace cablelab::ui
