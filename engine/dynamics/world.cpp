// World: the public face of the engine. Box2D lives behind box2d_bridge.h, the tensions in
// cable_solver.h; this file keeps the state a user edits and the order of a step.
#include "engine/dynamics/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/cable_solver.h"

namespace cablelab {

namespace {

SceneDef validated(SceneDef scene, const std::string& source) {
  validateScene(scene, source);
  return scene;
}

}  // namespace

World::World(SceneDef scene, const std::string& source)
    : scene_(validated(std::move(scene), source)),
      b2_(std::make_unique<Box2DBridge>(scene_)),
      solver_(std::make_unique<CableSolver>()),
      gravity_(scene_.gravity) {
  jointNeighbours_.assign(scene_.bodies.size(), {});
  for (const JointDef& jd : scene_.joints) {
    const int a = findBody(jd.bodyA), b = findBody(jd.bodyB);
    jointBodies_.push_back({a, b});
    if (a >= 0 && b >= 0) jointNeighbours_[a].push_back(b), jointNeighbours_[b].push_back(a);
    servoTargets_.push_back(jd.servo.target);
  }
  cables_.reserve(scene_.cables.size());
  for (int i = 0; i < static_cast<int>(scene_.cables.size()); ++i)
    cables_.emplace_back(scene_, i, source);
  b2_->readBodies(bodies_);
  for (size_t i = 0; i < cables_.size(); ++i) {
    cables_[i].update(bodies_, &warnings_);
    if (cables_[i].length() < 1e-9)
      throw InputError(source, "cables[" + std::to_string(i) + "]",
                       "zero-length cable: its ends coincide at the initial pose");
  }
}

World::~World() = default;

int World::findBody(std::string_view name) const {
  for (size_t i = 0; i < scene_.bodies.size(); ++i)
    if (scene_.bodies[i].name == name) return static_cast<int>(i);
  return -1;
}

int World::findCable(std::string_view name) const {
  for (size_t i = 0; i < cables_.size(); ++i)
    if (cables_[i].name() == name) return static_cast<int>(i);
  return -1;
}

int World::findJoint(std::string_view name) const {
  for (size_t i = 0; i < scene_.joints.size(); ++i)
    if (scene_.joints[i].name == name) return static_cast<int>(i);
  return -1;
}

void World::setBodyTransform(int i, const Vec2& position, double angle) {
  b2_->setTransform(i, position, angle);
  b2_->readBodies(bodies_);
}

void World::refreshCables() {
  b2_->readBodies(bodies_);
  for (Cable& c : cables_) {
    c.update(bodies_, &warnings_);
    c.refresh(bodies_);
  }
}

void World::setBodyVelocity(int i, const Vec2& velocity, double angularVelocity) {
  b2_->setVelocity(i, velocity, angularVelocity);
  b2_->readBodies(bodies_);
}

void World::applyForce(int i, const Vec2& force, const Vec2& worldPoint) {
  if (pendingForces_.size() != bodies_.size()) pendingForces_.assign(bodies_.size(), Vec3::Zero());
  const Vec2 r = worldPoint - bodies_[i].position;
  pendingForces_[i] += Vec3(force.x(), force.y(), cross(r, force));
}

void World::beginDrag(int body, const Vec2& worldPoint, double stiffnessHz) {
  endDrag();
  if (!b2_->beginDrag(body, worldPoint, stiffnessHz, gravity_.norm())) return;
  dragBody_ = body;
  dragTarget_ = worldPoint;
}

void World::dragTo(const Vec2& target) {
  if (dragBody_ < 0) return;
  b2_->dragTo(target);
  dragTarget_ = target;
}

void World::endDrag() {
  b2_->endDrag();
  dragBody_ = -1;
}

void World::setCableParameters(int i, double restLength, double stiffness, double preload,
                               double damping) {
  const std::string field = "cables[" + std::to_string(i) + "]";
  auto check = [&](double v, const char* name, bool positiveOnly) {
    if (!std::isfinite(v) || v < 0 || (positiveOnly && v == 0))
      throw InputError("live edit", field + "." + name,
                       std::string(positiveOnly ? "must be positive" : "must be >= 0") +
                           gotValue(v));
  };
  check(restLength, "rest_length", true);
  check(stiffness, "stiffness", false);
  check(preload, "preload", false);
  check(damping, "damping", false);
  cables_[i].setParameters({restLength, stiffness, preload, damping});
}

JointState World::joint(int i) const {
  const JointDef& def = scene_.joints[i];
  JointState s{def.name, def.kind, b2_->anchorA(i), b2_->anchorB(i)};
  const JointCoordinate q = b2_->jointCoordinate(i);
  s.value = q.value;
  s.speed = q.speed;
  s.servoTarget = servoTargets_[i];
  return s;
}

void World::setServoTarget(int i, double target) {
  servoTargets_[i] = target;
}

void World::setGravity(const Vec2& g) {
  gravity_ = g;
  b2_->setGravity(g);
}

double World::energy() const {
  double e = 0;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const BodyState& b = bodies_[i];
    if (b.invMass == 0) continue;
    const double m = 1.0 / b.invMass;
    e += 0.5 * m * b.velocity.squaredNorm() - m * gravity_.dot(b.position);
    if (b.invInertia > 0) e += 0.5 * b.angularVelocity * b.angularVelocity / b.invInertia;
  }
  for (const Cable& c : cables_)
    if (c.elastic()) e += 0.5 * c.stiffness() * std::pow(std::max(0.0, c.stretch()), 2);
  return e;
}

