// The servos' implicit PD (servo_drive.h; docs/servos.md for the equations).
#include "engine/dynamics/servo_drive.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/core/small_qp.h"
#include "engine/dynamics/disjoint_sets.h"

namespace cablelab {

// A rigid span's row is dropped only once its push passes this share of the impulse it pulled
// with over the last step: a rope on the edge of slack (a square spool's corner going by) keeps
// its row, where dropping it for a push of nothing moved the rope's length a little more per step.
constexpr double kSlackMargin = 0.01;
// Holds (docs/servos.md, "Held joints"): a joint the last step held stays near rest (rad/s or
// m/s) where the prediction expected it to move at more than this, by over 1 / kHeldShare times
// the rate it kept; a held joint moving faster than this again is released.
constexpr double kHeldRate = 1e-3;
constexpr double kHeldShare = 0.1;
// ... over this many steps in a row: a load the prediction sees from the next step on (a rope gone
// taut on a weight, its tension then known) stops a light drum for one step only.
constexpr int kHeldSteps = 2;

ServoDrive::ServoDrive(const SceneDef& scene, std::span<const std::array<int, 2>> jointBodies)
    : scene_(scene), forces_(scene.joints.size(), 0.0) {
  // Bodies tied together by joints, through dynamic bodies only: a static or kinematic body
  // moves as it is told whatever the servo does, so it joins nothing.
  const int n = static_cast<int>(scene.bodies.size());
  auto dynamic = [&](int b) { return b >= 0 && scene.bodies[b].type == BodyType::Dynamic; };
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : jointBodies)
    if (dynamic(a) && dynamic(b)) unite(parent, a, b);
  std::vector<char> driven(n, 0);
  for (size_t j = 0; j < scene.joints.size(); ++j) {
    if (!scene.joints[j].servo.enabled) continue;
    servos_.push_back(static_cast<int>(j));
    for (const int b : jointBodies[j])
      if (dynamic(b)) driven[findRoot(parent, b)] = 1;
  }
  auto inDriven = [&](int b) { return dynamic(b) && driven[findRoot(parent, b)]; };
  for (int b = 0; b < n; ++b)
    if (inDriven(b)) dofBodies_.push_back(b);
  for (size_t j = 0; j < jointBodies.size(); ++j)
    if (inDriven(jointBodies[j][0]) || inDriven(jointBodies[j][1]))
      joints_.push_back(static_cast<int>(j));
  dofOfBody_.assign(n, -1);
  held_.assign(servos_.size(), 0);
  stoppedSteps_.assign(servos_.size(), 0);
  pushed_.assign(servos_.size(), 0);
  expectedRate_.assign(servos_.size(), std::numeric_limits<double>::quiet_NaN());
}

void ServoDrive::forgetMotion() {
  std::fill(held_.begin(), held_.end(), 0);
  std::fill(stoppedSteps_.begin(), stoppedSteps_.end(), 0);
  std::fill(expectedRate_.begin(), expectedRate_.end(), std::numeric_limits<double>::quiet_NaN());
}

// The cables on the jointed bodies: an elastic span pulls with its tension, a load the prediction
// sees (a function of the pose: the membranes a hand's servos hold against). A taut rigid span on
// at most two moving bodies is a row like a joint's, its other body a dof too (a winch's weight:
// its inertia and weight then reach the drum's servo through the rope, with no lag). Other
// rigid spans, and contacts, act after the servos' forces are fixed (docs/servos.md).
void ServoDrive::addCables(std::span<const Cable> cables, std::span<const BodyState> bodies) {
  cableLoads_.assign(bodies.size(), Vec3::Zero());
  for (const Cable& c : cables)
    for (int k = 0; k < c.spanCount(); ++k) {
      const auto& jacobian = c.spanKinematics(k).jacobian;
      const double tension = c.spanTension(k);
      bool touches = false;
      for (const BodyJacobian& e : jacobian) touches |= dofOfBody_[e.body] >= 0;
      if (!touches || !(tension > 0)) continue;
      if (c.elastic()) {
        for (const BodyJacobian& e : jacobian) cableLoads_[e.body] -= tension * e.d;
        continue;
      }
      int moving = 0;
      for (const BodyJacobian& e : jacobian) moving += moves(bodies[e.body]);
      if (moving > 2) continue;
      for (const BodyJacobian& e : jacobian)
        if (moves(bodies[e.body]) && dofOfBody_[e.body] < 0) {
          dofOfBody_[e.body] = 3 * static_cast<int>(dofList_.size());
          dofList_.push_back(e.body);
        }
      JointRow row;
      int side = 0;
      for (const BodyJacobian& e : jacobian) {
        const BodyState& b = bodies[e.body];
        if (moves(b)) {
          row.dof[side] = dofOfBody_[e.body];
          row.coeff[side++] = e.d;
        } else {
          row.bias += e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
        }
      }
      cableRows_.push_back(row);
      cablePull_.push_back(tension);
    }
}

