// Friction on polygon pulleys against the capstan equation at their corners
// (docs/polygon_friction.md): a rope over a fixed square, hexagon and octagon between two
// masses, and over a polygon pivoted on an axle that the rope turns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace polygon_friction_test {  // named: unity batches join test files

using test::hangingMass;

constexpr double kG = 9.81;
using test::kDt;

// A regular polygon whose vertices sit at `phase` + 2 pi j / sides on a circle of radius
// `radius`: the square (phase pi/4) has a flat top and two corners over which a rope hanging
// down both sides turns by 90 degrees each; the hexagon and octagon (phase 0) have a corner at
// each side, where the rope turns by half a side's angle, and full sides' angles between.
struct Shape {
  const char* name;
  int sides;
  double phase;
  std::vector<double> turns;  ///< rad, at each corner the hanging rope turns on, left to right
};
const Shape kSquare{"square", 4, M_PI / 4, {M_PI / 2, M_PI / 2}};
const Shape kHexagon{"hexagon", 6, 0, {M_PI / 6, M_PI / 3, M_PI / 3, M_PI / 6}};
const Shape kOctagon{"octagon", 8, 0, {M_PI / 8, M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 8}};

struct Rope {
  Shape shape = kSquare;
  double radius = 0.3;
  double mu = 0.2;
  double m1 = 1, m2 = 1;  ///< kg, hanging left (the rope's start) and right
  double inertia = 0;     ///< kg m^2: > 0 pivots the polygon on an axle at its centre
  double angle = 0;       ///< rad, the pivoted polygon's angle at the start
};

// The rope hangs straight down from the polygon's leftmost and rightmost points (x = -/+ half
// the polygon's width), over its top: 180 degrees in all.
SceneDef ropeOverPolygon(const Rope& r) {
  const Vec2 centre(0, 3);
  std::vector<Vec2> vertices = test::sensorPolygon(r.shape.sides, r.radius, r.shape.phase).vertices;
  double half = 0;
  for (const Vec2& v : vertices) half = std::max(half, v.x());
  SceneDef s;
  s.name = "rope-over-" + std::string(r.shape.name);
  s.bodies = {hangingMass("left", centre + Vec2(-half, -2.0), r.m1),
              hangingMass("right", centre + Vec2(half, -2.0), r.m2)};
  PulleyDef over;
  over.kind = PulleyDef::Kind::Polygon;
  over.side = WrapSide::Left;  // over the top
  over.turns = 0.5;
  over.grip = r.mu > 0 ? Grip::Capstan : Grip::Frictionless;
  over.mu = r.mu;
  if (r.inertia > 0) {
    BodyDef wheel;
    wheel.name = "wheel";
    wheel.position = centre;
    wheel.angle = r.angle;
    wheel.mass = 1;
    wheel.inertia = r.inertia;
    ShapeDef shape;
    shape.kind = ShapeDef::Kind::Polygon;
    shape.vertices = vertices;
    shape.sensor = true;
    wheel.shapes = {shape};
    s.bodies.push_back(wheel);
    JointDef axle;
    axle.name = "axle";
    axle.bodyB = "wheel";
    axle.anchor = centre;
    s.joints = {axle};
    over.body = "wheel";
  } else {
    for (Vec2& v : vertices) v += centre;
    over.vertices = vertices;
  }
  CableDef rope;
  rope.name = "rope";
  rope.start = {"left", Vec2(0, 0.1)};
  rope.end = {"right", Vec2(0, 0.1)};
  rope.pulleys = {over};
  s.cables = {rope};
  return s;
}

// The left mass's mean vertical acceleration over `seconds`, after a step that settles the
// tensions.
double leftAcceleration(const Rope& r, double seconds = 0.5, double dt = kDt) {
  World w(ropeOverPolygon(r), "test");
  w.step(dt);
  const int left = w.findBody("left");
  const double v0 = w.body(left).velocity.y(), t0 = w.time();
  while (w.time() - t0 < seconds - 1e-9) w.step(dt);
  return (w.body(left).velocity.y() - v0) / (w.time() - t0);
}

// The capstan acceleration of the left mass when the rope slides (docs/polygon_friction.md):
// the heavy side's tension is e^(mu pi) times the light side's.
double capstanAcceleration(double mu, double m1, double m2) {
  const double e = std::exp(mu * M_PI);
  return m1 > m2 * e ? -kG * (m1 - m2 * e) / (m1 + m2 * e) : kG * (m2 - m1 * e) / (m2 + m1 * e);
}

