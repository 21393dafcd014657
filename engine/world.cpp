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
constexpr int kNewtonIterations = 3;  // on the end-of-step lengths; geometry is nearly linear

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

  jointNeighbours_.assign(scene_.bodies.size(), {});
  for (const JointDef& jd : scene_.joints) {
    const int a = findBody(jd.bodyA), b = findBody(jd.bodyB);
    if (a >= 0 && b >= 0) jointNeighbours_[a].push_back(b), jointNeighbours_[b].push_back(a);
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

// Generalized coordinates of the bodies the cables move: 3 per moving body.
struct World::DofMap {
  std::vector<int> ofBody;  // body -> first dof, -1 if the body does not move
  std::vector<int> body;    // dof / 3 -> body
  int size() const { return 3 * static_cast<int>(body.size()); }
  int add(int b) {
    if (ofBody[b] < 0) {
      ofBody[b] = size();
      body.push_back(b);
    }
    return ofBody[b];
  }
};

namespace {

}  // namespace

Eigen::VectorXd World::inverseMassOf(const DofMap& dofs) const {
  Eigen::VectorXd inv(dofs.size());
  for (size_t k = 0; k < dofs.body.size(); ++k) {
    const BodyState& s = bodies_[dofs.body[k]];
    inv.segment<3>(3 * k) = Vec3(s.invMass, s.invMass, s.invInertia);
  }
  return inv;
}

// Velocity-level Jacobian of the Box2D joints among `dofs` (rows: constrained relative motions;
// limits and motors are left to Box2D). Revolute: the anchor points move together (2 rows);
// prismatic: no motion across the axis and no relative turn (2 rows); weld: all three.
Eigen::MatrixXd World::jointJacobian(const DofMap& dofs) const {
  auto involved = [&](size_t j) {
    const int a = findBody(scene_.joints[j].bodyA), b = findBody(scene_.joints[j].bodyB);
    return (a >= 0 && dofs.ofBody[a] >= 0) || (b >= 0 && dofs.ofBody[b] >= 0);
  };
  int count = 0;
  for (size_t j = 0; j < scene_.joints.size(); ++j)
    if (involved(j)) count += scene_.joints[j].kind == JointDef::Kind::Weld ? 3 : 2;
  const int n = dofs.size();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(count, n);
  int row = 0;
  for (size_t j = 0; j < scene_.joints.size(); ++j) {
    if (!involved(j)) continue;
    const int a = findBody(scene_.joints[j].bodyA), b = findBody(scene_.joints[j].bodyB);
    const int da = a >= 0 ? dofs.ofBody[a] : -1, db = b >= 0 ? dofs.ofBody[b] : -1;
    const b2Joint* joint = b2_->joints[j];
    const Vec2 anchorB = fromB2(joint->GetAnchorB());
    const Vec2 rA = a >= 0 ? Vec2(anchorB - bodies_[a].position) : Vec2::Zero();
    const Vec2 rB = b >= 0 ? Vec2(anchorB - bodies_[b].position) : Vec2::Zero();
    // A row on the relative velocity of the anchor point along direction t.
    auto pointRow = [&](const Vec2& t) {
      if (db >= 0) C.block<1, 3>(row, db) += Eigen::RowVector3d(t.x(), t.y(), t.dot(perp(rB)));
      if (da >= 0) C.block<1, 3>(row, da) -= Eigen::RowVector3d(t.x(), t.y(), t.dot(perp(rA)));
      ++row;
    };
    auto angleRow = [&] {
      if (db >= 0) C(row, db + 2) += 1;
      if (da >= 0) C(row, da + 2) -= 1;
      ++row;
    };
    switch (scene_.joints[j].kind) {
      case JointDef::Kind::Revolute:
        pointRow(Vec2(1, 0));
        pointRow(Vec2(0, 1));
        break;
      case JointDef::Kind::Prismatic: {
        auto* pj = static_cast<const b2PrismaticJoint*>(joint);
        const double angleA = a >= 0 ? bodies_[a].angle : 0.0;
        pointRow(perp(rotate(fromB2(pj->GetLocalAxisA()), angleA)));
        angleRow();
        break;
      }
      case JointDef::Kind::Weld:
        pointRow(Vec2(1, 0));
        pointRow(Vec2(0, 1));
        angleRow();
        break;
    }
  }
  return C;
}

void World::solveCableForces(double h) {
  // 1. One row per cable that can pull on something that moves.
  std::vector<int> rows;
  DofMap dofs{std::vector<int>(bodies_.size(), -1), {}};
  for (size_t i = 0; i < cables_.size(); ++i) {
    bool moves = false;
    for (const auto& e : cables_[i].kinematics().jacobian) {
      const BodyState& b = bodies_[e.body];
      if (b.invMass > 0 || b.invInertia > 0) {
        dofs.add(e.body);
        moves = true;
      }
    }
    if (moves) rows.push_back(static_cast<int>(i));
    else cables_[i].setTension(0);
  }
  if (rows.empty()) return;
  // Bodies jointed to those the cables pull on move with them: add them (breadth first).
  for (size_t k = 0; k < dofs.body.size(); ++k)
    for (int other : jointNeighbours_[dofs.body[k]])
      if (bodies_[other].invMass > 0 || bodies_[other].invInertia > 0) dofs.add(other);
  const int m = static_cast<int>(rows.size()), n = dofs.size();

  // 2. J at the start of the step and the predicted velocity v* (gravity and loads, no cables).
  Eigen::MatrixXd J0 = Eigen::MatrixXd::Zero(m, n);
  Eigen::VectorXd vStar(n);
  const Eigen::VectorXd invM = inverseMassOf(dofs);
  for (size_t k = 0; k < dofs.body.size(); ++k) {
    const BodyState& s = bodies_[dofs.body[k]];
    Vec3 v(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    v += h * (invM.segment<3>(3 * k).cwiseProduct(forces_[dofs.body[k]]));
    if (s.invMass > 0) v.head<2>() += h * scene_.gravity;
    vStar.segment<3>(3 * k) = v;
  }
  for (int r = 0; r < m; ++r)
    for (const auto& e : cables_[rows[r]].kinematics().jacobian)
      if (dofs.ofBody[e.body] >= 0) J0.block<1, 3>(r, dofs.ofBody[e.body]) = e.d.transpose();
  const Eigen::VectorXd vFree = vStar;  // what Box2D would reach without cables and joints

  // 3. W = M'^-1 J^T projected onto what the joints allow: how tension impulses change
  // velocities. Box2D's joints act after our forces, so the cables must already see them (a
  // pulley on a pivoted body turns, it does not translate). M' adds the geometric stiffness
  // h^2 T d^2(length)/dx^2 of taut cables where it matters (a light body on a tight band turns
  // the force direction faster than one step resolves).
  std::vector<std::pair<int, std::vector<StiffnessBlock>>> hessians;  // (row, blocks) of taut cables
  bool stiff = false;
  for (int r = 0; r < m; ++r) {
    const Cable& c = cables_[rows[r]];
    const double tension = std::max(c.tension(), c.elastic() ? c.def().stiffness * std::max(0.0, c.stretch()) : 0.0);
    if (tension <= 0) continue;
    auto blocks = lengthHessianTranslation(c.path());
    for (const StiffnessBlock& blk : blocks)
      if (blk.a == blk.b && dofs.ofBody[blk.a] >= 0)
        stiff |= h * h * tension * blk.k.trace() * invM[dofs.ofBody[blk.a]] > 0.05;
    hessians.emplace_back(r, std::move(blocks));
  }
  const Eigen::MatrixXd C = jointJacobian(dofs);
  // M'^-1 X: a scaling unless the geometric stiffness couples the dofs. Immovable dofs stay put.
  Eigen::LDLT<Eigen::MatrixXd> mass;
  if (stiff) {
    Eigen::MatrixXd Mprime = Eigen::MatrixXd::Zero(n, n);
    for (const auto& [r, blocks] : hessians) {
      const Cable& c = cables_[rows[r]];
      const double tension = std::max(c.tension(), c.elastic() ? c.def().stiffness * std::max(0.0, c.stretch()) : 0.0);
      for (const StiffnessBlock& blk : blocks) {
        const int ia = dofs.ofBody[blk.a], ib = dofs.ofBody[blk.b];
        if (ia >= 0 && ib >= 0) Mprime.block<2, 2>(ia, ib) += h * h * tension * blk.k;
      }
    }
    for (int d = 0; d < n; ++d)
      if (invM[d] == 0) Mprime.row(d).setZero(), Mprime.col(d).setZero();
    for (int d = 0; d < n; ++d) Mprime(d, d) += invM[d] > 0 ? 1.0 / invM[d] : 1.0;
    mass.compute(Mprime);
  }
  auto inverseMass = [&](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
    if (!stiff) return invM.asDiagonal() * X;
    return mass.solve(invM.cwiseSign().asDiagonal() * X);
  };
  Eigen::MatrixXd W = inverseMass(J0.transpose());
  // Backward Euler on the turning force direction: (M + h^2 T G) v1 = M v* - J^T P, so the
  // stiffness also resists the motion v* already carries into the band.
  if (stiff) {
    Eigen::VectorXd momentum(n);
    for (int d = 0; d < n; ++d) momentum[d] = invM[d] > 0 ? vStar[d] / invM[d] : 0.0;
    vStar = mass.solve(momentum);
  }
  if (C.rows() > 0) {
    // Schur complement of the joint rows: W <- W - M'^-1 C^T (C M'^-1 C^T)^-1 C W, and v* made
    // joint-consistent the same way.
    const Eigen::MatrixXd MinvCt = inverseMass(C.transpose());
    Eigen::MatrixXd S = C * MinvCt;
    S.diagonal().array() += 1e-10 * (1 + S.diagonal().array());
    const Eigen::LDLT<Eigen::MatrixXd> schur(S);
    W -= MinvCt * schur.solve(C * W);
    vStar -= MinvCt * schur.solve(C * vStar);
  }

  // 4. Position-level targets. Rigid: length at the end of the step = now (the error below the
  // slop is float rounding: fixing it would amplify it by 1/h^2), a slack cable may come taut,
  // an over-long one is shortened by a share of the excess. Elastic: T = k phi1 + b (phi1 - phi0)/h.
  Eigen::VectorXd target(m), compliance = Eigen::VectorXd::Zero(m), damped = Eigen::VectorXd::Zero(m);
  for (int r = 0; r < m; ++r) {
    const Cable& c = cables_[rows[r]];
    const double phi = c.stretch();
    if (!c.elastic()) {
      target[r] = phi < -kLengthSlop ? 0.0 : phi > kLengthSlop ? phi - kBaumgarte * (phi - kLengthSlop) : phi;
    } else {
      const double stiffK = c.def().stiffness, damp = c.def().damping;
      compliance[r] = 1.0 / (h * (stiffK * h + damp));
      damped[r] = damp * phi / (stiffK * h + damp);
    }
  }

  // 5. Newton on the end-of-step lengths phi1(P) (Box2D integrates q1 = q0 + h v1), each
  // linearisation an LCP over all cables: tension >= 0, slack cables only shorten.
  Eigen::VectorXd P = Eigen::VectorXd::Zero(m), phi1(m);
  Eigen::MatrixXd J1 = Eigen::MatrixXd::Zero(m, n);
  std::vector<BodyState>& predicted = predictedScratch_;
  predicted = bodies_;
  std::vector<WrapPoint>& path = pathScratch_;
  for (int iteration = 0; iteration < kNewtonIterations; ++iteration) {
    const Eigen::VectorXd v1 = vStar - W * P;
    for (size_t k = 0; k < dofs.body.size(); ++k) {
      const BodyState& s = bodies_[dofs.body[k]];
      BodyState& p = predicted[dofs.body[k]];
      p.velocity = v1.segment<2>(3 * k);
      p.angularVelocity = v1[3 * k + 2];
      p.position = s.position + h * p.velocity;
      p.angle = s.angle + h * p.angularVelocity;
    }
    J1.setZero();
    for (int r = 0; r < m; ++r) {
      const Cable& c = cables_[rows[r]];
      path.assign(c.path().begin(), c.path().end());
      const CableKinematics k = cableKinematics(path, predicted);
      phi1[r] = c.stretch() + k.length - c.length();
      for (const auto& e : k.jacobian)
        if (dofs.ofBody[e.body] >= 0) J1.block<1, 3>(r, dofs.ofBody[e.body]) = e.d.transpose();
    }
    const Eigen::MatrixXd JW = J1 * W;
    Eigen::MatrixXd K = JW;
    K.diagonal() += compliance;
    Eigen::VectorXd b = JW * P;
    for (int r = 0; r < m; ++r)
      b[r] += (cables_[rows[r]].elastic() ? phi1[r] - damped[r] : phi1[r] - target[r]) / h;
    const LcpSolution sol = solveLcp(K, b);
    const double change = (sol.x - P).lpNorm<Eigen::Infinity>();
    P = sol.x;
    stats_.solverIterations += sol.iterations;
    stats_.residual = std::max(stats_.residual, sol.residual);
    // The end-of-step geometry is nearly linear in P: stop once the impulses have settled.
    if (iteration > 0 && change <= 1e-9 * (1e-9 + P.lpNorm<Eigen::Infinity>())) break;
  }
  for (int r = 0; r < m; ++r) cables_[rows[r]].setTension(P[r] / h);

  // 6. Box2D integrates v += h M^-1 F: the force that gives the end-of-step velocity we solved
  // for (cable pull, geometric stiffness and joint reactions together).
  const Eigen::VectorXd dv = vStar - W * P - vFree;
  for (size_t k = 0; k < dofs.body.size(); ++k)
    for (int c = 0; c < 3; ++c)
      if (invM[3 * k + c] > 0) forces_[dofs.body[k]][c] += dv[3 * k + c] / (h * invM[3 * k + c]);
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
