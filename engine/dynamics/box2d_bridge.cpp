// The Box2D bridge. Box2D is float; everything cablelab computes is double, converted here.
#include "engine/dynamics/box2d_bridge.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/dynamics/floors.h"
#include "engine/dynamics/hull_bounce.h"
#include "engine/dynamics/hull_contacts.h"
#include "engine/dynamics/pulley_knock.h"

namespace cablelab {

namespace {

constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;
/// Of its sub-step: a piece shorter than this is cut at a wrap event or a knock (world.cpp), its
/// contacts' impulses mostly a knock's, not a force held over it.
constexpr double kKnockPiece = 0.1;

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

void addShape(b2Body* body, const ShapeDef& sd) {
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

b2Body* createBody(b2World& w, const BodyDef& bd) {
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
  for (const ShapeDef& sd : bd.shapes) addShape(body, sd);
  if (bd.type == BodyType::Dynamic) {
    // The centre of mass is the body origin by definition, so the mass matrix is diagonal in
    // (x, y, theta) (docs/model.md). Inertia defaults to the shapes' at uniform density.
    const double shapeMass = body->GetMass();
    double inertia = bd.inertia;
    if (inertia <= 0) inertia = shapeMass > 0 ? body->GetInertia() * bd.mass / shapeMass : 0;
    if (inertia <= 0) inertia = 0.5 * bd.mass * 0.01;  // shapeless: a 0.1 m disc
    b2MassData md{static_cast<float>(bd.mass), b2Vec2(0, 0), static_cast<float>(inertia)};
    body->SetMassData(&md);
  }
  return body;
}

b2Joint* createJoint(b2World& w, const JointDef& jd, b2Body* a, b2Body* b) {
  switch (jd.kind) {
    case JointDef::Kind::Revolute: {
      b2RevoluteJointDef def;
      def.Initialize(a, b, toB2(jd.anchor));
      // The coordinate reads jd.value at the scene's pose (scene.h, JointDef::value).
      def.referenceAngle -= static_cast<float>(jd.value);
      def.enableLimit = jd.enableLimit;
      def.lowerAngle = static_cast<float>(jd.lower);
      def.upperAngle = static_cast<float>(jd.upper);
      def.collideConnected = jd.collideConnected;
      return w.CreateJoint(&def);
    }
    case JointDef::Kind::Prismatic: {
      b2PrismaticJointDef def;
      const Vec2 axis = jd.axis.normalized();
      def.Initialize(a, b, toB2(jd.anchor), toB2(axis));
      // The slide reads jd.value at the scene's pose: A's anchor sits that far back on the axis.
      if (jd.value != 0) def.localAnchorA = a->GetLocalPoint(toB2(jd.anchor - jd.value * axis));
      def.enableLimit = jd.enableLimit;
      def.lowerTranslation = static_cast<float>(jd.lower);
      def.upperTranslation = static_cast<float>(jd.upper);
      def.collideConnected = jd.collideConnected;
      return w.CreateJoint(&def);
    }
    case JointDef::Kind::Weld: {
      b2WeldJointDef def;
      def.Initialize(a, b, toB2(jd.anchor));
      def.collideConnected = jd.collideConnected;
      return w.CreateJoint(&def);
    }
  }
  return nullptr;
}

}  // namespace

// Sums the impulses Box2D's contact solver gives each body over a step (PostSolve reports each
// touching contact once per solve, TOI sub-steps included), as (px, py, angular) about the body's
// origin, the same frame as the loads.
struct ContactImpulses : b2ContactListener {
  std::vector<Vec3> perBody;
  /// Fixture pairs that do not touch yet (hull_contacts.h's apartFirst), each as (A, B) and
  /// (B, A): their contacts are switched off for the step.
  const std::vector<std::pair<b2Fixture*, b2Fixture*>>* untilApart = nullptr;
  /// A polygon pulley held still and a point on a moving body (hull_contacts.h), each as
  /// (polygon, point).
  std::vector<std::pair<b2Fixture*, b2Fixture*>> heldStill;
  float h = 0;  ///< the step's length (s)
  void PreSolve(b2Contact* contact, const b2Manifold*) override {
    const auto pair = std::make_pair(contact->GetFixtureA(), contact->GetFixtureB());
    if (!untilApart->empty() &&
        std::find(untilApart->begin(), untilApart->end(), pair) != untilApart->end())
      contact->SetEnabled(false);
    for (const auto& [polygon, point] : heldStill)
      if ((pair.first == polygon && pair.second == point) ||
          (pair.first == point && pair.second == polygon)) {
        if (ridesAFace(polygon, point)) contact->SetEnabled(false);
        return;
      }
  }
  /// Whether `point`'s centre lies on the line of one of `polygon`'s faces (within 0.1 mm) and the
  /// step keeps it there: a weight hauled up the face its rope hugs passes the corners it meets, up
  /// to the one its rope leaves from, where the rope's floor stops it (docs/knocks.md, "Wound up
  /// onto a peg").
  bool ridesAFace(const b2Fixture* polygon, const b2Fixture* point) const {
    const b2Body* still = polygon->GetBody();
    const b2Body* moving = point->GetBody();
    const auto* circle = static_cast<const b2CircleShape*>(point->GetShape());
    const b2Vec2 at = moving->GetWorldPoint(circle->m_p);
    const b2Vec2 velocity =
        moving->GetLinearVelocityFromWorldPoint(at) - still->GetLinearVelocityFromWorldPoint(at);
    const b2Vec2 now = still->GetLocalPoint(at), next = still->GetLocalPoint(at + h * velocity);
    const auto* hull = static_cast<const b2PolygonShape*>(polygon->GetShape());
    constexpr float kOnTheLine = 1e-4f;  // m
    for (int32 i = 0; i < hull->m_count; ++i)
      if (std::abs(b2Dot(hull->m_normals[i], now - hull->m_vertices[i])) <= kOnTheLine &&
          std::abs(b2Dot(hull->m_normals[i], next - hull->m_vertices[i])) <= kOnTheLine)
        return true;
    return false;
  }
  void PostSolve(b2Contact* contact, const b2ContactImpulse* impulse) override {
    b2WorldManifold m;
    contact->GetWorldManifold(&m);
    const b2Vec2 tangent = b2Cross(m.normal, 1.0f);
    for (int i = 0; i < impulse->count; ++i) {
      const b2Vec2 p =
          impulse->normalImpulses[i] * m.normal + impulse->tangentImpulses[i] * tangent;
      add(contact->GetFixtureA()->GetBody(), -p, m.points[i]);
      add(contact->GetFixtureB()->GetBody(), p, m.points[i]);
    }
  }
  void add(b2Body* body, const b2Vec2& p, const b2Vec2& at) {
    const uintptr_t index = body->GetUserData().pointer;  // body index + 1, 0: ground
    if (index == 0 || index > perBody.size()) return;
    const b2Vec2 r = at - body->GetPosition();
    perBody[index - 1] += Vec3(p.x, p.y, b2Cross(r, p));
  }
};

// Named, not anonymous: Box2DBridge::Impl (external linkage) holds a HullContactFilter.
namespace hull_fixtures {

// The fixtures that keep a polygon pulley and its neighbours apart (hull_contacts.h) touch only
// their own partners; every other pair keeps Box2D's filtering.
constexpr uintptr_t kHullFixture = 1;  // a fixture's user data: one of hull_contacts.h's

struct HullContactFilter : b2ContactFilter {
  std::vector<std::pair<b2Fixture*, b2Fixture*>> pairs;
  /// The pairs placed overlapping, both ways round, until a step starts with them apart.
  std::vector<std::pair<b2Fixture*, b2Fixture*>> untilApart;
  void keepApartOnceApart() {
    std::erase_if(untilApart, [](const std::pair<b2Fixture*, b2Fixture*>& pair) {
      for (b2ContactEdge* e = pair.first->GetBody()->GetContactList(); e; e = e->next) {
        const b2Contact* c = e->contact;
        if (c->GetFixtureA() == pair.first && c->GetFixtureB() == pair.second)
          return !c->IsTouching();
        if (c->GetFixtureA() == pair.second && c->GetFixtureB() == pair.first)
          return !c->IsTouching();
      }
      return true;  // no contact: their boxes do not even overlap
    });
  }
  bool ShouldCollide(b2Fixture* a, b2Fixture* b) override {
    const bool hullA = a->GetUserData().pointer == kHullFixture;
    const bool hullB = b->GetUserData().pointer == kHullFixture;
    if (!hullA && !hullB) return b2ContactFilter::ShouldCollide(a, b);
    return std::find(pairs.begin(), pairs.end(), std::make_pair(a, b)) != pairs.end() ||
           std::find(pairs.begin(), pairs.end(), std::make_pair(b, a)) != pairs.end();
  }
};

// A smooth, massless fixture (density 0 leaves the body's mass as set) of a hull contact: the
// polygon, or a point as a circle of Box2D's slop. It bounces with the largest restitution of the
// body's own shapes, sensors too (docs/scene-format.md), as the body does off its pulley: two
// pulleys that exist to carry the rope knock as their shapes say, not always dead.
b2Fixture* addHullFixture(b2Body* body, const std::vector<Vec2>& polygon, const Vec2& point,
                          double restitution) {
  b2FixtureDef fd;
  b2CircleShape circle;
  b2PolygonShape hull;
  if (polygon.empty()) {
    circle.m_radius = b2_linearSlop;
    circle.m_p = toB2(point);
    fd.shape = &circle;
  } else {
    std::vector<b2Vec2> v;
    for (const Vec2& p : polygon) v.push_back(toB2(p));
    hull.Set(v.data(), static_cast<int32>(v.size()));
    fd.shape = &hull;
  }
  fd.density = 0;
  fd.friction = 0;
  fd.restitution = static_cast<float>(restitution);
  fd.restitutionThreshold = static_cast<float>(kSlowestBounce);
  fd.userData.pointer = kHullFixture;
  return body->CreateFixture(&fd);
}

}  // namespace hull_fixtures

struct Box2DBridge::Impl {
  b2World world{b2Vec2(0, 0)};
  ContactImpulses contacts;
  hull_fixtures::HullContactFilter hullFilter;
  std::unique_ptr<HullBounce> bounce;
  std::unique_ptr<PulleyKnock> knock;
  b2Body* ground = nullptr;
  double lastStep = 0;           ///< the last step()'s h (s)
  std::vector<Vec3> impulseSum;  ///< contacts.perBody summed since restartContactSum()
  double sumTime = 0;            ///< the steps' time in impulseSum (s)
  std::vector<b2Body*> bodies;
  std::vector<b2Joint*> joints;
  std::vector<JointDef::Kind> kinds;
  b2MouseJoint* mouse = nullptr;
  /// Whole turns (2 pi k, rad) taken out of each body's Box2D angle, and whether it may be:
  /// Box2D integrates the angle in float, so a body spinning for minutes would hold it to ever
  /// fewer digits (0.5 mrad per step past 4096 rad) and its cable points would jitter by that
  /// (docs/model.md, "Coupling to Box2D"). Only bodies whose joints ignore the angle may be
  /// rewound: revolute joints without a limit (the offsets go back into their coordinate).
  std::vector<double> turns;
  std::vector<char> rewinds;
  /// Per body, the part of the pose placeBody was given that Box2D's float dropped (x, y, angle),
  /// until Box2D next steps (it moves the body from its float pose).
  std::vector<Vec3> dropped;
  std::vector<std::array<int, 2>> jointBodies;  ///< body indices of each joint, -1: the world
  void rewind();
  /// A joint's coordinate (rad or m, the turns taken out put back; 0 for welds).
  double jointValue(int joint) const;
};

// Keeps every body that may be rewound within (-pi, pi] in Box2D; the World sees the angle in
// full (readBodies adds the turns back).
void Box2DBridge::Impl::rewind() {
  for (size_t i = 0; i < bodies.size(); ++i) {
    b2Body* b = bodies[i];
    const float a = b->GetAngle();
    if (!rewinds[i] || std::abs(a) <= static_cast<float>(M_PI)) continue;
    const double k = std::round(a / (2 * M_PI));
    b->SetTransform(b->GetPosition(), static_cast<float>(a - 2 * M_PI * k));
    turns[i] += 2 * M_PI * k;
  }
}

Box2DBridge::Box2DBridge(const SceneDef& scene) : impl_(std::make_unique<Impl>()) {
  b2World& w = impl_->world;
  w.SetGravity(toB2(scene.gravity));
  w.SetAllowSleeping(false);
  b2BodyDef groundDef;
  impl_->ground = w.CreateBody(&groundDef);
  for (const BodyDef& bd : scene.bodies) {
    impl_->bodies.push_back(createBody(w, bd));
    impl_->bodies.back()->GetUserData().pointer = impl_->bodies.size();  // index + 1
  }
  impl_->contacts.perBody.assign(impl_->bodies.size(), Vec3::Zero());
  impl_->impulseSum.assign(impl_->bodies.size(), Vec3::Zero());
  w.SetContactListener(&impl_->contacts);
  auto bodyOf = [&](const std::string& name) {
    const int i = findBodyIndex(scene, name);
    return i < 0 ? impl_->ground : impl_->bodies[i];
  };
  for (const JointDef& jd : scene.joints) {
    impl_->joints.push_back(createJoint(w, jd, bodyOf(jd.bodyA), bodyOf(jd.bodyB)));
    impl_->kinds.push_back(jd.kind);
  }
  const std::vector<HullContact> pairs = hullContacts(scene);
  impl_->bounce = std::make_unique<HullBounce>(scene, pairs);
  impl_->knock = std::make_unique<PulleyKnock>(scene, pairs);
  for (const HullContact& c : pairs) {
    b2Body* other = c.otherBody < 0 ? impl_->ground : impl_->bodies[c.otherBody];
    b2Body* polygonBody = c.body < 0 ? impl_->ground : impl_->bodies[c.body];
    // Box2D sweeps a moving body against the world's fixtures, but against another moving body
    // only if one is a bullet: fast corners would go through a step's worth into the hull.
    if (c.otherBody >= 0 && polygonBody->GetType() == b2_dynamicBody) polygonBody->SetBullet(true);
    const auto pair =
        std::make_pair(hull_fixtures::addHullFixture(polygonBody, c.polygon, {},
                                                     largestRestitution(scene, c.body)),
                       hull_fixtures::addHullFixture(other, c.otherPolygon, c.point,
                                                     largestRestitution(scene, c.otherBody)));
    impl_->hullFilter.pairs.push_back(pair);
    if (polygonBody->GetType() != b2_dynamicBody) impl_->contacts.heldStill.push_back(pair);
    if (c.apartFirst)
      impl_->hullFilter.untilApart.insert(impl_->hullFilter.untilApart.end(),
                                          {pair, {pair.second, pair.first}});
  }
  w.SetContactFilter(&impl_->hullFilter);
  impl_->contacts.untilApart = &impl_->hullFilter.untilApart;
  impl_->turns.assign(scene.bodies.size(), 0.0);
  impl_->dropped.assign(scene.bodies.size(), Vec3::Zero());
  impl_->rewinds.assign(scene.bodies.size(), 1);
  for (const JointDef& jd : scene.joints) {
    impl_->jointBodies.push_back({findBodyIndex(scene, jd.bodyA), findBodyIndex(scene, jd.bodyB)});
    if (jd.kind != JointDef::Kind::Revolute || jd.enableLimit)
      for (const std::string& name : {jd.bodyA, jd.bodyB})
        if (const int i = findBodyIndex(scene, name); i >= 0) impl_->rewinds[i] = 0;
  }
}

Box2DBridge::~Box2DBridge() = default;

void Box2DBridge::readBodies(std::vector<BodyState>& bodies) const {
  bodies.resize(impl_->bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    const b2Body* b = impl_->bodies[i];
    BodyState& s = bodies[i];
    const Vec3& dropped = impl_->dropped[i];
    s.position = fromB2(b->GetPosition()) + dropped.head<2>();
    s.angle = b->GetAngle() + impl_->turns[i] + dropped.z();
    s.velocity = fromB2(b->GetLinearVelocity());
    s.angularVelocity = b->GetAngularVelocity();
    const bool dynamic = b->GetType() == b2_dynamicBody;
    s.invMass = dynamic && b->GetMass() > 0 ? 1.0 / b->GetMass() : 0.0;
    s.invInertia =
        dynamic && !b->IsFixedRotation() && b->GetInertia() > 0 ? 1.0 / b->GetInertia() : 0.0;
  }
}

void Box2DBridge::setTransform(int body, const Vec2& position, double angle) {
  impl_->turns[body] = 0;
  impl_->dropped[body].setZero();  // a pose set from outside is Box2D's float one
  impl_->bodies[body]->SetTransform(toB2(position), static_cast<float>(angle));
}

void Box2DBridge::placeBody(int body, const Vec2& position, double angle, bool keepDropped) {
  const double turned = angle - impl_->turns[body];
  const b2Vec2 p = toB2(position);
  const float a = static_cast<float>(turned);
  impl_->bodies[body]->SetTransform(p, a);
  impl_->dropped[body] =
      keepDropped ? Vec3(position.x() - p.x, position.y() - p.y, turned - a) : Vec3::Zero();
}

void Box2DBridge::setVelocity(int body, const Vec2& velocity, double angularVelocity) {
  impl_->bodies[body]->SetLinearVelocity(toB2(velocity));
  impl_->bodies[body]->SetAngularVelocity(static_cast<float>(angularVelocity));
}

void Box2DBridge::setGravity(const Vec2& g) {
  impl_->world.SetGravity(toB2(g));
}

void Box2DBridge::applyLoads(std::span<const Vec3> loads) {
  for (size_t b = 0; b < loads.size(); ++b) {
    if (loads[b].isZero()) continue;
    b2Body* body = impl_->bodies[b];
    body->ApplyForceToCenter(toB2(loads[b].head<2>()), false);
    body->ApplyTorque(static_cast<float>(loads[b].z()), false);
  }
}

void Box2DBridge::step(double h, double substep) {
  // Box2D warm-starts each contact with the impulse it took over the last step times h over that
  // step's length, as if a force held. After a short piece that impulse is mostly a knock's: one
  // over a 2 us piece came back 670 times over in the next 1.3 ms one, more than 8 iterations
  // take out where a light polygon lies between a point fixed in the world and a heavy polygon,
  // and the pair gained 30 times its energy scale (docs/knocks.md, "Warm-started from a short
  // piece"). There it starts with no more than it took; elsewhere Box2D's scaling stands, at most
  // 1 / kKnockPiece.
  if (impl_->lastStep > 0 && impl_->lastStep < kKnockPiece * substep && h > impl_->lastStep) {
    const float keep = static_cast<float>(impl_->lastStep) / static_cast<float>(h);
    for (b2Contact* c = impl_->world.GetContactList(); c; c = c->GetNext()) {
      b2Manifold* m = c->GetManifold();
      for (int32 i = 0; i < m->pointCount; ++i) {
        m->points[i].normalImpulse *= keep;
        m->points[i].tangentImpulse *= keep;
      }
    }
  }
  impl_->lastStep = h;
  impl_->contacts.h = static_cast<float>(h);
  std::fill(impl_->dropped.begin(), impl_->dropped.end(), Vec3::Zero());
  std::fill(impl_->contacts.perBody.begin(), impl_->contacts.perBody.end(), Vec3::Zero());
  impl_->world.Step(static_cast<float>(h), kVelocityIterations, kPositionIterations);
  for (size_t b = 0; b < impl_->impulseSum.size(); ++b)
    impl_->impulseSum[b] += impl_->contacts.perBody[b];
  impl_->sumTime += h;
  if (!impl_->hullFilter.untilApart.empty()) impl_->hullFilter.keepApartOnceApart();
  impl_->rewind();
}

void Box2DBridge::bounceHullPoints(std::vector<BodyState>& bodies, std::span<const Cable> cables,
                                   double horizon) {
  // Box2D's contact touches within the polygon's skin and the point's circle (addHullFixture),
  // two polygons within both their skins.
  const double skin = b2_polygonRadius + b2_linearSlop;
  for (const int b : impl_->bounce->bounce(bodies, horizon, skin))
    setVelocity(b, bodies[b].velocity, bodies[b].angularVelocity);
  for (const int b : impl_->knock->knock(bodies, cables, horizon, 2 * b2_polygonRadius))
    setVelocity(b, bodies[b].velocity, bodies[b].angularVelocity);
}

void Box2DBridge::addVelocities(std::span<const Vec3> dv) {
  for (size_t b = 0; b < dv.size(); ++b) {
    if (dv[b].isZero()) continue;
    b2Body* body = impl_->bodies[b];
    body->SetLinearVelocity(body->GetLinearVelocity() + toB2(dv[b].head<2>()));
    body->SetAngularVelocity(body->GetAngularVelocity() + static_cast<float>(dv[b].z()));
  }
}

std::span<const Vec3> Box2DBridge::contactImpulses() const {
  return impl_->contacts.perBody;
}

std::span<const Vec3> Box2DBridge::contactImpulseSum() const {
  return impl_->impulseSum;
}

double Box2DBridge::contactSumTime() const {
  return impl_->sumTime;
}

void Box2DBridge::restartContactSum() {
  std::fill(impl_->impulseSum.begin(), impl_->impulseSum.end(), Vec3::Zero());
  impl_->sumTime = 0;
}

std::vector<ContactForce> Box2DBridge::contactForces() const {
  std::vector<ContactForce> out;
  if (!(impl_->lastStep > 0)) return out;
  for (b2Contact* c = impl_->world.GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching() || !c->IsEnabled() || c->GetFixtureA()->IsSensor() ||
        c->GetFixtureB()->IsSensor())
      continue;
    const b2Manifold* manifold = c->GetManifold();
    b2WorldManifold m;
    c->GetWorldManifold(&m);
    const b2Vec2 tangent = b2Cross(m.normal, 1.0f);
    ContactForce f;
    f.bodyA = static_cast<int>(c->GetFixtureA()->GetBody()->GetUserData().pointer) - 1;
    f.bodyB = static_cast<int>(c->GetFixtureB()->GetBody()->GetUserData().pointer) - 1;
    f.normal = fromB2(m.normal);
    double weight = 0;
    for (int i = 0; i < manifold->pointCount; ++i) {
      const b2ManifoldPoint& p = manifold->points[i];
      f.force += fromB2(p.normalImpulse * m.normal + p.tangentImpulse * tangent);
      f.point += p.normalImpulse * fromB2(m.points[i]);
      weight += p.normalImpulse;
    }
    f.force /= impl_->lastStep;
    if (weight > 0) {
      f.point /= weight;
    } else {
      for (int i = 0; i < manifold->pointCount; ++i) f.point += fromB2(m.points[i]);
      f.point /= std::max(1, manifold->pointCount);
    }
    // One entry per pair, A the lower index (the world first).
    if (f.bodyA > f.bodyB) std::swap(f.bodyA, f.bodyB), f.force = -f.force, f.normal = -f.normal;
    auto same = [&f](const ContactForce& g) { return g.bodyA == f.bodyA && g.bodyB == f.bodyB; };
    if (auto it = std::find_if(out.begin(), out.end(), same); it != out.end()) {
      const double wa = it->force.norm(), wb = f.force.norm();
      if (wa + wb > 0) it->point = (wa * it->point + wb * f.point) / (wa + wb);
      it->force += f.force;
      it->normal = (it->normal + f.normal).normalized();
    } else {
      out.push_back(f);
    }
  }
  std::sort(out.begin(), out.end(), [](const ContactForce& a, const ContactForce& b) {
    return a.bodyA != b.bodyA ? a.bodyA < b.bodyA : a.bodyB < b.bodyB;
  });
  return out;
}

void Box2DBridge::markTouching(std::vector<char>& touching, bool leaveSeparatingKnocks) const {
  for (b2Contact* c = impl_->world.GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching() || !c->IsEnabled() || c->GetFixtureA()->IsSensor() ||
        c->GetFixtureB()->IsSensor())
      continue;
    if (leaveSeparatingKnocks && separatingKnock(c)) continue;
    for (b2Body* body : {c->GetFixtureA()->GetBody(), c->GetFixtureB()->GetBody()})
      if (const uintptr_t index = body->GetUserData().pointer;  // body index + 1, 0: ground
          index > 0 && index <= touching.size())
        touching[index - 1] = 1;
  }
}

