// The joint projection of the cable solver (joint_projection.h; docs/model.md for the equations).
#include "engine/dynamics/joint_projection.h"

#include <numeric>

#include "engine/dynamics/disjoint_sets.h"

namespace cablelab {

namespace {

// Rounding guard on S's diagonal: redundant joint rows (a closed loop) make S singular.
void regularise(Eigen::Ref<Eigen::MatrixXd> S) {
  S.diagonal().array() += 1e-10 * (1 + S.diagonal().array());
}

}  // namespace

// L D L^T without pivoting, in place in A's lower triangle (L's unit diagonal implied): S is
// positive definite once regularised, and a pivot that rounding still makes <= 0 (redundant
// rows) gets no inverse, as a rank-deficient LDLT would. Eigen's LDLT costs more than the whole
// projection at a finger's 6 x 6.
void SmallLdlt::factor(Eigen::MatrixXd& A) {
  const int n = static_cast<int>(A.rows());
  if (d.size() != n) d.resize(n), dInv.resize(n), work.resize(n);
  double* l = A.data();
  double* dl = work.data();
  for (int j = 0; j < n; ++j) {
    // Row j of L times D, once: every entry of column j below needs it.
    double dj = l[j + j * n];
    for (int k = 0; k < j; ++k) {
      dl[k] = l[j + k * n] * d[k];
      dj -= l[j + k * n] * dl[k];
    }
    d[j] = dj;
    dInv[j] = dj > 0 ? 1.0 / dj : 0.0;
    for (int i = j + 1; i < n; ++i) {
      double v = l[i + j * n];
      for (int k = 0; k < j; ++k) v -= l[i + k * n] * dl[k];
      l[i + j * n] = v * dInv[j];
    }
  }
}

// All columns together: each column's substitutions are a chain of dependent multiply-adds, so
// interleaving them keeps the pipeline full.
void SmallLdlt::solveInPlace(const Eigen::MatrixXd& A, Eigen::MatrixXd& B) const {
  const int n = static_cast<int>(A.rows()), cols = static_cast<int>(B.cols());
  const double* l = A.data();
  double* x = B.data();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < i; ++k) {
      const double lik = l[i + k * n];
      for (int c = 0; c < cols; ++c) x[i + c * n] -= lik * x[k + c * n];
    }
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < cols; ++c) x[i + c * n] *= dInv[i];
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k < n; ++k) {
      const double lki = l[k + i * n];
      for (int c = 0; c < cols; ++c) x[i + c * n] -= lki * x[k + c * n];
    }
}

// Rows sharing a body are in one block (union-find over rows, through the first row per body),
// listed in row order within each block.
void JointProjection::findBlocks(std::span<const JointRow> rows, int dofs) {
  const int c = static_cast<int>(rows.size());
  // The same rows on the same dofs as last time (every sub-step of a world whose joints and
  // island do not change): the same blocks.
  bool same = static_cast<int>(lastDofs.size()) == c && lastDofCount == dofs;
  for (int r = 0; same && r < c; ++r) same = lastDofs[r] == rows[r].dof;
  if (same) return;
  lastDofCount = dofs;
  lastDofs.resize(c);
  for (int r = 0; r < c; ++r) lastDofs[r] = rows[r].dof;
  parent.resize(c);
  std::iota(parent.begin(), parent.end(), 0);
  rowOfBody.assign(dofs / 3, -1);
  for (int r = 0; r < c; ++r)
    for (int d : rows[r].dof) {
      if (d < 0) continue;
      int& first = rowOfBody[d / 3];
      if (first < 0) {
        first = r;
      } else {
        unite(parent, first, r);
      }
    }
  blockOfRoot.assign(c, -1);
  start.assign(1, 0);
  for (int r = 0; r < c; ++r) {
    int& block = blockOfRoot[findRoot(parent, r)];
    if (block < 0) block = static_cast<int>(start.size()) - 1, start.push_back(0);
    ++start[block + 1];
  }
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  fill.assign(start.begin(), start.end() - 1);
  order.resize(c);
  for (int r = 0; r < c; ++r) order[fill[blockOfRoot[findRoot(parent, r)]]++] = r;
}

