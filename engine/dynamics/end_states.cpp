#include "engine/dynamics/end_states.h"

#include <cmath>

#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/box2d_velocity_update.h"

namespace cablelab {

namespace {
// m/s and rad/s: a body this slow at both ends of a step takes Box2D's update in double
// (setEndStates). It holds every body the float freezes (h v below half its spacing: up to
// 3.6e-6 m/s at 1 m and 60 Hz; the tackle's block stayed 1.4e-6 m/s short of its floors); far
// below the speeds of catches, where taking Box2D's step in double moved knife-edge variants by
// its noise (docs/model.md, "Coupling to Box2D").
constexpr double kSlowSpeed = 1e-3;
}  // namespace

// Box2D's float update leaves a body at rest moving at 1e-8 m/s: m g and the cables' pull cancel
// only to a float's last bit, h / m of it a step (2.5e-8 m/s on 5 kg at 30 Hz), and it moves the
// body with that velocity (a platform sank 2.5 um in 100 s on a rigid cable that kept no length);
// a body creeping by less than half a float's spacing a step does not move at all (a damped
// platform kept 8e-7 m/s with its pose frozen). So a body that is slower than kSlowSpeed at both
// ends of the step, and that Box2D's solver leaves alone after that update (no joint, contact or
// drag: b2Island::Solve applies their impulses after it), takes the update in double and the kick,
// and is placed at q0 + h v keeping what the float drops (docs/model.md, "Coupling to Box2D").
// Faster bodies keep Box2D's float step (chaotic catches moved by its noise flip knife-edge
// variants). The midpoint solve's undamped bodies take its end velocities, its damped ones that
// update in double.
void setEndStates(Box2DBridge& b2, const StepEnd& s, const Vec2& gravity, double dt) {
  static thread_local std::vector<char> free;  // scratch: no allocation a step
  free.assign(s.bodies.size(), 0);
  b2.markTouching(free);  // at the step's end: a contact begun within it acted on the body
  for (size_t b = 0; b < s.bodies.size(); ++b)
    free[b] =
        !free[b] && !s.excluded[b] && s.bodies[b].invMass > 0 && static_cast<int>(b) != s.dragBody;
  auto slow = [](const Vec2& v, double w) {
    return v.norm() <= kSlowSpeed && std::abs(w) <= kSlowSpeed;
  };
  for (int b = 0; b < static_cast<int>(s.bodies.size()); ++b) {
    if (!free[b]) continue;
    const BodyState& start = s.bodies[b];
    const Vec3 v = box2dVelocity(start, s.defs[b], gravity, s.forces[b], dt);
    const Vec3 end = v + s.kicks[b];
    if (!slow(start.velocity, start.angularVelocity) || !slow(end.head<2>(), end.z())) continue;
    b2.placeBody(b, start.position + dt * v.head<2>(), start.angle + dt * v.z(), true);
    b2.setVelocity(b, end.head<2>(), end.z());
  }
  for (const auto& [b, v] : s.ends) {
    const BodyDef& d = s.defs[b];
    const bool damped = d.linearDamping != 0 || d.angularDamping != 0;
    const Vec3 end =
        damped ? box2dVelocity(s.bodies[b], d, gravity, s.forces[b], dt) + s.kicks[b] : v;
    b2.setVelocity(b, end.head<2>(), end.z());
  }
}

}  // namespace cablelab