// PD servos on joint coordinates, accumulated into forces_ as equal and opposite loads.
void World::applyServos() {
  for (size_t i = 0; i < scene_.joints.size(); ++i) {
    const ServoDef& servo = scene_.joints[i].servo;
    if (!servo.enabled) continue;
    const int j = static_cast<int>(i);
    const JointCoordinate q = b2_->jointCoordinate(j);
    const double f = std::clamp(servo.kp * (servoTargets_[i] - q.value) - servo.kd * q.speed,
                                -servo.maxForce, servo.maxForce);
    const auto [a, b] = jointBodies_[i];
    Vec3 load = Vec3::Zero();
    if (scene_.joints[i].kind == JointDef::Kind::Revolute) {
      load = Vec3(0, 0, f);
    } else if (scene_.joints[i].kind == JointDef::Kind::Prismatic) {
      const Vec2 axis = b2_->prismaticAxis(j);
      load = Vec3(f * axis.x(), f * axis.y(), 0);
    }
    if (b >= 0) forces_[b] += load;
    if (a >= 0) forces_[a] -= load;
  }
}

void World::checkFinite() const {
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const BodyState& b = bodies_[i];
    if (!isFinite(b.position) || !isFinite(b.velocity) || !std::isfinite(b.angle) ||
        !std::isfinite(b.angularVelocity))
      throw SimulationError("body '" + scene_.bodies[i].name + "' has a non-finite state at t = " +
                            std::to_string(time_) + " s (reduce --dt or raise --substeps)");
  }
  for (const Cable& c : cables_)
    if (!std::isfinite(c.tension()) || !std::isfinite(c.length()))
      throw SimulationError("cable '" + c.name() + "' has a non-finite tension or length at t = " +
                            std::to_string(time_) + " s");
}

void World::step(double dt, int substeps) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  double cableSeconds = 0;
  stats_ = {};
  const double h = dt / std::max(1, substeps);
  if (pendingForces_.size() != bodies_.size()) pendingForces_.assign(bodies_.size(), Vec3::Zero());
  for (int s = 0; s < std::max(1, substeps); ++s) {
    // Loads: the user's applyForce() and the servos.
    b2_->readBodies(bodies_);
    forces_ = pendingForces_;
    applyServos();
    // Cables: wrap points and kinematics at the start of the sub-step, then the tensions.
    const auto c0 = Clock::now();
    for (Cable& c : cables_) c.update(bodies_, &warnings_);
    b2_->jointFrames(scene_.joints, jointBodies_, jointFrames_);
    solver_->solve({h, gravity_, bodies_, jointFrames_, jointNeighbours_}, cables_, forces_, stats_);
    cableSeconds += std::chrono::duration<double>(Clock::now() - c0).count();
    // Box2D: integrates with those forces, then contacts, friction and joints.
    b2_->applyLoads(forces_);
    b2_->step(h);
    b2_->readBodies(bodies_);
    time_ += h;
  }
  pendingForces_.assign(bodies_.size(), Vec3::Zero());
  // Lengths reported (and energy) belong to the end-of-step state; the wrap points are
  // re-selected at the start of the next step.
  for (Cable& c : cables_) c.refresh(bodies_);
  ++steps_;
  for (const Cable& c : cables_) stats_.wrapPoints += c.wraps();
  stats_.cableMicros = cableSeconds * 1e6;
  stats_.stepMicros = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  checkFinite();
}

}  // namespace cablelab
