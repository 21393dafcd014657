// Authoring: building a scene in the sandbox by clicks, with undo and redo.
//
// Needs: ui/sandbox.h. Every edit makes a new SceneDef from the sandbox's scene and rebuilds the
// world from it (Sandbox::replaceScene: the simulation restarts from the edited initial state);
// the previous SceneDef goes on the undo stack. Tools (one click each unless said):
//   Box, Circle         a body of the set size and mass at the click (dynamic, or static)
//   Polygon             clicks add vertices, Finish (or a right click) makes the convex hull body
//   PointPulley         a small static sensor disc the cable tool threads through
//   PolygonPulley       a static hexagon the cable wraps (side chosen from the cable's turn)
//   CirclePulley        a static 16-gon, the circle the cable wraps
//   Cable               click the start anchor (on a body or the world), then pulleys in order,
//                       then the end anchor (anywhere that is not a pulley); a right click cancels
//   Delete              removes the body (and its joints and cables) or the cable clicked
// Save writes the scene JSON that `cablelab run FILE` loads (engine/model/scene_json.h).
#pragma once

#include <string>
#include <vector>

#include "engine/model/scene.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

struct Authoring {
  enum class Tool {
    None,
    Box,
    Circle,
    Polygon,
    PointPulley,
    PolygonPulley,
    CirclePulley,
    Cable,
    Delete
  };
  Tool tool = Tool::None;
  double size = 0.4;  ///< box side, circle diameter, pulley diameter (m)
  double mass = 1.0;  ///< kg
  bool isStatic = false;
  std::vector<Vec2> polygon;  ///< polygon vertices clicked so far (world, m)
  // The cable in progress.
  bool cableStarted = false;
  AnchorDef start;
  std::vector<std::string> pulleyBodies;  ///< pulley bodies clicked so far, in order
  std::vector<Vec2> pulleyCentres;        ///< their centres (world) for the wrap sides
  Vec2 startWorld = Vec2::Zero();
  std::vector<SceneDef> undo, redo;
};

/// The tool's name for buttons and the status line.
const char* toolName(Authoring::Tool tool);

/// Handles a click at world point `p` (right = right button); true if the tool used it.
bool authoringClick(Sandbox& sandbox, const Vec2& p, bool right);
/// Makes the convex hull of the clicked polygon vertices a body; false if fewer than three.
bool finishPolygon(Sandbox& sandbox);
/// Applies `next` as an edit (undo remembers the current scene); false + sandbox.error if the
/// scene is invalid (nothing changes then).
bool applyEdit(Sandbox& sandbox, SceneDef next);
bool undoEdit(Sandbox& sandbox);
bool redoEdit(Sandbox& sandbox);
/// Replaces the scene by an empty one (a ground and nothing else), as an edit.
void newScene(Sandbox& sandbox);
/// The scene as edited, with the live settings: dt, substeps, gravity and every cable's live
/// parameters (rest length, stiffness, preload, damping, as the inspector or a fit set them).
SceneDef sceneToSave(const Sandbox& sandbox);
/// Writes sceneToSave() to `path`; throws InputError / std::runtime_error naming the path on
/// failure.
void saveScene(const Sandbox& sandbox, const std::string& path);

/// The Build section of the Simulation panel (tools, sizes, undo, redo, save).
void authoringPanel(Sandbox& sandbox);

/// World points the tool has collected so far (polygon vertices, cable route), for the overlay.
void authoringOverlay(const Sandbox& sandbox, Overlay& overlay);

}  // namespace cablelab::ui
