// Tests for engine/statics.{h,cpp}, statics_newton, statics_sensitivity, box_reduction,
// statics_io: the model, the default path against the SOCP, and the corner cases of
// docs/model.md#statics.
#include "engine/statics/statics.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>

#include "engine/core/error.h"
#include "engine/statics/box_reduction.h"
#include "engine/statics/socp.h"
#include "engine/statics/statics_io.h"
#include "engine/statics/statics_newton.h"
#include "engine/statics/statics_random.h"
#include "engine/statics/statics_sensitivity.h"

namespace cablelab {
namespace {

constexpr double kPositionTol = 1e-8;     // SOCP vs Newton, unique minimiser (m)
constexpr double kEnergyTol = 1e-10;      // SOCP vs Newton energy (relative to max(1, E))
constexpr double kForceTol = 1e-8;        // |net force| / max tension at the answer
constexpr double kSensitivityTol = 1e-5;  // analytic vs central differences (relative)

StaticsProblem twoCables() {
  StaticsProblem problem;
  problem.cables = {{Vec2(-1, 1), Vec2(1, 1), 150, 1.5}, {Vec2(-1, -1), Vec2(1, -1), 150, 1.5}};
  return problem;
}

/// True when the minimiser is unique: strictly on a fingertip, or a positive definite Hessian.
bool uniqueMinimiser(const StaticsProblem& problem, const StaticsResult& r) {
  if (r.anchor >= 0) return staticsKink(problem, r.p).excess() < -1e-9 * r.tensions[r.anchor / 2];
  const StaticsDerivatives d = staticsDerivatives(problem, r.p);
  if (d.maxTension == 0) return false;
  const double det = d.hessian.determinant(), tr = d.hessian.trace();
  return det > 1e-6 * tr * tr;
}

TEST(Statics, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int trial = 0; trial < 50; ++trial) {
    const StaticsProblem problem = randomStaticsProblem(rng, {.cables = 5});
    const Vec2 p(u(rng), u(rng));
    const StaticsDerivatives d = staticsDerivatives(problem, p);
    const double h = 1e-6;
    for (int k = 0; k < 2; ++k) {
      const Vec2 e = Vec2::Unit(k) * h;
      const double dE = (staticsEnergy(problem, p + e) - staticsEnergy(problem, p - e)) / (2 * h);
      EXPECT_NEAR(d.gradient(k), dE, 1e-6 * (1 + std::abs(dE)));
      const Vec2 dg = (staticsDerivatives(problem, p + e).gradient -
                       staticsDerivatives(problem, p - e).gradient) /
                      (2 * h);
      EXPECT_NEAR(d.hessian(0, k), dg.x(), 1e-5 * (1 + d.hessian.norm()));
      EXPECT_NEAR(d.hessian(1, k), dg.y(), 1e-5 * (1 + d.hessian.norm()));
    }
    EXPECT_NEAR(d.energy, staticsEnergy(problem, p), 1e-12 * (1 + d.energy));
  }
}

TEST(Statics, ValidationNamesTheField) {
  StaticsProblem problem = twoCables();
  problem.cables[1].k = 0;
  try {
    validateStatics(problem, "f.json");
    FAIL() << "k = 0 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "cables[1].k");
    EXPECT_EQ(e.source(), "f.json");
  }
  problem = twoCables();
  problem.cables[0].L = -1;
  EXPECT_THROW(validateStatics(problem, "f"), InputError);
  problem = twoCables();
  problem.cables[0].a.x() = NAN;
  EXPECT_THROW(validateStatics(problem, "f"), InputError);
  problem = twoCables();
  problem.p0 = Vec2(INFINITY, 0);
  EXPECT_THROW(validateStatics(problem, "f"), InputError);
  EXPECT_THROW(validateStatics(StaticsProblem{}, "f"), InputError);
  EXPECT_NO_THROW(validateStatics(twoCables(), "f"));
}

TEST(Statics, SymmetricProblemHasKnownAnswer) {
  const StaticsResult r = solveStatics(twoCables());
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.p.x(), 0, 1e-12);
  EXPECT_NEAR(r.p.y(), 0, 1e-12);
  const double length = 2 * std::sqrt(2.0);
  EXPECT_NEAR(r.lengths[0], length, 1e-12);
  EXPECT_NEAR(r.tensions[1], 150 * (length - 1.5), 1e-9);
  EXPECT_NEAR(r.energy, 2 * 0.5 * 150 * std::pow(length - 1.5, 2), 1e-9);
}

TEST(Statics, AllSlackIsZeroEnergy) {
  StaticsProblem problem = twoCables();
  for (StaticsCable& c : problem.cables) c.L = 10;
  for (const StaticsResult& r : {solveStatics(problem), solveStaticsSocp(problem)}) {
    EXPECT_EQ(r.energy, 0);
    EXPECT_EQ(r.residual, 0);
    EXPECT_EQ(r.tensions[0], 0);
  }
}

