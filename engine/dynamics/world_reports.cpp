// The World's end-of-step reports (World::warnings()): a rigid cable left long, redundant rows
// held at their lengths, a cable paying out, a weight wound up to its drum, a stalled servo. Split
// from world.cpp (the stepping) to keep each file to one concept.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/core/error.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/floors.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/stall_watch.h"
#include "engine/dynamics/world.h"

namespace cablelab {

namespace world_reports {

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

// A drum end on a servo's joint that winds its cable, the body at the segment's other end at the
// segment's floor (docs/floors.md): the weight is wound up to the drum, and the servo, which
// cannot wind further, pushes harder until it stalls (docs/servos.md, "Stalls"), which can take
// a minute (the built-in winch: 50 s). A weight that touches a solid drum is not held there: the
// rope winds it over and round the drum (a bare drum), so that arrival says so and no stall.
// Said once an arrival, with the time; a weight that bounces at the drum arrives once, and only
// one paid out past kFloorWatch arrives anew.
void World::reportDrumArrivals() {
  drumArrived_.resize(2 * cables_.size(), 0);
  std::vector<ContactForce> contacts;  // read once, for the first drum not at its floor
  bool contactsRead = false;
  auto touch = [&](int a, int b) {
    if (!contactsRead) contacts = b2_->contactForces(), contactsRead = true;
    return std::any_of(contacts.begin(), contacts.end(), [&](const ContactForce& c) {
      return (c.bodyA == a && c.bodyB == b) || (c.bodyA == b && c.bodyB == a);
    });
  };
  for (size_t i = 0; i < cables_.size(); ++i) {
    const std::vector<WrapPoint>& path = cables_[i].path();
    for (const bool atStart : {true, false}) {
      const size_t n = path.size();
      const WrapPoint& drum = atStart ? path[0] : path[n - 1];
      const WrapPoint& other = atStart ? path[1] : path[n - 2];
      char& said = drumArrived_[2 * i + (atStart ? 0 : 1)];
      if (drum.radius == 0 || drum.body < 0 || other.body < 0 || other.body == drum.body) continue;
      const double gap = atStart ? floorGap(drum, other) : floorGap(other, drum);
      if (gap > kFloorWatch) said = 0;  // paid out well clear: a later arrival is a new one
      const bool atFloor = gap <= kFloorLength + kLengthSlop ||
                           (atStart ? atRimFloor(drum, other) : atRimFloor(other, drum));
      if (said || !hasFloors(cables_[i])) continue;
      // touching_: both bodies in some contact in the last sub-step (a cheap test first).
      const bool touches =
          !atFloor && touching_[drum.body] && touching_[other.body] && touch(drum.body, other.body);
      if (!atFloor && !touches) continue;
      // d length / d drum angle, the cable's Jacobian (cable_kinematics.cpp): the length counts
      // the rope wound on the drum, so a drum that winds adds to it and the rope's row pulls the
      // weight in by as much.
      double lengthPerTurn = 0;
      for (const BodyJacobian& e : cables_[i].kinematics().jacobian)
        if (e.body == drum.body) lengthPerTurn = e.d.z();
      for (size_t j = 0; j < scene_.joints.size(); ++j) {
        const JointDef& joint = scene_.joints[j];
        const int a = jointBodies_[j][0], b = jointBodies_[j][1];
        if (!joint.servo.enabled || joint.kind != JointDef::Kind::Revolute) continue;
        if (a != drum.body && b != drum.body) continue;
        // The servo's torque on the drum: +f on body B, -f on body A.
        const double torque = b == drum.body ? jointForces_[j] : -jointForces_[j];
        if (torque * lengthPerTurn <= 0) continue;  // not winding
        said = 1;
        char when[32];
        std::snprintf(when, sizeof when, "%.6g", time_);
        const std::string arrived = "cable '" + cables_[i].name() + "': the weight '" +
                                    scene_.bodies[other.body].name + "' reached the drum '" +
                                    scene_.bodies[drum.body].name + "' at t = " + when + " s";
        if (touches)
          warnings_.push_back(arrived + " and touches it: the drum is solid, so where joint '" +
                              joint.name + "' lifts more than the weight it winds the weight " +
                              "over the drum and round it on the rope, as a bare drum does (a " +
                              "sensor drum holds it at the rim, where the servo stalls)");
        else
          warnings_.push_back(arrived + ": the rope is wound in as far as it goes, and joint '" +
                              joint.name +
                              "' pushes harder to wind it on until its servo stalls at max_force " +
                              formatNumber(joint.servo.maxForce) + " N m");
        break;
      }
    }
  }
}

// A servo at its max_force whose joint stays nearly still has stalled: it cannot move what it
// drives (StallWatch, docs/servos.md "Stalls"; one braking its joint, or pulled back by its load,
// moves it). Said once a stall, naming the joint and the window it kept still over.
void World::reportStalls(double dt) {
  for (size_t j = 0; j < scene_.joints.size(); ++j) {
    const ServoDef& servo = scene_.joints[j].servo;
    if (!servo.enabled) continue;
    const JointCoordinate q = b2_->jointCoordinate(static_cast<int>(j));
    StallWatch& watch = stalls_[j];
    if (!watch.update(jointForces_[j], servo.maxForce, q.value, q.speed, time_, dt)) continue;
    const bool turns = scene_.joints[j].kind == JointDef::Kind::Revolute;
    warnings_.push_back(
        "joint '" + scene_.joints[j].name + "': its servo pushes with all it has (" + "max_force " +
        formatNumber(servo.maxForce) + (turns ? " N m" : " N") +
        ") and cannot move what it drives: stalled from t = " + formatNumber(watch.start) +
        " s (still to within " + formatNumber(StallWatch::kStillRange) + (turns ? " rad" : " m") +
        " through t = " + formatNumber(time_) + " s; a stronger servo or a lighter load moves it)");
  }
}

}  // namespace cablelab
