#include "ui/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>

#include "tests/ui/test_support.h"

namespace cablelab::ui {
namespace {

/// Pixels that are neither white nor grey (data colours).
long colouredPixels(const Image& image) {
  long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto* p = image.pixel(x, y);
      const int lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
      if (hi - lo > 60) ++n;
    }
  return n;
}

TEST(Plot, LinePlotHasDataAxesAndText) {
  Plot plot("sine", "t (s)", "y (m)");
  std::vector<double> t, y, z;
  for (int i = 0; i <= 100; ++i) {
    t.push_back(i * 0.01);
    y.push_back(std::sin(6 * t.back()));
    z.push_back(i == 50 ? NAN : std::cos(6 * t.back()));  // a gap, not a crash
  }
  plot.addLine("sin", t, y).addLine("cos", t, z);
  const Image image = renderPlot(plot, 640, 480);
  EXPECT_GT(colouredPixels(image), 500);
  writePng(image, test::outputDir("plot") / "line.png");
}

TEST(Plot, ScatterWithIdentityLineAndQuiver) {
  Plot scatter("fy", "measured (N)", "model (N)");
  scatter.identityLine = true;
  scatter.addScatter("samples", {0, 1, 2, 3}, {0.1, 0.9, 2.2, 2.8});
  EXPECT_GT(colouredPixels(renderPlot(scatter)), 50);
  writePlotPng(scatter, test::outputDir("plot") / "scatter.png");

  Plot quiver("forces", "x (m)", "y (m)");
  quiver.equalAspect = true;
  quiver.addArrows("measured", {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 0, -1, 0}, {0, 1, 0, -1});
  quiver.addArrows("model", {0, 1, 0, 1}, {0, 0, 1, 1}, {0.9, 0.1, -1, 0}, {0.1, 1, 0, -0.9});
  EXPECT_GT(colouredPixels(renderPlot(quiver, 600, 600)), 100);
  writePlotPng(quiver, test::outputDir("plot") / "quiver.png", 600, 600);
}

TEST(Plot, RejectsMismatchedSeriesAndIsDeterministic) {
  Plot bad;
  bad.addLine("x", {0, 1}, {0});
  EXPECT_THROW(renderPlot(bad), std::runtime_error);
  Plot empty("empty", "", "");
  EXPECT_EQ(renderPlot(empty).rgba, renderPlot(empty).rgba);
}

}  // namespace
}  // namespace cablelab::ui
