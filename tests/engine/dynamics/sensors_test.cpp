// Sensors that tell the truth (issue 36, item 2): the tension a step reports is its impulse over
// the step, with no alternation after a wrap change, and rigid cables at rest report no velocity
// and tensions that balance the load. Scenes: tests/data/sensors/.
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
namespace sensors_test {  // named: unity batches join test files

struct Stepping {
  double dt;
  int substeps;
};
// 30 Hz to 480 Hz, 1 to 8 sub-steps.
const std::vector<Stepping> kSteppings = {{1.0 / 30, 1}, {1.0 / 60, 1},  {1.0 / 60, 4},
                                          {1.0 / 60, 8}, {1.0 / 120, 2}, {1.0 / 240, 1},
                                          {1.0 / 480, 1}};
const std::vector<double> kMasses = {0.3, 1.0, 5.0};

std::string label(double mass, const Stepping& s) {
  return "mass " + std::to_string(mass) + " kg, dt 1/" + std::to_string(std::lround(1 / s.dt)) +
         " s x " + std::to_string(s.substeps);
}

// The peg pendulum (tests/data/sensors/peg_pendulum.json): a bob on a 1 m rigid rope from an
// anchor at the origin, a peg below it that the rope wraps as it swings past.
const Vec2 kAnchor(0, 0);

// Where the rope acts on the bob from: its last wrap point (a circle's tangent point).
Vec2 pivotOf(const Cable& rope) {
  const WrapPoint& w = rope.path()[rope.path().size() - 2];
  return w.kind == WrapPoint::Kind::Circle ? w.tangentOut : w.world;
}

// The tension that keeps the bob on its path round `pivot`: m v^2 / l - m g . u, u the
// direction from the bob to the pivot, l their distance (for a rope winding onto a circle, the
// free length: the radius of curvature of the bob's involute).
double pathTension(const BodyState& bob, const Vec2& pivot, double mass, const Vec2& gravity) {
  const Vec2 d = pivot - bob.position;
  return mass * (bob.velocity.squaredNorm() / d.norm() - gravity.dot(d.normalized()));
}

// The share of a step from `before` to `after` spent before the rope met the peg: where the
// line from the old pivot to the bob reaches the new one (a circle's rim), the distance to it
// taken linear in time over the step.
double shareBeforeWrap(const Vec2& oldPivot, const Vec2& peg, double radius, const Vec2& before,
                       const Vec2& after) {
  auto side = [&](const Vec2& bob) { return cross((bob - oldPivot).normalized(), peg - oldPivot); };
  const double d0 = side(before), d1 = side(after);
  const double s0 = d0 - std::copysign(radius, d0), s1 = d1 - std::copysign(radius, d0);
  return std::clamp(s0 / (s0 - s1), 0.0, 1.0);
}

// A peg: where, on which side of the rope, what (a point, a square of half-side `size`, a circle
// of radius `size`), and where the bob is let go from (degrees from straight down, on the side
// the rope swings past the peg from).
struct PegVariant {
  Vec2 at;
  PulleyDef::Kind kind = PulleyDef::Kind::Point;
  double size = 0;
  double release = 90;    // degrees
  bool mirrored = false;  // let go on the left (the rope passes the peg on its right)
};

std::string describe(const PegVariant& p) {
  const char* kinds[] = {"point", "square", "circle"};
  return std::string(kinds[static_cast<int>(p.kind)]) + " peg at (" + std::to_string(p.at.x()) +
         ", " + std::to_string(p.at.y()) + "), released at " + std::to_string(p.release) + " deg" +
         (p.mirrored ? " from the left" : "");
}

SceneDef pegScene(const PegVariant& p, double mass) {
  SceneDef scene = loadSceneFile(test::sourcePath("tests/data/sensors/peg_pendulum.json"));
  const double sign = p.mirrored ? -1 : 1, angle = p.release * std::acos(-1.0) / 180;
  scene.bodies[0].mass = mass;
  scene.bodies[0].position = kAnchor + Vec2(sign * std::sin(angle), -std::cos(angle));
  PulleyDef& peg = scene.cables[0].pulleys[0];
  peg.kind = p.kind;
  peg.point = Vec2(sign * p.at.x(), p.at.y());
  peg.side = p.mirrored ? WrapSide::Right : WrapSide::Left;
  if (p.kind == PulleyDef::Kind::Circle) peg.radius = p.size;
  if (p.kind == PulleyDef::Kind::Polygon)
    for (const Vec2& corner : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)})
      peg.vertices.push_back(peg.point + p.size * corner);
  return scene;
}

