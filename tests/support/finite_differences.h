// Shared pieces of the finite-difference checks of the engine's derivatives.
#pragma once

#include <vector>

#include "engine/cable/cable.h"

namespace cablelab::test {

inline constexpr double kFdStep = 1e-6;    ///< central-difference step
inline constexpr double kRelative = 1e-6;  ///< tolerance relative to the derivative's size

/// Moves every body along its velocity for time t (theta with omega): q(t) = q + t v.
inline std::vector<BodyState> advance(std::vector<BodyState> bodies, double t) {
  for (BodyState& b : bodies) {
    b.position += t * b.velocity;
    b.angle += t * b.angularVelocity;
  }
  return bodies;
}

}  // namespace cablelab::test