void ServoDrive::solve(std::span<const JointFrame> frames,
                       std::span<const JointCoordinate> coordinates,
                       std::span<const BodyState> bodies, std::span<const Cable> cables,
                       std::span<const double> targets, const Vec2& gravity, double dt,
                       std::vector<Vec3>& loads) {
  std::fill(forces_.begin(), forces_.end(), 0.0);
  if (servos_.empty()) return;
  // The jointed bodies' velocities at the end of the step under gravity, the user's loads and
  // the cables' (v*), and M^-1 times each servo's unit load (W's columns), both restricted to
  // what the joints and taut rigid cables allow.
  std::fill(dofOfBody_.begin(), dofOfBody_.end(), -1);
  dofList_ = dofBodies_;
  for (size_t i = 0; i < dofList_.size(); ++i) dofOfBody_[dofList_[i]] = 3 * static_cast<int>(i);
  cableRows_.clear();
  cablePull_.clear();
  addCables(cables, bodies);
  const int dofs = 3 * static_cast<int>(dofList_.size());
  invM_.resize(dofs);
  vStarFree_.resize(dofs);
  for (size_t i = 0; i < dofList_.size(); ++i) {
    const int b = dofList_[i], d = 3 * static_cast<int>(i);
    const BodyState& s = bodies[b];
    const Vec3 load = loads[b] + cableLoads_[b];
    invM_.segment<3>(d) = Vec3(s.invMass, s.invMass, s.invInertia);
    const Vec2 accel =
        s.invMass > 0 ? Vec2(gravity + s.invMass * load.head<2>()) : Vec2(Vec2::Zero());
    vStarFree_.segment<3>(d) =
        Vec3(s.velocity.x() + dt * accel.x(), s.velocity.y() + dt * accel.y(),
             s.angularVelocity + dt * s.invInertia * load.z());
  }
  const int count = static_cast<int>(servos_.size());
  coordinateRows_.clear();
  WFree_.setZero(dofs, count);
  for (int s = 0; s < count; ++s) {
    const JointRow row = coordinateRow(frames[servos_[s]], bodies, dofOfBody_);
    for (int k = 0; k < 2; ++k)
      if (row.dof[k] >= 0)
        WFree_.col(s).segment<3>(row.dof[k]) =
            row.coeff[k].cwiseProduct(invM_.segment<3>(row.dof[k]));
    coordinateRows_.push_back(row);
  }
  rows_.clear();
  for (const int j : joints_) appendJointRows(frames[j], bodies, dofOfBody_, rows_);
  const size_t jointRows = rows_.size();
  findHolds(coordinates);

  // A rigid span is a row only while it pulls (a complementarity, solved by active set): a row
  // whose impulse would push is dropped and the forces found again, a dropped span the motion
  // would stretch comes back. Kept bilateral, a rope gone slack for a step (a weight jerked up
  // faster than the drum winds) had the force sized for drum and weight spin a light drum to
  // Box2D's turn limit, and the rope snapped taut and threw the weight (docs/servos.md).
  cableActive_.assign(cableRows_.size(), 1);
  const int passes = static_cast<int>(cableRows_.size()) + 1;
  int pass = 0;
  for (; pass < passes; ++pass) {
    rows_.resize(jointRows);
    for (const int s : holdRows_) rows_.push_back(coordinateRows_[s]);
    for (size_t i = 0; i < cableRows_.size(); ++i)
      if (cableActive_[i]) rows_.push_back(cableRows_[i]);
    W_ = WFree_;
    vStar_ = vStarFree_;
    const bool oneWay = !cableRows_.empty() || !holdRows_.empty();
    if (!rows_.empty())
      projection_.projectDiagonal(rows_, invM_, W_, vStar_, oneWay ? &multipliers_ : nullptr);
    solveForces(coordinates, targets, dt);
    if (releaseHolds(jointRows, dt)) {  // the rigid spans' active set starts again without them
      cableActive_.assign(cableRows_.size(), 1);
      pass = -1;
      continue;
    }
    if (cableRows_.empty()) break;
    if (pass == 0) fAllRows_ = f_;
    if (!updateActiveCables(jointRows + holdRows_.size(), dt)) break;
  }
  // With a span dropped, each servo pushes no harder than that solve says, nor past it in sign:
  // the force with every row, where it is the weaker one, makes the joint heavier than it is,
  // which errs on the stable side (docs/servos.md), and leaves a spool whose weight rides over its
  // top and falls ahead of the rope no faster than before, to be caught with no jerk.
  if (pass > 0)
    for (int s = 0; s < count; ++s)
      if (fAllRows_(s) * f_(s) > 0 && std::abs(fAllRows_(s)) < std::abs(f_(s)))
        f_(s) = fAllRows_(s);

  recordPrediction(dt);

  // Each servo's load: the coordinate row's coefficients times its force (a torque on both
  // bodies; a prismatic servo's force at the joint, along the axis).
  for (int s = 0; s < count; ++s) {
    const int j = servos_[s];
    forces_[j] = f_(s);
    const JointFrame& frame = frames[j];
    auto unitLoad = [&](int body) {
      if (frame.kind != JointDef::Kind::Prismatic) return Vec3(0, 0, 1);
      const Vec2 r = frame.anchor - bodies[body].position;
      return Vec3(frame.axis.x(), frame.axis.y(), cross(r, frame.axis));
    };
    if (frame.bodyB >= 0) loads[frame.bodyB] += f_(s) * unitLoad(frame.bodyB);
    if (frame.bodyA >= 0) loads[frame.bodyA] -= f_(s) * unitLoad(frame.bodyA);
  }
}

