// The turning box held by membranes with friction at its corners (box_friction.h,
// docs/control.md#membrane-friction): derivatives and sensitivities against finite differences,
// the capstan bound, and the frictionless limit.
#include "engine/statics/box_friction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/support/finite_differences.h"

namespace cablelab {
namespace box_friction_test {  // named: unity batches join test files

using test::kFdStep;
constexpr double kDerivativeTolerance = 1e-5;  // relative to the derivative's scale
// One-sided differences of 1e-4 m, re-solved to the solver's 1e-7 of the tension: a wrong
// derivative term is off by tens of percent.
constexpr double kSensitivityTolerance = 1e-2;

using Shift = Eigen::Matrix<double, 8, 1>;

/// The hand's two membranes round a 0.5 m box (as box_pose_test), fingertips moved by `shift`,
/// material shared at one strain at the pinch.
std::vector<FrictionBoxCable> pinch(double mu, const Shift& shift) {
  std::vector<FrictionBoxCable> cables(2);
  for (int f = 0; f < 2; ++f) {
    const double s = f == 0 ? 1 : -1;
    BoxCable& c = cables[f].cable;
    c.a = Vec2(-0.6, s * 0.15) + shift.segment<2>(4 * f);
    c.b = Vec2(0.6, s * 0.15) + shift.segment<2>(4 * f + 2);
    c.k = 150;
    c.L = 0.9;
    c.cornerA = Vec2(-0.25, s * 0.25);
    c.cornerB = Vec2(0.25, s * 0.25);
    cables[f].mu = mu;
  }
  shareMaterial(cables, BoxPose::Zero());
  return cables;
}

void moveTips(std::vector<FrictionBoxCable>& cables, const Shift& shift) {
  for (int f = 0; f < 2; ++f) {
    cables[f].cable.a += shift.segment<2>(4 * f);
    cables[f].cable.b += shift.segment<2>(4 * f + 2);
  }
}

TEST(BoxFriction, StickingEnergyDerivativesMatchCentralDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<FrictionBoxCable> cables = pinch(0.5, Shift::Zero());
    Shift shift;
    for (int i = 0; i < 8; ++i) shift[i] = jitter(rng);
    moveTips(cables, shift);
    cables[0].restA *= 1 + jitter(rng), cables[1].restB *= 1 + jitter(rng);
    const BoxPose q(jitter(rng), jitter(rng), 2 * jitter(rng));
    Eigen::Vector3d g;
    Eigen::Matrix3d H;
    ASSERT_GT(frictionBoxEnergy(cables, q, &g, &H), 0);
    for (int i = 0; i < 3; ++i) {
      BoxPose a = q, b = q;
      a[i] += kFdStep, b[i] -= kFdStep;
      Eigen::Vector3d ga, gb;
      const double fd =
          (frictionBoxEnergy(cables, a, &ga) - frictionBoxEnergy(cables, b, &gb)) / (2 * kFdStep);
      EXPECT_NEAR(g[i], fd, kDerivativeTolerance * (1 + g.norm())) << "trial " << trial;
      const Eigen::Vector3d hfd = (ga - gb) / (2 * kFdStep);
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(H(j, i), hfd[j], kDerivativeTolerance * (1 + H.norm())) << "trial " << trial;
    }
  }
}

// Material shared at one strain gives both spans the frictionless tension: the sticking
// equilibrium is the frictionless one (box_pose.h), and nothing slides.
TEST(BoxFriction, OneStrainIsTheFrictionlessEquilibrium) {
  Shift shift;
  shift << 0.05, 0.02, 0.03, -0.01, -0.04, 0.01, 0.02, 0.03;
  std::vector<BoxCable> plain;
  for (const FrictionBoxCable& c : pinch(0.5, shift)) plain.push_back(c.cable);
  const BoxPoseResult frictionless = solveBoxPose(plain, BoxPose::Zero(), 0.25);
  ASSERT_TRUE(frictionless.converged);
  std::vector<FrictionBoxCable> cables = pinch(0.5, shift);
  shareMaterial(cables, frictionless.pose);
  const FrictionBoxResult r = solveFrictionBoxPose(cables, frictionless.pose, 0.25);
  ASSERT_TRUE(r.converged);
  EXPECT_LT((r.pose - frictionless.pose).norm(), 1e-9);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(r.sliding[f], 0);
    EXPECT_NEAR(r.spans[f].tensionA, frictionless.tensions[f], 1e-9 * frictionless.tensions[f]);
    EXPECT_NEAR(r.spans[f].tensionB, frictionless.tensions[f], 1e-9 * frictionless.tensions[f]);
  }
}