// From the step the rope wraps the peg in, while the bob is below its pivot (the rope taut) and
// the rope wraps no less: each step's tension against the path tension's mean over it, and the
// bob's energy over the wrap step and the step after.
struct PegReading {
  double worst = 0;        // of the tension over the expected one, less 1
  double worstWrap = 0;    // ... over the steps whose wrap set changed
  double alternation = 0;  // a step's tension off its neighbours' mean, beyond the expected's
  double energy = 0;       // the bob's energy change over the wrap, over its kinetic energy
  double swing = 0;        // ... over the step before the wrap step: the integrator's own
  double wrapEnergy = 0;   // ... over the wrap step alone
  int steps = 0, wrapSteps = 0;
};

PegReading readPeg(const PegVariant& p, double mass, const Stepping& s, bool matched = true) {
  const SceneDef scene = pegScene(p, mass);
  World world(scene);
  world.setStartRatesMatched(matched);
  const int bob = world.findBody("bob");
  const Cable& rope = world.cable(0);
  auto energy = [&](const BodyState& b) {
    return 0.5 * mass * b.velocity.squaredNorm() - mass * scene.gravity.dot(b.position);
  };
  BodyState before = world.body(bob), earlier = before;
  Vec2 pivot = pivotOf(rope);
  int wraps = rope.wraps();
  for (int i = 0; i < 4000 && wraps == 0; ++i) {  // up to the wrap step
    earlier = before;
    before = world.body(bob);
    pivot = pivotOf(rope);
    world.step(s.dt, s.substeps);
    wraps = rope.wraps();
  }
  PegReading r;
  if (wraps == 0) return r;
  const double startEnergy = energy(before), scale = 0.5 * mass * before.velocity.squaredNorm();
  r.swing = std::abs(startEnergy - energy(earlier)) / scale;
  std::vector<double> reported, expected;
  bool wrapped = true;  // the step just taken changed the wrap set
  for (int i = 0; i < std::lround(0.4 / s.dt); ++i) {
    const BodyState& after = world.body(bob);
    const Vec2 now = pivotOf(rope);
    if (after.position.y() > now.y() - 0.25 * (after.position - now).norm()) break;
    double mean = 0.5 * (pathTension(before, now, mass, scene.gravity) +
                         pathTension(after, now, mass, scene.gravity));
    if (wrapped) {
      const Vec2 peg =
          p.kind == PulleyDef::Kind::Circle ? Vec2(scene.cables[0].pulleys[0].point) : now;
      const double radius = p.kind == PulleyDef::Kind::Circle ? p.size : 0;
      const double f = shareBeforeWrap(pivot, peg, radius, before.position, after.position);
      mean = f * pathTension(before, pivot, mass, scene.gravity) +
             (1 - f) * pathTension(after, now, mass, scene.gravity);
    }
    reported.push_back(rope.tension());
    expected.push_back(mean);
    const double off = std::abs(reported.back() / mean - 1);
    r.worst = std::max(r.worst, off);
    if (wrapped) r.worstWrap = std::max(r.worstWrap, off), ++r.wrapSteps;
    if (reported.size() == 1) r.wrapEnergy = std::abs(energy(after) - startEnergy) / scale;
    if (reported.size() == 2) r.energy = std::abs(energy(after) - startEnergy) / scale;
    before = after;
    pivot = now;
    world.step(s.dt, s.substeps);
    if (rope.wraps() < wraps) break;  // swung back: unwrapping
    wrapped = rope.wraps() != wraps;
    wraps = rope.wraps();
  }
  r.steps = static_cast<int>(reported.size());
  for (size_t k = 1; k + 1 < reported.size(); ++k) {
    const double off = reported[k] - 0.5 * (reported[k - 1] + reported[k + 1]);
    const double curve = expected[k] - 0.5 * (expected[k - 1] + expected[k + 1]);
    r.alternation = std::max(r.alternation, std::abs(off - curve) / expected[k]);
  }
  return r;
}

