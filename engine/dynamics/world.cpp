// The Box2D bridge. Box2D is float; everything cablelab computes is double, converted here.
#include "engine/dynamics/world.h"

#include <box2d/box2d.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/dynamics/tension_solver.h"

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

b2Vec2 toB2(const Vec2& v) {
  return b2Vec2(static_cast<float>(v.x()), static_cast<float>(v.y()));
}
Vec2 fromB2(const b2Vec2& v) {
  return Vec2(v.x, v.y);
}

b2BodyType toB2(BodyType t) {
  switch (t) {
    case BodyType::Static:
      return b2_staticBody;
    case BodyType::Kinematic:
      return b2_kinematicBody;
    case BodyType::Dynamic:
      return b2_dynamicBody;
  }
  return b2_dynamicBody;
}

// A joint's coordinate (angle or translation) and its rate; 0 for welds.
struct JointCoordinate {
  double value = 0, speed = 0;
};

JointCoordinate jointCoordinate(const b2Joint* j, JointDef::Kind kind) {
  JointCoordinate q;
  if (kind == JointDef::Kind::Revolute) {
    auto* r = static_cast<const b2RevoluteJoint*>(j);
    q.value = r->GetJointAngle();
    q.speed = r->GetJointSpeed();
  } else if (kind == JointDef::Kind::Prismatic) {
    auto* p = static_cast<const b2PrismaticJoint*>(j);
    q.value = p->GetJointTranslation();
    q.speed = p->GetJointSpeed();
  }
  return q;
}

}  // namespace

struct World::Box2D {
  b2World world{b2Vec2(0, 0)};
  b2Body* ground = nullptr;
  std::vector<b2Body*> bodies;
  std::vector<b2Joint*> joints;
  b2MouseJoint* mouse = nullptr;
};

// Generalized coordinates of the bodies the cables move: 3 per moving body.
struct World::DofMap {
  std::vector<int> ofBody;  // body -> first dof, -1 if the body does not move
  std::vector<int> body;    // dof / 3 -> body
  int size() const { return 3 * static_cast<int>(body.size()); }
  void reset(size_t bodies) {
    ofBody.assign(bodies, -1);
    body.clear();
  }
  int add(int b) {
    if (ofBody[b] < 0) {
      ofBody[b] = size();
      body.push_back(b);
    }
    return ofBody[b];
  }
};

namespace {

// One row of the joint Jacobian C: the relative motion of at most two bodies (dof -1: none).
// C has n columns but only 2-6 non-zeros per row, so products with C go through these.
struct JointRow {
  std::array<int, 2> dof{-1, -1};
  std::array<Vec3, 2> coeff{Vec3::Zero(), Vec3::Zero()};

  // This row times the dense column x.
  double dot(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    double sum = 0;
    for (int k = 0; k < 2; ++k)
      if (dof[k] >= 0) sum += coeff[k].dot(x.segment<3>(dof[k]));
    return sum;
  }
};

}  // namespace

// The buffers of solveCableForces. They live as long as the World so that a sub-step does not
// allocate: after the first step every size has been seen and Eigen reuses the storage.
struct World::CableWorkspace {
  DofMap dofs;
  std::vector<int> rows;         // cable of each LCP row
  Eigen::VectorXd invM;          // M^-1 diagonal over the dofs
  Eigen::VectorXd vStar, vFree;  // predicted velocities (see step 2)
  Eigen::MatrixXd W;             // M'^-1 J^T, then projected onto the joints (n x m)

