// The World's end-of-step reports (World::warnings()): a rigid cable left long, redundant rows
// held at their lengths, a cable paying out, a stalled servo. Split from world.cpp (the stepping)
// to keep each file to one concept.
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/world.h"

namespace cablelab {

namespace world_reports {

constexpr double kStallRate = 1e-3;  // rad/s or m/s: a servo's joint moving slower is stalled
constexpr double kStallAcceleration = 1e-3;  // rad/s^2 or m/s^2: ... and speeding up less
constexpr double kStallRelease = 0.9;  // of max_force: a stalled servo pushing less is released
constexpr double kOverstretch = 0.01;  // m: a rigid cable this far over its rest length is said

}  // namespace world_reports

// A rigid cable more than kOverstretch longer than its rest length at the end of a step: the step
// did not resolve the motion (a box spinning at 80 rad/s on a rope fixed to its corner, 1.4 rad a
// step: Newton's linearisation was far off, and the rope ran 10.6 cm long with no word). Say so
// once, until it is back within kLengthSlop of it.
void World::reportOverstretch() {
  overstretched_.resize(cables_.size(), 0);
  if (stats_.heldIslands > 0 && !heldSaid_) reportHeldRows();
  for (size_t i = 0; i < cables_.size(); ++i) {
    const Cable& c = cables_[i];
    if (c.elastic()) continue;
    const double stretch = c.stretch();
    if (stretch <= kLengthSlop) overstretched_[i] = 0;
    if (stretch <= world_reports::kOverstretch || overstretched_[i]) continue;
    overstretched_[i] = 1;
    warnings_.push_back("cable '" + c.name() + "': rigid and " + formatNumber(stretch) +
                        " m longer than its rest length at t = " + formatNumber(time_) +
                        " s: the step did not resolve the motion (a fast turn or impact); more "
                        "sub-steps hold it");
  }
}

// Redundant rigid cables whose rest lengths no pose meets: the solve holds them at their lengths
// (cable_solver.cpp, holdOverlongRows). Said once, naming the cables left long; they are not
// reported as overstretched after it, as more sub-steps would not shorten them.
void World::reportHeldRows() {
  heldSaid_ = true;
  std::string names;
  double longest = 0;
  for (size_t i = 0; i < cables_.size(); ++i) {
    const Cable& c = cables_[i];
    if (c.elastic() || c.stretch() <= kLengthSlop) continue;
    names += (names.empty() ? "'" : ", '") + c.name() + "'";
    longest = std::max(longest, c.stretch());
    overstretched_[i] = 1;
  }
  warnings_.push_back("rigid cables " + names + ": their rest lengths ask for a pose none meets " +
                      "(redundant cables that disagree); from t = " + formatNumber(time_) +
                      " s they are held at their lengths, up to " + formatNumber(longest) +
                      " m long (fit the rest lengths, or give them stiffness)");
}

// A rigid cable that a kinematic body hauls out against bodies that cannot give way pays out
// (cable_solver.cpp, stage 6d): say when it starts, naming the kinematic bodies on it, and how
// much it paid out when it stops.
void World::reportPayOuts() {
  paidOutSeen_.resize(cables_.size(), 0.0);
  payStart_.resize(cables_.size(), -1.0);
  for (size_t i = 0; i < cables_.size(); ++i) {
    const Cable& c = cables_[i];
    const double paid = c.paidOut();
    const bool paying = paid != paidOutSeen_[i];
    if (paying && payStart_[i] < 0) {
      payStart_[i] = paidOutSeen_[i];
      std::string haulers;
      for (const WrapPoint& w : c.path())
        if (w.body >= 0 && scene_.bodies[w.body].type == BodyType::Kinematic &&
            haulers.find("'" + scene_.bodies[w.body].name + "'") == std::string::npos)
          haulers += (haulers.empty() ? "'" : ", '") + scene_.bodies[w.body].name + "'";
      if (haulers.empty()) haulers = "(through a joint)";
      warnings_.push_back("cable '" + c.name() + "': pays out from t = " + formatNumber(time_) +
                          " s: kinematic body " + haulers +
                          " hauls it, and the bodies along it cannot give way (a load at its "
                          "pulley?), so no tension can hold its length");
    } else if (!paying && payStart_[i] >= 0) {
      warnings_.push_back("cable '" + c.name() + "': stopped paying out at t = " +
                          formatNumber(time_) + " s, " + formatNumber(paid - payStart_[i]) +
                          " m longer (rest length " + formatNumber(c.restLength()) + " m)");
      payStart_[i] = -1;
    }
    paidOutSeen_[i] = paid;
  }
}

// A servo at its max_force whose joint neither moves nor speeds up the way it pushes
// (kStallRate, kStallAcceleration) over the step is stalled: it cannot move what it drives (one
// braking its joint at max_force is moving it). Said once a stall, naming the joint; the stall
// ends when its force falls back below kStallRelease of max_force.
void World::reportStalls(double dt) {
  for (size_t j = 0; j < scene_.joints.size(); ++j) {
    const ServoDef& servo = scene_.joints[j].servo;
    if (!servo.enabled) continue;
    const double f = jointForces_[j];
    if (std::abs(f) < world_reports::kStallRelease * servo.maxForce) stalledSince_[j] = -1;
    const double rate = b2_->jointCoordinate(static_cast<int>(j)).speed;
    // applyServos read the rate at the start of the last Box2D step.
    const double gained = j < jointCoordinates_.size() ? rate - jointCoordinates_[j].speed : 0.0;
    const double push = f > 0 ? 1 : -1;
    const bool atMax = std::abs(f) >= (1 - 1e-9) * servo.maxForce;
    if (stalledSince_[j] >= 0 || !atMax || rate * push > world_reports::kStallRate ||
        gained * push > world_reports::kStallAcceleration * dt)
      continue;
    stalledSince_[j] = time_ - dt;
    const bool turns = scene_.joints[j].kind == JointDef::Kind::Revolute;
    warnings_.push_back(
        "joint '" + scene_.joints[j].name + "': its servo pushes with all it has (" + "max_force " +
        formatNumber(servo.maxForce) + (turns ? " N m" : " N") +
        ") and cannot move what it drives: stalled from t = " + formatNumber(stalledSince_[j]) +
        " s (a stronger servo or a lighter load moves it)");
  }
}

}  // namespace cablelab
