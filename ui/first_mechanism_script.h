// FirstMechanismScript: a student's first mechanism in a lecture hall, built through the window
// as the student builds it (`cablelab-gui --script first-mechanism`, ui/lecture_scripts.h).
//
// In presentation mode at projector scale, at 1280x720 then 1920x1080, every step is a click or
// a key sent as synthetic SDL events (ui/synthetic_events.h) through SDL's queue, Dear ImGui and
// the sandbox's input handler: the pointer moved onto the top bar's "Build" and clicked, "New
// scene" clicked in the menu, then each tool picked from the menu by clicking its item and put
// in the view by clicks there, the next body's kg and size typed into the fields of the menu's
// "next body" submenu (Ctrl+click, the number, Enter). Where to click comes from the rectangles the
// Build menu laid out in the last frame (ui/authoring.h, BuildMenuLayout), never from fixed pixels.
// First, at each size, what the fields cannot take (-1 kg, a 0 m and a 1e999 m size), each
// refused with one line (ui/typed_field.h) and dismissed; then the mechanism: a light box and a
// heavy box, the rope from the light one up over a round pulley, across over a hexagon, through an
// eyelet and down to the heavy one. Then Esc, Space, the light box dragged sideways, Space; after
// both sizes, the side panels (p).
//
// Reports, as JSON: every menu pick (the item clicked, the tool chosen after it, whether the
// menu closed), the new scene at each size (its name and bodies), every field typed (the value
// before and after it, the error line shown), each size's built scene (bodies, cables, the pulleys'
// kinds in the rope's order, wraps), every banner, how often the view moved while building, how
// many clicks fell outside it, and each view with its screenshot (ui/lecture_scripts.h,
// lectureViewJson), the Build menu open in three of them at each size (menu, menu-tools; menu-kg
// with its "next body" submenu). A step that finds nothing to click ends the run with "failure".
//
// Needs: an SDL video subsystem (the sandbox's Window), a Sandbox with a loaded scene.
#pragma once

#include <SDL.h>

#include <functional>
#include <string>
#include <vector>

#include "ui/authoring.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

class FirstMechanismScript {
 public:
  /// `out`: the prefix of the screenshots' paths (PREFIX-NAME.png).
  FirstMechanismScript(Uint32 windowId, std::string out);
  /// Called once per frame before events are polled; false when the script has finished.
  bool beforeFrame(Sandbox& sandbox);
  std::string report() const { return report_; }

 private:
  /// One thing the student does over `frames` frames: `act` is called with the frame's index in
  /// the step (0 .. frames - 1) and returns false when it cannot be done (the run ends).
  struct Step {
    std::string what;
    int frames = 1;
    std::function<bool(Sandbox&, int)> act;
  };
  /// Where a click goes (px), from the last frame's layout; empty: nothing there to click.
  using Where = std::function<PanelRect(const Sandbox&)>;

  void add(std::string what, int frames, std::function<bool(Sandbox&, int)> act);
  void atSize(int width, int height);
  /// The pointer onto `where`'s centre, pressed, released; `then` runs two frames later (the
  /// frame after ImGui acted on the release has been drawn).
  void click(const std::string& what, Where where, std::function<void(Sandbox&)> then = {});
  void openBuildMenu();
  void pickTool(Authoring::Tool tool);
  void viewClick(const Vec2& world);
  /// Ctrl+click on the field `where` of the Build menu's "next body" submenu, `text` typed,
  /// Enter; the menu stays open.
  void typeInField(const std::string& field, Where where, const std::string& text);
  void key(SDL_Keycode k);
  void shot(const std::string& name);
  void wait(int frames);
  void buildMechanism();
  void runAndDrag(int width);
  std::string finalReport(const Sandbox& sandbox) const;

  Uint32 windowId_;
  std::string out_, report_ = "{}", size_;
  std::vector<Step> steps_;
  size_t step_ = 0;
  int stepFrame_ = 0;
  std::string pending_;     ///< a view whose screenshot the last frame took
  Vec2 at_ = Vec2::Zero();  ///< the point of the click in progress (px)
  std::vector<std::string> views_, picks_, newScenes_, fields_, builds_, banners_;
  double before_ = 0;      ///< the field's value before the text was typed
  bool building_ = false;  ///< between New scene and Esc: the view should hold still
  Camera buildCamera_;
  int buildViewMoves_ = 0, clicksOffView_ = 0;
  int body_ = -1;
  Vec2 from_ = Vec2::Zero(), to_ = Vec2::Zero();
};

}  // namespace cablelab::ui
