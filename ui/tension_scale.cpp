#include "ui/tension_scale.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "engine/dynamics/world.h"
#include "ui/colormap.h"

namespace cablelab::ui {

double expectedTensionScale(const SceneDef& scene) {
  if (scene.cables.empty()) return 1;
  double largest = 0;
  try {
    World world(scene, "scene");
    const double dt = scene.dt > 0 ? scene.dt : 1.0 / 60.0;
    const long steps = std::lround(kTensionProbeSeconds / dt);
    for (long s = 0; s <= steps; ++s) {
      for (int i = 0; i < world.cableCount(); ++i) {
        const double t = world.cable(i).tension();
        if (std::isfinite(t)) largest = std::max(largest, t);
      }
      if (s < steps) world.step(dt, std::max(scene.substeps, 1));
    }
  } catch (const std::exception&) {
    // A scene that fails its probe still opens: the colours then start from 1 N.
  }
  return niceCeil(largest);
}

}  // namespace cablelab::ui
