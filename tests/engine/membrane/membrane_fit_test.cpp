// Tests for engine/membrane/membrane_fit.h on synthetic data with known parameters: recovery with
// the thesis's noise levels, exact recovery without noise, honest standard errors, and the errors
// for data that cannot determine k and preload.
#include "engine/membrane/membrane_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "engine/core/error.h"
#include "engine/membrane/membrane_synth.h"

namespace cablelab {
namespace {

constexpr double kRecoveryTolerance = 0.02;   // relative, with 0.05 N and 1 degree of noise
constexpr double kExactTolerance = 1e-8;      // relative, without noise
constexpr double kMinTwoSigmaCoverage = 0.8;  // fraction of fits with the truth within 2 SE
constexpr int kTrials = 100;                  // seeds and parameter sets (>= 20 asked)

/// Trial t: k in [15, 60] N/m, preload in [0.3, 1.0] m, pulleys 0.4 m apart around a shifted
/// centre, pressed from below (even t) or above (odd t), 16 x 12 = 192 points.
MembraneSynthDef trial(int t, double noiseFy, double noiseAngleDeg) {
  std::mt19937_64 rng(1000 + t);
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  MembraneSynthDef def;
  def.params.k = 15.0 + 45.0 * uniform();
  def.params.preload = 0.3 + 0.7 * uniform();
  const Vec2 centre(uniform() - 0.5, uniform() - 0.5);
  def.geometry = {centre + Vec2(-0.2, 0.0), centre + Vec2(0.2, 0.0)};
  def.noiseFy = noiseFy;
  def.noiseAngleDeg = noiseAngleDeg;
  def.seed = 5000 + t;
  def.nx = 16;
  def.ny = 12;
  if (t % 2 == 1) {
    def.depthMin = -0.05;
    def.depthMax = -0.35;
  }
  return def;
}

double relativeError(double estimate, double truth) {
  return std::abs(estimate / truth - 1.0);
}

TEST(MembraneFit, RecoversParametersWithThesisNoiseAndHonestErrors) {
  double worstK = 0.0, worstPreload = 0.0;
  int coveredK = 0, coveredPreload = 0, coveredBoth = 0;
  for (int t = 0; t < kTrials; ++t) {
    const MembraneSynthDef def = trial(t, 0.05, 1.0);
    const auto rows = generateMembraneData(def);
    const MembraneFitResult fit = fitMembrane(def.geometry, rows);
    const double errorK = relativeError(fit.params.k, def.params.k);
    const double errorPreload = relativeError(fit.params.preload, def.params.preload);
    EXPECT_LT(errorK, kRecoveryTolerance) << "trial " << t;
    EXPECT_LT(errorPreload, kRecoveryTolerance) << "trial " << t;
    worstK = std::max(worstK, errorK);
    worstPreload = std::max(worstPreload, errorPreload);
    const bool inK = std::abs(fit.params.k - def.params.k) <= 2.0 * fit.kStderr;
    const bool inPreload =
        std::abs(fit.params.preload - def.params.preload) <= 2.0 * fit.preloadStderr;
    coveredK += inK;
    coveredPreload += inPreload;
    coveredBoth += inK && inPreload;
    // The residuals measure the noise that was put in.
    EXPECT_NEAR(fit.rmsFy, 0.05, 0.01) << "trial " << t;
    EXPECT_NEAR(fit.rmsAngleDeg, 1.0, 0.2) << "trial " << t;
    EXPECT_EQ(fit.rows, 192);
  }
  EXPECT_GE(coveredBoth, kMinTwoSigmaCoverage * kTrials);
  std::printf(
      "[ figures  ] %d trials: worst |k error| %.4f%%, worst |preload error| %.4f%%, "
      "truth within 2 SE: k %d, preload %d, both %d\n",
      kTrials, 100 * worstK, 100 * worstPreload, coveredK, coveredPreload, coveredBoth);
}

TEST(MembraneFit, RecoversParametersExactlyWithoutNoise) {
  for (int t = 0; t < 20; ++t) {
    const MembraneSynthDef def = trial(t, 0.0, 0.0);
    const MembraneFitResult fit = fitMembrane(def.geometry, generateMembraneData(def));
    EXPECT_LT(relativeError(fit.params.k, def.params.k), kExactTolerance) << "trial " << t;
    EXPECT_LT(relativeError(fit.params.preload, def.params.preload), kExactTolerance)
        << "trial " << t;
    EXPECT_LT(fit.rmsFy, 1e-9);
    EXPECT_LT(fit.rmsAngleDeg, 1e-9);
  }
}

TEST(MembraneFit, GivenNoiseLevelsGiveTheSameErrorsAsEstimatedOnes) {
  const MembraneSynthDef def = trial(3, 0.05, 1.0);
  const auto rows = generateMembraneData(def);
  const MembraneFitResult estimated = fitMembrane(def.geometry, rows);
  MembraneFitOptions given;
  given.sigmaFy = 0.05;
  given.sigmaAngleDeg = 1.0;
  const MembraneFitResult fixed = fitMembrane(def.geometry, rows, given);
  EXPECT_EQ(fixed.rounds, 1);
  EXPECT_GE(estimated.rounds, 2);
  EXPECT_EQ(fixed.sigmaFy, 0.05);
  EXPECT_NEAR(fixed.params.k, estimated.params.k, 1e-9 * def.params.k);
  EXPECT_NEAR(fixed.kStderr / estimated.kStderr, 1.0, 0.2);
  EXPECT_NEAR(fixed.chi2PerDof, 1.0, 0.3);
  EXPECT_NEAR(estimated.chi2PerDof, 1.0, 1e-6);  // estimated levels make it 1 by construction
  // Standard errors scale with the stated noise level.
  given.sigmaFy = 0.5;
  EXPECT_NEAR(fitMembrane(def.geometry, rows, given).kStderr / fixed.kStderr, 10.0, 1e-6);
}

TEST(MembraneFit, AngleResidualsAreWrapped) {
  const MembraneSynthDef def = trial(4, 0.05, 1.0);
  auto rows = generateMembraneData(def);
  const MembraneFitResult before = fitMembrane(def.geometry, rows);
  for (size_t i = 0; i < rows.size(); ++i) rows[i].angleDeg += (i % 2 ? 360.0 : -720.0);
  const MembraneFitResult after = fitMembrane(def.geometry, rows);
  EXPECT_NEAR(after.rmsAngleDeg, before.rmsAngleDeg, 1e-9);
  EXPECT_NEAR(after.params.k, before.params.k, 1e-9 * before.params.k);
}

TEST(MembraneFit, AngleResidualsAcrossTheCutAreSmall) {
  // Points beyond pulley B on the pulley line are pulled towards -x: direction +-180 degrees.
  const MembraneGeometry g{Vec2(-0.2, 0.0), Vec2(0.2, 0.0)};
  const MembraneParams truth{25.0, 0.8};
  std::vector<MembraneSample> rows;
  for (double x : {0.3, 0.35, 0.4, 0.45}) {
    const Vec2 p(x, x < 0.37 ? 1e-3 : -1e-3);
    const double measured = membraneForceAngleDeg(g, p) + (p.y() > 0 ? -0.5 : 0.5);
    rows.push_back({p, membraneForce(g, truth, p).y(), wrapAngleDeg(measured)});
    ASSERT_GT(std::abs(rows.back().angleDeg), 179.5);  // the measurement crossed the cut
  }
  const MembraneFitResult fit = fitMembrane(g, rows);
  EXPECT_NEAR(fit.rmsAngleDeg, 0.5, 1e-6);  // 359.5 if the residuals were not wrapped
}

TEST(MembraneFit, RejectsDataThatCannotSeparateKAndPreload) {
  // Every point on one ellipse with the pulleys as foci: one stretch, so only k (s + preload).
  const MembraneGeometry g{Vec2(-0.2, 0.0), Vec2(0.2, 0.0)};
  const double semiMajor = 0.25, semiMinor = std::sqrt(semiMajor * semiMajor - 0.04);
  std::vector<MembraneSample> rows;
  for (double t : {-2.5, -2.0, -1.5, -1.0, -0.5}) {
    const Vec2 p(semiMajor * std::cos(t), semiMinor * std::sin(t));
    rows.push_back({p, membraneForce(g, {25.0, 0.8}, p).y(), membraneForceAngleDeg(g, p)});
  }
  EXPECT_THROW(fitMembrane(g, rows), InputError);
}

TEST(MembraneFit, RejectsForcesPointingAwayFromTheBand) {
  const MembraneSynthDef def = trial(0, 0.05, 1.0);
  auto rows = generateMembraneData(def);
  for (auto& row : rows) row.fy = -row.fy;
  try {
    fitMembrane(def.geometry, rows, {.source = "flipped.csv"});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "flipped.csv");
    EXPECT_EQ(e.field(), "fy");
  }
}

TEST(MembraneFit, RejectsTooFewRows) {
  const MembraneGeometry g;
  const std::vector<MembraneSample> rows = {{Vec2(0.0, -0.1), 5.0, 90.0},
                                            {Vec2(0.1, -0.1), 5.0, 80.0}};
  EXPECT_THROW(fitMembrane(g, rows), InputError);
}

}  // namespace
}  // namespace cablelab
