// wrapChain against a brute-force search over every run of polygon vertices.
#include "engine/cable/wrap.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

constexpr double kLengthTolerance = 1e-12;

std::vector<Vec2> randomConvexPolygon(test::Random& rng) {
  const int n = rng.integer(3, 8);
  const Vec2 c = rng.point(-1, 1);
  const double r = rng.uniform(0.2, 1.0);
  std::vector<double> angles;
  for (int i = 0; i < n; ++i) angles.push_back(rng.uniform(0, 2 * M_PI));
  std::sort(angles.begin(), angles.end());
  std::vector<Vec2> poly;
  for (double a : angles) poly.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  return poly;
}

bool inside(const std::vector<Vec2>& poly, const Vec2& p) {
  for (size_t i = 0; i < poly.size(); ++i)
    if (cross(poly[(i + 1) % poly.size()] - poly[i], p - poly[i]) <= 0) return false;
  return true;
}

// Every segment of a taut path keeps the whole polygon on one side (the cable's right for Left):
// try every run of consecutive vertices (walked with the polygon on that side) and the empty
// path, keep the valid ones, return the shortest.
std::vector<int> bruteForceChain(const Vec2& a, const Vec2& b, const std::vector<Vec2>& poly,
                                 WrapSide side) {
  const int n = static_cast<int>(poly.size());
  const double s = side == WrapSide::Left ? 1 : -1;
  auto keepsPolygonOnSide = [&](const Vec2& p, const Vec2& q) {
    for (const Vec2& v : poly)
      if (s * cross(q - p, v - p) > 1e-12) return false;
    return true;
  };
  std::vector<std::vector<int>> candidates{{}};
  const int step = side == WrapSide::Left ? -1 : 1;
  for (int start = 0; start < n; ++start)
    for (int len = 1; len <= n; ++len) {
      std::vector<int> run;
      for (int k = 0; k < len; ++k) run.push_back(((start + step * k) % n + n) % n);
      candidates.push_back(run);
    }
  std::vector<int> best;
  double bestLength = 1e300;
  for (const auto& c : candidates) {
    std::vector<Vec2> path{a};
    for (int i : c) path.push_back(poly[i]);
    path.push_back(b);
    bool valid = true;
    for (size_t i = 0; i + 1 < path.size() && valid; ++i)
      valid = keepsPolygonOnSide(path[i], path[i + 1]);
    if (!valid) continue;
    const double len = chainLength(a, b, poly, c);
    if (len < bestLength - kLengthTolerance) best = c, bestLength = len;
  }
  return best;
}

TEST(WrapChain, MatchesBruteForceShortestPathOnRandomCases) {
  test::Random rng(7);
  int tested = 0, wrapped = 0;
  while (tested < 400) {
    const auto poly = randomConvexPolygon(rng);
    if (!isConvexCCW(poly)) continue;
    const Vec2 a = rng.point(-3, 3), b = rng.point(-3, 3);
    if (inside(poly, a) || inside(poly, b) || (a - b).norm() < 1e-3) continue;
    for (WrapSide side : {WrapSide::Left, WrapSide::Right}) {
      const auto chain = wrapChain(a, b, poly, side);
      ASSERT_TRUE(chain.has_value());
      const auto expected = bruteForceChain(a, b, poly, side);
      EXPECT_NEAR(chainLength(a, b, poly, *chain), chainLength(a, b, poly, expected), 1e-9);
      EXPECT_EQ(*chain, expected) << "case " << tested;
      wrapped += !chain->empty();
      ++tested;
    }
  }
  EXPECT_GT(wrapped, 100);  // the cases exercise real wrapping, not only straight cables
}

TEST(WrapChainTurning, FromZeroIsTheHullChainWhereThatTurnsLessThanHalfATurn) {
  test::Random rng(11);
  int tested = 0, wrapped = 0;
  std::vector<int> chain;
  while (tested < 400) {
    const auto poly = randomConvexPolygon(rng);
    if (!isConvexCCW(poly)) continue;
    const Vec2 a = rng.point(-3, 3), b = rng.point(-3, 3);
    if (inside(poly, a) || inside(poly, b) || (a - b).norm() < 1e-3) continue;
    for (WrapSide side : {WrapSide::Left, WrapSide::Right}) {
      const auto hull = wrapChain(a, b, poly, side);
      const auto turn = wrapChainTurning(a, b, poly, side, 0.0, chain);
      ASSERT_TRUE(hull && turn);
      // The turn of the hull chain's path, measured directly.
      std::vector<Vec2> path{a};
      for (int i : *hull) path.push_back(poly[i]);
      path.push_back(b);
      double hullTurn = 0;
      for (size_t i = 1; i + 1 < path.size(); ++i) {
        const Vec2 in = path[i] - path[i - 1], out = path[i + 1] - path[i];
        hullTurn += (side == WrapSide::Left ? -1 : 1) * std::atan2(cross(in, out), in.dot(out));
      }
      if (hullTurn < M_PI - 1e-9) {
        EXPECT_EQ(chain, *hull) << "case " << tested;
        EXPECT_NEAR(std::max(*turn, 0.0), hullTurn, 1e-9);
      }
      wrapped += !chain.empty();
      ++tested;
    }
  }
  EXPECT_GT(wrapped, 100);
}

