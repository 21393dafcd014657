#include "ui/presentation.h"

#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "ui/scene_bounds.h"
#include "ui/view_furniture.h"

namespace cablelab::ui {
namespace {

constexpr double kMargin = 0.06;     // of the content's size, on every side
constexpr float kBarRowLines = 4.0;  // the colour bar's row, in text lines (view_furniture.h)

constexpr double kCloseUpBelow = 0.15;   // of the area's width: a thinner whole-run fit
constexpr double kCloseUpWidest = 3;     // of kCloseUpSpan: the farthest a close-up zooms out
constexpr double kCloseUpRoom = 0.12;    // of the close-up's height, kept above and below
constexpr double kFollowSeconds = 0.25;  // how fast the close-up catches up with its focus
constexpr double kZoomOutRate = 6;       // 1/s: the close-up zooms out at most e^6 times a second
constexpr double kKeyRoomCost = 0.1;     // of the scene's size, the most the key's room may take
constexpr double kRefitBelow = 0.55;  // of the view both ways: a scene that shrank so is refitted

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

/// In presentation mode the fit follows the scene (not while the user drags a body): fitted
/// again when a moving part leaves the view or the scene (with a demo's whole run) shrank to
/// less than kRefitBelow of it both ways (the hand opening its fingers wide for a new grasp and
/// closing them), or when the marker key grew over it (a new marker).
bool outgrown(const Sandbox& sandbox) {
  if (!sandbox.presentation || !sandbox.viewFitted || sandbox.closeUp || sandbox.drag.body >= 0)
    return false;
  const FurnitureLayout& f = sandbox.drawn.furniture;
  if (f.keyOnScene && f.keyRows.size() != sandbox.fittedKeyRows) return true;
  LabelBox s = sandbox.drawn.scene;
  if (s.empty()) return false;
  if (!sandbox.demo.stage.empty()) {
    const LabelBox stage = screenBox(sandbox.demo.stage, sandbox.camera);
    s = {std::min(s.x0, stage.x0), std::min(s.y0, stage.y0), std::max(s.x1, stage.x1),
         std::max(s.y1, stage.y1)};
  }
  const PanelRect a = sandbox.freeArea();
  const float height = a.height - barRowHeight(sandbox);
  const bool out =
      s.x0 < a.x - 1 || s.y0 < a.y - 1 || s.x1 > a.x + a.width + 1 || s.y1 > a.y + height + 1;
  // While building the view is the scene's own, which a small scene does not fill.
  const bool small = !sandbox.fittedCanvas && s.x1 - s.x0 < kRefitBelow * a.width &&
                     s.y1 - s.y0 < kRefitBelow * height;
  return out || small;
}

}  // namespace

bool showsCanvas(const Sandbox& sandbox) {
  const World* world = sandbox.world();
  if (sandbox.building() || !world) return true;
  if (world->cableCount() > 0) return false;
  for (int i = 0; i < world->bodyCount(); ++i)
    if (world->scene().bodies[i].type != BodyType::Static) return false;
  return true;  // a new scene: its ground alone
}

void togglePresentation(Sandbox& sandbox) {
  sandbox.presentation = !sandbox.presentation;
  sandbox.fitPending = true;  // the panels change this frame: fit once they are laid out
}

void keepViewFitted(Sandbox& sandbox) {
  const bool moved = !sameArea(sandbox.freeArea(), sandbox.fittedArea) ||
                     sandbox.fittedScale != sandbox.uiScale ||
                     (sandbox.presentation && sandbox.fittedCanvas != showsCanvas(sandbox));
  if (sandbox.fitPending || (sandbox.viewFitted && moved) || outgrown(sandbox)) sandbox.fitView();
}

float barRowHeight(const Sandbox& sandbox) {
  const World* world = sandbox.world();
  if (!world || (!sandbox.draw.grid && !(sandbox.draw.legend && world->cableCount() > 0))) return 0;
  // The colour bar's row, also without a cable (the scale bar and the PAUSED sign are in it, and
  // a student's first cable does not move the view).
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

CloseUpFrame closeUpFrame(const World& world, int followed) {
  const WorldBounds scene = sceneBounds(world);
  if (scene.empty()) return {};
  const double least = kCloseUpSpan * std::max(scene.hi.x() - scene.lo.x(), 1e-3);
  const double top = scene.hi.y() + kCloseUpRoom * least;
  // The bodies hanging below the top of the mechanism (the wheel, drum or pulleys the rope
  // hangs from) stay in view with it: all those within the widest close-up (the capstan's hold
  // and its load), else the nearest.
  const double widest = kCloseUpWidest * least;
  const auto reachOf = [&](double y) { return (top - y) * (1 + kCloseUpRoom); };
  int nearest = -1, farthestInReach = -1;
  for (int i = 0; i < world.bodyCount(); ++i) {
    const double y = world.body(i).position.y();
    if (world.scene().bodies[i].type != BodyType::Dynamic || y >= top - 0.5 * least) continue;
    if (nearest < 0 || y > world.body(nearest).position.y()) nearest = i;
    if (reachOf(y) <= widest &&
        (farthestInReach < 0 || y < world.body(farthestInReach).position.y()))
      farthestInReach = i;
  }
  CloseUpFrame f;
  f.nearest = nearest;
  f.body = farthestInReach >= 0 ? farthestInReach : nearest;
  f.reach = f.body >= 0 ? reachOf(world.body(f.body).position.y()) : 0.0;
  f.least = least;
  f.widest = widest;
  // The nearest body farther down than the widest close-up: the view the run zoomed out to
  // after it stays (no jump back in mid-run), else the mechanism alone (the winch's load
  // starts there).
  const bool hold = f.body >= 0 && f.body == followed;
  f.span = f.reach <= f.widest ? std::max(least, f.reach) : hold ? f.widest : least;
  f.focus = Vec2(0.5 * (scene.lo.x() + scene.hi.x()), top - 0.5 * f.span);
  f.width = scene.hi.x() - scene.lo.x();
  return f;
}

Camera closeUpCamera(const World& world, const Camera& camera, const PanelRect& area,
                     float bottomReserve, int followed) {
  Camera fitted = camera;
  const CloseUpFrame f = closeUpFrame(world, followed);
  const float height = area.height - bottomReserve;
  if (f.span <= 0 || area.width < 40 || height < 40) return fitted;
  fitted.metresPerPixel = std::max(f.span / height, f.width * (1 + 2 * kMargin) / area.width);
  fitted.center = centreAt(f.focus, fitted, area, bottomReserve);
  return fitted;
}

void followCloseUp(Sandbox& sandbox, double seconds) {
  const World* world = sandbox.world();
  if (!world || !sandbox.closeUp || !sandbox.viewFitted || !sandbox.presentation) return;
  // The view zoomed out after a hanging body: the run remembers it (ui/demo_loop.h DemoRun).
  const CloseUpFrame f = closeUpFrame(*world, sandbox.demo.closeUpBody);
  // (Only the nearest: a lower one in view with it, the capstan's load, is not followed.)
  if (f.reach > f.least && f.reach <= f.widest && f.body == f.nearest)
    sandbox.demo.closeUpBody = f.body;
  const Camera goal = presentationFit(sandbox, sandbox.freeArea());
  // Out as fast as a falling body needs, at most kZoomOutRate (a new nearest body far down
  // would be a jump), in and along smoothly.
  const double t = std::max(seconds, 0.0);
  const double share = 1 - std::exp(-t / kFollowSeconds);
  Camera& c = sandbox.camera;
  const double out = c.metresPerPixel * std::exp(kZoomOutRate * t);
  c.metresPerPixel = goal.metresPerPixel > c.metresPerPixel
                         ? std::min(goal.metresPerPixel, out)
                         : c.metresPerPixel + share * (goal.metresPerPixel - c.metresPerPixel);
  c.center += share * (goal.center - c.center);
  if (goal.metresPerPixel >= c.metresPerPixel) {
    // Zooming out: the top of the view (the mechanism) where the goal has it.
    const PanelRect a = sandbox.freeArea();
    const Vec2 top = goal.toWorld(Vec2(a.x + 0.5 * a.width, a.y));
    c.center = top + (goal.center - top) * (c.metresPerPixel / goal.metresPerPixel);
  }
}

Camera presentationFit(const Sandbox& sandbox, const PanelRect& free) {
  const World& world = *sandbox.world();
  const float bars = barRowHeight(sandbox);
  const auto fitIn = [&](const PanelRect& area) {
    return sandbox.closeUp
               ? closeUpCamera(world, sandbox.camera, area, bars, sandbox.demo.closeUpBody)
               : fitToContent(world, sandbox.camera, area, bars, sandbox.demo.stage);
  };
  const Camera whole = fitIn(free);
  // The marker key's size needs the text font: none before the first frame (nor in the tests
  // of the sandbox without a window).
  if (!ImGui::GetCurrentContext() || !ImGui::GetFont()) return whole;
  const Overlay overlay = sandbox.overlay();
  RenderOptions options = sandbox.renderOptions();
  options.keyGivesWay = true;
  const auto keyOnScene = [&](const Camera& camera) {
    const WorldBounds b = sceneBounds(world);
    if (b.empty()) return FurnitureLayout{};
    return layoutFurniture(world, overlay, options, camera, true, screenBox(b, camera));
  };
  const FurnitureLayout l = keyOnScene(whole);
  if (l.keyRows.empty() || !l.keyOnScene) return whole;
  // Room for the key: below its strip along the top, or left of its column.
  PanelRect below = free, left = free;
  const float band = static_cast<float>(l.keyAsStrip.y1) + 6 - free.y;
  below.y += band;
  below.height -= band;
  left.width = static_cast<float>(l.keyAsColumn.x0) - 6 - free.x;
  if (below.height < 40 || left.width < 40) return whole;
  const Camera a = fitIn(below), b = fitIn(left);
  const Camera& roomy = a.metresPerPixel <= b.metresPerPixel ? a : b;
  // A window too small for both (the scene would lose more than kKeyRoomCost of its size): the
  // scene wins, the key gives way (ui/view_furniture.h).
  return roomy.metresPerPixel * (1 - kKeyRoomCost) <= whole.metresPerPixel ? roomy : whole;
}

Camera clearOfKey(const Sandbox& sandbox, const Camera& fitted, const PanelRect& area,
                  float bottomReserve) {
  const World* world = sandbox.world();
  if (!world || !ImGui::GetCurrentContext() || !ImGui::GetFont()) return fitted;
  const WorldBounds parts = sceneBounds(*world);
  if (parts.empty()) return fitted;
  const LabelBox scene = screenBox(parts, fitted);
  RenderOptions options = sandbox.renderOptions();
  options.keyGivesWay = false;
  const FurnitureLayout l =
      layoutFurniture(*world, sandbox.overlay(), options, fitted, true, scene);
  if (l.key.empty() || !l.key.overlaps(scene)) return fitted;
  constexpr double kGap = 8;  // px between the key and the scene
  Camera moved = fitted;
  const double left = scene.x1 - (l.key.x0 - kGap);  // px
  if (scene.x0 - left >= area.x + kGap) {
    moved.center.x() += left * fitted.metresPerPixel;
    return moved;
  }
  const double down = l.key.y1 + kGap - scene.y0;  // px
  if (scene.y1 + down <= area.y + area.height - bottomReserve - kGap) {
    moved.center.y() += down * fitted.metresPerPixel;
    return moved;
  }
  return fitted;
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
