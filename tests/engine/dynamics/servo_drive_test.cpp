// Servos implicit in the step (engine/dynamics/servo_drive.cpp, docs/servos.md): stable at any
// gain and step, never above max_force, the right holding torque, and a stall that says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace servo_drive_test {

constexpr double kG = 9.81;
constexpr double kSettled = 1e-3;  // rad: the goal's settling band

// A rod of `mass` and `length` pinned at one end to the world at the origin, lying along +x,
// its servo driving the pin's angle.
SceneDef rodScene(double mass, double length, const ServoDef& servo, bool gravity) {
  SceneDef s;
  s.gravity = gravity ? Vec2(0, -kG) : Vec2::Zero();
  BodyDef rod;
  rod.name = "rod";
  rod.position = Vec2(0.5 * length, 0);
  rod.mass = mass;
  rod.inertia = mass * length * length / 12;
  ShapeDef dot;
  dot.radius = 0.05;
  dot.sensor = true;
  rod.shapes = {dot};
  s.bodies = {rod};
  JointDef pin;
  pin.name = "pin";
  pin.bodyB = "rod";
  pin.servo = servo;
  pin.servo.enabled = true;
  s.joints = {pin};
  return s;
}

ServoDef gains(double kp, double kd, double target = 1.0, double maxForce = 1e4) {
  ServoDef s;
  s.kp = kp;
  s.kd = kd;
  s.target = target;
  s.maxForce = maxForce;
  return s;
}

// How often the continuous PD on inertia I crosses its target going from e0 to `band`: the
// number of half periods in which its envelope exp(-zeta omega t) falls from e0 to band (none
// when it does not oscillate).
int continuousCrossings(double kp, double kd, double inertia, double e0, double band) {
  const double omega = std::sqrt(kp / inertia), zeta = kd / (2 * std::sqrt(kp * inertia));
  if (zeta >= 1) return 0;
  const double halfPeriod = M_PI / (omega * std::sqrt(1 - zeta * zeta));
  return static_cast<int>(std::ceil(std::log(e0 / band) / (zeta * omega * halfPeriod)));
}

struct RodRun {
  int crossings = 0;        // sign changes of the error while outside the band
  double settledAt = -1;    // s: from when the error stays inside the band (-1: never)
  double largestForce = 0;  // N m
  int alternations = 0;     // steps whose error changed sign twice in a row outside the band
};

RodRun runRod(double mass, double length, const ServoDef& servo, double dt, double seconds) {
  World w(rodScene(mass, length, servo, false));
  RodRun run;
  double previous = servo.target, before = servo.target;
  const int steps = static_cast<int>(std::lround(seconds / dt));
  for (int i = 0; i < steps; ++i) {
    w.step(dt);
    const JointState pin = w.joint(0);
    const double e = servo.target - pin.value;
    run.largestForce = std::max(run.largestForce, std::abs(pin.force));
    const bool outside = std::abs(e) > kSettled;
    if (outside && e * previous < 0) ++run.crossings;
    if (outside && e * previous < 0 && previous * before < 0) ++run.alternations;
    if (outside)
      run.settledAt = -1;
    else if (run.settledAt < 0)
      run.settledAt = w.time();
    before = previous;
    previous = e;
  }
  return run;
}

TEST(ServoDrive, TheDefaultServoOnARodConvergesWithoutAlternating) {
  // The user's case: 1 kg, 1 m rod, default gains (kp 500, kd 44.72), target 1 rad, 60 Hz. The
  // PD on the start-of-step state alternated 0.05 / 0.94 rad every step and never settled.
  const RodRun run = runRod(1, 1, gains(500, 44.72), 1.0 / 60, 3);
  EXPECT_EQ(run.crossings, 0);  // overdamped on I = 1/3 kg m^2: it never crosses its target
  EXPECT_GT(run.settledAt, 0);
  EXPECT_LT(run.settledAt, 2.0);
}

