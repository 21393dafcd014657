// The inverse of a matrix made of 3x3 blocks on its diagonal alone, one body's (x, y, theta) each:
// a fixed-size inverse per block instead of a factorisation of the whole.
//
// The midpoint solver's iteration matrix A = M + h/4 sum P H couples two bodies only through a
// cable segment running straight from one to the other; an island whose segments all end on
// fixed points (an Atwood machine over its pulleys) has A block-diagonal. Eigen's LDLT of the
// dynamic n x n A (with a matrix right-hand side) was 40% of the step of 1024 such machines,
// then a fixed 3x3 LDLT per block 13% (docs/performance.md); a block's inverse (cofactors over
// the determinant, A may be indefinite: H's turning terms) costs a third of that, allocates
// nothing once sized, and gives the same solution to rounding (A is a Newton iteration matrix:
// its rounding moves the iterates, not what they settle to).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace cablelab {

class BlockDiagonalInverse {
 public:
  /// Inverts the 3x3 diagonal blocks of `a` (n x n, n a multiple of 3); the rest of `a` is taken
  /// as zero, unread.
  void compute(const Eigen::MatrixXd& a) {
    blocks_.resize(a.rows() / 3);
    for (size_t k = 0; k < blocks_.size(); ++k) {
      const Eigen::Index at = 3 * static_cast<Eigen::Index>(k);
      blocks_[k] = a.block<3, 3>(at, at).inverse();
    }
  }

  /// x = A^-1 b, column by column, block by block (b: n x any, or a vector).
  template <class Rhs, class Dst>
  void solve(const Eigen::MatrixBase<Rhs>& b, Eigen::PlainObjectBase<Dst>& x) const {
    x.resize(b.rows(), b.cols());
    for (Eigen::Index j = 0; j < b.cols(); ++j)
      for (size_t k = 0; k < blocks_.size(); ++k) {
        const Eigen::Index at = 3 * static_cast<Eigen::Index>(k);
        x.template block<3, 1>(at, j).noalias() = blocks_[k] * b.template block<3, 1>(at, j);
      }
  }

 private:
  std::vector<Eigen::Matrix3d> blocks_;
};

}  // namespace cablelab