  // Geometric stiffness of the taut cables: their Hessian blocks, blocks[begin, end).
  struct TautCable {
    double tension;
    size_t begin, end;
  };
  std::vector<TautCable> taut;
  std::vector<StiffnessBlock> blocks;
  bool stiff = false;
  // M' = M + h^2 T G. G only couples the translations of bodies on stiff cables: those dofs
  // ("coupled") get a small dense LDLT, the others a division by their diagonal.
  std::vector<int> coupledIndex;  // dof -> row of coupledMass, -1: diagonal
  std::vector<int> coupledDofs;
  Eigen::VectorXd massDiagonal;
  Eigen::MatrixXd coupledMass;
  Eigen::LDLT<Eigen::MatrixXd> coupledLdlt;
  Eigen::VectorXd coupledRhs, coupledSolution;

  // Joint rows and the Schur complement S = C M'^-1 C^T.
  std::vector<JointRow> joints;
  Eigen::MatrixXd MinvCt, S, CW, schurCW, correction;
  Eigen::VectorXd Cv, schurCv, velocityCorrection;
  Eigen::LDLT<Eigen::MatrixXd> schur;

  // Newton on the end-of-step lengths.
  Eigen::VectorXd target, compliance, damped, P, phi1, b, WP, v1;
  Eigen::MatrixXd JW, K, JW0;
  std::vector<BodyState> predicted;
  std::vector<WrapPoint> path;
  CableKinematics kin;
  LcpWorkspace lcp;
  LcpSolution lcpSolution;

  void factorStiffMass(double h);
  void applyInverseMass(Eigen::Ref<Eigen::MatrixXd> X);
  void projectOntoJoints();
};

// Builds M' over the coupled dofs and factors it; immovable dofs (M^-1 = 0) stay put.
void World::CableWorkspace::factorStiffMass(double h) {
  const int n = dofs.size();
  coupledIndex.assign(n, -1);
  coupledDofs.clear();
  auto couple = [&](int d) {
    if (invM[d] > 0 && coupledIndex[d] < 0) {
      coupledIndex[d] = static_cast<int>(coupledDofs.size());
      coupledDofs.push_back(d);
    }
  };
  for (const TautCable& t : taut)
    for (size_t i = t.begin; i < t.end; ++i) {
      const int ia = dofs.ofBody[blocks[i].a], ib = dofs.ofBody[blocks[i].b];
      if (ia < 0 || ib < 0) continue;
      for (int c = 0; c < 2; ++c) couple(ia + c), couple(ib + c);
    }
  const int nc = static_cast<int>(coupledDofs.size());
  coupledMass.setZero(nc, nc);
  for (const TautCable& t : taut) {
    const double scale = h * h * t.tension;
    for (size_t i = t.begin; i < t.end; ++i) {
      const int ia = dofs.ofBody[blocks[i].a], ib = dofs.ofBody[blocks[i].b];
      if (ia < 0 || ib < 0) continue;
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
          const int cr = coupledIndex[ia + r], cc = coupledIndex[ib + c];
          if (cr >= 0 && cc >= 0) coupledMass(cr, cc) += scale * blocks[i].k(r, c);
        }
    }
  }
  massDiagonal.resize(n);
  for (int d = 0; d < n; ++d) {
    const double m = invM[d] > 0 ? 1.0 / invM[d] : 1.0;
    if (coupledIndex[d] >= 0) coupledMass(coupledIndex[d], coupledIndex[d]) += m;
    massDiagonal[d] = m;
  }
  if (nc > 0) coupledLdlt.compute(coupledMass);
}

// X <- M'^-1 X: a scaling unless the geometric stiffness couples the dofs.
void World::CableWorkspace::applyInverseMass(Eigen::Ref<Eigen::MatrixXd> X) {
  const int n = dofs.size();
  if (!stiff) {
    for (int d = 0; d < n; ++d) X.row(d) *= invM[d];
    return;
  }
  for (int d = 0; d < n; ++d) {
    if (invM[d] == 0) X.row(d).setZero();  // immovable: no motion whatever the load
    if (coupledIndex[d] < 0) X.row(d) /= massDiagonal[d];
  }
  const int nc = static_cast<int>(coupledDofs.size());
  if (nc == 0) return;
  coupledRhs.resize(nc);
  coupledSolution.resize(nc);
  for (Eigen::Index col = 0; col < X.cols(); ++col) {
    for (int i = 0; i < nc; ++i) coupledRhs[i] = X(coupledDofs[i], col);
    coupledSolution = coupledLdlt.solve(coupledRhs);
    for (int i = 0; i < nc; ++i) X(coupledDofs[i], col) = coupledSolution[i];
  }
}

