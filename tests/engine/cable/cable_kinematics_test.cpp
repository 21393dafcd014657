// J and J-dot-v of cable paths against central finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/cable/cable.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/finite_differences.h"

namespace cablelab {
namespace {

using test::advance;
using test::kRelative;

double lengthOf(std::vector<WrapPoint> path, const std::vector<BodyState>& bodies) {
  return cableKinematics(path, bodies).length;
}

TEST(CableKinematics, JacobianAndJdotVMatchFiniteDifferences) {
  test::Random rng(3);
  for (int trial = 0; trial < 150; ++trial) {
    std::vector<BodyState> bodies(3);
    for (BodyState& b : bodies) {
      b.position = rng.point(-2, 2);
      b.angle = rng.uniform(-3, 3);
      b.velocity = rng.point(-2, 2);
      b.angularVelocity = rng.uniform(-4, 4);
    }
    // anchor on body 0 -> three vertices of a polygon on body 1 -> point on body 2 -> world anchor
    std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, 0, rng.point(-0.3, 0.3)}};
    for (int v = 0; v < 3; ++v)
      path.push_back({WrapPoint::Kind::Vertex, 1, rng.point(-0.5, 0.5), Vec2::Zero(), 0, v});
    path.push_back({WrapPoint::Kind::Point, 2, rng.point(-0.3, 0.3), Vec2::Zero(), 1});
    path.push_back({WrapPoint::Kind::Anchor, -1, rng.point(-3, 3)});

    const CableKinematics k = cableKinematics(path, bodies);
    ASSERT_EQ(k.zeroLengthSegments, 0);
    const double eps = 1e-6;
    double jv = 0;
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c) {
        auto plus = bodies, minus = bodies;
        (c < 2 ? plus[b].position[c] : plus[b].angle) += eps;
        (c < 2 ? minus[b].position[c] : minus[b].angle) -= eps;
        const double fd = (lengthOf(path, plus) - lengthOf(path, minus)) / (2 * eps);
        double analytic = 0;
        for (const auto& e : k.jacobian)
          if (e.body == b) analytic = e.d[c];
        EXPECT_NEAR(analytic, fd, kRelative * std::max(1.0, std::abs(fd)))
            << "trial " << trial << " body " << b << " coord " << c;
        const double vc = c < 2 ? bodies[b].velocity[c] : bodies[b].angularVelocity;
        jv += analytic * vc;
      }
    EXPECT_NEAR(k.lengthRate, jv, 1e-12 * std::max(1.0, std::abs(jv)));
    // J-dot-v = d/dt (J v) along q + t v with v fixed.
    const double h = 1e-5;
    const double rateP = cableKinematics(path, advance(bodies, h)).lengthRate;
    const double rateM = cableKinematics(path, advance(bodies, -h)).lengthRate;
    const double fdJdot = (rateP - rateM) / (2 * h);
    EXPECT_NEAR(k.jdotV, fdJdot, kRelative * std::max(1.0, std::abs(fdJdot))) << "trial " << trial;
  }
}

