// The complementarity problem behind the cable tensions (a small dense LCP, Eigen).
//
// All cables of a world are solved together: with tension impulses P >= 0 over a step the
// velocities become v = v* - W P (W = M'^-1 J^T), and each taut cable asks
//     rigid:   J_i v = r_i                       (r_i: target length rate)
//     elastic: J_i v = r_i + compliance_i P_i    (implicit spring-damper: a soft constraint)
// so that w = K P - b >= 0, P >= 0, P . w = 0 with K = J W + diag(compliance), b = J v* - r.
// A slack cable (P_i = 0) may only shorten. World::solveCableForces() assembles K and b.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/Core>
#include <vector>

namespace cablelab {

struct LcpSolution {
  Eigen::VectorXd x;    ///< the impulses P (N s), >= 0
  int iterations = 0;   ///< active-set changes
  double residual = 0;  ///< max_i |min(x_i K_ii, w_i)| (m/s)
};

/// Solves w = K x - b >= 0, x >= 0, x . w = 0 exactly for a symmetric positive (semi)definite K
/// by principal pivoting on the active set (converges in a few changes for these sizes).
LcpSolution solveLcp(const Eigen::MatrixXd& K, const Eigen::VectorXd& b);

/// solveLcp's buffers: reused across calls, the solve does not allocate once the sizes settle.
struct LcpWorkspace {
  Eigen::MatrixXd K, Ks;
  Eigen::VectorXd bs, xs, w;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;  ///< for a non-symmetric K (sliding capstans)
  std::vector<char> active;
  std::vector<int> idx;
};

/// The same solve, writing into `sol` and using `work` for every temporary.
void solveLcp(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, LcpWorkspace& work,
              LcpSolution& sol);

}  // namespace cablelab
