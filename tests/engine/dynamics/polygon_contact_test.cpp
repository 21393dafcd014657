// Polygons side by side, points pressed into a polygon's hull, spools (issue 36, items 4 and 5;
// docs/cables.md, "Polygons side by side"). The scenes are tests/data/polygons/*.json; each test
// also runs its own variants (masses, step sizes, spool shapes and sides).
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

struct Figures {
  double drift = 0;      ///< largest |E - E0| over the largest kinetic energy
  double stretch = 0;    ///< largest |length - rest length| of a rigid cable (m)
  bool stayed = true;    ///< no polygon pulley left its cable once on it
  std::string warning;   ///< jumpWarning
};

Figures measure(World& world, double seconds, double dt, int substeps) {
  Figures r;
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

/// The first warning of a guard that dropped or released a polygon; "" if there is none.
std::string dropWarning(const World& world) {
  for (const std::string& w : world.warnings())
    if (w.find("left the path") != std::string::npos ||
        w.find("released with a jump") != std::string::npos)
      return w;
  return "";
}

// The scenes of the rows, each at its own settings and at other step sizes: a terminal
// pressed into a polygon's hull (a neighbour's corner, the rope's anchor, the weight wound up to
// its spool, the end anchor the hooked square winds onto) no longer drops the polygon. Before:
// 18, 2, 1 and 6 drops, with length jumps of 0.22, 0.48, 3.66 and 1.13 m.
TEST(PolygonContact, NoGuardDropsAPolygonThatAPointIsPressedInto) {
  for (const char* name : {"two_polygons_spinning", "polygons_in_rope_loops", "servo_spool",
                           "hooked_polygon"})
    for (const int substeps : {1, 2, 4}) {
      SCOPED_TRACE(std::string(name) + " substeps " + std::to_string(substeps));
      World world(fixture(name));
      double lowest = 0;
      for (int second = 0; second < 6; ++second) {
        measure(world, 1, 1.0 / 60, substeps);
        for (int b = 0; b < world.bodyCount(); ++b)
          lowest = std::min(lowest, world.body(b).position.y());
      }
      EXPECT_EQ(dropWarning(world), "");
      // The squares in the rope loops never fall through it: the rope (anchors 1 m up) cannot
      // hang a body lower than 1 m less half its length. Before: they fell to -21 m.
      if (std::string(name) == "polygons_in_rope_loops" && substeps <= 2) {
        EXPECT_GT(lowest, 1 - world.cable(0).restLength() / 2);
      }
    }
}

// Two hexagons on their pivots, close enough that their corners sweep into each other's hulls,
// spinning, one rigid rope over both: their common tangent, on the same and on opposite sides,
// at other spacings, speeds, weights and step sizes: no polygon is dropped for a point inside its
// hull. Before: a guard dropped one 18 times in 5 s in the scene as written (jumps up to 0.22 m).
TEST(PolygonContact, TwoPolygonsCloseTogetherSpinningStayOnTheRope) {
  const SceneDef base = fixture("two_polygons_spinning");
  for (const bool sameSide : {false, true})
    for (const double spacing : {0.45, 0.5, 0.57})
      for (const double spin : {5.0, 20.0})
        for (const int substeps : {1, 4}) {
          SCOPED_TRACE("spacing " + std::to_string(spacing) + " spin " + std::to_string(spin) +
                       " substeps " + std::to_string(substeps) +
                       (sameSide ? " same" : " opposite"));
          SceneDef scene = base;
          scene.bodies[0].position.x() = scene.joints[0].anchor.x() = -spacing / 2;
          scene.bodies[1].position.x() = scene.joints[1].anchor.x() = spacing / 2;
          scene.bodies[0].angularVelocity = spin;
          scene.bodies[1].angularVelocity = -0.7 * spin;
          scene.bodies[2].mass = substeps == 1 ? 1.0 : 4.0;
          if (sameSide) scene.cables[0].pulleys[1].side = scene.cables[0].pulleys[0].side;
          World world(scene);
          measure(world, 5, 1.0 / 60, substeps);
          for (const std::string& w : world.warnings())
            EXPECT_EQ(w.find("left the path"), std::string::npos) << w;
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
      stayed &= !joined || world.cable(0).engaged(0);
      joined |= world.cable(0).engaged(0);
    }
  }
  World world;
  double stretch = 0;
  bool joined = false, stayed = true;  ///< once on the rope, the spool stayed on it
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
    s.wind(sense, 3.0, v.substeps);  // the first turn lays the rope on
    const double turns1 = s.world.body(0).angle / (2 * M_PI) * sense;
    const double y1 = s.world.body(1).position.y();
    s.wind(10 * sense, 3.0, v.substeps);
    const double turns = s.world.body(0).angle / (2 * M_PI) * sense - turns1;
    const double rise = s.world.body(1).position.y() - y1;
    EXPECT_GT(turns, 9.8);
    EXPECT_NEAR(rise / turns, perimeter(spool), 0.01 * perimeter(spool));
    EXPECT_TRUE(s.stayed);  // wound on, the rope never came off
    s.wind(-11 * sense, 3.0, v.substeps);
    EXPECT_NEAR(s.world.body(1).position.y(), y0, 0.02);
    EXPECT_EQ(jumpWarning(s.world), "");
    EXPECT_LT(s.stretch, 1e-3);
  }
}

}  // namespace polygon_contact_test
}  // namespace cablelab
