#include "ui/scene_guide.h"

#include <map>

namespace cablelab::ui {

std::string whatToTry(const std::string& name) {
  static const std::map<std::string, std::string> guide = {
      {"ballast",
       "Watch the ballast: it starts towards the pulley at once (2 v0y^2 / l) while the point "
       "barely moves.\nRaise v0y or shorten l with the sliders and compare.\nStep frame by "
       "frame (s) through the first impact."},
      {"hand",
       "Click empty space to move the target: the Jacobian controller carries the box there.\n"
       "Start grasp runs the track sequence: open pose, closing ramp, grasp, control.\nLower "
       "k or raise box_mass and watch the membranes give; drag the box out to lose the grasp."},
      {"hexagon",
       "Watch the wrap points (squares) jump from vertex to vertex as the hexagon turns.\nDrag "
       "the weight to wind or unwind the cable; pause and drag to pose it.\nRaise omega to spin "
       "the hexagon faster."},
      {"membrane",
       "The blue arrow is the chapter 3 model force -T (u1 + u2) at the finger.\nDrag the "
       "point into the band and let go: it settles where the force balances its weight.\nLoad "
       "k and preload from a `cablelab fit` JSON and compare."},
      {"pulley",
       "The heavier left body falls with a = g (m1 - m2) / (m1 + m2).\nSet m_left = m_right "
       "for a balance, then drag one side.\nCompare with Box2D's pulley joint test."},
      {"wheel",
       "An Atwood machine whose wheel turns with the cable: a = g (m1 - m2) / (m1 + m2 + I/r^2)."
       "\nRaise I to slow it down; set m1 = m2 to balance it."},
      {"capstan",
       "The rope holds while m_load / m_hold <= e^(mu theta).\nAdd turns or friction (mu) to "
       "hold a heavier load; raise m_load until it slips."},
      {"winch",
       "The driven drum winds the cable and lifts the weight, turn after turn.\nChange omega or "
       "r to change the lifting speed (r omega)."},
  };
  const auto it = guide.find(name);
  if (it != guide.end()) return it->second;
  return "Drag a body with the left mouse button; right-drag pans, the wheel zooms.\nSpace "
         "pauses, s steps, r resets.";
}

}  // namespace cablelab::ui
