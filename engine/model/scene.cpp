#include "engine/model/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "engine/core/error.h"
#include "engine/core/polygon.h"

namespace cablelab {

int findBodyIndex(const SceneDef& scene, const std::string& name) {
  if (name == "world") return -1;
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    if (scene.bodies[i].name == name) return static_cast<int>(i);
  return -2;
}

double largestRestitution(const SceneDef& scene, int body) {
  double e = 0;
  if (body >= 0)
    for (const ShapeDef& shape : scene.bodies[body].shapes) e = std::max(e, shape.restitution);
  return e;
}

std::vector<Vec2> pulleyPolygon(const SceneDef& scene, const PulleyDef& pulley) {
  const int body = findBodyIndex(scene, pulley.body);
  if (!pulley.vertices.empty() || body < 0) return pulley.vertices;
  for (const ShapeDef& s : scene.bodies[body].shapes)
    if (s.kind == ShapeDef::Kind::Polygon) return s.vertices;
  return {};
}

namespace {

class Checker {
 public:
  explicit Checker(const std::string& source) : source_(source) {}
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(source_, field, what);
  }
  // Box2D is float (and Debian's build asserts on non-finite positions): a finite double beyond
  // float range would become inf there (a fuzzer finding). Every number is kept within
  // +/-kMaxMagnitude, far beyond anything physical yet safe in float products.
  static constexpr double kMaxMagnitude = 1e12;
  void finite(double v, const std::string& field) const {
    if (!std::isfinite(v)) fail(field, "must be a finite number" + gotValue(v));
    if (std::abs(v) > kMaxMagnitude) fail(field, "must be within +/-1e12" + gotValue(v));
  }
  void finite(const Vec2& v, const std::string& field) const {
    if (!isFinite(v))
      fail(field, "must be finite numbers (got [" + formatNumber(v.x()) + ", " +
                      formatNumber(v.y()) + "])");
    finite(v.x(), field);
    finite(v.y(), field);
  }
  void nonNegative(double v, const std::string& field) const {
    finite(v, field);
    if (v < 0) fail(field, "must be >= 0" + gotValue(v));
  }
  void positive(double v, const std::string& field) const {
    finite(v, field);
    if (v <= 0) fail(field, "must be positive" + gotValue(v));
  }

