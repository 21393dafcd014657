// The hand experiments as `cablelab track` and `cablelab reach` take and report them. The CLI
// (app/cmd_track.cpp, app/cmd_reach.cpp) and the Python module (python/py_hand.cpp) both go
// through these, so that they check the same options with the same messages and report the same
// fields.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "engine/hand/hand_reach.h"
#include "engine/hand/hand_tracking.h"

namespace cablelab {

/// `track`'s options as given, already numbers; the optional ones may be absent.
struct TrackRequest {
  std::optional<Vec2> target;                 ///< --target X,Y (m)
  std::optional<std::array<double, 3>> ramp;  ///< --ramp X,Y,SECONDS (m, m, s)
  std::optional<Vec2> start;                  ///< --start X,Y (m)
  double time = 15;                           ///< --time (s)
  bool pid = false;                           ///< --pid
};

/// The checked TrackOptions; throws InputError("command line", "--OPTION", ...), the CLI's
/// message.
TrackOptions trackOptions(const TrackRequest& request, const HandModel& model = {});

/// The JSON object `cablelab track` prints: final_error, rms_error, grasp_time, start_error,
/// grasp_held, losses, start, final_box, max_tension, events [{t, what}].
nlohmann::json trackSummary(const TrackResult& r);

/// `reach`'s options: --grid N, --model simulation|quasi-static, --pd; threads 0: one per core.
/// Throws InputError as the CLI reports it.
ReachOptions reachOptions(int grid, const std::string& model, bool pd, int threads = 0);

/// The name --model takes for m.
const char* reachModelName(ReachModel m);

/// Whether target t is in r's object set (the chosen model's verdict; the CSV's object_reached).
bool objectReached(const ReachResult& r, const ReachTarget& t);

/// The JSON object `cablelab reach` prints: object_area, fingertip_area, ratio, points, model,
/// law, object_points, fingertip_points, beyond_fingertips, quasi_static_area,
/// quasi_static_points (the last three are counts), threads, simulated_s, seconds.
nlohmann::json reachSummary(const ReachResult& r, const ReachOptions& options);

}  // namespace cablelab