TEST(ServoDrive, ARodConvergesAtAnyGainAndStepAsADampedSystemDoes) {
  // kp from 50 to 1e6 at 30, 60 and 240 Hz; kd critical for the rod (I = m l^2 / 3) and, from
  // kp 500, the default 44.72 too (underdamped up there: it may cross its target as often as the
  // continuous system would). Never alternating step by step, within 1e-3 rad in 2 s, and the
  // force never above max_force (1e4 N m: kp 1e6 asks 1e6 N m at the start).
  for (const double mass : {1.0, 0.05, 20.0})
    for (const double hz : {30.0, 60.0, 240.0})
      for (const double kp : {50.0, 500.0, 5e3, 5e4, 1e6}) {
        const double inertia = mass / 3;
        for (const double kd : {2 * std::sqrt(kp * inertia), 44.72}) {
          if (kd == 44.72 && (kp < 500 || mass != 1.0)) continue;
          SCOPED_TRACE("m " + std::to_string(mass) + " kp " + std::to_string(kp) + " kd " +
                       std::to_string(kd) + " at " + std::to_string(hz) + " Hz");
          const RodRun run = runRod(mass, 1, gains(kp, kd), 1 / hz, 2.5);
          EXPECT_EQ(run.alternations, 0);
          EXPECT_LE(run.crossings, std::max(1, continuousCrossings(kp, kd, inertia, 1, kSettled)));
          // Settling within 2 s where the continuous system does (natural frequency 10 rad/s
          // or more; kp 50 on the 20 kg rod takes 3.4 s at critical damping).
          if (kp / inertia >= 100) {
            EXPECT_GT(run.settledAt, 0);
            EXPECT_LT(run.settledAt, 2.0);
          }
          EXPECT_LE(run.largestForce, 1e4);
        }
      }
}

TEST(ServoDrive, AServosEnergyNeverRisesAtAnyGainStepOrSubSteps) {
  // A PD servo is a spring and a damper: with no other load, E = I w^2 / 2 + kp e^2 / 2 (I about
  // the pin) never rises from one step to the next, at any damping ratio (0.2 swings), any gain
  // and any number of sub-steps; an explicit or late PD gains energy at large kp h^2 / I.
  for (const double mass : {0.05, 20.0})
    for (const double kp : {500.0, 1e5, 1e8})
      for (const double zeta : {0.2, 1.0})
        for (const double hz : {30.0, 240.0})
          for (const int substeps : {1, 2, 4}) {
            const double inertia = mass / 3, kd = 2 * zeta * std::sqrt(kp * inertia);
            SCOPED_TRACE("m " + std::to_string(mass) + " kp " + std::to_string(kp) + " zeta " +
                         std::to_string(zeta) + " at " + std::to_string(hz) + " Hz x " +
                         std::to_string(substeps));
            World w(rodScene(mass, 1, gains(kp, kd, 1.0, 1e12), false));
            const auto energy = [&] {
              const JointState pin = w.joint(0);
              return 0.5 * inertia * pin.speed * pin.speed +
                     0.5 * kp * (1 - pin.value) * (1 - pin.value);
            };
            double before = energy();
            int rises = 0;
            for (int i = 0; i < 30; ++i) {
              w.step(1 / hz, substeps);
              const double now = energy();
              if (now > before * (1 + 1e-6) + 1e-12 * kp) ++rises;
              before = now;
            }
            EXPECT_EQ(rises, 0);
          }
}

TEST(ServoDrive, AServoHoldingARodLevelAgainstGravityReportsItsWeightTimesHalfItsLength) {
  // The rod level (target 0) under gravity: the servo holds m g l/2 cos(angle) at rest.
  test::Random rng(36);
  for (int trial = 0; trial < 8; ++trial) {
    const double mass = rng.uniform(0.2, 5), length = rng.uniform(0.3, 2);
    const double kp = std::pow(10, rng.uniform(2.5, 5)), hz = trial % 2 ? 60 : 240;
    const double inertia = mass * length * length / 3;
    World w(rodScene(mass, length, gains(kp, 2 * std::sqrt(kp * inertia), 0), true));
    while (w.time() < 4) w.step(1 / hz);
    const JointState pin = w.joint(0);
    const double expected = mass * kG * length / 2 * std::cos(pin.value);
    SCOPED_TRACE("trial " + std::to_string(trial));
    EXPECT_NEAR(pin.force, expected, 1e-3 * expected);
    EXPECT_NEAR(pin.force, kp * -pin.value, 1e-3 * expected);  // the PD law at rest
    EXPECT_TRUE(w.warnings().empty());
  }
}

