// When Newton on the end-of-step lengths has settled: the dense solve's (cable_solver.cpp, stage
// 6) and the sparse one's (sparse_island.cpp) ask the same. Private to engine/dynamics.
#pragma once

#include <cmath>

namespace cablelab {

/// Whether Newton's iterate has settled after a step of `change` (the largest change of an
/// impulse, N s) that followed one of `lastChange` (infinity at the first iteration), with
/// `largest` the largest impulse now: the step is below 1e-9 of it, or the steps contract by
/// theta < 1 an iteration and the iterate is then within theta / (1 - theta) times the step of
/// the root, below a tenth of that (Hairer and Wanner's stopping rule for Newton in implicit
/// integrators). A hand carrying its box took a third iteration only to see a step of 1e-13 of
/// its impulses after one of 1e-7.
inline bool newtonSettled(double change, double lastChange, double largest) {
  const double tolerance = 1e-9 * (1e-9 + largest);
  if (change <= tolerance) return true;
  // The first step (lastChange infinite) says nothing of the rate; steps that grow, no rate.
  if (!std::isfinite(lastChange) || !(change < lastChange)) return false;
  const double theta = change / lastChange;
  return theta / (1 - theta) * change <= 0.1 * tolerance;
}

/// Whether a warm-started Newton that ran out of iterations is kept anyway: its last step was
/// under 1e-4 of its impulses and shrinking. From P = 0 Newton ends where it did (a weight
/// resting at a wheel's rim: steps of 1e-6 after three iterations, both ways), at twice the cost.
inline bool newtonClose(double lastChange, double largest) {
  return lastChange <= 1e-4 * largest;
}

}  // namespace cablelab
