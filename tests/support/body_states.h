// Every body's pose and velocity in one list: what bit-for-bit replay tests compare.
#pragma once

#include <algorithm>
#include <cmath>
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

/// The largest |a[i] - b[i]| (lists of one length): how far two runs' records part.
inline double largestDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

/// The largest |v[i]|, at least `floor`: the scale a record's differences are measured on.
inline double largestMagnitude(const std::vector<double>& v, double floor) {
  double m = floor;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace cablelab::test
