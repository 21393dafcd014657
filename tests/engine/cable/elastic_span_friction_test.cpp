// An elastic band over a polygon with friction (docs/polygon_friction.md, "Elastic cables"):
// its spans stick, each a spring of its own material, and slide after the step where their
// tensions break the capstan ratio (Cable::slideElasticSpans).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace elastic_span_friction_test {  // named: unity batches join test files

using test::hangingMass;

constexpr double kG = 9.81;
using test::kDt;

struct Band {
  double mu = 0.3;
  double m1 = 1, m2 = 1;    ///< kg, hanging left and right
  double stiffness = 400;   ///< N/m, the whole band's
  double damping = 20;      ///< N s/m
  double restLength = 3.0;  ///< m (the band's length at the start is 3.6 m)
  double preload = 0.0;     ///< m
};

// A fixed 0.4 m square with a flat top at y = 3.2; the band hangs straight down its sides to the
// masses, turning 90 degrees at each top corner (180 in all).
SceneDef bandOverSquare(const Band& b) {
  SceneDef s;
  s.name = "band-over-square";
  s.bodies = {hangingMass("left", Vec2(-0.2, 1.5), b.m1),
              hangingMass("right", Vec2(0.2, 1.5), b.m2)};
  PulleyDef over;
  over.kind = PulleyDef::Kind::Polygon;
  over.side = WrapSide::Left;
  over.turns = 0.5;  // over the top from the start
  over.vertices = {Vec2(-0.2, 2.8), Vec2(0.2, 2.8), Vec2(0.2, 3.2), Vec2(-0.2, 3.2)};
  over.grip = b.mu > 0 ? Grip::Capstan : Grip::Frictionless;
  over.mu = b.mu;
  CableDef band;
  band.name = "band";
  band.start = {"left", Vec2(0, 0.1)};
  band.end = {"right", Vec2(0, 0.1)};
  band.pulleys = {over};
  band.stiffness = b.stiffness;
  band.damping = b.damping;
  band.restLength = b.restLength;
  band.preload = b.preload;
  s.cables = {band};
  return s;
}

// Where the band splits, every span starts with the unsplit band's tension: each piece gets
// material in proportion to its length (one strain throughout).
TEST(ElasticSpanFriction, SplittingKeepsTheTension) {
  Band b;
  b.preload = 0.4;
  World w(bandOverSquare(b), "test");
  const Cable& band = w.cable(0);
  ASSERT_EQ(band.spanCount(), 2);
  const double unsplit = b.stiffness * (band.length() - (b.restLength - b.preload));
  for (int k = 0; k < 2; ++k)
    EXPECT_NEAR(band.spanStiffness(k) * band.spanStretch(k), unsplit, 1e-9 * unsplit) << k;
}

// Below the capstan ratio the band holds both masses: each hangs at rest on its own span,
// tension m g, where a frictionless band lets the heavier one fall.
TEST(ElasticSpanFriction, HoldsBelowTheCapstanRatio) {
  Band b;
  b.m1 = 1.5;  // ratio 1.5 < e^(0.3 pi) = 2.57
  World w(bandOverSquare(b), "test");
  for (int i = 0; i < 600; ++i) w.step(kDt);  // 10 s: the band's damping settles both masses
  const Cable& band = w.cable(0);
  ASSERT_EQ(band.spanCount(), 2);
  EXPECT_NEAR(band.spanTension(0), b.m1 * kG, 0.01 * b.m1 * kG);
  EXPECT_NEAR(band.spanTension(1), b.m2 * kG, 0.01 * b.m2 * kG);
  EXPECT_LT(w.body(w.findBody("left")).velocity.norm(), 1e-3);
  EXPECT_LT(w.body(w.findBody("right")).velocity.norm(), 1e-3);

  b.mu = 0;
  World frictionless(bandOverSquare(b), "test");
  for (int i = 0; i < 120; ++i) frictionless.step(kDt);
  EXPECT_LT(frictionless.body(0).position.y(), w.body(0).position.y() - 0.1);
}

// Above it the band slides over the corners: its tensions settle at exactly the capstan ratio and
// the masses at the capstan acceleration g (m1 - E m2) / (m1 + E m2). Known broken, so disabled:
// the slide after each sub-step (Cable::slideElasticSpans) does run, but the masses stay at rest
// with the tensions in the masses' ratio (measured: acceleration 2e-4 m/s^2 against 3.27). Why:
// the slide moves material between the spans, not the masses; in the next solve each span, stuck,
// holds its mass again, so the material creeps about 0.7 mm a step while the masses barely move.
// What would fix it: the solve itself letting elastic spans past the ratio slide within the step,
// as stage 6b (mergeSlidingSpans) does for rigid ones (docs/polygon_friction.md).
TEST(ElasticSpanFriction, SlidesAtTheCapstanRatioAbove) {
  for (const double mu : {0.15, 0.3}) {
    Band b;
    b.mu = mu;
    // A stiff undamped band: a small bounce at the start. (The band's damping, which the
    // solver applies to the span's length rate, would resist the slide itself.)
    b.stiffness = 4000, b.damping = 0;
    const double ratio = std::exp(mu * M_PI);
    b.m1 = 2 * ratio * b.m2;
    // Both spans start near the light mass's tension when sliding (m2 (g + a)).
    b.restLength = 3.6 - 1.5 * b.m2 * kG / b.stiffness;
    World w(bandOverSquare(b), "test");
    for (int i = 0; i < 24; ++i) w.step(kDt);  // 0.4 s: the bounce has died down
    const Cable& band = w.cable(0);
    ASSERT_EQ(band.spanCount(), 2);
    EXPECT_NEAR(band.spanTension(0) / band.spanTension(1), ratio, 0.01 * ratio) << mu;
    const double v0 = w.body(0).velocity.y(), t0 = w.time();
    for (int i = 0; i < 12; ++i) w.step(kDt);  // 0.2 s, before the light mass reaches the top
    const double a = (w.body(0).velocity.y() - v0) / (w.time() - t0);
    const double expected = -kG * (b.m1 - ratio * b.m2) / (b.m1 + ratio * b.m2);
    EXPECT_NEAR(a, expected, 0.03 * std::abs(expected)) << mu;
  }
}

}  // namespace elastic_span_friction_test
}  // namespace cablelab
