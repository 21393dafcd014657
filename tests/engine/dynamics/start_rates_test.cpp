// The start rate of a taut rigid cable turned to the one its next step ends on (start_rates.h):
// over random bobs on a rope wrapped round a peg, the kinetic energy and the pose are kept and the
// rate becomes the next step's, (dt / 2) v^2 / l under the main solve, none under the midpoint
// rule; a rate no step could leave is left alone.
#include "engine/dynamics/start_rates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace start_rates_test {  // named: unity batches join test files

constexpr double kH = 1.0 / 60;

double rateOf(const Cable& rope, const std::vector<BodyState>& bodies) {
  double rate = 0;
  for (const auto& e : rope.kinematics().jacobian) {
    const BodyState& b = bodies[e.body];
    rate += e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
  }
  return rate;
}

TEST(StartRates, TurnsTheRateAcrossTheRopeKeepingTheKineticEnergy) {
  SceneDef scene = loadSceneFile(test::sourcePath("tests/data/sensors/peg_pendulum.json"));
  std::mt19937 random(36);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
  };
  double worstEnergy = 0, worstRate = 0;
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const double mass = uniform(0.1, 10), depth = uniform(0.2, 0.8), angle = uniform(-1.2, 1.2);
    const double length = 1 - depth;  // round the peg
    scene.bodies[0].mass = mass;
    scene.cables[0].pulleys[0].point = Vec2(0, -depth);
    const Vec2 out(std::sin(angle), -std::cos(angle));
    scene.bodies[0].position = Vec2(0, -depth) + length * out;
    // Wrapped at the start: the peg lies on the straight rope only at angle 0, so a point pulley
    // threaded in the path holds it there.
    scene.cables[0].pulleys[0].side = WrapSide::Threaded;
    World world(scene);
    world.step(1e-4);  // the rope's tension and kinematics at this pose
    const Cable& rope = world.cable(0);
    ASSERT_EQ(rope.wraps(), 1);
    ASSERT_GT(rope.tension(), 0);
    std::vector<BodyState> bodies(world.bodyCount());
    for (int b = 0; b < world.bodyCount(); ++b) bodies[b] = world.body(b);
    // Across the rope at v, along it at the main solve's chord rate of a whole step.
    const Vec2 across(out.y(), -out.x());
    const double speed = uniform(0.5, 8), second = speed * speed / length;
    const double last = kH, next = uniform(0, 1) < 0.5 ? 0.0 : uniform(1e-4, 1) * kH;
    bodies[0].velocity = speed * across + 0.5 * last * second * out;
    bodies[0].angularVelocity = uniform(-3, 3);
    const BodyState start = bodies[0];
    const std::vector<double> lastSteps = {last}, nextSteps = {next};
    const std::vector<char> excluded(bodies.size(), 0);
    const std::vector<int> changed = matchStartRates(
        {std::span<const Cable>(&rope, 1), lastSteps, nextSteps, excluded, -1, kH}, bodies);
    ASSERT_EQ(changed.size(), 1u);
    EXPECT_EQ(bodies[0].position, start.position);
    EXPECT_EQ(bodies[0].angle, start.angle);
    const double energy = std::abs(kineticEnergy(bodies[0]) / kineticEnergy(start) - 1);
    // The rate the next step ends on, at the speed across the rope now.
    const double across1 = bodies[0].velocity.dot(across);
    const double rate = rateOf(rope, bodies) - 0.5 * next * across1 * across1 / length;
    worstEnergy = std::max(worstEnergy, energy);
    worstRate = std::max(worstRate, std::abs(rate) / (0.5 * kH * second));
    EXPECT_LT(energy, 1e-12);
    // Exact for the midpoint rule; for the main solve's step the rate was set before the speed
    // across was scaled up to keep the energy, which moves v^2 / l by a few per cent.
    EXPECT_LT(std::abs(rate), (next == 0 ? 1e-9 : 0.1) * 0.5 * kH * second);
    // A rate no step of the main solve could leave (a rope coming slack): left alone.
    bodies[0] = start;
    bodies[0].velocity += 2 * kH * second * out;
    EXPECT_TRUE(
        matchStartRates({std::span<const Cable>(&rope, 1), lastSteps, nextSteps, excluded, -1, kH},
                        bodies)
            .empty());
  }
  std::printf("start rates: energy off by %.1e, rate by %.1e of a step's chord rate\n", worstEnergy,
              worstRate);
}

