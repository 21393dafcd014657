// Authoring: building a scene in the sandbox by clicks, with undo and redo.
//
// Needs: ui/sandbox.h. Every edit makes a new SceneDef from the sandbox's scene and rebuilds the
// world from it (Sandbox::replaceScene: the simulation restarts from the edited initial state);
// the previous SceneDef goes on the undo stack. Tools (one click each unless said):
//   Box, Circle         a body of the set size and mass at the click (dynamic, static, kinematic)
//   Polygon             clicks add vertices, Finish (or a right click) makes the convex hull body
//   PointPulley         an eyelet (a small sensor disc) the cable threads through
//   PolygonPulley       a hexagon the cable wraps
//   CirclePulley        a wheel (a circle) the cable wraps; no-slip and capstan grip in the
//   Inspector
//                       Pulleys clicked in empty space are fixed (static); clicked on a body they
//                       are mounted on it (a revolute axle at their centre; an eyelet is welded).
//   Cable               click the start (a point of a body, or empty space), then pulleys in order
//                       (Shift+click: any body as a pulley round its shape; Alt+click: an eyelet at
//                       the clicked point of any body), then the end; a right click cancels.
//                       The cable runs over the pulleys in click order (ui/authoring_route.h).
//   Revolute, Prismatic, Weld  click two bodies (empty space = the world); the joint sits at the
//                       second click. Limits, motor and servo in the Inspector.
//   Delete              removes the body (and its joints and cables) or the cable clicked
// Save writes the scene JSON that `cablelab run FILE` loads (engine/model/scene_json.h).
#pragma once

#include <string>
#include <vector>

#include "engine/model/scene.h"
#include "ui/authoring_route.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

/// Where the menu bar's Build menu laid out its items in the last frame (px, window coordinates),
/// so that a script clicks them where a student would (ui/lecture_scripts.h, first-mechanism).
struct BuildMenuLayout {
  PanelRect title;  ///< "Build" in the menu bar (as last drawn closed: an open menu keeps it)
  bool open = false;
  // The open menu; empty rectangles while it is closed.
  PanelRect popup;               ///< the menu's window
  PanelRect newScene;            ///< "New scene"
  std::vector<PanelRect> tools;  ///< each tool's item, in Authoring::Tool's order
  PanelRect nextBody;            ///< "next body" (kept while its submenu is open)
  bool nextBodyOpen = false;
  PanelRect nextBodyPopup;  ///< its submenu's window
  PanelRect size, mass;     ///< the submenu's "size (m)" and "kg" fields
  /// How far (px) a row of the menu or its submenu reaches past its window's right edge, and how
  /// much of either's height is scrolled out of sight (0, 0: every row shown whole).
  float rowOverflow = 0, hiddenHeight = 0;
};

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
    Revolute,
    Prismatic,
    Weld,
    Delete
  };
  static constexpr int kToolCount = 12;
  Tool tool = Tool::None;
  double size = 0.4;                      ///< box side, circle diameter, pulley diameter (m)
  double mass = 1.0;                      ///< kg
  BodyType bodyType = BodyType::Dynamic;  ///< of the next box, circle or polygon
  bool drumEnds = false;      ///< cable ends clicked on a round body wind on it (a drum)
  std::vector<Vec2> polygon;  ///< polygon vertices clicked so far (world, m)
  // The cable in progress.
  bool cableStarted = false;
  AnchorDef start;
  Vec2 startWorld = Vec2::Zero();
  std::vector<RouteStop> route;  ///< pulleys clicked so far, in order
  // The joint in progress: its first click.
  bool jointStarted = false;
  std::string jointBodyA;
  int selectedJoint = 0;  ///< the joint the Inspector edits
  std::vector<SceneDef> undo, redo;
  BuildMenuLayout menu;  ///< the Build menu as last drawn
};

/// The tool's name for buttons and the status line.
const char* toolName(Authoring::Tool tool);

/// Handles a click at world point `p` (right = right button); true if the tool used it.
/// `shift`, `alt`: the cable tool's Shift+click and Alt+click (see above).
bool authoringClick(Sandbox& sandbox, const Vec2& p, bool right, bool shift = false,
                    bool alt = false);
/// Makes the convex hull of the clicked polygon vertices a body; false if fewer than three.
bool finishPolygon(Sandbox& sandbox);
/// Applies `next` as an edit (undo remembers the current scene); false + sandbox.error if the
/// scene is invalid (nothing changes then).
bool applyEdit(Sandbox& sandbox, SceneDef next);
bool undoEdit(Sandbox& sandbox);
bool redoEdit(Sandbox& sandbox);
/// Replaces the scene by an empty one (a ground and nothing else), as an edit, paused.
void newScene(Sandbox& sandbox);
/// Replaces pulley `k` of cable `cable` by `p` as an edit (side auto: it joins when the cable
/// touches it, so no wrap at the start); says so in `error` when the cable then misses a pulley.
bool editPulley(Sandbox& sandbox, int cable, int k, PulleyDef p);
/// The scene without body `name`, its joints and the cables that use it.
SceneDef withoutBody(const SceneDef& scene, const std::string& name);
/// The scene as edited, with the live settings: dt, substeps, gravity and every cable's live
/// parameters (rest length, stiffness, preload, damping, as the inspector or a fit set them).
SceneDef sceneToSave(const Sandbox& sandbox);
/// Writes sceneToSave() to `path`; throws InputError / std::runtime_error naming the path on
/// failure.
void saveScene(const Sandbox& sandbox, const std::string& path);

/// Chooses `tool`, dropping a polygon, cable or joint in progress.
void chooseTool(Authoring& authoring, Authoring::Tool tool);

/// The Build section of the Simulation panel (tools, sizes, undo, redo, save).
void authoringPanel(Sandbox& sandbox);
/// The menu bar's Build menu, there in presentation mode too: New scene (paused), the tools (Esc
/// goes back to selecting), the next body's size, mass and type (a submenu: the menu fits a
/// 1280x720 window at projector scale), undo and redo.
void buildMenu(Sandbox& sandbox);

/// World points the tool has collected so far (polygon vertices, cable route), for the overlay.
void authoringOverlay(const Sandbox& sandbox, Overlay& overlay);

}  // namespace cablelab::ui
