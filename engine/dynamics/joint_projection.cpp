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

// The same on a column-major n x n array.
void regularise(double* S, int n) {
  for (int i = 0; i < n; ++i) S[i + i * n] += 1e-10 * (1 + S[i + i * n]);
}

// L D L^T without pivoting, in place in the lower triangle of the column-major n x n array l.
// kN > 0: n is that constant (the loops unroll); 0: n = runtimeN. The solve has no unroll
// pragmas: with them GCC 12 -O3 gets n = 3 with several columns wrong (SmallLdlt's test).

template <int kN>
void factorLdlt(double* l, int runtimeN, double* d, double* dInv, double* dl) {
  const int n = kN > 0 ? kN : runtimeN;
#pragma GCC unroll 8
  for (int j = 0; j < n; ++j) {
    // Row j of L times D, once: every entry of column j below needs it.
    double dj = l[j + j * n];
#pragma GCC unroll 8
    for (int k = 0; k < j; ++k) {
      dl[k] = l[j + k * n] * d[k];
      dj -= l[j + k * n] * dl[k];
    }
    d[j] = dj;
    dInv[j] = dj > 0 ? 1.0 / dj : 0.0;
#pragma GCC unroll 8
    for (int i = j + 1; i < n; ++i) {
      double v = l[i + j * n];
#pragma GCC unroll 8
      for (int k = 0; k < j; ++k) v -= l[i + k * n] * dl[k];
      l[i + j * n] = v * dInv[j];
    }
  }
}

template <int kN>
void solveLdlt(const double* l, int runtimeN, const double* dInv, double* x, int cols) {
  const int n = kN > 0 ? kN : runtimeN;
  for (int c = 0; c < cols; ++c, x += n) {
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < i; ++k) x[i] -= l[i + k * n] * x[k];
    for (int i = 0; i < n; ++i) x[i] *= dInv[i];
    for (int i = n - 1; i >= 0; --i)
      for (int k = i + 1; k < n; ++k) x[i] -= l[k + i * n] * x[k];
  }
}

}  // namespace

void SmallLdlt::factor(double* a, int n) {
  if (static_cast<int>(d.size()) < n) d.resize(n), dInv.resize(n), work.resize(n);
  withFixedSize(n, [&]<int kN>() { factorLdlt<kN>(a, n, d.data(), dInv.data(), work.data()); });
}

void SmallLdlt::solveInPlace(const double* a, int n, double* x, int cols) const {
  withFixedSize(n, [&]<int kN>() { solveLdlt<kN>(a, n, dInv.data(), x, cols); });
}

namespace {

// Builds the rows of one joint: the relative velocity of its anchor point along a direction, or
// its bodies' relative turn.
class JointRowBuilder {
 public:
  JointRowBuilder(const JointFrame& joint, std::span<const BodyState> bodies,
                  std::span<const int> dofOfBody)
      : a_(joint.bodyA), b_(joint.bodyB) {
    da_ = a_ >= 0 ? dofOfBody[a_] : -1;
    db_ = b_ >= 0 ? dofOfBody[b_] : -1;
    rA_ = a_ >= 0 ? Vec2(joint.anchor - bodies[a_].position) : Vec2::Zero();
    rB_ = b_ >= 0 ? Vec2(joint.anchor - bodies[b_].position) : Vec2::Zero();
    vA_ = prescribed(bodies, a_, da_);
    vB_ = prescribed(bodies, b_, db_);
  }
  bool onDofs() const { return da_ >= 0 || db_ >= 0; }
  JointRow point(const Vec2& t) const {
    return row(Vec3(t.x(), t.y(), t.dot(perp(rB_))), -Vec3(t.x(), t.y(), t.dot(perp(rA_))));
  }
  JointRow turn() const { return row(Vec3(0, 0, 1), Vec3(0, 0, -1)); }

 private:
  // A body that is not a dof enters through its prescribed velocity (the row's bias).
  static Vec3 prescribed(std::span<const BodyState> bodies, int body, int dof) {
    if (body < 0 || dof >= 0) return Vec3::Zero();
    const BodyState& s = bodies[body];
    return Vec3(s.velocity.x(), s.velocity.y(), s.angularVelocity);
  }
  JointRow row(const Vec3& cb, const Vec3& ca) const {
    JointRow r;
    r.dof = {db_, da_};
    r.coeff = {cb, ca};
    r.bias = cb.dot(vB_) + ca.dot(vA_);
    return r;
  }
  int a_, b_, da_ = -1, db_ = -1;
  Vec2 rA_, rB_;
  Vec3 vA_, vB_;
};

}  // namespace

JointRow coordinateRow(const JointFrame& joint, std::span<const BodyState> bodies,
                       std::span<const int> dofOfBody) {
  const JointRowBuilder build(joint, bodies, dofOfBody);
  return joint.kind == JointDef::Kind::Prismatic ? build.point(joint.axis) : build.turn();
}

