#include "engine/model/scene_json.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/json_reader.h"

namespace cablelab {

namespace {

using nlohmann::json;
using Reader = JsonReader;

ShapeDef readShape(Reader&& r) {
  ShapeDef s;
  const std::string type = r.requiredString("type");
  s.friction = r.number("friction", s.friction);
  s.restitution = r.number("restitution", s.restitution);
  s.sensor = r.boolean("sensor", false);
  if (type == "circle") {
    s.kind = ShapeDef::Kind::Circle;
    s.radius = r.number("radius", s.radius);
    s.center = r.vec2("center", Vec2::Zero());
  } else if (type == "box") {
    s.kind = ShapeDef::Kind::Polygon;
    const Vec2 half = r.vec2("half_size", Vec2(0.1, 0.1));
    if (half.x() <= 0 || half.y() <= 0)
      r.fail("half_size", "must be positive (got [" + formatNumber(half.x()) + ", " +
                              formatNumber(half.y()) + "])");
    const Vec2 c = r.vec2("center", Vec2::Zero());
    const double angle = r.number("angle", 0);
    for (const Vec2& corner : {Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)})
      s.vertices.push_back(c + rotate(corner.cwiseProduct(half), angle));
  } else if (type == "polygon") {
    s.kind = ShapeDef::Kind::Polygon;
    s.vertices = r.points("vertices");
  } else {
    r.fail("type", "must be circle, box or polygon" + gotValue(type));
  }
  return s;
}

BodyDef readBody(Reader&& r) {
  BodyDef b;
  b.name = r.requiredString("name");
  const std::string type = r.string("type", "dynamic");
  if (type == "dynamic")
    b.type = BodyType::Dynamic;
  else if (type == "static")
    b.type = BodyType::Static;
  else if (type == "kinematic")
    b.type = BodyType::Kinematic;
  else
    r.fail("type", "must be dynamic, static or kinematic" + gotValue(type));
  b.position = r.vec2("position", b.position);
  b.angle = r.number("angle", 0);
  b.velocity = r.vec2("velocity", b.velocity);
  b.angularVelocity = r.number("angular_velocity", 0);
  b.mass = r.number("mass", b.mass);
  b.inertia = r.number("inertia", 0);
  b.fixedRotation = r.boolean("fixed_rotation", false);
  b.linearDamping = r.number("linear_damping", 0);
  b.angularDamping = r.number("angular_damping", 0);
  const json& shapes = r.list("shapes");
  for (size_t i = 0; i < shapes.size(); ++i) b.shapes.push_back(readShape(r.item("shapes", i)));
  return b;
}

JointDef readJoint(Reader&& r) {
  JointDef j;
  const std::string type = r.requiredString("type");
  if (type == "revolute")
    j.kind = JointDef::Kind::Revolute;
  else if (type == "prismatic")
    j.kind = JointDef::Kind::Prismatic;
  else if (type == "weld")
    j.kind = JointDef::Kind::Weld;
  else
    r.fail("type", "must be revolute, prismatic or weld" + gotValue(type));
  j.name = r.string("name", "");
  j.bodyA = r.string("body_a", "world");
  j.bodyB = r.requiredString("body_b");
  j.anchor = r.vec2("anchor", j.anchor);
  j.axis = r.vec2("axis", j.axis);
  if (r.has("limits")) {
    const Vec2 lim = r.vec2("limits", Vec2::Zero());
    j.enableLimit = true;
    j.lower = lim.x();
    j.upper = lim.y();
  }
  j.collideConnected = r.boolean("collide_connected", false);
  j.value = r.number("value", 0);
  if (r.has("servo")) {
    Reader s = r.child("servo");
    j.servo.enabled = true;
    j.servo.kp = s.number("kp", j.servo.kp);
    j.servo.kd = s.number("kd", j.servo.kd);
    j.servo.target = s.number("target", 0);
    j.servo.maxForce = s.number("max_force", j.servo.maxForce);
    j.servo.speed = s.number("speed", 0);
  }
  return j;
}

const char* sideName(WrapSide s) {
  switch (s) {
    case WrapSide::Left:
      return "left";
    case WrapSide::Right:
      return "right";
    case WrapSide::Threaded:
      return "threaded";
    case WrapSide::Auto:
      return "auto";
  }
  return "left";
}

WrapSide readSide(Reader& r, WrapSide fallback) {
  const std::string side = r.string("side", sideName(fallback));
  if (side == "left") return WrapSide::Left;
  if (side == "right") return WrapSide::Right;
  if (side == "threaded") return WrapSide::Threaded;
  if (side == "auto") return WrapSide::Auto;
  r.fail("side", "must be left, right, threaded or auto" + gotValue(side));
}

AnchorDef readAnchor(Reader&& r) {
  AnchorDef a;
  a.body = r.string("body", "world");
  a.point = r.vec2("point", Vec2::Zero());
  if (r.has("radius")) {
    a.radius = r.number("radius", 0);
    if (a.radius <= 0)
      r.fail("radius", "a drum's radius must be positive (got " + formatNumber(a.radius) + ")");
    a.side = readSide(r, WrapSide::Left);
    a.turns = r.number("turns", a.turns);
  }
  return a;
}

// Circle and polygon pulleys: either "no_slip": true (circles) or "mu" (capstan friction;
// on a polygon, at each corner).
void readGrip(Reader& p, PulleyDef& pd) {
  const bool noSlip = p.boolean("no_slip", false);
  if (p.has("mu")) {
    pd.mu = p.number("mu", 0);
    if (noSlip)
      p.fail("mu", "give either mu or no_slip, not both (got mu " + formatNumber(pd.mu) +
                       " with no_slip true)");
    if (pd.mu < 0) p.fail("mu", "must be >= 0" + gotValue(pd.mu));
    pd.grip = pd.mu > 0 ? Grip::Capstan : Grip::Frictionless;
  } else if (noSlip) {
    pd.grip = Grip::NoSlip;
  }
}

// Circle pulleys: "radius", and a grip (readGrip).
void readCircle(Reader& p, PulleyDef& pd) {
  pd.kind = PulleyDef::Kind::Circle;
  pd.point = p.vec2("point", Vec2::Zero());
  if (!p.has("radius")) p.fail("radius", "is required for a circle pulley");
  pd.radius = p.number("radius", 0);
  pd.side = readSide(p, WrapSide::Left);
  pd.turns = p.number("turns", 0);
  readGrip(p, pd);
}

CableDef readCable(Reader&& r) {
  CableDef c;
  c.name = r.requiredString("name");
  if (!r.has("start")) r.fail("start", "is required");
  if (!r.has("end")) r.fail("end", "is required");
  c.start = readAnchor(r.child("start"));
  c.end = readAnchor(r.child("end"));
  const json& pulleys = r.list("pulleys");
  for (size_t i = 0; i < pulleys.size(); ++i) {
    Reader p = r.item("pulleys", i);
    PulleyDef pd;
    const std::string type = p.string("type", "point");
    pd.body = p.string("body", "world");
    if (type == "point") {
      pd.kind = PulleyDef::Kind::Point;
      pd.point = p.vec2("point", Vec2::Zero());
      pd.side = readSide(p, WrapSide::Threaded);
    } else if (type == "polygon") {
      pd.kind = PulleyDef::Kind::Polygon;
      pd.vertices = p.points("vertices");
      pd.side = readSide(p, WrapSide::Left);
      pd.turns = p.number("turns", 0);
      readGrip(p, pd);
    } else if (type == "circle") {
      readCircle(p, pd);
    } else {
      p.fail("type", "must be point, polygon or circle" + gotValue(type));
    }
    c.pulleys.push_back(pd);
  }
  c.restLength = r.number("rest_length", -1);
  if (c.restLength < 0 && r.has("rest_length"))
    r.fail("rest_length", "must be positive" + gotValue(c.restLength));
  c.stiffness = r.number("stiffness", 0);
  c.preload = r.number("preload", 0);
  c.damping = r.number("damping", 0);
  return c;
}

json vec(const Vec2& v) {
  return json::array({v.x(), v.y()});
}
json polygonJson(const std::vector<Vec2>& vs) {
  json out = json::array();
  for (const Vec2& v : vs) out.push_back(vec(v));
  return out;
}
json anchorJson(const AnchorDef& a) {
  json j = {{"body", a.body}, {"point", vec(a.point)}};
  if (a.radius > 0) {
    j["radius"] = a.radius;
    j["side"] = sideName(a.side);
    j["turns"] = a.turns;
  }
  return j;
}

/// "history": {"scene": {...}, "inputs": [[kind, index, count, v0, v1, v2, v3], ...]}: the scene
/// a World was built from and its inputs since (scene.h, SceneHistory).
std::shared_ptr<const SceneHistory> readHistory(const json& j, const std::string& source) {
  Reader r(j, source, "history");
  auto h = std::make_shared<SceneHistory>();
  if (!r.has("scene")) r.fail("scene", "is required");
  h->origin = sceneFromJson(j.at("scene"), source + " (history.scene)");
  if (h->origin.history) r.fail("scene", "must not have a history of its own");
  if (!r.has("inputs")) r.fail("inputs", "is required");
  const json& inputs = r.list("inputs");
  for (size_t i = 0; i < inputs.size(); ++i) {
    const std::string field = r.field("inputs") + "[" + std::to_string(i) + "]";
    const json& row = inputs[i];
    if (!row.is_array() || row.size() != 7)
      throw InputError(source, field,
                       "must be a list of 7 numbers (got " + describeJson(row) + ")");
    std::array<double, 7> values{};
    for (size_t k = 0; k < 7; ++k) values[k] = r.numberValue(row[k], field);
    h->inputs.push_back(values);
  }
  return h;
}

}  // namespace

