// The figure 4-4 experiment: which box positions the Jacobian controller reaches, against the
// range of the fingertips themselves.
//
// Both sets live on one N x N grid over a window round the hand's workspace (cell area known):
//  * fingertip set: grid points g where both fingers can hold the pinch rigidly, paddles face-on
//    (horizontal) with their centres at g +/- (0, baseY), within every joint limit (analytic);
//  * object set: grid points the controller drives the box to (|error| < tolerance, membranes
//    wrapping face-on), quasi-statically: the fingers sit at the commanded joints and the box at
//    the statics equilibrium after every outer-loop update (no dynamics, so no k_d term; error
//    saturated at 10 cm), starting from the pinch pose. Runs on `threads` threads.
#pragma once

#include <functional>
#include <vector>

#include "engine/hand/hand_model.h"

namespace cablelab {

struct ReachOptions {
  int grid = 50;  ///< N: N x N targets
  int threads = 2;
  int maxUpdates = 600;      ///< outer-loop updates per target
  double tolerance = 0.005;  ///< m
};

struct ReachResult {
  double objectArea = 0;                            ///< m^2
  double fingertipArea = 0;                         ///< m^2
  int points = 0;                                   ///< targets tried (N^2)
  std::vector<Vec2> objectPoints, fingertipPoints;  ///< the grid points in each set (m)
  Vec2 lower = Vec2::Zero(), upper = Vec2::Zero();  ///< grid window (m)
  double seconds = 0;                               ///< wall time
};

/// `progress(done, total)` is called from the calling thread about every 0.1 s.
ReachResult runReach(const ReachOptions& options, const HandModel& model = {},
                     const std::function<void(long, long)>& progress = {});

/// Whether both fingers can hold a rigid pinch centred at g (see above).
bool fingertipsReach(const HandModel& model, const Vec2& g);

}  // namespace cablelab
