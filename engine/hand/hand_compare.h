// The two outer-loop laws side by side (`cablelab track --compare`): the Jacobian controller with
// its integral term (PID, hand_controller.h) and model-predictive control (hand_mpc.h) track the
// same seeded targets inside the reach set from the same grasp, and each law's runs are summed up
// as the comparison asks: median time to within 5 mm, final error, overshoot, grasp
// losses and joint-limit hits.
#pragma once

#include <functional>
#include <vector>

#include "engine/hand/hand_tracking.h"

namespace cablelab {

struct CompareOptions {
  int targets = 20;                       ///< how many targets
  unsigned seed = 1;                      ///< of the targets' draw
  double time = 15;                       ///< s simulated per run
  int horizon = HandMpcParams{}.horizon;  ///< the MPC's
  int threads = 0;                        ///< 0: one per hardware thread
};

/// One law's runs summed up.
struct LawSummary {
  double medianTimeTo5mm = -1;  ///< s (an unsettled run counts as never); -1: half never settled
  double medianFinalError = 0;  ///< m
  double maxFinalError = 0;     ///< m
  double medianOvershoot = 0;   ///< m
  double maxOvershoot = 0;      ///< m
  int graspLosses = 0;          ///< summed over the runs
  int limitHits = 0;            ///< summed over the runs
  int settled = 0;              ///< runs that ended within 5 mm
  double solveMicros = 0;       ///< mean wall time of one update over every run (us)
  double maxSolveMicros = 0;    ///< the longest update (us)
};

struct CompareResult {
  std::vector<Vec2> targets;
  std::vector<TrackResult> jacobian, mpc;  ///< per target, in order
  LawSummary jacobianSummary, mpcSummary;
};

/// `count` targets drawn uniformly (seeded) from the points the fingertips can pinch
/// (pinchWithinLimits, a subset of either law's reach set) at least 10 cm off the start (the
/// pinch at the origin) and 5 cm inside the fingertips' range.
std::vector<Vec2> compareTargets(const HandModel& model, int count, unsigned seed);

/// The runs' summary (above).
LawSummary summariseLaw(const std::vector<TrackResult>& runs);

/// Runs both laws on compareTargets(); `progress(done, total)` after every run.
CompareResult compareLaws(const CompareOptions& options, const HandModel& model = {},
                          const std::function<void(long, long)>& progress = {});

}  // namespace cablelab
