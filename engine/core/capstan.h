// The capstan slide of an elastic rope over a gripping corner chain (docs/polygon_friction.md,
// "Elastic cables"), shared by the dynamics (Cable) and the statics (box_friction.h).
#pragma once

#include <algorithm>

namespace cablelab {

/// Tension per unit stiffness k of a span of length `length` holding material `rest`, on a rope
/// whose whole material is `material`: L (l / r - 1) while taut (span stiffness k L / r).
inline double materialTension(double material, double length, double rest) {
  return material * std::max(0.0, length / rest - 1);
}

/// Where the tighter of two spans breaks T_tight <= ratio T_loose: the material it holds once
/// rope has slid over to it until T_tight = ratio T_loose exactly (the two hold `sum` together;
/// the tension difference falls as the tight span gains material, so bisection finds it).
inline double slideMaterial(double material, double tightLength, double tightRest,
                            double looseLength, double sum, double ratio) {
  double lo = tightRest, hi = sum;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * sum; ++i) {
    const double x = 0.5 * (lo + hi);
    const double g = materialTension(material, tightLength, x) -
                     ratio * materialTension(material, looseLength, sum - x);
    (g > 0 ? lo : hi) = x;
  }
  return lo;
}

}  // namespace cablelab
