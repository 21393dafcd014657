#include "ui/authoring.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "engine/dynamics/world_state.h"
#include "engine/model/scene_json.h"

namespace cablelab::ui {
namespace {

Authoring& state(Sandbox& sandbox) {
  return *sandbox.authoring;
}

/// A name not used by any body yet: prefix1, prefix2, ...
std::string freshBodyName(const SceneDef& scene, const std::string& prefix) {
  for (int n = 1;; ++n) {
    const std::string name = prefix + std::to_string(n);
    if (findBodyIndex(scene, name) == -2) return name;
  }
}

std::string freshCableName(const SceneDef& scene) {
  for (int n = 1;; ++n) {
    const std::string name = "cable" + std::to_string(n);
    if (std::none_of(scene.cables.begin(), scene.cables.end(),
                     [&](const CableDef& c) { return c.name == name; }))
      return name;
  }
}

std::vector<Vec2> regularPolygon(int n, double radius) {
  std::vector<Vec2> v;
  for (int k = 0; k < n; ++k)
    v.push_back(
        snapped(radius * Vec2(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n)), kFineSnap));
  return v;
}

/// Counter-clockwise convex hull (monotone chain); collinear points dropped.
std::vector<Vec2> convexHull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 1] - h[k - 2], p[i - 1] - h[k - 2]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

BodyDef makeBody(const SceneDef& scene, const std::string& prefix, const Vec2& at, BodyType type,
                 double mass, ShapeDef shape) {
  BodyDef b;
  b.name = freshBodyName(scene, prefix);
  b.type = type;
  b.position = at;
  b.mass = mass;
  b.shapes = {std::move(shape)};
  return b;
}

ShapeDef polygonShape(std::vector<Vec2> vertices) {
  ShapeDef s;
  s.kind = ShapeDef::Kind::Polygon;
  s.vertices = std::move(vertices);
  return s;
}

/// A body the pulley tools made (clicked with the cable tool, it is a pulley, not an end).
bool isPulleyBody(const BodyDef& b) {
  return b.name.rfind("pulley", 0) == 0;
}

/// The body under a click, any type; -1 for none.
int bodyUnder(const Sandbox& sandbox, const Vec2& p) {
  return sandbox.bodyAt(p, true);
}

/// The clicked end of a cable: the clicked point of the body under it, else a world point. With
/// drum ends on, an end clicked on a round body winds on it (a drum round its centre).
AnchorDef anchorAt(const Sandbox& sandbox, const Vec2& p) {
  const int body = bodyUnder(sandbox, p);
  if (body < 0) return {"world", p};
  const BodyState& s = sandbox.world()->body(body);
  const BodyDef& def = sandbox.scene.bodies[body];
  AnchorDef a{def.name, snapped(rotate(p - s.position, -s.angle), kSnap)};
  const ShapeDef& shape = def.shapes.front();
  if (sandbox.authoring->drumEnds && shape.kind == ShapeDef::Kind::Circle &&
      shape.radius > kEyeletRadius) {
    a.point = shape.center;
    a.radius = shape.radius;
  }
  return a;
}

/// The rope leaves (isStart) or reaches the drum on its side facing `toward` horizontally, as a
/// rope hangs off a winch: the drum is on the cable's right (Left) or left (Right).
void drumSide(AnchorDef& a, const Vec2& centre, const Vec2& toward, bool isStart) {
  if (a.radius <= 0) return;
  const Vec2 d = toward - centre;
  const double facing = d.x() >= 0 ? 1 : -1;
  a.side = (isStart ? -d.y() : d.y()) * facing > 0 ? WrapSide::Left : WrapSide::Right;
}

Vec2 anchorWorld(const Sandbox& sandbox, const AnchorDef& a) {
  const int b = findBodyIndex(sandbox.scene, a.body);
  if (b < 0) return a.point;
  const BodyState& s = sandbox.world()->body(b);
  return s.position + rotate(a.point, s.angle);
}