void JointProjection::projectDiagonal(std::span<const JointRow> rows, const Eigen::VectorXd& invM,
                                      Eigen::MatrixXd& W, Eigen::VectorXd& vStar) {
  const int c = static_cast<int>(rows.size()), m = static_cast<int>(W.cols());
  const Eigen::Index n = W.rows();
  findBlocks(rows, static_cast<int>(n));
  // M'^-1 C^T, row by row: each row's coefficients scaled by its dofs' inverse masses.
  scaled.resize(c);
  for (int r = 0; r < c; ++r)
    for (int k = 0; k < 2; ++k)
      scaled[r][k] = rows[r].dof[k] >= 0
                         ? Vec3(rows[r].coeff[k].cwiseProduct(invM.segment<3>(rows[r].dof[k])))
                         : Vec3(Vec3::Zero());
  const int blocks = static_cast<int>(start.size()) - 1;
  for (int b = 0; b < blocks; ++b) {
    const int first = start[b], size = start[b + 1] - first;
    const int* index = order.data() + first;
    // The lower triangle of S's block (the factorisation reads only that): rows meet on shared
    // dofs. Then C W and C v* + bias, one column each (the last is v*'s).
    if (blockS.rows() != size) blockS.resize(size, size);
    if (blockSolution.rows() != size || blockSolution.cols() != m + 1)
      blockSolution.resize(size, m + 1);
    for (int i = 0; i < size; ++i) {
      const JointRow& ri = rows[index[i]];
      for (int j = 0; j <= i; ++j) {
        const JointRow& rj = rows[index[j]];
        double sum = 0;
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l)
            if (ri.dof[k] >= 0 && ri.dof[k] == rj.dof[l])
              sum += scaled[index[i]][k].dot(rj.coeff[l]);
        blockS(i, j) = sum;
      }
      for (int s = 0; s < m; ++s) {
        const double* w = W.data() + s * n;
        double sum = 0;
        for (int k = 0; k < 2; ++k)
          if (ri.dof[k] >= 0) sum += ri.coeff[k].dot(Eigen::Map<const Vec3>(w + ri.dof[k]));
        blockSolution(i, s) = sum;
      }
      double cv = ri.bias;
      for (int k = 0; k < 2; ++k)
        if (ri.dof[k] >= 0) cv += ri.coeff[k].dot(vStar.segment<3>(ri.dof[k]));
      blockSolution(i, m) = cv;
    }
    regularise(blockS);
    ldlt.factor(blockS);
    ldlt.solveInPlace(blockS, blockSolution);
    // W -= M'^-1 C^T S^-1 C W (and v*): each row adds to its own few dofs.
    for (int i = 0; i < size; ++i) {
      const JointRow& row = rows[index[i]];
      for (int k = 0; k < 2; ++k) {
        if (row.dof[k] < 0) continue;
        const Vec3& push = scaled[index[i]][k];
        for (int s = 0; s < m; ++s) W.block<3, 1>(row.dof[k], s) -= push * blockSolution(i, s);
        vStar.segment<3>(row.dof[k]) -= push * blockSolution(i, m);
      }
    }
  }
}

void JointProjection::projectDense(
    std::span<const JointRow> rows,
    const std::function<void(Eigen::Ref<Eigen::MatrixXd>)>& applyInverseMass, Eigen::MatrixXd& W,
    Eigen::VectorXd& vStar) {
  const int n = static_cast<int>(W.rows()), c = static_cast<int>(rows.size());
  const int m = static_cast<int>(W.cols());
  MinvCt.setZero(n, c);
  for (int r = 0; r < c; ++r)
    for (int k = 0; k < 2; ++k)
      if (rows[r].dof[k] >= 0) MinvCt.block<3, 1>(rows[r].dof[k], r) += rows[r].coeff[k];
  applyInverseMass(MinvCt);
  // S is symmetric and the LDLT reads its lower triangle only.
  S.resize(c, c);
  for (int r = 0; r < c; ++r)
    for (int s = 0; s <= r; ++s) S(r, s) = rows[r].dot(MinvCt.col(s));
  regularise(S);
  schur.compute(S);

  // A few columns (one per cable, then v*): column by column is cheaper than the blocked solve.
  CW.resize(c, m);
  schurCW.resize(c, m);
  for (int s = 0; s < m; ++s) {
    for (int r = 0; r < c; ++r) CW(r, s) = rows[r].dot(W.col(s));
    schurCW.col(s) = schur.solve(CW.col(s));
  }
  correction.noalias() = MinvCt.lazyProduct(schurCW);
  W -= correction;

  Cv.resize(c);
  for (int r = 0; r < c; ++r) Cv[r] = rows[r].dot(vStar) + rows[r].bias;
  schurCv = schur.solve(Cv);
  velocityCorrection.noalias() = MinvCt * schurCv;
  vStar -= velocityCorrection;
}

}  // namespace cablelab