bool Box2DBridge::separatingKnock(b2Contact* c) const {
  b2Fixture *a = c->GetFixtureA(), *b = c->GetFixtureB();
  if (a->GetUserData().pointer != hull_fixtures::kHullFixture ||
      b->GetUserData().pointer != hull_fixtures::kHullFixture)
    return false;
  b2Body *bodyA = a->GetBody(), *bodyB = b->GetBody();
  // body index + 1, 0: ground
  const int indexA = static_cast<int>(bodyA->GetUserData().pointer) - 1;
  const int indexB = static_cast<int>(bodyB->GetUserData().pointer) - 1;
  if (!impl_->knock->knocks(indexA, indexB)) return false;
  b2WorldManifold m;
  c->GetWorldManifold(&m);
  for (int i = 0; i < c->GetManifold()->pointCount; ++i) {
    const b2Vec2 relative = bodyB->GetLinearVelocityFromWorldPoint(m.points[i]) -
                            bodyA->GetLinearVelocityFromWorldPoint(m.points[i]);
    if (b2Dot(relative, m.normal) < 0) return false;
  }
  return true;
}

bool Box2DBridge::anyTouching() const {
  for (b2Contact* c = impl_->world.GetContactList(); c; c = c->GetNext())
    if (c->IsTouching() && c->IsEnabled() && !c->GetFixtureA()->IsSensor() &&
        !c->GetFixtureB()->IsSensor())
      return true;
  return false;
}

