// An elastic band over a polygon with friction (docs/polygon_friction.md, "Elastic cables"):
// its spans stick, each a spring of its own material, and slide within the step where their
// tensions break the capstan ratio (stage 6b, Cable::shareSlidMaterial).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "tests/support/engine_test_support.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace elastic_span_friction_test {  // named: unity batches join test files

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
  SceneDef s = test::bandOverPolygon(
      {Vec2(-0.2, 2.8), Vec2(0.2, 2.8), Vec2(0.2, 3.2), Vec2(-0.2, 3.2)}, b.mu, b.m1, b.m2);
  CableDef& band = s.cables[0];
  band.stiffness = b.stiffness;
  band.damping = b.damping;
  band.restLength = b.restLength;
  band.preload = b.preload;
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

// Above it the band slides over the corners within the step (stage 6b merges its spans, each its
// own spring): its tensions settle at exactly the capstan ratio and the masses at the capstan
// acceleration g (m1 - E m2) / (m1 + E m2). (Sliding only after the step, the masses stayed at
// rest while material crept between the spans.)
TEST(ElasticSpanFriction, SlidesAtTheCapstanRatioAbove) {
  for (const double mu : {0.15, 0.3}) {
    Band b;
    b.mu = mu;
    // A stiff undamped band: a small bounce at the start.
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

// A step of the scene clock: dt in `substeps` equal sub-steps (60 Hz x1, x4; 240 Hz).
struct Stepping {
  double dt = kDt;
  int substeps = 1;
};
const Stepping kSteppings[] = {{kDt, 1}, {kDt, 4}, {1.0 / 240, 1}};

// Kinetic, gravity's and the spans' elastic energy (J): each span a spring of its own material.
// (The band between the corners of the fixed square keeps its length and material.)
double bandEnergy(const World& w) {
  double e = 0;
  for (int b = 0; b < w.bodyCount(); ++b) {
    const double m = w.scene().bodies[b].mass;
    e += 0.5 * m * w.body(b).velocity.squaredNorm() + m * kG * w.body(b).position.y();
  }
  const Cable& band = w.cable(0);
  for (int k = 0; k < band.spanCount(); ++k)
    e += 0.5 * band.spanStiffness(k) * std::pow(std::max(0.0, band.spanStretch(k)), 2);
  return e;
}

// Sliding, m1 ÿ1 = m1 g - T1 and m2 ÿ2 = T2 - m2 g with T1 = E T2 (ÿ1 down, ÿ2 up): the
// weighted acceleration (m1 ÿ1 + E m2 ÿ2) / (m1 + E m2) is the capstan acceleration
// g (m1 - E m2) / (m1 + E m2) exactly, however the band's stretch bounces. Its mean over [t0, t1].
struct Slide {
  double weighted = 0;     ///< m/s^2, the mean weighted acceleration
  double heavy = 0;        ///< m/s^2, the mean acceleration of m1 (down)
  double worstRatio = 0;   ///< the largest |T0 / T1 / E - 1| over the steps
  double worstRise = 0;    ///< J, the largest rise of bandEnergy in one step
  double energyScale = 0;  ///< J, |bandEnergy| at the start
};
Slide slide(const Band& b, const Stepping& stepping, double t0, double t1) {
  World w(bandOverSquare(b), "test");
  const double ratio = std::exp(b.mu * M_PI);
  const int left = w.findBody("left"), right = w.findBody("right");
  auto momentum = [&] {
    return -b.m1 * w.body(left).velocity.y() + ratio * b.m2 * w.body(right).velocity.y();
  };
  Slide s;
  s.energyScale = std::abs(bandEnergy(w));
  double start = 0, startHeavy = 0, previous = bandEnergy(w);
  while (w.time() < t1 - 1e-9) {
    if (std::abs(w.time() - t0) < 1e-9) start = momentum(), startHeavy = -w.body(left).velocity.y();
    w.step(stepping.dt, stepping.substeps);
    const double e = bandEnergy(w);
    s.worstRise = std::max(s.worstRise, e - previous);
    previous = e;
    const Cable& band = w.cable(0);
    if (w.time() > t0 - 1e-9)
      s.worstRatio =
          std::max(s.worstRatio, std::abs(band.spanTension(0) / band.spanTension(1) / ratio - 1));
  }
  s.weighted = (momentum() - start) / ((b.m1 + ratio * b.m2) * (t1 - t0));
  s.heavy = (-w.body(left).velocity.y() - startHeavy) / (t1 - t0);
  return s;
}

// Adversarial: soft to stiff bands, damped or not, at 60 Hz in 1 or 4 sub-steps and at 240 Hz,
// for both mu: the tensions stay at the capstan ratio while the band slides, the masses take the
// capstan acceleration, and the friction never gains energy.
TEST(ElasticSpanFriction, SlidesAtTheRatioForAnyStiffnessDampingAndStep) {
  for (const double mu : {0.15, 0.3})
    for (const double stiffness : {400.0, 4000.0, 1e5})
      for (const double damping : {0.0, 20.0})
        for (const Stepping& stepping : kSteppings) {
          Band b;
          b.mu = mu, b.stiffness = stiffness, b.damping = damping;
          const double ratio = std::exp(mu * M_PI);
          b.m1 = 2 * ratio * b.m2;
          b.restLength = 3.6 - 1.5 * b.m2 * kG / b.stiffness;
          const Slide s = slide(b, stepping, 0.1, 0.5);
          const double expected = kG * (b.m1 - ratio * b.m2) / (b.m1 + ratio * b.m2);
          SCOPED_TRACE("mu " + std::to_string(mu) + " k " + std::to_string(stiffness) + " d " +
                       std::to_string(damping) + " dt " + std::to_string(stepping.dt) + " x" +
                       std::to_string(stepping.substeps));
          EXPECT_LT(s.worstRatio, 0.01);
          EXPECT_NEAR(s.weighted, expected, 0.03 * expected);
          EXPECT_LT(s.worstRise, 1e-3 * s.energyScale);
        }
}

// Masses just inside the ratio hold, just outside it slide: a damped band, its bounce settled
// after 1 s, then 2 s more (the light mass stays below the square).
TEST(ElasticSpanFriction, HoldsJustBelowAndSlidesJustAboveTheRatio) {
  for (const double mu : {0.15, 0.3})
    for (const double share : {0.97, 1.03}) {
      Band b;
      b.mu = mu, b.stiffness = 4000, b.damping = 40;
      const double ratio = std::exp(mu * M_PI);
      b.m2 = 1.3;
      b.m1 = share * ratio * b.m2;
      b.restLength = 3.6 - 0.5 * (b.m1 + b.m2) * kG / b.stiffness;
      SCOPED_TRACE("mu " + std::to_string(mu) + " m1 / (E m2) " + std::to_string(share));
      if (share < 1) {
        World w(bandOverSquare(b), "test");
        while (w.time() < 3.0) w.step(kDt);
        const Cable& band = w.cable(0);
        EXPECT_NEAR(band.spanTension(0), b.m1 * kG, 0.01 * b.m1 * kG);
        EXPECT_NEAR(band.spanTension(1), b.m2 * kG, 0.01 * b.m2 * kG);
        EXPECT_LT(w.body(w.findBody("left")).velocity.norm(), 1e-3);
        EXPECT_LT(w.body(w.findBody("right")).velocity.norm(), 1e-3);
        continue;
      }
      const Slide s = slide(b, kSteppings[0], 1.0, 3.0);
      const double expected = kG * (b.m1 - ratio * b.m2) / (b.m1 + ratio * b.m2);  // 0.145
      EXPECT_LT(s.worstRatio, 0.01);
      EXPECT_NEAR(s.weighted, expected, 0.03 * expected);
      EXPECT_NEAR(s.heavy, expected, 0.03 * expected);
      EXPECT_LT(s.worstRise, 1e-3 * s.energyScale);
    }
}

// The other way, on a preloaded band: the right mass heavier, the band slides towards it with
// T_right = E T_left and the weighted acceleration g (m2 - E m1) / (m2 + E m1), every step.
TEST(ElasticSpanFriction, SlidesTheOtherWayOnAPreloadedBand) {
  for (const double mu : {0.15, 0.3}) {
    Band b;
    b.mu = mu, b.stiffness = 1e4, b.damping = 5;
    const double ratio = std::exp(mu * M_PI);
    b.m1 = 0.7;
    b.m2 = 1.5 * ratio * b.m1;
    b.preload = 0.3;
    b.restLength =
        3.6 + b.preload - 1.2 * b.m1 * kG / b.stiffness;  // material 3.6 m - 1.2 m1 g / k
    World w(bandOverSquare(b), "test");
    const int left = w.findBody("left"), right = w.findBody("right");
    const double expected = kG * (b.m2 - ratio * b.m1) / (b.m2 + ratio * b.m1);
    for (int i = 0; i < 36; ++i) {  // 0.6 s
      const double before =
          -b.m2 * w.body(right).velocity.y() + ratio * b.m1 * w.body(left).velocity.y();
      w.step(kDt);
      const double after =
          -b.m2 * w.body(right).velocity.y() + ratio * b.m1 * w.body(left).velocity.y();
      const Cable& band = w.cable(0);
      if (i < 3) continue;  // the first steps: sticking, then merged
      EXPECT_NEAR(band.spanTension(1) / band.spanTension(0), ratio, 0.01 * ratio) << mu << " " << i;
      EXPECT_NEAR((after - before) / ((b.m2 + ratio * b.m1) * kDt), expected, 0.03 * expected)
          << mu << " " << i;
    }
    EXPECT_LT(w.body(right).position.y(), 1.5 - 0.5 * 0.5 * expected * 0.36);  // fell
  }
}

}  // namespace elastic_span_friction_test
}  // namespace cablelab
