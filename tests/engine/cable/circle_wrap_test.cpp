// Circle pulleys: the length against the analytic tangent-arc formula and a fine polygon, and
// J, J-dot-v against central finite differences (both sides, rotating bodies, drums).
#include "engine/cable/circle_wrap.h"

#include <gtest/gtest.h>

#include "engine/cable/cable.h"
#include "engine/cable/wrap.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/finite_differences.h"

namespace cablelab {
namespace {

using test::advance;
using test::kRelative;

WrapPoint circlePoint(int body, const Vec2& centre, double rho) {
  WrapPoint p{WrapPoint::Kind::Circle, body, centre};
  p.radius = rho;
  return p;
}

// The textbook tangent-arc length of A -> circle -> B, worked out from angles alone.
double tangentArcLength(const Vec2& a, const Vec2& c, double r, WrapSide side, const Vec2& b) {
  const double da = (a - c).norm(), db = (b - c).norm();
  const double angleA = std::atan2(a.y() - c.y(), a.x() - c.x());
  const double angleB = std::atan2(b.y() - c.y(), b.x() - c.x());
  // Left: the cable turns clockwise round the circle, touching it at angleA - acos(r / da)
  // (walking from A) and leaving at angleB + acos(r / db).
  const double s = side == WrapSide::Left ? 1 : -1;
  const double ta = angleA - s * std::acos(r / da);
  const double tb = angleB + s * std::acos(r / db);
  double arc = s * (ta - tb);
  arc = std::fmod(std::fmod(arc, 2 * M_PI) + 2 * M_PI, 2 * M_PI);
  return std::sqrt(da * da - r * r) + std::sqrt(db * db - r * r) + r * arc;
}

TEST(CircleWrap, LengthMatchesTangentArcFormulaAndAFinePolygon) {
  test::Random rng(11);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec2 c = rng.point(-1, 1);
    const double r = rng.uniform(0.05, 1.0);
    const Vec2 a = c + rng.uniform(1.2 * r, 4) * rotate(Vec2(1, 0), rng.uniform(-M_PI, M_PI));
    const Vec2 b = c + rng.uniform(1.2 * r, 4) * rotate(Vec2(1, 0), rng.uniform(-M_PI, M_PI));
    const WrapSide side = rng.integer(0, 1) ? WrapSide::Left : WrapSide::Right;
    const double rho = side == WrapSide::Left ? r : -r;
    std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, -1, a},
                                   circlePoint(-1, c, rho),
                                   {WrapPoint::Kind::Anchor, -1, b}};
    // Start the arc on the wrapped branch [0, 2 pi): the textbook formula's.
    path[1].arc = M_PI;
    const double expected = tangentArcLength(a, c, r, side, b);
    const double length = cableKinematics(path, {}).length;
    EXPECT_NEAR(length, expected, 1e-12 * expected) << "trial " << trial;
    // A regular 2048-gon inscribed in the circle: the polygon wrap is shorter by O(r / N^2).
    if (path[1].arc < M_PI - 0.3) {
      std::vector<Vec2> polygon;
      const int n = 2048;
      for (int i = 0; i < n; ++i) polygon.push_back(c + r * rotate(Vec2(1, 0), 2 * M_PI * i / n));
      const auto chain = wrapChain(a, b, polygon, side);
      ASSERT_TRUE(chain.has_value());
      const double polygonLength = chainLength(a, b, polygon, *chain);
      EXPECT_NEAR(polygonLength, length, 4 * r * (2 * M_PI) * (M_PI * M_PI / (n * n)))
          << "trial " << trial;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

// Random bodies; a path mixing anchors, points, polygon vertices and circles of both sides on
// moving, spinning bodies, optionally starting and ending on drums (circles with marks).
struct RandomPath {
  std::vector<BodyState> bodies;
  std::vector<WrapPoint> path;
};

bool wellSeparated(std::vector<WrapPoint>& path, const std::vector<BodyState>& bodies) {
  cableKinematics(path, bodies);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const double r0 = std::abs(path[i].radius), r1 = std::abs(path[i + 1].radius);
    if ((path[i + 1].world - path[i].world).norm() < r0 + r1 + 0.05) return false;
  }
  return true;
}

RandomPath randomPath(test::Random& rng, bool drums) {
  RandomPath rp;
  rp.bodies.resize(5);
  for (BodyState& b : rp.bodies) {
    b.position = rng.point(-3, 3);
    b.angle = rng.uniform(-3, 3);
    b.velocity = rng.point(-2, 2);
    b.angularVelocity = rng.uniform(-4, 4);
  }
  auto radius = [&] { return (rng.integer(0, 1) ? 1 : -1) * rng.uniform(0.05, 0.5); };
  auto& path = rp.path;
  if (drums) {
    path.push_back(circlePoint(0, rng.point(-0.2, 0.2), radius()));
    path.back().mark = rng.uniform(-3, 3);
  } else {
    path.push_back({WrapPoint::Kind::Anchor, 0, rng.point(-0.3, 0.3)});
  }
  path.push_back(circlePoint(1, rng.point(-0.3, 0.3), radius()));
  path.push_back({WrapPoint::Kind::Vertex, 2, rng.point(-0.3, 0.3), Vec2::Zero(), 0, 0});
  path.push_back(circlePoint(3, rng.point(-0.3, 0.3), radius()));
  path.push_back(circlePoint(3, rng.point(-0.3, 0.3) + Vec2(1.5, 0), radius()));  // same body
  if (drums) {
    path.push_back(circlePoint(4, rng.point(-0.2, 0.2), radius()));
    path.back().mark = rng.uniform(-3, 3);
  } else {
    path.push_back({WrapPoint::Kind::Anchor, -1, rng.point(-3, 3)});
  }
  return rp;
}

void checkDerivatives(RandomPath rp, int trial) {
  auto& bodies = rp.bodies;
  auto& path = rp.path;
  const CableKinematics k = cableKinematics(path, bodies);  // also settles the arcs' branches
  ASSERT_EQ(k.zeroLengthSegments, 0);
  auto lengthOf = [&](const std::vector<BodyState>& b) {
    std::vector<WrapPoint> copy = path;
    return cableKinematics(copy, b).length;
  };
  const double eps = 1e-6;
  double jv = 0;
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b)
    for (int c = 0; c < 3; ++c) {
      auto plus = bodies, minus = bodies;
      (c < 2 ? plus[b].position[c] : plus[b].angle) += eps;
      (c < 2 ? minus[b].position[c] : minus[b].angle) -= eps;
      const double fd = (lengthOf(plus) - lengthOf(minus)) / (2 * eps);
      double analytic = 0;
      for (const auto& e : k.jacobian)
        if (e.body == b) analytic = e.d[c];
      EXPECT_NEAR(analytic, fd, kRelative * std::max(1.0, std::abs(fd)))
          << "trial " << trial << " body " << b << " coord " << c;
      jv += analytic * (c < 2 ? bodies[b].velocity[c] : bodies[b].angularVelocity);
    }
  EXPECT_NEAR(k.lengthRate, jv, 1e-10 * std::max(1.0, std::abs(jv))) << "trial " << trial;
  const double h = 1e-5;
  auto rateAt = [&](double t) {
    std::vector<WrapPoint> copy = path;
    return cableKinematics(copy, advance(bodies, t)).lengthRate;
  };
  const double fdJdot = (rateAt(h) - rateAt(-h)) / (2 * h);
  EXPECT_NEAR(k.jdotV, fdJdot, 1e-5 * std::max(1.0, std::abs(fdJdot))) << "trial " << trial;
}

