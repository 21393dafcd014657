// The most Box2D moves a body in one step (b2_maxTranslation, b2_maxRotation in its b2_common.h):
// a body that would move further is slowed to fit. The cable solves check their answers against
// these (cable_solver_checks.cpp, world.cpp).
#pragma once

#include <box2d/b2_common.h>

#include <numbers>

namespace cablelab {

inline constexpr double kBox2DMaxStepMove = 2.0;                     // m
inline constexpr double kBox2DMaxStepTurn = 0.5 * std::numbers::pi;  // rad

static_assert(kBox2DMaxStepMove == b2_maxTranslation);
static_assert(kBox2DMaxStepTurn - b2_maxRotation < 1e-6 &&
              b2_maxRotation - kBox2DMaxStepTurn < 1e-6);

}  // namespace cablelab