// f = b - c qdot1 with qdot1 = qdot* + dt K f: (C^-1 + dt K) f = C^-1 b - qdot*, a symmetric
// positive definite system (K = G W, the servos' inverse effective inertia), under |f| <= max.
void ServoDrive::solveForces(std::span<const JointCoordinate> coordinates,
                             std::span<const double> targets, double dt) {
  const int count = static_cast<int>(servos_.size());
  Eigen::MatrixXd& A = A_;
  Eigen::VectorXd &rhs = rhs_, &upper = upper_, &f = f_;
  A.resize(count, count);
  rhs.resize(count);
  upper.resize(count);
  for (int s = 0; s < count; ++s) {
    const int j = servos_[s];
    const ServoDef& servo = scene_.joints[j].servo;
    const double c = servo.kp * dt + servo.kd;
    const double b =
        servo.kp * (targets[j] + dt * servo.speed - coordinates[j].value) + servo.kd * servo.speed;
    for (int t = 0; t < count; ++t) A(s, t) = dt * coordinateRows_[s].dot(W_.col(t));
    // A servo without gains (c = 0) pushes with nothing: f = 0 through an infinite C^-1.
    A(s, s) += c > 0 ? 1.0 / c : 1.0;
    rhs(s) = c > 0 ? b / c - (coordinateRows_[s].dot(vStar_) + coordinateRows_[s].bias) : 0.0;
    upper(s) = servo.maxForce;
  }
  // Symmetrised in place (the same sums as 0.5 (A + A^T), without a temporary: no allocation
  // per sub-step).
  for (int s = 0; s < count; ++s)
    for (int t = s + 1; t < count; ++t) A(s, t) = A(t, s) = 0.5 * (A(s, t) + A(t, s));
  f = ldlt_.compute(A).solve(rhs);
  if ((f.array().abs() > upper.array()).any()) {
    // Some servos at their max_force: the box-constrained minimum of 1/2 f^T A f - rhs^T f.
    Eigen::MatrixXd C(2 * count, count);
    Eigen::VectorXd lower(2 * count);
    C << Eigen::MatrixXd::Identity(count, count), -Eigen::MatrixXd::Identity(count, count);
    lower << -upper, -upper;
    f = solveSmallQp(A, -rhs, C, lower, f.cwiseMax(-upper).cwiseMin(upper)).x;
    f = f.cwiseMax(-upper).cwiseMin(upper);
  }
}

