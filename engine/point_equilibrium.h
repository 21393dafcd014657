// Static equilibrium of a point held by elastic cables, and its sensitivity to the cables' ends.
//
// Cable i runs a_i -> p -> b_i with stiffness k_i and rest length L_i; its tension is
// k_i max(0, |p - a_i| + |b_i - p| - L_i). The equilibrium p* minimises
//   E(p) = sum_i k_i / 2 max(0, |p - a_i| + |b_i - p| - L_i)^2     (thesis 4.2, NOTES.md).
// This is the controller's own damped-Newton solver, a stand-in with the same meaning as the
// statics engineer's SOCP (`solveStatics` / `staticsSensitivity`); the controller only sees the
// EquilibriumSolver function type below, so either can be plugged in.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "engine/math.h"

namespace cablelab {

struct SpringCable {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  ///< the cable's two fixed ends (m)
  double k = 0;                             ///< stiffness (N/m)
  double L = 0;                             ///< rest length incl. preload: L = rest - preload (m)
};

struct PointEquilibrium {
  Vec2 p = Vec2::Zero();  ///< the minimiser (m)
  /// dp*/d(ends): 2 x 4N, columns a_i.x, a_i.y, b_i.x, b_i.y per cable (dimensionless).
  Eigen::Matrix<double, 2, Eigen::Dynamic> sensitivity;
  double energy = 0;      ///< J
  int iterations = 0;
  bool converged = false; ///< gradient below tolerance and the Hessian positive definite
};

/// Damped Newton from `guess` with a backtracking line search on E; steps off a cable end a bad
/// iterate lands on (the energy's kink, NOTES.md). Never throws; check `converged`.
PointEquilibrium solvePointEquilibrium(const std::vector<SpringCable>& cables, const Vec2& guess);

/// E(p) (J).
double springEnergy(const std::vector<SpringCable>& cables, const Vec2& p);

/// Solver signature the controller takes: (cables, warm-start guess) -> equilibrium + sensitivity.
using EquilibriumSolver = std::function<PointEquilibrium(const std::vector<SpringCable>&, const Vec2&)>;

}  // namespace cablelab