// The wrap step reports the rope's impulse over it: the tension before the wrap for the time
// before it, after for the rest (docs/model.md, "Coupling to Box2D"). Before, the
// main solve's chord rate along the rope, (h / 2) v^2 / l, was taken out by an impulse as the
// midpoint rule took over at the wrap: 17% high at 60 Hz, and 1.4e-3 of the energy lost.
TEST(SensorsTest, WrappedPendulumReportsTheStepsTensionWithoutAlternation) {
  for (const double mass : kMasses)
    for (const Stepping& s : kSteppings) {
      SCOPED_TRACE(label(mass, s));
      const PegReading r = readPeg({Vec2(0, -0.6)}, mass, s),
                       before = readPeg({Vec2(0, -0.6)}, mass, s, false);
      std::printf(
          "peg %s: worst %.4f (before %.4f), wrap step %.4f (before %.4f), energy %.1e "
          "(before %.1e)\n",
          label(mass, s).c_str(), r.worst, before.worst, r.worstWrap, before.worstWrap, r.energy,
          before.energy);
      ASSERT_GE(r.steps, 3);
      ASSERT_GE(r.wrapSteps, 1);
      EXPECT_LT(r.worst, 0.03);
      EXPECT_LT(r.alternation, 0.005);
      EXPECT_LT(r.energy, 1e-3);
    }
}

// Pegs at other depths and sides, a square peg and a round one (5 cm), let go from 60 to 120
// degrees (above the anchor the rope is slack until it catches the bob), 0.1 to 10 kg.
TEST(SensorsTest, PegsOfEveryKindReportTheStepsTensionFromTheWrapOn) {
  const std::vector<Stepping> steppings = {{1.0 / 60, 1}, {1.0 / 60, 4}, {1.0 / 240, 1}};
  const std::vector<PegVariant> pegs = {{Vec2(0, -0.6), PulleyDef::Kind::Point, 0, 60},
                                        {Vec2(0, -0.3), PulleyDef::Kind::Point, 0, 120},
                                        {Vec2(0, -0.8), PulleyDef::Kind::Point, 0, 90, true},
                                        {Vec2(0.15, -0.5), PulleyDef::Kind::Point, 0, 100},
                                        {Vec2(-0.2, -0.6), PulleyDef::Kind::Point, 0, 75, true},
                                        {Vec2(0, -0.6), PulleyDef::Kind::Circle, 0.05, 90},
                                        {Vec2(0.1, -0.4), PulleyDef::Kind::Circle, 0.05, 120, true},
                                        {Vec2(0, -0.6), PulleyDef::Kind::Polygon, 0.03, 90},
                                        {Vec2(0, -0.5), PulleyDef::Kind::Polygon, 0.03, 110, true}};
  double worst = 0, worstWrap = 0, alternation = 0, energy = 0;
  for (const PegVariant& p : pegs)
    for (const double mass : {0.1, 1.0, 10.0})
      for (const Stepping& s : steppings) {
        SCOPED_TRACE(describe(p) + ", " + label(mass, s));
        const PegReading r = readPeg(p, mass, s), before = readPeg(p, mass, s, false);
        std::printf(
            "%s, %s: worst %.4f (before %.4f), wrap step %.4f (%d), alternation %.4f, "
            "(before %.4f), energy %.1e (before %.1e, a step's swing %.1e), wrap step %.1e "
            "(before %.1e)\n",
            describe(p).c_str(), label(mass, s).c_str(), r.worst, before.worst, r.worstWrap,
            r.wrapSteps, r.alternation, before.alternation, r.energy, before.energy, r.swing,
            r.wrapEnergy, before.wrapEnergy);
        ASSERT_GE(r.steps, 3);
        ASSERT_GE(r.wrapSteps, 1);
        EXPECT_LT(r.worst, 0.03);
        // Measured: up to 0.011 at 60 Hz (the round peg let go from 120 degrees), 0.0024 at 60 Hz
        // x 4; before, 0.05 to 0.89.
        EXPECT_LT(r.alternation, 0.015);
        // Over the wrap step, the bob's energy moves no more than the main solve's own swing over
        // the step before (its symplectic Euler, up to 2.7e-3 of the kinetic energy at 60 Hz),
        // and by under 1e-3 at 60 Hz x 4 and 240 Hz.
        EXPECT_LT(r.wrapEnergy, std::max(1e-3, r.swing));
        worst = std::max(worst, r.worst);
        worstWrap = std::max(worstWrap, r.worstWrap);
        alternation = std::max(alternation, r.alternation);
        energy = std::max(energy, r.energy);
      }
  std::printf("all pegs: worst %.4f, wrap steps %.4f, alternation %.4f, energy %.1e\n", worst,
              worstWrap, alternation, energy);
}