 private:
  const std::string& source_;
};

std::string at(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

// " (got [[x, y], ...])": a polygon's vertices as the scene gave them.
std::string gotPoints(const std::vector<Vec2>& points) {
  std::string text = " (got [";
  for (size_t i = 0; i < points.size(); ++i)
    text +=
        (i ? ", [" : "[") + formatNumber(points[i].x()) + ", " + formatNumber(points[i].y()) + "]";
  return text + "])";
}

// Box2D 2.4 merges a polygon's vertices closer than half its linear slop (each against those it
// kept before it) and asserts, aborting the program, when fewer than three are left or their
// area is under float's epsilon: a collision polygon must keep clear of both.
constexpr double kBox2DWeldDistance = 0.0025;  // m: 0.5 b2_linearSlop
constexpr double kBox2DMinArea = 1.2e-7;       // m^2: b2_epsilon

void checkCollisionPolygon(const Checker& check, const std::vector<Vec2>& polygon,
                           const std::string& field) {
  std::vector<Vec2> kept;  // what Box2D keeps, in order (a convex polygon's vertices stay convex)
  for (const Vec2& v : polygon)
    if (std::none_of(kept.begin(), kept.end(),
                     [&](const Vec2& k) { return (v - k).norm() < kBox2DWeldDistance; }))
      kept.push_back(v);
  if (kept.size() < 3)
    check.fail(field,
               "polygon too small for Box2D: it merges vertices closer than 0.0025 m and "
               "keeps " +
                   std::to_string(kept.size()) +
                   " of them (a box needs a half size of at least 0.00125 m)");
  double area2 = 0;
  for (size_t i = 0; i < kept.size(); ++i) area2 += cross(kept[i], kept[(i + 1) % kept.size()]);
  if (0.5 * area2 < kBox2DMinArea)
    check.fail(field, "polygon too thin for Box2D: area " + formatNumber(0.5 * area2) +
                          " m^2, it needs more than 1.2e-07 m^2");
}

// A pulley that grips the cable (a wheel with no slip or friction, a polygon with friction)
// splits it in spans: each a rigid constraint of its own, on a side known in advance.
// A polygon's corners may also grip an elastic cable: its spans slide after the step
// (docs/polygon_friction.md), which a wheel's turning constraint does not allow.
void checkGrip(const Checker& check, const PulleyDef& pd, const CableDef& c,
               const std::string& field, const std::string& what, bool elasticAllowed = false) {
  if (pd.grip == Grip::Capstan) check.positive(pd.mu, field + ".mu");
  if (!gripsCable(pd)) return;
  if (c.stiffness > 0 && !elasticAllowed)
    check.fail(field + (pd.grip == Grip::Capstan ? ".mu" : ".no_slip"),
               what + " needs a rigid cable (stiffness 0)");
  if (pd.side == WrapSide::Auto)
    check.fail(field + ".side", what + " needs side left or right" + gotValue("auto"));
}

}  // namespace

void validateScene(const SceneDef& scene, const std::string& source) {
  Checker check(source);
  check.finite(scene.gravity, "gravity");
  check.positive(scene.dt, "dt");
  if (scene.dt > 1) check.fail("dt", "must be in (0, 1] s, as --dt" + gotValue(scene.dt));
  if (scene.substeps < 1 || scene.substeps > 1000)
    check.fail("substeps", "must be 1..1000" + gotValue(scene.substeps));
  check.finite(scene.view.center, "view.center");
  check.positive(scene.view.height, "view.height");

  std::set<std::string> names;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDef& b = scene.bodies[i];
    const std::string f = at("bodies", i);
    if (b.name.empty()) check.fail(f + ".name", "must not be empty");
    if (b.name == "world")
      check.fail(f + ".name", "is reserved for the fixed frame" + gotValue(b.name));
    if (!names.insert(b.name).second)
      check.fail(f + ".name", "duplicate body name" + gotValue(b.name));
    check.finite(b.position, f + ".position");
    check.finite(b.angle, f + ".angle");
    check.finite(b.velocity, f + ".velocity");
    check.finite(b.angularVelocity, f + ".angular_velocity");
    if (b.type == BodyType::Dynamic) check.positive(b.mass, f + ".mass");
    check.nonNegative(b.inertia, f + ".inertia");
    check.nonNegative(b.linearDamping, f + ".linear_damping");
    check.nonNegative(b.angularDamping, f + ".angular_damping");
    for (size_t s = 0; s < b.shapes.size(); ++s) {
      const ShapeDef& sh = b.shapes[s];
      const std::string fs = f + at(".shapes", s);
      check.nonNegative(sh.friction, fs + ".friction");
      check.nonNegative(sh.restitution, fs + ".restitution");
      if (sh.kind == ShapeDef::Kind::Circle) {
        check.positive(sh.radius, fs + ".radius");
        check.finite(sh.center, fs + ".center");
      } else {
        if (sh.vertices.size() < 3 || sh.vertices.size() > 8)
          check.fail(fs + ".vertices", "a polygon needs 3 to 8 vertices" +
                                           gotValue(static_cast<double>(sh.vertices.size())));
        for (size_t v = 0; v < sh.vertices.size(); ++v)
          check.finite(sh.vertices[v], fs + at(".vertices", v));
        if (!isConvexCCW(sh.vertices))
          check.fail(fs + ".vertices",
                     "polygon must be convex and counter-clockwise" + gotPoints(sh.vertices));
        checkCollisionPolygon(check, sh.vertices, fs + ".vertices");
      }
    }
  }

