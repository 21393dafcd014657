// The energy tests' measure: how far a world's energy strays over a run, against its motion.
#pragma once

#include <algorithm>
#include <cmath>

#include "engine/dynamics/world.h"

namespace cablelab::test {

/// The kinetic energy (translation and turn) of all of `world`'s moving bodies.
inline double kineticEnergy(const World& world) {
  double kinetic = 0;
  for (int b = 0; b < world.bodyCount(); ++b) kinetic += kineticEnergy(world.body(b));
  return kinetic;
}

/// Steps `world` `steps` times (dt, `substeps`) and returns the largest |E - E0| over the largest
/// kinetic energy (translation and turn) of its body 0. `each` is called after every step.
template <class Each>
double energyDriftShare(World& world, int steps, double dt, int substeps, Each each) {
  const double e0 = world.energy();
  double worst = 0, scale = 0;
  for (int step = 0; step < steps; ++step) {
    world.step(dt, substeps);
    worst = std::max(worst, std::abs(world.energy() - e0));
    const BodyState& b = world.body(0);
    scale = std::max(
        scale,
        0.5 * b.velocity.squaredNorm() / b.invMass +
            (b.invInertia > 0 ? 0.5 * b.angularVelocity * b.angularVelocity / b.invInertia : 0.0));
    each();
  }
  return worst / scale;
}

inline double energyDriftShare(World& world, int steps, double dt, int substeps) {
  return energyDriftShare(world, steps, dt, substeps, [] {});
}

}  // namespace cablelab::test
