// A dense convex QP with inequality constraints, for problems of a few variables (the hand
// controller's bounded joint steps: 6 joints, a dozen constraints):
//
//   minimise 1/2 x^T H x + f^T x   subject to   C x >= b,
//
// H symmetric positive definite (n x n), C (m x n), b (m). Primal active set (Nocedal & Wright,
// Numerical Optimization, algorithm 16.3) from a feasible start (or an elastic one): every
// iterate stays feasible, so a step cut short still respects the constraints. Each working-set
// subproblem is solved in the null space of the working rows (a rank-revealing QR, so dependent
// rows do no harm).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace cablelab {

struct SmallQpResult {
  Eigen::VectorXd x;            ///< the minimiser (n)
  Eigen::VectorXd multipliers;  ///< lambda >= 0 per constraint (m), zero for inactive ones:
                                ///< H x + f = C^T lambda at the optimum
  std::vector<int> active;      ///< the working set at the end (constraint indices)
  double slack = 0;  ///< how far every constraint had to be relaxed (0 when they can be met)
  int iterations = 0;
  bool converged = false;  ///< KKT conditions met within the iteration budget
};

/// Solves the QP above from x0. When x0 violates a constraint a first phase finds a feasible start
/// (the least slack s >= 0 with C x + s >= b, near x0); if the constraints cannot all be met the
/// result meets them relaxed by that slack (reported).
SmallQpResult solveSmallQp(const Eigen::MatrixXd& H, const Eigen::VectorXd& f,
                           const Eigen::MatrixXd& C, const Eigen::VectorXd& b,
                           const Eigen::VectorXd& x0, int maxIterations = 100);

}  // namespace cablelab
