// The LDLT of a matrix made of 3x3 blocks on its diagonal alone, one body's (x, y, theta) each:
// a fixed-size factorisation per block instead of one of the whole.
//
// The midpoint solver's iteration matrix A = M + h/4 sum P H couples two bodies only through a
// cable segment running straight from one to the other; an island whose segments all end on
// fixed points (an Atwood machine over its pulleys) has A block-diagonal. Eigen's LDLT of the
// dynamic n x n A (with a matrix right-hand side) was 40% of the step of 1024 such machines
// (docs/performance.md); per block it costs what a fixed 3x3 factorisation does, allocates
// nothing once sized, and gives the same solution to rounding.
#pragma once

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace cablelab {

class BlockDiagonalLdlt {
 public:
  /// Factors the 3x3 diagonal blocks of `a` (n x n, n a multiple of 3); the rest of `a` is taken
  /// as zero, unread.
  void compute(const Eigen::MatrixXd& a) {
    blocks_.resize(a.rows() / 3);
    for (size_t k = 0; k < blocks_.size(); ++k) blocks_[k].compute(a.block<3, 3>(3 * k, 3 * k));
  }

  /// x = A^-1 b, column by column, block by block (b: n x any, or a vector).
  template <class Rhs, class Dst>
  void solve(const Eigen::MatrixBase<Rhs>& b, Eigen::PlainObjectBase<Dst>& x) const {
    x.resize(b.rows(), b.cols());
    for (Eigen::Index j = 0; j < b.cols(); ++j)
      for (size_t k = 0; k < blocks_.size(); ++k) {
        const Eigen::Index at = 3 * static_cast<Eigen::Index>(k);
        x.template block<3, 1>(at, j) = blocks_[k].solve(b.template block<3, 1>(at, j));
      }
  }

 private:
  std::vector<Eigen::LDLT<Eigen::Matrix3d>> blocks_;
};

}  // namespace cablelab
