#include "ui/label_layout.h"

#include <algorithm>
#include <cmath>

namespace cablelab::ui {
namespace {

constexpr int kColumns = 5, kRows = 3;  // sample points per label
// Distances (in units of `gap`) of the candidate rings; from the third ring on a leader line.
constexpr double kRings[] = {1, 3, 6, 10, 16, 25, 40, 60};
constexpr int kLeaderRing = 2;

bool insideConvex(const LabelObstacle& poly, const Vec2& p) {
  if (poly.size() < 3) return false;
  int sign = 0;
  for (size_t k = 0; k < poly.size(); ++k) {
    const double c = cross(poly[(k + 1) % poly.size()] - poly[k], p - poly[k]);
    const int s = c > 0 ? 1 : c < 0 ? -1 : 0;
    if (s == 0) continue;
    if (sign == 0) sign = s;
    if (s != sign) return false;
  }
  return true;
}

LabelBox bounds(const LabelObstacle& poly) {
  LabelBox b{1e300, 1e300, -1e300, -1e300};
  for (const Vec2& p : poly) {
    b.x0 = std::min(b.x0, p.x()), b.y0 = std::min(b.y0, p.y());
    b.x1 = std::max(b.x1, p.x()), b.y1 = std::max(b.y1, p.y());
  }
  return b;
}

}  // namespace

double LabelBox::overlapArea(const LabelBox& o) const {
  return std::max(0.0, std::min(x1, o.x1) - std::max(x0, o.x0)) *
         std::max(0.0, std::min(y1, o.y1) - std::max(y0, o.y0));
}

bool crossesConvex(const LabelBox& box, const LabelObstacle& poly) {
  if (poly.size() < 3) return false;
  const LabelBox b = bounds(poly);
  if (b.x1 < box.x0 || b.x0 > box.x1 || b.y1 < box.y0 || b.y0 > box.y1) return false;
  const Vec2 corners[] = {{box.x0, box.y0}, {box.x1, box.y0}, {box.x1, box.y1}, {box.x0, box.y1}};
  for (size_t k = 0; k < poly.size(); ++k) {  // each edge's normal as a separating axis
    const Vec2 edge = poly[(k + 1) % poly.size()] - poly[k];
    const Vec2 axis(-edge.y(), edge.x());
    double lo = 1e300, hi = -1e300, plo = 1e300, phi = -1e300;
    for (const Vec2& c : corners) lo = std::min(lo, axis.dot(c)), hi = std::max(hi, axis.dot(c));
    for (const Vec2& p : poly) plo = std::min(plo, axis.dot(p)), phi = std::max(phi, axis.dot(p));
    if (hi < plo || phi < lo) return false;
  }
  return true;
}

double obstacleCover(const LabelBox& box, const std::vector<LabelObstacle>& obstacles) {
  int hits = 0, samples = kColumns * kRows;
  for (const LabelObstacle& poly : obstacles) {
    const LabelBox b = bounds(poly);
    if (b.x1 < box.x0 || b.x0 > box.x1 || b.y1 < box.y0 || b.y0 > box.y1) continue;
    for (int i = 0; i < kColumns; ++i)
      for (int j = 0; j < kRows; ++j) {
        const Vec2 p(box.x0 + (box.x1 - box.x0) * i / (kColumns - 1),
                     box.y0 + (box.y1 - box.y0) * j / (kRows - 1));
        hits += insideConvex(poly, p);
      }
    const int before = hits;
    for (const Vec2& v : poly)
      hits += v.x() > box.x0 && v.x() < box.x1 && v.y() > box.y0 && v.y() < box.y1;
    if (hits == before && crossesConvex(box, poly)) ++hits;
  }
  return std::min(1.0, static_cast<double>(hits) / samples);
}

std::vector<LabelPlacement> placeLabels(const std::vector<LabelRequest>& labels,
                                        const std::vector<LabelObstacle>& obstacles,
                                        const LabelBox& view, double gap,
                                        const std::vector<LabelBox>& reserved) {
  std::vector<LabelPlacement> placed;
  placed.reserve(labels.size());
  std::vector<Vec2> offsets;
  for (const LabelRequest& l : labels) {
    const double w = l.width, h = l.height, area = std::max(w * h, 1.0);
    offsets.clear();
    offsets.push_back(l.offset);
    for (double ring : kRings) {
      const double d = ring * gap;
      for (const Vec2& o :
           {Vec2(d, d), Vec2(d, -h - d), Vec2(-w - d, d), Vec2(-w - d, -h - d), Vec2(-0.5 * w, d),
            Vec2(-0.5 * w, -h - d), Vec2(d, -0.5 * h), Vec2(-w - d, -0.5 * h)})
        offsets.push_back(o);
    }
    double best = 1e300;
    LabelPlacement choice;
    for (size_t k = 0; k < offsets.size(); ++k) {
      const Vec2 p = l.anchor + offsets[k];
      const LabelBox r{p.x(), p.y(), p.x() + w, p.y() + h};
      // Hard limits first (each costs more than any cover of bodies), then the bodies' cover.
      double clash = 0;
      for (const LabelPlacement& q : placed)
        if (q.shown) clash += r.overlapArea(q.box);
      for (const LabelBox& q : reserved) clash += r.overlapArea(q);
      if (r.x0 < view.x0 || r.y0 < view.y0 || r.x1 > view.x1 || r.y1 > view.y1) clash += area;
      double bad = clash > 0 ? 2 * area + clash : 0;
      if (bad < best) bad += obstacleCover(r, obstacles) * area;  // the costly part last
      // Nearer places win ties: a small penalty per ring.
      const int ring = k == 0 ? 0 : static_cast<int>((k - 1) / 8);
      const double score = bad + 1e-3 * ring;
      if (score < best) {
        best = score;
        choice = {r, ring >= kLeaderRing, clash <= 0};
      }
      if (bad <= 0) break;
    }
    placed.push_back(choice);
  }
  return placed;
}

}  // namespace cablelab::ui
