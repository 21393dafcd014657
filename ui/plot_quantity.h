// What the sandbox can plot against time: a body's position, velocity or angle; a cable's length,
// tension or one span's tension; the world's energy; the controller's error (the hand: distance
// from the box to the target). Each with a name and unit for the plot's legend and axis.
//
// Needs: the engine's World. No ImGui, no GL.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"

namespace cablelab::ui {

struct Quantity {
  enum class Kind { X, Y, Vx, Vy, Angle, Length, Tension, SpanTension, Energy, ControllerError };
  Kind kind = Kind::Energy;
  int index = -1;  ///< body (X .. Angle) or cable (Length .. SpanTension)
  int span = 0;    ///< SpanTension: the span
  bool operator==(const Quantity& o) const {
    return kind == o.kind && index == o.index && span == o.span;
  }
};

/// "m", "m/s", "rad", "N", "J".
const char* quantityUnit(Quantity::Kind kind);

/// What the plot's legend says: "box: x", "cable 'rope': tension", "cable 'rope', span 2:
/// tension", "energy", "controller error".
std::string quantityName(const World& world, const Quantity& q);

/// The value now; NaN when there is none (no target, an index the world lacks).
double quantityValue(const World& world, const std::optional<Vec2>& target, int controlledBody,
                     const Quantity& q);

/// Every quantity `world` offers, bodies' first (dynamic bodies only), then cables' (spans when a
/// cable has more than one), energy; controller error when `controlledBody` >= 0.
std::vector<Quantity> availableQuantities(const World& world, int controlledBody);

}  // namespace cablelab::ui
