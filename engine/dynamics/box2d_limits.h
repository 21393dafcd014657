// The most Box2D moves a body in one step (b2_maxTranslation, b2_maxRotation in its b2_common.h):
// a body that would move further is slowed to fit. The cable solves check their answers against
// these (cable_solver_checks.cpp, world.cpp).
#pragma once

#include <box2d/b2_common.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "engine/cable/cable.h"

namespace cablelab {

inline constexpr double kBox2DMaxStepMove = 2.0;                     // m
inline constexpr double kBox2DMaxStepTurn = 0.5 * std::numbers::pi;  // rad

static_assert(kBox2DMaxStepMove == b2_maxTranslation);
static_assert(kBox2DMaxStepTurn - b2_maxRotation < 1e-6 &&
              b2_maxRotation - kBox2DMaxStepTurn < 1e-6);

// How far past the step limits maxTurn, maxMove (these, less a margin) the midpoint solve's bodies
// move over dt at their midpoint velocities (v0 + v1) / 2, the ones Box2D steps them with (ends:
// v1): the largest share used (above 1: Box2D would move them less than the solve assumed).
inline double shareOfBox2DLimits(std::span<const BodyState> bodies,
                                 const std::vector<std::pair<int, Vec3>>& ends, double dt,
                                 double maxTurn, double maxMove) {
  double share = 0;
  for (const auto& [b, v1] : ends) {
    const Vec2 v = 0.5 * (bodies[b].velocity + v1.head<2>());
    const double w = 0.5 * (bodies[b].angularVelocity + v1.z());
    share = std::max({share, dt * std::abs(w) / maxTurn, dt * v.norm() / maxMove});
  }
  return share;
}

}  // namespace cablelab