// From the pinch, the fingertips move by random amounts: every membrane ends within its capstan
// bound, a sliding one exactly on it; with mu = 0 both spans always carry one tension.
TEST(BoxFriction, EveryMembraneHoldsWithinTheCapstanRatioOrSlidesOnIt) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.06, 0.06);
  int slid = 0, held = 0;
  for (const double mu : {0.0, 0.1, 0.5, 2.0})
    for (int trial = 0; trial < 10; ++trial) {
      std::vector<FrictionBoxCable> cables = pinch(mu, Shift::Zero());
      Shift shift;
      for (int i = 0; i < 8; ++i) shift[i] = jitter(rng);
      moveTips(cables, shift);
      const FrictionBoxResult r = solveFrictionBoxPose(cables, BoxPose::Zero(), 0.25);
      ASSERT_TRUE(r.converged) << mu << " " << trial << ": " << r.iterations << " solves";
      for (int f = 0; f < 2; ++f) {
        const FrictionSpans& s = r.spans[f];
        const double high = std::max(s.tensionA, s.tensionB),
                     low = std::min(s.tensionA, s.tensionB);
        ASSERT_GT(low, 0);
        EXPECT_LE(high, s.ratio * low * (1 + 1e-9)) << mu << " " << trial;
        if (r.sliding[f] != 0) {
          EXPECT_NEAR(high, s.ratio * low, 1e-9 * high);
        }
        if (mu == 0) {
          EXPECT_NEAR(s.tensionA, s.tensionB, 1e-9 * high);
        }
        (r.sliding[f] != 0 ? slid : held) += mu > 0;
      }
    }
  EXPECT_GT(slid, 0);  // both cases were exercised
  EXPECT_GT(held, 0);
}

// d pose / d fingertips against re-solved differences from the equilibrium's own state (its
// materials). A sliding membrane slides on in one direction of a tip's move and sticks in the
// other: the derivative is the one-sided one in which it slides on.
TEST(BoxFriction, SensitivityMatchesResolvedDifferences) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  int slidingChecked = 0, columns = 0, matchedColumns = 0;
  for (const double mu : {0.1, 0.5, 3.0})
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<FrictionBoxCable> cables = pinch(mu, Shift::Zero());
      Shift shift;
      for (int i = 0; i < 8; ++i) shift[i] = jitter(rng);
      moveTips(cables, shift);
      const FrictionBoxResult eq = solveFrictionBoxPose(cables, BoxPose::Zero(), 0.25);
      ASSERT_TRUE(eq.converged);
      const Eigen::MatrixXd S = frictionBoxSensitivity(eq);
      ASSERT_GT(S.norm(), 0);
      const double h = 1e-4;
      for (int col = 0; col < 8; ++col) {
        bool matched = false;
        for (const double sign : {1.0, -1.0}) {
          std::vector<FrictionBoxCable> moved = eq.cables;
          Vec2& tip = col % 4 < 2 ? moved[col / 4].cable.a : moved[col / 4].cable.b;
          tip[col % 2] += sign * h;
          const FrictionBoxResult r = solveFrictionBoxPose(moved, eq.pose, 0.25);
          if (!r.converged) continue;
          // One-sided: the move keeps every membrane in the state it was in.
          bool same = true;
          for (int f = 0; f < 2; ++f) same &= (r.sliding[f] != 0) == (eq.sliding[f] != 0);
          if (!same) continue;
          const Eigen::Vector3d fd = (r.pose - eq.pose) / (sign * h);
          EXPECT_LT((S.col(col) - fd).norm(), kSensitivityTolerance * (1 + S.col(col).norm()))
              << "mu " << mu << " trial " << trial << " column " << col;
          matched = true;
          break;
        }
        columns += 1, matchedColumns += matched;
      }
      slidingChecked += eq.sliding[0] != 0 || eq.sliding[1] != 0;
    }
  EXPECT_GT(slidingChecked, 0);
  // A move may also switch a membrane between holding and sliding both ways (or the re-solve
  // stall): those columns have no one-sided derivative to compare.
  EXPECT_GE(matchedColumns, 0.9 * columns) << matchedColumns << " of " << columns;
}

}  // namespace box_friction_test
}  // namespace cablelab