void appendJointRows(const JointFrame& joint, std::span<const BodyState> bodies,
                     std::span<const int> dofOfBody, std::vector<JointRow>& rows,
                     std::optional<double> lock) {
  const JointRowBuilder build(joint, bodies, dofOfBody);
  if (!build.onDofs()) return;
  switch (joint.kind) {
    case JointDef::Kind::Revolute:
      rows.push_back(build.point(Vec2(1, 0)));
      rows.push_back(build.point(Vec2(0, 1)));
      break;
    case JointDef::Kind::Prismatic:
      rows.push_back(build.point(perp(joint.axis)));
      rows.push_back(build.turn());
      break;
    case JointDef::Kind::Weld:
      rows.push_back(build.point(Vec2(1, 0)));
      rows.push_back(build.point(Vec2(0, 1)));
      rows.push_back(build.turn());
      break;
  }
  if (lock && joint.kind != JointDef::Kind::Weld) {
    // dot(v) + bias = *lock: the coordinate moves at the locked rate.
    rows.push_back(coordinateRow(joint, bodies, dofOfBody));
    rows.back().bias -= *lock;
  }
}

// Rows sharing a body are in one block (union-find over rows, through the first row per body),
// listed in row order within each block.
void JointProjection::findBlocks(std::span<const JointRow> rows, int dofs) {
  const int c = static_cast<int>(rows.size());
  // The same rows on the same dofs as last time (every sub-step of a world whose joints and
  // island do not change): the same blocks.
  bool same = static_cast<int>(lastDofs.size()) == c && lastDofCount == dofs;
  for (int r = 0; same && r < c; ++r)  // element by element: std::array's == is a memcmp call
    same = lastDofs[r][0] == rows[r].dof[0] && lastDofs[r][1] == rows[r].dof[1];
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
  // S's terms: rows meet on shared dofs.
  terms.clear();
  termStart.assign(1, 0);
  for (size_t b = 0; b + 1 < start.size(); ++b) {
    const int first = start[b], size = start[b + 1] - first;
    for (int i = 0; i < size; ++i)
      for (int j = 0; j <= i; ++j) {
        const int ri = order[first + i], rj = order[first + j];
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l)
            if (rows[ri].dof[k] >= 0 && rows[ri].dof[k] == rows[rj].dof[l])
              terms.push_back({i + j * size, ri, rj, k, l});
      }
    termStart.push_back(static_cast<int>(terms.size()));
  }
}

void JointProjection::projectDiagonal(std::span<const JointRow> rows, const Eigen::VectorXd& invM,
                                      Eigen::MatrixXd& W, Eigen::VectorXd& vStar,
                                      Eigen::MatrixXd* multipliers) {
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
  const int cols = m + 1;  // C W, then C v* + bias
  if (multipliers) multipliers->resize(c, cols);
  for (int b = 0; b < blocks; ++b) {
    const int first = start[b], size = start[b + 1] - first;
    const int* index = order.data() + first;
    // The lower triangle of S's block (the factorisation reads only that).
    blockS.assign(static_cast<size_t>(size) * size, 0.0);
    for (int t = termStart[b]; t < termStart[b + 1]; ++t) {
      const Term& term = terms[t];
      blockS[term.entry] += scaled[term.ri][term.k].dot(rows[term.rj].coeff[term.l]);
    }
    // The right-hand sides, column after column: C W, then C v* + bias.
    blockSolution.resize(static_cast<size_t>(size) * cols);
    for (int i = 0; i < size; ++i) {
      const JointRow& ri = rows[index[i]];
      for (int s = 0; s < m; ++s) {
        const double* w = W.data() + s * n;
        double sum = 0;
        for (int k = 0; k < 2; ++k)
          if (ri.dof[k] >= 0) sum += ri.coeff[k].dot(Eigen::Map<const Vec3>(w + ri.dof[k]));
        blockSolution[i + s * size] = sum;
      }
      double cv = ri.bias;
      for (int k = 0; k < 2; ++k)
        if (ri.dof[k] >= 0) cv += ri.coeff[k].dot(vStar.segment<3>(ri.dof[k]));
      blockSolution[i + m * size] = cv;
    }
    regularise(blockS.data(), size);
    ldlt.factor(blockS.data(), size);
    ldlt.solveInPlace(blockS.data(), size, blockSolution.data(), cols);
    if (multipliers)
      for (int i = 0; i < size; ++i)
        for (int s = 0; s < cols; ++s) (*multipliers)(index[i], s) = blockSolution[i + s * size];
    // W -= M'^-1 C^T S^-1 C W (and v*): each row adds to its own few dofs.
    for (int i = 0; i < size; ++i) {
      const JointRow& row = rows[index[i]];
      for (int k = 0; k < 2; ++k) {
        if (row.dof[k] < 0) continue;
        const Vec3& push = scaled[index[i]][k];
        for (int s = 0; s < m; ++s)
          W.block<3, 1>(row.dof[k], s) -= push * blockSolution[i + s * size];
        vStar.segment<3>(row.dof[k]) -= push * blockSolution[i + m * size];
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
