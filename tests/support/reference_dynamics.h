// Reference constrained dynamics in generalized coordinates (thesis equation 2.3), small and exact.
//
//   H qdd = f + J^T lambda,   J qdd + Jdot v = 0
//   lambda = -(J H^-1 J^T)^+ (J H^-1 f + Jdot v)
// (c(q, v) = 0 for planar rigid bodies in world coordinates, docs/model.md#conventions.) Used by
// the tests as the ground truth the Box2D bridge is checked against; not used when stepping a
// World.
#pragma once

#include <Eigen/Core>

namespace cablelab {

struct ConstrainedAcceleration {
  Eigen::VectorXd qdd;     ///< generalized accelerations (n)
  Eigen::VectorXd lambda;  ///< constraint forces (m); for a cable, -tension (J is d length/dq)
};

/// @param H      mass matrix (n x n), positive definite
/// @param J      constraint Jacobian (m x n)
/// @param jdotV  J-dot v (m)
/// @param force  generalized applied force B u (n)
ConstrainedAcceleration constrainedAcceleration(const Eigen::MatrixXd& H, const Eigen::MatrixXd& J,
                                                const Eigen::VectorXd& jdotV,
                                                const Eigen::VectorXd& force);

}  // namespace cablelab
