// The tension LCP (engine/dynamics/tension_solver.h) against brute force over every active set,
// and the midpoint solver's helpers against the general code: its per-body inverse against
// Eigen's LDLT of the whole matrix, its held-start path points (step_chords.h) against
// lengthDiscreteGradient and cableLengthJacobian.
//
// w = K x - b >= 0, x >= 0, x . w = 0 with K = J W J^T + diag(compliance) symmetric positive
// semidefinite. Brute force tries every subset S as the taut set: x_S = K_SS^-1 b_S, x = 0
// elsewhere, and keeps the subset that satisfies the sign conditions. For a positive definite K
// that solution is unique. For a semidefinite K (rank-deficient J: more cables than body
// freedoms) x may not be unique, but w and the value 1/2 x'Kx - b'x are the same for every
// solution (it is a convex QP), and a solution with K_SS invertible exists whenever any does
// (a null direction of K_SS is one of K, so it can be followed until an entry of x hits zero).
#include "engine/dynamics/tension_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/dynamics/block_diagonal_inverse.h"
#include "engine/dynamics/step_chords.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct Lcp {
  MatrixXd K;
  VectorXd b;
};

// n cables on m body freedoms: J (n x m) random, W = M^-1 diagonal, b = J v* - r.
// m < n makes K rank-deficient unless compliance is added.
Lcp randomLcp(test::Random& rng, int n, int m, double compliance) {
  MatrixXd J(n, m);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < m; ++c) J(i, c) = rng.uniform(-1, 1);
  VectorXd invMass(m), v(m), r(n);
  for (int c = 0; c < m; ++c) invMass[c] = std::pow(10.0, rng.uniform(-2, 2));
  for (int c = 0; c < m; ++c) v[c] = rng.uniform(-1, 1);
  for (int i = 0; i < n; ++i) r[i] = rng.uniform(-0.5, 0.5);
  Lcp p;
  p.K = J * invMass.asDiagonal() * J.transpose();
  for (int i = 0; i < n; ++i) p.K(i, i) += compliance * rng.uniform(0, 1);
  p.b = J * v - r;
  return p;
}

// The solver adds 1e-12 (1 + K_ii) to the diagonal so that a row touching no moving body
// (K_ii = 0) stays solvable: it solves this LCP exactly, and so does the brute force below.
Lcp regularised(Lcp p) {
  for (int i = 0; i < p.K.rows(); ++i) p.K(i, i) += 1e-12 * (1 + p.K(i, i));
  return p;
}

// Round-off in K x - b.
double tolerance(const Lcp& p, const VectorXd& x) {
  return 1e-9 * (1 + p.b.lpNorm<Eigen::Infinity>() +
                 (p.K.cwiseAbs() * x.cwiseAbs()).lpNorm<Eigen::Infinity>());
}

// The complementary solution with K_SS invertible, if the LCP has one.
std::optional<VectorXd> bruteForce(const Lcp& p) {
  const int n = static_cast<int>(p.b.size());
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> s;
    for (int i = 0; i < n; ++i)
      if (mask & (1 << i)) s.push_back(i);
    VectorXd x = VectorXd::Zero(n);
    if (!s.empty()) {
      const int k = static_cast<int>(s.size());
      MatrixXd Ks(k, k);
      VectorXd bs(k);
      for (int r = 0; r < k; ++r) {
        bs[r] = p.b[s[r]];
        for (int c = 0; c < k; ++c) Ks(r, c) = p.K(s[r], s[c]);
      }
      Eigen::FullPivLU<MatrixXd> lu(Ks);
      lu.setThreshold(1e-10);
      if (lu.rank() < k) continue;
      const VectorXd xs = lu.solve(bs);
      for (int r = 0; r < k; ++r) x[s[r]] = xs[r];
    }
    const VectorXd w = p.K * x - p.b;
    const double tol = tolerance(p, x);
    if (x.minCoeff() >= -tol && w.minCoeff() >= -tol) return x;
  }
  return std::nullopt;
}

double value(const Lcp& p, const VectorXd& x) {
  return 0.5 * x.dot(p.K * x) - p.b.dot(x);
}

// The solver's answer satisfies the LCP, and agrees with brute force on w and the QP value
// (and on x itself when K is positive definite).
void expectSolves(const Lcp& original, const VectorXd& truth, bool unique,
                  const std::string& what) {
  const int n = static_cast<int>(original.b.size());
  const LcpSolution sol = solveLcp(original.K, original.b);
  const Lcp p = regularised(original);
  ASSERT_EQ(sol.x.size(), n) << what;
  ASSERT_TRUE(sol.x.allFinite()) << what;
  EXPECT_LT(sol.iterations, 4 * n + 10) << what << ": stopped at the iteration limit";
  const VectorXd w = p.K * sol.x - p.b;
  const double tol = tolerance(p, sol.x) + tolerance(p, truth);
  EXPECT_GE(sol.x.minCoeff(), 0.0) << what;
  EXPECT_GE(w.minCoeff(), -tol) << what;
  for (int i = 0; i < n; ++i)
    EXPECT_LE(std::abs(sol.x[i] * w[i]), tol * (1 + std::abs(sol.x[i]))) << what << " row " << i;
  const VectorXd wTruth = p.K * truth - p.b;
  EXPECT_LE((w - wTruth).lpNorm<Eigen::Infinity>(), tol) << what;
  EXPECT_NEAR(value(p, sol.x), value(p, truth), tol * (1 + truth.lpNorm<1>())) << what;
  if (unique) {
    EXPECT_LE((sol.x - truth).lpNorm<Eigen::Infinity>(), 1e-6 * (1 + truth.norm())) << what;
  }
}

