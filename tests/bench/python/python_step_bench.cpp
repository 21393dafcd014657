// The cost of stepping cablelab from Python, next to the C++ step, in one process:
// cablelab_python_bench embeds Debian's Python (pybind11/embed.h), imports the built module
// (build/python/cablelab) and times, on the hand and the pulley scenes,
//   * a Python loop `for _ in range(n): step()` over a cablelab.World (the module's own copy of
//     the engine), against
//   * the same n World::step calls in C++ on a World built here from the same scene,
// in alternating pairs from the same state (both worlds advance alike, and start afresh every 1000
// steps), so that the two halves of a pair see the same machine load. Times are this thread's CPU
// time. Counters: cpp_step_us and python_step_us (medians over the pairs) and ratio (median of the
// per-pair ratios, Python / C++); the benchmark's own time is the Python loop's. Also: reading all
// state of a 100-body world from Python, body_states() (a new (100, 6) array) and body_states(out=)
// (into a buffer).
//
//   build/bin/cablelab_python_bench [--benchmark_filter=Step] [--benchmark_format=json]
//
// Not a test (benchmarks are not in ctest): run it by hand on a quiet machine.
#include <benchmark/benchmark.h>
#include <pybind11/embed.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"

namespace py = pybind11;

namespace {

double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Python side: a World and a loop over its bound step method (what a user's script does).
const char* kPythonSide = R"(
import cablelab

def stepper(scene):
    w = cablelab.World.load(scene)
    step = w.step
    def loop(n):
        for _ in range(n):
            step()
    return w, loop

def reader(bodies):
    w = cablelab.World.from_dict({"name": "many", "gravity": [0, 0], "bodies": [
        {"name": f"b{i}", "position": [1.5 * (i % 10), 1.5 * (i // 10)], "mass": 1.0,
         "shapes": [{"type": "circle", "radius": 0.5}]} for i in range(bodies)]})
    buffer = w.body_states()
    read = w.body_states
    def new_arrays(n):
        for _ in range(n):
            read()
    def into_buffer(n):
        for _ in range(n):
            read(out=buffer)
    return w, new_arrays, into_buffer
)";

py::dict& pythonSide() {
  static py::dict scope = [] {
    py::dict d;
    py::exec(kPythonSide, d);
    return d;
  }();
  return scope;
}

constexpr int kStepsPerSample = 100;
constexpr int kWarmup = 30;
constexpr int kSamplesPerStart = 10;  // 1000 steps from a fresh start

void BM_StepFromPython(benchmark::State& state, const std::string& scene) {
  const cablelab::SceneDef def = cablelab::makeScene(scene);
  std::unique_ptr<cablelab::World> world;
  py::object loop;
  // Both worlds start afresh every kSamplesPerStart samples (untimed), so that every sample steps
  // the scene's first seconds (the pulley's masses would otherwise run far from the pulleys).
  auto fresh = [&] {
    world = std::make_unique<cablelab::World>(def, scene);
    py::tuple made = pythonSide()["stepper"](scene);
    loop = made[1];
    for (int i = 0; i < kWarmup; ++i) world->step(def.dt, def.substeps);
    loop(kWarmup);
  };
  long samples = 0;
  std::vector<double> cpp, python, ratio;
  bool pythonFirst = false;
  for (auto _ : state) {
    if (samples++ % kSamplesPerStart == 0) fresh();
    double tc = 0, tp = 0;
    auto runCpp = [&] {
      const double t0 = threadSeconds();
      for (int i = 0; i < kStepsPerSample; ++i) world->step(def.dt, def.substeps);
      tc = threadSeconds() - t0;
    };
    auto runPython = [&] {
      const double t0 = threadSeconds();
      loop(kStepsPerSample);
      tp = threadSeconds() - t0;
    };
    if (pythonFirst)
      runPython(), runCpp();
    else
      runCpp(), runPython();
    pythonFirst = !pythonFirst;
    state.SetIterationTime(tp);
    cpp.push_back(tc / kStepsPerSample * 1e6);
    python.push_back(tp / kStepsPerSample * 1e6);
    ratio.push_back(tp / tc);
  }
  state.SetItemsProcessed(state.iterations() * kStepsPerSample);
  state.counters["cpp_step_us"] = median(cpp);
  state.counters["python_step_us"] = median(python);
  state.counters["ratio"] = median(ratio);
  state.counters["steps_per_sample"] = kStepsPerSample;
}
BENCHMARK_CAPTURE(BM_StepFromPython, hand, std::string("hand"))
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(1.0);
BENCHMARK_CAPTURE(BM_StepFromPython, pulley, std::string("pulley"))
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(1.0);

/// All state of a world of range(0) bodies read from Python: a Python loop of 1000 calls per
/// iteration; us_per_call is the figure (new array, or range(1) = 1: into a buffer).
void BM_BodyStatesFromPython(benchmark::State& state) {
  constexpr int kCalls = 1000;
  py::tuple made = pythonSide()["reader"](state.range(0));
  py::object loop = made[state.range(1) ? 2 : 1];
  std::vector<double> perCall;
  for (auto _ : state) {
    const double t0 = threadSeconds();
    loop(kCalls);
    const double t = threadSeconds() - t0;
    state.SetIterationTime(t);
    perCall.push_back(t / kCalls * 1e6);
  }
  state.counters["us_per_call"] = median(perCall);
}
BENCHMARK(BM_BodyStatesFromPython)
    ->ArgNames({"bodies", "out"})
    ->Args({100, 0})
    ->Args({100, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  py::scoped_interpreter interpreter;
  try {
    py::module_::import("sys").attr("path").attr("insert")(0, CABLELAB_PYTHON_DIR);
    py::module_::import("cablelab");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cablelab_python_bench: cannot import cablelab from %s: %s\n",
                 CABLELAB_PYTHON_DIR, e.what());
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
