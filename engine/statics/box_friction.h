// Statics of a box that may turn, held by membranes with friction at its corners
// (docs/control.md#membrane-friction): pose q = (x, y, theta) with stick and slip.
//
// A membrane runs fingertip a -> corner A -> (along the box) -> corner B -> fingertip b. With
// friction its two free spans carry different tensions: each is a spring of its own unstretched
// material, r_A and r_B (the whole membrane's k and material L give span stiffness k L / r, so
// one strain throughout gives the frictionless tension k (l - L)):
//   T_A = k L / r_A max(0, l_A(q) - r_A),   T_B = k L / r_B max(0, l_B(q) - r_B).
// Sticking, the materials are fixed and the pose minimises
//   E(q) = sum k L / (2 r) max(0, l(q) - r)^2   over both spans of every membrane,
// a smooth 3-variable energy (Newton as box_pose.h). The corners hold while
// T_high <= e^(mu theta) T_low, theta(q) the angle the membrane turns at its two corners; beyond,
// material slides over the corners to the tighter span until the ratio is e^(mu theta) exactly.
// The problem is incremental (friction remembers): it starts from the materials it is given, and
// returns the ones it ends with.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/statics/box_pose.h"

namespace cablelab {

/// A membrane round the box with friction at its corners.
struct FrictionBoxCable {
  BoxCable cable;    ///< fingertips, corners; k the whole membrane's (N/m), L its material (m)
  double mu = 0;     ///< friction coefficient between membrane and box
  double restA = 0;  ///< material of the free span a -> corner A (m)
  double restB = 0;  ///< material of the free span corner B -> b (m)
};

/// Per membrane at a pose: its span tensions (N) and the capstan ratio e^(mu theta).
struct FrictionSpans {
  double tensionA = 0, tensionB = 0;
  double turn = 0;   ///< rad, theta: the turn at both corners together
  double ratio = 1;  ///< e^(mu theta)
};

/// Shares each membrane's material over its pieces at one strain at pose q (a membrane that has
/// just wrapped the box): both spans then carry the frictionless tension.
void shareMaterial(std::vector<FrictionBoxCable>& cables, const BoxPose& q);

FrictionSpans frictionSpans(const FrictionBoxCable& c, const BoxPose& q);

/// The sticking energy E(q) (J) at the cables' materials; gradient and Hessian when asked.
double frictionBoxEnergy(const std::vector<FrictionBoxCable>& cables, const BoxPose& q,
                         Eigen::Vector3d* gradient = nullptr, Eigen::Matrix3d* hessian = nullptr);

struct FrictionBoxResult {
  BoxPose pose = BoxPose::Zero();
  std::vector<FrictionBoxCable> cables;  ///< with the materials after any slide
  std::vector<int> sliding;  ///< per membrane: 0 holds, +1 slid towards span A, -1 towards B
  std::vector<FrictionSpans> spans;
  int iterations = 0;  ///< stick solves
  bool converged = false;
};

/// Stick, then slide where the capstan ratio is broken, until both hold at the same pose.
FrictionBoxResult solveFrictionBoxPose(const std::vector<FrictionBoxCable>& cables,
                                       const BoxPose& start, double size = 1.0);

/// d pose* / d fingertips at a solved equilibrium (3 x 4N, columns a_i.x, a_i.y, b_i.x, b_i.y):
/// holding membranes keep their materials; sliding ones keep T_tight = e^(mu theta) T_loose.
/// Zero where the equilibrium is not isolated.
Eigen::MatrixXd frictionBoxSensitivity(const FrictionBoxResult& equilibrium);

}  // namespace cablelab
