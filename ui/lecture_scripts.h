// LectureScript: the scripted checks of the sandbox in a lecture hall (`cablelab-gui --script
// NAME`, dispatched by ui/scenario_script.h), driven by synthetic SDL events and the same calls
// the menus make. Each reports one JSON object; tests/ui/lecture_test.cpp judges the figures.
//
//   present       p (presentation mode), then the UI scale down and up again (projector mode),
//                 the window resized and back, the next built-in scene, Space (pause), p again;
//                 after each, what the view showed (ui/renderer.h DrawnView: the scene's box,
//                 every label, the bars, the key, the banner, the PAUSED sign), the free area,
//                 the panels' and the status line's overflow, and a screenshot
//                 (--script-out PREFIX: PREFIX-NAME.png)
//   grasp-quiet   the hand: the grasp sequence (the panel's "open (grasp)"), then a click on
//                 empty space (a new target) and 4 s of control; reports every banner shown and
//                 the log's size
//   tension-run   a hard drag, a reset, then the scale locked and the next scene opened; reports
//                 the colour bar's maximum over every frame and the scenes' load scales
//   walkthrough   a lecture with one scene: projector mode and p, screenshots at the start, after
//                 3 s and 10 s, while dragging the body at a cable's end and after the drop,
//                 after the scene's "what to try" slider step (the hand: the grasp sequence),
//                 paused, after 60 presses of b (rewind) and after playing on (the capstan: then
//                 its turns slider to 2, "more turns hold a heavier load"); reports each view
//   select-rope   clicks a point of a cable (none of a body) in the view; reports whether the
//                 Inspector was open before and after, the cable selected and the Inspector's
//                 row overflow
//   tour          the built-in scenes the walkthrough tests do not walk (ballast, pulley, hexagon,
//                 membrane, hand), each opened from the Scene menu in presentation mode at
//                 projector scale, 1280x720: the body at a cable's end dragged (the hexagon's onto
//                 the colour bar, then onto the scale bar), the scene's "what to try" step (the
//                 membrane's: a click on the band), Space; then 1920x1080 paused and running
//                 again; the pulley's run recorded as a clip (F9 twice, into the working
//                 directory) before its "what to try" view. Reports each view (with the notes'
//                 texts) and every banner shown
//   first-mechanism  a student's first mechanism in presentation mode at projector scale, at
//                 1280x720 then 1920x1080, every step a click on the top bar's Build menu, its
//                 items and fields or the view (ui/first_mechanism_script.h)
//   laptop        every built-in scene opened from the Scene menu out of presentation mode, at
//                 the window's size and text size (--ui-scale); reports each view (with the panels'
//                 rectangles: a collapsed Inspector is its title bar)
//   hand-export   the hand: 2.5 s of control, then the wheel over the Simulation panel until the
//                 Controller section's "Export PNG" is in view, a screenshot of the thumbnails
//                 above it (OUT-thumbnails.png) and a click on it; reports the message shown (the
//                 files written in the working directory) and the thumbnails' legend rectangles
//   follow        projector mode and p, then 25 s of the scene's run untouched: the largest change
//                 of the view's scale between two frames of one run and the most it zoomed back
//                 in within a run (a ratio of scales), the frames in which a body
//                 moves and those in which none of the moving ones is in view, those in which the
//                 body the close-up followed down (ui/presentation.h) is at rest out of it, and
//                 screenshots after 1, 4, 6, 10 and 20 s (the walkthrough reports the same of its
//                 first 10 s)
//
// Needs: an SDL video subsystem (the sandbox's Window), a Sandbox with a loaded scene.
#pragma once

#include <SDL.h>

#include <memory>
#include <string>
#include <vector>

#include "ui/sandbox.h"

namespace cablelab::ui {

class FirstMechanismScript;  // ui/first_mechanism_script.h

/// What the last frame showed, as JSON: the scene's box, every label, the bars, the key, the
/// banner, the PAUSED sign (ui/renderer.h DrawnView), the free area, the panels' and the status
/// line's overflow, the Build menu's layout, and `shot` (the screenshot's path).
std::string lectureViewJson(const Sandbox& s, const std::string& name, const std::string& shot);

class LectureScript {
 public:
  static const std::vector<std::string>& names();
  /// `out`: the prefix of the screenshots' paths.
  LectureScript(std::string name, Uint32 windowId, std::string out);
  ~LectureScript();
  /// Called once per frame before events are polled; false when the script has finished.
  bool beforeFrame(Sandbox& sandbox, int frame);
  std::string report() const { return report_; }

 private:
  bool present(Sandbox& sandbox, int frame);
  bool graspQuiet(Sandbox& sandbox, int frame);
  bool tensionRun(Sandbox& sandbox, int frame);
  bool walkthrough(Sandbox& sandbox, int frame);
  bool selectRope(Sandbox& sandbox, int frame);
  bool tour(Sandbox& sandbox, int frame);
  bool firstMechanism(Sandbox& sandbox, int frame);
  bool laptop(Sandbox& sandbox, int frame);
  bool handExport(Sandbox& sandbox, int frame);
  bool follow(Sandbox& sandbox, int frame);
  /// Adds this frame of an untouched run to the follow figures (followJson()).
  void watchFollow(const Sandbox& sandbox);
  std::string followJson() const;
  void key(SDL_Keycode k);
  void mouse(Uint32 type, const Vec2& screen);
  void projectorScale(Sandbox& sandbox);
  /// Records the view whose screenshot the last frame took, if any.
  void recordPendingView(Sandbox& sandbox);
  /// Takes a screenshot of the whole window this frame, named `name`; its view is recorded next
  /// frame (the view drawn in the frame the screenshot was taken of).
  void snapshot(Sandbox& sandbox, const char* name);

  std::string name_, out_, report_ = "{}";
  Uint32 windowId_;
  std::vector<std::string> items_;  ///< JSON pieces gathered so far
  std::string pending_;             ///< a view to record next frame (its screenshot was taken)
  int body_ = -1;
  Vec2 from_ = Vec2::Zero(), to_ = Vec2::Zero();
  Vec2 target_ = Vec2::Zero();  ///< grasp-quiet: the point clicked (m)
  double lowest_ = 1e300, highest_ = -1e300, largest_ = 0;
  int bannerFrames_ = 0;
  int clickStage_ = 0;                ///< hand-export: 0 not yet, 1 pressed, 2 released
  std::string plotLabels_;            ///< hand-export: the thumbnails' legend texts (JSON)
  int pointerAway_ = 0;               ///< hand-export: frames the pointer was off the plots
  int width_ = 0, height_ = 0;        ///< present: the window's size before the resize
  std::vector<std::string> banners_;  ///< tour: every banner shown, "scene: text"
  std::string shotName_;              ///< tour: the screenshot's name, "scene-what"
  std::unique_ptr<FirstMechanismScript> first_;
  // follow and walkthrough: how the view followed the run (watchFollow()).
  double lastScale_ = 0;        ///< m per px in the last frame watched (0: none yet)
  int lastRestarts_ = 0;        ///< the demo's restarts then
  double largestZoomStep_ = 1;  ///< the largest ratio of two frames' scales in one run
  double widestInRun_ = 0;      ///< the largest scale (m per px) in this run so far
  double largestZoomIn_ = 1;    ///< the largest ratio of that to a later scale in the run
  int movingFrames_ = 0, movingOutOfViewFrames_ = 0;
  int followedOutOfViewFrames_ = 0;  ///< frames the close-up's followed body was out of view
};

}  // namespace cablelab::ui
