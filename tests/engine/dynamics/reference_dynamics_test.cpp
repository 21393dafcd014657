// Equation 2.3 on the ballast example of thesis section 2.4.2, against the analytic solution.
#include "tests/support/reference_dynamics.h"

#include <gtest/gtest.h>

#include "engine/cable/cable.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

constexpr double kReferenceTolerance = 1e-9;

// q = (point x, y, theta, ballast x, y, theta); the cable runs (-l, 0) -> point -> (l, 0) ->
// ballast.
struct Ballast {
  double l, mPoint, mBallast;
  Vec2 v0;
  Vec2 ballastPos;
};

TEST(ReferenceDynamics, BallastAccelerationsMatchTheAnalyticSolution) {
  test::Random rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    Ballast c{rng.uniform(0.2, 5), rng.uniform(0.1, 10), rng.uniform(0.1, 10), rng.point(-3, 3),
              Vec2(0, 0)};
    c.ballastPos = Vec2(c.l, -rng.uniform(0.3, 3));
    std::vector<BodyState> bodies(2);
    bodies[0].velocity = c.v0;
    bodies[1].position = c.ballastPos;
    std::vector<WrapPoint> path = {
        {WrapPoint::Kind::Anchor, -1, Vec2(-c.l, 0)},
        {WrapPoint::Kind::Point, 0, Vec2::Zero()},
        {WrapPoint::Kind::Point, -1, Vec2(c.l, 0)},
        {WrapPoint::Kind::Anchor, 1, Vec2::Zero()},
    };
    const CableKinematics k = cableKinematics(path, bodies);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(1, 6);
    for (const auto& e : k.jacobian) J.block<1, 3>(0, 3 * e.body) = e.d.transpose();
    Eigen::VectorXd H(6);
    H << c.mPoint, c.mPoint, 1.0, c.mBallast, c.mBallast, 1.0;
    const auto acc =
        constrainedAcceleration(H.asDiagonal().toDenseMatrix(), J,
                                Eigen::VectorXd::Constant(1, k.jdotV), Eigen::VectorXd::Zero(6));
    const double expected = 2 * c.v0.y() * c.v0.y() / c.l;  // ballast, towards the pulley (+y)
    EXPECT_NEAR(acc.qdd[0], 0, kReferenceTolerance);
    EXPECT_NEAR(acc.qdd[1], 0, kReferenceTolerance);
    EXPECT_NEAR(acc.qdd[3], 0, kReferenceTolerance);
    EXPECT_NEAR(acc.qdd[4], expected, kReferenceTolerance * std::max(1.0, expected));
    EXPECT_NEAR(-acc.lambda[0], c.mBallast * expected,
                kReferenceTolerance * std::max(1.0, c.mBallast * expected));
  }
}

TEST(ReferenceDynamics, RedundantConstraintsStillSolve) {
  // Two identical rows (a rank-deficient J): the pseudo-inverse must still satisfy J qdd = -Jdot v.
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2) * 2.0;
  Eigen::MatrixXd J(2, 2);
  J << 1, 0, 1, 0;
  Eigen::VectorXd jdotV(2);
  jdotV << 0.5, 0.5;
  Eigen::VectorXd f(2);
  f << 1, 3;
  const auto acc = constrainedAcceleration(H, J, jdotV, f);
  EXPECT_NEAR(acc.qdd[0], -0.5, 1e-12);
  EXPECT_NEAR(acc.qdd[1], 1.5, 1e-12);
}

}  // namespace
}  // namespace cablelab