TEST(ServoDrive, AServoTooWeakToLiftTheRodStallsAtItsMaxForceAndSaysSo) {
  // The rod hangs from its pin and the servo, at half the level rod's weight torque, is asked to
  // lift it level: it rises to where max_force balances the weight, m g l/2 sin(angle) =
  // max_force (30 degrees; Box2D's damping settles the swing), and stays there pushing
  // with max_force: a stall, said once, naming the joint.
  for (const double hz : {30.0, 60.0, 240.0}) {
    const double mass = 1, length = 1, weakest = 0.5 * mass * kG * length / 2;
    SceneDef s = rodScene(mass, length, gains(500, 44.72, M_PI / 2, weakest), true);
    s.bodies[0].position = Vec2(0, -length / 2);
    s.bodies[0].angle = -M_PI / 2;
    s.bodies[0].angularDamping = 3;
    s.bodies[0].linearDamping = 3;
    World w(s);
    double largest = 0;
    while (w.time() < 10) {
      w.step(1 / hz);
      largest = std::max(largest, std::abs(w.joint(0).force));
    }
    SCOPED_TRACE(std::to_string(hz) + " Hz");
    EXPECT_LE(largest, weakest);
    EXPECT_NEAR(w.joint(0).force, weakest, 1e-9);
    EXPECT_NEAR(mass * kG * length / 2 * std::sin(w.joint(0).value), weakest, 1e-3 * weakest);
    ASSERT_EQ(w.warnings().size(), 1u);
    EXPECT_NE(w.warnings()[0].find("joint 'pin'"), std::string::npos) << w.warnings()[0];
    EXPECT_NE(w.warnings()[0].find("stalled"), std::string::npos) << w.warnings()[0];
  }
}

TEST(ServoDrive, AServoBrakingAtItsMaxForceIsNoStall) {
  // A servo too weak for its gains (max_force 2 N m on the free 1 kg, 1 m rod, kp 500): it
  // speeds the rod up at max_force, then brakes it at -max_force while the rod still turns
  // forwards, overshoots and turns back. It moves its load all along: no stall, no warning (a
  // stall once said so whenever the joint moved against the force, braking included).
  for (const double hz : {30.0, 60.0, 240.0}) {
    World w(rodScene(1, 1, gains(500, 44.72, 1.0, 2.0), false));
    bool braked = false;
    while (w.time() < 4) {
      w.step(1 / hz);
      const JointState pin = w.joint(0);
      braked |= pin.force <= -2.0 * (1 - 1e-9) && pin.speed > 0.1;
    }
    SCOPED_TRACE(std::to_string(hz) + " Hz");
    EXPECT_TRUE(braked);
    EXPECT_NEAR(w.joint(0).value, 1.0, 1e-3);
    EXPECT_TRUE(w.warnings().empty()) << w.warnings()[0];
  }
}

TEST(ServoDrive, AMotorAtItsSpeedTurnsTheRodAtThatRate) {
  // A servo with a speed (a motor): the rod turns at it, the force only what the damping needs
  // (none: no load), at any step.
  for (const double hz : {30.0, 60.0, 240.0}) {
    ServoDef motor = gains(2000, 100, 0);
    motor.speed = 3;
    World w(rodScene(2, 1, motor, false));
    while (w.time() < 2) w.step(1 / hz);
    EXPECT_NEAR(w.joint(0).speed, 3, 1e-2) << hz;
    EXPECT_NEAR(w.joint(0).value, w.joint(0).servoTarget, 1e-3) << hz;
    EXPECT_NEAR(w.joint(0).force, 0, 1e-2) << hz;
  }
}

TEST(ServoDrive, APrismaticServoHoldsAWeightWithItsWeight) {
  // A vertical slide holding a mass: the force is m g, along the axis, at any gain and step.
  for (const double kp : {100.0, 1e4, 1e6})
    for (const double hz : {30.0, 240.0}) {
      SceneDef s;
      s.gravity = Vec2(0, -kG);
      BodyDef car;
      car.name = "car";
      car.mass = 3;
      ShapeDef dot;
      dot.sensor = true;
      car.shapes = {dot};
      s.bodies = {car};
      JointDef slide;
      slide.kind = JointDef::Kind::Prismatic;
      slide.name = "slide";
      slide.bodyB = "car";
      slide.axis = Vec2(0, 1);
      slide.servo = gains(kp, 2 * std::sqrt(kp * 3), 0.5);
      slide.servo.enabled = true;
      s.joints = {slide};
      World w(s);
      double previous = 0.5, crossings = 0;
      while (w.time() < 3) {
        w.step(1 / hz);
        const double e = 0.5 - w.joint(0).value;
        crossings += std::abs(e) > kSettled && e * previous < 0;
        previous = e;
      }
      SCOPED_TRACE("kp " + std::to_string(kp) + " at " + std::to_string(hz) + " Hz");
      EXPECT_NEAR(w.joint(0).force, 3 * kG, 1e-3 * 3 * kG);
      EXPECT_NEAR(w.joint(0).value, 0.5 - 3 * kG / kp, 1e-4);
      EXPECT_LE(crossings, 1);
    }
}