// A peg a scene places as a body of its own (static, or kinematic at rest) is as fixed as one on
// the world: the rope over it starts its steps on the same rates, so the bob swings and reads
// the same tensions. Before, only pegs on the world were matched: a round peg (5 cm) on a static
// body read 52% off the world peg's tension in the steps round the wrap, and the bob lost 1.1e-3
// of its kinetic energy more; a point peg at 240 Hz, 26%.
TEST(StartRates, APegOnAStaticBodySwingsTheBobAsAPegOnTheWorld) {
  const SceneDef base = loadSceneFile(test::sourcePath("tests/data/sensors/peg_pendulum.json"));
  auto pegOn = [&](PulleyDef::Kind kind, BodyType type, double mass, double release) {
    SceneDef scene = base;
    scene.bodies[0].mass = mass;
    scene.bodies[0].position = Vec2(std::sin(release), -std::cos(release));
    PulleyDef& peg = scene.cables[0].pulleys[0];
    const Vec2 at = peg.point;
    peg.kind = kind;
    if (kind == PulleyDef::Kind::Circle) peg.radius = 0.05;
    if (kind == PulleyDef::Kind::Polygon)
      for (const Vec2& corner : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)})
        peg.vertices.push_back(0.03 * corner);
    if (type == BodyType::Dynamic) {  // on the world
      if (kind == PulleyDef::Kind::Polygon)
        for (Vec2& corner : peg.vertices) corner += at;
      return scene;
    }
    BodyDef body;
    body.name = "peg";
    body.type = type;
    body.position = at;
    scene.bodies.push_back(body);
    peg.body = "peg";
    peg.point = Vec2::Zero();
    return scene;
  };
  struct Stepping {
    double dt;
    int substeps;
  };
  double worst = 0;
  for (const auto kind :
       {PulleyDef::Kind::Point, PulleyDef::Kind::Polygon, PulleyDef::Kind::Circle})
    for (const BodyType type : {BodyType::Static, BodyType::Kinematic})
      for (const double mass : {0.2, 3.0})
        for (const double release : {1.2, 1.9})
          for (const Stepping s :
               {Stepping{1.0 / 60, 1}, Stepping{1.0 / 60, 4}, Stepping{1.0 / 240, 1}}) {
            SCOPED_TRACE("kind " + std::to_string(static_cast<int>(kind)) + " on type " +
                         std::to_string(static_cast<int>(type)) + ", " + std::to_string(mass) +
                         " kg from " + std::to_string(release) + " rad, dt " +
                         std::to_string(s.dt) + " x " + std::to_string(s.substeps));
            World onWorld(pegOn(kind, BodyType::Dynamic, mass, release));
            World onBody(pegOn(kind, type, mass, release));
            int wrapped = 0;
            for (int i = 0; i < std::lround(0.8 / s.dt); ++i) {
              onWorld.step(s.dt, s.substeps);
              onBody.step(s.dt, s.substeps);
              const double t = onWorld.cable(0).tension();
              const double off = std::abs(onBody.cable(0).tension() - t) / std::max(t, mass * 9.81);
              worst = std::max(worst, off);
              ASSERT_LT(off, 1e-4) << "step " << i;  // Box2D keeps the peg body's pose in floats
              wrapped += onWorld.cable(0).wraps() > 0;
            }
            EXPECT_GT(wrapped, 0);
            EXPECT_NEAR(onBody.energy(), onWorld.energy(), 1e-5 * mass);
          }
  std::printf("pegs on bodies against pegs on the world: tensions off by %.1e\n", worst);
}

}  // namespace start_rates_test
}  // namespace cablelab
