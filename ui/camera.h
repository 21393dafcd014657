// Camera: maps world metres to framebuffer pixels for the renderer and the sandbox's mouse.
//
// Needs: engine/core/math.h only. A camera is a centre (m), a scale (metres per pixel) and a
// viewport size (px). Screen pixels have their origin at the top-left corner, y down; world
// coordinates have y up. The camera never changes by itself: the app owns it.
#pragma once

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab::ui {

struct Camera {
  Vec2 center = Vec2::Zero();    ///< world point at the centre of the viewport (m)
  double metresPerPixel = 0.01;  ///< m/px, > 0
  int width = 800;               ///< viewport width (px)
  int height = 600;              ///< viewport height (px)

  /// A camera showing `view` (its centre, and its height filling the viewport's height).
  static Camera fit(const ViewDef& view, int width, int height);

  /// World (m) -> screen (px, origin top-left, y down).
  Vec2 toScreen(const Vec2& world) const;
  /// Screen (px, origin top-left, y down) -> world (m).
  Vec2 toWorld(const Vec2& screen) const;

  /// Scales by `factor` (> 1 zooms in) keeping the world point under `screenPoint` fixed.
  void zoomAt(const Vec2& screenPoint, double factor);
  /// Moves the view by a screen-space displacement (px), as when the mouse drags the scene.
  void panPixels(const Vec2& deltaPixels);

  /// World rectangle in view: left, right, bottom, top (m).
  double left() const { return center.x() - 0.5 * width * metresPerPixel; }
  double right() const { return center.x() + 0.5 * width * metresPerPixel; }
  double bottom() const { return center.y() - 0.5 * height * metresPerPixel; }
  double top() const { return center.y() + 0.5 * height * metresPerPixel; }
};

}  // namespace cablelab::ui
