// Tests for engine/membrane/membrane_model.h: the force is the negative energy gradient, and the
// conventions (sign, angle, slack) are the documented ones.
#include "engine/membrane/membrane_model.h"

#include <gtest/gtest.h>

#include <random>

namespace cablelab {
namespace {

constexpr double kFiniteDifferenceTolerance = 1e-6;  // relative to |F|, step 1e-6 m

TEST(MembraneModel, ForceIsMinusEnergyGradientByCentralDifferences) {
  const MembraneGeometry g{Vec2(-0.3, 0.1), Vec2(0.25, -0.05)};  // tilted, off the origin
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-0.6, 0.6);
  std::uniform_real_distribution<double> k(5.0, 100.0), preload(0.0, 1.0);
  int checked = 0;
  while (checked < 200) {
    const Vec2 p(coord(rng), coord(rng));
    if ((p - g.a).norm() < 0.01 || (p - g.b).norm() < 0.01) continue;  // kink at the pulleys
    if (membraneDirectionSum(g, p).norm() < 0.01) continue;            // on the band itself
    const MembraneParams m{k(rng), preload(rng)};
    const double h = 1e-6;
    Vec2 gradient;
    for (int axis = 0; axis < 2; ++axis) {
      Vec2 step = Vec2::Zero();
      step[axis] = h;
      gradient[axis] =
          (membraneEnergy(g, m, p + step) - membraneEnergy(g, m, p - step)) / (2.0 * h);
    }
    const Vec2 force = membraneForce(g, m, p);
    EXPECT_LT((force + gradient).norm(), kFiniteDifferenceTolerance * std::max(1.0, force.norm()))
        << "p = " << p.transpose() << " k = " << m.k << " preload = " << m.preload;
    ++checked;
  }
}

TEST(MembraneModel, PointBelowIsPushedUpAndAboveDown) {
  const MembraneGeometry g{Vec2(-0.2, 0.0), Vec2(0.2, 0.0)};
  const MembraneParams m{25.0, 0.8};
  const Vec2 below = membraneForce(g, m, Vec2(0.0, -0.1));
  const Vec2 above = membraneForce(g, m, Vec2(0.0, 0.1));
  EXPECT_GT(below.y(), 0.0);
  EXPECT_LT(above.y(), 0.0);
  EXPECT_NEAR(below.x(), 0.0, 1e-12);
  EXPECT_NEAR(membraneForceAngleDeg(g, Vec2(0.0, -0.1)), 90.0, 1e-12);
  EXPECT_NEAR(membraneForceAngleDeg(g, Vec2(0.0, 0.1)), -90.0, 1e-12);
  // No factor 1/2 (docs/model.md#membranes): |F| = 2 T sin(theta) at the midpoint.
  const double stretch = 2.0 * std::hypot(0.2, 0.1) - 0.4;
  const double tension = 25.0 * (stretch + 0.8);
  EXPECT_NEAR(below.y(), tension * 2.0 * 0.1 / std::hypot(0.2, 0.1), 1e-12);
}

TEST(MembraneModel, SlackBandExertsNothing) {
  const MembraneGeometry g{Vec2(-0.2, 0.0), Vec2(0.2, 0.0)};
  // A negative preload (a loose band) larger than the stretch: the band cannot push.
  const MembraneParams loose{25.0, -0.5};
  EXPECT_EQ(membraneTension(g, loose, Vec2(0.0, -0.05)), 0.0);
  EXPECT_EQ(membraneForce(g, loose, Vec2(0.0, -0.05)).norm(), 0.0);
}

TEST(MembraneModel, WrapAngleIntoHalfOpenRange) {
  EXPECT_DOUBLE_EQ(wrapAngleDeg(180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrapAngleDeg(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrapAngleDeg(359.0), -1.0);
  EXPECT_DOUBLE_EQ(wrapAngleDeg(-359.0), 1.0);
  EXPECT_DOUBLE_EQ(wrapAngleDeg(179.5 - (-179.5)), -1.0);
  EXPECT_DOUBLE_EQ(wrapAngleDeg(720.0 + 30.0), 30.0);
}

}  // namespace
}  // namespace cablelab
