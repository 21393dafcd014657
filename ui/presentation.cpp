#include "ui/presentation.h"

#include <algorithm>
#include <cmath>

#include "ui/scene_bounds.h"

namespace cablelab::ui {
namespace {

constexpr double kMargin = 0.06;     // of the content's size, on every side
constexpr float kBarRowLines = 4.0;  // the colour bar's row, in text lines (view_furniture.h)

constexpr double kCloseUpBelow = 0.15;   // of the area's width: a thinner whole-run fit
constexpr double kCloseUpWidest = 3;     // of kCloseUpSpan: the farthest a close-up zooms out
constexpr double kCloseUpRoom = 0.12;    // of the close-up's height, kept above and below
constexpr double kFollowSeconds = 0.25;  // how fast the close-up catches up with its focus

/// The camera centre that puts world point `p` at the centre of `area` above `bottomReserve`.
Vec2 centreAt(const Vec2& p, const Camera& camera, const PanelRect& area, float bottomReserve) {
  const double dx = area.x + 0.5 * area.width - 0.5 * camera.width;
  const double dy = area.y + 0.5 * (area.height - bottomReserve) - 0.5 * camera.height;
  return p - Vec2(dx * camera.metresPerPixel, -dy * camera.metresPerPixel);
}

bool sameArea(const PanelRect& a, const PanelRect& b) {
  return std::abs(a.x - b.x) < 0.5f && std::abs(a.y - b.y) < 0.5f &&
         std::abs(a.width - b.width) < 0.5f && std::abs(a.height - b.height) < 0.5f;
}

}  // namespace

void togglePresentation(Sandbox& sandbox) {
  sandbox.presentation = !sandbox.presentation;
  sandbox.fitPending = true;  // the panels change this frame: fit once they are laid out
}

void keepViewFitted(Sandbox& sandbox) {
  const bool moved =
      !sameArea(sandbox.freeArea(), sandbox.fittedArea) || sandbox.fittedScale != sandbox.uiScale;
  if (sandbox.fitPending || (sandbox.viewFitted && moved)) sandbox.fitView();
}

float barRowHeight(const Sandbox& sandbox) {
  const World* world = sandbox.world();
  if (!sandbox.draw.legend || !world || world->cableCount() == 0) return 0;
  return kBarRowLines * std::round(13.0f * sandbox.uiScale);  // the font is 13 px x UI scale
}

bool wantsCloseUp(const Sandbox& sandbox) {
  const World* world = sandbox.world();
  const PanelRect area = sandbox.freeArea();
  if (!world || !sandbox.demo.loops || sandbox.demo.stage.empty() || area.width < 40) return false;
  const Camera whole =
      fitToContent(*world, sandbox.camera, area, barRowHeight(sandbox), sandbox.demo.stage);
  const WorldBounds& stage = sandbox.demo.stage;
  return (stage.hi.x() - stage.lo.x()) / whole.metresPerPixel < kCloseUpBelow * area.width;
}

CloseUpFrame closeUpFrame(const World& world) {
  const WorldBounds scene = sceneBounds(world);
  if (scene.empty()) return {};
  const double least = kCloseUpSpan * std::max(scene.hi.x() - scene.lo.x(), 1e-3);
  const double top = scene.hi.y() + kCloseUpRoom * least;
  // The nearest body hanging below the top of the mechanism (the wheel, drum or pulleys the
  // rope hangs from) stays in view with it.
  double nearest = -1e300;
  for (int i = 0; i < world.bodyCount(); ++i) {
    const double y = world.body(i).position.y();
    if (world.scene().bodies[i].type == BodyType::Dynamic && y < top - 0.5 * least)
      nearest = std::max(nearest, y);
  }
  CloseUpFrame f;
  const double reach = nearest > -1e299 ? (top - nearest) * (1 + kCloseUpRoom) : 0.0;
  // A body farther down than the widest close-up leaves the view for a while: the mechanism
  // stays readable (it comes back, or the run starts again, ui/demo_loop.h).
  f.span = reach <= kCloseUpWidest * least ? std::max(least, reach) : least;
  f.focus = Vec2(0.5 * (scene.lo.x() + scene.hi.x()), top - 0.5 * f.span);
  f.width = scene.hi.x() - scene.lo.x();
  return f;
}

Camera closeUpCamera(const World& world, const Camera& camera, const PanelRect& area,
                     float bottomReserve) {
  Camera fitted = camera;
  const CloseUpFrame f = closeUpFrame(world);
  const float height = area.height - bottomReserve;
  if (f.span <= 0 || area.width < 40 || height < 40) return fitted;
  fitted.metresPerPixel = std::max(f.span / height, f.width * (1 + 2 * kMargin) / area.width);
  fitted.center = centreAt(f.focus, fitted, area, bottomReserve);
  return fitted;
}

void followCloseUp(Sandbox& sandbox, double seconds) {
  const World* world = sandbox.world();
  if (!world || !sandbox.closeUp || !sandbox.viewFitted || !sandbox.presentation) return;
  const Camera goal =
      closeUpCamera(*world, sandbox.camera, sandbox.freeArea(), barRowHeight(sandbox));
  // Out quickly (nothing leaves the view), in and along smoothly.
  const double share = 1 - std::exp(-std::max(seconds, 0.0) / kFollowSeconds);
  Camera& c = sandbox.camera;
  c.metresPerPixel = goal.metresPerPixel > c.metresPerPixel
                         ? goal.metresPerPixel
                         : c.metresPerPixel + share * (goal.metresPerPixel - c.metresPerPixel);
  c.center += share * (goal.center - c.center);
  if (goal.metresPerPixel >= c.metresPerPixel) c.center = goal.center;
}

Camera fitToContent(const World& world, const Camera& camera, const PanelRect& area,
                    float bottomReserve, const WorldBounds& stage) {
  Camera fitted = camera;
  WorldBounds b = sceneBounds(world);
  if (!stage.empty()) {
    b.include(stage.lo);
    b.include(stage.hi);
  }
  const float height = area.height - bottomReserve;
  if (b.empty() || area.width < 40 || height < 40) return fitted;
  const Vec2 size = (b.hi - b.lo).cwiseMax(Vec2(1e-3, 1e-3));
  const Vec2 span = size * (1 + 2 * kMargin);
  fitted.metresPerPixel = std::max(span.x() / area.width, span.y() / height);
  // The content's centre at the centre of the area above the reserve.
  const Vec2 centre = 0.5 * (b.lo + b.hi);
  const double dx = area.x + 0.5 * area.width - 0.5 * camera.width;
  const double dy = area.y + 0.5 * height - 0.5 * camera.height;
  fitted.center = centre - Vec2(dx * fitted.metresPerPixel, -dy * fitted.metresPerPixel);
  return fitted;
}

}  // namespace cablelab::ui