// Schur complement of the joint rows: W <- W - M'^-1 C^T S^-1 C W, and v* made
// joint-consistent the same way (S = C M'^-1 C^T).
void World::CableWorkspace::projectOntoJoints() {
  const int n = dofs.size(), c = static_cast<int>(joints.size()), m = static_cast<int>(W.cols());
  MinvCt.setZero(n, c);
  for (int r = 0; r < c; ++r)
    for (int k = 0; k < 2; ++k)
      if (joints[r].dof[k] >= 0) MinvCt.block<3, 1>(joints[r].dof[k], r) += joints[r].coeff[k];
  applyInverseMass(MinvCt);
  // S is symmetric and the LDLT reads its lower triangle only.
  S.resize(c, c);
  for (int r = 0; r < c; ++r)
    for (int s = 0; s <= r; ++s) S(r, s) = joints[r].dot(MinvCt.col(s));
  S.diagonal().array() += 1e-10 * (1 + S.diagonal().array());
  schur.compute(S);

  // A few columns (one per cable, then v*): column by column is cheaper than the blocked solve.
  CW.resize(c, m);
  schurCW.resize(c, m);
  for (int s = 0; s < m; ++s) {
    for (int r = 0; r < c; ++r) CW(r, s) = joints[r].dot(W.col(s));
    schurCW.col(s) = schur.solve(CW.col(s));
  }
  correction.noalias() = MinvCt.lazyProduct(schurCW);
  W -= correction;

  Cv.resize(c);
  for (int r = 0; r < c; ++r) Cv[r] = joints[r].dot(vStar);
  schurCv = schur.solve(Cv);
  velocityCorrection.noalias() = MinvCt * schurCv;
  vStar -= velocityCorrection;
}

World::World(SceneDef scene, const std::string& source)
    : scene_(std::move(scene)), b2_(std::make_unique<Box2D>()) {
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
    jointBodies_.push_back({a, b});
    if (a >= 0 && b >= 0) jointNeighbours_[a].push_back(b), jointNeighbours_[b].push_back(a);
  }
  work_ = std::make_unique<CableWorkspace>();
  for (int i = 0; i < static_cast<int>(scene_.cables.size()); ++i)
    cables_.emplace_back(scene_, i, source);
  readBodies();
  for (size_t i = 0; i < cables_.size(); ++i) {
    cables_[i].update(bodies_, &warnings_);
    if (cables_[i].length() < 1e-9)
      throw InputError(source, "cables[" + std::to_string(i) + "]",
                       "zero-length cable: its ends coincide at the initial pose");
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
    s.invInertia =
        dynamic && !b->IsFixedRotation() && b->GetInertia() > 0 ? 1.0 / b->GetInertia() : 0.0;
  }
}

void World::setBodyTransform(int i, const Vec2& position, double angle) {
  b2_->bodies[i]->SetTransform(toB2(position), static_cast<float>(angle));
  readBodies();
}

