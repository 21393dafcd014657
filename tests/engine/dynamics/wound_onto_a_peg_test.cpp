// A bob whose rope winds it up onto a polygon pulley held still (a peg on a static body or on the
// world) stops at the peg and rides round it, sensor or not, as a weight wound up to its spool
// does (engine/dynamics/hull_contacts.h; docs/cables.md, "Points inside a hull").
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "engine/dynamics/hull_contacts.h"
#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace wound_onto_a_peg_test {

constexpr double kHalf = 0.05;  // the square peg's half size (m)
const Vec2 kPegAt(-3.5, 0.2);   // 0.8 m below the rope's anchor
const Vec2 kAnchorAt(-3.5, 1.0);

struct Peg {
  bool pegSensor = true, bobSensor = true;
  bool onTheWorld = false;  // the polygon pulley on the world, not on a static body
  double mass = 0.6;
  double stiffness = 0;       // N/m, 0: rigid
  bool kinematic = false;     // the peg's body kinematic, moving at these (not static)
  double spin = 0;            // rad/s
  Vec2 drift = Vec2::Zero();  // m/s
};

// A bob on a 0.9 m rope from kAnchorAt, let go level with the anchor and 0.9 m to the side: the
// rope catches the 10 cm square peg below the anchor and winds the bob up onto it.
SceneDef pegPendulum(const Peg& p) {
  SceneDef s;
  BodyDef peg;
  peg.name = "peg";
  peg.type = p.kinematic ? BodyType::Kinematic : BodyType::Static;
  peg.position = kPegAt;
  peg.angularVelocity = p.spin;
  peg.velocity = p.drift;
  peg.shapes = {test::sensorBox(kHalf, kHalf)};
  peg.shapes[0].sensor = p.pegSensor;
  BodyDef bob;
  bob.name = "bob";
  bob.position = Vec2(-2.6, 0.9);
  bob.mass = p.mass;
  bob.fixedRotation = true;
  bob.shapes = {test::sensorDisc(0.03)};
  bob.shapes[0].sensor = p.bobSensor;
  s.bodies = {peg, bob};
  CableDef rope;
  rope.name = "pend";
  rope.start.point = kAnchorAt;
  rope.end.body = "bob";
  rope.stiffness = p.stiffness;
  PulleyDef square;
  square.kind = PulleyDef::Kind::Polygon;
  square.side = WrapSide::Auto;
  if (p.onTheWorld) {
    square.body = "world";
    for (const Vec2& v : peg.shapes[0].vertices) square.vertices.push_back(kPegAt + v);
    s.bodies[0].shapes[0].sensor = true;  // the body only marks the place
  } else {
    square.body = "peg";
  }
  rope.pulleys = {square};
  s.cables = {rope};
  return s;
}

struct Swing {
  double deepest = -1;  // the bob's anchor furthest into the peg's square (m, > 0: inside)
  double rise = -1e9;   // the energy's largest rise above its start (J)
  int jumps = 0;        // warnings of a length jump above 1 mm or a dropped pulley
  int warnings = 0;
};

Swing swing(const Peg& p, double hz, int substeps, double seconds) {
  World world(pegPendulum(p));
  const double e0 = world.energy();
  Swing r;
  for (int i = 0; i < std::lround(seconds * hz); ++i) {
    world.step(1 / hz, substeps);
    // In the peg's frame (it may turn and move).
    const BodyState& peg = world.body(0);
    const Vec2 d = rotate(world.body(1).position - peg.position, -peg.angle);
    r.deepest = std::max(r.deepest, kHalf - std::max(std::abs(d.x()), std::abs(d.y())));
    r.rise = std::max(r.rise, world.energy() - e0);
  }
  for (const std::string& w : world.warnings())
    r.jumps += w.find("moved the length") != std::string::npos ||
               w.find("left the path") != std::string::npos;
  r.warnings = static_cast<int>(world.warnings().size());
  return r;
}

// The peg held still touches the bob's anchor (whatever the shapes' sensor flags), in the bob's
// frame, on a static body or on the world.
TEST(WoundOntoAPeg, APegHeldStillTouchesTheBobOnItsRope) {
  for (const bool onTheWorld : {false, true}) {
    Peg p;
    p.onTheWorld = onTheWorld;
    const std::vector<HullContact> pairs = hullContacts(pegPendulum(p));
    ASSERT_EQ(pairs.size(), 1u) << onTheWorld;
    EXPECT_EQ(pairs[0].body, onTheWorld ? -1 : 0);
    EXPECT_EQ(pairs[0].otherBody, 1);
    EXPECT_EQ(pairs[0].point, Vec2::Zero());
    EXPECT_EQ(pairs[0].polygon.size(), 4u);
    EXPECT_FALSE(pairs[0].bounces);  // Box2D's knock, inelastic
  }
}

