// Scene bounds: the world rectangle (m) that holds what a scene shows moving, for fitting the
// view (ui/sandbox.h, ui/presentation.h) and for checking that the scene sits inside the window.
//
// Needs: the engine's World. The pulleys the cables run over are in, wherever they sit. Fixed
// (static) bodies are in as far as they reach near the moving parts: a student's ground or wall
// is part of the mechanism, but a very wide ground would shrink it to a sliver.
#pragma once

#include "engine/dynamics/world.h"
#include "ui/camera.h"
#include "ui/label_layout.h"

namespace cablelab::ui {

struct WorldBounds {
  Vec2 lo = Vec2(1e300, 1e300), hi = Vec2(-1e300, -1e300);  ///< m; lo > hi: empty
  bool empty() const { return lo.x() > hi.x() || lo.y() > hi.y(); }
  void include(const Vec2& p, double margin = 0) {
    lo = lo.cwiseMin(p - Vec2(margin, margin));
    hi = hi.cwiseMax(p + Vec2(margin, margin));
  }
};

/// How far beyond the moving parts a fixed body counts, in units of their larger side.
inline constexpr double kFixedReach = 1;

/// The shapes of the dynamic and kinematic bodies, the cables' paths and their pulleys, each
/// grown by `margin` (m), as they are now; with the fixed bodies' shapes cut to kFixedReach
/// times the moving parts' larger side beyond them (whole when nothing moves).
WorldBounds sceneBounds(const World& world, double margin = 0);

/// The shapes of body `body` (an index of `world`), grown by `margin` (m), as they are now.
WorldBounds bodyBounds(const World& world, int body, double margin = 0);

/// `bounds` on screen through `camera` (px, y down); empty when `bounds` is.
LabelBox screenBox(const WorldBounds& bounds, const Camera& camera);

}  // namespace cablelab::ui
