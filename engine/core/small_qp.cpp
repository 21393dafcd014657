#include "engine/core/small_qp.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace cablelab {

namespace {

constexpr double kFeasibilityWeight = 1e-8;  // phase 1: the pull towards x0 against the slack
constexpr int kFeasibilityPasses = 4;

/// The equality-constrained step: minimise 1/2 p^T H p + g^T p subject to C_W p = 0, in the null
/// space of the working rows (exactly zero once they span every direction). Returns p and the
/// working rows' multipliers, the least-squares solution of C_W^T lambda = g + H p.
void workingStep(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const Eigen::MatrixXd& CW,
                 Eigen::VectorXd& p, Eigen::VectorXd& lambda) {
  const Eigen::Index n = H.rows();
  if (CW.rows() == 0) {
    p = -H.ldlt().solve(g);
    lambda.resize(0);
    return;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(CW.transpose());
  const Eigen::Index rank = qr.rank();
  p = Eigen::VectorXd::Zero(n);
  if (rank < n) {
    const Eigen::MatrixXd Q = qr.householderQ();
    const Eigen::MatrixXd Z = Q.rightCols(n - rank);  // null space of C_W
    p = -Z * (Z.transpose() * H * Z).ldlt().solve(Z.transpose() * g);
  }
  lambda = CW.transpose().completeOrthogonalDecomposition().solve(g + H * p);
}

}  // namespace

SmallQpResult solveSmallQp(const Eigen::MatrixXd& H, const Eigen::VectorXd& f,
                           const Eigen::MatrixXd& C, const Eigen::VectorXd& b,
                           const Eigen::VectorXd& x0, int maxIterations) {
  const Eigen::Index n = H.rows(), m = C.rows();
  const double violation = m > 0 ? std::max(0.0, -(C * x0 - b).minCoeff()) : 0.0;
  if (violation > 1e-12 * (1 + b.cwiseAbs().maxCoeff())) {
    // Phase 1: a feasible start. One slack s >= 0 relaxes every constraint (C x + s >= b): the
    // least slack, with a faint pull (in H's metric) towards the previous point. The pull leaves
    // a slack of its own, smaller each pass (it pulls towards an ever nearer point).
    const double weight = kFeasibilityWeight / (1 + H.diagonal().cwiseAbs().maxCoeff());
    Eigen::MatrixXd He = Eigen::MatrixXd::Zero(n + 1, n + 1), Ce(m + 1, n + 1);
    He.topLeftCorner(n, n) = weight * H, He(n, n) = 1;
    Ce << C, Eigen::VectorXd::Ones(m), Eigen::RowVectorXd::Zero(n), 1;
    Eigen::VectorXd be(m + 1), xe(n + 1);
    be << b, 0;
    xe << x0, violation;
    SmallQpResult feasible;
    for (int pass = 0; pass < kFeasibilityPasses; ++pass) {
      const Eigen::VectorXd fe = -He * (Eigen::VectorXd(n + 1) << xe.head(n), 0).finished();
      feasible = solveSmallQp(He, fe, Ce, be, xe, maxIterations);
      const double previous = xe[n];
      xe = feasible.x;
      if (xe[n] < 1e-14 * (1 + b.cwiseAbs().maxCoeff()) || xe[n] > 0.5 * previous) break;
    }
    // Phase 2 from there (the slack it leaves, if any, is what the constraints cannot give).
    const Eigen::VectorXd start = feasible.x.head(n);
    const Eigen::VectorXd relaxed =
        (b - Eigen::VectorXd::Constant(m, feasible.x[n])).cwiseMin(C * start);
    SmallQpResult out = solveSmallQp(H, f, C, relaxed, start, maxIterations);
    out.slack = feasible.x[n];
    out.iterations += feasible.iterations;
    out.converged = out.converged && feasible.converged;
    return out;
  }
  SmallQpResult out;
  out.x = x0;
  out.multipliers = Eigen::VectorXd::Zero(m);
  // Scale of the problem for the stopping tests.
  const double scale = 1 + H.cwiseAbs().maxCoeff() * (1 + x0.norm()) + f.norm();
  const double multiplierTolerance = 1e-12 * scale;
  std::vector<int>& W = out.active;
  for (out.iterations = 0; out.iterations < maxIterations; ++out.iterations) {
    Eigen::MatrixXd CW(W.size(), C.cols());
    for (size_t k = 0; k < W.size(); ++k) CW.row(k) = C.row(W[k]);
    Eigen::VectorXd p, lambda;
    workingStep(H, H * out.x + f, CW, p, lambda);
    if (p.norm() <= 1e-12 * (1 + out.x.norm())) {
      // Stationary on the working set: optimal unless a constraint pulls the wrong way.
      Eigen::Index worst = -1;
      if (lambda.size() > 0 && lambda.minCoeff(&worst) < -multiplierTolerance) {
        W.erase(W.begin() + worst);
        continue;
      }
      out.multipliers.setZero();
      for (size_t k = 0; k < W.size(); ++k) out.multipliers[W[k]] = std::max(0.0, lambda[k]);
      out.converged = true;
      return out;
    }
    // Longest step along p that keeps every constraint outside the working set satisfied.
    double alpha = 1;
    int blocking = -1;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (std::find(W.begin(), W.end(), static_cast<int>(i)) != W.end()) continue;
      const double rate = C.row(i).dot(p);
      if (rate >= -1e-15 * C.row(i).norm() * p.norm()) continue;
      const double room = std::max(0.0, C.row(i).dot(out.x) - b[i]);
      if (room / -rate < alpha) alpha = room / -rate, blocking = static_cast<int>(i);
    }
    out.x += alpha * p;
    if (blocking >= 0) W.push_back(blocking);
  }
  return out;
}

}  // namespace cablelab
