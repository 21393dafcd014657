// A servo's stall, over a window of steps (stall_watch.h, docs/servos.md "Stalls").
#include "engine/dynamics/stall_watch.h"

#include <algorithm>
#include <cmath>

namespace cablelab {

bool StallWatch::update(double force, double maxForce, double value, double rate, double time,
                        double dt) {
  const double before = seen ? last : value;
  last = value;
  seen = true;
  const double sign = force > 0 ? 1 : -1;
  if (stalled) {
    // Said once a stall: it ends when the servo lets up or the joint moves off.
    const bool moved = value < low - kLeaveRange || value > high + kLeaveRange;
    if (std::abs(force) >= kRelease * maxForce && sign == push && !moved) return false;
    stalled = false;
    start = -1;
  }
  if (std::abs(force) < (1 - 1e-9) * maxForce) {
    start = -1;
    return false;
  }
  const bool widens = std::max(high, value) - std::min(low, value) > kStillRange;
  if (start < 0 || sign != push || widens) {
    // A new window: from this step's start where the joint kept still over it, else its end.
    const bool stillOverStep = std::abs(value - before) <= kStillRange;
    start = stillOverStep ? time - dt : time;
    low = stillOverStep ? std::min(before, value) : value;
    high = stillOverStep ? std::max(before, value) : value;
    push = sign;
  } else {
    low = std::min(low, value);
    high = std::max(high, value);
  }
  // 1e-9 s: the time summed over the window's steps.
  if (time - start < kWindow - 1e-9 || std::abs(rate) > kStillRate) return false;
  stalled = true;
  return true;
}

}  // namespace cablelab
