// Sensitivity of the statics equilibrium to the fingertip points (feeds the Jacobian
// controller of thesis section 4.3: d b / d p_ij).
//
// At a smooth minimiser p* the optimality condition g(p*, theta) = dE/dp = 0 holds for the
// fingertip coordinates theta, so by implicit differentiation
//   d p* / d theta = -H^-1 d g / d theta,   H = d2E/dp2 at p*,
// with, for a taut cable i of tension T_i and unit vectors u_a = (p - a_i)/|p - a_i|, u_b:
//   d g / d a_i = -k_i (u_a + u_b) u_a^T - T_i (I - u_a u_a^T) / |p - a_i|   (same for b_i).
// Slack cables contribute nothing. Analytic throughout; no finite differences.
#pragma once

#include <Eigen/Core>

#include "engine/statics/statics.h"

namespace cablelab {

struct StaticsSensitivity {
  enum class Kind {
    Smooth,       ///< p* off every fingertip with a positive definite Hessian: exact derivative
    OnFingertip,  ///< p* is a fingertip point that strictly absorbs the net force: p* follows
                  ///< that fingertip (identity columns), every other column is zero
    Singular,     ///< non-unique minimiser or non-strict kink: a least-squares (pseudo-inverse)
                  ///< answer, or zeros; the derivative does not exist
  };
  /// 2 x 4N: columns a_i.x, a_i.y, b_i.x, b_i.y for cable i = 0..N-1 (m/m, dimensionless).
  Eigen::Matrix<double, 2, Eigen::Dynamic> dp;
  Kind kind = Kind::Smooth;
};

/// d p* / d (a_i, b_i) at the minimiser p (from any solver).
StaticsSensitivity staticsSensitivity(const StaticsProblem& problem, const Vec2& p);

}  // namespace cablelab
