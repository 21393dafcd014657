// The figure 4-4 experiment: which box positions the Jacobian controller reaches, against the
// range of the fingertips themselves.
//
// Every set lives on one N x N grid over a window round the hand's workspace (cell area known):
//  * fingertip set: grid points g where both fingers can hold the pinch rigidly, paddles face-on
//    (horizontal) with their centres at g +/- (0, baseY), within every joint limit (analytic,
//    pinchWithinLimits);
//  * simulated object set (the default model): grid points where the full dynamic run of
//    `cablelab track --target g --pid` (hand_tracking.h) ends within the tolerance with the grasp
//    held. A run stops early once it has settled within the tolerance, lost the box, or stopped
//    getting closer; the runs share out over `threads` threads;
//  * quasi-static object set: the fingers sit at the commanded joints and the box at the statics
//    equilibrium after every outer-loop update (no dynamics, so no k_d term), starting from the
//    pinch pose; the statics model's own prediction of the set.
#pragma once

#include <functional>
#include <vector>

#include "engine/hand/hand_model.h"
#include "engine/hand/hand_tracking.h"

namespace cablelab {

enum class ReachModel { Simulation, QuasiStatic };

struct ReachOptions {
  int grid = 50;    ///< N: N x N targets
  int threads = 0;  ///< 0: one per hardware thread
  ReachModel model = ReachModel::Simulation;
  bool pid = true;           ///< the integral term (as `track --pid`); false: PD
  double time = 15;          ///< s simulated per target at most
  int maxUpdates = 600;      ///< quasi-static outer-loop updates per target
  double tolerance = 0.005;  ///< m
  /// The box angle every target asks for (rad; `reach --angles`); non-zero needs a box that may
  /// turn. A target is then reached within `tolerance` and `angleTolerance` of (x, y, angle).
  double angle = 0;
  double angleTolerance = 0.02;  ///< rad
  /// The simulated runs' outer loop (`pid` is the Jacobian controller's) and the MPC's horizon.
  HandLaw law = HandLaw::Jacobian;
  int horizon = HandMpcParams{}.horizon;
};

/// One grid target's outcome.
struct ReachTarget {
  Vec2 point = Vec2::Zero();
  bool fingertip = false;    ///< in the fingertip set
  bool quasiStatic = false;  ///< in the quasi-static object set
  bool simulated = false;    ///< in the simulated object set (simulation model only)
  double error = 0;          ///< simulation: final |box - target| (m)
  bool graspHeld = false;    ///< simulation: the grasp was never lost
  double simulatedTime = 0;  ///< s of simulation before the run stopped
};

struct ReachResult {
  ReachModel model = ReachModel::Simulation;
  double objectArea = 0;             ///< m^2, the chosen model's object set
  double fingertipArea = 0;          ///< m^2
  double quasiStaticArea = 0;        ///< m^2
  int points = 0;                    ///< targets tried (N^2)
  std::vector<ReachTarget> targets;  ///< N^2, row by row from the window's lower left
  std::vector<Vec2> objectPoints, fingertipPoints, quasiStaticPoints;  ///< the sets (m)
  Vec2 lower = Vec2::Zero(), upper = Vec2::Zero();                     ///< grid window (m)
  double seconds = 0;                                                  ///< wall time
  double simulatedSeconds = 0;                                         ///< summed over the runs
  int threads = 1;
};

/// `progress(done, total)` is called from the calling thread about every 0.1 s. If it throws, the
/// sweep stops (the runs under way finish first) and the exception propagates.
ReachResult runReach(const ReachOptions& options, const HandModel& model = {},
                     const std::function<void(long, long)>& progress = {});

// runReach in three parts, for sweeps that evaluate the targets elsewhere (`cablelab reach
// --scheduler` on Dask): the same grid, the same per-target runs, the same sets and areas.

/// The N x N targets (points and fingertip verdicts) and the window; nothing evaluated yet.
ReachResult reachGrid(const ReachOptions& options, const HandModel& model = {});

/// Target t's object-set verdicts: the quasi-static one, and for the simulation model the
/// full dynamic run's (simulated, error, graspHeld, simulatedTime).
void evaluateReachTarget(const HandModel& model, const ReachOptions& options, ReachTarget& t);

/// The sets, their areas and the summed simulated time from r's evaluated targets.
void summariseReach(ReachResult& r);

/// Whether both fingers can hold a rigid pinch centred at g (see above).
bool fingertipsReach(const HandModel& model, const Vec2& g);

/// The quasi-static sweep's verdict for one target.
bool quasiStaticReach(const HandModel& model, const Vec2& target, const ReachOptions& options);

}  // namespace cablelab
