// Joint tension solve for all cables of a world at once (a small LCP, dense, Eigen).
//
// Each cable i is a row with Jacobian J_i (d length / d q). With tension impulses P >= 0 over a
// step the velocities become v = v* - M^-1 J^T P, and each taut row asks
//     rigid:   J_i v = r_i                       (r_i: stabilised target length rate)
//     elastic: J_i v = r_i + compliance_i P_i    (implicit spring-damper, a soft constraint)
// so that w = (A + E) P - b >= 0, P >= 0, P . w = 0 with A = J M^-1 J^T, E = diag(compliance),
// b_i = J_i v* - r_i. Solved exactly by an active-set (principal pivoting) method; a slack cable
// (P_i = 0) only lets the length shrink or stay.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "engine/cable.h"

namespace cablelab {

struct TensionRow {
  const std::vector<BodyJacobian>* jacobian = nullptr;  ///< d length / d(x, y, theta)
  double targetRate = 0;   ///< r_i (m/s)
  double compliance = 0;   ///< E_ii (m/s per N s); 0 for rigid cables
};

struct TensionSolution {
  Eigen::VectorXd impulse;  ///< P (N s), >= 0, one per row
  int iterations = 0;       ///< active-set changes
  double residual = 0;      ///< max_i |min(P_i, w_i)| scaled by the row's effective mass
};

/// `velocity[b]` holds body b's predicted (x, y, theta) velocity v*; bodies give inverse masses.
TensionSolution solveTensions(std::span<const TensionRow> rows, std::span<const BodyState> bodies,
                              std::span<const Vec3> velocity);

/// Generalized velocity change -M^-1 J^T P of one row, added into `dv` (per body x, y, theta).
void applyTensionImpulse(const TensionRow& row, double impulse, std::span<const BodyState> bodies,
                         std::span<Vec3> dv);

}  // namespace cablelab
