// The joints' servos, implicit in the step (docs/servos.md): each servo's force is its PD law on
// the joint's coordinate and rate at the END of the Box2D step,
//     f = kp (target(t + h) - q(t + h)) + kd (speed - qdot(t + h)),   |f| <= max_force,
// with q(t + h) = q + h qdot(t + h) as Box2D integrates. The end-of-step rates follow from the
// forces through the joints' effective inertia: the mass of the jointed bodies seen along each
// servo's coordinate once the joints (and taut rigid cables) hold (the joint projection,
// joint_projection.h), with gravity, the user's loads and the elastic cables' pull. So the force is
// the root of a small linear system, clamped to max_force: stable at any kp, kd and step, where the
// PD on the start-of-step state alternated once kd h / I or kp h^2 / I passed 2. Private to
// engine/dynamics.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/model/scene.h"

namespace cablelab {

class ServoDrive {
 public:
  /// The scene's servos, and the bodies their joints tie them to (`jointBodies`: body A, body B
  /// per joint, -1 the world).
  ServoDrive(const SceneDef& scene, std::span<const std::array<int, 2>> jointBodies);

  /// Every servo's force over a Box2D step of dt (N or N m, in forces()), its loads added to
  /// `loads` (fx, fy, torque per body, which hold the user's loads on entry). `frames`: the
  /// joints now; `coordinates`: their values and rates; `cables`: their paths and the last
  /// step's tensions; `targets`: the servo targets now (rad or m; each moves on at its servo's
  /// speed over the step).
  void solve(std::span<const JointFrame> frames, std::span<const JointCoordinate> coordinates,
             std::span<const BodyState> bodies, std::span<const Cable> cables,
             std::span<const double> targets, const Vec2& gravity, double dt,
             std::vector<Vec3>& loads);

  /// Per joint, the force the last solve() applied (N or N m; 0 for joints without a servo).
  std::span<const double> forces() const { return forces_; }
  bool any() const { return !servos_.empty(); }
  /// The bodies were moved or their velocities set: the next solve() cannot compare the joints'
  /// rates with the last prediction (no servo is found held from it).
  void forgetMotion();

 private:
  void addCables(std::span<const Cable> cables, std::span<const BodyState> bodies);
  void solveForces(std::span<const JointCoordinate> coordinates, std::span<const double> targets,
                   double dt);
  bool updateActiveCables(size_t jointRows, double dt);
  void findHolds(std::span<const JointCoordinate> coordinates);
  bool releaseHolds(size_t jointRows, double dt);
  void recordPrediction(double dt);

  const SceneDef& scene_;
  std::vector<int> servos_;     // joints with a servo
  std::vector<int> joints_;     // every joint jointed to a servo's bodies (the rows)
  std::vector<int> dofBodies_;  // the dynamic bodies those joints tie together
  std::vector<double> forces_;  // per joint
  // Scratch, reused.
  std::vector<int> dofOfBody_, dofList_;  // this solve's dofs: dofBodies_, then cables' bodies
  std::vector<Vec3> cableLoads_;          // per body: the elastic cables' pull
  std::vector<JointRow> rows_, coordinateRows_, cableRows_;
  JointProjection projection_;
  Eigen::VectorXd invM_, vStar_;
  Eigen::MatrixXd W_, A_;
  Eigen::VectorXd rhs_, upper_, f_;
  Eigen::VectorXd vStarFree_;  // v* and W before the projection (each active-set pass starts there)
  Eigen::MatrixXd WFree_, multipliers_;
  Eigen::VectorXd fAllRows_;       // the forces with every rigid span's row
  std::vector<double> cablePull_;  // per rigid span's row: its last tension (N)
  std::vector<char> cableActive_;  // per rigid span's row: kept (it pulls)
  // Holds (docs/servos.md, "Held joints"), per servo: the direction a load the prediction does not
  // see holds its joint against (+1, -1; 0 none), and what the last solve predicted.
  std::vector<signed char> held_, pushed_;  // pushed_: the sign of the last force
  std::vector<double> expectedRate_;        // the joint's rate at the step's end (NaN: unknown)
  std::vector<int> stoppedSteps_;           // steps in a row that stopped the joint unexpectedly
  std::vector<int> holdRows_;               // servos whose coordinate rows hold in this pass
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};

}  // namespace cablelab