TEST(CableKinematics, LengthRemainderBoundCoversTheLinearisationError) {
  // |length(q1) - length(q0) - J(q0) (q1 - q0)| <= the bound for moves from 1e-5 to 0.1 (m and
  // rad), pure turns about far origins included (the bound's |r| dtheta^2 / 2 term), and the
  // bound is not slack by orders of magnitude where the remainder is not small by cancellation.
  test::Random rng(21);
  int checked = 0, tight = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::vector<BodyState> q0(3);
    for (BodyState& b : q0) {
      b.position = rng.point(-2, 2);
      b.angle = rng.uniform(-3, 3);
    }
    std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, 0, rng.point(-1.5, 1.5)}};
    for (int v = 0; v < 3; ++v)
      path.push_back({WrapPoint::Kind::Vertex, 1, rng.point(-0.5, 0.5), Vec2::Zero(), 0, v});
    path.push_back({WrapPoint::Kind::Point, 2, rng.point(-1.5, 1.5), Vec2::Zero(), 1});
    path.push_back({WrapPoint::Kind::Anchor, -1, rng.point(-3, 3)});
    const CableKinematics k = cableKinematics(path, q0);
    const double scale = std::pow(10.0, rng.uniform(-5, -1));
    const bool turnOnly = trial % 3 == 0;
    std::vector<BodyState> q1 = q0;
    for (BodyState& b : q1) {
      if (!turnOnly) b.position += scale * rng.point(-1, 1);
      b.angle += scale * rng.uniform(-1, 1);
    }
    const double bound = lengthRemainderBound(path, q0, q1);
    if (!std::isfinite(bound)) continue;
    double linear = 0;
    for (const auto& e : k.jacobian)
      linear += e.d.dot(Vec3(q1[e.body].position.x() - q0[e.body].position.x(),
                             q1[e.body].position.y() - q0[e.body].position.y(),
                             q1[e.body].angle - q0[e.body].angle));
    const double remainder = std::abs(lengthOf(path, q1) - k.length - linear);
    EXPECT_LE(remainder, bound * (1 + 1e-9) + 1e-15)
        << "trial " << trial << " scale " << scale << (turnOnly ? " (turns only)" : "");
    ++checked;
    if (remainder > 1e-14) tight += bound < 1e3 * remainder;
  }
  EXPECT_GT(checked, 500);
  EXPECT_GT(tight, checked / 2);
}

TEST(CableKinematics, DiscreteGradientGivesTheExactLengthChange) {
  // G (q1 - q0) = length(q1) - length(q0) to rounding, for any step (large turns included), and
  // G tends to J as the step shrinks.
  test::Random rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<BodyState> q0(3), q1;
    for (BodyState& b : q0) {
      b.position = rng.point(-2, 2);
      b.angle = rng.uniform(-3, 3);
      b.velocity = rng.point(-3, 3);
      b.angularVelocity = rng.uniform(-6, 6);
    }
    std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, 0, rng.point(-0.3, 0.3)}};
    for (int v = 0; v < 2; ++v)
      path.push_back({WrapPoint::Kind::Vertex, 1, rng.point(-0.5, 0.5), Vec2::Zero(), 0, v});
    path.push_back({WrapPoint::Kind::Point, 2, rng.point(-0.3, 0.3), Vec2::Zero(), 1});
    path.push_back({WrapPoint::Kind::Anchor, -1, rng.point(-3, 3)});
    const double step = trial < 100 ? 0.3 : 1e-7;
    q1 = advance(q0, step);
    std::vector<BodyJacobian> g;
    lengthDiscreteGradient(path, q0, q1, g);
    double change = 0;
    for (const auto& e : g) {
      const Vec3 dq(q1[e.body].position.x() - q0[e.body].position.x(),
                    q1[e.body].position.y() - q0[e.body].position.y(),
                    q1[e.body].angle - q0[e.body].angle);
      change += e.d.dot(dq);
    }
    const double exact = lengthOf(path, q1) - lengthOf(path, q0);
    EXPECT_NEAR(change, exact, 1e-12 * std::max(1.0, lengthOf(path, q0))) << "trial " << trial;
    if (step < 1e-3) {
      const CableKinematics k = cableKinematics(path, q0);
      ASSERT_EQ(k.jacobian.size(), g.size());
      for (size_t i = 0; i < g.size(); ++i)
        EXPECT_LT((k.jacobian[i].d - g[i].d).norm(), 1e-5) << "trial " << trial;
    }
  }
}

TEST(CableKinematics, CoincidentPointsAreLeftOutNotNaN) {
  std::vector<BodyState> bodies(1);
  bodies[0].position = Vec2(1, 0);
  bodies[0].velocity = Vec2(0, 1);
  std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, -1, Vec2(0, 0)},
                                 {WrapPoint::Kind::Point, -1, Vec2(1, 0)},
                                 {WrapPoint::Kind::Anchor, 0, Vec2::Zero()}};
  const CableKinematics k = cableKinematics(path, bodies);
  EXPECT_EQ(k.zeroLengthSegments, 1);
  EXPECT_DOUBLE_EQ(k.length, 1.0);
  EXPECT_TRUE(std::isfinite(k.jdotV));
  EXPECT_TRUE(k.jacobian.empty());  // the only moving segment has no direction
}

}  // namespace
}  // namespace cablelab
