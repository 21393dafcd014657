// Polygons side by side, points pressed into a polygon's hull, spools and hooks (issue 36, items 4
// and 5; docs/cables.md, "Polygons side by side"). The scenes are tests/data/polygons/*.json; each
// test also runs its own variants (masses, speeds, spacings, step sizes).
//
// A guard that drops a polygon, or any wrap change off the old path, says so in a warning naming
// the length jump (cable.h), so "no such warning" means no wrap change moved a length by 1 mm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace polygon_contact_test {

SceneDef fixture(const std::string& name) {
  return loadSceneFile(test::dataPath("polygons/" + name + ".json"));
}

/// The first warning of a guard that dropped or released a polygon, or of a wrap change that
/// moved a length by more than 1 mm; "" if there is none.
std::string jumpWarning(const World& world) {
  for (const std::string& w : world.warnings())
    if (w.find("left the path") != std::string::npos ||
        w.find("released with a jump") != std::string::npos ||
        w.find("moved the length by") != std::string::npos)
      return w;
  return "";
}

/// Kinetic energy of every body (J).
double kinetic(const World& world) {
  double e = 0;
  for (int b = 0; b < world.bodyCount(); ++b) {
    const BodyState& s = world.body(b);
    if (s.invMass > 0) e += 0.5 * s.velocity.squaredNorm() / s.invMass;
    if (s.invInertia > 0) e += 0.5 * s.angularVelocity * s.angularVelocity / s.invInertia;
  }
  return e;
}

struct Run {
  double drift = 0;      ///< largest |E - E0| over the largest kinetic energy
  double stretch = 0;    ///< largest |length - rest length| of a rigid cable (m)
  bool stayed = true;    ///< no polygon pulley left its cable once on it
  std::string warning;   ///< jumpWarning
};

Run run(World& world, double seconds, double dt, int substeps) {
  Run r;
  const double e0 = world.energy();
  double scale = kinetic(world);
  const int steps = static_cast<int>(std::lround(seconds / dt));
  std::vector<std::vector<char>> joined(world.cableCount());
  for (int c = 0; c < world.cableCount(); ++c) joined[c].assign(world.cable(c).pulleyCount(), 0);
  for (int s = 0; s < steps; ++s) {
    world.step(dt, substeps);
    r.drift = std::max(r.drift, std::abs(world.energy() - e0));
    scale = std::max(scale, kinetic(world));
    for (int c = 0; c < world.cableCount(); ++c) {
      const Cable& cable = world.cable(c);
      if (!cable.elastic()) r.stretch = std::max(r.stretch, std::abs(cable.stretch()));
      for (int j = 0; j < cable.pulleyCount(); ++j)
        if (cable.def().pulleys[j].kind == PulleyDef::Kind::Polygon) {
          r.stayed &= !joined[c][j] || cable.engaged(j);
          joined[c][j] |= cable.engaged(j);
        }
    }
  }
  r.drift /= scale;
  r.warning = jumpWarning(world);
  return r;
}

// Two hexagons 0.57 m apart on their pivots, spinning at 10 and -7 rad/s: their corners sweep
// into each other's hulls every few steps. One rigid rope over both to a hanging weight. Before:
// a guard dropped a polygon with a length jump of 1.05 m and 72% of the energy went.
TEST(PolygonContact, TwoPolygonsCloseTogetherSpinningKeepTheRopeAndTheEnergy) {
  const SceneDef base = fixture("two_polygons_spinning");
  struct Variant {
    WrapSide first, second;
    double spacing, spin, weight;
    int substeps;
  };
  for (const Variant& v : {Variant{WrapSide::Left, WrapSide::Right, 0.57, 10, 1, 1},
                           Variant{WrapSide::Left, WrapSide::Left, 0.57, 10, 1, 1},
                           Variant{WrapSide::Left, WrapSide::Right, 0.5, 20, 0.2, 1},
                           Variant{WrapSide::Left, WrapSide::Left, 0.45, 20, 5, 4},
                           Variant{WrapSide::Right, WrapSide::Left, 0.6, 5, 1, 2}}) {
    SCOPED_TRACE("spacing " + std::to_string(v.spacing) + " spin " + std::to_string(v.spin) +
                 " weight " + std::to_string(v.weight) + " substeps " + std::to_string(v.substeps) +
                 (v.first == v.second ? " same sides" : " opposite sides"));
    SceneDef scene = base;
    scene.bodies[0].position.x() = -v.spacing / 2;
    scene.bodies[1].position.x() = v.spacing / 2;
    scene.joints[0].anchor.x() = -v.spacing / 2;
    scene.joints[1].anchor.x() = v.spacing / 2;
    scene.bodies[0].angularVelocity = v.spin;
    scene.bodies[1].angularVelocity = -0.7 * v.spin;
    scene.bodies[2].mass = v.weight;
    scene.cables[0].pulleys[0].side = v.first;
    scene.cables[0].pulleys[1].side = v.second;
    World world(scene);
    const Run r = run(world, 5, 1.0 / 60, v.substeps);
    EXPECT_EQ(r.warning, "");
    EXPECT_LT(r.stretch, 1e-3);
    EXPECT_LT(r.drift, 0.05);
  }
}

