// Seeded random statics problems (statics.h) for tests and benchmarks.
//
// Fingertip points uniform in [-1, 1]^2 (m), stiffness log-uniform in [0.2, 5] N/m. A cable is
// "loose" with probability `looseFraction`: its rest length exceeds |a - b| by 0.2..1.5 m, so it
// may end slack; the others are shorter than |a - b| (always taut). With `onFingertip` the
// problem is built so that its unique minimiser is exactly the fingertip point a_0 (the kink
// case of docs/model.md#statics): cable 0 is aimed against the others' pull at a_0 and made strong
// enough for a_0 to absorb their net force with margin.
#pragma once

#include <random>

#include "engine/statics/statics.h"

namespace cablelab {

struct RandomStaticsOptions {
  int cables = 4;              ///< N >= 1 (>= 2 with onFingertip)
  double looseFraction = 0.3;  ///< probability that a cable's rest length exceeds |a - b|
  bool onFingertip = false;    ///< the minimiser is exactly cables[0].a
};

/// A random problem drawn from `rng` (p0 not set).
StaticsProblem randomStaticsProblem(std::mt19937_64& rng, const RandomStaticsOptions& options);

}  // namespace cablelab