void World::refreshCables() {
  readBodies();
  for (Cable& c : cables_) {
    c.update(bodies_, &warnings_);
    c.refresh(bodies_);
  }
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
  b2LinearStiffness(def.stiffness, def.damping, static_cast<float>(stiffnessHz), 0.7f, def.bodyA,
                    def.bodyB);
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

void World::setCableParameters(int i, double restLength, double stiffness, double preload,
                               double damping) {
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
  def.restLength = restLength, def.stiffness = stiffness, def.preload = preload,
  def.damping = damping;
}

JointState World::joint(int i) const {
  const JointDef& def = scene_.joints[i];
  const b2Joint* j = b2_->joints[i];
  JointState s{def.name, def.kind, fromB2(j->GetAnchorA()), fromB2(j->GetAnchorB())};
  const JointCoordinate q = jointCoordinate(j, def.kind);
  s.value = q.value;
  s.speed = q.speed;
  s.servoTarget = def.servo.target;
  return s;
}

void World::setServoTarget(int i, double target) {
  scene_.joints[i].servo.target = target;
}

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
    b2Joint* j = b2_->joints[i];
    const JointCoordinate q = jointCoordinate(j, scene_.joints[i].kind);
    const double f = std::clamp(servo.kp * (servo.target - q.value) - servo.kd * q.speed,
                                -servo.maxForce, servo.maxForce);
    const auto [a, b] = jointBodies_[i];
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

void World::inverseMassOf(CableWorkspace& ws) const {
  ws.invM.resize(ws.dofs.size());
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const BodyState& s = bodies_[ws.dofs.body[k]];
    ws.invM.segment<3>(3 * k) = Vec3(s.invMass, s.invMass, s.invInertia);
  }
}