TEST(ServoDrive, TwoServosOnAnArmSettleTogetherWithoutAlternating) {
  // Two 1 m links in a chain (world - shoulder - upper - elbow - fore), a servo on each joint:
  // each servo's force moves the other joint too, so the forces solve together (K couples them).
  // Gains of 500 and 1e5 per kg of link at 30 to 240 Hz, light and heavy links: both joints reach
  // their targets within 1e-3 rad in 2 s with no step-by-step alternation, never above max_force.
  for (const double mass : {0.1, 1.0, 10.0})
    for (const double kpPerKg : {500.0, 1e5})
      for (const double hz : {30.0, 60.0, 240.0}) {
        const double kp = kpPerKg * mass;
        SceneDef s;
        s.gravity = Vec2::Zero();
        for (int i = 0; i < 2; ++i) {
          BodyDef link;
          link.name = i == 0 ? "upper" : "fore";
          link.position = Vec2(0.5 + i, 0);
          link.mass = mass;
          link.inertia = mass / 12;
          ShapeDef dot;
          dot.sensor = true;
          link.shapes = {dot};
          s.bodies.push_back(link);
          JointDef joint;
          joint.name = i == 0 ? "shoulder" : "elbow";
          joint.bodyA = i == 0 ? "world" : "upper";
          joint.bodyB = link.name;
          joint.anchor = Vec2(i, 0);
          // Critically damped on the whole arm's inertia about the shoulder (8/3 m l^2).
          joint.servo = gains(kp, 2 * std::sqrt(kp * mass * 8 / 3), i == 0 ? 0.5 : -0.7, 1e6);
          joint.servo.enabled = true;
          s.joints.push_back(joint);
        }
        World w(s);
        std::array<double, 2> previous{0.5, -0.7}, before = previous;
        int alternations = 0;
        double largest = 0, settledAt = -1;
        while (w.time() < 2.5) {
          w.step(1 / hz);
          bool outside = false;
          for (int j = 0; j < 2; ++j) {
            const double e = w.joint(j).servoTarget - w.joint(j).value;
            const bool far = std::abs(e) > kSettled;
            outside |= far;
            alternations += far && e * previous[j] < 0 && previous[j] * before[j] < 0;
            largest = std::max(largest, std::abs(w.joint(j).force));
            before[j] = previous[j];
            previous[j] = e;
          }
          if (outside)
            settledAt = -1;
          else if (settledAt < 0)
            settledAt = w.time();
        }
        SCOPED_TRACE("m " + std::to_string(mass) + " kp " + std::to_string(kp) + " at " +
                     std::to_string(hz) + " Hz");
        EXPECT_EQ(alternations, 0);
        EXPECT_GT(settledAt, 0);
        EXPECT_LT(settledAt, 2.0);
        EXPECT_LE(largest, 1e6);
      }
}

// The winch scene with a light drum and a stiff servo.
World lightWinch(double kp, double kd, double maxForce, double omega, double drumInertia,
                 double weight = 1.0) {
  SceneDef s = makeScene("winch", {{"omega", omega}, {"mass", weight}});
  s.bodies[0].inertia = drumInertia;
  s.joints[0].servo.kp = kp;
  s.joints[0].servo.kd = kd;
  s.joints[0].servo.maxForce = maxForce;
  return World(s, "winch");
}

