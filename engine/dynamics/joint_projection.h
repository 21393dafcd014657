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
#include <optional>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/core/math.h"
#include "engine/dynamics/box2d_bridge.h"

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

/// Appends the velocity-level rows of one Box2D joint among an island's dofs (`dofOfBody`: body
/// -> first dof, -1 if not a dof), the constrained relative motions: revolute, the anchor points
/// move together (2 rows); prismatic, no motion across the axis and no relative turn (2); weld,
/// all three. A `lock` (joint_limits.h: a limit the step would cross) adds the coordinate's row,
/// its rate held at *lock. Motors are left to Box2D. A body that is not a dof enters through its
/// prescribed velocity (the rows' bias); a joint on no dof adds nothing.
void appendJointRows(const JointFrame& joint, std::span<const BodyState> bodies,
                     std::span<const int> dofOfBody, std::vector<JointRow>& rows,
                     std::optional<double> lock = std::nullopt);

/// The rate of a revolute or prismatic joint's coordinate (its relative turn; its slide along
/// the axis, as Box2D's GetJointSpeed) as a row: dot(v) + bias, bias from bodies that are not
/// dofs. Dof -1 on both sides if neither body is a dof.
JointRow coordinateRow(const JointFrame& joint, std::span<const BodyState> bodies,
                       std::span<const int> dofOfBody);

/// A small dense symmetric positive definite factorisation L D L^T without pivoting, in place in
/// a column-major n x n array's lower triangle (L's unit diagonal implied). A pivot that rounding
/// makes <= 0 (redundant rows) gets no inverse, as a rank-deficient LDLT would. Blocks up to
/// kFixedBlock rows run loops of constant length, which the compiler unrolls: Eigen's LDLT costs
/// more than the whole projection at a finger's 6 x 6 (joint_projection.cpp).
struct SmallLdlt {
  static constexpr int kFixedBlock = 8;
  std::vector<double> d, dInv, work;
  void factor(double* a, int n);
  /// x <- A^-1 x for `cols` columns of length n stored one after the other.
  void solveInPlace(const double* a, int n, double* x, int cols) const;
};

/// Calls f.template operator()<N>() with n as the constant N up to SmallLdlt::kFixedBlock, N = 0
/// beyond (the loops then run to n).
template <class F>
void withFixedSize(int n, F&& f) {
  static_assert(SmallLdlt::kFixedBlock == 8);
  switch (n) {
    case 1:
      return f.template operator()<1>();
    case 2:
      return f.template operator()<2>();
    case 3:
      return f.template operator()<3>();
    case 4:
      return f.template operator()<4>();
    case 5:
      return f.template operator()<5>();
    case 6:
      return f.template operator()<6>();
    case 7:
      return f.template operator()<7>();
    case 8:
      return f.template operator()<8>();
    default:
      return f.template operator()<0>();
  }
}

/// The projection's buffers, reused across sub-steps (no allocation once the sizes settle).
class JointProjection {
 public:
  /// M'^-1 = diag(invM) (0: the dof does not move): block by block, sparse products. With
  /// `multipliers`, its row r gets S^-1 C W and S^-1 (C v* + bias) of row r (m + 1 columns, W
  /// and v* before the projection): row r's impulse for loads f on W's columns is -(last + f .
  /// the first m), negative where the row pulls its bodies together along -C^T.
  void projectDiagonal(std::span<const JointRow> rows, const Eigen::VectorXd& invM,
                       Eigen::MatrixXd& W, Eigen::VectorXd& vStar,
                       Eigen::MatrixXd* multipliers = nullptr);
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
  // Where S's lower triangle gets its terms: entry (i, j) of block b (rows order[start[b] + i]
  // and order[start[b] + j]) adds scaled[ri][k] . coeff[l] of row rj wherever dof k of ri is dof
  // l of rj. Terms of block b are terms[termStart[b], termStart[b + 1]).
  struct Term {
    int entry;  // i + j * size within the block
    int ri, rj;
    int k, l;
  };
  std::vector<Term> terms;
  std::vector<int> termStart;
  std::vector<std::array<Vec3, 2>> scaled;  // M'^-1 C^T by rows
  SmallLdlt ldlt;
  std::vector<double> blockS, blockSolution;  // one block's S and its right-hand sides
  // The dense path.
  Eigen::MatrixXd MinvCt, S, CW, schurCW, correction;
  Eigen::VectorXd Cv, schurCv, velocityCorrection;  // Cv includes each row's bias
  Eigen::LDLT<Eigen::MatrixXd> schur;
};

}  // namespace cablelab
