#include "engine/statics/statics_bench.h"

#include <algorithm>
#include <chrono>
#include <random>
#include <vector>

#include "engine/statics/socp.h"
#include "engine/statics/statics_newton.h"
#include "engine/statics/statics_random.h"

namespace cablelab {

namespace {

constexpr int kRepeats = 8;  // solves per timed batch

double median(std::vector<double>& values) {
  if (values.empty()) return 0;
  auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

/// Wall time of one call of `solve` (us), from a batch of kRepeats.
template <class Solve>
double timeBatch(Solve&& solve) {
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < kRepeats; ++r) solve();
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
             .count() /
         kRepeats;
}

}  // namespace

StaticsTimings measureStatics(int n, int instances, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<StaticsProblem> problems;
  problems.reserve(instances);
  for (int i = 0; i < instances; ++i) {
    RandomStaticsOptions options;
    options.cables = n;
    options.onFingertip = n >= 2 && i % 10 == 9;
    problems.push_back(randomStaticsProblem(rng, options));
  }
  StaticsTimings t;
  t.cables = n;
  t.instances = instances;
  SocpWorkspace workspace;
  StaticsResult result;
  NewtonOptions plain;
  plain.detectFingertips = false;
  std::vector<double> socp, newton, fallback;
  long iterations = 0;
  for (const StaticsProblem& problem : problems) {
    socp.push_back(timeBatch([&] { solveStaticsSocp(problem, result, workspace); }));
    iterations += result.iterations;
    t.socpMaxIterations = std::max(t.socpMaxIterations, result.iterations);
    t.socpMaxResidual = std::max(t.socpMaxResidual, result.residual);
    newton.push_back(timeBatch([&] { solveStaticsNewton(problem, result, plain); }));
    fallback.push_back(timeBatch([&] { solveStatics(problem, result, &workspace); }));
    t.defaultMaxResidual = std::max(t.defaultMaxResidual, result.residual);
    t.fallbacks += result.fellBack;
  }
  t.socpMeanIterations = instances > 0 ? double(iterations) / instances : 0;
  t.socpMicros = median(socp);
  t.newtonMicros = median(newton);
  t.defaultMicros = median(fallback);
  return t;
}

}  // namespace cablelab
