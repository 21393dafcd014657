// Two polygon pulleys of one rope knocking (engine/dynamics/pulley_knock.h): the knock is one
// impulse solved with the taut rigid ropes on the bodies, so that a pair let go in one rope loop
// with restitution 1 knocks without loss (docs/knocks.md, "Two pulleys in one loop").
#include "engine/dynamics/pulley_knock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "engine/dynamics/hull_contacts.h"
#include "engine/dynamics/world.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace {

struct Loop {
  int sides;      // of both polygons
  double radius;  // m, corner radius
  double mass;    // kg, each
  double gap;     // m between their corner circles at the start
  double hz;      // steps per second
  int substeps;
};

// Two sensor polygons at rest 0.8 m below a rigid rope from (-1, 1) under both (right) and over a
// point at (0, 1) to (1, 1): they slide together to the bottom of the loop and knock.
SceneDef twoInOneLoop(const Loop& l, double restitution) {
  SceneDef s;
  const double xs[] = {-0.55, -0.55 + 2 * l.radius + l.gap};
  for (int i = 0; i < 2; ++i) {
    BodyDef b;
    b.name = "P" + std::to_string(i);
    b.position = Vec2(xs[i], 0.2);
    b.mass = l.mass;
    b.shapes = {test::sensorPolygon(l.sides, l.radius, 0.1 * i)};
    b.shapes[0].restitution = restitution;
    s.bodies.push_back(b);
  }
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(-1, 1)};
  for (const char* body : {"P0", "P1"}) {
    PulleyDef under;
    under.kind = PulleyDef::Kind::Polygon;
    under.body = body;
    under.side = WrapSide::Right;
    rope.pulleys.push_back(under);
  }
  PulleyDef point;
  point.kind = PulleyDef::Kind::Point;
  point.point = Vec2(0, 1);
  point.side = WrapSide::Left;
  rope.pulleys.push_back(point);
  rope.end = {"world", Vec2(1, 1)};
  s.cables = {rope};
  s.dt = 1 / l.hz;
  s.substeps = l.substeps;
  return s;
}

double kineticEnergy(const std::vector<BodyState>& bodies) {
  double e = 0;
  for (const BodyState& b : bodies)
    e += 0.5 * b.velocity.squaredNorm() / b.invMass +
         0.5 * b.angularVelocity * b.angularVelocity / b.invInertia;
  return e;
}

// Random free pairs about to knock, no rope: restitution 1 keeps the kinetic energy to rounding,
// less takes some, and a knocked pair is moving apart (a second knock finds nothing to do).
TEST(PulleyKnock, AKnockKeepsTheKineticEnergyAtRestitutionOneAndPartsThePair) {
  constexpr double kHorizon = 0.02, kSkin = 0.02;  // s, m: a sub-step, Box2D's two skins
  std::mt19937 rng(38);
  int knocks = 0;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int run = 0; run < 200; ++run) {
    const double e = run % 2 ? 1.0 : 0.4 * unit(rng);
    const Loop l{3 + run % 3, 0.08 + 0.1 * unit(rng), 0.2 + 3 * unit(rng), 0.025, 60, 1};
    SceneDef s = twoInOneLoop(l, e);
    s.bodies[1].angle = 2 * M_PI * unit(rng);
    PulleyKnock knock(s, hullContacts(s));
    ASSERT_EQ(knock.pairCount(), 1);
    std::vector<BodyState> bodies(2);
    for (int i = 0; i < 2; ++i) {
      BodyState& b = bodies[i];
      b.position = s.bodies[i].position;
      b.angle = s.bodies[i].angle;
      b.invMass = 1 / l.mass * (i ? 1 + unit(rng) : 1.0);
      b.invInertia = b.invMass / (0.3 * l.radius * l.radius);
      b.velocity = Vec2((i ? -1 : 1) * (0.5 + 3 * unit(rng)), unit(rng) - 0.5);
      b.angularVelocity = 10 * (unit(rng) - 0.5);
    }
    const double before = kineticEnergy(bodies);
    const std::vector<int> knocked = knock.knock(bodies, {}, kHorizon, kSkin);
    SCOPED_TRACE("run " + std::to_string(run) + " restitution " + std::to_string(e));
    if (knocked.empty()) continue;  // a spin carried the near corners apart
    ++knocks;
    const double after = kineticEnergy(bodies);
    if (e == 1.0)
      EXPECT_NEAR(after, before, 1e-12 * before);
    else
      EXPECT_LT(after, before);
    EXPECT_TRUE(knock.knock(bodies, {}, kHorizon, kSkin).empty()) << "knocked twice";
  }
  EXPECT_GT(knocks, 100);
}

