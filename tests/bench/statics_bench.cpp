// Statics solvers on 1000 random instances per cable count, cold start: the interior-point
// SOCP, plain damped Newton, and the default path (Newton with fingertip handling, SOCP
// fallback). One benchmark iteration = one solve; instances cycle.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "engine/statics/socp.h"
#include "engine/statics/statics_bench.h"
#include "engine/statics/statics_newton.h"
#include "engine/statics/statics_random.h"

namespace {

using namespace cablelab;

constexpr int kInstances = 1000;

const std::vector<StaticsProblem>& instances(int n) {
  static std::vector<std::vector<StaticsProblem>> cache(17);
  auto& set = cache[n];
  if (set.empty()) {
    std::mt19937_64 rng(1234 + n);
    for (int i = 0; i < kInstances; ++i) {
      RandomStaticsOptions options;
      options.cables = n;
      options.onFingertip = i % 10 == 9;
      set.push_back(randomStaticsProblem(rng, options));
    }
  }
  return set;
}

void BM_StaticsSocp(benchmark::State& state) {
  const auto& set = instances(int(state.range(0)));
  SocpWorkspace workspace;
  StaticsResult result;
  size_t i = 0;
  long iterations = 0;
  for (auto _ : state) {
    solveStaticsSocp(set[i++ % set.size()], result, workspace);
    iterations += result.iterations;
    benchmark::DoNotOptimize(result.p);
  }
  state.counters["ipm_iters"] = double(iterations) / double(state.iterations());
}

void BM_StaticsNewtonPlain(benchmark::State& state) {
  const auto& set = instances(int(state.range(0)));
  NewtonOptions plain;
  plain.detectFingertips = false;
  StaticsResult result;
  size_t i = 0;
  for (auto _ : state) {
    solveStaticsNewton(set[i++ % set.size()], result, plain);
    benchmark::DoNotOptimize(result.p);
  }
}

void BM_StaticsDefault(benchmark::State& state) {
  const auto& set = instances(int(state.range(0)));
  SocpWorkspace workspace;
  StaticsResult result;
  size_t i = 0;
  for (auto _ : state) {
    solveStatics(set[i++ % set.size()], result, &workspace);
    benchmark::DoNotOptimize(result.p);
  }
}

/// The medians `cablelab bench` will report (measureStatics), as counters.
void BM_StaticsMedians(benchmark::State& state) {
  StaticsTimings t;
  for (auto _ : state) t = measureStatics(int(state.range(0)), kInstances, 42);
  state.counters["socp_us"] = t.socpMicros;
  state.counters["newton_us"] = t.newtonMicros;
  state.counters["default_us"] = t.defaultMicros;
  state.counters["socp_max_iters"] = t.socpMaxIterations;
  state.counters["socp_mean_iters"] = t.socpMeanIterations;
  state.counters["socp_max_residual"] = t.socpMaxResidual;
  state.counters["default_max_residual"] = t.defaultMaxResidual;
  state.counters["fallbacks"] = t.fallbacks;
}

BENCHMARK(BM_StaticsSocp)->Arg(2)->Arg(4)->Arg(8)->Arg(16);
BENCHMARK(BM_StaticsNewtonPlain)->Arg(2)->Arg(4)->Arg(8)->Arg(16);
BENCHMARK(BM_StaticsDefault)->Arg(2)->Arg(4)->Arg(8)->Arg(16);
BENCHMARK(BM_StaticsMedians)
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
