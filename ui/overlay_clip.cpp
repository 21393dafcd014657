#include "ui/overlay_clip.h"

#include <algorithm>
#include <utility>

namespace cablelab::ui {
namespace {

/// The parameter range [t0, t1] of a + t (b - a), t in [0, 1], inside `box` (Liang-Barsky);
/// false when the segment misses it.
bool insideRange(const Vec2& a, const Vec2& b, const LabelBox& box, double& t0, double& t1) {
  t0 = 0;
  t1 = 1;
  const Vec2 d = b - a;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() - box.x0, box.x1 - a.x(), a.y() - box.y0, box.y1 - a.y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0) {
      if (q[k] < 0) return false;  // parallel to this edge and outside it
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
  }
  return t1 > t0;
}

}  // namespace

std::vector<ScreenSegment> partsOutside(const Vec2& a, const Vec2& b,
                                        const std::vector<LabelBox>& keepOff) {
  std::vector<std::pair<double, double>> covered;
  for (const LabelBox& box : keepOff) {
    double t0 = 0, t1 = 0;
    if (!box.empty() && insideRange(a, b, box, t0, t1)) covered.emplace_back(t0, t1);
  }
  std::sort(covered.begin(), covered.end());
  std::vector<ScreenSegment> parts;
  double from = 0;  // the start of the next visible part
  for (const auto& [t0, t1] : covered) {
    if (t0 > from) parts.push_back({a + from * (b - a), a + t0 * (b - a)});
    from = std::max(from, t1);
  }
  if (from < 1) parts.push_back({a + from * (b - a), b});
  return parts;
}

}  // namespace cablelab::ui