  auto bodyRef = [&](const std::string& name, const std::string& field) {
    if (findBodyIndex(scene, name) == -2) check.fail(field, "unknown body" + gotValue(name));
  };
  std::set<std::string> jointNames;
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    const JointDef& j = scene.joints[i];
    const std::string f = at("joints", i);
    if (!j.name.empty() && !jointNames.insert(j.name).second)
      check.fail(f + ".name", "duplicate joint name" + gotValue(j.name));
    bodyRef(j.bodyA, f + ".body_a");
    bodyRef(j.bodyB, f + ".body_b");
    if (j.bodyB == "world")
      check.fail(f + ".body_b", "must be a body, not the world" + gotValue(j.bodyB));
    if (j.bodyA == j.bodyB)
      check.fail(f + ".body_b", "a joint needs two different bodies" + gotValue(j.bodyB));
    check.finite(j.anchor, f + ".anchor");
    check.finite(j.axis, f + ".axis");
    if (j.kind == JointDef::Kind::Prismatic && j.axis.norm() < 1e-9)
      check.fail(f + ".axis", "must not be zero (got [" + formatNumber(j.axis.x()) + ", " +
                                  formatNumber(j.axis.y()) + "])");
    check.finite(j.lower, f + ".limits");
    check.finite(j.upper, f + ".limits");
    if (j.enableLimit && j.lower > j.upper)
      check.fail(f + ".limits", "lower limit above upper limit (got [" + formatNumber(j.lower) +
                                    ", " + formatNumber(j.upper) + "])");
    if (j.servo.enabled && j.kind == JointDef::Kind::Weld)
      check.fail(f + ".servo",
                 "only a revolute or prismatic joint can be driven" + gotValue("weld"));
    check.nonNegative(j.servo.kp, f + ".servo.kp");
    check.nonNegative(j.servo.kd, f + ".servo.kd");
    check.finite(j.servo.target, f + ".servo.target");
    check.positive(j.servo.maxForce, f + ".servo.max_force");
    check.finite(j.servo.speed, f + ".servo.speed");
    check.finite(j.value, f + ".value");
  }
  check.nonNegative(scene.time, "time");

  std::set<std::string> cableNames;
  for (size_t i = 0; i < scene.cables.size(); ++i) {
    const CableDef& c = scene.cables[i];
    const std::string f = at("cables", i);
    if (c.name.empty()) check.fail(f + ".name", "must not be empty");
    if (!cableNames.insert(c.name).second)
      check.fail(f + ".name", "duplicate cable name" + gotValue(c.name));
    bodyRef(c.start.body, f + ".start.body");
    bodyRef(c.end.body, f + ".end.body");
    check.finite(c.start.point, f + ".start.point");
    check.finite(c.end.point, f + ".end.point");
    for (const auto& [end, name] : {std::pair{&c.start, ".start"}, std::pair{&c.end, ".end"}}) {
      check.nonNegative(end->radius, f + name + ".radius");
      if (end->radius == 0) continue;
      check.positive(end->turns, f + name + ".turns");
      if (end->side != WrapSide::Left && end->side != WrapSide::Right)
        check.fail(f + name + ".side",
                   "a drum is wound on the left or the right" +
                       gotValue(end->side == WrapSide::Auto ? "auto" : "threaded"));
    }
    check.finite(c.restLength, f + ".rest_length");
    if (c.restLength == 0) check.fail(f + ".rest_length", "zero-length cable" + gotValue(0.0));
    check.nonNegative(c.stiffness, f + ".stiffness");
    check.nonNegative(c.preload, f + ".preload");
    check.nonNegative(c.damping, f + ".damping");
    for (size_t p = 0; p < c.pulleys.size(); ++p) {
      const PulleyDef& pd = c.pulleys[p];
      const std::string fp = f + at(".pulleys", p);
      bodyRef(pd.body, fp + ".body");
      check.finite(pd.point, fp + ".point");
      for (size_t v = 0; v < pd.vertices.size(); ++v)
        check.finite(pd.vertices[v], fp + at(".vertices", v));
      if (pd.kind == PulleyDef::Kind::Polygon && !pd.vertices.empty() && !isConvexCCW(pd.vertices))
        check.fail(fp + ".vertices",
                   "polygon must be convex and counter-clockwise" + gotPoints(pd.vertices));
      // Without vertices a polygon pulley takes its body's first polygon shape
      // (docs/scene-format.md).
      if (pd.kind == PulleyDef::Kind::Polygon && pd.vertices.empty() &&
          pulleyPolygon(scene, pd).empty() && findBodyIndex(scene, pd.body) != -2)
        check.fail(
            fp + ".vertices",
            (pd.body == "world" ? std::string("is required for a polygon pulley on the world")
                                : "is required: body \"" + pd.body +
                                      "\" has no polygon or box shape to take them from") +
                " (got nothing)");
      if (pd.kind == PulleyDef::Kind::Point && pd.side == WrapSide::Auto)
        check.fail(fp + ".side", "a point pulley cannot be auto (use left, right or threaded)" +
                                     gotValue("auto"));
      if (pd.kind == PulleyDef::Kind::Point) continue;
      check.nonNegative(pd.turns, fp + ".turns");
      if (pd.side == WrapSide::Auto && pd.turns > 0)
        check.fail(fp + ".side",
                   "a pulley wound at the start needs side left or right" + gotValue("auto"));
      if (pd.kind == PulleyDef::Kind::Polygon) {
        if (pd.grip == Grip::NoSlip)
          check.fail(fp + ".no_slip", "a polygon pulley cannot be no_slip (give it mu) (got true)");
        checkGrip(check, pd, c, fp, "a polygon pulley with friction", true);
        continue;
      }
      check.positive(pd.radius, fp + ".radius");
      if (pd.side == WrapSide::Threaded)
        check.fail(fp + ".side", "a circle pulley cannot be threaded (use left, right or auto)" +
                                     gotValue("threaded"));
      checkGrip(check, pd, c, fp, "a wheel that grips the cable");
    }
  }
}

}  // namespace cablelab
