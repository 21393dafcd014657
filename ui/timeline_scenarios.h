// The rewind and plot scenarios of `cablelab-gui --script NAME` (ui/scenario_script.h runs them):
//
//   rewind       the hand, its controller driving the box to a target: 150 steps recorded, 30
//                presses of b (step back), Space (play on) and 60 frames; reports whether the
//                stepped-back moment and the replay equal the recorded run (largest difference,
//                m and rad), the timeline's frames and bytes, and whether the h list has b;
//                ends paused, rewound one step (the screenshot shows the Timeline row)
//   plot-export  the hand with three charts (controller error; box x and y; both membranes'
//                tensions), 2 s shown; a target 5 m away for 0.5 s, then one near the box for
//                2.3 s; reports the error chart's range with the far target in view and after,
//                exports every chart to --script-out-N.png/.csv at 1600 x 900 and reports the
//                files and the error chart's last sample
//
// Needs: an SDL video subsystem (synthetic keys), a Sandbox with the hand scene.
#pragma once

#include <SDL.h>

#include <string>
#include <vector>

#include "ui/sandbox.h"

namespace cablelab::ui {

class TimelineScenario {
 public:
  static const std::vector<std::string>& names();
  TimelineScenario(std::string name, Uint32 windowId, std::string out);
  /// Called once per frame before events are polled; false when finished (`report` set).
  bool beforeFrame(Sandbox& sandbox, int frame, std::string& report);

 private:
  bool rewind(Sandbox& sandbox, int frame, std::string& report);
  bool plotExport(Sandbox& sandbox, int frame, std::string& report);

  std::string name_, out_;
  Uint32 windowId_;
  std::vector<std::vector<double>> recorded_;  ///< rewind: poses after step k (index k)
  bool equalAfterBack_ = false;
  long stepAfterBack_ = -1;
  double largest_ = 0;  ///< rewind: the largest difference in the replay
  int compared_ = 0;
  double rangeFar_[2] = {0, 0};
};

}  // namespace cablelab::ui
