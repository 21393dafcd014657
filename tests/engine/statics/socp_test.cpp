// Tests for engine/socp.{h,cpp}: the interior-point solver on its own.
#include "engine/statics/socp.h"

#include <gtest/gtest.h>

#include <random>

#include "engine/statics/statics_newton.h"
#include "engine/statics/statics_random.h"

namespace cablelab {
namespace {

constexpr int kMaxIterations = 30;
constexpr double kResidualTol = 1e-9;

TEST(Socp, ConvergesWithinThirtyIterationsForOneToSixteenCables) {
  std::mt19937_64 rng(99);
  SocpWorkspace workspace;
  StaticsResult r;
  int worst = 0;
  for (int i = 0; i < 320; ++i) {
    RandomStaticsOptions options;
    options.cables = 1 + i % 16;
    options.onFingertip = options.cables >= 2 && i % 5 == 0;
    const StaticsProblem problem = randomStaticsProblem(rng, options);
    solveStaticsSocp(problem, r, workspace);
    SCOPED_TRACE("instance " + std::to_string(i));
    EXPECT_TRUE(r.converged);
    EXPECT_LE(r.iterations, kMaxIterations);
    EXPECT_LE(r.residual, kResidualTol);
    EXPECT_LE(workspace.stats().primalResidual, 1e-12);
    EXPECT_EQ(r.method, StaticsMethod::Socp);
    worst = std::max(worst, r.iterations);
  }
  EXPECT_GT(worst, 5);  // it is an iterative method: a count of 0 would mean it did nothing
}

TEST(Socp, ObjectiveIsTheEnergyAtTheNewtonMinimiser) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 50; ++i) {
    const StaticsProblem problem = randomStaticsProblem(rng, {.cables = 6});
    const StaticsResult socp = solveStaticsSocp(problem), newton = solveStaticsNewton(problem);
    EXPECT_NEAR(socp.energy, newton.energy, 1e-10 * std::max(1.0, newton.energy));
  }
}

TEST(Socp, InteriorPointAloneGetsCloseBeforePolish) {
  // Without the Newton polish the interior point's own answer must already be near optimal.
  std::mt19937_64 rng(17);
  SocpOptions options;
  options.polishSteps = 0;
  for (int i = 0; i < 30; ++i) {
    const StaticsProblem problem = randomStaticsProblem(rng, {.cables = 4, .looseFraction = 0});
    const StaticsResult raw = solveStaticsSocp(problem, options);
    const StaticsResult ref = solveStaticsNewton(problem);
    EXPECT_LE((raw.p - ref.p).norm(), 1e-4);
    EXPECT_NEAR(raw.energy, ref.energy, 1e-8 * std::max(1.0, ref.energy));
  }
}

TEST(Socp, WarmStartFromANearbySolutionTakesFewerIterations) {
  std::mt19937_64 rng(23);
  int cold = 0, warm = 0;
  for (int i = 0; i < 30; ++i) {
    StaticsProblem problem = randomStaticsProblem(rng, {.cables = 6, .looseFraction = 0.2});
    SocpWorkspace workspace;
    StaticsResult r;
    solveStaticsSocp(problem, r, workspace);
    for (StaticsCable& c : problem.cables) c.a.x() += 1e-3;  // the fingers moved a little
    SocpOptions options;
    solveStaticsSocp(problem, r, workspace, options);
    cold += r.iterations;
    const Vec2 coldP = r.p;
    solveStaticsSocp(problem, r, workspace);  // re-seat lastP at this problem's answer nearby
    options.warmStart = true;
    for (StaticsCable& c : problem.cables) c.a.x() += 1e-3;
    StaticsResult w;
    solveStaticsSocp(problem, w, workspace, options);
    warm += w.iterations;
    EXPECT_LE(w.residual, kResidualTol);
    EXPECT_NEAR((w.p - coldP).norm(), 0, 1e-2);
  }
  EXPECT_LT(warm, cold);
}

TEST(Socp, WorkspaceReuseGivesIdenticalAnswers) {
  std::mt19937_64 rng(29);
  SocpWorkspace shared;
  for (int i = 0; i < 20; ++i) {
    const StaticsProblem problem = randomStaticsProblem(rng, {.cables = 1 + i % 9});
    StaticsResult a;
    solveStaticsSocp(problem, a, shared);
    const StaticsResult b = solveStaticsSocp(problem);
    EXPECT_EQ(a.p, b.p);
    EXPECT_EQ(a.iterations, b.iterations);
  }
}

}  // namespace
}  // namespace cablelab
