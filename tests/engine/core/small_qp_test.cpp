#include "engine/core/small_qp.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace cablelab {
namespace {

constexpr double kTolerance = 1e-9;

double objective(const Eigen::MatrixXd& H, const Eigen::VectorXd& f, const Eigen::VectorXd& x) {
  return 0.5 * x.dot(H * x) + f.dot(x);
}

/// The exact optimum by enumeration: every subset of constraints held as equalities, the best
/// feasible stationary point (a convex QP's optimum is one of them).
double bruteForceOptimum(const Eigen::MatrixXd& H, const Eigen::VectorXd& f,
                         const Eigen::MatrixXd& C, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(H.rows()), m = static_cast<int>(C.rows());
  double best = 1e300;
  for (int mask = 0; mask < (1 << m); ++mask) {
    std::vector<int> rows;
    for (int i = 0; i < m; ++i)
      if (mask & (1 << i)) rows.push_back(i);
    const int k = static_cast<int>(rows.size());
    if (k > n) continue;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + k, n + k);
    Eigen::VectorXd rhs(n + k);
    K.topLeftCorner(n, n) = H;
    rhs.head(n) = -f;
    for (int r = 0; r < k; ++r) {
      K.block(n + r, 0, 1, n) = C.row(rows[r]);
      K.block(0, n + r, n, 1) = -C.row(rows[r]).transpose();
      rhs[n + r] = b[rows[r]];
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd x = lu.solve(rhs).head(n);
    if (((C * x - b).array() < -1e-9).any()) continue;
    best = std::min(best, objective(H, f, x));
  }
  return best;
}

TEST(SmallQp, ProjectionOntoABoxIsTheClampedPoint) {
  // minimise |x - y|^2 / 2 with lower <= x <= upper: x = clamp(y).
  const Eigen::Vector4d y(2.0, -3.0, 0.5, 0.9), lower(-1, -1, -1, -1), upper(1, 1, 1, 0.8);
  Eigen::MatrixXd C(8, 4);
  Eigen::VectorXd b(8);
  C << Eigen::Matrix4d::Identity(), -Eigen::Matrix4d::Identity();
  b << lower, -upper;
  const SmallQpResult r =
      solveSmallQp(Eigen::Matrix4d::Identity(), -y, C, b, Eigen::Vector4d::Zero());
  ASSERT_TRUE(r.converged);
  const Eigen::Vector4d clamped = y.cwiseMax(lower).cwiseMin(upper);
  EXPECT_LT((r.x - clamped).norm(), kTolerance) << r.x.transpose();
  // The multipliers are the pull of the objective on the active bounds: |y - x| per bound.
  EXPECT_NEAR(r.multipliers[0 + 4], 1.0, kTolerance);  // x0 at its upper bound, y0 - 1 = 1
  EXPECT_NEAR(r.multipliers[1], 2.0, kTolerance);      // x1 at its lower bound, -1 - y1 = 2
  EXPECT_NEAR(r.multipliers[3 + 4], 0.1, kTolerance);
}

TEST(SmallQp, RandomProblemsMeetKktAndTheEnumeratedOptimum) {
  std::mt19937 rng(13);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 5, m = 3 + trial % 6;
    Eigen::MatrixXd A(n, n), C(m, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
    const Eigen::MatrixXd H = A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd f(n), b(m);
    for (int i = 0; i < n; ++i) f[i] = 3 * normal(rng);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < n; ++j) C(i, j) = normal(rng);
      b[i] = -std::abs(normal(rng));  // x = 0 is feasible
    }
    if (trial % 7 == 0) C.row(m - 1) = C.row(0), b[m - 1] = b[0];  // a duplicated constraint
    const SmallQpResult r = solveSmallQp(H, f, C, b, Eigen::VectorXd::Zero(n));
    ASSERT_TRUE(r.converged) << "trial " << trial;
    const Eigen::VectorXd slack = C * r.x - b;
    EXPECT_GT(slack.minCoeff(), -kTolerance) << "trial " << trial;
    EXPECT_GE(r.multipliers.minCoeff(), 0.0);
    EXPECT_LT((H * r.x + f - C.transpose() * r.multipliers).norm(), 1e-8 * (1 + f.norm()))
        << "trial " << trial;
    EXPECT_LT(std::abs(r.multipliers.dot(slack)), 1e-8) << "trial " << trial;
    const double best = bruteForceOptimum(H, f, C, b);
    EXPECT_NEAR(objective(H, f, r.x), best, 1e-8 * (1 + std::abs(best))) << "trial " << trial;
  }
}

TEST(SmallQp, AnInfeasibleStartEndsAtTheFeasibleOptimum) {
  // x0 = 0 violates some constraints: the solver finds a feasible start itself and the same
  // optimum as the enumeration; where no point meets every constraint it reports the slack.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  int feasibleTrials = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 4, m = 2 + trial % 5;
    Eigen::MatrixXd A(n, n), C(m, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
    const Eigen::MatrixXd H = A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd f(n), b(m);
    for (int i = 0; i < n; ++i) f[i] = normal(rng);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < n; ++j) C(i, j) = normal(rng);
      b[i] = normal(rng);
    }
    const SmallQpResult r = solveSmallQp(H, f, C, b, Eigen::VectorXd::Zero(n));
    ASSERT_TRUE(r.converged) << "trial " << trial;
    const double best = bruteForceOptimum(H, f, C, b);
    if (best == 1e300) {
      EXPECT_GT(r.slack, 1e-6) << "trial " << trial << ": no feasible point, yet no slack";
      continue;
    }
    ++feasibleTrials;
    EXPECT_GT((C * r.x - b).minCoeff(), -kTolerance) << "trial " << trial;
    EXPECT_NEAR(objective(H, f, r.x), best, 1e-7 * (1 + std::abs(best))) << "trial " << trial;
  }
  EXPECT_GT(feasibleTrials, 100);
}

}  // namespace
}  // namespace cablelab