// A peg near the anchor at 20 and 30 Hz: the rope round it swings faster than the main solve
// resolves, so it takes the midpoint rule, which the fast-catch refinement cut into a part of
// 0.3 / omega and a rest. The rest went to the main solve and each sub-step turned the rope's
// rate twice: 4.2% high at 30 Hz let go from 82 degrees, 16% from 106. Each part of a sub-step
// now keeps one rule (docs/model.md, "Coupling to Box2D"); the sweep's worst such variants.
TEST(SensorsTest, PegsNearTheAnchorKeepOneRuleOverEachSubStep) {
  const std::vector<Stepping> steppings = {{1.0 / 20, 1}, {1.0 / 30, 1}};
  const std::vector<PegVariant> pegs = {{Vec2(0, -0.26), PulleyDef::Kind::Point, 0, 82},
                                        {Vec2(0, -0.26), PulleyDef::Kind::Point, 0, 106},
                                        {Vec2(0, -0.26), PulleyDef::Kind::Point, 0, 125, true}};
  for (const PegVariant& p : pegs)
    for (const double mass : {0.2, 5.0})
      for (const Stepping& s : steppings) {
        SCOPED_TRACE(describe(p) + ", " + label(mass, s));
        const PegReading r = readPeg(p, mass, s);
        std::printf("%s, %s: worst %.4f, wrap step %.4f, alternation %.4f, wrap energy %.1e\n",
                    describe(p).c_str(), label(mass, s).c_str(), r.worst, r.worstWrap,
                    r.alternation, r.wrapEnergy);
        ASSERT_GE(r.steps, 3);
        ASSERT_GE(r.wrapSteps, 1);
        EXPECT_LT(r.worstWrap, 0.03);
        EXPECT_LT(r.worst, 0.03);
      }
}