// Before, a sensor peg (or bob) let the bob wind into the square: 43-47 mm deep, 14-139 warnings
// in 10 s ("pulley 0 left the path: a neighbouring point lies inside its hull", wrap changes
// moving the length 3-6 cm). Now Box2D's contact stops the bob 8-12 mm outside: no warning, no
// jump, the energy never above its start (an elastic rope's within 5e-6 J). Variants: the sensor on
// the peg, the bob, both; the peg on the world; 0.1 to 5 kg; 30 to 240 Hz at 1 and 4 sub-steps; an
// elastic rope.
TEST(WoundOntoAPeg, ABobWoundOntoASensorPegStopsOutsideItWithoutAJump) {
  struct Flags {
    bool peg, bob, world;
  };
  for (const Flags f : {Flags{true, false, false}, Flags{false, true, false},
                        Flags{true, true, false}, Flags{true, true, true}})
    for (const double mass : {0.1, 0.6, 5.0})
      for (const double hz : {30.0, 60.0, 240.0})
        for (const int substeps : {1, 4})
          for (const double stiffness : {0.0, 2e4}) {
            if (stiffness > 0 && (mass != 0.6 || hz == 240)) continue;
            SCOPED_TRACE(std::string("sensor peg ") + (f.peg ? "yes" : "no") + ", sensor bob " +
                         (f.bob ? "yes" : "no") + (f.world ? ", on the world, " : ", ") +
                         std::to_string(mass) + " kg, " + std::to_string(hz) + " Hz x" +
                         std::to_string(substeps) + ", k " + std::to_string(stiffness));
            Peg p;
            p.pegSensor = f.peg;
            p.bobSensor = f.bob;
            p.onTheWorld = f.world;
            p.mass = mass;
            p.stiffness = stiffness;
            const Swing r = swing(p, hz, substeps, 15);
            EXPECT_LT(r.deepest, -2e-3);  // Box2D's contact skin keeps it about 1 cm out
            EXPECT_EQ(r.jumps, 0);
            // Within the elastic rope's integration (up to 5e-6 J here) of the swing's scale.
            EXPECT_LE(r.rise, 1e-5 * mass * 9.81 * 0.9);
            // 30 Hz at 1 sub-step: the first catch may run the rigid rope long, and says so.
            if (hz > 30 || substeps > 1) {
              EXPECT_EQ(r.warnings, 0);
            }
          }
}

// The rope over a fixed square with friction: the light weight, its anchor on the line of the
// square's right face (the rope hugs it), is hauled up that face past its lower corner to the
// upper one, where its rope leaves and the rope's floor stops it (anchor 1 cm below it), as before
// the peg touched points on moving bodies; touching the lower corner stopped it there with a 2.7 cm
// over-length warning. Variants: 1, 2 and 4 sub-steps, 30 to 240 Hz, a heavier pull.
TEST(WoundOntoAPeg, AWeightHauledUpTheFaceItsRopeHugsPassesItsCorners) {
  const SceneDef base =
      loadSceneFile(test::dataPath("polygon_friction/good_polygon_friction_scene.json"));
  for (const double heavy : {3.0, 8.0})
    for (const double hz : {30.0, 60.0, 240.0})
      for (const int substeps : {1, 2, 4}) {
        SCOPED_TRACE(std::to_string(heavy) + " kg, " + std::to_string(hz) + " Hz x" +
                     std::to_string(substeps));
        SceneDef scene = base;
        scene.bodies[0].mass = heavy;
        World world(scene);
        for (int i = 0; i < std::lround(3 * hz); ++i) world.step(1 / hz, substeps);
        EXPECT_NEAR(world.body(1).position.y() + 0.1, 3.24, 0.005);  // the anchor at the corner
        for (const std::string& w : world.warnings()) ADD_FAILURE() << w;
      }
}

// The sensor peg on a kinematic body turning (-3 to 8 rad/s) and moving (up to 0.11 m/s), the bob
// wound onto it at 60 and 240 Hz in 1 and 4 sub-steps: it stops 5-14 mm outside the square, the
// square never leaves the rope nor jumps its length. (A kinematic peg does work on the rope: no
// energy bound; where it hauls the rigid rope it may say so.)
TEST(WoundOntoAPeg, ABobWoundOntoATurningOrMovingKinematicPegStaysOutsideWithoutAJump) {
  for (const double spin : {-3.0, 1.0, 8.0})
    for (const Vec2& drift : {Vec2(0, 0), Vec2(0.1, 0), Vec2(-0.1, 0.05)})
      for (const double hz : {60.0, 240.0})
        for (const int substeps : {1, 4}) {
          SCOPED_TRACE("spin " + std::to_string(spin) + " rad/s, drift " +
                       std::to_string(drift.x()) + ", " + std::to_string(drift.y()) + " m/s, " +
                       std::to_string(hz) + " Hz x" + std::to_string(substeps));
          Peg p;
          p.kinematic = true;
          p.spin = spin;
          p.drift = drift;
          const Swing r = swing(p, hz, substeps, 5);
          EXPECT_LT(r.deepest, -2e-3);
          EXPECT_EQ(r.jumps, 0);
        }
}

}  // namespace wound_onto_a_peg_test
}  // namespace cablelab
