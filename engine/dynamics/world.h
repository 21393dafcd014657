// World: Box2D's rigid bodies, joints and contacts, plus cablelab's cables and membranes.
//
// Coupling (why it is done this way, docs/model.md): Box2D 2.4 has no custom-joint API, so cables
// act through forces applied before each Box2D sub-step. Knowing that Box2D then integrates
// v1 = v0 + h M^-1 F and q1 = q0 + h v1, the force is chosen so that the cable lengths at the END
// of the sub-step are right (a SHAKE-like position-level condition, solved by Newton on the
// end-of-step geometry): this keeps rigid cables at length without drift or a projection pass,
// conserves energy far better than a velocity-level condition, and contains the J-dot-v term
// implicitly. All cables are solved together, one small LCP per Newton iteration (tension >= 0,
// slack allowed). Elastic cables (membranes) enter the same problem as soft constraints
// (implicit spring-damper), and light bodies on tight bands also get the cable's geometric
// stiffness implicitly, which keeps k = 1e4 N/m on 0.01 kg stable at 60 Hz. Box2D then keeps
// contacts, friction and joints (their impulses act after ours; any length error they leave is
// corrected at the next sub-step). See step().
//
// Model and state: the SceneDef is fixed once the World is built (scene()). What changes while
// it runs lives in the World: bodies (in Box2D), cable parameters (Cable::parameters()), gravity
// and servo targets.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "engine/cable/cable.h"
#include "engine/dynamics/contact_force.h"
#include "engine/dynamics/servo_targets.h"
#include "engine/dynamics/stall_watch.h"
#include "engine/dynamics/world_history.h"
#include "engine/model/scene.h"

namespace cablelab {

class Box2DBridge;
class CableIslands;
class JointEnergy;
class CableSolver;
class MidpointSolver;
class ServoDrive;
struct JointCoordinate;
struct JointFrame;
struct Placement;

/// Per-joint state read back from Box2D.
struct JointState {
  std::string name;
  JointDef::Kind kind;
  Vec2 anchorA, anchorB;   ///< world (m)
  double value = 0;        ///< angle (rad) or translation (m)
  double speed = 0;        ///< rad/s or m/s
  double servoTarget = 0;  ///< rad or m
  /// The servo's force (N, prismatic) or torque (N m, revolute) over the last step, positive
  /// along the coordinate: its impulse over the step's dt; 0 without a servo.
  double force = 0;
};

/// What World::poseBody() or settlePose() did.
struct PoseResult {
  Vec2 reached = Vec2::Zero();  ///< poseBody: where the grabbed point ended (world, m)
  double miss = 0;              ///< poseBody: its distance from the target (m): what was held back
  std::vector<int> moved;       ///< bodies the pose moved (each now at rest), ascending
  std::vector<int> taut;        ///< rigid cables at their rest length after the pose
  std::vector<std::pair<int, double>> paidOut;  ///< (cable, m): rest length let out (payOut)
  double longest = 0;  ///< the largest rigid span's length over its rest length after it (m)
};

/// Timing and solver figures of the last step() call.
struct StepStats {
  double stepMicros = 0;   ///< wall time of the whole step (us)
  double cableMicros = 0;  ///< of that, cable geometry + tension solve (us)
  int wrapPoints = 0;      ///< pulley wrap points in use, all cables
  int solverIterations =
      0;  ///< LCP active-set iterations (with those of solves given up), summed over sub-steps
  double residual = 0;             ///< largest complementarity residual of the tension solve
  int linearisationFallbacks = 0;  ///< cable rows solved on the start-of-step Jacobian (guard)
  int keptImpulses = 0;  ///< main-solve islands the last sub-step's impulses still held (no LCP)
  int linearSolves = 0;  ///< main-solve islands whose start-of-step linearisation was exact enough
  int newtonDivergences = 0;  ///< islands whose Newton diverged (solved on the start-of-step J)
  int unsettledIslands = 0;   ///< of those, answers that miss their lengths (World halves the step)
  int heldIslands = 0;        ///< of those, rows no pose meets, held at their lengths (World warns)
  int events = 0;             ///< Box2D steps cut short at a wrap event
  int midpointSolves = 0;     ///< island solves by the energy-consistent midpoint rule
  int midpointFallbacks = 0;  ///< of those tried, not converged (the main solve took it)
  int midpointRedundant = 0;  ///< of the fallbacks, given up at once: redundant rows pull
  int midpointFloorHits = 0;  ///< of the fallbacks, a floor pushed (a body at its pulley)
  int refinements = 0;        ///< Box2D steps shortened: a fast catch, or an unsettled solve
  int selectionSkips = 0;  ///< cable updates that kept the wrap set unsearched (Cable::setSkipping)
  int searchSkips = 0;     ///< event searches skipped: no wrap change can happen in the sub-step
  int sparseIslands = 0;   ///< island solves by the sparse path (big islands, docs/model.md)
};

class World {
 public:
  /// Builds the world; throws InputError (source `source`) if the scene is invalid.
  explicit World(SceneDef scene, const std::string& source = "scene");
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const SceneDef& scene() const { return scene_; }

