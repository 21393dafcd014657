// Posing: the poses a drag may give the bodies of a paused world without stretching a rigid
// cable or pulling a joint apart (docs/model.md, "Posing"). World::poseBody and
// World::settlePose are its public face; private to engine/dynamics.
//
// Each call is a few Gauss-Newton steps of the projection
//     minimise 1/2 |q - q0|^2_M + W/2 |p(q) - w|^2
//     subject to  length_k(q) <= rest_k  (every span of every rigid cable, wraps as they are),
//                 joint anchors together, joint coordinates within their limits,
// over the pose q of every dynamic body (x, y, theta; M = diag(m, m, I), fixed rotations held),
// from the pose q0 the step starts at, p the dragged point and w the mouse's point. W is large,
// so the other bodies give way first: pull one end of a rope over a pulley and the other end
// rises. Each step is one small QP on the lengths' Jacobians (engine/core/small_qp.h); the grabbed
// point advances at most kSubMove a projection, so the wrap points follow it continuously.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/world.h"

namespace cablelab {

/// The drag to project; body -1: none (settle the constraints only).
struct PoseGoal {
  int body = -1;
  Vec2 grabLocal = Vec2::Zero();  ///< the grabbed point, body frame (m)
  Vec2 target = Vec2::Zero();     ///< where it should go, world (m)
  bool payOut = false;            ///< rigid cables let out length instead of holding
};

/// The World's members the projection reads and moves.
struct PoseWorld {
  const SceneDef& scene;
  Box2DBridge& box2d;
  std::vector<Cable>& cables;
  std::vector<BodyState>& bodies;                   ///< read back after every step
  std::span<const std::array<int, 2>> jointBodies;  ///< (body A, body B) per joint, -1: world
  std::vector<std::string>& warnings;
};

/// Moves the bodies (in Box2D and `bodies`) and updates the cables; see the top of the file.
PoseResult projectPose(PoseWorld& world, const PoseGoal& goal);

}  // namespace cablelab
