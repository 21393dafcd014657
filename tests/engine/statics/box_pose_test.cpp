#include "engine/statics/box_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/statics/statics.h"
#include "tests/support/finite_differences.h"

namespace cablelab {
namespace {

using test::kFdStep;
constexpr double kDerivativeTolerance = 1e-5;  // relative to the derivative's scale
constexpr double kPoseTolerance = 1e-9;

/// Two membranes as in the hand: one below a paddle above the box wrapping the top face's
/// corners, one above a paddle below wrapping the bottom face's, fingertips moved by `shift`.
std::vector<BoxCable> pinch(double h, const Eigen::Matrix<double, 8, 1>& shift) {
  std::vector<BoxCable> cables(2);
  for (int f = 0; f < 2; ++f) {
    const double s = f == 0 ? 1 : -1;
    BoxCable& c = cables[f];
    c.a = Vec2(-0.6, s * 0.15) + shift.segment<2>(4 * f);
    c.b = Vec2(0.6, s * 0.15) + shift.segment<2>(4 * f + 2);
    c.k = 150;
    c.L = 0.9;
    c.cornerA = Vec2(-h, s * h);
    c.cornerB = Vec2(h, s * h);
  }
  return cables;
}

TEST(BoxPose, GradientAndHessianMatchCentralDifferences) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix<double, 8, 1> shift;
    for (int i = 0; i < 8; ++i) shift[i] = jitter(rng);
    const std::vector<BoxCable> cables = pinch(0.25, shift);
    const BoxPose q(jitter(rng), jitter(rng), 2 * jitter(rng));
    Eigen::Vector3d g;
    Eigen::Matrix3d H;
    const double E = boxPoseEnergy(cables, q, &g, &H);
    ASSERT_GT(E, 0);
    for (int i = 0; i < 3; ++i) {
      BoxPose a = q, b = q;
      a[i] += kFdStep, b[i] -= kFdStep;
      Eigen::Vector3d ga, gb;
      const double fd =
          (boxPoseEnergy(cables, a, &ga) - boxPoseEnergy(cables, b, &gb)) / (2 * kFdStep);
      EXPECT_NEAR(g[i], fd, kDerivativeTolerance * (1 + g.norm())) << "trial " << trial;
      const Eigen::Vector3d hfd = (ga - gb) / (2 * kFdStep);
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(H(j, i), hfd[j], kDerivativeTolerance * (1 + H.norm()))
            << "trial " << trial << " H(" << j << "," << i << ")";
    }
  }
}

TEST(BoxPose, TwoCablesOnOppositeCornersAlignTheBoxWithTheirAnchors) {
  // Analytic: a box of half side h pulled by two doubled cables (both ends on one anchor) at the
  // mid-points of its left and right sides towards anchors (-D, y1) and (D, y2), equal k and L.
  // The two forces must be collinear and opposite, so the corners lie on the line through the
  // anchors: theta = atan2(y2 - y1, 2 D), the centre half-way between the anchors.
  const double h = 0.25, D = 1.5, y1 = -0.3, y2 = 0.5;
  std::vector<BoxCable> cables(2);
  cables[0].a = cables[0].b = Vec2(-D, y1);
  cables[0].cornerA = cables[0].cornerB = Vec2(-h, 0);
  cables[1].a = cables[1].b = Vec2(D, y2);
  cables[1].cornerA = cables[1].cornerB = Vec2(h, 0);
  for (BoxCable& c : cables) c.k = 200, c.L = 1.0;
  const BoxPoseResult r = solveBoxPose(cables, BoxPose::Zero(), h);
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.pose[2], std::atan2(y2 - y1, 2 * D), kPoseTolerance);
  EXPECT_NEAR(r.pose[0], 0, kPoseTolerance);
  EXPECT_NEAR(r.pose[1], 0.5 * (y1 + y2), kPoseTolerance);
  EXPECT_NEAR(r.tensions[0], r.tensions[1], 1e-6);
  EXPECT_GT(r.tensions[0], 0);
}

