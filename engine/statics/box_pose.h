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
#include <functional>
#include <vector>

#include "engine/statics/box_reduction.h"

namespace cablelab {

/// (x, y, theta): the box centre (m) and its angle (rad).
using BoxPose = Eigen::Vector3d;

/// A free segment from a box corner r (box frame) to a fixed anchor: s(q) = |c(q) - anchor| with
/// c(q) = (x, y) + R(theta) r, its gradient u^T D and Hessian in q.
struct BoxSegment {
  double length = 0;  ///< m; 0: the corner on its anchor (no gradient)
  Eigen::RowVector3d gradient = Eigen::RowVector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  Vec2 u = Vec2::Zero();  ///< unit vector anchor -> corner
  Eigen::Matrix<double, 2, 3> D = Eigen::Matrix<double, 2, 3>::Zero();  ///< dc/dq
  /// d(grad E)/d anchor (3 x 2) of a spring term whose tension T(l) has dT/dl = `stiffness`,
  /// pulling along `dl` (its length's whole gradient): k dl^T (-u^T) - T D^T (I - u u^T) / s.
  Eigen::Matrix<double, 3, 2> mixedAnchor(double stiffness, double tension,
                                          const Eigen::RowVector3d& dl) const;
};
BoxSegment boxSegment(const BoxPose& q, const Vec2& corner, const Vec2& anchor);

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

/// -H^-1 mixed: the equilibrium's sensitivity from E's Hessian and d(grad E)/d parameters; zero
/// where H is not positive definite.
Eigen::MatrixXd equilibriumSensitivity(const Eigen::Matrix3d& H, const Eigen::MatrixXd& mixed);

/// An energy of the pose: E(q), filling the gradient and Hessian where not null.
using BoxEnergy = std::function<double(const BoxPose&, Eigen::Vector3d*, Eigen::Matrix3d*)>;

/// Newton on `energy` from `start`, Levenberg-shifted, with a backtracking line search, until the
/// gradient (torque / `size`) is below 1e-10 of `maxTension(q)` (tensions and energy left empty).
BoxPoseResult minimiseBoxEnergy(const BoxEnergy& energy,
                                const std::function<double(const BoxPose&)>& maxTension,
                                const BoxPose& start, double size, int maxIterations);

/// Newton on E from `start`; `size` (m) scales the torque in the convergence test (the box's
/// half side, say).
BoxPoseResult solveBoxPose(const std::vector<BoxCable>& cables, const BoxPose& start,
                           double size = 1.0, int maxIterations = 100);

}  // namespace cablelab
