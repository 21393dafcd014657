#include "ui/tension_scale.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "engine/dynamics/world.h"
#include "ui/colormap.h"

namespace cablelab::ui {

double loadTensionScale(const SceneDef& scene) {
  if (scene.cables.empty()) return 1;
  double load = 0, startTension = 0, shortest = 1e300;
  try {
    const World world(scene, "scene");
    for (int i = 0; i < world.cableCount(); ++i) {
      const Cable& c = world.cable(i);
      // An elastic cable's pull at the start, k (length - rest + preload); a rigid one has none
      // until the first step.
      const double pull =
          c.elastic() ? c.stiffness() * (c.length() - c.restLength() + c.preload()) : c.tension();
      if (std::isfinite(pull)) startTension = std::max(startTension, pull);
      if (!c.elastic() && c.restLength() > 0) shortest = std::min(shortest, c.restLength());
    }
  } catch (const std::exception&) {
    // A scene the engine refuses opens with its error shown; the weights still give a scale.
  }
  // A body on an axle or a slide fixed to the ground: its weight goes into the joint.
  auto grounded = [&](const std::string& name) {
    for (const JointDef& j : scene.joints) {
      const std::string& other = j.bodyA == name ? j.bodyB : j.bodyB == name ? j.bodyA : name;
      const int k = findBodyIndex(scene, other);
      if (other != name &&
          (other == "world" || (k >= 0 && scene.bodies[k].type == BodyType::Static)))
        return true;
    }
    return false;
  };
  for (const BodyDef& b : scene.bodies) {
    if (b.type != BodyType::Dynamic || grounded(b.name)) continue;
    load += b.mass * scene.gravity.norm();
    if (shortest < 1e300) load += b.mass * b.velocity.squaredNorm() / shortest;
  }
  load = std::max(load, startTension);
  return std::max(niceCeil(load), kLeastTensionScale);
}

}  // namespace cablelab::ui
