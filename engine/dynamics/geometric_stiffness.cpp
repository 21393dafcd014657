#include "engine/dynamics/geometric_stiffness.h"

#include <algorithm>

namespace cablelab {

namespace {

// Whether a segment of the path could pass the stiffness test below: a segment's Hessian block
// has trace 1 / length (appendLengthHessianTranslation), so this bounds the test without
// building the blocks. A cable that cannot needs none.
bool mayBeStiff(double h2Tension, std::span<const WrapPoint> path, std::span<const int> dofOfBody,
                const Eigen::VectorXd& invM) {
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i].body, b = path[i + 1].body;
    if (a == b) continue;
    const Vec2 from = path[i].leaving();
    const Vec2 to = path[i + 1].arriving();
    double invMass = 0;
    for (int e : {a, b})
      if (e >= 0 && dofOfBody[e] >= 0) invMass = std::max(invMass, invM[dofOfBody[e]]);
    if (h2Tension * invMass > 0.04 * (to - from).norm()) return true;
  }
  return false;
}

}  // namespace

void addGeometricStiffness(const Cable& cable, double pulling, double h,
                           std::span<const int> dofOfBody, const Eigen::VectorXd& invM,
                           std::vector<StiffnessBlock>& blocks, std::vector<TautCable>& taut,
                           bool& stiff) {
  const double tension =
      std::max(pulling, cable.elastic() ? cable.stiffness() * std::max(0.0, cable.stretch()) : 0.0);
  if (tension <= 0 || !mayBeStiff(h * h * tension, cable.path(), dofOfBody, invM)) return;
  const size_t begin = blocks.size();
  appendLengthHessianTranslation(cable.path(), blocks);
  for (size_t i = begin; i < blocks.size(); ++i) {
    const StiffnessBlock& blk = blocks[i];
    if (blk.a == blk.b && dofOfBody[blk.a] >= 0)
      stiff |= h * h * tension * blk.k.trace() * invM[dofOfBody[blk.a]] > 0.05;
  }
  taut.push_back({tension, begin, blocks.size()});
}

}  // namespace cablelab