// The step after the fast-catch refinement's parts started on the rate the last part left, a
// midpoint rate of another step's length, and read m (the difference) / h off: 3.8% at 30 Hz
// let go from 82 degrees, 9.5% from 80, 7.1% from 70 (docs/swings.md, "The fast catch near a
// peg"). Let go from 30 to 122 degrees either side, 0.2 and 5 kg, 20 and 30 Hz. Higher, the
// rope caught from slack goes slack again within the steps read, where the path tension says
// nothing of the rope (60-500% off, before as now).
TEST(SensorsTest, PegsNearTheAnchorLetGoFromAnyAngleReadTheStepsTension) {
  const std::vector<Stepping> steppings = {{1.0 / 20, 1}, {1.0 / 30, 1}};
  double worst = 0, worstWrap = 0;
  for (int release = 30; release <= 122; release += 4)
    for (const bool mirrored : {false, true})
      for (const double mass : {0.2, 5.0})
        for (const Stepping& s : steppings) {
          const PegVariant p{Vec2(0, -0.26), PulleyDef::Kind::Point, 0, double(release), mirrored};
          SCOPED_TRACE(describe(p) + ", " + label(mass, s));
          const PegReading r = readPeg(p, mass, s);
          ASSERT_GE(r.steps, 3);
          ASSERT_GE(r.wrapSteps, 1);
          // Measured: up to 2.0% (20 Hz), 1.3% at 30 Hz; before, up to 7.1% at
          // 30 Hz and 4.4% at 20 Hz. The midpoint rule's own error over a step, about
          // (omega h)^2 / 12 with omega h up to 0.45 at 20 Hz, is 1.7% of the tension.
          EXPECT_LT(r.worstWrap, 0.03);
          EXPECT_LT(r.worst, 0.03);
          worst = std::max(worst, r.worst);
          worstWrap = std::max(worstWrap, r.worstWrap);
        }
  std::printf("pegs near the anchor, 30-122 degrees: worst %.4f, wrap steps %.4f\n", worst,
              worstWrap);
}

// What gravity and the cables leave on the platform (fx, fy, torque about its centre): each cable
// pulls its end towards the world along its last segment.
Vec3 leftOverLoad(const World& world, const BodyState& platform, double mass, const Vec2& gravity) {
  Vec2 force = mass * gravity;
  double torque = 0;
  for (int c = 0; c < world.cableCount(); ++c) {
    const auto& path = world.cable(c).path();
    const Vec2 end = path.back().world, towards = path[path.size() - 2].world;
    const Vec2 pull = world.cable(c).tension() * (towards - end).normalized();
    force += pull;
    torque += cross(Vec2(end - platform.position), pull);
  }
  return {force.x(), force.y(), torque};
}

// The platform: two rigid cables at its ends, two damped elastic ones inside them.
TEST(SensorsTest, PlatformAtRestReportsNoVelocityAndTensionsThatBalanceTheLoad) {
  SceneDef scene = loadSceneFile(test::sourcePath("tests/data/sensors/platform_rest.json"));
  // From 1 kg: lighter, the elastic cables alone hold it and the rigid ones go slack.
  for (const double mass : {1.0, 4.0, 20.0})
    for (const Stepping& s : kSteppings) {
      SCOPED_TRACE(label(mass, s));
      scene.bodies[0].mass = mass;
      scene.bodies[0].inertia = mass * 0.35 / 4;
      World world(scene);
      const int platform = world.findBody("platform");
      const double load = mass * scene.gravity.norm();
      while (world.time() < 30) world.step(s.dt, s.substeps);
      const BodyState settled = world.body(platform);
      double fastest = 0, spin = 0, unbalanced = 0, untwisted = 0, moved = 0;
      for (int i = 0; i < 60; ++i) {
        world.step(s.dt, s.substeps);
        const BodyState& b = world.body(platform);
        fastest = std::max(fastest, b.velocity.norm());
        spin = std::max(spin, std::abs(b.angularVelocity));
        moved = std::max(moved, (b.position - settled.position).norm());
        const Vec3 left = leftOverLoad(world, b, mass, scene.gravity);
        unbalanced = std::max(unbalanced, left.head<2>().norm());
        untwisted = std::max(untwisted, std::abs(left.z()));
      }
      // Measured: below 4e-12 m/s and 1e-11 of the load in all 21 variants. Before: 2.4-4.9e-9
      // m/s at 20 kg (30, 60, 480 Hz, 60 Hz x 8) and 4 kg at 30 Hz, a sway the solve's restarts
      // kept up (the elastic rows' secant slope, rounding over the squared stretch change, made
      // the midpoint Newton give up at rest: midpoint_solver.cpp, springSecant). Before the
      // end-rate step: 1 cm/s with the pose frozen.
      std::printf("platform %s: %.1e m/s, %.1e rad/s, force off by %.1e of the load\n",
                  label(mass, s).c_str(), fastest, spin, unbalanced / load);
      EXPECT_LT(fastest, 1e-9);
      EXPECT_LT(spin, 1e-9);
      EXPECT_LT(unbalanced, 1e-6 * load);
      EXPECT_LT(untwisted, 1e-6 * load * 1.0);  // about the platform's centre, arms below 1 m
      EXPECT_LT(moved, 1e-6);
      for (int c = 0; c < world.cableCount(); ++c) EXPECT_GT(world.cable(c).tension(), 0) << c;
    }
}

