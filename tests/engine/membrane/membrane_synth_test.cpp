// Tests for engine/membrane/membrane_synth.h: reproducible, noise of the requested size, the model
// exactly when noise-free, the documented grid, and validated defs.
#include "engine/membrane/membrane_synth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"

namespace cablelab {
namespace {

TEST(MembraneSynth, SameSeedSameDataOtherSeedOtherData) {
  MembraneSynthDef def;
  const auto first = generateMembraneData(def);
  const auto again = generateMembraneData(def);
  def.seed = 2;
  const auto other = generateMembraneData(def);
  ASSERT_EQ(first.size(), static_cast<size_t>(def.nx * def.ny));
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].fy, again[i].fy);
    EXPECT_EQ(first[i].angleDeg, again[i].angleDeg);
  }
  EXPECT_NE(first[0].fy, other[0].fy);
}

TEST(MembraneSynth, NoiseFreeDataIsTheModelOnTheDocumentedGrid) {
  MembraneSynthDef def;
  def.noiseFy = 0.0;
  def.noiseAngleDeg = 0.0;
  def.nx = 3;
  def.ny = 2;
  const auto rows = generateMembraneData(def);
  ASSERT_EQ(rows.size(), 6u);
  // Default pulleys (-0.2, 0), (0.2, 0): along 0.1..0.9 of 0.4 m, depth 0.05..0.35 below.
  EXPECT_NEAR(rows[0].p.x(), -0.16, 1e-15);
  EXPECT_NEAR(rows[0].p.y(), -0.02, 1e-15);
  EXPECT_NEAR(rows[5].p.x(), 0.16, 1e-15);
  EXPECT_NEAR(rows[5].p.y(), -0.14, 1e-15);
  for (const auto& r : rows) {
    EXPECT_EQ(r.fy, membraneForce(def.geometry, def.params, r.p).y());
    EXPECT_EQ(r.angleDeg, membraneForceAngleDeg(def.geometry, r.p));
  }
}

TEST(MembraneSynth, NoiseHasTheRequestedStandardDeviation) {
  MembraneSynthDef def;
  def.nx = 100;
  def.ny = 100;
  def.noiseFy = 0.05;
  def.noiseAngleDeg = 1.0;
  double sumFy = 0, sumFy2 = 0, sumAngle2 = 0;
  for (const auto& r : generateMembraneData(def)) {
    const double dFy = r.fy - membraneForce(def.geometry, def.params, r.p).y();
    const double dAngle = wrapAngleDeg(r.angleDeg - membraneForceAngleDeg(def.geometry, r.p));
    sumFy += dFy;
    sumFy2 += dFy * dFy;
    sumAngle2 += dAngle * dAngle;
  }
  const double n = 1e4;
  EXPECT_NEAR(sumFy / n, 0.0, 0.002);  // 4 standard errors of the mean
  EXPECT_NEAR(std::sqrt(sumFy2 / n), 0.05, 0.05 * 0.03);
  EXPECT_NEAR(std::sqrt(sumAngle2 / n), 1.0, 0.03);
}

TEST(MembraneSynth, ValidationNamesTheField) {
  auto fieldOf = [](MembraneSynthDef def) -> std::string {
    try {
      validateMembraneSynth(def, "--generate");
    } catch (const InputError& e) {
      return e.field();
    }
    return "";
  };
  MembraneSynthDef def;
  EXPECT_EQ(fieldOf(def), "");
  def.params.k = -1;
  EXPECT_EQ(fieldOf(def), "k");
  def = {};
  def.params.preload = -0.1;
  EXPECT_EQ(fieldOf(def), "preload");
  def = {};
  def.noiseFy = NAN;
  EXPECT_EQ(fieldOf(def), "noise_fy");
  def = {};
  def.nx = 1;
  def.ny = 2;
  EXPECT_EQ(fieldOf(def), "grid");
  def = {};
  def.depthMin = 0.0;
  EXPECT_EQ(fieldOf(def), "depth");
  def = {};
  def.geometry.b = def.geometry.a;
  EXPECT_EQ(fieldOf(def), "pulleys");
}

}  // namespace
}  // namespace cablelab