  /// Advances by dt seconds in `substeps` equal sub-steps. Throws SimulationError on NaN.
  void step(double dt, int substeps = 1);
  double time() const { return time_; }
  long stepCount() const { return steps_; }
  const StepStats& lastStepStats() const { return stats_; }

  // Bodies, indexed as in scene().bodies. Pose and velocity in double precision.
  int bodyCount() const { return static_cast<int>(bodies_.size()); }
  const BodyState& body(int i) const { return bodies_[i]; }
  int findBody(std::string_view name) const;  ///< -1 if unknown
  void setBodyTransform(int i, const Vec2& position, double angle);
  void setBodyVelocity(int i, const Vec2& velocity, double angularVelocity);
  /// Recomputes every cable's path and length from the current poses (after setBodyTransform
  /// while paused, so that what is drawn matches the posed bodies); step() does this itself.
  void refreshCables();
  /// Adds a force (N) at a world point for the next step only.
  void applyForce(int i, const Vec2& force, const Vec2& worldPoint);

  /// Mouse drag, like Box2D's testbed: a soft spring from a point on the body to the target.
  void beginDrag(int body, const Vec2& worldPoint, double stiffnessHz = 5.0);
  void dragTo(const Vec2& target);
  void endDrag();
  int draggedBody() const { return dragBody_; }
  Vec2 dragTarget() const { return dragTarget_; }

  /// Posing while paused (docs/model.md, "Posing"): moves `body` so that its point `grabLocal`
  /// (body frame, m) goes to `target` (world, m) as far as the rigid cables, the joints and
  /// their limits allow; the other dynamic bodies follow with the least mass-weighted motion,
  /// as a pulley system pulled by hand does. Where the target cannot be reached the body stops
  /// at the nearest pose that can. With `payOut` the rigid cables do not hold: each one the pose
  /// lengthens lets out rest length to match. Every body moved ends at rest, and the servos of
  /// the joints it moved hold the new pose (their targets move to it). Call it with small moves
  /// (a mouse's), as the wrap points follow the bodies continuously.
  PoseResult poseBody(int body, const Vec2& grabLocal, const Vec2& target, bool payOut = false);
  /// Brings every rigid cable back within its rest length and every joint together with the
  /// least mass-weighted motion (before a paused world runs again); the bodies moved end at rest.
  PoseResult settlePose();
  /// The largest (length - rest length) of any span of any rigid cable (m): over 0, stretched.
  double longestRigidStretch() const;

  // Cables, indexed as in scene().cables.
  int cableCount() const { return static_cast<int>(cables_.size()); }
  const Cable& cable(int i) const { return cables_[i]; }
  int findCable(std::string_view name) const;  ///< -1 if unknown
  /// Live edits of rest length, stiffness, preload, damping (validated; throws InputError).
  /// The scene keeps the authored values; cable(i).parameters() has the live ones.
  void setCableParameters(int i, double restLength, double stiffness, double preload,
                          double damping);

