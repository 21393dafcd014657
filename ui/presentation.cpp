#include "ui/presentation.h"

#include <algorithm>
#include <cmath>

#include "ui/scene_bounds.h"

namespace cablelab::ui {
namespace {

constexpr double kMargin = 0.06;     // of the content's size, on every side
constexpr float kBarRowLines = 4.0;  // the colour bar's row, in text lines (view_furniture.h)

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