TEST(ServoDrive, AStiffServoOnALightDrumLiftsTheWeightWithoutThrowingIt) {
  // kp 2000 on a drum of 0.01 kg m^2 (the scene's flywheel taken off): the PD on the
  // start-of-step state pulled 1.8e5 N and threw the weight above the drum. Now the weight rises
  // at r omega, the tension stays near its weight once the start's jerk is over (a stiff servo
  // takes the weight from rest to r omega in a few ms: m (g + a), 20-70 N) until the weight
  // reaches the drum, never more than max_force / r after it, and the rope's end never goes over
  // the drum's top.
  const double r = 0.1;
  for (const double inertia : {0.01, 0.001})
    for (const double kd : {20.0, 200.0})
      for (const double hz : {60.0, 240.0}) {
        World w = lightWinch(2000, kd, 1e3, 2.0, inertia);
        const int drum = w.findBody("drum"), weight = w.findBody("weight");
        const double m = 1.0 / w.body(weight).invMass;
        double highest = -1e9, lifting = 0, largest = 0;
        while (w.time() < 25) {
          w.step(1 / hz);
          const BodyState& b = w.body(weight);
          const Vec2 end = b.position + rotate(Vec2(0, 0.1), b.angle);  // the rope's end
          highest = std::max(highest, end.y() - w.body(drum).position.y());
          const double tension = w.cable(0).tension();
          largest = std::max(largest, tension);
          if (w.time() > 1 && end.y() < w.body(drum).position.y() - 1)
            lifting = std::max(lifting, tension);
        }
        SCOPED_TRACE("I " + std::to_string(inertia) + " kd " + std::to_string(kd) + " at " +
                     std::to_string(hz) + " Hz");
        EXPECT_LT(highest, r + 1e-3);  // never over the drum's top
        EXPECT_LT(lifting, 1.5 * m * kG);
        EXPECT_LE(largest, 1.01 * 1e3 / r);
      }
}

TEST(ServoDrive, AWinchThatWindsOnAfterItsWeightReachesTheDrumStallsAtMaxForce) {
  // Winding on with the weight at the drum: the servo's target runs on, its force reaches
  // max_force and stays there; the tension then is max_force / r (it grew without bound, 5.7 kN
  // in 5 s), and a warning names the joint.
  const double r = 0.1;
  for (const double maxForce : {3.0, 20.0})
    for (const double hz : {60.0, 240.0}) {
      World w = lightWinch(500, 44.72, maxForce, 5.0, 0.05);
      double worst = 0, stalledAt = -1;
      while (w.time() < 20) {
        w.step(1 / hz);
        if (stalledAt < 0 && !w.warnings().empty() &&
            w.warnings().back().find("stalled") != std::string::npos)
          stalledAt = w.time();
        if (stalledAt >= 0 && w.time() > stalledAt + 0.5)
          worst = std::max(worst, w.cable(0).tension());
        ASSERT_LE(std::abs(w.joint(0).force), maxForce);
      }
      SCOPED_TRACE("max_force " + std::to_string(maxForce) + " at " + std::to_string(hz) + " Hz");
      // The weight's arrival at the drum is said first, then the stall.
      ASSERT_EQ(w.warnings().size(), 2u);
      EXPECT_NE(w.warnings()[0].find("reached the drum"), std::string::npos) << w.warnings()[0];
      EXPECT_NE(w.warnings()[1].find("joint 'axle'"), std::string::npos) << w.warnings()[1];
      EXPECT_NEAR(w.joint(0).force, maxForce, 1e-9);
      EXPECT_LE(worst, 1.01 * maxForce / r);
      EXPECT_NEAR(w.cable(0).tension(), maxForce / r, 0.01 * maxForce / r);
    }
}

TEST(ServoDrive, AWinchRopeGoingSlackLeavesTheLightDrumAlone) {
  // A 5 cm drum of 1.25e-4 kg m^2 (0.1 kg) lifting 5 and 20 kg with a stiff servo (kp 3e4 at
  // the default kd, or kp 2000 critical on drum and weight) at 30 and 60 Hz. The start's jerk
  // throws the weight up faster than the rope winds and the rope goes slack for a step: the
  // servo's force, sized for the weight on the rope, spun the bare drum to Box2D's turn limit and
  // threw the weight at 400 to 1200 times the rope's speed (5 of these 16), with up to 4000 m g of
  // tension. Now the servo sees a rope that would go slack as none: the weight never outruns the
  // rope more than the jerk does (5x), the tension stays under 10 m g.
  const double r = 0.05, drum = 1.25e-4;
  for (const double hz : {30.0, 60.0})
    for (const double weight : {5.0, 20.0})
      for (const double omega : {2.0, 6.0})
        for (const bool stiff : {true, false}) {
          const double kp = stiff ? 3e4 : 2000;
          const double kd = stiff ? 44.72 : 2 * std::sqrt(kp * (drum + weight * r * r));
          SceneDef s = makeScene("winch", {{"r", r}, {"omega", omega}, {"mass", weight}});
          s.bodies[0].inertia = drum;
          s.joints[0].servo.kp = kp;
          s.joints[0].servo.kd = kd;
          World w(s, "winch");
          const int hung = w.findBody("weight");
          double fastest = 0, largest = 0;
          while (w.time() < 3) {
            w.step(1 / hz);
            fastest = std::max(fastest, w.body(hung).velocity.norm());
            largest = std::max(largest, w.cable(0).tension());
          }
          SCOPED_TRACE("kp " + std::to_string(kp) + " weight " + std::to_string(weight) +
                       " omega " + std::to_string(omega) + " at " + std::to_string(hz) + " Hz");
          EXPECT_LT(fastest, 10 * omega * r);
          EXPECT_LT(largest, 10 * weight * kG);
        }
}