// Two free squares ride in the loops of one rigid rope hung from two anchors and a peg, thrown
// up and sideways so that an anchor or the peg is pressed into a square. Before: the guard dropped
// the square and the bodies fell through the rope.
TEST(PolygonContact, FreePolygonsRidingInRopeLoopsNeverFallThroughIt) {
  const SceneDef base = fixture("polygons_in_rope_loops");
  for (const double throwSpeed : {1.5, 3.0, 5.0})
    for (const double mass : {0.3, 1.0, 4.0})
      for (const int substeps : {1, 4}) {
        SCOPED_TRACE("throw " + std::to_string(throwSpeed) + " mass " + std::to_string(mass) +
                     " substeps " + std::to_string(substeps));
        SceneDef scene = base;
        scene.bodies[0].velocity = throwSpeed * Vec2(-1, 1);
        scene.bodies[1].velocity = throwSpeed * Vec2(1, 0.5);
        scene.bodies[0].mass = mass;
        World world(scene);
        double lowest = 0;
        Run r;
        for (int second = 0; second < 6; ++second) {
          const Run piece = run(world, 1, 1.0 / 60, substeps);
          r.stayed &= piece.stayed;
          r.stretch = std::max(r.stretch, piece.stretch);
          for (int b = 0; b < 2; ++b) lowest = std::min(lowest, world.body(b).position.y());
        }
        EXPECT_EQ(jumpWarning(world), "");
        EXPECT_TRUE(r.stayed);
        EXPECT_LT(r.stretch, 0.01);
        // The rope (2.9 m from anchors 1 m up) cannot hang a body lower than 1 - 2.9 / 2.
        EXPECT_GT(lowest, 1 - 1.45);
      }
}

// The spool's servo is driven by its target (a profile set here, step by step).
struct Spool {
  explicit Spool(const SceneDef& scene) : world(scene) {}
  /// Turns the target by `turns` at `rate` (rad/s) and lets the spool settle (s).
  void wind(double turns, double rate, int substeps) {
    const double dt = 1.0 / 60, start = world.joint(0).servoTarget;
    const double sweep = 2 * M_PI * turns;
    const int steps = static_cast<int>(std::ceil(std::abs(sweep / rate) / dt));
    for (int s = 1; s <= steps + 120; ++s) {
      world.setServoTarget(0, start + sweep * std::min(1.0, double(s) / steps));
      world.step(dt, substeps);
      stretch = std::max(stretch, std::abs(world.cable(0).stretch()));
      stayed &= world.cable(0).engaged(0);
    }
  }
  World world;
  double stretch = 0;
  bool stayed = true;
};

double perimeter(const std::vector<Vec2>& polygon) {
  double total = 0;
  for (size_t i = 0; i < polygon.size(); ++i)
    total += (polygon[(i + 1) % polygon.size()] - polygon[i]).norm();
  return total;
}

