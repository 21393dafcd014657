#include "engine/statics/box_reduction.h"

namespace cablelab {

StaticsCable reduceBoxCable(const BoxCable& cable) {
  StaticsCable out;
  out.a = cable.a - cable.cornerA;
  out.b = cable.b - cable.cornerB;
  out.k = cable.k;
  out.L = cable.L - (cable.cornerB - cable.cornerA).norm();
  return out;
}

StaticsProblem reduceBoxToPoint(const std::vector<BoxCable>& cables,
                                std::optional<Vec2> boxPosition) {
  StaticsProblem problem;
  problem.cables.reserve(cables.size());
  for (const BoxCable& c : cables) problem.cables.push_back(reduceBoxCable(c));
  problem.p0 = boxPosition;
  return problem;
}

}  // namespace cablelab