// Velocity-level Jacobian of the Box2D joints among the dofs (rows: constrained relative motions;
// limits and motors are left to Box2D). Revolute: the anchor points move together (2 rows);
// prismatic: no motion across the axis and no relative turn (2 rows); weld: all three.
void World::jointJacobian(CableWorkspace& ws) const {
  const DofMap& dofs = ws.dofs;
  ws.joints.clear();
  for (size_t j = 0; j < scene_.joints.size(); ++j) {
    const auto [a, b] = jointBodies_[j];
    const int da = a >= 0 ? dofs.ofBody[a] : -1, db = b >= 0 ? dofs.ofBody[b] : -1;
    if (da < 0 && db < 0) continue;
    const b2Joint* joint = b2_->joints[j];
    const Vec2 anchorB = fromB2(joint->GetAnchorB());
    const Vec2 rA = a >= 0 ? Vec2(anchorB - bodies_[a].position) : Vec2::Zero();
    const Vec2 rB = b >= 0 ? Vec2(anchorB - bodies_[b].position) : Vec2::Zero();
    // A row on the relative velocity of the anchor point along direction t.
    auto pointRow = [&](const Vec2& t) {
      JointRow row;
      row.dof = {db, da};
      row.coeff = {Vec3(t.x(), t.y(), t.dot(perp(rB))), -Vec3(t.x(), t.y(), t.dot(perp(rA)))};
      ws.joints.push_back(row);
    };
    auto angleRow = [&] {
      JointRow row;
      row.dof = {db, da};
      row.coeff = {Vec3(0, 0, 1), Vec3(0, 0, -1)};
      ws.joints.push_back(row);
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
}

void World::solveCableForces(double h) {
  CableWorkspace& ws = *work_;
  DofMap& dofs = ws.dofs;
  std::vector<int>& rows = ws.rows;

  // 1. One row per cable that can pull on something that moves.
  rows.clear();
  dofs.reset(bodies_.size());
  for (size_t i = 0; i < cables_.size(); ++i) {
    bool moves = false;
    for (const auto& e : cables_[i].kinematics().jacobian) {
      const BodyState& b = bodies_[e.body];
      if (b.invMass > 0 || b.invInertia > 0) {
        dofs.add(e.body);
        moves = true;
      }
    }
    if (moves)
      rows.push_back(static_cast<int>(i));
    else
      cables_[i].setTension(0);
  }
  if (rows.empty()) return;
  // Bodies jointed to those the cables pull on move with them: add them (breadth first).
  for (size_t k = 0; k < dofs.body.size(); ++k)
    for (int other : jointNeighbours_[dofs.body[k]])
      if (bodies_[other].invMass > 0 || bodies_[other].invInertia > 0) dofs.add(other);
  const int m = static_cast<int>(rows.size()), n = dofs.size();

  // 2. The predicted velocity v* (gravity and loads, no cables) and J at the start of the step,
  // stored transposed in W (it becomes M'^-1 J^T below).
  inverseMassOf(ws);
  const Eigen::VectorXd& invM = ws.invM;
  Eigen::VectorXd& vStar = ws.vStar;
  vStar.resize(n);
  for (size_t k = 0; k < dofs.body.size(); ++k) {
    const BodyState& s = bodies_[dofs.body[k]];
    Vec3 v(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    v += h * (invM.segment<3>(3 * k).cwiseProduct(forces_[dofs.body[k]]));
    if (s.invMass > 0) v.head<2>() += h * scene_.gravity;
    vStar.segment<3>(3 * k) = v;
  }
  Eigen::MatrixXd& W = ws.W;
  W.setZero(n, m);
  for (int r = 0; r < m; ++r)
    for (const auto& e : cables_[rows[r]].kinematics().jacobian)
      if (dofs.ofBody[e.body] >= 0) W.block<3, 1>(dofs.ofBody[e.body], r) = e.d;
  ws.vFree = vStar;  // what Box2D would reach without cables and joints

  // 3. W = M'^-1 J^T projected onto what the joints allow: how tension impulses change
  // velocities. Box2D's joints act after our forces, so the cables must already see them (a
  // pulley on a pivoted body turns, it does not translate). M' adds the geometric stiffness
  // h^2 T d^2(length)/dx^2 of taut cables where it matters (a light body on a tight band turns
  // the force direction faster than one step resolves).
  ws.taut.clear();
  ws.blocks.clear();
  ws.stiff = false;
  for (int r = 0; r < m; ++r) {
    const Cable& c = cables_[rows[r]];
    const double tension =
        std::max(c.tension(), c.elastic() ? c.def().stiffness * std::max(0.0, c.stretch()) : 0.0);
    if (tension <= 0) continue;
    const size_t begin = ws.blocks.size();
    appendLengthHessianTranslation(c.path(), ws.blocks);
    for (size_t i = begin; i < ws.blocks.size(); ++i) {
      const StiffnessBlock& blk = ws.blocks[i];
      if (blk.a == blk.b && dofs.ofBody[blk.a] >= 0)
        ws.stiff |= h * h * tension * blk.k.trace() * invM[dofs.ofBody[blk.a]] > 0.05;
    }
    ws.taut.push_back({tension, begin, ws.blocks.size()});
  }
  jointJacobian(ws);
  if (ws.stiff) ws.factorStiffMass(h);
  ws.applyInverseMass(W);
  // Backward Euler on the turning force direction: (M + h^2 T G) v1 = M v* - J^T P, so the
  // stiffness also resists the motion v* already carries into the band.
  if (ws.stiff) {
    for (int d = 0; d < n; ++d) vStar[d] = invM[d] > 0 ? vStar[d] / invM[d] : 0.0;
    ws.applyInverseMass(vStar);
  }
  if (!ws.joints.empty()) ws.projectOntoJoints();

  // 4. Position-level targets. Rigid: length at the end of the step = now (the error below the
  // slop is float rounding: fixing it would amplify it by 1/h^2), a slack cable may come taut,
  // an over-long one is shortened by a share of the excess. Elastic: T = k phi1 + b (phi1 -
  // phi0)/h.
  Eigen::VectorXd &target = ws.target, &compliance = ws.compliance, &damped = ws.damped;
  target.resize(m);
  compliance.setZero(m);
  damped.setZero(m);
  for (int r = 0; r < m; ++r) {
    const Cable& c = cables_[rows[r]];
    const double phi = c.stretch();
    if (!c.elastic()) {
      target[r] = phi < -kLengthSlop  ? 0.0
                  : phi > kLengthSlop ? phi - kBaumgarte * (phi - kLengthSlop)
                                      : phi;
    } else {
      const double stiffK = c.def().stiffness, damp = c.def().damping;
      compliance[r] = 1.0 / (h * (stiffK * h + damp));
      damped[r] = damp * phi / (stiffK * h + damp);
    }
  }

  // 5. Newton on the end-of-step lengths phi1(P) (Box2D integrates q1 = q0 + h v1), each
  // linearisation an LCP over all cables: tension >= 0, slack cables only shorten.
  Eigen::VectorXd &P = ws.P, &phi1 = ws.phi1, &v1 = ws.v1, &b = ws.b;
  Eigen::MatrixXd &JW = ws.JW, &K = ws.K;
  P.setZero(m);
  phi1.resize(m);
  JW.resize(m, m);
  std::vector<BodyState>& predicted = ws.predicted;
  predicted = bodies_;
  // J0 W from the start-of-step Jacobians (positive semidefinite), for the guard below.
  Eigen::MatrixXd& JW0 = ws.JW0;
  JW0.setZero(m, m);
  for (int r = 0; r < m; ++r)
    for (const auto& e : cables_[rows[r]].kinematics().jacobian)
      if (const int d = dofs.ofBody[e.body]; d >= 0)
        JW0.row(r) += e.d.transpose() * W.middleRows<3>(d);
  for (int iteration = 0; iteration < kNewtonIterations; ++iteration) {
    ws.WP.noalias() = W * P;
    v1 = vStar - ws.WP;
    for (size_t k = 0; k < dofs.body.size(); ++k) {
      const BodyState& s = bodies_[dofs.body[k]];
      BodyState& p = predicted[dofs.body[k]];
      p.velocity = v1.segment<2>(3 * k);
      p.angularVelocity = v1[3 * k + 2];
      p.position = s.position + h * p.velocity;
      p.angle = s.angle + h * p.angularVelocity;
    }
    // JW = J1 W straight from the sparse J1 (a cable touches a few of the n dofs).
    for (int r = 0; r < m; ++r) {
      const Cable& c = cables_[rows[r]];
      ws.path.assign(c.path().begin(), c.path().end());
      cableKinematics(ws.path, predicted, ws.kin);
      phi1[r] = c.stretch() + ws.kin.length - c.length();
      JW.row(r).setZero();
      for (const auto& e : ws.kin.jacobian)
        if (const int d = dofs.ofBody[e.body]; d >= 0)
          JW.row(r) += e.d.transpose() * W.middleRows<3>(d);
    }
    // Guard (degenerate geometry): far from the start pose the end-of-step linearisation can lose
    // positive definiteness (a wrap point the predicted motion carries past its neighbour turns a
    // row's J1 against its J0: K_ii <= 0), and the LCP then answers with impulses of 1e6 N s.
    // Such a row falls back to the start-of-step Jacobian, whose J0 W is positive semidefinite.
    for (int r = 0; r < m; ++r)
      if (!(JW(r, r) > 1e-3 * JW0(r, r))) {
        JW.row(r) = JW0.row(r);
        ++stats_.linearisationFallbacks;
      }
    K = JW;
    K.diagonal() += compliance;
    b.noalias() = JW * P;
    for (int r = 0; r < m; ++r)
      b[r] += (cables_[rows[r]].elastic() ? phi1[r] - damped[r] : phi1[r] - target[r]) / h;
    LcpSolution& sol = ws.lcpSolution;
    solveLcp(K, b, ws.lcp, sol);
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
  ws.WP.noalias() = W * P;
  for (size_t k = 0; k < dofs.body.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const int d = 3 * static_cast<int>(k) + c;
      const double dv = vStar[d] - ws.WP[d] - ws.vFree[d];
      if (invM[d] > 0) forces_[dofs.body[k]][c] += dv / (h * invM[d]);
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