namespace {

// Box2D's GetAnchorA and GetAnchorB, GetJointAngle and GetJointTranslation written out with its
// inline accessors: the same float arithmetic without a call into the library (virtual, for the
// anchors) each, and a prismatic joint's slide from the anchors already read. jointFrames runs
// twice a sub-step over every joint.

// A joint's anchor points on its bodies A and B, in the world.
template <class Joint>
std::array<b2Vec2, 2> worldAnchors(b2Joint* j) {
  const auto* joint = static_cast<const Joint*>(j);
  return {j->GetBodyA()->GetWorldPoint(joint->GetLocalAnchorA()),
          j->GetBodyB()->GetWorldPoint(joint->GetLocalAnchorB())};
}

std::array<b2Vec2, 2> worldAnchors(b2Joint* j, JointDef::Kind kind) {
  switch (kind) {
    case JointDef::Kind::Revolute:
      return worldAnchors<b2RevoluteJoint>(j);
    case JointDef::Kind::Prismatic:
      return worldAnchors<b2PrismaticJoint>(j);
    case JointDef::Kind::Weld:
      return worldAnchors<b2WeldJoint>(j);
  }
  return {j->GetAnchorA(), j->GetAnchorB()};
}

// A revolute joint's turn, body B's relative to body A's (Box2D's float angles).
float revoluteAngle(b2Joint* j) {
  return j->GetBodyB()->GetAngle() - j->GetBodyA()->GetAngle() -
         static_cast<const b2RevoluteJoint*>(j)->GetReferenceAngle();
}

// A prismatic joint's slide along its axis, from its world anchors.
float prismaticTranslation(b2Joint* j, const std::array<b2Vec2, 2>& anchors) {
  const b2Vec2& axis = static_cast<const b2PrismaticJoint*>(j)->GetLocalAxisA();
  return b2Dot(anchors[1] - anchors[0], j->GetBodyA()->GetWorldVector(axis));
}

}  // namespace