  // Joints, indexed as in scene().joints.
  int jointCount() const { return static_cast<int>(scene_.joints.size()); }
  JointState joint(int i) const;
  int findJoint(std::string_view name) const;  ///< -1 if unknown
  /// Reached over the next step: the servo's target moves on to it across the sub-steps.
  void setServoTarget(int i, double target);
  /// Taken at once, from the next step's first sub-step: for a controller that samples its joints
  /// each step with its own gains (the hand's, tuned so), as every target was taken before.
  void setServoTargetAtOnce(int i, double target);

  /// Taut rigid cables start a step whose rule or length changes on the rate it ends on, their
  /// start rate turned across them, the kinetic energy kept (start_rates.h, on by default); off
  /// brings back the impulse that took it out (for comparison).
  void setStartRatesMatched(bool on) { matchesStartRates_ = on; }

  void setGravity(const Vec2& g);
  /// Wrap-set skipping on every cable (on by default; the same trajectory either way).
  void setWrapSkipping(bool on);
  /// The energy-consistent solve chosen per cable island (on by default) or, off, for the whole
  /// world at once (every cable or none: the engine before islands, kept for comparison).
  void setMidpointPerIsland(bool on) {
    midpointPerIsland_ = on;
    history_.add({WorldInput::Kind::MidpointPerIsland, on});
  }
  /// Joint trees carried onto each new pose keeping their kinetic energy (on by default;
  /// off: Box2D's own joint solve alone, which loses about (h omega)^2 / 2 of it a step).
  void setJointEnergyKept(bool on) {
    keepsJointEnergy_ = on;
    history_.add({WorldInput::Kind::JointEnergyKept, on});
  }
  Vec2 gravity() const { return gravity_; }

  /// Per pair of bodies in touch, Box2D's contact force over its last step (contact_force.h).
  std::vector<ContactForce> contactForces() const;

  /// Kinetic + gravitational + elastic (membrane) energy (J); an elastic cable split by a polygon
  /// with friction stores each span's and each corner piece's own (Cable::elasticEnergy).
  double energy() const;

  /// Human-readable notes from the guards (zero-length segments merged, ...), newest last.
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// Every input since the World was built; the scene plus this rebuilds it bit for bit
  /// (world_state.h).
  const WorldHistory& history() const { return history_; }

 private:
  void applyServos(double dt);
  void reportStalls(double dt);
  void reportDrumArrivals();
  void checkFinite() const;
  void reportPayOuts();
  void reportOverstretch();
  void reportHeldRows();
  void payOutUnheld();
  void expectContacts(double dt);
  void selectWraps(double h);
  void predictMotion(double dt);
  void solveForces(double dt, double h);
  double advance(double left, double h, bool locate);
  void keepJointEnergy(double dt);
  void flyFreeBodies(double dt);
  void addImpulses(double dt, bool first);
  void averageTensions(double h);
  void reportStepTensions(bool end);
  bool matchRates(double dt, double h);
  bool takesMidpointRule(std::span<const int> island, double dt, double h);
  void recordRates(double dt, bool whole);

