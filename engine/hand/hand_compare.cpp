#include "engine/hand/hand_compare.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <random>
#include <thread>

#include "engine/hand/hand_kinematics.h"

namespace cablelab {

namespace {
constexpr double kMinDistance = 0.1;  // m: a target at least this far from the start
constexpr double kInside = 0.05;      // m: and this far inside the fingertips' range

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

std::vector<Vec2> compareTargets(const HandModel& model, int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> x(-1.6, 1.6), y(-2.6, 2.6);  // the reach grid's window
  std::vector<Vec2> out;
  while (static_cast<int>(out.size()) < count) {
    const Vec2 g(x(random), y(random));
    bool inside = g.norm() >= kMinDistance;
    for (int k = 0; k < 8 && inside; ++k) {
      const double a = k * M_PI / 4;
      inside = pinchWithinLimits(model, g + kInside * Vec2(std::cos(a), std::sin(a)));
    }
    if (inside) out.push_back(g);
  }
  return out;
}

LawSummary summariseLaw(const std::vector<TrackResult>& runs) {
  LawSummary s;
  std::vector<double> times, errors, overshoots;
  double solveSum = 0;
  for (const TrackResult& r : runs) {
    times.push_back(r.timeTo5mm >= 0 ? r.timeTo5mm : std::numeric_limits<double>::infinity());
    errors.push_back(r.finalError), overshoots.push_back(r.overshoot);
    s.maxFinalError = std::max(s.maxFinalError, r.finalError);
    s.maxOvershoot = std::max(s.maxOvershoot, r.overshoot);
    s.graspLosses += r.losses;
    s.limitHits += r.limitHits;
    s.settled += r.timeTo5mm >= 0;
    solveSum += r.solveMicros;
    s.maxSolveMicros = std::max(s.maxSolveMicros, r.maxSolveMicros);
  }
  const double t = median(times);
  s.medianTimeTo5mm = std::isfinite(t) ? t : -1;
  s.medianFinalError = median(errors);
  s.medianOvershoot = median(overshoots);
  s.solveMicros = runs.empty() ? 0 : solveSum / runs.size();
  return s;
}

CompareResult compareLaws(const CompareOptions& o, const HandModel& model,
                          const std::function<void(long, long)>& progress) {
  CompareResult result;
  result.targets = compareTargets(model, o.targets, o.seed);
  const int n = static_cast<int>(result.targets.size());
  result.jacobian.resize(n), result.mpc.resize(n);
  std::atomic<int> next{0}, done{0};
  auto worker = [&] {
    for (int k = next++; k < 2 * n; k = next++) {
      TrackOptions track;
      track.target = result.targets[k / 2];
      track.time = o.time;
      track.pid = true;
      track.law = k % 2 ? HandLaw::Mpc : HandLaw::Jacobian;
      track.mpc.horizon = o.horizon;
      TrackResult& run = (k % 2 ? result.mpc : result.jacobian)[k / 2];
      try {
        run = runTracking(track, model);
      } catch (const std::exception&) {  // the simulation blew up (SimulationError): a lost box
        run.losses = 1;
        run.finalError = std::numeric_limits<double>::infinity();
      }
      ++done;
    }
  };
  const int threads = o.threads > 0 ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
  while (progress && done < 2 * n) {
    progress(done, 2L * n);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& t : pool) t.join();
  if (progress) progress(done, 2L * n);
  result.jacobianSummary = summariseLaw(result.jacobian);
  result.mpcSummary = summariseLaw(result.mpc);
  return result;
}

}  // namespace cablelab
