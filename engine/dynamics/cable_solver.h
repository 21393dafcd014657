// The cable solver: the tensions of every cable for one sub-step, as forces Box2D then applies.
//
// Box2D integrates v1 = v0 + h M^-1 F and q1 = q0 + h v1 (a jointed body turns about its
// pivot: step_pose.h, and World leaves it there). The solver picks the cable forces so
// that the cable lengths at the END of the sub-step are right (a SHAKE-like position-level
// condition, docs/model.md). Cables and the moving bodies they connect (through cables or
// joints) form islands, solved one after the other, so the cost grows with the islands' sizes,
// not with the square of the world's. Per island, in named stages: cable_solver.cpp lists them, one
// file (cable_solver_*.cpp) per stage or family of stages.
// Private to engine/dynamics.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/world.h"

namespace cablelab {

/// A pose to put a body at after Box2D's step (`place`), or none.
struct Placement {
  bool place = false;
  Vec2 position = Vec2::Zero();
  double angle = 0;
};

/// What one solve reads: the sub-step, the bodies now, and the joints among them.
struct CableSolveInput {
  double h = 0;  ///< sub-step (s)
  /// h over the nominal sub-step (<= 1): a step cut short at a wrap event fixes only this share
  /// of a rigid cable's length error, so the correcting velocity does not grow as h shrinks.
  double share = 1;
  Vec2 gravity = Vec2::Zero();                        ///< m/s^2
  std::span<const BodyState> bodies;                  ///< start of the sub-step
  std::span<const JointFrame> joints;                 ///< every joint, indexed as the scene's
  std::span<const std::vector<int>> jointNeighbours;  ///< bodies jointed to each body
  /// Per cable, 1: another solve (the midpoint one) has set its tension this step; its islands
  /// share no moving body with the rest. Empty: every cable is this solve's.
  std::span<const char> skip;
  /// Per body, 1: in a touching contact (empty: none). Such islands keep Box2D's integration.
  std::span<const char> touching;
  /// Per body, a velocity World adds after Box2D's step (empty: none). An island of undamped
  /// elastic cables on jointed bodies takes the implicit midpoint rule through it (stage 5).
  std::span<Vec3> kicks;
  /// Per body, the pose World gives it after Box2D's step (empty: none): where the midpoint rule
  /// balanced the cable's energy for a jointed body, which Box2D's joint correction would miss
  /// by (h omega)^3 or so.
  std::span<Placement> placements;
  /// Per body, the contact force (fx, fy, torque) Box2D is expected to apply over the step
  /// (World::expectContacts; empty: none): part of the predicted motion, not applied.
  std::span<const Vec3> contacts;
};

struct CableSolverWorkspace;  // the stages' buffers (cable_solver_stages.h)

/// Off: Newton always runs, never the start-of-step linearisation alone (tests compare the two).
void setLinearShortcut(bool on);
/// Off: floor rows start Newton at 0 and Newton always runs, never keeping the last sub-step's
/// impulses for a body resting at its pulley (docs/floors.md; tests compare the two).
void setKeptImpulses(bool on);

class CableSolver {
 public:
  /// `restitution`: per body, the largest of its shapes' (a floor bounces, docs/floors.md).
  explicit CableSolver(std::vector<double> restitution = {});
  ~CableSolver();
  CableSolver(const CableSolver&) = delete;
  CableSolver& operator=(const CableSolver&) = delete;

  /// Sets every (not skipped) cable's tension and adds to `loads` (fx, fy, torque per body, already
  /// holding gravity-free external loads) the forces that realise them. Adds its LCP figures to
  /// `stats`.
  void solve(const CableSolveInput& in, std::span<Cable> cables, std::span<Vec3> loads,
             StepStats& stats);

 private:
  std::unique_ptr<CableSolverWorkspace> ws_;  // reused across sub-steps: no allocation
};

}  // namespace cablelab