// The rigid spans' rows after a solve: a kept row whose impulse pushes (its multiplier, from the
// projection, with the servos' forces f_) is dropped; a dropped row whose span the motion would
// stretch comes back. Whether the active set changed.
bool ServoDrive::updateActiveCables(size_t jointRows, double dt) {
  const int count = static_cast<int>(servos_.size());
  bool changed = false;
  size_t row = jointRows;
  for (size_t i = 0; i < cableRows_.size(); ++i) {
    if (cableActive_[i]) {
      // Row r's impulse is -(S^-1 (C v* + bias) + dt S^-1 C W f): it pulls while that is > 0.
      const double pull = multipliers_(static_cast<Eigen::Index>(row), count) +
                          dt * multipliers_.row(static_cast<Eigen::Index>(row)).head(count).dot(f_);
      ++row;
      if (pull >= -kSlackMargin * cablePull_[i] * dt) continue;
    } else {
      const JointRow& r = cableRows_[i];
      double stretch = r.bias;
      for (int k = 0; k < 2; ++k)
        if (r.dof[k] >= 0)
          stretch +=
              r.coeff[k].dot(vStar_.segment<3>(r.dof[k]) + dt * W_.middleRows<3>(r.dof[k]) * f_);
      if (stretch <= 0) continue;
    }
    cableActive_[i] = !cableActive_[i];
    changed = true;
  }
  return changed;
}

// A joint is held where a load the prediction does not see stopped it: the last step predicted
// it would move the way its servo pushed, and it stayed near rest. The next steps predict it held
// that way (its coordinate a row of the projection: K = 0, f = b), so the force rises at kp
// |speed| as against a rigid stop, not kp |speed| / (1 + h c / m) (docs/servos.md, "Held
// joints"). A held joint that moves again is released at once.
void ServoDrive::findHolds(std::span<const JointCoordinate> coordinates) {
  holdRows_.clear();
  for (size_t s = 0; s < servos_.size(); ++s) {
    const double rate = coordinates[servos_[s]].speed;
    if (held_[s] != 0) {
      if (std::abs(rate) > kHeldRate) {
        held_[s] = 0;
        stoppedSteps_[s] = 0;
      }
    } else {
      const double expected = pushed_[s] * expectedRate_[s];  // NaN: unknown, no stop
      const bool stopped = pushed_[s] != 0 && expected > kHeldRate &&
                           std::abs(rate) <= std::min(kHeldRate, kHeldShare * expected);
      stoppedSteps_[s] = stopped ? stoppedSteps_[s] + 1 : 0;
      if (stoppedSteps_[s] >= kHeldSteps) held_[s] = pushed_[s];
    }
    if (held_[s] != 0) holdRows_.push_back(static_cast<int>(s));
  }
}

// A hold is one-way: it holds while its servo pushes into it and its row's impulse (from the
// projection, as a rigid span's) opposes the push. Otherwise it is released and the forces found
// again. Whether any was released.
bool ServoDrive::releaseHolds(size_t jointRows, double dt) {
  const int count = static_cast<int>(servos_.size());
  bool released = false;
  for (size_t i = 0; i < holdRows_.size(); ++i) {
    const int s = holdRows_[i];
    const auto row = static_cast<Eigen::Index>(jointRows + i);
    // The row's impulse along the coordinate is -pull (updateActiveCables).
    const double pull = multipliers_(row, count) + dt * multipliers_.row(row).head(count).dot(f_);
    if (held_[s] * pull >= 0 && held_[s] * f_(s) > 0) continue;
    held_[s] = 0;
    stoppedSteps_[s] = 0;
    released = true;
  }
  if (released)
    holdRows_.erase(
        std::remove_if(holdRows_.begin(), holdRows_.end(), [&](int s) { return held_[s] == 0; }),
        holdRows_.end());
  return released;
}

// Each servo's joint rate at the step's end as the solve predicts it, qdot* + dt K f, and the way
// it pushes: the next solve compares them with the rate the step gave (findHolds).
void ServoDrive::recordPrediction(double dt) {
  for (size_t s = 0; s < servos_.size(); ++s) {
    const JointRow& row = coordinateRows_[s];
    const auto i = static_cast<Eigen::Index>(s);
    expectedRate_[s] = row.dot(vStar_ + dt * W_ * f_) + row.bias;
    pushed_[s] = f_(i) > 0 ? 1 : (f_(i) < 0 ? -1 : 0);
  }
}

}  // namespace cablelab
