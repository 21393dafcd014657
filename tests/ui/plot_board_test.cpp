// The sandbox's plots against time (ui/plot_board.h) and their slide export (ui/plot_image.h):
// the vertical range follows the data in view and shrinks back after an outlier; the exported
// PNG is slide-sized with the curve where the data puts it and the title clear of it; the CSV
// holds the recorded samples exactly; the CPU drawing matches the OSMesa one.
#include "ui/plot_board.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "tests/ui/test_support.h"
#include "ui/plot_image.h"
#include "ui/plot_panel.h"
#include "ui/sandbox.h"

namespace cablelab::ui {
namespace plot_board_test {  // named: unity batches join test files

constexpr double kDt = 1.0 / 60;

/// Pixels of the first palette colour (the first curve, rgb 31, 120, 181), within `tolerance`.
bool isCurve(const std::uint8_t* p, int tolerance = 40) {
  return std::abs(p[0] - 31) <= tolerance && std::abs(p[1] - 120) <= tolerance &&
         std::abs(p[2] - 181) <= tolerance;
}

/// A sandbox showing `seconds` of y = sin(2 pi t / 4) (peaks at t = 1, 5, 9, ...) as its one
/// chart, in the pulley scene (the world only names things).
Sandbox& sineSandbox(Sandbox& sandbox, double seconds) {
  EXPECT_TRUE(sandbox.open("pulley"));
  sandbox.plots->addCurve(0, {Quantity::Kind::Y, 1, 0});
  for (int i = 0; i * kDt <= seconds + 1e-9; ++i)
    sandbox.plots->addSample(i * kDt, {{std::sin(2 * M_PI * i * kDt / 4)}});
  return sandbox;
}

TEST(PlotBoard, TheRangeShrinksBackAfterAnOutlierLeavesTheView) {
  PlotBoard board;
  board.windowSeconds = 5;
  board.addCurve(0, {Quantity::Kind::ControllerError, -1, 0});
  std::array<double, 2> during{}, after{};
  for (int i = 0; i <= 1200; ++i) {  // 20 s; one far target at t = 2 s (50 m away)
    const double t = i * kDt;
    board.addSample(t, {{std::abs(i - 120) < 3 ? 50.0 : 0.2 + 0.1 * std::sin(t)}});
    if (i == 300) during = board.valueRange(board.charts[0], t);
  }
  after = board.valueRange(board.charts[0], 20);
  EXPECT_GE(during[1], 50);
  // The data in view, 0.2 + 0.1 sin(t) over 15..20 s, spans [0.1, 0.291]; padded 5% and
  // rounded outwards to steps of 0.05.
  EXPECT_GE(after[0], 0.05 - 1e-12);
  EXPECT_LE(after[0], 0.1 + 1e-12);
  EXPECT_GE(after[1], 0.29);
  EXPECT_LE(after[1], 0.35 + 1e-12);
  // The 30 s kept: older samples go.
  EXPECT_LE(board.times().back() - board.times().front(), PlotBoard::kKeptSeconds);
}

// The lecture walkthrough's pulley: its rope's steady 13.08 N, 2e-5 N higher in the first
// sample, was drawn as a cliff between eight ticks that all read "13.08". Now a level line in a
// band of 5% about it; a body 10 m out wobbling 5 cm still fills its chart.
TEST(PlotBoard, ASteadyTensionIsALevelLineAndAWobbleStillShows) {
  PlotBoard steady, wobble;
  steady.addCurve(0, {Quantity::Kind::Tension, 0, 0});
  wobble.addCurve(0, {Quantity::Kind::X, 0, 0});
  for (int i = 0; i <= 120; ++i) {
    steady.addSample(i * kDt, {{i == 0 ? 13.08002 : 13.08}});
    wobble.addSample(i * kDt, {{10 + 0.05 * std::sin(i * kDt * 3)}});
  }
  const auto flat = steady.valueRange(steady.charts[0], 2);
  EXPECT_LE(flat[0], 13.08 - 0.6);
  EXPECT_GE(flat[1], 13.08 + 0.6);
  EXPECT_LE(flat[1] - flat[0], 2);
  const auto moving = wobble.valueRange(wobble.charts[0], 2);
  EXPECT_LE(moving[1] - moving[0], 0.2);
  EXPECT_GE(moving[1] - moving[0], 0.1);
}

// Issue 38: a tension added to a chart of positions drew both on one axis, "value (N, m)". Each
// unit has its own chart now: a quantity in another unit goes to the last chart in its unit.
TEST(PlotBoard, EachChartsAxisHasOneUnit) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("pulley"));
  PlotBoard& board = *sandbox.plots;
  EXPECT_EQ(board.addCurve(0, {Quantity::Kind::Tension, 0, 0}), 0u);
  EXPECT_EQ(board.addCurve(0, {Quantity::Kind::Y, 1, 0}), 1u);  // metres: a chart of its own
  EXPECT_EQ(board.addCurve(1, {Quantity::Kind::Y, 2, 0}), 1u);  // metres with metres
  EXPECT_EQ(board.addCurve(1, {Quantity::Kind::Length, 0, 0}), 1u);
  EXPECT_EQ(board.addCurve(1, {Quantity::Kind::SpanTension, 0, 1}), 0u);  // back to the newtons
  ASSERT_EQ(board.charts.size(), 2u);
  EXPECT_EQ(board.charts[0].curves.size(), 2u);
  EXPECT_EQ(board.charts[1].curves.size(), 3u);
  for (int i = 0; i < 3; ++i) board.addSample(i * kDt, {{1, 2}, {3, 4, 5}});
  const World& world = *sandbox.world();
  const std::string newtons = board.plot(board.charts[0], world, 2 * kDt).yLabel,
                    metres = board.plot(board.charts[1], world, 2 * kDt).yLabel;
  EXPECT_EQ(newtons, "tension (N)");
  EXPECT_NE(metres.find("(m)"), std::string::npos) << metres;
  EXPECT_EQ(metres.find(','), std::string::npos) << metres;
}

