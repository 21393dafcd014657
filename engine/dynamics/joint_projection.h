// Stage 4 of the cable solver (cable_solver.h): W = M'^-1 J^T and v* restricted to what Box2D's
// joints allow, through the Schur complement S = C M'^-1 C^T of the joint rows C:
//     W <- W - M'^-1 C^T S^-1 C W,   v* <- v* - M'^-1 C^T S^-1 (C v* + bias).
// With a diagonal M' (no geometric stiffness, the usual case) S only couples rows that share a
// body, so it is block diagonal: one block per jointed chain (a hand finger), each factored on
// its own, and every product with C or M'^-1 C^T goes through the rows' few non-zeros. A coupled
// M' takes the dense path. Private to engine/dynamics.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <array>
#include <functional>
#include <span>
#include <vector>

#include "engine/core/math.h"

namespace cablelab {

/// One row of the joint Jacobian C: the relative motion of at most two bodies (dof -1: none).
/// C has n columns but only 2-6 non-zeros per row, so products with C go through these.
struct JointRow {
  std::array<int, 2> dof{-1, -1};
  std::array<Vec3, 2> coeff{Vec3::Zero(), Vec3::Zero()};
  double bias = 0;  ///< the row's rate from bodies that are not dofs (kinematic: prescribed motion)

  /// This row times the dense column x.
  double dot(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    double sum = 0;
    for (int k = 0; k < 2; ++k)
      if (dof[k] >= 0) sum += coeff[k].dot(x.segment<3>(dof[k]));
    return sum;
  }
};

/// A small dense symmetric positive definite factorisation, in place (joint_projection.cpp).
struct SmallLdlt {
  Eigen::VectorXd d, dInv, work;
  void factor(Eigen::MatrixXd& A);  ///< A's lower triangle becomes L (unit diagonal implied)
  void solveInPlace(const Eigen::MatrixXd& A, Eigen::MatrixXd& B) const;
};

/// The projection's buffers, reused across sub-steps (no allocation once the sizes settle).
class JointProjection {
 public:
  /// M'^-1 = diag(invM) (0: the dof does not move): block by block, sparse products.
  void projectDiagonal(std::span<const JointRow> rows, const Eigen::VectorXd& invM,
                       Eigen::MatrixXd& W, Eigen::VectorXd& vStar);
  /// Any M'^-1, given as X <- M'^-1 X: one dense S.
  void projectDense(std::span<const JointRow> rows,
                    const std::function<void(Eigen::Ref<Eigen::MatrixXd>)>& applyInverseMass,
                    Eigen::MatrixXd& W, Eigen::VectorXd& vStar);

 private:
  void findBlocks(std::span<const JointRow> rows, int dofs);

  // Blocks of S: rows connected through shared bodies; block b is order[start[b], start[b+1]).
  std::vector<int> parent, rowOfBody, blockOfRoot, order, start, fill;
  std::vector<std::array<int, 2>> lastDofs;  // the rows' dofs the blocks were found for
  int lastDofCount = -1;
  std::vector<std::array<Vec3, 2>> scaled;  // M'^-1 C^T by rows
  SmallLdlt ldlt;
  Eigen::MatrixXd blockS, blockSolution;
  // The dense path.
  Eigen::MatrixXd MinvCt, S, CW, schurCW, correction;
  Eigen::VectorXd Cv, schurCv, velocityCorrection;  // Cv includes each row's bias
  Eigen::LDLT<Eigen::MatrixXd> schur;
};

}  // namespace cablelab