bool cableClick(Sandbox& sandbox, Authoring& a, const Vec2& p, bool shift, bool alt) {
  const int body = bodyUnder(sandbox, p);
  if (!a.cableStarted) {
    a.start = anchorAt(sandbox, p);
    a.startWorld = a.start.radius > 0 ? anchorWorld(sandbox, a.start) : p;
    a.route.clear();
    a.cableStarted = true;
    sandbox.message =
        "cable: click the pulleys in order, then the end (right click cancels; Shift+click uses "
        "any body as a pulley, Alt+click puts an eyelet on it)";
    return true;
  }
  if (body >= 0 && (shift || alt || isPulleyBody(sandbox.scene.bodies[body]))) {
    if (!a.route.empty() && a.route.back().body == sandbox.scene.bodies[body].name && !alt)
      return true;  // clicked twice: one stop
    a.route.push_back(routeStop(sandbox.scene.bodies[body], sandbox.world()->body(body), p, alt));
    return true;
  }
  AnchorDef end = anchorAt(sandbox, p);
  const Vec2 endWorld = end.radius > 0 ? anchorWorld(sandbox, end) : p;
  drumSide(a.start, a.startWorld, a.route.empty() ? endWorld : a.route.front().world, true);
  drumSide(end, endWorld, a.route.empty() ? a.startWorld : a.route.back().world, false);
  SceneDef next = sandbox.scene;
  next.cables.push_back(routedCable(sandbox.scene, freshCableName(sandbox.scene), a.start,
                                    a.startWorld, a.route, end, endWorld));
  a.cableStarted = false;
  a.route.clear();
  if (!applyEdit(sandbox, std::move(next))) return true;
  const std::string problem =
      routeProblem(*sandbox.world(), static_cast<int>(sandbox.scene.cables.size()) - 1);
  if (!problem.empty()) {  // take the cable back: it would not run where it was clicked
    undoEdit(sandbox);
    a.redo.clear();
    sandbox.message = "the cable was not added";
    sandbox.error = problem;
    return true;
  }
  sandbox.message = "added " + sandbox.scene.cables.back().name;
  return true;
}

/// Revolute, prismatic or weld between the two clicked bodies (empty space: the world), at the
/// second click.
bool jointClick(Sandbox& sandbox, Authoring& a, const Vec2& p) {
  const int body = bodyUnder(sandbox, p);
  const std::string name = body >= 0 ? sandbox.scene.bodies[body].name : "world";
  if (!a.jointStarted) {
    a.jointStarted = true;
    a.jointBodyA = name;
    sandbox.message = std::string(toolName(a.tool)) +
                      " joint: now click the second body at the "
                      "point where they are joined (empty space: the ground)";
    return true;
  }
  a.jointStarted = false;
  JointDef j;
  j.kind = a.tool == Authoring::Tool::Revolute    ? JointDef::Kind::Revolute
           : a.tool == Authoring::Tool::Prismatic ? JointDef::Kind::Prismatic
                                                  : JointDef::Kind::Weld;
  j.bodyA = a.jointBodyA;
  j.bodyB = name;
  if (j.bodyB == "world") std::swap(j.bodyA, j.bodyB);
  if (j.bodyB == "world" || j.bodyA == j.bodyB) {
    sandbox.error =
        "A joint needs two different bodies (or a body and the ground): click a "
        "body, then another one.";
    return true;
  }
  j.anchor = p;
  SceneDef next = sandbox.scene;
  for (int n = 1;; ++n) {
    j.name = "joint" + std::to_string(n);
    if (std::none_of(next.joints.begin(), next.joints.end(),
                     [&](const JointDef& k) { return k.name == j.name; }))
      break;
  }
  next.joints.push_back(j);
  if (applyEdit(sandbox, std::move(next))) sandbox.message = "added " + j.name;
  return true;
}

/// A pulley body at `p`: fixed in empty space; on a body, mounted on it (revolute axle at its
/// centre, an eyelet welded), so it moves with that body.
void addPulley(Sandbox& sandbox, Authoring& a, SceneDef& next, const Vec2& p, ShapeDef shape,
               bool eyelet) {
  int host = bodyUnder(sandbox, p);
  if (host >= 0 && sandbox.scene.bodies[host].type == BodyType::Static) host = -1;
  shape.sensor = true;  // the cable wraps it; bodies pass through
  BodyDef b = makeBody(next, "pulley", p, host < 0 ? BodyType::Static : BodyType::Dynamic,
                       host < 0 ? 1.0 : a.mass, std::move(shape));
  if (host >= 0) {
    JointDef j;
    j.kind = eyelet ? JointDef::Kind::Weld : JointDef::Kind::Revolute;
    j.name = b.name + "_mount";
    j.bodyA = next.bodies[host].name;
    j.bodyB = b.name;
    j.anchor = p;
    next.joints.push_back(j);
  }
  next.bodies.push_back(std::move(b));
}