TEST(ServoDrive, OtherGainsStepsAndWeightsOnALightDrumLiftWithoutThrowing) {
  // The stiff-servo row's adversarial variants: kp from 500 to 2e5, kd from 5 to critical on the
  // weight's inertia at the drum and more, weights of 0.2 and 5 kg, 30 and 120 Hz. The same
  // bounds: never over the drum's top, the tension while lifting under 1.5 m g, never above
  // max_force / r.
  const double r = 0.1, maxForce = 1e3;
  for (const double kp : {500.0, 2e4, 2e5})
    for (const double weight : {0.2, 5.0})
      for (const double kd : {5.0, 4 * std::sqrt(kp * weight * r * r)})
        for (const double hz : {30.0, 120.0}) {
          World w = lightWinch(kp, kd, maxForce, 2.0, 0.001, weight);
          const int drum = w.findBody("drum"), hung = w.findBody("weight");
          double highest = -1e9, lifting = 0, largest = 0;
          while (w.time() < 25) {
            w.step(1 / hz);
            const BodyState& b = w.body(hung);
            const Vec2 end = b.position + rotate(Vec2(0, 0.1), b.angle);
            highest = std::max(highest, end.y() - w.body(drum).position.y());
            largest = std::max(largest, w.cable(0).tension());
            if (w.time() > 1 && end.y() < w.body(drum).position.y() - 1)
              lifting = std::max(lifting, w.cable(0).tension());
          }
          SCOPED_TRACE("kp " + std::to_string(kp) + " kd " + std::to_string(kd) + " weight " +
                       std::to_string(weight) + " at " + std::to_string(hz) + " Hz");
          EXPECT_LT(highest, r + 1e-3);
          EXPECT_GT(lifting, 0);  // it did lift
          EXPECT_LT(lifting, 1.5 * weight * kG);
          EXPECT_LE(largest, 1.01 * maxForce / r);
        }
}

TEST(ServoDrive, OtherGainsStepsAndWeightsThatWindOnStallAtMaxForce) {
  // The winding-on row's adversarial variants: kp 100 and 5e3, kd 5 and 200, weights of 0.3 and
  // 3 kg (max_force 20 N m lifts both: m g r = 2.9 N m at 3 kg), 30 and 120 Hz. One warning
  // naming the joint, the force at max_force, never above it, the tension then max_force / r.
  const double r = 0.1, maxForce = 20;
  for (const double kp : {100.0, 5e3})
    for (const double kd : {5.0, 200.0})
      for (const double weight : {0.3, 3.0})
        for (const double hz : {30.0, 120.0}) {
          World w = lightWinch(kp, kd, maxForce, 5.0, 0.05, weight);
          double worst = 0, stalledAt = -1, above = 0;
          while (w.time() < 20) {
            w.step(1 / hz);
            if (stalledAt < 0 && !w.warnings().empty() &&
                w.warnings().back().find("stalled") != std::string::npos)
              stalledAt = w.time();
            if (stalledAt >= 0 && w.time() > stalledAt + 0.5)
              worst = std::max(worst, w.cable(0).tension());
            above = std::max(above, std::abs(w.joint(0).force) - maxForce);
          }
          SCOPED_TRACE("kp " + std::to_string(kp) + " kd " + std::to_string(kd) + " weight " +
                       std::to_string(weight) + " at " + std::to_string(hz) + " Hz");
          EXPECT_LE(above, 0);
          // The weight's arrival at the drum is said first, then the stall.
          ASSERT_EQ(w.warnings().size(), 2u);
          EXPECT_NE(w.warnings()[0].find("reached the drum"), std::string::npos) << w.warnings()[0];
          EXPECT_NE(w.warnings()[1].find("joint 'axle'"), std::string::npos) << w.warnings()[1];
          EXPECT_NEAR(w.joint(0).force, maxForce, 1e-9);
          EXPECT_LE(worst, 1.01 * maxForce / r);
          EXPECT_NEAR(w.cable(0).tension(), maxForce / r, 0.01 * maxForce / r);
        }
}

}  // namespace servo_drive_test
}  // namespace cablelab
