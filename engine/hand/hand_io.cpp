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
  const std::vector<double> angles =
      parseNumberList(text, count, kCommandLine, "--angles", "A,B,...");
  for (const double a : angles) {
    if (!(std::abs(a) <= M_PI))
      throw InputError(kCommandLine, "--angles",
                       "each angle must be in [-pi, pi] rad" + gotValue(a));
    if (a != 0 && !model.turn)
      throw InputError(
          kCommandLine, "--angles",
          "an angle other than 0 needs a box that may turn (scene parameter turn=1)" + gotValue(a));
  }
  return angles;
}

HandLaw handLaw(const std::string& text, const std::string& source, const std::string& field) {
  if (text == "jacobian") return HandLaw::Jacobian;
  if (text == "mpc") return HandLaw::Mpc;
  throw InputError(source, field, "must be jacobian or mpc" + gotValue(text));
}

const char* handLawName(HandLaw law) {
  return law == HandLaw::Mpc ? "mpc" : "jacobian";
}

int checkedHorizon(int horizon, const std::string& source, const std::string& field) {
  if (horizon < 1 || horizon > 40)
    throw InputError(source, field, "must be a whole number in [1, 40]" + gotValue(horizon));
  return horizon;
}

TrackOptions trackOptions(const TrackRequest& q, const HandModel& model) {
  TrackOptions o;
  o.law = q.law;
  o.mpc.horizon = checkedHorizon(q.horizon, kCommandLine, "--horizon");
  if (q.target && q.ramp)
    throw InputError(kCommandLine, "--ramp", "give either --target or --ramp, not both (got both)");
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

namespace {
/// A time that may not exist (-1) as a number or null.
nlohmann::json timeOrNull(double t) {
  return t >= 0 ? nlohmann::json(t) : nlohmann::json(nullptr);
}
}  // namespace

nlohmann::json trackSummary(const TrackResult& r, HandLaw law) {
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
          {"events", events},
          {"controller", handLawName(law)},
          {"time_to_5mm", timeOrNull(r.timeTo5mm)},
          {"overshoot", r.overshoot},
          {"joint_limit_hits", r.limitHits},
          {"controller_solve_us", r.solveMicros},
          {"controller_solve_max_us", r.maxSolveMicros}};
}

nlohmann::json compareSummary(const CompareResult& r, const CompareOptions& o) {
  auto law = [](const LawSummary& s) {
    return nlohmann::json{{"median_time_to_5mm", timeOrNull(s.medianTimeTo5mm)},
                          {"median_final_error", s.medianFinalError},
                          {"max_final_error", s.maxFinalError},
                          {"median_overshoot", s.medianOvershoot},
                          {"max_overshoot", s.maxOvershoot},
                          {"grasp_losses", s.graspLosses},
                          {"joint_limit_hits", s.limitHits},
                          {"settled", s.settled},
                          {"controller_solve_us", s.solveMicros},
                          {"controller_solve_max_us", s.maxSolveMicros}};
  };
  const double pid = r.jacobianSummary.medianTimeTo5mm, mpc = r.mpcSummary.medianTimeTo5mm;
  nlohmann::json targets = nlohmann::json::array();
  for (const Vec2& t : r.targets) targets.push_back({t.x(), t.y()});
  return {
      {"targets", targets},
      {"seed", o.seed},
      {"horizon", o.horizon},
      {"time", o.time},
      {"jacobian", law(r.jacobianSummary)},
      {"mpc", law(r.mpcSummary)},
      {"time_ratio", pid > 0 && mpc >= 0 ? nlohmann::json(mpc / pid) : nlohmann::json(nullptr)}};
}

ReachOptions reachOptions(int grid, const std::string& model, bool pd, int threads, HandLaw law,
                          int horizon) {
  if (grid < 1 || grid > 1000)
    throw InputError(kCommandLine, "--grid",
                     "must be a whole number in [1, 1000]" + gotValue(grid));
  if (model != "simulation" && model != "quasi-static")
    throw InputError(kCommandLine, "--model",
                     "must be simulation or quasi-static" + gotValue(model));
  ReachOptions o;
  o.grid = grid;
  o.model = model == "simulation" ? ReachModel::Simulation : ReachModel::QuasiStatic;
  o.pid = !pd;
  o.threads = threads;
  o.law = law;
  o.horizon = checkedHorizon(horizon, kCommandLine, "--horizon");
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
          {"law", o.law == HandLaw::Mpc ? "MPC"
                  : o.pid               ? "PID"
                                        : "PD"},
          {"controller", handLawName(o.law)},
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