void deleteAt(Sandbox& sandbox, const Vec2& p) {
  const int body = bodyUnder(sandbox, p);
  if (body >= 0) {
    const std::string name = sandbox.scene.bodies[body].name;
    if (applyEdit(sandbox, withoutBody(sandbox.scene, name))) sandbox.message = "deleted " + name;
    return;
  }
  const int cable = sandbox.cableAt(p, 6 * sandbox.camera.metresPerPixel);
  if (cable < 0) return;
  SceneDef next = sandbox.scene;
  const std::string name = next.cables[cable].name;
  next.cables.erase(next.cables.begin() + cable);
  if (applyEdit(sandbox, std::move(next))) sandbox.message = "deleted " + name;
}

}  // namespace

const char* toolName(Authoring::Tool tool) {
  switch (tool) {
    case Authoring::Tool::None:
      return "select";
    case Authoring::Tool::Box:
      return "box";
    case Authoring::Tool::Circle:
      return "circle";
    case Authoring::Tool::Polygon:
      return "polygon";
    case Authoring::Tool::PointPulley:
      return "point pulley";
    case Authoring::Tool::PolygonPulley:
      return "polygon pulley";
    case Authoring::Tool::CirclePulley:
      return "circle pulley";
    case Authoring::Tool::Cable:
      return "cable";
    case Authoring::Tool::Revolute:
      return "hinge";
    case Authoring::Tool::Prismatic:
      return "slider";
    case Authoring::Tool::Weld:
      return "weld";
    case Authoring::Tool::Delete:
      return "delete";
  }
  return "?";
}

bool applyEdit(Sandbox& sandbox, SceneDef next) {
  Authoring& a = state(sandbox);
  SceneDef previous = sandbox.scene;
  if (!sandbox.replaceScene(next)) return false;
  a.undo.push_back(std::move(previous));
  a.redo.clear();
  return true;
}

void chooseTool(Authoring& a, Authoring::Tool tool) {
  a.tool = tool;
  a.polygon.clear();
  a.route.clear();
  a.cableStarted = a.jointStarted = false;
}

bool undoEdit(Sandbox& sandbox) {
  Authoring& a = state(sandbox);
  if (a.undo.empty()) return false;
  SceneDef current = sandbox.scene;
  if (!sandbox.replaceScene(a.undo.back())) return false;
  a.undo.pop_back();
  a.redo.push_back(std::move(current));
  sandbox.message = "undid the last edit (Ctrl+Y redoes it)";
  return true;
}

bool redoEdit(Sandbox& sandbox) {
  Authoring& a = state(sandbox);
  if (a.redo.empty()) return false;
  SceneDef current = sandbox.scene;
  if (!sandbox.replaceScene(a.redo.back())) return false;
  a.redo.pop_back();
  a.undo.push_back(std::move(current));
  sandbox.message = "redid the edit";
  return true;
}

void newScene(Sandbox& sandbox) {
  SceneDef s;
  s.name = "my_mechanism";  // shown as "my mechanism"; saved as my_mechanism.json
  s.description = "built in the sandbox";
  s.view = {Vec2(0, 1.5), 4.0};
  BodyDef ground;
  ground.name = "ground";
  ground.type = BodyType::Static;
  ground.position = Vec2(0, -0.1);
  ground.shapes = {polygonShape({Vec2(-3, -0.1), Vec2(3, -0.1), Vec2(3, 0.1), Vec2(-3, 0.1)})};
  s.bodies = {ground};
  if (!applyEdit(sandbox, std::move(s))) return;
  sandbox.sceneFile.clear();  // a new scene is not the file opened before
  sandbox.paused = true;      // it waits for its first bodies; Space runs it
  sandbox.fitView();
}

bool finishPolygon(Sandbox& sandbox) {
  Authoring& a = state(sandbox);
  std::vector<Vec2> hull = convexHull(a.polygon);
  a.polygon.clear();
  if (hull.size() < 3) return false;
  if (hull.size() > 8) hull.resize(8);  // Box2D's polygon limit; still convex (a sub-hull)
  Vec2 centre = Vec2::Zero();
  for (const Vec2& v : hull) centre += v / static_cast<double>(hull.size());
  for (Vec2& v : hull) v -= centre;
  SceneDef next = sandbox.scene;
  next.bodies.push_back(makeBody(next, "polygon", centre, a.bodyType, a.mass, polygonShape(hull)));
  return applyEdit(sandbox, std::move(next));
}