// The same platform with body damping (linear and angular): Box2D damps its velocity after the
// forces, and the step's float arithmetic left a damped body at rest moving at up to 3e-8 m/s
// (30 kg, 30 Hz) where an undamped one reports 1e-12 m/s.
TEST(SensorsTest, DampedPlatformAtRestReportsNoVelocityAndTensionsThatBalanceTheLoad) {
  SceneDef scene = loadSceneFile(test::sourcePath("tests/data/sensors/platform_rest.json"));
  const std::vector<Stepping> steppings = {
      {1.0 / 30, 1}, {1.0 / 60, 1}, {1.0 / 60, 4}, {1.0 / 240, 4}};
  for (const double damping : {0.5, 2.0, 10.0})
    for (const double mass : {4.0, 30.0})
      for (const Stepping& s : steppings) {
        SCOPED_TRACE(label(mass, s) + ", damping " + std::to_string(damping));
        scene.bodies[0].mass = mass;
        scene.bodies[0].inertia = mass * 0.35 / 4;
        scene.bodies[0].linearDamping = scene.bodies[0].angularDamping = damping;
        World world(scene);
        const int platform = world.findBody("platform");
        const double load = mass * scene.gravity.norm();
        while (world.time() < 10) world.step(s.dt, s.substeps);
        double fastest = 0, spin = 0, unbalanced = 0;
        for (int i = 0; i < 30; ++i) {
          world.step(s.dt, s.substeps);
          const BodyState& b = world.body(platform);
          fastest = std::max(fastest, b.velocity.norm());
          spin = std::max(spin, std::abs(b.angularVelocity));
          Vec2 force = mass * scene.gravity;  // the cables pull along their last segments
          for (int c = 0; c < world.cableCount(); ++c) {
            const auto& path = world.cable(c).path();
            const Vec2 end = path.back().world, towards = path[path.size() - 2].world;
            force += world.cable(c).tension() * (towards - end).normalized();
          }
          unbalanced = std::max(unbalanced, force.norm());
        }
        // Measured: below 6e-12 m/s and 1e-10 of the load in all 24; before, 12 of 24 over
        // 1e-9 m/s (up to 3.3e-8) and 2e-7 of the load.
        EXPECT_LT(fastest, 1e-9);
        EXPECT_LT(spin, 1e-9);
        EXPECT_LT(unbalanced, 1e-6 * load);
      }
}

// The most a platform moves, reports and is left unbalanced by over `seconds` (after `settle`).
struct RestReading {
  double fastest = 0, spin = 0, unbalanced = 0, untwisted = 0, moved = 0;
};

RestReading readRest(World& world, double mass, const Vec2& gravity, const Stepping& s,
                     double settle, double seconds) {
  const int platform = world.findBody("platform");
  while (world.time() < settle) world.step(s.dt, s.substeps);
  const BodyState start = world.body(platform);
  RestReading r;
  for (int i = 0; i < std::lround(seconds / s.dt); ++i) {
    world.step(s.dt, s.substeps);
    const BodyState& b = world.body(platform);
    const Vec3 left = leftOverLoad(world, b, mass, gravity);
    r.fastest = std::max(r.fastest, b.velocity.norm());
    r.spin = std::max(r.spin, std::abs(b.angularVelocity));
    r.unbalanced = std::max(r.unbalanced, left.head<2>().norm());
    r.untwisted = std::max(r.untwisted, std::abs(left.z()));
    r.moved = std::max(r.moved, (b.position - start.position).norm());
  }
  return r;
}

