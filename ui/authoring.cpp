#include "ui/authoring.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "engine/model/scene_json.h"
#include "ui/panels.h"

namespace cablelab::ui {
namespace {

constexpr Colour kDraft{0.1f, 0.45f, 0.2f, 1.0f};

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
    v.push_back(radius * Vec2(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n)));
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

BodyDef makeBody(const SceneDef& scene, const std::string& prefix, const Vec2& at, bool isStatic,
                 double mass, ShapeDef shape) {
  BodyDef b;
  b.name = freshBodyName(scene, prefix);
  b.type = isStatic ? BodyType::Static : BodyType::Dynamic;
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

bool isPulleyBody(const BodyDef& b) {
  return b.name.rfind("pulley", 0) == 0 && b.type == BodyType::Static;
}

/// The clicked end of a cable: a body-frame point on the body under it, else a world point.
AnchorDef anchorAt(const Sandbox& sandbox, const Vec2& p) {
  const int body = sandbox.bodyAt(p, true);
  if (body < 0) return {"world", p};
  const BodyState& s = sandbox.world()->body(body);
  return {sandbox.scene.bodies[body].name, rotate(p - s.position, -s.angle)};
}

/// The cable from the clicked route; polygon pulleys wrap on the side the route turns away from.
CableDef routedCable(const Sandbox& sandbox, const Authoring& a, const AnchorDef& end,
                     const Vec2& endWorld) {
  CableDef c;
  c.name = freshCableName(sandbox.scene);
  c.start = a.start;
  c.end = end;
  for (size_t k = 0; k < a.pulleyBodies.size(); ++k) {
    const BodyDef& body = sandbox.scene.bodies[findBodyIndex(sandbox.scene, a.pulleyBodies[k])];
    PulleyDef p;
    p.body = body.name;
    const bool point = body.shapes.front().kind == ShapeDef::Kind::Circle;
    if (point) {
      p.kind = PulleyDef::Kind::Point;
      p.point = Vec2::Zero();
      p.side = WrapSide::Threaded;
    } else {
      p.kind = PulleyDef::Kind::Polygon;  // the body's own polygon
      const Vec2 before = k == 0 ? a.startWorld : a.pulleyCentres[k - 1];
      const Vec2 after = k + 1 < a.pulleyCentres.size() ? a.pulleyCentres[k + 1] : endWorld;
      const Vec2 c0 = a.pulleyCentres[k];
      // Turning left round the pulley puts it on the cable's left: the cable passes its right.
      p.side = cross(c0 - before, after - c0) > 0 ? WrapSide::Right : WrapSide::Left;
    }
    c.pulleys.push_back(p);
  }
  return c;
}

bool cableClick(Sandbox& sandbox, Authoring& a, const Vec2& p) {
  const int body = sandbox.bodyAt(p, true);
  if (!a.cableStarted) {
    a.start = anchorAt(sandbox, p);
    a.startWorld = p;
    a.pulleyBodies.clear();
    a.pulleyCentres.clear();
    a.cableStarted = true;
    sandbox.message = "cable: click pulleys in order, then the end anchor (right click cancels)";
    return true;
  }
  if (body >= 0 && isPulleyBody(sandbox.scene.bodies[body])) {
    a.pulleyBodies.push_back(sandbox.scene.bodies[body].name);
    a.pulleyCentres.push_back(sandbox.world()->body(body).position);
    return true;
  }
  SceneDef next = sandbox.scene;
  next.cables.push_back(routedCable(sandbox, a, anchorAt(sandbox, p), p));
  a.cableStarted = false;
  if (applyEdit(sandbox, std::move(next)))
    sandbox.message = "added " + sandbox.scene.cables.back().name;
  return true;
}

void deleteAt(Sandbox& sandbox, const Vec2& p) {
  SceneDef next = sandbox.scene;
  const int body = sandbox.bodyAt(p, true);
  if (body >= 0) {
    const std::string name = next.bodies[body].name;
    auto uses = [&](const CableDef& c) {
      if (c.start.body == name || c.end.body == name) return true;
      return std::any_of(c.pulleys.begin(), c.pulleys.end(),
                         [&](const PulleyDef& q) { return q.body == name; });
    };
    next.bodies.erase(next.bodies.begin() + body);
    std::erase_if(next.cables, uses);
    std::erase_if(next.joints,
                  [&](const JointDef& j) { return j.bodyA == name || j.bodyB == name; });
    if (applyEdit(sandbox, std::move(next))) sandbox.message = "deleted " + name;
    return;
  }
  const int cable = sandbox.cableAt(p, 6 * sandbox.camera.metresPerPixel);
  if (cable < 0) return;
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

bool undoEdit(Sandbox& sandbox) {
  Authoring& a = state(sandbox);
  if (a.undo.empty()) return false;
  SceneDef current = sandbox.scene;
  if (!sandbox.replaceScene(a.undo.back())) return false;
  a.undo.pop_back();
  a.redo.push_back(std::move(current));
  return true;
}

bool redoEdit(Sandbox& sandbox) {
  Authoring& a = state(sandbox);
  if (a.redo.empty()) return false;
  SceneDef current = sandbox.scene;
  if (!sandbox.replaceScene(a.redo.back())) return false;
  a.redo.pop_back();
  a.undo.push_back(std::move(current));
  return true;
}

void newScene(Sandbox& sandbox) {
  SceneDef s;
  s.name = "my_scene";
  s.description = "built in the sandbox";
  s.view = {Vec2(0, 1.5), 4.0};
  BodyDef ground;
  ground.name = "ground";
  ground.type = BodyType::Static;
  ground.position = Vec2(0, -0.1);
  ground.shapes = {polygonShape({Vec2(-3, -0.1), Vec2(3, -0.1), Vec2(3, 0.1), Vec2(-3, 0.1)})};
  s.bodies = {ground};
  if (applyEdit(sandbox, std::move(s))) sandbox.fitView();
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
  next.bodies.push_back(makeBody(next, "polygon", centre, a.isStatic, a.mass, polygonShape(hull)));
  return applyEdit(sandbox, std::move(next));
}

bool authoringClick(Sandbox& sandbox, const Vec2& p, bool right) {
  Authoring& a = state(sandbox);
  using Tool = Authoring::Tool;
  if (a.tool == Tool::None) return false;
  if (right) {  // finishes a polygon, cancels a cable
    if (a.tool == Tool::Polygon) finishPolygon(sandbox);
    a.cableStarted = false;
    return true;
  }
  SceneDef next = sandbox.scene;
  const double r = 0.5 * a.size;
  switch (a.tool) {
    case Tool::Box:
      next.bodies.push_back(
          makeBody(next, "box", p, a.isStatic, a.mass,
                   polygonShape({Vec2(-r, -r), Vec2(r, -r), Vec2(r, r), Vec2(-r, r)})));
      break;
    case Tool::Circle: {
      ShapeDef c;
      c.radius = r;
      next.bodies.push_back(makeBody(next, "circle", p, a.isStatic, a.mass, c));
      break;
    }
    case Tool::Polygon:
      a.polygon.push_back(p);
      return true;
    case Tool::PointPulley: {
      ShapeDef c;
      c.radius = 0.03;
      c.sensor = true;
      next.bodies.push_back(makeBody(next, "pulley", p, true, 1, c));
      break;
    }
    case Tool::PolygonPulley:
    case Tool::CirclePulley: {
      ShapeDef s = polygonShape(regularPolygon(a.tool == Tool::PolygonPulley ? 6 : 16, r));
      s.sensor = true;  // the cable wraps it; bodies pass through
      next.bodies.push_back(makeBody(next, "pulley", p, true, 1, s));
      break;
    }
    case Tool::Cable:
      return cableClick(sandbox, a, p);
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

SceneDef sceneToSave(const Sandbox& sandbox) {
  SceneDef def = sandbox.scene;
  def.dt = sandbox.dt, def.substeps = sandbox.substeps, def.gravity = sandbox.gravity;
  const World* world = sandbox.world();
  if (!world || world->cableCount() != static_cast<int>(def.cables.size())) return def;
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

void authoringPanel(Sandbox& sandbox) {
  Authoring& a = state(sandbox);
  using Tool = Authoring::Tool;
  static const std::array<std::pair<Tool, const char*>, 9> tools = {{
      {Tool::None, "Clicks select and drag, as usual."},
      {Tool::Box, "Click to add a box."},
      {Tool::Circle, "Click to add a circle."},
      {Tool::Polygon, "Click the vertices, then Finish (or right click): their convex hull."},
      {Tool::PointPulley, "Click to add a point pulley the cable threads through."},
      {Tool::PolygonPulley, "Click to add a hexagonal pulley the cable wraps."},
      {Tool::CirclePulley, "Click to add a round pulley (a 16-gon) the cable wraps."},
      {Tool::Cable, "Click the start (a body or empty space), the pulleys in order, then the end."},
      {Tool::Delete, "Click a body or a cable to delete it (with its cables and joints)."},
  }};
  for (const auto& [tool, tip] : tools) {
    if (tool != Tool::None) sameLineIfRoom(checkboxWidth(toolName(tool)));
    if (ImGui::RadioButton(toolName(tool), a.tool == tool)) {
      a.tool = tool;
      a.polygon.clear();
      a.cableStarted = false;
    }
    tooltip(tip);
  }
  float size = static_cast<float>(a.size), mass = static_cast<float>(a.mass);
  ImGui::SetNextItemWidth(fieldWidth("size (m)", ImGui::GetFontSize() * 5));
  if (ImGui::DragFloat("size (m)", &size, 0.01f, 0.02f, 10.0f, "%.2f")) a.size = size;
  tooltip("Box side, circle and pulley diameter.");
  sameLineIfRoom(ImGui::GetFontSize() * 4 + checkboxWidth("kg") - ImGui::GetFrameHeight());
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 4);
  if (ImGui::DragFloat("kg", &mass, 0.05f, 0.01f, 1000.0f, "%.2f")) a.mass = mass;
  tooltip("Mass of the next body.");
  ImGui::Checkbox("static", &a.isStatic);
  tooltip("The next body is fixed (a wall, a ground).");
  if (a.tool == Tool::Polygon) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Finish")) finishPolygon(sandbox);
    tooltip("Make the polygon from the vertices clicked so far.");
  }
  if (ImGui::Button("Undo")) undoEdit(sandbox);
  tooltip("Undo the last edit.");
  sameLineIfRoom(buttonWidth("Redo"));
  if (ImGui::Button("Redo")) redoEdit(sandbox);
  tooltip("Redo the edit undone last.");
  sameLineIfRoom(buttonWidth("New"));
  if (ImGui::Button("New")) newScene(sandbox);
  tooltip("An empty scene with a ground (undo brings the old one back).");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%zu undo, %zu redo; Scene > Save scene as...", a.undo.size(), a.redo.size());
  ImGui::PopStyleColor();
}

void authoringOverlay(const Sandbox& sandbox, Overlay& overlay) {
  const Authoring& a = *sandbox.authoring;
  for (const Vec2& p : a.polygon) overlay.targets.push_back({p, "", kDraft});
  if (!a.cableStarted) return;
  Vec2 from = a.startWorld;
  for (const Vec2& c : a.pulleyCentres) {
    overlay.arrows.push_back({from, c, "", kDraft});
    from = c;
  }
  overlay.targets.push_back({a.startWorld, "cable start", kDraft});
  overlay.keys.push_back({Overlay::Key::Marker::Cross, "cable being routed", kDraft});
}

}  // namespace cablelab::ui