TEST(PolygonFriction, HoldsBelowTheCapstanRatioAndSlidesAtTheCapstanAccelerationAbove) {
  test::Random rng(41);
  for (const Shape& shape : {kSquare, kHexagon, kOctagon})
    for (int trial = 0; trial < 3; ++trial) {
      Rope r;
      r.shape = shape;
      r.radius = rng.uniform(0.15, 0.5);
      r.mu = rng.uniform(0.05, 0.6);
      r.m2 = rng.uniform(0.5, 3);
      const double ratio = std::exp(r.mu * M_PI);
      SCOPED_TRACE(std::string(shape.name) + " mu " + std::to_string(r.mu) + " m2 " +
                   std::to_string(r.m2));
      for (const double factor : {0.98, 1.02 / (ratio * ratio)}) {  // holds: neither moves
        r.m1 = factor * ratio * r.m2;
        EXPECT_LT(std::abs(leftAcceleration(r)), 1e-4) << "m1 " << factor << " x ratio";
      }
      for (const double factor : {1.02, 3.0}) {  // slides left
        r.m1 = factor * ratio * r.m2;
        const double expected = capstanAcceleration(r.mu, r.m1, r.m2);
        EXPECT_NEAR(leftAcceleration(r), expected, 0.01 * std::abs(expected))
            << "m1 " << factor << " x ratio";
      }
      r.m1 = r.m2 / (2 * ratio);  // the right side heavier: slides right
      const double expected = capstanAcceleration(r.mu, r.m1, r.m2);
      EXPECT_GT(expected, 0);
      EXPECT_NEAR(leftAcceleration(r), expected, 0.01 * expected);
    }
}

TEST(PolygonFriction, AccelerationHoldsForOtherSteps) {
  Rope r;
  r.shape = kHexagon;
  r.mu = 0.35;
  r.m2 = 1.3;
  r.m1 = 4 * r.m2;
  const double expected = capstanAcceleration(r.mu, r.m1, r.m2);
  for (const double dt : {1.0 / 30, 1.0 / 240})
    EXPECT_NEAR(leftAcceleration(r, 0.5, dt), expected, 0.01 * std::abs(expected)) << "dt " << dt;
}

TEST(PolygonFriction, FrictionlessPolygonIsOneSpanAtTheAtwoodAcceleration) {
  for (const double mu : {0.0, 0.3}) {
    Rope r;
    r.shape = kOctagon;
    r.mu = mu;
    r.m1 = 2, r.m2 = 1;
    World w(ropeOverPolygon(r), "test");
    w.step(kDt);
    EXPECT_EQ(w.cable(0).spanCount(), mu > 0 ? 2 : 1);
  }
  Rope r;
  r.shape = kOctagon;
  r.mu = 0;
  r.m1 = 2, r.m2 = 1;
  EXPECT_NEAR(leftAcceleration(r), -kG / 3, 0.01 * kG / 3);
}

// Sliding, the tension falls by e^(mu theta_i) at every corner, theta_i the corner's turn.
TEST(PolygonFriction, EachCornerSlidesAtItsOwnRatio) {
  for (const Shape& shape : {kSquare, kHexagon, kOctagon}) {
    Rope r;
    r.shape = shape;
    r.mu = 0.4;
    r.m2 = 1;
    r.m1 = 2 * std::exp(r.mu * M_PI);
    World w(ropeOverPolygon(r), "test");
    for (int i = 0; i < 20; ++i) w.step(kDt);
    const Cable& rope = w.cable(0);
    ASSERT_EQ(rope.spanCount(), 2) << shape.name;
    EXPECT_NEAR(rope.link(0).wrapAngle, M_PI, 1e-6) << shape.name;
    std::vector<CornerTension> corners;
    rope.cornerTensions(0, corners);
    ASSERT_EQ(corners.size(), shape.turns.size()) << shape.name;
    EXPECT_DOUBLE_EQ(corners.front().tensionIn, rope.spanTension(0));
    EXPECT_DOUBLE_EQ(corners.back().tensionOut, rope.spanTension(1));
    for (size_t i = 0; i < corners.size(); ++i) {
      EXPECT_NEAR(corners[i].turn, shape.turns[i], 1e-6) << shape.name << " corner " << i;
      EXPECT_NEAR(corners[i].tensionIn / corners[i].tensionOut, std::exp(r.mu * shape.turns[i]),
                  1e-6)
          << shape.name << " corner " << i;
      if (i + 1 < corners.size()) {
        EXPECT_DOUBLE_EQ(corners[i].tensionOut, corners[i + 1].tensionIn);
        // The segment between the corners carries that tension too (the renderer's colour).
        const size_t segment = rope.path().size() - corners.size() - 1 + i;
        EXPECT_DOUBLE_EQ(rope.segmentTension(segment), corners[i].tensionOut);
      }
    }
    // The light side carries m2 (g + a): the whole ratio is e^(mu pi).
    const double a = -capstanAcceleration(r.mu, r.m1, r.m2);
    EXPECT_NEAR(rope.spanTension(1), r.m2 * (kG + a), 1e-3 * r.m2 * kG);
    EXPECT_NEAR(rope.spanTension(0) / rope.spanTension(1), std::exp(r.mu * M_PI), 1e-6);
  }
}