bool authoringClick(Sandbox& sandbox, const Vec2& clicked, bool right, bool shift, bool alt) {
  Authoring& a = state(sandbox);
  const Vec2 p = snapped(clicked, kSnap);
  using Tool = Authoring::Tool;
  if (a.tool == Tool::None || !sandbox.world()) return false;
  if (right) {  // finishes a polygon, cancels a cable or a joint
    if (a.tool == Tool::Polygon) finishPolygon(sandbox);
    a.cableStarted = a.jointStarted = false;
    a.route.clear();
    return true;
  }
  SceneDef next = sandbox.scene;
  const double r = 0.5 * a.size;
  switch (a.tool) {
    case Tool::Box:
      next.bodies.push_back(
          makeBody(next, "box", p, a.bodyType, a.mass,
                   polygonShape({Vec2(-r, -r), Vec2(r, -r), Vec2(r, r), Vec2(-r, r)})));
      break;
    case Tool::Circle: {
      ShapeDef c;
      c.radius = r;
      next.bodies.push_back(makeBody(next, "circle", p, a.bodyType, a.mass, c));
      break;
    }
    case Tool::Polygon:
      a.polygon.push_back(p);
      return true;
    case Tool::PointPulley: {
      ShapeDef c;
      c.radius = kEyeletRadius;
      addPulley(sandbox, a, next, p, c, true);
      break;
    }
    case Tool::PolygonPulley:
      addPulley(sandbox, a, next, p, polygonShape(regularPolygon(6, r)), false);
      break;
    case Tool::CirclePulley: {
      ShapeDef c;
      c.radius = r;
      addPulley(sandbox, a, next, p, c, false);
      break;
    }
    case Tool::Cable:
      return cableClick(sandbox, a, p, shift, alt);
    case Tool::Revolute:
    case Tool::Prismatic:
    case Tool::Weld:
      return jointClick(sandbox, a, p);
    case Tool::Delete:
      deleteAt(sandbox, p);
      return true;
    case Tool::None:
      return false;
  }
  if (applyEdit(sandbox, std::move(next)))
    sandbox.message = "added " + sandbox.scene.bodies.back().name;
  return true;
}

bool editPulley(Sandbox& sandbox, int cable, int k, PulleyDef p) {
  if (p.side == WrapSide::Auto) p.turns = 0;
  SceneDef next = sandbox.scene;
  next.cables[cable].pulleys[k] = p;
  if (!applyEdit(sandbox, std::move(next))) return false;
  const std::string problem = routeProblem(*sandbox.world(), cable);
  if (!problem.empty()) sandbox.error = problem;
  return true;
}

SceneDef withoutBody(const SceneDef& scene, const std::string& name) {
  SceneDef next = scene;
  auto uses = [&](const CableDef& c) {
    if (c.start.body == name || c.end.body == name) return true;
    return std::any_of(c.pulleys.begin(), c.pulleys.end(),
                       [&](const PulleyDef& q) { return q.body == name; });
  };
  std::erase_if(next.bodies, [&](const BodyDef& b) { return b.name == name; });
  std::erase_if(next.cables, uses);
  std::erase_if(next.joints, [&](const JointDef& j) { return j.bodyA == name || j.bodyB == name; });
  return next;
}

namespace {

bool posedBeforeTheFirstStep(const World& world) {
  if (world.stepCount() != 0) return false;
  const auto& inputs = world.history().inputs();
  return std::any_of(inputs.begin(), inputs.end(),
                     [](const WorldInput& in) { return in.kind == WorldInput::Kind::Pose; });
}

}  // namespace

SceneDef sceneToSave(const Sandbox& sandbox) {
  SceneDef def = sandbox.scene;
  def.dt = sandbox.dt, def.substeps = sandbox.substeps, def.gravity = sandbox.gravity;
  const World* world = sandbox.world();
  if (!world || world->cableCount() != static_cast<int>(def.cables.size())) return def;
  if (posedBeforeTheFirstStep(*world)) {
    // Where the user posed the bodies is where the scene starts: the world as it stands, with
    // the poses that led there, so `cablelab run` starts from it (docs/scene-format.md).
    SceneDef now = sceneNow(*world);
    now.name = def.name, now.description = def.description, now.view = def.view;
    now.dt = def.dt, now.substeps = def.substeps;
    return now;
  }
  // Live cable edits (the inspector, a loaded fit) are World state: write them. The rest length
  // only where it differs from the one the file gives (an unset one is the initial length).
  const World fresh(def, sandbox.sceneName);
  for (int i = 0; i < world->cableCount(); ++i) {
    const Cable& live = world->cable(i);
    CableDef& c = def.cables[i];
    c.stiffness = live.stiffness();
    c.preload = live.preload();
    c.damping = live.damping();
    if (live.restLength() != fresh.cable(i).restLength()) c.restLength = live.restLength();
  }
  return def;
}

void saveScene(const Sandbox& sandbox, const std::string& path) {
  saveSceneFile(sceneToSave(sandbox), path);
}

}  // namespace cablelab::ui
