// A pendulum whose rope wraps a peg keeps its energy swing after swing (issue 36, theorem 1: wrap
// points come and go without impulses). The rope took the midpoint rule while wrapped and the
// main solve while straight; each switch locked in the main solve's energy swing, and a 0.7 kg
// bob let go 50 degrees out lost 37% of its swing in 10 minutes at 60 Hz (91% in 5 round a 4 cm
// square peg). A rigid rope over pulleys that swings, taut for the last steps, now keeps the
// midpoint rule wrapped or straight, and a rope just caught from slack keeps the main solve's
// catch (docs/swings.md). Scene: tests/data/sensors/peg_pendulum.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace peg_swing_energy_test {  // named: unity batches join test files

struct PegSwing {
  PulleyDef::Kind kind;
  double depth;    // m below the anchor, on a 1 m rope
  double mass;     // kg
  double release;  // degrees out
  double dt;
  int substeps;
};

std::string describe(const PegSwing& p) {
  const char* kinds[] = {"point", "square", "circle"};
  return std::string(kinds[static_cast<int>(p.kind)]) + " peg " + std::to_string(p.depth) +
         " m down, " + std::to_string(p.mass) + " kg, " + std::to_string(p.release) +
         " deg, dt 1/" + std::to_string(std::lround(1 / p.dt)) + " x " + std::to_string(p.substeps);
}

SceneDef pegScene(const PegSwing& p) {
  SceneDef scene = loadSceneFile(test::sourcePath("tests/data/sensors/peg_pendulum.json"));
  const double angle = p.release * std::acos(-1.0) / 180;
  scene.bodies[0].mass = p.mass;
  scene.bodies[0].position = Vec2(std::sin(angle), -std::cos(angle));
  PulleyDef& peg = scene.cables[0].pulleys[0];
  peg.kind = p.kind;
  peg.point = Vec2(0, -p.depth);
  constexpr double kHalfSize = 0.02;  // m: a 4 cm square, a 2 cm round peg
  if (p.kind == PulleyDef::Kind::Circle) peg.radius = kHalfSize;
  if (p.kind == PulleyDef::Kind::Polygon)
    for (const Vec2& corner : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)})
      peg.vertices.push_back(peg.point + kHalfSize * corner);
  return scene;
}

// The bob's energy relative to its start, over its swing (m g times the height it falls to the
// bottom), at the end of each of `periods` periods of `period` s; the most it rose above its
// start; and how many wraps it made.
struct SwingReading {
  std::vector<double> changes;
  double gain = 0;
  int wraps = 0;
};

SwingReading swing(const PegSwing& p, double period, int periods) {
  const SceneDef scene = pegScene(p);
  World world(scene);
  const int bob = world.findBody("bob");
  const Cable& rope = world.cable(0);
  auto energy = [&] {
    const BodyState& b = world.body(bob);
    return 0.5 * p.mass * b.velocity.squaredNorm() - p.mass * scene.gravity.dot(b.position);
  };
  const double scale =
      p.mass * scene.gravity.norm() * (1 - std::cos(p.release * std::acos(-1.0) / 180));
  const double start = energy();
  SwingReading r;
  int wraps = rope.wraps();
  for (int k = 1; k <= periods; ++k) {
    while (world.time() < k * period - 0.5 * p.dt) {
      world.step(p.dt, p.substeps);
      r.wraps += rope.wraps() > wraps;
      wraps = rope.wraps();
      r.gain = std::max(r.gain, (energy() - start) / scale);
    }
    r.changes.push_back((energy() - start) / scale);
  }
  return r;
}

// 20 s, at least 8 wraps, over point, square and round pegs, two depths, masses and releases,
// 30 Hz, 60 Hz, 60 Hz x 4 and 240 Hz. Before, the bob lost 0.15% (point peg) to 0.8% (square)
// of its swing a swing at 60 Hz; now under 1e-4, and it never rises 1% above its start (the
// main solve's own swing within a step was 2.7% at 60 Hz).
TEST(PegSwingEnergy, SwingsRoundAPegKeepTheirEnergy) {
  constexpr double kSeconds = 20;
  double worst = 0;
  for (const auto kind :
       {PulleyDef::Kind::Point, PulleyDef::Kind::Polygon, PulleyDef::Kind::Circle})
    for (const double depth : {0.3, 0.45})
      for (const double mass : {0.7, 5.0})
        for (const double release : {30.0, 55.0})
          for (const auto& [dt, substeps] : std::vector<std::pair<double, int>>{
                   {1.0 / 30, 1}, {1.0 / 60, 1}, {1.0 / 60, 4}, {1.0 / 240, 1}}) {
            const PegSwing p{kind, depth, mass, release, dt, substeps};
            SCOPED_TRACE(describe(p));
            const SwingReading r = swing(p, kSeconds, 1);
            ASSERT_GE(r.wraps, 8);
            const double perSwing = r.changes.back() / r.wraps;
            worst = std::max(worst, std::abs(perSwing));
            EXPECT_LT(std::abs(perSwing), 1e-4) << "lost " << -r.changes.back() << " of the swing";
            EXPECT_LT(r.gain, 0.01);
          }
  std::printf("worst change a swing: %.2e of the swing\n", worst);
}

// Bobs like the (0.7 kg let go 50 degrees out, the peg 0.45 m down; here on 1 m), 10
// minutes at 60 Hz: within 2% of the swing, and no minute moves it by more than 0.2%. The
// issue's (on 0.8 m) lost 37% round a point peg, 91% in 5 minutes round a square one.
TEST(PegSwingEnergy, TenMinutesRoundAPegAt60HzKeepTheSwing) {
  for (const auto kind :
       {PulleyDef::Kind::Point, PulleyDef::Kind::Polygon, PulleyDef::Kind::Circle}) {
    PegSwing p{kind, 0.45, 0.7, 50, 1.0 / 60, 1};
    SCOPED_TRACE(describe(p));
    const SwingReading r = swing(p, 60, 10);
    double worstMinute = std::abs(r.changes.front());
    for (size_t k = 1; k < r.changes.size(); ++k)
      worstMinute = std::max(worstMinute, std::abs(r.changes[k] - r.changes[k - 1]));
    std::printf("%s: 10 min %.2e of the swing, worst minute %.2e, gain %.2e, %d wraps\n",
                describe(p).c_str(), r.changes.back(), worstMinute, r.gain, r.wraps);
    EXPECT_LT(std::abs(r.changes.back()), 0.02);
    EXPECT_LT(worstMinute, 0.002);
    EXPECT_GE(r.wraps, 300);
  }
}

}  // namespace peg_swing_energy_test
}  // namespace cablelab