// Holding, no corner uses more than its friction: T_in / T_out <= e^(mu theta_i) at each.
TEST(PolygonFriction, HoldingCornersStayWithinTheirFriction) {
  Rope r;
  r.shape = kOctagon;
  r.mu = 0.3;
  r.m2 = 1;
  r.m1 = 0.9 * std::exp(r.mu * M_PI);
  World w(ropeOverPolygon(r), "test");
  for (int i = 0; i < 20; ++i) w.step(kDt);
  const Cable& rope = w.cable(0);
  EXPECT_NEAR(rope.spanTension(0), r.m1 * kG, 1e-6 * r.m1 * kG);
  EXPECT_NEAR(rope.spanTension(1), r.m2 * kG, 1e-6 * r.m2 * kG);
  EXPECT_FALSE(rope.link(0).slipped);
  std::vector<CornerTension> corners;
  rope.cornerTensions(0, corners);
  ASSERT_EQ(corners.size(), 5u);
  for (const CornerTension& c : corners) {
    const double ratio = c.tensionIn / c.tensionOut;
    EXPECT_GT(ratio, 1.0);
    EXPECT_LE(ratio, std::exp(r.mu * c.turn));
  }
}

// The energy Box2D's step keeps under constant gravity: it moves a body by h v at the end of the
// step (symplectic Euler), so the potential is taken half a step back, m g (y - h v_y / 2); then a
// step's change is exactly the work of the other forces at the step's mean velocity.
double energy(const World& w, double h) {
  double e = 0;
  for (int b = 0; b < w.bodyCount(); ++b) {
    const BodyState& s = w.body(b);
    const BodyDef& def = w.scene().bodies[b];
    if (def.type != BodyType::Dynamic) continue;
    e += 0.5 * def.mass * s.velocity.squaredNorm() +
         def.mass * kG * (s.position.y() - 0.5 * h * s.velocity.y());
    if (def.inertia > 0) e += 0.5 * def.inertia * s.angularVelocity * s.angularVelocity;
  }
  return e;
}

// Friction only takes energy out: sliding, the rope dissipates; holding on a pivoted polygon it
// drives, the energy stays (to the solver's tolerance).
TEST(PolygonFriction, EnergyNeverGrows) {
  struct Case {
    Rope rope;
    double dt;
  };
  std::vector<Case> cases;
  for (const double dt : {kDt, 1.0 / 240}) {
    Rope sliding;
    sliding.shape = kHexagon;
    sliding.mu = 0.25;
    sliding.m1 = 5;
    cases.push_back({sliding, dt});
    Rope pivoted;
    pivoted.shape = kOctagon;
    pivoted.mu = 0.5;
    pivoted.m1 = 1.5;
    pivoted.inertia = 0.05;
    cases.push_back({pivoted, dt});
    pivoted.mu = 0.05;  // slides on the polygon that turns
    pivoted.m1 = 3;
    cases.push_back({pivoted, dt});
  }
  for (const Case& c : cases) {
    World w(ropeOverPolygon(c.rope), "test");
    const double e0 = energy(w, c.dt);
    double highest = e0, previous = e0;
    double worstRise = 0;
    while (w.time() < 0.6) {  // the rising mass stays clear of the polygon
      w.step(c.dt);
      const double e = energy(w, c.dt);
      highest = std::max(highest, e);
      worstRise = std::max(worstRise, e - previous);
      previous = e;
    }
    SCOPED_TRACE(std::string(c.rope.shape.name) + " I " + std::to_string(c.rope.inertia) + " mu " +
                 std::to_string(c.rope.mu) + " dt " + std::to_string(c.dt));
    EXPECT_LT(highest - e0, 1e-3 * std::abs(e0));
    EXPECT_LT(worstRise, 1e-4 * std::abs(e0));
  }
}

// Over a fixed polygon, what the masses lose is the friction's work: (T_high - T_low) times the
// speed the rope slides at, summed over the steps.
TEST(PolygonFriction, TheEnergyLostIsTheFrictionWork) {
  for (const double mu : {0.1, 0.4}) {
    Rope r;
    r.shape = kSquare;
    r.mu = mu;
    r.m2 = 1;
    r.m1 = 2 * std::exp(mu * M_PI);
    World w(ropeOverPolygon(r), "test");
    const int left = w.findBody("left");
    const double e0 = energy(w, kDt);
    double work = 0;
    while (w.time() < 0.6) {
      const double v0 = w.body(left).velocity.y();
      w.step(kDt);
      const double speed = -0.5 * (v0 + w.body(left).velocity.y());  // the step's mean
      work += (w.cable(0).spanTension(0) - w.cable(0).spanTension(1)) * speed * kDt;
    }
    EXPECT_GT(work, 1.0);
    EXPECT_NEAR(e0 - energy(w, kDt), work, 1e-3 * work) << "mu " << mu;
  }
}

