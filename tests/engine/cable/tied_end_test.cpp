// A cable end tied to the polygon it winds round (engine/cable/tied_end.cpp): the corner it leaves
// the hull at, and the wound length over many turns against the analytic one.
#include "engine/cable/tied_end.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/cable/wrap.h"

namespace cablelab {
namespace tied_end_test {

// A regular polygon of `sides` corners `radius` from `centre`, the first at angle `phase`.
std::vector<Vec2> regular(int sides, double radius, double phase, const Vec2& centre) {
  std::vector<Vec2> p;
  for (int k = 0; k < sides; ++k) {
    const double a = phase + 2 * M_PI * k / sides;
    p.push_back(centre + radius * Vec2(std::cos(a), std::sin(a)));
  }
  return p;
}

double perimeter(const std::vector<Vec2>& p) {
  double total = 0;
  for (size_t i = 0; i < p.size(); ++i) total += (p[(i + 1) % p.size()] - p[i]).norm();
  return total;
}

TEST(TiedEnd, TheCornerIsTheOneBeforeTheEndWalkingRoundThePolygon) {
  const std::vector<Vec2> hexagon = regular(6, 0.2, 0, Vec2::Zero());
  bool inside = true;
  // At vertex 0: walking counter-clockwise (Right) the cable comes from vertex 5, clockwise
  // (Left) from vertex 1.
  EXPECT_EQ(tiedEndCorner(hexagon[0], hexagon, WrapSide::Right, inside), 5);
  EXPECT_FALSE(inside);
  EXPECT_EQ(tiedEndCorner(hexagon[0], hexagon, WrapSide::Left, inside), 1);
  // Mid-edge 0-1: from vertex 0 counter-clockwise, from vertex 1 clockwise.
  const Vec2 middle = 0.5 * (hexagon[0] + hexagon[1]);
  EXPECT_EQ(tiedEndCorner(middle, hexagon, WrapSide::Right, inside), 0);
  EXPECT_EQ(tiedEndCorner(middle, hexagon, WrapSide::Left, inside), 1);
  EXPECT_FALSE(inside);
  // Inside, nearest edge 2-3: through its first corner on the walk.
  const Vec2 deep = 0.5 * (0.5 * (hexagon[2] + hexagon[3]));
  EXPECT_EQ(tiedEndCorner(deep, hexagon, WrapSide::Right, inside), 2);
  EXPECT_TRUE(inside);
  EXPECT_EQ(tiedEndCorner(deep, hexagon, WrapSide::Left, inside), 3);
  // Outside by a millimetre: an ordinary terminal.
  EXPECT_EQ(tiedEndCorner(Vec2(0.201, 0), hexagon, WrapSide::Right, inside), -1);
}

// The path A -> chain -> end, with the polygon turned by phi about its centre.
struct Wound {
  double length = 0;
  double turn = 0;
  std::vector<int> chain;
  std::vector<Vec2> polygon;
};

Wound woundPath(int sides, double radius, bool atVertex, WrapSide side, double phi, const Vec2& a,
                double reference) {
  // The cable hangs from the polygon's outermost corner on its side (+x for Right), the end tied
  // at that corner or in the middle of the edge the walk goes on along.
  const double phase = (side == WrapSide::Right ? 0.0 : M_PI) + phi;
  Wound w;
  w.polygon = regular(sides, radius, phase, Vec2::Zero());
  const int next = side == WrapSide::Right ? 1 : sides - 1;
  const Vec2 end = atVertex ? w.polygon[0] : 0.5 * (w.polygon[0] + w.polygon[next]);
  bool inside;
  const std::vector<Vec2> rest = regular(sides, radius, phase - phi, Vec2::Zero());
  const Vec2 restEnd = atVertex ? rest[0] : 0.5 * (rest[0] + rest[next]);
  const int corner = tiedEndCorner(restEnd, rest, side, inside);
  const auto turn = wrapChainToTiedEnd(a, w.polygon, side, corner, reference, -1, w.chain);
  EXPECT_TRUE(turn.has_value());
  w.turn = turn.value_or(0);
  w.length = chainLength(a, end, w.polygon, w.chain);
  return w;
}

TEST(TiedEnd, EachTurnWindsOnePerimeterAndTheLengthFollowsTheLeverArm) {
  // Turning the polygon in its winding sense by phi lengthens the path to the fixed free end (a
  // rope of fixed length pulls that end in) at the rate of the distance from the centre to the
  // free segment's line (the lever arm): checked by central differences at every 0.05 rad over
  // 12 turns and back, and the length after k whole turns is the start's plus k perimeters.
  // Triangle to octagon, both sides, end at a corner and mid-edge; the free end below, off the
  // spool's axis.
  for (const int sides : {3, 4, 6, 8})
    for (const WrapSide side : {WrapSide::Right, WrapSide::Left})
      for (const bool atVertex : {true, false}) {
        SCOPED_TRACE(std::to_string(sides) + " sides, " +
                     (side == WrapSide::Right ? "right" : "left") +
                     (atVertex ? ", at a corner" : ", mid-edge"));
        const double sense = side == WrapSide::Right ? 1 : -1, radius = 0.2;
        const Vec2 a(sense * 0.3, -3);
        const double p = perimeter(regular(sides, radius, 0, Vec2::Zero()));
        const double start = 1.3;  // rad: the cable is on the polygon in every case
        double reference = woundPath(sides, radius, atVertex, side, sense * start, a, 0).turn;
        const double first = woundPath(sides, radius, atVertex, side, sense * start, a, 0).length;
        const int turns = 12, perTurn = 126;
        const double d = 2 * M_PI / perTurn, fd = 1e-6;
        for (int dir : {1, -1})
          for (int i = 1; i <= turns * perTurn; ++i) {
            const double phi = start + (dir > 0 ? i : turns * perTurn - i) * d;
            const Wound w = woundPath(sides, radius, atVertex, side, sense * phi, a, reference);
            reference = w.turn;
            ASSERT_FALSE(w.chain.empty());
            if (i % perTurn == 0) {
              const int k = dir > 0 ? i / perTurn : turns - i / perTurn;
              EXPECT_NEAR(w.length, first + k * p, 1e-12);
            }
            // Lever arm: the free segment a -> first corner.
            const Vec2 t = w.polygon[w.chain.front()], u = (t - a).normalized();
            const double arm = std::abs(cross(u, -a));
            const double ahead =
                woundPath(sides, radius, atVertex, side, sense * (phi + fd), a, w.turn).length;
            const double behind =
                woundPath(sides, radius, atVertex, side, sense * (phi - fd), a, w.turn).length;
            // A corner's change between the two (a kink of the length) is left out.
            if (woundPath(sides, radius, atVertex, side, sense * (phi + fd), a, w.turn).chain !=
                woundPath(sides, radius, atVertex, side, sense * (phi - fd), a, w.turn).chain)
              continue;
            EXPECT_NEAR((ahead - behind) / (2 * fd), arm, 1e-6);
          }
      }
}

TEST(TiedEnd, UnwoundPastItsCornerTheCableRunsStraightToTheEnd) {
  // A hexagon tied at its corner 0, the cable hanging straight below it: no turn yet (the
  // path bends at corner 5 only once the hexagon has turned 30 degrees), the chain is empty and
  // the length is the straight one; turned on by 40 degrees the cable wraps corner 5.
  std::vector<int> chain;
  const Vec2 a(0.2, -3);
  const std::vector<Vec2> hexagon = regular(6, 0.2, 0, Vec2::Zero());
  const auto straight = wrapChainToTiedEnd(a, hexagon, WrapSide::Right, 5, 0, -1, chain);
  ASSERT_TRUE(straight.has_value());
  EXPECT_NEAR(*straight, -M_PI / 6, 1e-12);
  EXPECT_TRUE(chain.empty());
  const std::vector<Vec2> turned = regular(6, 0.2, 40 * M_PI / 180, Vec2::Zero());
  const auto wrapped = wrapChainToTiedEnd(a, turned, WrapSide::Right, 5, *straight, -1, chain);
  ASSERT_TRUE(wrapped.has_value());
  EXPECT_GT(*wrapped, 0);
  EXPECT_EQ(chain, std::vector<int>{5});
  // The free end pressed into the hull (wound up to the spool): it keeps the corner it came
  // over (3, half a turn wound), and with none held there is no taut path.
  const Vec2 pressed(0.05, 0);
  const auto held = wrapChainToTiedEnd(pressed, hexagon, WrapSide::Right, 5, M_PI, 3, chain);
  ASSERT_TRUE(held.has_value());
  EXPECT_EQ(chain, (std::vector<int>{3, 4, 5}));
  EXPECT_FALSE(wrapChainToTiedEnd(pressed, hexagon, WrapSide::Right, 5, 0, -1, chain));
}

}  // namespace tied_end_test
}  // namespace cablelab
