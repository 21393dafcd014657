// Newton's stopping rule (newton_stop.h): it must stop where the iterate is provably near the
// root, and only there.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/dynamics/newton_stop.h"

namespace cablelab {
namespace {

constexpr double kFirst = std::numeric_limits<double>::infinity();

// Newton on f(x) = x^2 - 2 from x = 1.4 (quadratic convergence): steps 1.4e-2, 7.2e-5, 1.8e-9,
// 2e-16. The plain step test (below 1.4e-9) needs the fourth; the rule trusts the third's rate
// (theta 2.6e-5: within 4.7e-14 of the root) and stops there, the iterate exact to 1 ulp.
TEST(NewtonStop, StopsQuadraticConvergenceOneIterationEarlierWithinTheTolerance) {
  double x = 1.4, last = kFirst;
  int iterations = 0;
  for (; iterations < 10; ++iterations) {
    const double next = x - (x * x - 2) / (2 * x);
    const double change = std::abs(next - x);
    x = next;
    if (newtonSettled(change, last, std::abs(x))) break;
    last = change;
  }
  EXPECT_EQ(iterations, 2);  // 0-based: the third step
  EXPECT_LT(std::abs(x - std::sqrt(2.0)), 1e-12);
}

TEST(NewtonStop, NeverStopsOnTheFirstStepOrOnStepsThatDoNotContract) {
  EXPECT_FALSE(newtonSettled(1e-6, kFirst, 1));  // no rate yet
  EXPECT_FALSE(newtonSettled(1e-6, 1e-6, 1));    // theta = 1: no contraction
  EXPECT_FALSE(newtonSettled(2e-6, 1e-6, 1));    // growing
  EXPECT_TRUE(newtonSettled(1e-10, kFirst, 1));  // below the tolerance whatever the rate
}

// A step above the tolerance (1e-9 of the largest impulse, 1 here): at theta = 0.5 (a chord
// method) the iterate may still be a step away, so no stop; at theta = 2e-5 it is within 4e-14.
TEST(NewtonStop, WaitsOnSlowContraction) {
  EXPECT_FALSE(newtonSettled(2e-9, 4e-9, 1));
  EXPECT_TRUE(newtonSettled(2e-9, 1e-4, 1));
}

}  // namespace
}  // namespace cablelab