TEST(PlotBoard, ARewoundRunPlayedOnReplacesTheLaterSamples) {
  PlotBoard board;
  board.addCurve(0, {Quantity::Kind::Energy, -1, 0});
  for (int i = 1; i <= 100; ++i) board.addSample(i * kDt, {{1.0}});
  board.addSample(50 * kDt + 1e-12, {{2.0}});  // the step after t = 50 dt, in a new run
  ASSERT_EQ(board.times().size(), 51u);
  EXPECT_EQ(board.charts[0].values[0].back(), 2.0);
}

TEST(PlotBoard, TheSlidePngHasTheSineWhereTheDataSaysAndTheTitleClearOfIt) {
  Sandbox sandbox(800, 600);
  sineSandbox(sandbox, 10);
  const auto dir = test::outputDir("plot_board");
  const std::string stem = (dir / "sine").string();
  const double now = 10;
  // exportChart draws the chart at the world's time: keep the world at t = 0, use `now`.
  const Plot plot = sandbox.plots->plot(sandbox.plots->charts[0], *sandbox.world(), now);
  writePng(renderPlotImage(plot, 1600, 900), stem + ".png");
  writePlotCsv(plot, stem + ".csv");
  const Image image = readPng(stem + ".png");
  ASSERT_EQ(image.width, 1600);
  ASSERT_EQ(image.height, 900);

  // The layout of renderPlot grown slideScale times.
  const double u = slideScale(1600, 900), left = 72 * u, right = 1600 - 24 * u, top = 44 * u,
               bottom = 900 - 52 * u;
  const auto yr = sandbox.plots->valueRange(sandbox.plots->charts[0], now);
  const auto xr = sandbox.plots->timeRange(now);
  EXPECT_EQ(xr[0], 0);
  EXPECT_EQ(xr[1], 10);
  auto column = [&](double t) { return left + (t - xr[0]) / (xr[1] - xr[0]) * (right - left); };
  auto row = [&](double y) { return bottom - (y - yr[0]) / (yr[1] - yr[0]) * (bottom - top); };

  // Over 0..4 s (clear of the legend, top right) the topmost curve pixel is the peak's: its
  // row, at the column of t = 1.
  int peakRow = image.height, peakColumn = -1;
  for (int y = 0; y < image.height && peakColumn < 0; ++y)
    for (int x = static_cast<int>(left); x < column(4); ++x)
      if (isCurve(image.pixel(x, y))) {
        peakRow = y, peakColumn = x;
        break;
      }
  const double lineHalfWidth = 0.5 * 3.5 * u;  // a single curve is drawn 3.5 px wide (x u)
  EXPECT_GT(row(1), top + 10);                 // the range is padded: the peak is inside
  EXPECT_NEAR(peakRow, row(1) - lineHalfWidth, 2.5);
  // The first curve pixel found on that row: the left end of the flat top (2 px of a sine's
  // top span about +-0.04 s there).
  EXPECT_NEAR(peakColumn, column(1), 0.06 * (right - left) / 10);
  // The curve crosses zero at t = 2: a curve pixel at (column(2), row(0)).
  bool crossing = false;
  for (int dy = -3; dy <= 3; ++dy)
    for (int dx = -3; dx <= 3; ++dx)
      crossing |=
          isCurve(image.pixel(static_cast<int>(column(2)) + dx, static_cast<int>(row(0)) + dy));
  EXPECT_TRUE(crossing);

  // The title's rows (above the plot area) hold dark text and no curve pixel.
  long titleInk = 0, curveAboveTop = 0;
  for (int y = 0; y < static_cast<int>(top); ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto* p = image.pixel(x, y);
      titleInk += p[0] < 90 && p[1] < 90 && p[2] < 90;
      curveAboveTop += isCurve(p);
    }
  EXPECT_GT(titleInk, 200);
  EXPECT_EQ(curveAboveTop, 0);
  // The axes' frame: dark pixels down the left edge of the plot area; tick labels below it.
  long frame = 0;
  for (int y = static_cast<int>(top) + 5; y < static_cast<int>(bottom) - 5; ++y)
    frame += image.pixel(static_cast<int>(left), y)[0] < 100;
  EXPECT_GT(frame, 0.9 * (bottom - top - 10));
  // A tick label under every tick (0, 2, ..., 10 s): dark pixels just below the axis there.
  for (double tick = 0; tick <= 10; tick += 2) {
    long ink = 0;
    for (int y = static_cast<int>(bottom + 8 * u); y < static_cast<int>(bottom + 22 * u); ++y)
      for (int x = static_cast<int>(column(tick) - 20 * u); x < column(tick) + 20 * u; ++x)
        ink += x >= 0 && x < image.width && image.pixel(x, y)[0] < 90;
    EXPECT_GT(ink, 20) << "tick " << tick;
  }

  // The CSV: the recorded samples in view, bit for bit.
  std::ifstream csv(stem + ".csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time (s),right: y (m)") << "header";
  const auto& t = sandbox.plots->times();
  const auto& v = sandbox.plots->charts[0].values[0];
  size_t rows = 0;
  while (std::getline(csv, line)) {
    std::stringstream fields(line);
    std::string a, b;
    std::getline(fields, a, ',');
    std::getline(fields, b, ',');
    ASSERT_LT(rows, t.size());
    EXPECT_EQ(std::stod(a), t[rows]);
    EXPECT_EQ(std::stod(b), v[rows]);
    ++rows;
  }
  EXPECT_EQ(rows, t.size());  // all 10 s are in view
}

// The CPU rasterizer draws what OSMesa draws (the same draw commands): at 640 x 400 (scale 1)
// the two differ only in the anti-aliased edges.
TEST(PlotBoard, TheCpuDrawingMatchesTheOffscreenRenderer) {
  Plot plot("sine and cosine", "t (s)", "y (m)");
  std::vector<double> t, y, z;
  for (int i = 0; i <= 200; ++i) {
    t.push_back(i * 0.05);
    y.push_back(std::sin(t.back()));
    z.push_back(std::cos(t.back()));
  }
  plot.addLine("sin", t, y).addLine("cos", t, z);
  ASSERT_EQ(slideScale(640, 400), 1.0f);
  const Image cpu = renderPlotImage(plot, 640, 400);
  const Image gl = renderPlot(plot, 640, 400);
  const ImageComparison c = compareImages(gl, cpu, 96);
  writePng(cpu, (test::outputDir("plot_board") / "cpu.png").string());
  writePng(c.diff, (test::outputDir("plot_board") / "cpu-vs-gl.png").string());
  EXPECT_LT(c.share(), 0.01);
}

}  // namespace plot_board_test
}  // namespace cablelab::ui
