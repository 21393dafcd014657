// After each Box2D step: the jointed bodies' velocities carried onto the joints' new pose
// without losing energy (docs/model.md, "Coupling to Box2D").
//
// Box2D makes the velocities agree with the joints at the start of its step, then moves the
// bodies. At the new pose the joints have turned, so those velocities cut slightly across them,
// and the next step's joint solve takes that part out: about (h omega)^2 / 2 of a swinging
// link's kinetic energy every step (a pendulum on a revolute joint, let go 0.2 rad out, lost 17%
// of its energy in a minute at 60 Hz, 4.7% at 4 sub-steps). Here each joint tree (joint_tree.h) is
// projected onto its joints at the new pose and scaled back to the kinetic energy it had, so the
// joints' rates carry over and the next solve has nothing to take out. Groups that are not trees
// hanging from bodies that do not move (loops, jointed groups floating free) are left to Box2D.
// Private to engine/dynamics.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/joint_tree.h"

namespace cablelab {

class JointEnergy {
 public:
  /// The bodies at the start of a step (keep() balances the energy of free swings against it).
  void remember(std::span<const BodyState> bodies);

  /// `joints` as the bridge reads them now; `bodies` the state after the step. Changes the
  /// velocities of the jointed bodies in `bodies` and lists those bodies in `changed`.
  void keep(std::span<const JointFrame> joints, std::vector<BodyState>& bodies,
            std::vector<int>& changed);

  /// After keep() (or alone where the joints hardly turned): each group of bodies joined by
  /// joints without limits on which only gravity (m/s^2) and the joints acted over the step
  /// (`swinging`, per body) keeps its kinetic plus gravity's energy since remember() (Box2D's
  /// symplectic Euler swings a pendulum's by about omega h / 2). Adds the bodies it changed to
  /// `changed`.
  void keepSwingEnergy(std::span<const JointFrame> joints, std::vector<BodyState>& bodies,
                       std::vector<int>& changed, std::span<const char> swinging,
                       const Vec2& gravity);

 private:
  JointTree tree_;
  std::vector<int> jointIndex_, dofOfBody_, bodyOfDof_;
  Eigen::VectorXd invM_, v_;
  std::vector<BodyState> start_;   // remember()
  std::vector<int> group_;         // body -> its joined group's root, -1: none
  std::vector<char> groupSwings_;  // per root: every body of the group swinging
  std::vector<char> groupOwed_;    // per root: starts where the last step left it
  std::vector<double> startEnergy_, endPotential_, endKinetic_;  // per root (J)
  std::vector<double> owed_;     // per root: the energy the last step could not give back (J)
  std::vector<BodyState> left_;  // the bodies as the last step left them
};

}  // namespace cablelab