TEST(TensionSolver, MatchesBruteForceOnPositiveDefiniteProblems) {
  test::Random rng(11);
  int taut = 0, slack = 0;
  for (int n = 1; n <= 6; ++n)
    for (int trial = 0; trial < 150; ++trial) {
      const Lcp p = randomLcp(rng, n, n + 2, 1e-3);  // more freedoms than cables: K invertible
      const auto truth = bruteForce(regularised(p));
      ASSERT_TRUE(truth) << "n " << n << " trial " << trial << ": a PD LCP always has a solution";
      for (int i = 0; i < n; ++i) ((*truth)[i] > 0 ? taut : slack)++;
      expectSolves(p, *truth, true, "n " + std::to_string(n) + " trial " + std::to_string(trial));
    }
  // The random problems exercise both sides of every complementarity pair.
  EXPECT_GT(taut, 500);
  EXPECT_GT(slack, 500);
}

TEST(TensionSolver, MatchesBruteForceOnRankDeficientProblems) {
  // More cables than body freedoms, rigid (no compliance): K = J W J^T is singular.
  test::Random rng(12);
  int solvable = 0, total = 0;
  for (int n = 2; n <= 6; ++n)
    for (int m = 1; m < n; ++m)
      for (int trial = 0; trial < 60; ++trial) {
        const Lcp p = randomLcp(rng, n, m, 0.0);
        ++total;
        const std::string what = "n " + std::to_string(n) + " m " + std::to_string(m) + " trial " +
                                 std::to_string(trial);
        if (!bruteForce(p)) {  // unbounded (a positive null direction pulls): still no NaN
          EXPECT_TRUE(solveLcp(p.K, p.b).x.allFinite()) << what;
          continue;
        }
        ++solvable;
        const auto truth = bruteForce(regularised(p));
        ASSERT_TRUE(truth) << what;
        expectSolves(p, *truth, false, what);
      }
  EXPECT_GT(solvable, total / 2) << "too few solvable problems to mean anything";
}

TEST(TensionSolver, DuplicateCablesShareTheTensionOfOne) {
  // Two copies of the same rigid cable: K = [[k, k], [k, k]], rank 1. Any split with
  // x0 + x1 = b/k solves it; brute force finds the one-cable answer.
  const double k = 2.5, bValue = 0.75;
  Lcp p{MatrixXd::Constant(2, 2, k), VectorXd::Constant(2, bValue)};
  const LcpSolution sol = solveLcp(p.K, p.b);
  EXPECT_NEAR(sol.x.sum(), bValue / k, 1e-9);
  EXPECT_GE(sol.x.minCoeff(), 0.0);
  expectSolves(p, *bruteForce(regularised(p)), false, "duplicate cables");
}

TEST(TensionSolver, ImmovableRowStaysSlackAndFinite) {
  // A cable between fixed points has K_ii = 0 (its row touches no moving body). With b_i <= 0
  // it is slack; the other cable is unaffected.
  Lcp p{MatrixXd::Zero(2, 2), VectorXd(2)};
  p.K(1, 1) = 4;
  p.b << -0.1, 2;
  const LcpSolution sol = solveLcp(p.K, p.b);
  ASSERT_TRUE(sol.x.allFinite());
  EXPECT_EQ(sol.x[0], 0.0);
  EXPECT_NEAR(sol.x[1], 0.5, 1e-9);
  // b_i = 0 on that row: any x_0 >= 0 solves it; the answer must still be finite and complementary.
  p.b[0] = 0;
  expectSolves(p, *bruteForce(regularised(p)), false, "immovable row, b = 0");
}

TEST(TensionSolver, WorkspaceGivesTheSameAnswerAsTheAllocatingSolve) {
  test::Random rng(13);
  LcpWorkspace work;
  LcpSolution reused;
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + trial % 6;
    const Lcp p = randomLcp(rng, n, 1 + trial % 7, trial % 2 ? 1e-3 : 0.0);
    solveLcp(p.K, p.b, work, reused);
    const LcpSolution fresh = solveLcp(p.K, p.b);
    EXPECT_EQ(reused.x, fresh.x) << trial;  // bitwise: the workspace holds no state
    EXPECT_EQ(reused.iterations, fresh.iterations) << trial;
  }
}

