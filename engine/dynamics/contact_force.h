// ContactForce: what Box2D's contacts did between two bodies (World::contactForces).
#pragma once

#include "engine/core/math.h"

namespace cablelab {

/// The contact force between bodies A and B (indices into the scene's bodies, -1: the world's
/// static ground) over the last Box2D step, summed over the pair's touching contact points.
struct ContactForce {
  int bodyA = -1, bodyB = -1;
  Vec2 force = Vec2::Zero();   ///< on B from A (N); A gets the opposite
  Vec2 point = Vec2::Zero();   ///< where it acts: the contact points' mean, weighted by force (m)
  Vec2 normal = Vec2::Zero();  ///< unit, from A to B
};

}  // namespace cablelab
