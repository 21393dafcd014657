#include "ui/build_scenarios.h"

#include <algorithm>

#include "ui/synthetic_events.h"

namespace cablelab::ui {
namespace {

using Kind = BuildStep::Kind;
using Tool = Authoring::Tool;

BuildStep tool(Tool t) {
  return {Kind::Tool, t, Vec2::Zero(), {}};
}
BuildStep click(double x, double y, Kind kind = Kind::Click) {
  return {kind, Tool::None, Vec2(x, y), {}};
}
/// Undo, Redo or the Delete key.
BuildStep keyStep(Kind kind) {
  return {kind, Tool::None, Vec2::Zero(), {}};
}
BuildStep setting(std::function<void(Sandbox&)> set) {
  return {Kind::Setting, Tool::None, Vec2::Zero(), std::move(set)};
}
/// The Build panel's kg field.
BuildStep mass(double kg) {
  return setting([kg](Sandbox& s) { s.authoring->mass = kg; });
}
/// The Inspector's fields of the last joint (an authoring edit, as jointEdits makes it).
BuildStep jointSetting(std::function<void(JointDef&)> edit) {
  return setting([edit](Sandbox& s) {
    SceneDef next = s.scene;
    edit(next.joints.back());
    applyEdit(s, std::move(next));
  });
}

std::vector<BuildScenario> makeScenarios() {
  return {
      // An Atwood machine (1 kg and 2 kg) over a round pulley 0.8 m across fixed in space: the
      // ropes hang straight down from its sides.
      {"build-circle-pulley",
       {tool(Tool::Box), click(-0.4, 1), mass(2), click(0.4, 1),
        setting([](Sandbox& s) { s.authoring->size = 0.8; }), tool(Tool::CirclePulley),
        click(0, 2.5), tool(Tool::Cable), click(-0.4, 1.1), click(0, 2.5), click(0.4, 1.1)}},
      // Two equal boxes under a hexagon 0.8 m across: the cable goes over it and holds them
      // still, the ropes straight down from its side corners.
      {"build-polygon-route",
       {tool(Tool::Box), click(-0.4, 1), click(0.4, 1),
        setting([](Sandbox& s) { s.authoring->size = 0.8; }), tool(Tool::PolygonPulley),
        click(0, 2.5), tool(Tool::Cable), click(-0.4, 1.1), click(0, 2.5), click(0.4, 1.1)}},
      // A box hung by its top-right corner from a point in space.
      {"build-cable-corner",
       {tool(Tool::Box), click(0, 1), tool(Tool::Cable), click(0, 2.5), click(0.19, 1.19)}},
      // The hexagon route, then the Inspector's side "auto": the straight cable misses the
      // hexagon, and the window says so.
      {"build-route-auto",
       {tool(Tool::Box), click(-0.6, 1), click(0.6, 1), tool(Tool::PolygonPulley), click(0, 2.5),
        tool(Tool::Cable), click(-0.6, 1.1), click(0, 2.5), click(0.6, 1.1),
        setting([](Sandbox& s) {
          PulleyDef p = s.scene.cables.back().pulleys.front();
          p.side = WrapSide::Auto;
          editPulley(s, 0, 0, p);
        })}},
      // A box on a hinge near its left side, driven by a motor at 1 rad/s (gains for its 0.05
      // kg m^2: the default kd 44.7 would overshoot at 60 Hz, kd dt / I = 15).
      {"build-hinge-motor",
       {tool(Tool::Box), click(0, 1.5), tool(Tool::Revolute), click(-1, 2.5), click(-0.15, 1.5),
        jointSetting([](JointDef& j) {
          j.servo.enabled = true;
          j.servo.speed = 1;
          j.servo.kp = 20;
          j.servo.kd = 2;
        })}},
      // A box on a slider (left-right) with limits, pulled by a sloping cable.
      {"build-slider-limits",
       {tool(Tool::Box), click(0, 1.5), tool(Tool::Prismatic), click(-1, 2.5), click(0, 1.5),
        jointSetting([](JointDef& j) {
          j.enableLimit = true;
          j.lower = -0.5;
          j.upper = 0.3;
        }),
        tool(Tool::Box), click(1.2, 1), tool(Tool::PointPulley), click(1.2, 2.5), tool(Tool::Cable),
        click(0.1, 1.5), click(1.2, 2.5), click(1.2, 1.1)}},
      // Two boxes glued by a weld, the pair hung from one cable.
      {"build-weld",
       {tool(Tool::Box), click(0, 1.5), click(0.4, 1.5), tool(Tool::Weld), click(0, 1.5),
        click(0.3, 1.5), tool(Tool::Cable), click(0, 2.8), click(0, 1.6)}},
      // A round pulley on a swinging arm (an axle on the arm), a box hanging over it.
      {"build-pulley-on-body",
       {tool(Tool::Box), click(0, 2.4), tool(Tool::Revolute), click(-1, 3), click(-0.1, 2.4),
        tool(Tool::CirclePulley), click(0.1, 2.4), tool(Tool::Box), click(0.6, 1),
        tool(Tool::Cable), click(-1, 2.6), click(0.1, 2.4), click(0.6, 1.1)}},
      // A winch drum (a circle on an axle) with the cable's start wound on it, a box below.
      {"build-drum",
       {setting([](Sandbox& s) { s.authoring->drumEnds = true; }), tool(Tool::Circle),
        click(0, 2.5), tool(Tool::Revolute), click(-1, 3), click(0, 2.5), tool(Tool::Box),
        click(0.2, 1), tool(Tool::Cable), click(0.05, 2.5), click(0.2, 1.1)}},
      // A circle on an axle, Shift+clicked as a pulley, with capstan friction: an Atwood machine.
      {"build-capstan",
       {tool(Tool::Circle), click(0, 2.5), tool(Tool::Revolute), click(-1, 3), click(0, 2.5),
        tool(Tool::Box), click(-0.5, 1), mass(2), click(0.5, 1), tool(Tool::Cable),
        click(-0.5, 1.1), click(0, 2.5, Kind::ShiftClick), click(0.5, 1.1),
        setting([](Sandbox& s) {  // the Inspector's grip and mu
          SceneDef next = s.scene;
          next.cables.back().pulleys.front().grip = Grip::Capstan;
          next.cables.back().pulleys.front().mu = 0.1;
          applyEdit(s, std::move(next));
        })}},
      // An elastic cord: a box on a spring of 200 N/m, pre-stretched 2 cm, with some damping (the
      // Inspector's fields).
      {"build-elastic",
       {tool(Tool::Box), click(0, 1.5), tool(Tool::Cable), click(0, 2.8), click(0, 1.6),
        setting([](Sandbox& s) {
          s.selectedCable = 0;
          s.cableEdit = {s.world()->cable(0).restLength(), 200, 0.02, 2};
          s.applyCableEdit();
        })}},
      // A driven (kinematic) box moving right at 0.2 m/s, dragging a box on a cable.
      {"build-kinematic",
       {setting([](Sandbox& s) { s.authoring->bodyType = BodyType::Kinematic; }), tool(Tool::Box),
        click(-1, 2.5), setting([](Sandbox& s) {  // the Inspector's speed field
          SceneDef next = s.scene;
          next.bodies.back().velocity = Vec2(0.2, 0);
          applyEdit(s, std::move(next));
        }),
        setting([](Sandbox& s) { s.authoring->bodyType = BodyType::Dynamic; }), click(-1, 1),
        tool(Tool::Cable), click(-1, 2.4), click(-1, 1.1)}},
      // A round wheel on an axle (a circle body and a hinge), Shift+clicked as a pulley, the
      // Inspector's grip "no slip": an Atwood machine whose rope turns the wheel.
      {"build-no-slip",
       {setting([](Sandbox& s) { s.authoring->size = 0.8; }), tool(Tool::Circle), click(0, 2.5),
        tool(Tool::Revolute), click(-1.5, 3), click(0, 2.5),
        setting([](Sandbox& s) { s.authoring->size = 0.4; }), tool(Tool::Box), click(-0.4, 1),
        mass(2), click(0.4, 1), tool(Tool::Cable), click(-0.4, 1.1),
        click(0, 2.5, Kind::ShiftClick), click(0.4, 1.1), setting([](Sandbox& s) {
          PulleyDef p = s.scene.cables.back().pulleys.front();
          p.grip = Grip::NoSlip;  // the Inspector's grip buttons
          editPulley(s, 0, 0, p);
        })}},
      // A fixed ramp drawn with the polygon tool (three corners, right click), a ball (a circle)
      // rolling down it, and a loose triangle (three corners, Finish) standing on the ground.
      {"build-ramp",
       {setting([](Sandbox& s) { s.authoring->bodyType = BodyType::Static; }), tool(Tool::Polygon),
        click(-1.8, 0), click(0.2, 0), click(-1.8, 1), click(-1.8, 1, Kind::RightClick),
        setting([](Sandbox& s) { s.authoring->bodyType = BodyType::Dynamic; }),
        setting([](Sandbox& s) { s.authoring->size = 0.2; }), tool(Tool::Circle),
        click(-1.25, 0.85), tool(Tool::Polygon), click(1, 0.05), click(1.4, 0.05), click(1.2, 0.4),
        setting([](Sandbox& s) { finishPolygon(s); })}},
      // Two boxes on hinges at their left sides: the first held by a servo at 0.5 rad, the
      // second stopped by its limits [-0.3, 0.3] rad as it falls.
      {"build-hinge-servo-limits",
       {tool(Tool::Box), click(-0.8, 1.5), tool(Tool::Revolute), click(-1.5, 3), click(-0.95, 1.5),
        jointSetting([](JointDef& j) {
          j.servo.enabled = true;
          j.servo.target = 0.5;
          j.servo.kp = 20;
          j.servo.kd = 2;
        }),
        tool(Tool::Box), click(0.8, 1.5), tool(Tool::Revolute), click(1.5, 3), click(0.65, 1.5),
        jointSetting([](JointDef& j) {
          j.enableLimit = true;
          j.lower = -0.3;
          j.upper = 0.3;
        })}},
      // A carriage on a slider (left-right) whose servo drives it 0.5 m right, an eyelet on it
      // (the point pulley tool clicked on the carriage), a cable from a point in space through
      // the eyelet down to a hanging box.
      {"build-eyelet-on-slider",
       {tool(Tool::Box), click(0, 2.5), tool(Tool::Prismatic), click(-1.5, 3.2), click(0, 2.5),
        jointSetting([](JointDef& j) {
          j.servo.enabled = true;
          j.servo.target = 0.5;
          j.servo.kp = 2000;
          j.servo.kd = 2000;  // slow (1 s), so that the box rises without a jerk
        }),
        tool(Tool::PointPulley), click(0.1, 2.5), tool(Tool::Box), click(0.1, 1), tool(Tool::Cable),
        click(-1.5, 2.5), click(0.1, 2.5), click(0.1, 1.1)}},
      // A hexagon pulley clicked on an arm hinged with limits (it turns on an axle there), the
      // cable from a
      // point in space over it, through an eyelet Alt+clicked on a box's corner, up to another
      // point in space: the box hangs in the loop.
      {"build-hexagon-on-arm",
       {tool(Tool::Box), click(0, 2.4), tool(Tool::Revolute), click(-1, 3), click(-0.1, 2.4),
        jointSetting([](JointDef& j) {  // the arm swings 0.6 rad at most
          j.enableLimit = true;
          j.lower = -0.6;
          j.upper = 0.6;
        }),
        tool(Tool::PolygonPulley), click(0.1, 2.4), tool(Tool::Box), click(0.6, 1),
        tool(Tool::Cable), click(-1, 2.6), click(0.1, 2.4), click(0.75, 1.15, Kind::AltClick),
        click(1.5, 2.6)}},
      // Delete, undo and redo with Ctrl+Z and Ctrl+Y; then the second box selected with a click
      // and deleted with the Delete key.
      {"build-undo-redo",
       {tool(Tool::Box), click(-0.5, 1), click(0.5, 1), tool(Tool::Delete), click(-0.5, 1),
        keyStep(Kind::Undo), keyStep(Kind::Redo), keyStep(Kind::Undo), tool(Tool::Circle),
        click(0, 2), keyStep(Kind::Undo), tool(Tool::None), click(0.5, 1),
        keyStep(Kind::DeleteKey)}},
  };
}

}  // namespace

const std::vector<BuildScenario>& buildScenarios() {
  static const std::vector<BuildScenario> all = makeScenarios();
  return all;
}

const BuildScenario* findBuildScenario(const std::string& name) {
  const auto& all = buildScenarios();
  const auto it =
      std::find_if(all.begin(), all.end(), [&](const BuildScenario& b) { return b.name == name; });
  return it == all.end() ? nullptr : &*it;
}

void playBuildStep(Sandbox& sandbox, std::uint32_t windowId, const BuildStep& s) {
  const Vec2 at = sandbox.camera.toScreen(s.at);
  auto clickAt = [&](Uint8 button) {
    pushMouseEvent(windowId, SDL_MOUSEMOTION, at);
    pushMouseEvent(windowId, SDL_MOUSEBUTTONDOWN, at, button);
    pushMouseEvent(windowId, SDL_MOUSEBUTTONUP, at, button);
  };
  switch (s.kind) {
    case Kind::Tool:
      chooseTool(*sandbox.authoring, s.tool);
      break;
    case Kind::Click:
      clickAt(SDL_BUTTON_LEFT);
      break;
    case Kind::ShiftClick:
      SDL_SetModState(KMOD_LSHIFT);
      clickAt(SDL_BUTTON_LEFT);
      break;
    case Kind::AltClick:
      SDL_SetModState(KMOD_LALT);
      clickAt(SDL_BUTTON_LEFT);
      break;
    case Kind::RightClick:
      clickAt(SDL_BUTTON_RIGHT);
      break;
    case Kind::Undo:
      SDL_SetModState(KMOD_LCTRL);
      pushKeyPress(windowId, SDLK_z);
      break;
    case Kind::Redo:
      SDL_SetModState(KMOD_LCTRL);
      pushKeyPress(windowId, SDLK_y);
      break;
    case Kind::DeleteKey:
      pushKeyPress(windowId, SDLK_DELETE);
      break;
    case Kind::Setting:
      s.set(sandbox);
      break;
  }
}

}  // namespace cablelab::ui