// The midpoint solver's per-body inverse (block_diagonal_inverse.h) solves what Eigen's LDLT
// of the whole matrix does, on random symmetric positive definite 3x3 blocks of 1..4 bodies with
// masses and inertias far apart, for a matrix and a vector right-hand side.
TEST(BlockDiagonalInverse, SolvesAsTheWholeMatrixLdltOnRandomPositiveDefiniteBlocks) {
  test::Random rng(36);
  BlockDiagonalInverse blocks;
  MatrixXd x;
  VectorXd y;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 3 * (1 + trial % 4);
    MatrixXd a = MatrixXd::Zero(n, n);
    for (int k = 0; k < n; k += 3) {
      Eigen::Matrix3d g;
      for (int i = 0; i < 9; ++i) g(i / 3, i % 3) = rng.uniform(-1, 1);
      const double scale = std::pow(10.0, rng.uniform(-3, 2));
      a.block<3, 3>(k, k) = scale * (g * g.transpose() + 0.05 * Eigen::Matrix3d::Identity());
    }
    MatrixXd b(n, 2);
    for (int i = 0; i < 2 * n; ++i) b(i % n, i / n) = rng.uniform(-1, 1);
    blocks.compute(a);
    blocks.solve(b, x);
    blocks.solve(b.col(1), y);
    const MatrixXd whole = Eigen::LDLT<MatrixXd>(a).solve(b);
    const double size = whole.lpNorm<Eigen::Infinity>();
    EXPECT_LE((x - whole).lpNorm<Eigen::Infinity>(), 1e-12 * size) << trial;
    EXPECT_LE((y - whole.col(1)).lpNorm<Eigen::Infinity>(), 1e-12 * size) << trial;
    EXPECT_LE((a * x - b).lpNorm<Eigen::Infinity>(), 1e-12 * (1 + a.norm() * size)) << trial;
  }
}

// StepChords (the midpoint solver's paths without circles, the start pose held over the Newton
// iterations) gives what the general functions give from the path at every iterate, to rounding:
// the discrete gradient and the end length, J at the end pose, the midpoint positions. Two moved
// bodies turned by up to 3 rad a step, one body on the path not moved, world points.
TEST(StepChords, MatchesTheGeneralDiscreteGradientAndJacobianAtEachIterate) {
  test::Random rng(37);
  StepChords chords;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<BodyState> q0(3);
    for (BodyState& b : q0) b.position = rng.point(-2, 2), b.angle = rng.uniform(-30, 30);
    std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, 0, rng.point(-0.3, 0.3)},
                                   {WrapPoint::Kind::Point, -1, rng.point(-3, 3)},
                                   {WrapPoint::Kind::Vertex, 1, rng.point(-0.5, 0.5)},
                                   {WrapPoint::Kind::Point, 2, rng.point(-0.3, 0.3)},
                                   {WrapPoint::Kind::Anchor, 1, rng.point(-0.3, 0.3)}};
    const std::vector<int> moved = {1, 0};  // body 2 is not moved
    chords.start(q0, moved);
    const int held = chords.addPath(path, q0, [](int b) { return b == 2 ? -1 : 1 - b; });
    for (int iterate = 0; iterate < 3; ++iterate) {
      std::vector<BodyState> q1 = q0, mid = q0;
      for (const int b : moved) {
        q1[b].position += rng.point(-0.2, 0.2);
        q1[b].angle += iterate == 0 ? 1e-9 * rng.uniform(-1, 1) : rng.uniform(-3, 3);
        mid[b].position = 0.5 * (q0[b].position + q1[b].position);
        mid[b].angle = 0.5 * (q0[b].angle + q1[b].angle);
      }
      chords.move(q0, q1, mid, moved);
      std::vector<BodyJacobian> g, expected;
      std::vector<WrapPoint> scratch = path;
      const double length = chords.discreteGradient(held, g);
      EXPECT_NEAR(length, lengthDiscreteGradient(scratch, q0, q1, expected), 1e-12);
      auto same = [&](std::vector<BodyJacobian> a, std::vector<BodyJacobian> b) {
        auto byBody = [](const BodyJacobian& x, const BodyJacobian& y) { return x.body < y.body; };
        std::sort(a.begin(), a.end(), byBody), std::sort(b.begin(), b.end(), byBody);
        ASSERT_EQ(a.size(), b.size()) << trial;
        for (size_t i = 0; i < a.size(); ++i) {
          EXPECT_EQ(a[i].body, b[i].body) << trial;
          EXPECT_LT((a[i].d - b[i].d).norm(), 1e-12) << trial << " iterate " << iterate;
        }
      };
      same(g, expected);
      CableKinematics k;
      scratch = path;
      cableLengthJacobian(scratch, q1, k);
      chords.endJacobian(held, q1, g);
      same(g, k.jacobian);
      const std::span<const StepChords::Point> points = chords.points(held);
      for (size_t i = 0; i < path.size(); ++i)
        EXPECT_LT((points[i].mid - worldPoint(mid, path[i].body, path[i].local)).norm(), 1e-12);
    }
  }
}

}  // namespace
}  // namespace cablelab
