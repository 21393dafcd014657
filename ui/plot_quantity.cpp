// Plottable quantities (ui/plot_quantity.h).
#include "ui/plot_quantity.h"

#include <cmath>
#include <limits>

namespace cablelab::ui {

const char* quantityUnit(Quantity::Kind kind) {
  switch (kind) {
    case Quantity::Kind::X:
    case Quantity::Kind::Y:
    case Quantity::Kind::Length:
    case Quantity::Kind::ControllerError:
      return "m";
    case Quantity::Kind::Vx:
    case Quantity::Kind::Vy:
      return "m/s";
    case Quantity::Kind::Angle:
      return "rad";
    case Quantity::Kind::Tension:
    case Quantity::Kind::SpanTension:
      return "N";
    case Quantity::Kind::Energy:
      return "J";
  }
  return "";
}

std::string quantityName(const World& world, const Quantity& q) {
  using K = Quantity::Kind;
  const bool body =
      q.kind == K::X || q.kind == K::Y || q.kind == K::Vx || q.kind == K::Vy || q.kind == K::Angle;
  const bool cable = q.kind == K::Length || q.kind == K::Tension || q.kind == K::SpanTension;
  std::string owner;
  if (body && q.index >= 0 && q.index < world.bodyCount())
    owner = world.scene().bodies[q.index].name + ": ";
  if (cable && q.index >= 0 && q.index < world.cableCount())
    owner = "cable '" + world.cable(q.index).name() + "'" +
            (q.kind == K::SpanTension ? ", span " + std::to_string(q.span + 1) : "") + ": ";
  switch (q.kind) {
    case K::X:
      return owner + "x";
    case K::Y:
      return owner + "y";
    case K::Vx:
      return owner + "x velocity";
    case K::Vy:
      return owner + "y velocity";
    case K::Angle:
      return owner + "angle";
    case K::Length:
      return owner + "length";
    case K::Tension:
    case K::SpanTension:
      return owner + "tension";
    case K::Energy:
      return "energy";
    case K::ControllerError:
      return "controller error";
  }
  return owner;
}

double quantityValue(const World& world, const std::optional<Vec2>& target, int controlledBody,
                     const Quantity& q) {
  using K = Quantity::Kind;
  const double none = std::numeric_limits<double>::quiet_NaN();
  switch (q.kind) {
    case K::X:
    case K::Y:
    case K::Vx:
    case K::Vy:
    case K::Angle: {
      if (q.index < 0 || q.index >= world.bodyCount()) return none;
      const BodyState& s = world.body(q.index);
      return q.kind == K::X    ? s.position.x()
             : q.kind == K::Y  ? s.position.y()
             : q.kind == K::Vx ? s.velocity.x()
             : q.kind == K::Vy ? s.velocity.y()
                               : s.angle;
    }
    case K::Length:
    case K::Tension:
    case K::SpanTension: {
      if (q.index < 0 || q.index >= world.cableCount()) return none;
      const Cable& c = world.cable(q.index);
      if (q.kind == K::Length) return c.length();
      if (q.kind == K::Tension) return c.tension();
      return q.span >= 0 && q.span < c.spanCount() ? c.spanTension(q.span) : none;
    }
    case K::Energy:
      return world.energy();
    case K::ControllerError:
      if (!target || controlledBody < 0 || controlledBody >= world.bodyCount()) return none;
      return (world.body(controlledBody).position - *target).norm();
  }
  return none;
}

std::vector<Quantity> availableQuantities(const World& world, int controlledBody) {
  using K = Quantity::Kind;
  std::vector<Quantity> out;
  for (int i = 0; i < world.bodyCount(); ++i) {
    if (world.scene().bodies[i].type != BodyType::Dynamic) continue;
    for (K k : {K::X, K::Y, K::Vx, K::Vy, K::Angle}) out.push_back({k, i, 0});
  }
  for (int i = 0; i < world.cableCount(); ++i) {
    out.push_back({K::Length, i, 0});
    out.push_back({K::Tension, i, 0});
    const int spans = world.cable(i).spanCount();
    for (int k = 0; k < spans && spans > 1; ++k) out.push_back({K::SpanTension, i, k});
  }
  out.push_back({K::Energy, -1, 0});
  if (controlledBody >= 0) out.push_back({K::ControllerError, -1, 0});
  return out;
}

}  // namespace cablelab::ui
