// A point pulley the rope does not reach when the World is built: said once, in plain words
// (docs/scene-format.md, "A pulley the rope does not reach"). The join rule (cable.h) leaves a
// one-sided point out until it crosses the rope from its non-wrap side, so a side given the wrong
// way round silently took the pulley out of the path.
#include <algorithm>
#include <cstdio>
#include <string>

#include "engine/cable/cable.h"
#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

const char* sideName(WrapSide side) {
  return side == WrapSide::Right ? "right" : "left";
}

// The distance from p to the segment a-b (m).
double segmentDistance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

// Only pulleys fixed where they are (the world, a static body, a kinematic one at rest): one on a
// body that moves may be brought to the rope, as the membrane's finger is pressed into its band.
void Cable::reportPulleysLeftOut(std::span<const BodyState> bodies,
                                 std::vector<std::string>* warnings) const {
  if (!warnings) return;
  size_t host = 0;  // path index of the last point before pulley j
  for (const int j : order_) {
    const PulleyState& p = pulleys_[j];
    if (j >= namedPulleys_) continue;
    if (p.engaged) {
      while (host + 1 < path_.size() - 1 && path_[host + 1].pulley == j) ++host;
      continue;
    }
    if (p.polygon || p.circle || p.autoSide || p.side == WrapSide::Threaded) continue;
    if (p.body >= 0 && (moves(bodies[p.body]) || driven(bodies[p.body]))) continue;
    const Vec2 a = path_[host].leaving(), b = path_[host + 1].arriving(), x = p.world[0];
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? (x - a).dot(ab) / len2 : -1.0;
    char away[32];
    std::snprintf(away, sizeof away, "%.3g m", segmentDistance(a, b, x));
    const std::string named = "cable '" + def_->name + "': pulley " + std::to_string(j) +
                              " (a point on '" + def_->pulleys[j].body + "') is left out: ";
    const char* listed = sideName(p.side);
    const char* other = sideName(p.side == WrapSide::Left ? WrapSide::Right : WrapSide::Left);
    if (t > 0 && t < 1 && wrapSideDistance(a, b, x, p.side) < 0)
      warnings->push_back(named + "from the point before it to the one after, the rope passes to " +
                          "its " + other + ", not its " + listed + " as \"side\": \"" + listed +
                          "\" says, so it runs straight past it (" + away +
                          " away) and does not use it until the rope reaches it (\"side\": \"" +
                          other + "\" takes it from the start)");
    else
      warnings->push_back(named + "the rope from the point before it to the one after does not " +
                          "reach it (" + away +
                          " away), so it runs straight and does not use it until it does");
  }
}

}  // namespace cablelab
