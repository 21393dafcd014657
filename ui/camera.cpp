#include "ui/camera.h"

#include <algorithm>

namespace cablelab::ui {

Camera Camera::fit(const ViewDef& view, int width, int height) {
  Camera c;
  c.center = view.center;
  c.width = std::max(width, 1);
  c.height = std::max(height, 1);
  c.metresPerPixel = (view.height > 0 ? view.height : 4.0) / c.height;
  return c;
}

Vec2 Camera::toScreen(const Vec2& world) const {
  return {(world.x() - center.x()) / metresPerPixel + 0.5 * width,
          0.5 * height - (world.y() - center.y()) / metresPerPixel};
}

Vec2 Camera::toWorld(const Vec2& screen) const {
  return {center.x() + (screen.x() - 0.5 * width) * metresPerPixel,
          center.y() + (0.5 * height - screen.y()) * metresPerPixel};
}

void Camera::zoomAt(const Vec2& screenPoint, double factor) {
  if (!(factor > 0)) return;
  const Vec2 anchor = toWorld(screenPoint);
  metresPerPixel = std::clamp(metresPerPixel / factor, 1e-6, 1e3);
  center += anchor - toWorld(screenPoint);  // keep the anchor under the cursor
}

void Camera::panPixels(const Vec2& deltaPixels) {
  center += Vec2(-deltaPixels.x(), deltaPixels.y()) * metresPerPixel;
}

}  // namespace cablelab::ui
