#include "engine/hand/hand_io.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/parse.h"
#include "engine/hand/hand_kinematics.h"

namespace cablelab {

std::vector<double> targetNumbers(std::string_view text, const std::string& source,
                                  const std::string& field) {
  const size_t count = std::count(text.begin(), text.end(), ',') + 1;
  if (count != 2 && count != 3)
    throw InputError(source, field,
                     "must be X,Y or X,Y,THETA, 2 or 3 finite numbers" + gotValue(text));
  return parseNumberList(text, count, source, field, count == 3 ? "X,Y,THETA" : "X,Y");
}

void setTarget(TrackRequest& request, const std::vector<double>& v, const std::string& source,
               const std::string& field) {
  if (v.size() != 2 && v.size() != 3)
    throw InputError(source, field,
                     "must be X,Y or X,Y,THETA (got " + std::to_string(v.size()) + " numbers)");
  request.target = Vec2(v[0], v[1]);
  request.targetAngle = v.size() == 3 ? v[2] : 0.0;
}

std::vector<double> reachAngles(std::string_view text, const HandModel& model) {
  const size_t count = std::count(text.begin(), text.end(), ',') + 1;
  const std::vector<double> angles = parseNumberList(text, count, kCommandLine, "--angles", "A,B,...");
  for (const double a : angles) {
    if (!(std::abs(a) <= M_PI))
      throw InputError(kCommandLine, "--angles", "each angle must be in [-pi, pi] rad" + gotValue(a));
    if (a != 0 && !model.turn)
      throw InputError(kCommandLine, "--angles",
                       "an angle other than 0 needs a box that may turn (scene parameter turn=1)" +
                           gotValue(a));
  }
  return angles;
}

TrackOptions trackOptions(const TrackRequest& q, const HandModel& model) {
  TrackOptions o;
  if (q.target && q.ramp)
    throw InputError(kCommandLine, "--ramp", "give either --target or --ramp, not both");
  if (q.target) o.target = *q.target;
  if (q.targetAngle != 0 && !model.turn)
    throw InputError(
        kCommandLine, "--target",
        "THETA needs a box that may turn (scene parameter turn=1)" + gotValue(q.targetAngle));
  if (!(std::abs(q.targetAngle) <= M_PI))
    throw InputError(kCommandLine, "--target",
                     "THETA must be in [-pi, pi] rad" + gotValue(q.targetAngle));
  o.targetAngle = q.targetAngle;
  if (q.ramp) {
    const auto& v = *q.ramp;
    if (!(v[2] > 0))
      throw InputError(kCommandLine, "--ramp", "SECONDS must be positive" + gotValue(v[2]));
    o.target = Vec2(v[0], v[1]);
    o.rampTime = v[2];
  }
  requireInRange(o.target.norm(), kCommandLine, q.ramp ? "--ramp" : "--target", 0, 100);
  if (q.start) {
    if (!pinchWithinLimits(model, *q.start))
      throw InputError(kCommandLine, "--start",
                       "the fingers cannot pinch the box there (got " + formatNumber(q.start->x()) +
                           "," + formatNumber(q.start->y()) + ")");
    o.start = *q.start;
  }
  requireInRange(q.time, kCommandLine, "--time", 0, 1e5);
  o.time = q.time;
  o.pid = q.pid;
  return o;
}

nlohmann::json trackSummary(const TrackResult& r) {
  nlohmann::json events = nlohmann::json::array();
  for (const GraspEvent& e : r.events) events.push_back({{"t", e.t}, {"what", e.what}});
  const Vec2 last = r.samples.empty() ? r.start : r.samples.back().box;
  return {{"final_error", r.finalError},
          {"rms_error", r.rmsError},
          {"final_angle_error", r.finalAngleError},
          {"rms_angle_error", r.rmsAngleError},
          {"final_angle", r.samples.empty() ? 0.0 : r.samples.back().angle},
          {"grasp_time", r.graspTime},
          {"start_error", r.startError},
          {"grasp_held", r.graspHeld},
          {"losses", r.losses},
          {"start", {r.start.x(), r.start.y()}},
          {"final_box", {last.x(), last.y()}},
          {"max_tension", r.maxTension},
          {"events", events}};
}

ReachOptions reachOptions(int grid, const std::string& model, bool pd, int threads) {
  if (grid < 1 || grid > 1000)
    throw InputError(kCommandLine, "--grid",
                     "must be a whole number in [1, 1000]" + gotValue(grid));
  if (model != "simulation" && model != "quasi-static")
    throw InputError(kCommandLine, "--model",
                     "must be simulation or quasi-static (got " + model + ")");
  ReachOptions o;
  o.grid = grid;
  o.model = model == "simulation" ? ReachModel::Simulation : ReachModel::QuasiStatic;
  o.pid = !pd;
  o.threads = threads;
  return o;
}

const char* reachModelName(ReachModel m) {
  return m == ReachModel::Simulation ? "simulation" : "quasi-static";
}

bool objectReached(const ReachResult& r, const ReachTarget& t) {
  return r.model == ReachModel::Simulation ? t.simulated : t.quasiStatic;
}

nlohmann::json reachSummary(const ReachResult& r, const ReachOptions& o) {
  int beyond = 0;
  for (const ReachTarget& t : r.targets) beyond += objectReached(r, t) && !t.fingertip;
  return {{"object_area", r.objectArea},
          {"fingertip_area", r.fingertipArea},
          {"ratio", r.fingertipArea > 0 ? r.objectArea / r.fingertipArea : 0.0},
          {"points", r.points},
          {"model", reachModelName(r.model)},
          {"law", o.pid ? "PID" : "PD"},
          {"object_points", r.objectPoints.size()},
          {"fingertip_points", r.fingertipPoints.size()},
          {"beyond_fingertips", beyond},
          {"quasi_static_area", r.quasiStaticArea},
          {"quasi_static_points", r.quasiStaticPoints.size()},
          {"threads", r.threads},
          {"simulated_s", r.simulatedSeconds},
          {"seconds", r.seconds}};
}

}  // namespace cablelab