SceneDef sceneFromJson(const json& j, const std::string& source) {
  SceneDef s;
  {
    Reader r(j, source, "");
    s.name = r.string("name", "");
    s.description = r.string("description", "");
    s.gravity = r.vec2("gravity", s.gravity);
    s.dt = r.number("dt", s.dt);
    s.substeps = r.integer("substeps", s.substeps);
    if (r.has("view")) {
      Reader v = r.child("view");
      s.view.center = v.vec2("center", s.view.center);
      s.view.height = v.number("height", s.view.height);
    }
    const json& bodies = r.list("bodies");
    // An empty object would run as an empty world: surely not what the author meant.
    if (bodies.empty()) r.fail("bodies", "must list at least one body (the scene has none)");
    for (size_t i = 0; i < bodies.size(); ++i) s.bodies.push_back(readBody(r.item("bodies", i)));
    const json& joints = r.list("joints");
    for (size_t i = 0; i < joints.size(); ++i) s.joints.push_back(readJoint(r.item("joints", i)));
    const json& cables = r.list("cables");
    for (size_t i = 0; i < cables.size(); ++i) s.cables.push_back(readCable(r.item("cables", i)));
    s.time = r.number("time", 0);
    const double steps = r.number("step_count", 0);
    if (!(steps >= 0 && steps <= 1e15 && steps == std::floor(steps)))
      r.fail("step_count", "must be a whole number >= 0" + gotValue(steps));
    s.stepCount = static_cast<long>(steps);
    if (r.has("history")) s.history = readHistory(j.at("history"), source);
  }
  validateScene(s, source);
  return s;
}

