// Joint limits in the cable solve (docs/model.md, "Joint limits").
//
// Box2D holds a limited joint's coordinate q in [lower, upper] with a one-sided row that lets it
// reach a bound within the step and no further: q' >= -max(q - lower, 0) / h at the lower bound,
// q' <= max(upper - q, 0) / h at the upper. The cable solve projects onto the joints' equality
// rows only, so it solves each island with its limits free first. A limited joint whose
// end-of-step rate would then cross its bound is locked at the rate that reaches it, and the
// island is solved again: the cables see the arm stop, as Box2D will stop it. Without this, a
// 5 kg weight on a rigid rope from an arm at its stop stretched the rope 32 cm at the jerk and
// still 16 cm after 5 s (the solve kept predicting that the arm gives way). A lock is kept for
// the rest of the sub-step, never released within it: one solve more per joint that reaches a
// bound. Private to engine/dynamics.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/box2d_bridge.h"

namespace cablelab {

class JointLimits {
 public:
  /// Frees every joint of `island` (indices into the joints).
  void free(std::span<const int> island, int jointCount);
  /// The rate joint j is held at, or none.
  std::optional<double> lock(int j) const {
    if (j < static_cast<int>(locked_.size()) && locked_[j]) return rate_[j];
    return std::nullopt;
  }
  /// Holds joint j's coordinate at `rate` (free() to release).
  void lockAt(int j, double rate);
  /// Whether any joint is held (most sub-steps none: the projections then ask no joint).
  bool anyLocked() const { return lockedCount_ > 0; }

  /// Locks each limited, free joint of `island` whose rate at the end-of-step velocities `v1`
  /// (the dofs as `dofOfBody` numbers them; other bodies at their own velocity) crosses its
  /// bound within h. True if it locked one (solve the island again).
  bool lockCrossing(std::span<const JointFrame> joints, std::span<const int> island,
                    std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                    const Eigen::VectorXd& v1, double h);

 private:
  std::vector<char> locked_;
  std::vector<double> rate_;
  int lockedCount_ = 0;  // how many of locked_ are set
};

}  // namespace cablelab