// Acceptance: >= 200 seeded instances, 2..8 cables, some slack, some minimisers on a fingertip.
TEST(Statics, DefaultPathAgreesWithSocpOnRandomInstances) {
  std::mt19937_64 rng(20240611);
  SocpWorkspace workspace;
  int unique = 0, onFingertip = 0, withSlack = 0;
  for (int i = 0; i < 300; ++i) {
    RandomStaticsOptions options;
    options.cables = 2 + i % 7;
    options.onFingertip = i % 4 == 3;
    const StaticsProblem problem = randomStaticsProblem(rng, options);
    StaticsResult socp, fast;
    solveStaticsSocp(problem, socp, workspace);
    solveStatics(problem, fast);
    SCOPED_TRACE("instance " + std::to_string(i));
    EXPECT_LE(socp.iterations, 30);
    EXPECT_TRUE(socp.converged);
    EXPECT_TRUE(fast.converged);
    EXPECT_NEAR(socp.energy, fast.energy, kEnergyTol * std::max(1.0, fast.energy));
    // The residual is the subgradient condition where p sits on a fingertip.
    EXPECT_LE(socp.residual, kForceTol);
    EXPECT_LE(fast.residual, kForceTol);
    if (uniqueMinimiser(problem, fast)) {
      ++unique;
      EXPECT_LE((socp.p - fast.p).norm(), kPositionTol);
    }
    if (options.onFingertip) {
      ++onFingertip;
      EXPECT_EQ(fast.anchor, 0);
      EXPECT_EQ(socp.anchor, 0);
      EXPECT_EQ(fast.p, problem.cables[0].a);
    }
    for (double t : fast.tensions) withSlack += t == 0;
  }
  EXPECT_GE(unique, 200);
  EXPECT_GE(onFingertip, 50);
  EXPECT_GE(withSlack, 50);
}

TEST(Statics, PlainNewtonStallsOnAFingertipMinimiser) {
  // docs/model.md#statics: the kink makes plain Newton crawl; the default path must not.
  std::mt19937_64 rng(5);
  int plainFailures = 0;
  for (int i = 0; i < 40; ++i) {
    const StaticsProblem problem = randomStaticsProblem(rng, {.cables = 3, .onFingertip = true});
    NewtonOptions plain;
    plain.detectFingertips = false;
    const StaticsResult r = solveStaticsNewton(problem, plain);
    plainFailures += !(r.converged && r.p == problem.cables[0].a);
    const StaticsResult safe = solveStaticsNewton(problem);
    EXPECT_TRUE(safe.converged);
    EXPECT_EQ(safe.p, problem.cables[0].a);
    EXPECT_FALSE(solveStatics(problem).fellBack);
  }
  EXPECT_GT(plainFailures, 20);
}

TEST(Statics, StartingOnANonMinimisingFingertipStepsOff) {
  StaticsProblem problem = twoCables();
  problem.p0 = problem.cables[0].a;
  const StaticsResult r = solveStaticsNewton(problem);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.p.norm(), 1e-10);
  EXPECT_EQ(r.anchor, -1);
}

TEST(Statics, NonUniqueMinimiserMatchesInEnergy) {
  // One taut cable: every point of its a-b segment is a minimiser.
  StaticsProblem problem;
  problem.cables = {{Vec2(0, 0), Vec2(2, 0), 3, 1.0}, {Vec2(5, 5), Vec2(6, 5), 1, 20}};
  problem.p0 = Vec2(0.7, 0.3);
  const StaticsResult fast = solveStatics(problem), socp = solveStaticsSocp(problem);
  EXPECT_NEAR(fast.energy, 0.5 * 3 * 1.0, 1e-12);
  EXPECT_NEAR(socp.energy, fast.energy, 1e-10);
  EXPECT_NEAR(fast.p.y(), 0, 1e-9);
  EXPECT_LE(fast.residual, kForceTol);
}

TEST(StaticsSensitivity, MatchesCentralDifferences) {
  std::mt19937_64 rng(11);
  int checked = 0;
  for (int i = 0; i < 60 && checked < 30; ++i) {
    StaticsProblem problem = randomStaticsProblem(rng, {.cables = 2 + i % 5});
    const StaticsResult r = solveStatics(problem);
    if (!uniqueMinimiser(problem, r) || r.anchor >= 0) continue;
    const StaticsSensitivity s = staticsSensitivity(problem, r.p);
    ASSERT_EQ(s.kind, StaticsSensitivity::Kind::Smooth);
    ASSERT_EQ(s.dp.cols(), 4 * int(problem.cables.size()));
    ++checked;
    const double h = 1e-5;
    for (int col = 0; col < s.dp.cols(); ++col) {
      StaticsCable& c = problem.cables[col / 4];
      double& x = (col % 4 < 2 ? c.a : c.b)(col % 2);
      const double x0 = x;
      x = x0 + h;
      const Vec2 plus = solveStatics(problem).p;
      x = x0 - h;
      const Vec2 minus = solveStatics(problem).p;
      x = x0;
      const Vec2 fd = (plus - minus) / (2 * h);
      EXPECT_LE((fd - s.dp.col(col)).norm(), kSensitivityTol * std::max(1.0, fd.norm()))
          << "instance " << i << " column " << col;
    }
  }
  EXPECT_GE(checked, 20);
}

