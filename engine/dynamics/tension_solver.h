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
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>
#include <vector>

namespace cablelab {

/// Pivots of an active set's LDLT below this share of the largest make it rank-deficient.
constexpr double kRankTolerance = 1e-9;

struct LcpSolution {
  Eigen::VectorXd x;           ///< the impulses P (N s), >= 0
  int iterations = 0;          ///< active-set changes
  bool rankDeficient = false;  ///< K was singular: least-squares targets, minimum-norm x
  double residual = 0;         ///< max_i |min(x_i K_ii, w_i)| (m/s)
};

/// Solves w = K x - b >= 0, x >= 0, x . w = 0 exactly for a symmetric positive (semi)definite K
/// by principal pivoting on the active set (converges in a few changes for these sizes).
///
/// Redundant cables make K singular (more taut cables than the bodies have freedoms, e.g. 28
/// rigid cables on one ring: rank 2 or 3). Then the tensions are not unique, and targets that
/// do not quite agree (float rounding of Box2D's poses, length corrections) have no exact
/// solution. For such redundant cables (solveLcp with `redundant`), a rank-deficient K (an LDLT
/// pivot below kRankTolerance of the largest) is solved
/// with b replaced by its projection onto the range of K (the least-squares part: the smallest
/// violation instead of an unbounded impulse) and K + eps I, eps tiny: of all tension
/// distributions that hold the bodies, the minimum-norm one, the limit of giving every cable
/// the same vanishing compliance (docs/model.md, "Redundant cables"). That problem is solved by
/// Lawson and Hanson's active-set method, which cannot cycle on nearly dependent rows.
LcpSolution solveLcp(const Eigen::MatrixXd& K, const Eigen::VectorXd& b);

/// The equal compliance (m/s per N s) that solveLcp's minimum-norm path adds to every row of a
/// redundant K with this diagonal: its answer x leaves each pulling row i at w_i = -c x_i, where
/// an exact solve leaves 0 (a tackle's block at its sheave: its rope 3.5e-7 m long each step).
double minimumNormCompliance(const Eigen::VectorXd& diagonal);

/// Whether the (pivoted) LDLT of a positive semidefinite matrix has a pivot below kRankTolerance
/// of the largest: the matrix is singular up to rounding (redundant rows).
bool rankDeficient(const Eigen::LDLT<Eigen::MatrixXd>& ldlt);

/// solveLcp's buffers: reused across calls, the solve does not allocate once the sizes settle.
struct LcpWorkspace {
  Eigen::MatrixXd K, Ks;
  Eigen::VectorXd bs, xs, w, projected, step;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;  ///< for a non-symmetric K (sliding capstans)
  bool symmetric = true;                    ///< K is (LDLT), else LU
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;  ///< rank-deficient active sets
  Eigen::MatrixXd plain, sub;  ///< a redundant K made symmetric; its pulling rows' block
  Eigen::VectorXd subB, subX;  ///< that block's targets and least-squares solution
  std::vector<char> pulling;   ///< the rows whose targets are made consistent
  std::vector<char> active, blocked;
  std::vector<int> idx;
};

/// The same solve, writing into `sol` and using `work` for every temporary. With
/// `redundant` (the cable solver's islands whose J0 W is singular), a rank-deficient K takes the
/// minimum-norm path described above; otherwise the exact principal pivoting always.
void solveLcp(const Eigen::MatrixXd& K, const Eigen::VectorXd& b, LcpWorkspace& work,
              LcpSolution& sol, bool redundant = false);

}  // namespace cablelab