TEST(BoxPose, SymmetricPinchMatchesTheBoxToPointReduction) {
  // With the fingertips symmetric about the box's vertical axis nothing turns the box: theta = 0
  // and the centre is the point reduction's.
  Eigen::Matrix<double, 8, 1> shift = Eigen::Matrix<double, 8, 1>::Zero();
  shift[1] = shift[3] = 0.03;  // the top membrane's fingertips both 3 cm up
  const std::vector<BoxCable> cables = pinch(0.25, shift);
  const BoxPoseResult r = solveBoxPose(cables, BoxPose(0.01, 0.0, 0.05), 0.25);
  ASSERT_TRUE(r.converged);
  StaticsResult point;
  solveStatics(reduceBoxToPoint(cables, Vec2::Zero()), point);
  ASSERT_TRUE(point.converged);
  EXPECT_NEAR(r.pose[2], 0, kPoseTolerance);
  EXPECT_NEAR(r.pose[0], point.p.x(), 1e-8);
  EXPECT_NEAR(r.pose[1], point.p.y(), 1e-8);
}

TEST(BoxPose, AnAsymmetricPinchTurnsTheBoxIntoForceAndTorqueBalance) {
  // One fingertip raised: the box turns. At the solution the cables' forces on the corners
  // (tension along each free segment, computed here from the geometry alone) sum to zero, and
  // so do their moments about the centre; and the energy is below the non-turning reduction's.
  Eigen::Matrix<double, 8, 1> shift = Eigen::Matrix<double, 8, 1>::Zero();
  shift[3] = 0.06;  // the top membrane's right fingertip 6 cm up
  const std::vector<BoxCable> cables = pinch(0.25, shift);
  const BoxPoseResult r = solveBoxPose(cables, BoxPose::Zero(), 0.25);
  ASSERT_TRUE(r.converged);
  EXPECT_GT(std::abs(r.pose[2]), 1e-3) << "the box did not turn";
  Vec2 force = Vec2::Zero();
  double torque = 0;
  for (size_t i = 0; i < cables.size(); ++i) {
    const BoxCable& c = cables[i];
    const Vec2 armA = rotate(c.cornerA, r.pose[2]), armB = rotate(c.cornerB, r.pose[2]);
    const Vec2 centre = r.pose.head<2>();
    const Vec2 fA = r.tensions[i] * (c.a - (centre + armA)).normalized();
    const Vec2 fB = r.tensions[i] * (c.b - (centre + armB)).normalized();
    // The run along the box pulls its two corners equally and oppositely along the face: no net
    // force, no moment.
    force += fA + fB;
    torque += cross(armA, fA) + cross(armB, fB);
  }
  EXPECT_LT(force.norm(), 1e-8 * r.tensions[0]);
  EXPECT_LT(std::abs(torque), 1e-8 * r.tensions[0]);
  StaticsResult point;
  solveStatics(reduceBoxToPoint(cables, Vec2::Zero()), point);
  EXPECT_LT(r.energy, boxPoseEnergy(cables, BoxPose(point.p.x(), point.p.y(), 0)));
}

TEST(BoxPose, SensitivityMatchesReSolvedFiniteDifferences) {
  // d pose* / d fingertips against central differences of re-solved equilibria, on an
  // asymmetric pinch where the box has turned.
  Eigen::Matrix<double, 8, 1> shift = Eigen::Matrix<double, 8, 1>::Zero();
  shift << 0.02, -0.01, 0.03, 0.06, -0.02, 0.01, 0.0, -0.03;
  const std::vector<BoxCable> cables = pinch(0.25, shift);
  const BoxPoseResult r = solveBoxPose(cables, BoxPose::Zero(), 0.25);
  ASSERT_TRUE(r.converged);
  ASSERT_GT(std::abs(r.pose[2]), 1e-3);
  const Eigen::MatrixXd S = boxPoseSensitivity(cables, r.pose);
  ASSERT_EQ(S.cols(), 8);
  for (int j = 0; j < 8; ++j) {
    std::vector<BoxCable> a = cables, b = cables;
    Vec2& ta = (j % 4 < 2) ? a[j / 4].a : a[j / 4].b;
    Vec2& tb = (j % 4 < 2) ? b[j / 4].a : b[j / 4].b;
    ta[j % 2] += kFdStep, tb[j % 2] -= kFdStep;
    const BoxPoseResult ra = solveBoxPose(a, r.pose, 0.25), rb = solveBoxPose(b, r.pose, 0.25);
    ASSERT_TRUE(ra.converged && rb.converged);
    const Eigen::Vector3d fd = (ra.pose - rb.pose) / (2 * kFdStep);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(S(i, j), fd[i], kDerivativeTolerance) << "pose " << i << " fingertip " << j;
  }
}

}  // namespace
}  // namespace cablelab
