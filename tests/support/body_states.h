// Every body's pose and velocity in one list: what bit-for-bit replay tests compare.
#pragma once

#include <vector>

#include "engine/dynamics/world.h"

namespace cablelab::test {

/// x, y, angle, vx, vy, angular velocity of each body in turn.
inline std::vector<double> bodyStates(const World& w) {
  std::vector<double> out;
  for (int i = 0; i < w.bodyCount(); ++i) {
    const BodyState& s = w.body(i);
    out.insert(out.end(), {s.position.x(), s.position.y(), s.angle, s.velocity.x(), s.velocity.y(),
                           s.angularVelocity});
  }
  return out;
}

}  // namespace cablelab::test