double Box2DBridge::Impl::jointValue(int joint) const {
  b2Joint* j = joints[joint];
  auto turnsOf = [&](int body) { return body >= 0 ? turns[body] : 0.0; };
  if (kinds[joint] == JointDef::Kind::Revolute) {
    const auto [a, b] = jointBodies[joint];
    return revoluteAngle(j) + turnsOf(b) - turnsOf(a);
  }
  if (kinds[joint] == JointDef::Kind::Prismatic)
    return prismaticTranslation(j, worldAnchors<b2PrismaticJoint>(j));
  return 0;
}

JointCoordinate Box2DBridge::jointCoordinate(int joint) const {
  b2Joint* j = impl_->joints[joint];
  JointCoordinate q;
  q.value = impl_->jointValue(joint);
  if (impl_->kinds[joint] == JointDef::Kind::Revolute)  // (GetJointSpeed, written out)
    q.speed = j->GetBodyB()->GetAngularVelocity() - j->GetBodyA()->GetAngularVelocity();
  else if (impl_->kinds[joint] == JointDef::Kind::Prismatic)
    q.speed = static_cast<const b2PrismaticJoint*>(j)->GetJointSpeed();
  return q;
}

Vec2 Box2DBridge::anchorA(int joint) const {
  return fromB2(impl_->joints[joint]->GetAnchorA());
}

