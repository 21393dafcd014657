#include "engine/hand/hand_reach.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <thread>

#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_kinematics.h"
#include "engine/hand/hand_tracking.h"

namespace cablelab {

bool fingertipsReach(const HandModel& m, const Vec2& g) {
  return pinchWithinLimits(m, g);
}

bool quasiStaticReach(const HandModel& m, const Vec2& target, const ReachOptions& o) {
  // Quasi-static: the box sits at the statics prediction after every update, so its change
  // over a period is exactly the commanded J dq. A derivative term on it would only feed the
  // last step back with the opposite sign (a pole at -k_d: alternating steps that leave the
  // face-on grasp), so the sweep runs with k_d = 0.
  HandControllerParams params;
  params.kd = 0;
  HandController controller(m, params);
  HandJoints q = HandJoints::Zero();
  Vec2 box = Vec2::Zero();
  double angle = 0;
  for (int u = 0; u < o.maxUpdates; ++u) {
    const BoxPrediction p = controller.predict(q, box, angle);
    box = p.box;
    angle = p.angle;
    if (!p.valid) return false;
    if ((box - target).norm() < o.tolerance && std::abs(angle - o.angle) < o.angleTolerance)
      return true;
    q = m.clamp(q + controller.update(q, BoxPose(box.x(), box.y(), angle),
                                      BoxPose(target.x(), target.y(), o.angle), q));
  }
  return false;
}

namespace {

ReachTarget simulateTarget(const HandModel& m, const Vec2& target, const ReachOptions& o) {
  TrackOptions track;
  track.target = target;
  track.targetAngle = o.angle;
  track.stop.angleTolerance = o.angleTolerance;
  track.pid = o.pid;
  track.law = o.law;
  track.mpc.horizon = o.horizon;
  track.time = o.time;
  track.stop.enabled = true;
  track.stop.tolerance = o.tolerance;
  ReachTarget t;
  TrackResult r;
  try {
    r = runTracking(track, m);
  } catch (const std::exception&) {
    return t;  // the simulation blew up (SimulationError): not reached, and no crash of the sweep
  }
  t.error = r.finalError;
  t.graspHeld = r.graspHeld;
  t.simulated = r.graspHeld && r.finalError < o.tolerance &&
                r.finalAngleError < (m.turn ? o.angleTolerance : INFINITY);
  t.simulatedTime = r.samples.back().t;
  return t;
}

}  // namespace

ReachResult reachGrid(const ReachOptions& o, const HandModel& m) {
  ReachResult r;
  r.model = o.model;
  r.lower = Vec2(-1.6, -2.6);
  r.upper = Vec2(1.6, 2.6);
  const int n = o.grid;
  const Vec2 cell = (r.upper - r.lower) / n;
  r.targets.resize(static_cast<size_t>(n) * n);
  for (int k = 0; k < n * n; ++k) {
    ReachTarget& t = r.targets[k];
    t.point = Vec2(r.lower.x() + (k % n + 0.5) * cell.x(), r.lower.y() + (k / n + 0.5) * cell.y());
    t.fingertip = fingertipsReach(m, t.point);
  }
  r.points = n * n;
  return r;
}

void evaluateReachTarget(const HandModel& m, const ReachOptions& o, ReachTarget& t) {
  if (o.model == ReachModel::Simulation) {
    const ReachTarget s = simulateTarget(m, t.point, o);
    t.simulated = s.simulated, t.error = s.error, t.graspHeld = s.graspHeld;
    t.simulatedTime = s.simulatedTime;
  }
  t.quasiStatic = quasiStaticReach(m, t.point, o);
}

void summariseReach(ReachResult& r) {
  const bool simulate = r.model == ReachModel::Simulation;
  r.fingertipPoints.clear(), r.quasiStaticPoints.clear(), r.objectPoints.clear();
  r.simulatedSeconds = 0;
  for (const ReachTarget& t : r.targets) {
    if (t.fingertip) r.fingertipPoints.push_back(t.point);
    if (t.quasiStatic) r.quasiStaticPoints.push_back(t.point);
    if (simulate ? t.simulated : t.quasiStatic) r.objectPoints.push_back(t.point);
    r.simulatedSeconds += t.simulatedTime;
  }
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(r.targets.size()))));
  const Vec2 cell = (r.upper - r.lower) / n;  // the grid's cell, as reachGrid laid it out
  const double area = cell.x() * cell.y();
  r.points = static_cast<int>(r.targets.size());
  r.objectArea = r.objectPoints.size() * area;
  r.fingertipArea = r.fingertipPoints.size() * area;
  r.quasiStaticArea = r.quasiStaticPoints.size() * area;
}

ReachResult runReach(const ReachOptions& o, const HandModel& m,
                     const std::function<void(long, long)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  ReachResult r = reachGrid(o, m);
  const int n = o.grid;
  std::atomic<int> next{0}, done{0};
  auto worker = [&] {
    for (int k = next++; k < n * n; k = next++) {
      evaluateReachTarget(m, o, r.targets[k]);
      ++done;
    }
  };
  r.threads = o.threads > 0 ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> threads;
  for (int i = 0; i < r.threads; ++i) threads.emplace_back(worker);
  std::exception_ptr stopped;  // progress threw (e.g. Ctrl-C from Python): stop the sweep
  while (done < n * n && !stopped) {
    try {
      if (progress) progress(done, static_cast<long>(n) * n);
    } catch (...) {
      stopped = std::current_exception();
      next = n * n;  // the workers take no new targets; the runs under way finish
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& t : threads) t.join();
  if (stopped) std::rethrow_exception(stopped);
  if (progress) progress(done, static_cast<long>(n) * n);
  summariseReach(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace cablelab
