// The servos' implicit PD (servo_drive.h; docs/servos.md for the equations).
#include "engine/dynamics/servo_drive.h"

#include <algorithm>
#include <numeric>

#include "engine/core/small_qp.h"
#include "engine/dynamics/disjoint_sets.h"

namespace cablelab {

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
  addCables(cables, bodies);
  const int dofs = 3 * static_cast<int>(dofList_.size());
  invM_.resize(dofs);
  vStar_.resize(dofs);
  for (size_t i = 0; i < dofList_.size(); ++i) {
    const int b = dofList_[i], d = 3 * static_cast<int>(i);
    const BodyState& s = bodies[b];
    const Vec3 load = loads[b] + cableLoads_[b];
    invM_.segment<3>(d) = Vec3(s.invMass, s.invMass, s.invInertia);
    const Vec2 accel =
        s.invMass > 0 ? Vec2(gravity + s.invMass * load.head<2>()) : Vec2(Vec2::Zero());
    vStar_.segment<3>(d) = Vec3(s.velocity.x() + dt * accel.x(), s.velocity.y() + dt * accel.y(),
                                s.angularVelocity + dt * s.invInertia * load.z());
  }
  rows_.clear();
  for (const int j : joints_) appendJointRows(frames[j], bodies, dofOfBody_, rows_);
  rows_.insert(rows_.end(), cableRows_.begin(), cableRows_.end());
  const int count = static_cast<int>(servos_.size());
  coordinateRows_.clear();
  W_.setZero(dofs, count);
  for (int s = 0; s < count; ++s) {
    const JointRow row = coordinateRow(frames[servos_[s]], bodies, dofOfBody_);
    for (int k = 0; k < 2; ++k)
      if (row.dof[k] >= 0)
        W_.col(s).segment<3>(row.dof[k]) = row.coeff[k].cwiseProduct(invM_.segment<3>(row.dof[k]));
    coordinateRows_.push_back(row);
  }
  if (!rows_.empty()) projection_.projectDiagonal(rows_, invM_, W_, vStar_);

  // f = b - c qdot1 with qdot1 = qdot* + dt K f: (C^-1 + dt K) f = C^-1 b - qdot*, a symmetric
  // positive definite system (K = G W, the servos' inverse effective inertia), under |f| <= max.
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

  // Each servo's load: the coordinate row's coefficients times its force (a torque on both
  // bodies; a prismatic servo's force at the joint, along the axis).
  for (int s = 0; s < count; ++s) {
    const int j = servos_[s];
    forces_[j] = f(s);
    const JointFrame& frame = frames[j];
    auto unitLoad = [&](int body) {
      if (frame.kind != JointDef::Kind::Prismatic) return Vec3(0, 0, 1);
      const Vec2 r = frame.anchor - bodies[body].position;
      return Vec3(frame.axis.x(), frame.axis.y(), cross(r, frame.axis));
    };
    if (frame.bodyB >= 0) loads[frame.bodyB] += f(s) * unitLoad(frame.bodyB);
    if (frame.bodyA >= 0) loads[frame.bodyA] -= f(s) * unitLoad(frame.bodyA);
  }
}

}  // namespace cablelab