const char* pulleyTypeName(PulleyDef::Kind kind) {
  switch (kind) {
    case PulleyDef::Kind::Point:
      return "point";
    case PulleyDef::Kind::Polygon:
      return "polygon";
    case PulleyDef::Kind::Circle:
      return "circle";
  }
  return "point";
}

json sceneToJson(const SceneDef& s) {
  json j;
  j["name"] = s.name;
  j["description"] = s.description;
  j["gravity"] = vec(s.gravity);
  j["dt"] = s.dt;
  j["substeps"] = s.substeps;
  j["view"] = {{"center", vec(s.view.center)}, {"height", s.view.height}};
  j["bodies"] = json::array();
  for (const BodyDef& b : s.bodies) {
    json jb = {{"name", b.name},
               {"type", b.type == BodyType::Dynamic  ? "dynamic"
                        : b.type == BodyType::Static ? "static"
                                                     : "kinematic"},
               {"position", vec(b.position)},
               {"angle", b.angle},
               {"velocity", vec(b.velocity)},
               {"angular_velocity", b.angularVelocity},
               {"mass", b.mass},
               {"inertia", b.inertia},
               {"fixed_rotation", b.fixedRotation},
               {"linear_damping", b.linearDamping},
               {"angular_damping", b.angularDamping},
               {"shapes", json::array()}};
    for (const ShapeDef& sh : b.shapes) {
      json js = {{"friction", sh.friction}, {"restitution", sh.restitution}, {"sensor", sh.sensor}};
      if (sh.kind == ShapeDef::Kind::Circle) {
        js["type"] = "circle";
        js["radius"] = sh.radius;
        js["center"] = vec(sh.center);
      } else {
        js["type"] = "polygon";
        js["vertices"] = polygonJson(sh.vertices);
      }
      jb["shapes"].push_back(js);
    }
    j["bodies"].push_back(jb);
  }
  j["joints"] = json::array();
  for (const JointDef& jd : s.joints) {
    json jj = {{"type", jd.kind == JointDef::Kind::Revolute    ? "revolute"
                        : jd.kind == JointDef::Kind::Prismatic ? "prismatic"
                                                               : "weld"},
               {"name", jd.name},
               {"body_a", jd.bodyA},
               {"body_b", jd.bodyB},
               {"anchor", vec(jd.anchor)},
               {"axis", vec(jd.axis)},
               {"collide_connected", jd.collideConnected}};
    if (jd.value != 0) jj["value"] = jd.value;
    if (jd.enableLimit) jj["limits"] = json::array({jd.lower, jd.upper});
    if (jd.servo.enabled)
      jj["servo"] = {{"kp", jd.servo.kp},
                     {"kd", jd.servo.kd},
                     {"target", jd.servo.target},
                     {"max_force", jd.servo.maxForce},
                     {"speed", jd.servo.speed}};
    j["joints"].push_back(jj);
  }
  j["cables"] = json::array();
  for (const CableDef& c : s.cables) {
    json jc = {{"name", c.name},           {"start", anchorJson(c.start)},
               {"end", anchorJson(c.end)}, {"pulleys", json::array()},
               {"stiffness", c.stiffness}, {"preload", c.preload},
               {"damping", c.damping}};
    if (c.restLength > 0) jc["rest_length"] = c.restLength;
    for (const PulleyDef& p : c.pulleys) {
      json jp = {{"type", pulleyTypeName(p.kind)}, {"body", p.body}, {"side", sideName(p.side)}};
      if (p.kind != PulleyDef::Kind::Polygon) jp["point"] = vec(p.point);
      if (p.kind == PulleyDef::Kind::Circle) {
        jp["radius"] = p.radius;
        jp["turns"] = p.turns;
        if (p.grip == Grip::NoSlip) jp["no_slip"] = true;
        if (p.grip == Grip::Capstan) jp["mu"] = p.mu;
      }
      if (p.kind == PulleyDef::Kind::Polygon && !p.vertices.empty())
        jp["vertices"] = polygonJson(p.vertices);
      if (p.kind == PulleyDef::Kind::Polygon && p.turns > 0) jp["turns"] = p.turns;
      if (p.kind == PulleyDef::Kind::Polygon && p.grip == Grip::Capstan) jp["mu"] = p.mu;
      jc["pulleys"].push_back(jp);
    }
    j["cables"].push_back(jc);
  }
  if (s.time != 0 || s.stepCount != 0) j["time"] = s.time, j["step_count"] = s.stepCount;
  if (s.history) {
    json inputs = json::array();
    for (const auto& row : s.history->inputs) inputs.push_back(row);
    j["history"] = {{"scene", sceneToJson(s.history->origin)}, {"inputs", inputs}};
  }
  return j;
}

SceneDef loadSceneFile(const std::string& path) {
  return sceneFromJson(readJsonFile(path), path);
}

void saveSceneFile(const SceneDef& scene, const std::string& path) {
  std::ofstream out(path);
  if (!out)
    throw InputError(path, "(file)",
                     std::string("cannot write: ") + std::strerror(errno) + gotValue(path));
  out << sceneToJson(scene).dump(2) << "\n";
  if (!out.flush())
    throw InputError(path, "(file)",
                     std::string("write failed: ") + std::strerror(errno) + gotValue(path));
}

}  // namespace cablelab