const std::vector<Stepping> kRestSteppings = {
    {1.0 / 30, 1}, {1.0 / 60, 1}, {1.0 / 60, 4}, {1.0 / 240, 1}};

// Rigid cables alone, exactly taut from the start (the main solve's bodies, no midpoint rule):
// Box2D's float velocity update, m g and the cables' pull cancelling only to a float's last bit,
// left the platform moving at h / m of it a step, and sinking with it (2.5e-8 m/s on 5 kg at
// 30 Hz). The update is now taken in double (world.cpp, setEndStates).
TEST(SensorsTest, PlatformOnRigidCablesAloneStaysAtRestAndReportsNoVelocity) {
  const SceneDef all =
      loadSceneFile(test::sourcePath("tests/data/sensors/platform_rigid_rest.json"));
  const std::vector<std::vector<std::string>> layouts = {
      {"vertical"}, {"left", "right"}, {"left", "right", "middle"}};
  for (const auto& layout : layouts)
    for (const double mass : {0.5, 5.0, 30.0})
      for (const Stepping& s : kRestSteppings) {
        SCOPED_TRACE(label(mass, s) + ", " + std::to_string(layout.size()) + " cables");
        SceneDef scene = all;
        auto unused = [&](const CableDef& c) {
          return std::find(layout.begin(), layout.end(), c.name) == layout.end();
        };
        scene.cables.erase(std::remove_if(scene.cables.begin(), scene.cables.end(), unused),
                           scene.cables.end());
        scene.bodies[0].mass = mass;
        scene.bodies[0].inertia = mass * 0.35 / 4;
        World world(scene);
        const RestReading r = readRest(world, mass, scene.gravity, s, 2, 1);
        const double load = mass * scene.gravity.norm();
        // Measured: below 4e-11 m/s in all 36; before, 24 of 36 over 1e-9 m/s (up to 3.4e-8).
        EXPECT_LT(r.fastest, 1e-9);
        EXPECT_LT(r.spin, 1e-9);
        EXPECT_LT(r.moved, 1e-9);
        EXPECT_LT(r.unbalanced, 1e-6 * load);
        EXPECT_LT(r.untwisted, 1e-6 * load * 1.0);  // arms below 1 m
      }
}

// A heavily damped platform creeping to rest, one of its three rigid cables gone slack: its last
// creep, less than half a float's spacing at its pose a step, left Box2D's float pose where it was
// while the velocity stayed (8e-7 m/s at 240 Hz, forever). The part of the pose a float drops is
// now kept until it adds up (box2d_bridge.h, placeBody).
TEST(SensorsTest, DampedPlatformCreepingToRestGetsThereAndReportsNoVelocity) {
  SceneDef scene = loadSceneFile(test::sourcePath("tests/data/sensors/platform_damped_creep.json"));
  for (const double mass : {4.0, 30.0})
    for (const Stepping& s : kRestSteppings) {
      SCOPED_TRACE(label(mass, s));
      scene.bodies[0].mass = mass;
      scene.bodies[0].inertia = mass / 12;
      World world(scene);
      const RestReading r = readRest(world, mass, scene.gravity, s, 20, 1);
      const double load = mass * scene.gravity.norm();
      // Measured: below 3e-10 m/s and 2e-10 of the load in all 8; before, all 8 over 1e-9 m/s
      // (7e-8 to 8e-7) and 1e-7 of the load.
      EXPECT_LT(r.fastest, 1e-9);
      EXPECT_LT(r.spin, 1e-9);
      EXPECT_LT(r.unbalanced, 1e-6 * load);
      EXPECT_LT(r.untwisted, 1e-6 * load * 1.0);
    }
}

}  // namespace sensors_test

}  // namespace cablelab