TEST(WrapChainTurning, WholeTurnsFollowTheReference) {
  // The square [-1, 1]^2 and a cable from a = (-3, 0.5) to b = (-3, -0.5) on its left, both
  // terminals on the square's left: hooked round its far side over all four corners, the path
  // turns by pi + 2 atan(1/4) (more than half a turn: no hull chain between a and b holds it).
  const std::vector<Vec2> square{Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)};
  const Vec2 a(-3, 0.5), b(-3, -0.5);
  std::vector<int> chain;
  const auto hooked = wrapChainTurning(a, b, square, WrapSide::Left, M_PI, chain);
  ASSERT_TRUE(hooked);
  EXPECT_EQ(chain, (std::vector<int>{3, 2, 1, 0}));
  EXPECT_NEAR(*hooked, M_PI + 2 * std::atan(0.25), 1e-12);
  const double once = chainLength(a, b, square, chain);
  EXPECT_NEAR(once, 2 * std::hypot(2.0, 0.5) + 6, 1e-12);
  // From near 0 (a polygon that just joined) the same geometry is the straight cable.
  EXPECT_LE(*wrapChainTurning(a, b, square, WrapSide::Left, 0.0, chain), 0.0);
  EXPECT_TRUE(chain.empty());
  // One whole turn more: every vertex once more, ending where the walk ends; the length grows
  // by the perimeter.
  const auto twice = wrapChainTurning(a, b, square, WrapSide::Left, *hooked + 2 * M_PI, chain);
  EXPECT_NEAR(*twice, *hooked + 2 * M_PI, 1e-12);
  EXPECT_EQ(chain, (std::vector<int>{3, 2, 1, 0, 3, 2, 1, 0}));
  EXPECT_NEAR(chainLength(a, b, square, chain), once + 8, 1e-12);
}

// A terminal on a face, in the hull by no more than the poses' rounding (a weight hanging along a
// square's side, docs/polygon_friction.md "Elastic cables"), has the tangent vertex of a point
// just outside that face, for either side and end; deeper in, or outside, it has none here.
TEST(TangentVertexOnFace, IsTheTangentFromJustOutsideTheFace) {
  test::Random rng(23);
  int tested = 0;
  while (tested < 300) {
    const auto poly = randomConvexPolygon(rng);
    if (!isConvexCCW(poly)) continue;
    const int n = static_cast<int>(poly.size()), face = rng.integer(0, n - 1);
    const Vec2 p = poly[face], edge = poly[(face + 1) % n] - p;
    if (edge.norm() < 0.05) continue;
    const Vec2 in = Vec2(-edge.y(), edge.x()) / edge.norm();  // into the hull
    // Corners that turn the boundary clearly: from just outside, the face's ends are the tangents.
    const Vec2 before = poly[(face + n - 1) % n], after = poly[(face + 2) % n];
    if (in.dot(before - p) < 1e-2 || in.dot(after - p) < 1e-2) continue;
    const Vec2 on = p + rng.uniform(0.2, 0.8) * edge;
    const double tolerance = poseRounding(2.0);
    for (const WrapSide side : {WrapSide::Left, WrapSide::Right})
      for (const bool into : {false, true}) {
        const int expected = tangentVertex(on - 1e-6 * in, poly, side, into);
        EXPECT_TRUE(expected == face || expected == (face + 1) % n) << tested;
        for (const double depth : {1e-11, 0.5 * tolerance})
          EXPECT_EQ(tangentVertexOnFace(on + depth * in, poly, side, into, tolerance), expected)
              << tested << " depth " << depth;
        EXPECT_EQ(tangentVertexOnFace(on + 2 * tolerance * in, poly, side, into, tolerance), -1);
        EXPECT_EQ(tangentVertexOnFace(on - 1e-6 * in, poly, side, into, tolerance), -1);
      }
    ++tested;
  }
}

TEST(WrapChain, SquareFromBothSides) {
  const std::vector<Vec2> square{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  const Vec2 a(-2, 0), b(2, 0);
  EXPECT_EQ(*wrapChain(a, b, square, WrapSide::Left), (std::vector<int>{3, 2}));   // over the top
  EXPECT_EQ(*wrapChain(a, b, square, WrapSide::Right), (std::vector<int>{0, 1}));  // underneath
  EXPECT_NEAR(chainLength(a, b, square, {3, 2}), 2 * std::hypot(1.5, 0.5) + 1, 1e-15);
}

TEST(WrapChain, TerminalInsideHasNoPath) {
  const std::vector<Vec2> square{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  EXPECT_FALSE(wrapChain(Vec2(0.1, 0.4), Vec2(2, 2), square, WrapSide::Left).has_value());
}

TEST(WrapChain, PolygonOnTheOtherSideLeavesTheCableStraight) {
  const std::vector<Vec2> square{{-0.5, 1}, {0.5, 1}, {0.5, 2}, {-0.5, 2}};
  EXPECT_TRUE(wrapChain(Vec2(-2, 0), Vec2(2, 0), square, WrapSide::Right)->empty());
}

TEST(SegmentCutsPolygon, CrossingTouchingAndMissing) {
  const std::vector<Vec2> square{{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  EXPECT_TRUE(segmentCutsPolygon(Vec2(-2, 0), Vec2(2, 0.1), square));
  EXPECT_FALSE(segmentCutsPolygon(Vec2(-2, 0.5), Vec2(2, 0.5), square));  // along an edge
  EXPECT_FALSE(segmentCutsPolygon(Vec2(-2, 0), Vec2(-0.6, 0), square));   // stops short
}

TEST(IsConvexCCW, RejectsClockwiseAndReflex) {
  EXPECT_TRUE(isConvexCCW(std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
  EXPECT_FALSE(isConvexCCW(std::vector<Vec2>{{0, 0}, {0, 1}, {1, 0}}));
  EXPECT_FALSE(isConvexCCW(std::vector<Vec2>{{0, 0}, {2, 0}, {1, 0.2}, {2, 2}, {0, 2}}));
  EXPECT_FALSE(isConvexCCW(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}, {0, 1}}));
}

}  // namespace
}  // namespace cablelab
