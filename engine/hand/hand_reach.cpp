#include "engine/hand/hand_reach.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include "engine/hand/hand_controller.h"

namespace cablelab {

bool fingertipsReach(const HandModel& m, const Vec2& g) {
  for (int f = 0; f < 2; ++f) {
    const Vec2 d = g + Vec2(0, HandModel::side(f) * m.baseY) - m.base(f);
    const double tp = std::atan2(d.y(), d.x()), slide = d.norm() - m.linkLength, td = -tp;
    const double v[3] = {tp, slide, td};
    for (int j = 0; j < 3; ++j)
      if (v[j] < m.lower[3 * f + j] || v[j] > m.upper[3 * f + j]) return false;
  }
  return true;
}

ReachResult runReach(const ReachOptions& o, const HandModel& m,
                     const std::function<void(long, long)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  ReachResult r;
  r.lower = Vec2(-1.6, -2.6);
  r.upper = Vec2(1.6, 2.6);
  const int n = o.grid;
  const Vec2 cell = (r.upper - r.lower) / n;
  auto point = [&](int k) {
    return Vec2(r.lower.x() + (k % n + 0.5) * cell.x(), r.lower.y() + (k / n + 0.5) * cell.y());
  };
  std::vector<char> reached(n * n, 0);
  std::atomic<int> next{0}, done{0};

  auto worker = [&] {
    // Quasi-static: the box sits at the statics prediction after every update, so its change
    // over a period is exactly the commanded J dq. A derivative term on it would only feed the
    // last step back with the opposite sign (a pole at -k_d: alternating steps that leave the
    // face-on grasp), so the sweep runs the proportional law with k_d = 0 and 10 cm saturation.
    HandControllerParams params;
    params.kd = 0;
    params.maxError = 0.1;
    HandController controller(m, params);
    for (int k = next++; k < n * n; k = next++) {
      const Vec2 target = point(k);
      HandJoints q = HandJoints::Zero();
      Vec2 box = Vec2::Zero();
      controller.reset();
      for (int u = 0; u < o.maxUpdates; ++u) {
        const BoxPrediction p = controller.predict(q, box);
        box = p.box;
        if (!p.valid) break;
        if ((box - target).norm() < o.tolerance) {
          reached[k] = 1;
          break;
        }
        q = m.clamp(q + controller.update(q, box, target, q));
      }
      ++done;
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::max(1, o.threads); ++t) threads.emplace_back(worker);
  while (done < n * n) {
    if (progress) progress(done, static_cast<long>(n) * n);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& t : threads) t.join();

  for (int k = 0; k < n * n; ++k) {
    if (reached[k]) r.objectPoints.push_back(point(k));
    if (fingertipsReach(m, point(k))) r.fingertipPoints.push_back(point(k));
  }
  r.points = n * n;
  r.objectArea = r.objectPoints.size() * cell.x() * cell.y();
  r.fingertipArea = r.fingertipPoints.size() * cell.x() * cell.y();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace cablelab