  const SceneDef scene_;                      ///< the model: never edited after construction
  std::unique_ptr<Box2DBridge> b2_;           ///< bodies, joints, contacts
  std::unique_ptr<CableSolver> solver_;       ///< tensions, one solve per sub-step
  std::unique_ptr<MidpointSolver> midpoint_;  ///< the energy-consistent solve, where it applies
  std::unique_ptr<CableIslands> islands_;     ///< which solve takes which cables
  std::unique_ptr<JointEnergy> jointEnergy_;  ///< joint velocities carried to the new pose
  std::unique_ptr<ServoDrive> servos_;        ///< the servos' forces, implicit in each step
  bool keepsJointEnergy_ = true;              ///< setJointEnergyKept()
  std::vector<int> reprojected_;              ///< bodies whose velocities keepJointEnergy() changed
  std::vector<BodyState> motion_;             ///< look-ahead or predicted body states (wrap events)
  std::vector<char> excluded_;     ///< bodies the midpoint solve leaves alone (joints, contacts)
  std::vector<char> touching_;     ///< bodies in a touching contact this sub-step
  std::vector<Vec3> contactLast_;  ///< per body, Box2D's mean contact force over the last sub-step
  std::vector<Vec3> contactExpected_;  ///< ... the one the cable solve expects (expectContacts)
  std::vector<Vec3> kicks_;            ///< velocity added after Box2D's step (midpoint rules)
  std::vector<std::pair<int, Vec3>> ends_;  ///< velocities set after it (the midpoint solve's)
  std::vector<char> onCable_;  ///< scratch: bodies on some cable's path (flyFreeBodies)
  std::vector<Placement>
      placements_;             ///< poses given after Box2D's step (the main solve's midpoint rule)
  bool midpointUsed_ = false;  ///< the last solveForces() solved some midpoint island
  bool midpointUnsettled_ = false;     ///< ... and in some island its Newton did not settle
  bool mainUnsettled_ = false;         ///< the main solve's answer missed some island's lengths
  bool midpointPerIsland_ = true;      ///< setMidpointPerIsland()
  std::vector<char> midpointCable_;    ///< per cable: the midpoint solve took it (main solve skips)
  std::vector<int> midpointCables_;    ///< those cables
  bool matchesStartRates_ = true;      ///< setStartRatesMatched()
  std::vector<double> rateSteps_;      ///< per cable: the step its length rate was left by...
  std::vector<double> nextSteps_;      ///< ... and the one about to be taken (start_rates.h)
  std::vector<double> midpointSteps_;  ///< per cable: the midpoint step its rate was left by
  std::vector<int> tautSteps_;         ///< per cable: whole steps in a row it ended taut
  std::vector<char> tookMidpoint_;     ///< scratch: per cable, the midpoint solve took it
  bool rulesKept_ = false;             ///< matchRates ran: solves keep tookMidpoint_'s rules
  int cutCable_ = -1;                  ///< the last Box2D step ended at this cable's event...
  WrapEvent cutEvent_;                 ///< ...this one (-1: it ran to its end)
  std::vector<BodyState> bodies_;      ///< read back from Box2D
  std::vector<Vec3> forces_;           ///< (fx, fy, torque) per body for the current sub-step
  std::vector<Vec3> pendingForces_;    ///< applyForce() loads for the next step
  std::vector<Cable> cables_;
  std::vector<std::vector<double>> impulses_;      ///< per cable and span, over this sub-step (N s)
  std::vector<std::vector<double>> stepImpulses_;  ///< ... over this step (N s)
  std::vector<double> stepTimes_;                  ///< ... and the time they are over (s)
  std::vector<std::vector<double>> solved_;  ///< ... the last sub-step's tensions (N), the solves'
  std::vector<std::string> warnings_;
  std::vector<double> paidOutSeen_;  ///< per cable: Cable::paidOut() at the last step's end
  std::vector<double> payStart_;     ///< ... when it began paying out (< 0: it is not)
  std::vector<char> overstretched_;  ///< per cable: reportOverstretch() said so, not yet back
  bool heldSaid_ = false;            ///< reportHeldRows() has spoken
  std::vector<std::vector<int>> jointNeighbours_;  ///< bodies jointed to each body
  std::vector<std::array<int, 2>> jointBodies_;    ///< (body A, body B) per joint, -1: world
  std::vector<JointFrame> jointFrames_;            ///< the joints as the solver sees them
  // State the user edits while the world runs (the scene keeps the authored values).
  Vec2 gravity_ = Vec2::Zero();
  ServoTargets servoTargets_;                      ///< per joint (rad or m)
  std::vector<JointCoordinate> jointCoordinates_;  ///< scratch: every joint's value and rate
  std::vector<double> servoImpulses_;  ///< per joint, its servo's impulse over this step (N s)
  std::vector<double> jointForces_;    ///< ... over the last step (N or N m): JointState::force
  std::vector<StallWatch> stalls_;     ///< per joint: whether its servo has stalled
  std::vector<char> drumArrived_;  ///< per cable end (2 i + 1 the end): reportDrumArrivals() said
  StepStats stats_;
  double time_ = 0;
  long steps_ = 0;
  int dragBody_ = -1;
  Vec2 dragTarget_ = Vec2::Zero();
  WorldHistory history_;
};

}  // namespace cablelab
