#include "ui/membrane_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>

namespace cablelab::ui {
namespace {

constexpr Colour kMeasured{0.86f, 0.08f, 0.08f, 1};
constexpr Colour kModel{0.0f, 0.0f, 0.0f, 1};
constexpr Colour kMirror{0.0f, 0.75f, 0.85f, 1};
constexpr Colour kPulley{0.25f, 0.25f, 0.25f, 1};

std::string parameterText(const MembraneParams& p) {
  char text[128];
  std::snprintf(text, sizeof text, "k = %.4g N/m, preload = %.4g m", p.k, p.preload);
  return text;
}

/// Unit arrows at (x, y) pointing at `degrees`.
void addDirections(Plot& plot, const std::string& label, const Colour& colour, float width,
                   const std::vector<Vec2>& at, const std::vector<double>& degrees) {
  std::vector<double> x, y, u, v;
  for (size_t i = 0; i < at.size(); ++i) {
    const double a = degrees[i] * std::numbers::pi / 180;
    x.push_back(at[i].x()), y.push_back(at[i].y());
    u.push_back(std::cos(a)), v.push_back(std::sin(a));
  }
  plot.addArrows(label, x, y, u, v);
  plot.arrows.back().colour = colour;
  plot.arrows.back().lineWidth = width;
}

/// Median distance from each site to its nearest other site (m); 0 with fewer than 2 sites.
double medianNearest(const std::vector<Vec2>& sites) {
  std::vector<double> nearest;
  const size_t n = std::min<size_t>(sites.size(), 2000);
  for (size_t i = 0; i < n; ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < n; ++j)
      if (const double d = (sites[i] - sites[j]).norm(); d > 0) best = std::min(best, d);
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (nearest.empty()) return 0;
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return nearest[nearest.size() / 2];
}

}  // namespace

Plot membraneQuiverPlot(const MembraneGeometry& g, const MembraneParams& fitted,
                        const MembranePlotData& data) {
  Plot plot("Force directions at the deformation points (" + parameterText(fitted) + ")", "x (m)",
            "y (m)");
  plot.equalAspect = true;
  plot.addLine("band at rest", {g.a.x(), g.b.x()}, {g.a.y(), g.b.y()});
  plot.series.back().colour = Colour{0.6f, 0.6f, 0.6f, 1};
  plot.series.back().lineWidth = 1.5f;
  plot.addScatter("pulleys A, B", {g.a.x(), g.b.x()}, {g.a.y(), g.b.y()});
  plot.series.back().colour = kPulley;
  plot.series.back().markerRadius = 6;
  const double offset = 0.025 * (g.b - g.a).norm();
  plot.labels.push_back({g.a.x() + offset, g.a.y() + offset, "A"});
  plot.labels.push_back({g.b.x() + offset, g.b.y() + offset, "B"});

  std::vector<Vec2> sites, mirrorSites;
  std::vector<double> measured, model, mirror;
  for (const MembraneQuiverRow& r : data.quiver) {
    sites.push_back(r.p), mirrorSites.push_back(r.mirrorP);
    measured.push_back(r.measuredAngleDeg), model.push_back(r.modelAngleDeg);
    mirror.push_back(r.mirrorAngleDeg);
  }
  // Unit arrows as long as the sites' (vertical) spacing: tip to tail, readable at 800 px.
  plot.arrowScale = 0.95 * medianNearest(sites);
  // Back to front: mirrored, measured, then the model on top (thinnest, so both show).
  addDirections(plot, "measured, mirrored", kMirror, 2.5f, mirrorSites, mirror);
  addDirections(plot, "measured", kMeasured, 2.5f, sites, measured);
  addDirections(plot, "model", kModel, 1.2f, sites, model);
  std::vector<double> px, py;
  for (const Vec2& p : sites) px.push_back(p.x()), py.push_back(p.y());
  plot.addScatter("deformation points", px, py);
  plot.series.back().colour = Colour{0.3f, 0.3f, 0.3f, 1};
  plot.series.back().markerRadius = 1.5f;
  return plot;
}

Plot membraneScatterPlot(const MembraneParams& fitted, const MembranePlotData& data) {
  Plot plot("Vertical force, measured vs model (" + parameterText(fitted) + ")", "measured fy (N)",
            "model fy (N)");
  plot.identityLine = true;
  plot.identityLabel = "y = x (perfect fit)";
  std::vector<double> measured, model;
  for (const MembraneScatterRow& r : data.scatter)
    measured.push_back(r.measuredFy), model.push_back(r.modelFy);
  plot.addScatter("measurements (" + std::to_string(measured.size()) + ")", measured, model);
  plot.series.back().colour = Colour{0.12f, 0.47f, 0.71f, 1};
  return plot;
}

void writeMembraneFigures(const MembraneGeometry& g, const MembraneParams& fitted,
                          const MembranePlotData& data, const std::string& dir, int width,
                          int height) {
  const std::filesystem::path d(dir);
  writePlotPng(membraneQuiverPlot(g, fitted, data), (d / "quiver.png").string(), width, height);
  writePlotPng(membraneScatterPlot(fitted, data), (d / "scatter.png").string(), width, height);
}

}  // namespace cablelab::ui
