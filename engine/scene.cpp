#include "engine/scene.h"

#include "engine/error.h"

namespace cablelab {

int findBodyIndex(const SceneDef& scene, const std::string& name) {
  if (name == "world") return -1;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    if (scene.bodies[i].name == name) return static_cast<int>(i);
  return -2;
}

void validateScene(const SceneDef& scene, const std::string& source) {}

}  // namespace cablelab
