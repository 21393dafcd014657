// The Box2D bridge. Box2D is float; everything cablelab computes is double, converted here.
#include "engine/world.h"

#include <box2d/box2d.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/error.h"
#include "engine/tension_solver.h"

namespace cablelab {

namespace {

constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;
constexpr double kBaumgarte = 0.2;  // share of a rigid cable's length error fixed per step
// Length error a rigid cable tolerates before stabilisation acts (m). Box2D keeps positions in
// float (about 1e-7 m resolution at 1 m): correcting below that only amplifies rounding, by
// beta / h^2 in the tension.
constexpr double kLengthSlop = 1e-5;

b2Vec2 toB2(const Vec2& v) { return b2Vec2(static_cast<float>(v.x()), static_cast<float>(v.y())); }
Vec2 fromB2(const b2Vec2& v) { return Vec2(v.x, v.y); }

b2BodyType toB2(BodyType t) {
  switch (t) {
    case BodyType::Static: return b2_staticBody;
    case BodyType::Kinematic: return b2_kinematicBody;
    case BodyType::Dynamic: return b2_dynamicBody;
  }
  return b2_dynamicBody;
}

}  // namespace

struct World::Box2D {
  b2World world{b2Vec2(0, 0)};
  b2Body* ground = nullptr;
  std::vector<b2Body*> bodies;
  std::vector<b2Joint*> joints;
  b2MouseJoint* mouse = nullptr;
};

World::World(SceneDef scene, const std::string& source) : scene_(std::move(scene)), b2_(std::make_unique<Box2D>()) {
  validateScene(scene_, source);
  b2World& w = b2_->world;
  w.SetGravity(toB2(scene_.gravity));
  w.SetAllowSleeping(false);
  b2BodyDef groundDef;
  b2_->ground = w.CreateBody(&groundDef);

  for (const BodyDef& bd : scene_.bodies) {
    b2BodyDef def;
    def.type = toB2(bd.type);
    def.position = toB2(bd.position);
    def.angle = static_cast<float>(bd.angle);
    def.linearVelocity = toB2(bd.velocity);
    def.angularVelocity = static_cast<float>(bd.angularVelocity);
    def.fixedRotation = bd.fixedRotation;
    def.linearDamping = static_cast<float>(bd.linearDamping);
    def.angularDamping = static_cast<float>(bd.angularDamping);
    def.allowSleep = false;
    b2Body* body = w.CreateBody(&def);
    for (const ShapeDef& sd : bd.shapes) {
      b2FixtureDef fd;
      b2CircleShape circle;
      b2PolygonShape polygon;
      if (sd.kind == ShapeDef::Kind::Circle) {
        circle.m_radius = static_cast<float>(sd.radius);
        circle.m_p = toB2(sd.center);
        fd.shape = &circle;
      } else {
        std::vector<b2Vec2> v;
        for (const Vec2& p : sd.vertices) v.push_back(toB2(p));
        polygon.Set(v.data(), static_cast<int32>(v.size()));
        fd.shape = &polygon;
      }
      fd.density = 1.0f;
      fd.friction = static_cast<float>(sd.friction);
      fd.restitution = static_cast<float>(sd.restitution);
      fd.isSensor = sd.sensor;
      body->CreateFixture(&fd);
    }
    if (bd.type == BodyType::Dynamic) {
      // The centre of mass is the body origin by definition, so the mass matrix is diagonal in
      // (x, y, theta) (NOTES.md conventions). Inertia defaults to the shapes' at uniform density.
      const double shapeMass = body->GetMass();
      double inertia = bd.inertia;
      if (inertia <= 0) inertia = shapeMass > 0 ? body->GetInertia() * bd.mass / shapeMass : 0;
      if (inertia <= 0) inertia = 0.5 * bd.mass * 0.01;  // shapeless: a 0.1 m disc
      b2MassData md{static_cast<float>(bd.mass), b2Vec2(0, 0), static_cast<float>(inertia)};
      body->SetMassData(&md);
    }
    b2_->bodies.push_back(body);
  }

  auto bodyOf = [&](const std::string& name) {
    const int i = findBodyIndex(scene_, name);
    return i < 0 ? b2_->ground : b2_->bodies[i];
  };
  for (const JointDef& jd : scene_.joints) {
    b2Body* a = bodyOf(jd.bodyA);
    b2Body* b = bodyOf(jd.bodyB);
    b2Joint* joint = nullptr;
    switch (jd.kind) {
      case JointDef::Kind::Revolute: {
        b2RevoluteJointDef def;
        def.Initialize(a, b, toB2(jd.anchor));
        def.enableLimit = jd.enableLimit;
        def.lowerAngle = static_cast<float>(jd.lower);
        def.upperAngle = static_cast<float>(jd.upper);
        def.collideConnected = jd.collideConnected;
        joint = w.CreateJoint(&def);
        break;
      }
      case JointDef::Kind::Prismatic: {
        b2PrismaticJointDef def;
        def.Initialize(a, b, toB2(jd.anchor), toB2(jd.axis.normalized()));
        def.enableLimit = jd.enableLimit;
        def.lowerTranslation = static_cast<float>(jd.lower);
        def.upperTranslation = static_cast<float>(jd.upper);
        def.collideConnected = jd.collideConnected;
        joint = w.CreateJoint(&def);
        break;
      }
      case JointDef::Kind::Weld: {
        b2WeldJointDef def;
        def.Initialize(a, b, toB2(jd.anchor));
        def.collideConnected = jd.collideConnected;
        joint = w.CreateJoint(&def);
        break;
      }
    }
    b2_->joints.push_back(joint);
  }

  for (int i = 0; i < static_cast<int>(scene_.cables.size()); ++i) cables_.emplace_back(scene_, i, source);
  readBodies();
  for (size_t i = 0; i < cables_.size(); ++i) {
    cables_[i].update(bodies_, &warnings_);
    if (cables_[i].length() < 1e-9)
      throw InputError(source, "cables[" + std::to_string(i) + "]", "zero-length cable: its ends coincide at the initial pose");
    scene_.cables[i].restLength = cables_[i].restLength();
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

void World::readBodies() {
  bodies_.resize(b2_->bodies.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const b2Body* b = b2_->bodies[i];
    BodyState& s = bodies_[i];
    s.position = fromB2(b->GetPosition());
    s.angle = b->GetAngle();
    s.velocity = fromB2(b->GetLinearVelocity());
    s.angularVelocity = b->GetAngularVelocity();
    const bool dynamic = b->GetType() == b2_dynamicBody;
    s.invMass = dynamic && b->GetMass() > 0 ? 1.0 / b->GetMass() : 0.0;
    s.invInertia = dynamic && !b->IsFixedRotation() && b->GetInertia() > 0 ? 1.0 / b->GetInertia() : 0.0;
  }
}

void World::setBodyTransform(int i, const Vec2& position, double angle) {
  b2_->bodies[i]->SetTransform(toB2(position), static_cast<float>(angle));
  readBodies();
}

void World::setBodyVelocity(int i, const Vec2& velocity, double angularVelocity) {
  b2_->bodies[i]->SetLinearVelocity(toB2(velocity));
  b2_->bodies[i]->SetAngularVelocity(static_cast<float>(angularVelocity));
  readBodies();
}

void World::applyForce(int i, const Vec2& force, const Vec2& worldPoint) {
  if (pendingForces_.size() != bodies_.size()) pendingForces_.assign(bodies_.size(), Vec3::Zero());
  const Vec2 r = worldPoint - bodies_[i].position;
  pendingForces_[i] += Vec3(force.x(), force.y(), cross(r, force));
}

void World::beginDrag(int body, const Vec2& worldPoint, double stiffnessHz) {
  endDrag();
  b2Body* b = b2_->bodies[body];
  if (b->GetType() != b2_dynamicBody) return;
  b2MouseJointDef def;
  def.bodyA = b2_->ground;
  def.bodyB = b;
  def.target = toB2(worldPoint);
  def.maxForce = static_cast<float>(1000.0 * b->GetMass() * std::max(9.81, scene_.gravity.norm()));
  b2LinearStiffness(def.stiffness, def.damping, static_cast<float>(stiffnessHz), 0.7f, def.bodyA, def.bodyB);
  b2_->mouse = static_cast<b2MouseJoint*>(b2_->world.CreateJoint(&def));
  dragBody_ = body;
  dragTarget_ = worldPoint;
}

void World::dragTo(const Vec2& target) {
  if (!b2_->mouse) return;
  b2_->mouse->SetTarget(toB2(target));
  dragTarget_ = target;
}

void World::endDrag() {
  if (b2_->mouse) b2_->world.DestroyJoint(b2_->mouse);
  b2_->mouse = nullptr;
  dragBody_ = -1;
}

void World::setCableParameters(int i, double restLength, double stiffness, double preload, double damping) {
  const std::string field = "cables[" + std::to_string(i) + "]";
  auto check = [&](double v, const char* name, bool positiveOnly) {
    if (!std::isfinite(v) || v < 0 || (positiveOnly && v == 0))
      throw InputError("parameters", field + "." + name, "must be a finite number >= 0");
  };
  check(restLength, "rest_length", true);
  check(stiffness, "stiffness", false);
  check(preload, "preload", false);
  check(damping, "damping", false);
  cables_[i].setParameters(restLength, stiffness, preload, damping);
  CableDef& def = scene_.cables[i];
  def.restLength = restLength, def.stiffness = stiffness, def.preload = preload, def.damping = damping;
}

JointState World::joint(int i) const {
  const JointDef& def = scene_.joints[i];
  const b2Joint* j = b2_->joints[i];
  JointState s{def.name, def.kind, fromB2(j->GetAnchorA()), fromB2(j->GetAnchorB())};
  if (def.kind == JointDef::Kind::Revolute) {
    auto* r = static_cast<const b2RevoluteJoint*>(j);
    s.value = r->GetJointAngle();
    s.speed = r->GetJointSpeed();
  } else if (def.kind == JointDef::Kind::Prismatic) {
    auto* p = static_cast<const b2PrismaticJoint*>(j);
    s.value = p->GetJointTranslation();
    s.speed = p->GetJointSpeed();
  }
  s.servoTarget = def.servo.target;
  return s;
}

void World::setServoTarget(int i, double target) { scene_.joints[i].servo.target = target; }

void World::setGravity(const Vec2& g) {
  scene_.gravity = g;
  b2_->world.SetGravity(toB2(g));
}

double World::energy() const {
  double e = 0;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const BodyState& b = bodies_[i];
    if (b.invMass == 0) continue;
    const double m = 1.0 / b.invMass;
    e += 0.5 * m * b.velocity.squaredNorm() - m * scene_.gravity.dot(b.position);
    if (b.invInertia > 0) e += 0.5 * b.angularVelocity * b.angularVelocity / b.invInertia;
  }
  for (const Cable& c : cables_)
    if (c.elastic()) e += 0.5 * c.def().stiffness * std::pow(std::max(0.0, c.stretch()), 2);
  return e;
}

// PD servos on joint coordinates, accumulated into forces_ as equal and opposite loads.
void World::applyServos() {
  for (size_t i = 0; i < scene_.joints.size(); ++i) {
    const ServoDef& servo = scene_.joints[i].servo;
    if (!servo.enabled) continue;
    const JointState s = joint(static_cast<int>(i));
    const double f = std::clamp(servo.kp * (servo.target - s.value) - servo.kd * s.speed, -servo.maxForce, servo.maxForce);
    b2Joint* j = b2_->joints[i];
    const int a = findBody(scene_.joints[i].bodyA);
    const int b = findBody(scene_.joints[i].bodyB);
    Vec3 load = Vec3::Zero();
    if (scene_.joints[i].kind == JointDef::Kind::Revolute) {
      load = Vec3(0, 0, f);
    } else if (scene_.joints[i].kind == JointDef::Kind::Prismatic) {
      auto* p = static_cast<b2PrismaticJoint*>(j);
      const Vec2 axis = rotate(fromB2(p->GetLocalAxisA()), j->GetBodyA()->GetAngle());
      load = Vec3(f * axis.x(), f * axis.y(), 0);
    }
    if (b >= 0) forces_[b] += load;
    if (a >= 0) forces_[a] -= load;
  }
}

void World::solveCableForces(double h) {
  std::vector<TensionRow> rows;
  std::vector<int> cableOfRow;
  for (size_t i = 0; i < cables_.size(); ++i) {
    const Cable& c = cables_[i];
    const CableKinematics& k = c.kinematics();
    cables_[i].setTension(0);
    if (k.jacobian.empty()) continue;  // both ends immovable: nothing to push on
    TensionRow row;
    row.jacobian = &k.jacobian;
    const double phi = c.stretch();
    if (!c.elastic()) {
      // Acceleration-level condition J a + Jdot v = 0 at velocity level, plus Baumgarte on the
      // length error beyond the slop.
      const double error = std::copysign(std::max(0.0, std::abs(phi) - kLengthSlop), phi);
      row.targetRate = -kBaumgarte * error / h - h * k.jdotV;
    } else {
      // Implicit spring-damper: T = k (phi + h J v) + b J v with v the end-of-step velocity and
      // the same J-dot-v correction, T >= 0. Stable for any k and mass at any h.
      const double stiff = c.def().stiffness, damp = c.def().damping;
      const double gamma = stiff / (stiff * h + damp);
      row.targetRate = -gamma * phi - h * k.jdotV;
      row.compliance = 1.0 / (h * (stiff * h + damp));
    }
    rows.push_back(row);
    cableOfRow.push_back(static_cast<int>(i));
  }
  if (rows.empty()) return;

  std::vector<Vec3> predicted(bodies_.size());
  for (size_t b = 0; b < bodies_.size(); ++b) {
    const BodyState& s = bodies_[b];
    const Vec3 inv(s.invMass, s.invMass, s.invInertia);
    Vec3 v(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    if (s.invMass > 0) v += h * (Vec3(scene_.gravity.x(), scene_.gravity.y(), 0) + inv.cwiseProduct(forces_[b]));
    predicted[b] = v;
  }
  const TensionSolution sol = solveTensions(rows, bodies_, predicted);
  stats_.solverIterations += sol.iterations;
  stats_.residual = std::max(stats_.residual, sol.residual);
  for (size_t r = 0; r < rows.size(); ++r) {
    const double tension = sol.impulse[r] / h;
    cables_[cableOfRow[r]].setTension(tension);
    for (const auto& e : *rows[r].jacobian) forces_[e.body] -= tension * e.d;
  }
}

// Nonlinear projection of over-long rigid cables back to their rest length (one Newton step on
// all violated cables together, mass-weighted like Box2D's position solver).
void World::projectRigidCables() {
  std::vector<int> violated;
  std::vector<CableKinematics> kin;
  for (size_t i = 0; i < cables_.size(); ++i) {
    Cable& c = cables_[i];
    if (c.elastic()) continue;
    c.refresh(bodies_);
    if (c.stretch() > kLengthSlop && !c.kinematics().jacobian.empty()) violated.push_back(static_cast<int>(i));
  }
  if (violated.empty()) return;
  const int n = static_cast<int>(violated.size());
  std::vector<TensionRow> rows(n);
  Eigen::MatrixXd K(n, n);
  Eigen::VectorXd phi(n);
  std::vector<Vec3> zero(bodies_.size(), Vec3::Zero());
  for (int r = 0; r < n; ++r) {
    rows[r].jacobian = &cables_[violated[r]].kinematics().jacobian;
    phi[r] = cables_[violated[r]].stretch() - 0.5 * kLengthSlop;
  }
  // Reuse the tension solver with zero velocity: it solves K x = -phi... with sign handled here.
  for (int r = 0; r < n; ++r) rows[r].targetRate = -phi[r];
  const TensionSolution sol = solveTensions(rows, bodies_, zero);
  std::vector<Vec3> dq(bodies_.size(), Vec3::Zero());
  for (int r = 0; r < n; ++r) applyTensionImpulse(rows[r], sol.impulse[r], bodies_, dq);
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (dq[b].isZero()) continue;
    const BodyState& s = bodies_[b];
    b2_->bodies[b]->SetTransform(toB2(s.position + dq[b].head<2>()), static_cast<float>(s.angle + dq[b].z()));
  }
  readBodies();
  for (int i : violated) cables_[i].refresh(bodies_);
}

void World::checkFinite() const {
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const BodyState& b = bodies_[i];
    if (!isFinite(b.position) || !isFinite(b.velocity) || !std::isfinite(b.angle) || !std::isfinite(b.angularVelocity))
      throw SimulationError("body '" + scene_.bodies[i].name + "' has a non-finite state at t = " + std::to_string(time_) +
                            " s (reduce --dt or raise --substeps)");
  }
  for (const Cable& c : cables_)
    if (!std::isfinite(c.tension()) || !std::isfinite(c.length()))
      throw SimulationError("cable '" + c.name() + "' has a non-finite tension or length at t = " + std::to_string(time_) + " s");
}

void World::step(double dt, int substeps) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  double cableSeconds = 0;
  stats_ = {};
  const double h = dt / std::max(1, substeps);
  if (pendingForces_.size() != bodies_.size()) pendingForces_.assign(bodies_.size(), Vec3::Zero());
  for (int s = 0; s < std::max(1, substeps); ++s) {
    readBodies();
    forces_ = pendingForces_;
    applyServos();
    const auto c0 = Clock::now();
    for (Cable& c : cables_) c.update(bodies_, &warnings_);
    solveCableForces(h);
    cableSeconds += std::chrono::duration<double>(Clock::now() - c0).count();
    for (size_t b = 0; b < bodies_.size(); ++b) {
      if (forces_[b].isZero()) continue;
      b2Body* body = b2_->bodies[b];
      body->ApplyForceToCenter(toB2(forces_[b].head<2>()), false);
      body->ApplyTorque(static_cast<float>(forces_[b].z()), false);
    }
    b2_->world.Step(static_cast<float>(h), kVelocityIterations, kPositionIterations);
    readBodies();
    const auto c1 = Clock::now();
    projectRigidCables();
    cableSeconds += std::chrono::duration<double>(Clock::now() - c1).count();
    time_ += h;
  }
  pendingForces_.assign(bodies_.size(), Vec3::Zero());
  ++steps_;
  for (const Cable& c : cables_) stats_.wrapPoints += c.wraps();
  stats_.cableMicros = cableSeconds * 1e6;
  stats_.stepMicros = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  checkFinite();
}

}  // namespace cablelab