// A servo turns a polygon spool on its axle; the rope from a hanging weight is tied to a corner
// of the spool and winds round it: 11 turns up and 11 back down. Each turn lifts the weight by
// one perimeter. Before: the rope's wrap was lost (a length jump of 3.3 m) within a few turns.
TEST(PolygonContact, AServoSpoolWindsAndUnwindsARopeForElevenTurns) {
  const SceneDef base = fixture("servo_spool");
  struct Variant {
    int corners;
    WrapSide side;
    double weight;
    int substeps;
  };
  for (const Variant& v : {Variant{6, WrapSide::Right, 1, 1}, Variant{6, WrapSide::Left, 1, 1},
                           Variant{4, WrapSide::Right, 3, 1}, Variant{8, WrapSide::Left, 0.3, 4},
                           Variant{3, WrapSide::Right, 1, 2}}) {
    SCOPED_TRACE(std::to_string(v.corners) + " corners, weight " + std::to_string(v.weight) +
                 ", substeps " + std::to_string(v.substeps) +
                 (v.side == WrapSide::Left ? ", left" : ", right"));
    SceneDef scene = base;
    std::vector<Vec2> spool;
    for (int k = 0; k < v.corners; ++k)
      spool.push_back(0.2 * Vec2(std::cos(2 * M_PI * k / v.corners),
                                 std::sin(2 * M_PI * k / v.corners)));
    scene.bodies[0].shapes[0].vertices = spool;
    scene.bodies[1].mass = v.weight;
    scene.bodies[1].position = Vec2(spool[0].x(), -12);  // 15 m of rope
    scene.cables[0].end.point = spool[0];
    scene.cables[0].pulleys[0].side = v.side;
    scene.joints[0].servo.speed = 0;
    const double sense = v.side == WrapSide::Right ? 1 : -1;  // the turn that winds the rope
    Spool s(scene);
    const double y0 = s.world.body(1).position.y();
    s.wind(11 * sense, 3.0, v.substeps);
    const double turns = s.world.body(0).angle / (2 * M_PI) * sense;
    const double rise = s.world.body(1).position.y() - y0;
    EXPECT_GT(turns, 10.5);
    EXPECT_NEAR(rise / turns, perimeter(spool), 0.01 * perimeter(spool));
    s.wind(-11 * sense, 3.0, v.substeps);
    EXPECT_NEAR(s.world.body(1).position.y(), y0, 0.02);
    EXPECT_EQ(jumpWarning(s.world), "");
    EXPECT_TRUE(s.stayed);
    EXPECT_LT(s.stretch, 1e-3);
  }
}

// The same spool with 4 m of rope keeps winding after the weight reaches it: the spool's corners
// sweep into the weight's point. Before: the guard dropped the spool with a length jump of the
// whole wound rope (3.65 m here) and the weight fell.
TEST(PolygonContact, AWeightWoundUpToTheSpoolStaysOnItsRope) {
  for (const double weight : {0.3, 1.0, 3.0})
    for (const int substeps : {1, 4}) {
      SCOPED_TRACE("weight " + std::to_string(weight) + " substeps " + std::to_string(substeps));
      SceneDef scene = fixture("servo_spool");
      scene.bodies[1].mass = weight;
      scene.joints[0].servo.speed = 0;
      Spool s(scene);
      s.wind(5, 2.0, substeps);
      EXPECT_EQ(jumpWarning(s.world), "");
      EXPECT_TRUE(s.stayed);
      EXPECT_LT(s.stretch, 0.01);
      EXPECT_GT(s.world.body(1).position.y(), 2.5);  // at the spool (3 m up), not fallen
    }
}

// A square whirled on a stiff tether round the rope's end anchor hooks the rope and winds it on,
// then unwinds; nothing is damped. Before: the end anchor entered the square's hull while hooked,
// the guard dropped the square and 96% of the energy drifted away (99.6% in the scene).
TEST(PolygonContact, APolygonHookedBeyondTheEndAnchorKeepsItsEnergy) {
  const SceneDef base = fixture("hooked_polygon");
  for (const double speed : {6.0, 12.0, 18.0})
    for (const double k : {50.0, 500.0})
      for (const int substeps : {1, 4}) {
        SCOPED_TRACE("speed " + std::to_string(speed) + " k " + std::to_string(k) +
                     " substeps " + std::to_string(substeps));
        SceneDef scene = base;
        scene.bodies[0].velocity *= speed / scene.bodies[0].velocity.norm();
        scene.cables[1].stiffness = k;
        World world(scene);
        const Run r = run(world, 5, 1.0 / 60, substeps);
        EXPECT_EQ(r.warning, "");
        EXPECT_TRUE(r.stayed);
        EXPECT_LT(r.drift, 0.02);
      }
}

}  // namespace polygon_contact_test
}  // namespace cablelab
