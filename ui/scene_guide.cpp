#include "ui/scene_guide.h"

#include <map>

#include "engine/core/error.h"

namespace cablelab::ui {
namespace {

struct Guide {
  const char* description;  // two to four plain sentences: what it is, what to watch
  const char* tryThis;      // steps that work in the window with the default settings
};

const std::map<std::string, Guide>& guides() {
  static const std::map<std::string, Guide> g = {
      {"ballast",
       {"A small point flies into a cable that is pulled tight between two fixed eyelets. The "
        "cable's other end carries a ballast, and there is no gravity. Watch the ballast: it "
        "starts moving the moment the point hits the cable.",
        "Press Space to pause, then s to step through the impact one frame at a time.\n"
        "Drag the v0y slider (Parameters) to 3 and let go: the faster point jerks the ballast "
        "harder.\nPress r to run it again."}},
      {"hand",
       {"A soft two-finger hand seen from above holds a square box between two stretchy "
        "bands. A controller moves the fingers so that the bands carry the box to the target "
        "(the magenta cross). The fingers and the box pass through each other on purpose: "
        "only the bands touch the box.",
        "Click empty space: the box moves to the new target.\n"
        "Press open (grasp) in the Controller section: the fingers open, close on the box and "
        "take hold of it again.\n"
        "Set the drag limit (View section) to 20, drag the box far out of the bands and let go: "
        "the hand loses its grasp and reaches for the box again."}},
      {"hexagon",
       {"A weight hangs on a cable wrapped round a hexagon that turns on an axle. As the "
        "hexagon turns, the cable touches its corners one after another. The small squares "
        "show where the cable touches.",
        "Watch the squares jump from corner to corner as the hexagon swings.\n"
        "Drag the weight sideways: the cable winds on or off the hexagon.\n"
        "Press Space to pause, drag the weight to a new place, then Space to let it swing "
        "from there."}},
      {"membrane",
       {"A weighted point is pressed into a stretchy band held between two pulleys. The band "
        "stretches until its pull balances the weight. The blue arrow is the force the band "
        "model predicts.",
        "Drag the point into the band and let go: it bounces and settles where the band's "
        "pull balances its weight.\n"
        "Select the band (click it) and watch its tension in the Inspector as the point "
        "bounces."}},
      {"pulley",
       {"Two bodies hang from one cable over two pulleys fixed to the ceiling. The heavier "
        "left body sinks and pulls the lighter one up; the cable keeps the same length "
        "throughout.",
        "Watch the colour of the cable: one tension everywhere along it.\n"
        "Drag m_left (Parameters) down to 1 and let go: the two bodies balance.\n"
        "Drag one body down and let go: the other follows."}},
      {"wheel",
       {"Two boxes hang from a cable over a heavy wheel that turns with the cable. The "
        "heavier left box sinks, but the wheel has to be spun up too, so it sinks more "
        "slowly than over a light pulley.",
        "Watch the wheel's spoke turn as the boxes move.\n"
        "Drag the I slider (the wheel's inertia) to 0 and let go: the boxes move faster.\n"
        "Drag a box and let go: the wheel turns with it."}},
      {"capstan",
       {"A rope wraps round a fixed drum with friction, holding a heavy load with a light "
        "weight. Friction lets a small pull hold a big one, up to a limit that grows with "
        "every turn of rope. Past that limit the rope slips.",
        "Select the rope (click it) and watch the two tensions in the Inspector.\n"
        "Drag the m_load slider to 6 and let go: the rope slips and the load falls.\n"
        "Drag the turns slider up and let go: more turns hold a heavier load."}},
      {"winch",
       {"A motor turns a drum that winds up a cable and lifts a weight. Each turn of the drum "
        "takes in one drum's circumference of cable.",
        "Watch the weight rise as the cable winds on.\n"
        "Drag the omega slider (drum speed) below 0 and let go: the drum lets the weight "
        "down.\nPress r to start again."}},
      {"tackle",
       {"A block and tackle: one rope runs over pulleys up and down four times, so the small "
        "effort weight on its end lifts a load four times heavier. The effort moves four "
        "times as far as the load.",
        "Watch the effort sink four times as far as the load rises.\n"
        "Drag the m_effort slider to 1 and let go: effort and load balance.\n"
        "Press Space to pause, drag the load down, then Space: the effort rises."}},
  };
  return g;
}

}  // namespace

std::string studentDescription(const std::string& name) {
  const auto it = guides().find(name);
  return it == guides().end() ? "" : it->second.description;
}

std::string sceneMenuTip(const std::string& name, const std::string& fallback) {
  const std::string all = studentDescription(name);
  if (all.empty()) return fallback;
  const size_t end = all.find(". ");
  return end == std::string::npos ? all : all.substr(0, end + 1);
}

std::string whatToTry(const std::string& name) {
  const auto it = guides().find(name);
  if (it != guides().end()) return it->second.tryThis;
  return "Drag a body with the left mouse button; right-drag pans, the wheel zooms.\nSpace "
         "pauses, s steps, r resets.";
}

std::string parameterTip(const std::string& description, double value) {
  // The unit from the description's last "(...)": "left body mass (kg)" -> "kg".
  const size_t open = description.rfind(" (");
  const std::string unit = open != std::string::npos && description.back() == ')'
                               ? " " + description.substr(open + 2, description.size() - open - 3)
                               : "";
  return description + "\nDefault " + formatNumber(value) + unit +
         ". Let go of the slider to start the scene again with the new value (Ctrl+click to "
         "type one).";
}

}  // namespace cablelab::ui