// The unit vector from a to b.
Vec2 toward(const Vec2& a, const Vec2& b) {
  return (b - a).normalized();
}

// A polygon on an axle that the rope's friction turns: I alpha is the torque of the two spans'
// tensions at its first and last engaged corners (the rope between the corners pulls both ways
// on the rigid polygon: no torque of its own).
TEST(PolygonFriction, APivotedPolygonTurnsWithTheTorqueOfItsSpanTensions) {
  struct Case {
    double mu, m1, inertia, angle;
  };
  for (const Case& c :
       {Case{1.0, 2.0, 0.05, 0.0}, Case{0.08, 3.0, 0.2, 0.1}, Case{0.2, 0.4, 0.02, -0.2}}) {
    Rope r;
    r.shape = kHexagon;
    r.mu = c.mu, r.m1 = c.m1, r.inertia = c.inertia, r.angle = c.angle;
    World w(ropeOverPolygon(r), "test");
    const int wheel = w.findBody("wheel"), left = w.findBody("left");
    const Vec2 centre = w.body(wheel).position;
    w.step(kDt);
    int checked = 0;
    for (int i = 0; i < 40; ++i) {
      const std::vector<WrapPoint> path = w.cable(0).path();
      const double omega0 = w.body(wheel).angularVelocity, v0 = w.body(left).velocity.y();
      w.step(kDt);
      const Cable& rope = w.cable(0);
      bool same = rope.path().size() == path.size();
      for (size_t p = 0; same && p < path.size(); ++p)
        same = rope.path()[p].vertex == path[p].vertex;
      if (!same || rope.spanCount() != 2) continue;  // a corner came or went within the step
      const size_t first = 1, last = path.size() - 2;
      const double t0 = rope.spanTension(0), t1 = rope.spanTension(1);
      const double torque =
          cross(Vec2(path[first].world - centre), t0 * toward(path[first].world, path[0].world)) +
          cross(Vec2(path[last].world - centre),
                t1 * toward(path[last].world, path[last + 1].world));
      const double alpha = (w.body(wheel).angularVelocity - omega0) / kDt;
      EXPECT_NEAR(c.inertia * alpha, torque, 0.02 * std::abs(torque) + 1e-3)
          << "mu " << c.mu << " step " << i;
      // ... and the left mass's rope pulls it up with the first span's tension.
      const double a = (w.body(left).velocity.y() - v0) / kDt;
      EXPECT_NEAR(r.m1 * (a + kG), t0, 0.02 * t0) << "mu " << c.mu << " step " << i;
      ++checked;
    }
    EXPECT_GT(checked, 20);
    EXPECT_GT(std::abs(w.body(wheel).angularVelocity), 0.5) << "mu " << c.mu;
  }
}

// Held by friction, the rope turns the polygon round with it: corners come onto the rope and go
// off it, and each time the rope between the corners changes, its length does not.
TEST(PolygonFriction, APolygonTurningUnderTheHeldRopeKeepsItsLength) {
  for (const double dt : {kDt, 1.0 / 200}) {
    Rope r;
    r.shape = kHexagon;
    r.mu = 1.5;  // e^(1.5 pi) = 111: holds
    r.m1 = 2;
    r.inertia = 0.02;
    World w(ropeOverPolygon(r), "test");
    const int wheel = w.findBody("wheel");
    w.step(dt);
    const double length0 = w.cable(0).length();
    std::vector<int> vertices;
    int changes = 0;
    double worst = 0;
    while (w.time() < 0.8) {
      w.step(dt);
      const Cable& rope = w.cable(0);
      std::vector<int> now;
      for (const WrapPoint& p : rope.path()) now.push_back(p.vertex);
      changes += now != vertices && !vertices.empty();
      vertices = now;
      worst = std::max(worst, std::abs(rope.length() - length0));
      ASSERT_FALSE(rope.link(0).slipped) << "t " << w.time();
    }
    SCOPED_TRACE("dt " + std::to_string(dt));
    EXPECT_GT(std::abs(w.body(wheel).angle), M_PI / 3);  // a sixth of a turn or more
    EXPECT_GE(changes, 2);
    EXPECT_LT(worst, 1e-4);
    EXPECT_TRUE(w.warnings().empty()) << w.warnings().front();
  }
}

}  // namespace polygon_friction_test
}  // namespace cablelab
