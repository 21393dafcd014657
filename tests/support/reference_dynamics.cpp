#include "tests/support/reference_dynamics.h"

#include <Eigen/Dense>

namespace cablelab {

ConstrainedAcceleration constrainedAcceleration(const Eigen::MatrixXd& H, const Eigen::MatrixXd& J,
                                                const Eigen::VectorXd& jdotV,
                                                const Eigen::VectorXd& force) {
  const Eigen::LDLT<Eigen::MatrixXd> Hinv(H);
  const Eigen::MatrixXd HinvJt = Hinv.solve(J.transpose());
  const Eigen::MatrixXd A = J * HinvJt;
  // Pseudo-inverse: redundant constraints (rank-deficient J) still get a consistent lambda.
  const Eigen::MatrixXd Apinv = A.completeOrthogonalDecomposition().pseudoInverse();
  ConstrainedAcceleration out;
  out.lambda = -Apinv * (J * Hinv.solve(force) + jdotV);
  out.qdd = Hinv.solve(force + J.transpose() * out.lambda);
  return out;
}

}  // namespace cablelab