TEST(StaticsSensitivity, MinimiserOnAFingertipFollowsIt) {
  std::mt19937_64 rng(13);
  const StaticsProblem problem = randomStaticsProblem(rng, {.cables = 4, .onFingertip = true});
  const StaticsResult r = solveStatics(problem);
  ASSERT_EQ(r.anchor, 0);
  const StaticsSensitivity s = staticsSensitivity(problem, r.p);
  EXPECT_EQ(s.kind, StaticsSensitivity::Kind::OnFingertip);
  EXPECT_TRUE((s.dp.block<2, 2>(0, 0).isIdentity()));
  EXPECT_EQ(s.dp.rightCols(s.dp.cols() - 2).norm(), 0);
}

TEST(BoxReduction, ReducedMinimiserBalancesTheBox) {
  // A 0.4 x 0.2 box: the top cable touches both top corners, the bottom one the bottom edge's
  // corners, a side cable one corner.
  const Vec2 tl(-0.2, 0.1), tr(0.2, 0.1), bl(-0.2, -0.1), br(0.2, -0.1);
  const std::vector<BoxCable> cables = {
      {Vec2(-1, 0.8), Vec2(1, 0.9), 150, 1.8, tl, tr},
      {Vec2(-1, -0.7), Vec2(1, -0.9), 120, 1.7, bl, br},
      {Vec2(1.2, 0.5), Vec2(1.3, -0.4), 40, 0.6, tr, tr},
  };
  const StaticsProblem problem = reduceBoxToPoint(cables, Vec2(0, 0));
  EXPECT_NEAR(problem.cables[0].L, 1.8 - 0.4, 1e-15);
  const StaticsResult r = solveStatics(problem);
  ASSERT_TRUE(r.converged);
  // Forces on the box from the unreduced cables: tension along each segment at its corner.
  Vec2 net = Vec2::Zero();
  double maxTension = 0;
  for (size_t i = 0; i < cables.size(); ++i) {
    const BoxCable& c = cables[i];
    const Vec2 ca = r.p + c.cornerA, cb = r.p + c.cornerB;
    const double length = (ca - c.a).norm() + (cb - ca).norm() + (c.b - cb).norm();
    EXPECT_NEAR(length, r.lengths[i] + (c.cornerB - c.cornerA).norm(), 1e-12);
    const double tension = c.k * std::max(0.0, length - c.L);
    EXPECT_NEAR(tension, r.tensions[i], 1e-9);
    net += tension * ((c.a - ca).normalized() + (c.b - cb).normalized());
    maxTension = std::max(maxTension, tension);
  }
  EXPECT_GT(maxTension, 0);
  EXPECT_LE(net.norm(), kForceTol * maxTension);
}

TEST(StaticsIo, ParsesAndRejectsWithFieldNames) {
  const StaticsProblem p = parseStaticsJson(
      R"({"cables": [{"a": [0, 1], "b": [2, 1], "k": 3, "L": 0.5}], "p0": [1, 0]})", "s");
  ASSERT_EQ(p.cables.size(), 1u);
  EXPECT_EQ(p.cables[0].b, Vec2(2, 1));
  EXPECT_EQ(*p.p0, Vec2(1, 0));
  const auto fieldOf = [](const std::string& text) {
    try {
      parseStaticsJson(text, "s");
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(fieldOf(R"({"cables": [{"a": [0, 1], "b": [2, 1], "k": "3", "L": 0.5}]})"),
            "cables[0].k");
  EXPECT_EQ(fieldOf(R"({"cables": [{"a": [0, 1], "b": [2], "k": 3, "L": 0.5}]})"), "cables[0].b");
  EXPECT_EQ(fieldOf(R"({"cables": [{"a": [0, 1], "b": [2, 1], "k": 3}]})"), "cables[0].L");
  EXPECT_EQ(fieldOf(R"({"cables": [{"a": [0, 1e999], "b": [2, 1], "k": 3, "L": 1}]})"), "(json)");
  EXPECT_EQ(fieldOf(R"({"cables": []})"), "cables");
  EXPECT_EQ(fieldOf(R"({"cable": []})"), "cable");
  EXPECT_EQ(fieldOf("[1, 2"), "(json)");
}

}  // namespace
}  // namespace cablelab