TEST(CircleWrap, JacobianAndJdotVMatchFiniteDifferences) {
  test::Random rng(5);
  int checked = 0;
  for (int trial = 0; trial < 2000 && checked < 400; ++trial) {
    RandomPath rp = randomPath(rng, trial % 2 == 1);
    if (!wellSeparated(rp.path, rp.bodies)) continue;
    checkDerivatives(rp, trial);
    ++checked;
  }
  EXPECT_GE(checked, 400);
}

// The midpoint solve's discrete gradient on paths with arcs: G (q1 - q0) = length(q1) -
// length(q0) to rounding for a sub-step's motion, and G -> J as the step shrinks.
TEST(CircleWrap, DiscreteGradientGivesTheExactLengthChange) {
  test::Random rng(11);
  int checked = 0;
  for (int trial = 0; trial < 2000 && checked < 200; ++trial) {
    RandomPath rp = randomPath(rng, trial % 2 == 1);
    if (!wellSeparated(rp.path, rp.bodies)) continue;
    const auto& q0 = rp.bodies;
    const double step = checked < 100 ? 0.02 : 1e-7;
    const std::vector<BodyState> q1 = advance(q0, step);
    std::vector<WrapPoint> path = rp.path;
    std::vector<BodyJacobian> g;
    const double length1 = lengthDiscreteGradient(path, q0, q1, g);
    std::vector<WrapPoint> copy0 = rp.path, copy1 = rp.path;
    const double exact0 = cableKinematics(copy0, q0).length;
    const double exact1 = cableKinematics(copy1, q1).length;
    EXPECT_NEAR(length1, exact1, 1e-12 * exact1) << "trial " << trial;
    double change = 0;
    for (const auto& e : g)
      change += e.d.dot(Vec3(q1[e.body].position.x() - q0[e.body].position.x(),
                             q1[e.body].position.y() - q0[e.body].position.y(),
                             q1[e.body].angle - q0[e.body].angle));
    EXPECT_NEAR(change, exact1 - exact0, 1e-12 * exact0) << "trial " << trial;
    if (step < 1e-3) {
      const CableKinematics k = cableKinematics(copy0, q0);
      ASSERT_EQ(k.jacobian.size(), g.size());
      for (size_t i = 0; i < g.size(); ++i)
        EXPECT_LT((k.jacobian[i].d - g[i].d).norm(), 1e-5) << "trial " << trial;
    }
    ++checked;
  }
  EXPECT_GE(checked, 200);
}