Vec2 Box2DBridge::anchorB(int joint) const {
  return fromB2(impl_->joints[joint]->GetAnchorB());
}

Vec2 Box2DBridge::prismaticAxis(int joint) const {
  b2Joint* j = impl_->joints[joint];
  auto* p = static_cast<const b2PrismaticJoint*>(j);
  return rotate(fromB2(p->GetLocalAxisA()), j->GetBodyA()->GetAngle());
}

void Box2DBridge::jointFrames(std::span<const JointDef> defs,
                              std::span<const std::array<int, 2>> bodies,
                              std::vector<JointFrame>& frames) const {
  frames.resize(defs.size());
  for (size_t j = 0; j < defs.size(); ++j) {
    JointFrame& f = frames[j];
    f.kind = defs[j].kind;
    f.bodyA = bodies[j][0];
    f.bodyB = bodies[j][1];
    b2Joint* joint = impl_->joints[j];
    const std::array<b2Vec2, 2> anchors = worldAnchors(joint, impl_->kinds[j]);
    f.anchor = fromB2(anchors[1]);
    f.anchorA = fromB2(anchors[0]);
    f.limited = defs[j].enableLimit && f.kind != JointDef::Kind::Weld;
    if (f.kind == JointDef::Kind::Prismatic) f.axis = prismaticAxis(static_cast<int>(j));
    if (f.limited) {
      // The coordinate only: its rate would cost more.
      f.value = f.kind == JointDef::Kind::Prismatic ? prismaticTranslation(joint, anchors)
                                                    : impl_->jointValue(static_cast<int>(j));
      f.lower = defs[j].lower;
      f.upper = defs[j].upper;
    }
  }
}

