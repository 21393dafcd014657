// Statics of a box that may rotate (docs/model.md#rotating-box): pose q = (x, y, theta).
//
// The box-to-point reduction (box_reduction.h) holds only while the box does not turn. Here each
// cable runs fingertip a -> corner cA(q) -> (along the box) -> corner cB(q) -> fingertip b with
// the corners on the turning box, c(q) = (x, y) + R(theta) r for a corner offset r in the box
// frame. Its length is
//   l(q) = |cA(q) - a| + |rB - rA| + |b - cB(q)|
// (the run along the box is rigid), its tension k max(0, l - L), and the pose minimises the
// elastic energy E(q) = sum k / 2 max(0, l(q) - L)^2. E is not convex in theta, so the solver is
// Newton on E with the Hessian shifted until positive definite (Levenberg) and a backtracking
// line search: every step lowers E.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/statics/box_reduction.h"

namespace cablelab {

/// (x, y, theta): the box centre (m) and its angle (rad).
using BoxPose = Eigen::Vector3d;

/// E(q) (J); with gradient (N, N m) and Hessian when asked.
double boxPoseEnergy(const std::vector<BoxCable>& cables, const BoxPose& q,
                     Eigen::Vector3d* gradient = nullptr, Eigen::Matrix3d* hessian = nullptr);

struct BoxPoseResult {
  BoxPose pose = BoxPose::Zero();
  std::vector<double> tensions;  ///< (N) per cable (N)
  double energy = 0;             ///< J
  double residual = 0;  ///< |gradient| scaled: |(F_x, F_y, torque / box size)| / max tension
  int iterations = 0;
  bool converged = false;
};

/// d pose* / d fingertips at an equilibrium `pose` (3 x 4N; columns a_i.x, a_i.y, b_i.x, b_i.y
/// per cable, in order): from grad E(q*, tips) = 0, dq* = -H^-1 (d grad E / d tips) d tips.
/// Zero where H is not positive definite (no isolated equilibrium).
Eigen::MatrixXd boxPoseSensitivity(const std::vector<BoxCable>& cables, const BoxPose& pose);

/// Newton on E from `start`; `size` (m) scales the torque in the convergence test (the box's
/// half side, say).
BoxPoseResult solveBoxPose(const std::vector<BoxCable>& cables, const BoxPose& start,
                           double size = 1.0, int maxIterations = 100);

}  // namespace cablelab
