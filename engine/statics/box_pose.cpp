#include "engine/statics/box_pose.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace cablelab {

namespace {

constexpr double kResidualTolerance = 1e-10;  // |net force, torque / size| per unit max tension
constexpr double kPoseArmijo = 1e-4;          // sufficient decrease of the line search
constexpr double kEnergyRounding = 1e-12;     // relative: an energy change E cannot resolve

double tension(const BoxCable& c, const BoxPose& q) {
  const double l = boxSegment(q, c.cornerA, c.a).length + (c.cornerB - c.cornerA).norm() +
                   boxSegment(q, c.cornerB, c.b).length;
  return c.k * std::max(0.0, l - c.L);
}

}  // namespace

BoxSegment boxSegment(const BoxPose& q, const Vec2& corner, const Vec2& anchor) {
  const Vec2 arm = rotate(corner, q[2]);  // R(theta) r
  const Vec2 d = q.head<2>() + arm - anchor;
  BoxSegment s;
  s.length = d.norm();
  if (s.length < 1e-300) return s;  // the corner on its fingertip: a kink, no gradient
  // dc/dq: the corner moves with the centre and turns about it (d(R r)/dtheta = perp(R r)).
  s.D << 1, 0, -arm.y(), 0, 1, arm.x();
  s.u = d / s.length;
  s.gradient = s.u.transpose() * s.D;
  s.hessian =
      s.D.transpose() * ((Eigen::Matrix2d::Identity() - s.u * s.u.transpose()) / s.length) * s.D;
  s.hessian(2, 2) -= s.u.dot(arm);  // d2c/dtheta2 = -R r
  return s;
}

Eigen::Matrix<double, 3, 2> BoxSegment::mixedAnchor(double stiffness, double tension,
                                                    const Eigen::RowVector3d& dl) const {
  if (length < 1e-300) return Eigen::Matrix<double, 3, 2>::Zero();
  const Eigen::Matrix2d P = (Eigen::Matrix2d::Identity() - u * u.transpose()) / length;
  return stiffness * (dl.transpose() * (-u.transpose())) - tension * D.transpose() * P;
}

double boxPoseEnergy(const std::vector<BoxCable>& cables, const BoxPose& q,
                     Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) {
  double energy = 0;
  if (gradient) gradient->setZero();
  if (hessian) hessian->setZero();
  for (const BoxCable& c : cables) {
    const BoxSegment A = boxSegment(q, c.cornerA, c.a), B = boxSegment(q, c.cornerB, c.b);
    const double stretch = A.length + (c.cornerB - c.cornerA).norm() + B.length - c.L;
    if (stretch <= 0) continue;  // slack: no energy, no force
    energy += 0.5 * c.k * stretch * stretch;
    const Eigen::RowVector3d dl = A.gradient + B.gradient;
    if (gradient) *gradient += c.k * stretch * dl.transpose();
    if (hessian) *hessian += c.k * (dl.transpose() * dl + stretch * (A.hessian + B.hessian));
  }
  return energy;
}

Eigen::MatrixXd boxPoseSensitivity(const std::vector<BoxCable>& cables, const BoxPose& pose) {
  const Eigen::Index n = static_cast<Eigen::Index>(cables.size());
  Eigen::MatrixXd mixed = Eigen::MatrixXd::Zero(3, 4 * n);  // d grad E / d fingertips
  for (Eigen::Index i = 0; i < n; ++i) {
    const BoxCable& c = cables[i];
    const BoxSegment A = boxSegment(pose, c.cornerA, c.a), B = boxSegment(pose, c.cornerB, c.b);
    const double stretch = A.length + (c.cornerB - c.cornerA).norm() + B.length - c.L;
    if (stretch <= 0) continue;
    const Eigen::RowVector3d dl = A.gradient + B.gradient;
    mixed.block<3, 2>(0, 4 * i) += A.mixedAnchor(c.k, c.k * stretch, dl);
    mixed.block<3, 2>(0, 4 * i + 2) += B.mixedAnchor(c.k, c.k * stretch, dl);
  }
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  boxPoseEnergy(cables, pose, &g, &H);
  return equilibriumSensitivity(H, mixed);
}

Eigen::MatrixXd equilibriumSensitivity(const Eigen::Matrix3d& H, const Eigen::MatrixXd& mixed) {
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(H);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.vectorD().minCoeff() <= 0)
    return Eigen::MatrixXd::Zero(3, mixed.cols());
  return -ldlt.solve(mixed);
}

BoxPoseResult solveBoxPose(const std::vector<BoxCable>& cables, const BoxPose& start, double size,
                           int maxIterations) {
  BoxPoseResult out =
      minimiseBoxEnergy([&](const BoxPose& q, Eigen::Vector3d* g,
                            Eigen::Matrix3d* H) { return boxPoseEnergy(cables, q, g, H); },
                        [&](const BoxPose& q) {
                          double maxTension = 0;
                          for (const BoxCable& c : cables)
                            maxTension = std::max(maxTension, tension(c, q));
                          return maxTension;
                        },
                        start, size, maxIterations);
  out.tensions.clear();
  for (const BoxCable& c : cables) out.tensions.push_back(tension(c, out.pose));
  return out;
}

BoxPoseResult minimiseBoxEnergy(const BoxEnergy& energy,
                                const std::function<double(const BoxPose&)>& maxTension,
                                const BoxPose& start, double size, int maxIterations) {
  BoxPoseResult out;
  out.pose = start;
  auto residual = [&](const Eigen::Vector3d& g, const BoxPose& q) {
    const double largest = maxTension(q);
    if (largest == 0) return 0.0;  // every cable slack: any pose is an equilibrium
    return Eigen::Vector3d(g[0], g[1], g[2] / size).norm() / largest;
  };
  for (out.iterations = 0; out.iterations <= maxIterations; ++out.iterations) {
    Eigen::Vector3d g;
    Eigen::Matrix3d H;
    const double E = energy(out.pose, &g, &H);
    out.energy = E;
    out.residual = residual(g, out.pose);
    if (out.residual <= kResidualTolerance) {
      out.converged = true;
      break;
    }
    if (out.iterations == maxIterations) break;
    // Levenberg: shift the Hessian until it is positive definite (E is not convex in theta).
    double shift = 0;
    Eigen::LDLT<Eigen::Matrix3d> ldlt(H);
    while (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= 0 || !ldlt.isPositive()) {
      shift = std::max(2 * shift, 1e-8 * (1 + H.cwiseAbs().maxCoeff()));
      ldlt.compute(H + shift * Eigen::Matrix3d::Identity());
    }
    const Eigen::Vector3d step = -ldlt.solve(g);
    // Backtracking: every accepted step lowers E. Near the minimum E's decrease (about
    // g^T H^-1 g / 2) falls below E's rounding, so a step whose energy change is within it is
    // judged by the gradient it leaves instead (Newton's full step shrinks it quadratically);
    // judged by the energy alone, the solve stalls a little above the tolerance.
    double t = 1;
    for (; t > 1e-12; t *= 0.5) {
      const BoxPose trial = out.pose + t * step;
      const double trialEnergy = energy(trial, nullptr, nullptr);
      if (trialEnergy <= E + kPoseArmijo * t * g.dot(step)) break;
      if (std::abs(trialEnergy - E) > kEnergyRounding * std::abs(E)) continue;
      Eigen::Vector3d trialGradient;
      energy(trial, &trialGradient, nullptr);
      if (residual(trialGradient, trial) < out.residual) break;
    }
    if (t <= 1e-12) break;  // no descent left at double precision
    out.pose += t * step;
  }
  return out;
}

}  // namespace cablelab