TEST(PulleyKnock, DeadPairsKeepBox2DsKnock) {
  const SceneDef s = twoInOneLoop({3, 0.12, 0.3, 0.06, 60, 1}, 0);
  EXPECT_EQ(PulleyKnock(s, hullContacts(s)).pairCount(), 0);
}

struct Kept {
  // Each over the largest kinetic energy of the run: the energy change summed over the steps
  // that start with the rope taut (knocks, the rope's pull) and over those that start slack (the
  // rigid rope's catches), and the largest gain in a step.
  double taut = 0, slack = 0, worstGain = 0;
};

Kept run(const Loop& l, double restitution, double seconds) {
  World w(twoInOneLoop(l, restitution), "loop");
  auto kinetic = [&] {
    double e = w.energy();
    for (int i = 0; i < 2; ++i) e -= l.mass * 9.81 * w.body(i).position.y();
    return e;
  };
  Kept kept;
  double largest = 0;
  for (int k = 0; k < static_cast<int>(std::lround(seconds * l.hz)); ++k) {
    const double e = w.energy();
    const bool slack = w.cable(0).stretch() < -1e-4;
    w.step(1 / l.hz, l.substeps);
    (slack ? kept.slack : kept.taut) += w.energy() - e;
    kept.worstGain = std::max(kept.worstGain, w.energy() - e);
    largest = std::max(largest, kinetic());
  }
  kept.taut /= largest;
  kept.slack /= largest;
  kept.worstGain /= largest;
  return kept;
}

const Loop kLoops[] = {
    {3, 0.12, 0.3, 0.06, 60, 1}, {3, 0.12, 3.0, 0.06, 60, 2}, {4, 0.12, 0.3, 0.2, 60, 4},
    {3, 0.08, 0.3, 0.2, 120, 1}, {4, 0.08, 3.0, 0.06, 60, 1}, {3, 0.12, 0.3, 0.2, 120, 2},
    {4, 0.12, 3.0, 0.2, 60, 2},  {3, 0.08, 3.0, 0.06, 60, 4},
};

// With restitution 1 the knocks keep the energy: what the steps with the rope taut change stays
// small (Box2D's knock and the contact catch: up to 97% of the largest kinetic energy lost or
// gained in those steps, and 97% gained in one step). What is still lost is the rigid rope's
// catches from slack, inelastic by design (docs/knocks.md, "Two pulleys in one loop").
TEST(PulleyKnock, PolygonsLetGoInOneLoopWithRestitutionOneKnockWithoutLoss) {
  for (const Loop& l : kLoops) {
    SCOPED_TRACE(std::to_string(l.sides) + " sides, " + std::to_string(l.radius) + " m, " +
                 std::to_string(l.mass) + " kg, gap " + std::to_string(l.gap) + " at " +
                 std::to_string(l.hz) + " Hz x " + std::to_string(l.substeps));
    const Kept kept = run(l, 1, 6);
    EXPECT_GT(kept.taut, -0.15);
    EXPECT_LT(kept.taut, 0.02);
    EXPECT_LT(kept.slack, 1e-3) << "a catch gained";
    EXPECT_LT(kept.worstGain, 0.05);
  }
}

}  // namespace
}  // namespace cablelab