TEST(CircleWrap, DrumStoresRadiusTimesAngleTurned) {
  // A fixed point held by a cable wound counter-clockwise (rho < 0) onto a drum: turning the
  // drum counter-clockwise by dtheta winds r dtheta more onto it, for many turns, smoothly.
  std::vector<BodyState> bodies(1);
  const double r = 0.3;
  std::vector<WrapPoint> path = {{WrapPoint::Kind::Anchor, -1, Vec2(-0.3, 5)},
                                 circlePoint(0, Vec2::Zero(), -r)};
  path[1].mark = -M_PI / 2;  // the cable's end at the drum's bottom, a quarter turn wound
  const double l0 = cableKinematics(path, bodies).length;
  EXPECT_NEAR(path[1].arc, M_PI / 2, 1e-12);
  EXPECT_NEAR(l0, 5 + r * M_PI / 2, 1e-12);
  double previous = l0;
  for (int i = 1; i <= 5000; ++i) {
    bodies[0].angle = 5 * 2 * M_PI * i / 5000.0;
    const double l = cableKinematics(path, bodies).length;
    ASSERT_NEAR(l, l0 + r * bodies[0].angle, 1e-9) << "step " << i;
    ASSERT_LT(std::abs(l - previous), 1.01 * r * 2 * M_PI / 1000);
    previous = l;
  }
  EXPECT_NEAR(path[1].arc, M_PI / 2 + 5 * 2 * M_PI, 1e-9);
}

TEST(CircleWrap, TouchingCircleChangesNeitherLengthNorJacobian) {
  // Theorem 1: a circle tangent to the straight segment adds a wrap of zero angle.
  test::Random rng(8);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<BodyState> bodies(2);
    for (BodyState& b : bodies) {
      b.position = rng.point(-2, 2);
      b.angle = rng.uniform(-3, 3);
      b.velocity = rng.point(-1, 1);
      b.angularVelocity = rng.uniform(-2, 2);
    }
    const Vec2 a = worldPoint(bodies, 0, Vec2(0.1, 0.2));
    const Vec2 b = Vec2(3, 3);
    const Vec2 u = (b - a).normalized();
    const double r = rng.uniform(0.05, 0.5);
    const WrapSide side = rng.integer(0, 1) ? WrapSide::Left : WrapSide::Right;
    const double rho = side == WrapSide::Left ? r : -r;
    // The centre on the wrap side at distance r from the segment, inside its span.
    const Vec2 c = a + rng.uniform(0.2, 0.8) * (b - a) - rho * perp(u);
    const Vec2 local = rotate(c - bodies[1].position, -bodies[1].angle);
    std::vector<WrapPoint> straight = {{WrapPoint::Kind::Anchor, 0, Vec2(0.1, 0.2)},
                                       {WrapPoint::Kind::Anchor, -1, b}};
    std::vector<WrapPoint> wrapped = {straight[0], circlePoint(1, local, rho), straight[1]};
    const CableKinematics k0 = cableKinematics(straight, bodies);
    const CableKinematics k1 = cableKinematics(wrapped, bodies);
    EXPECT_NEAR(k1.length, k0.length, 1e-12);
    EXPECT_NEAR(std::remainder(wrapped[1].arc, 2 * M_PI), 0, 1e-9);
    EXPECT_NEAR(k1.lengthRate, k0.lengthRate, 1e-9);
    for (const BodyJacobian& e : k0.jacobian)
      for (const BodyJacobian& f : k1.jacobian)
        if (e.body == f.body) {
          EXPECT_LT((e.d - f.d).norm(), 1e-9) << "trial " << trial;
        }
    // The wheel's own row is zero at the touch (its centre sees u_in - u_out = 0).
    for (const BodyJacobian& f : k1.jacobian)
      if (f.body == 1) {
        EXPECT_LT(f.d.norm(), 1e-9);
      }
  }
}

}  // namespace
}  // namespace cablelab
