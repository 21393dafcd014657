#include "engine/dynamics/wheel_rope_energy.h"

#include <cmath>

#include "engine/dynamics/disjoint_sets.h"
#include "engine/dynamics/floors.h"

namespace cablelab {

namespace {

// m: a segment this much past its floor, plus twice the way its ends move in the step, is near no
// knock. A body arriving at its pulley stops or bounces there (docs/floors.md): energy is lost
// by design, or kept by the bounce's own rule, and not made up here.
constexpr double kKnockMargin = 2 * kFloorLength;
// m: a rope this much shorter than its rest length at the start was slack: its catch is plastic.
constexpr double kTautSlop = 1e-4;
// The sine of the angle between a body's velocity and its change over the step below which it
// moves straight, and a change (m/s) too small to turn it.
constexpr double kStraight = 0.05;
constexpr double kStillChange = 1e-9;

// Whether a rigid rope's step is one the main solve alone moved it through: taut at both ends
// of the step, no capstan or polygon friction, no segment near its floor.
bool ropeKeepsEnergy(const Cable& cable, std::span<const BodyState> start, double dt) {
  if (cable.elastic() || cable.damping() != 0 || !(cable.tension() > 0) ||
      cable.length() < cable.restLength() - kTautSlop)
    return false;
  for (int k = 0; k + 1 < cable.spanCount(); ++k)
    if (cable.link(k).mu != 0) return false;
  const auto& path = cable.path();
  auto speed = [&](const WrapPoint& w) {
    return w.body < 0 ? 0.0 : pointVelocity(start[w.body], w.world).norm();
  };
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    if (path[i].body == path[i + 1].body) continue;
    const double near =
        kFloorLength + kKnockMargin + 2 * dt * (speed(path[i]) + speed(path[i + 1]));
    if (floorGap(path[i], path[i + 1]) < near) return false;
    if (rimEnd(path[i], path[i + 1]) >= 0 && floorGap(path[i], path[i + 1], true) < near)
      return false;
  }
  return true;
}

// Whether a body's velocity changed along itself over the step (or hardly at all): the
// trapezoid's shift, (h/2) (v1 - v0), then runs along its path. On a turning path it points off
// it, and the rope's length with it: a ball whirled round a post on its rope, shifted so, gained
// 83% of its energy in a minute.
bool movesStraight(const BodyState& start, const BodyState& end) {
  const Vec2 change = end.velocity - start.velocity;
  const double across = std::abs(start.velocity.x() * change.y() - start.velocity.y() * change.x());
  return change.norm() < kStillChange ||
         across <= kStraight * start.velocity.norm() * change.norm();
}

}  // namespace

void keepWheelRopeEnergy(const WheelRopeStep& step, std::vector<BodyState>& bodies,
                         std::vector<int>& changed) {
  const int n = static_cast<int>(bodies.size());
  if (static_cast<int>(step.start.size()) != n) return;
  static thread_local std::vector<int> group;  // scratch: no allocation a step
  static thread_local std::vector<char> keeps, wheel;
  group.resize(n);
  for (int b = 0; b < n; ++b) group[b] = b;
  keeps.assign(n, 1);
  wheel.assign(n, 0);
  // Groups: the moving bodies on each rope (its ends and pulleys) and those joined to them.
  for (const Cable& cable : step.cables) {
    int first = -1;
    bool circle = false, kept = ropeKeepsEnergy(cable, step.start, step.dt);
    for (const WrapPoint& w : cable.path()) circle |= w.radius != 0;
    for (const WrapPoint& w : cable.path()) {
      if (w.body < 0) continue;
      if (!moves(bodies[w.body])) {
        kept &= !driven(step.start[w.body]);
        continue;
      }
      if (first >= 0) unite(group, first, w.body);
      first = w.body;
    }
    if (first < 0) continue;
    const int r = findRoot(group, first);
    keeps[r] &= kept;
    wheel[r] |= circle;
  }
  const auto& joints = step.scene->joints;
  for (size_t j = 0; j < joints.size(); ++j) {
    const auto [a, b] = step.jointBodies[j];
    const bool movesA = a >= 0 && moves(bodies[a]), movesB = b >= 0 && moves(bodies[b]);
    if (movesA && movesB) unite(group, a, b);
    const bool free = !joints[j].enableLimit && !joints[j].servo.enabled &&
                      !(a >= 0 && !movesA && driven(step.start[a])) &&
                      !(b >= 0 && !movesB && driven(step.start[b]));
    for (const int body : {a, b})
      if (body >= 0 && moves(bodies[body])) keeps[body] &= free;
  }
  for (int b = 0; b < n; ++b) {
    const int r = findRoot(group, b);
    if (r != b) {
      keeps[r] &= keeps[b];
      wheel[r] |= wheel[b];
    }
    const BodyDef& def = step.scene->bodies[b];
    if (moves(bodies[b]) && (step.worked[b] || def.linearDamping != 0 || def.angularDamping != 0 ||
                             !movesStraight(step.start[b], bodies[b])))
      keeps[r] = 0;
  }
  for (int b = 0; b < n; ++b) {
    const int r = findRoot(group, b);
    if (!keeps[r] || !wheel[r] || !moves(bodies[b])) continue;
    const BodyState& s = step.start[b];
    bodies[b].position = s.position + 0.5 * step.dt * (s.velocity + bodies[b].velocity);
    bodies[b].angle = s.angle + 0.5 * step.dt * (s.angularVelocity + bodies[b].angularVelocity);
    changed.push_back(b);
  }
}

}  // namespace cablelab
