// The hand experiments as `cablelab track` and `cablelab reach` take and report them. The CLI
// (app/cmd_track.cpp, app/cmd_reach.cpp) and the Python module (python/py_hand.cpp) both go
// through these, so that they check the same options with the same messages and report the same
// fields.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "engine/hand/hand_compare.h"
#include "engine/hand/hand_reach.h"
#include "engine/hand/hand_tracking.h"

namespace cablelab {

/// `track`'s options as given, already numbers; the optional ones may be absent.
struct TrackRequest {
  std::optional<Vec2> target;                 ///< --target X,Y (m)
  double targetAngle = 0;                     ///< --target's THETA (rad), X,Y,THETA
  std::optional<std::array<double, 3>> ramp;  ///< --ramp X,Y,SECONDS (m, m, s)
  std::optional<Vec2> start;                  ///< --start X,Y (m)
  double time = 15;                           ///< --time (s)
  bool pid = false;                           ///< --pid
  HandLaw law = HandLaw::Jacobian;            ///< --controller
  int horizon = HandMpcParams{}.horizon;      ///< --horizon (MPC only)
};

/// --controller's value: "jacobian" or "mpc"; throws InputError(source, field, ...).
HandLaw handLaw(const std::string& text, const std::string& source, const std::string& field);
/// The name --controller takes for law.
const char* handLawName(HandLaw law);
/// --horizon checked: a whole number in [1, 40]; throws InputError(source, field, ...).
int checkedHorizon(int horizon, const std::string& source, const std::string& field);

/// --target's X,Y or X,Y,THETA as 2 or 3 finite numbers; throws InputError(source, field, ...).
std::vector<double> targetNumbers(std::string_view text, const std::string& source,
                                  const std::string& field);
/// Sets request's target (and angle) from 2 or 3 numbers; throws InputError(source, field, ...).
void setTarget(TrackRequest& request, const std::vector<double>& v, const std::string& source,
               const std::string& field);

/// The checked TrackOptions; throws InputError("command line", "--OPTION", ...), the CLI's
/// message.
TrackOptions trackOptions(const TrackRequest& request, const HandModel& model = {});

/// The JSON object `cablelab track` prints: final_error, rms_error, final_angle_error,
/// rms_angle_error, grasp_time, start_error, grasp_held, losses, start, final_box, final_angle,
/// max_tension, events [{t, what}], controller, time_to_5mm (s or null), overshoot (m),
/// joint_limit_hits, controller_solve_us and controller_solve_max_us (wall time per update).
nlohmann::json trackSummary(const TrackResult& r, HandLaw law = HandLaw::Jacobian);

/// The JSON object `cablelab track --compare` prints: targets, seed, horizon, and per law
/// ("jacobian" with its integral term, "mpc") median_time_to_5mm (s or null), median and max
/// final error, median and max overshoot (m), grasp_losses, joint_limit_hits, settled (runs),
/// controller_solve_us, controller_solve_max_us; time_ratio (MPC's median time over PID's).
nlohmann::json compareSummary(const CompareResult& r, const CompareOptions& options);

/// `reach`'s options: --grid N, --model simulation|quasi-static, --pd; threads 0: one per core.
/// Throws InputError as the CLI reports it.
ReachOptions reachOptions(int grid, const std::string& model, bool pd, int threads = 0,
                          HandLaw law = HandLaw::Jacobian, int horizon = HandMpcParams{}.horizon);

/// `reach --angles A,B,...`: one or more box angles (rad, each in [-pi, pi]; any but 0 needs a
/// box that may turn); throws InputError(kCommandLine, "--angles", ...).
std::vector<double> reachAngles(std::string_view text, const HandModel& model);

/// The name --model takes for m.
const char* reachModelName(ReachModel m);

/// Whether target t is in r's object set (the chosen model's verdict; the CSV's object_reached).
bool objectReached(const ReachResult& r, const ReachTarget& t);

/// The JSON object `cablelab reach` prints: object_area, fingertip_area, ratio, points, model,
/// law (PID, PD or MPC), controller (jacobian or mpc), object_points, fingertip_points,
/// beyond_fingertips, quasi_static_area,
/// quasi_static_points (the last three are counts), threads, simulated_s, seconds.
nlohmann::json reachSummary(const ReachResult& r, const ReachOptions& options);

}  // namespace cablelab
