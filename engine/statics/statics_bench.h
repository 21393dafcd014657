// Timing of the statics solvers on seeded random problems, for `cablelab bench` and
// tests/bench/statics_bench.cpp.
#pragma once

#include "engine/statics/statics.h"

namespace cablelab {

/// Medians over the instances of the per-solve wall time, cold start every solve.
struct StaticsTimings {
  int cables = 0;
  int instances = 0;
  double socpMicros = 0;     ///< interior-point SOCP (socp.h), us
  double newtonMicros = 0;   ///< plain damped Newton (no fingertip handling), us
  double defaultMicros = 0;  ///< solveStatics(): Newton with fingertip handling, SOCP fallback, us
  double socpMeanIterations = 0;
  int socpMaxIterations = 0;
  double socpMaxResidual = 0;     ///< largest |net force| / max tension, SOCP
  double defaultMaxResidual = 0;  ///< same, default path
  int fallbacks = 0;              ///< default-path solves that needed the SOCP
};

/// Times `instances` random problems with n cables (statics_random.h, 30% loose cables, every
/// tenth with its minimiser on a fingertip) drawn from `seed`. Each instance is solved in a
/// batch of repeats (to beat the clock's resolution) and the batch time divided by the count.
StaticsTimings measureStatics(int n, int instances, unsigned seed);

}  // namespace cablelab