bool Box2DBridge::beginDrag(int body, const Vec2& worldPoint, double stiffnessHz, double gravity) {
  endDrag();
  b2Body* b = impl_->bodies[body];
  if (b->GetType() != b2_dynamicBody) return false;
  b2MouseJointDef def;
  def.bodyA = impl_->ground;
  def.bodyB = b;
  def.target = toB2(worldPoint);
  def.maxForce = static_cast<float>(1000.0 * b->GetMass() * std::max(9.81, gravity));
  b2LinearStiffness(def.stiffness, def.damping, static_cast<float>(stiffnessHz), 0.7f, def.bodyA,
                    def.bodyB);
  impl_->mouse = static_cast<b2MouseJoint*>(impl_->world.CreateJoint(&def));
  return true;
}

void Box2DBridge::dragTo(const Vec2& target) {
  if (impl_->mouse) impl_->mouse->SetTarget(toB2(target));
}

void Box2DBridge::endDrag() {
  if (impl_->mouse) impl_->world.DestroyJoint(impl_->mouse);
  impl_->mouse = nullptr;
}

}  // namespace cablelab

// Box2D's profile timers, in place of libbox2d's own (it calls them through its PLT, so these
// take precedence in a program that links the engine). Box2D reads the clock about seven times
// per island per step for b2World::GetProfile, which cablelab never reads: with a Box2D island per
// body (bodies held only by cables share no joint or contact) that was 13% of the step of 1024
// Atwood machines (docs/performance.md). The profile reads zero.
b2Timer::b2Timer() = default;
void b2Timer::Reset() {}
float b2Timer::GetMilliseconds() const {
  return 0;
}
