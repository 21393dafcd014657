// The cable solver's workspace and its stages, shared by the stage files (cable_solver_*.cpp);
// cable_solver.cpp calls them in order (its table of contents). Private to the cable solver.
#pragma once

#include <Eigen/Dense>
#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/dynamics/cable_solver.h"
#include "engine/dynamics/geometric_stiffness.h"
#include "engine/dynamics/joint_limits.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/dynamics/joint_tree.h"
#include "engine/dynamics/sparse_island.h"
#include "engine/dynamics/step_pose.h"
#include "engine/dynamics/tension_solver.h"

namespace cablelab {

// Generalized coordinates of the bodies one island's cables move: 3 per moving body.
struct DofMap {
  std::vector<int> ofBody;  // body -> first dof, -1 if the body does not move (in this island)
  std::vector<int> body;    // dof / 3 -> body
  int size() const { return 3 * static_cast<int>(body.size()); }
  void reset(size_t bodies) {
    ofBody.assign(bodies, -1);
    body.clear();
  }
  // Forgets this island's bodies only: the cost is the island's, not the world's.
  void clear() {
    for (int b : body) ofBody[b] = -1;
    body.clear();
  }
  int add(int b) {
    if (ofBody[b] < 0) {
      ofBody[b] = size();
      body.push_back(b);
    }
    return ofBody[b];
  }
};

// The buffers of the stages. They live as long as the World so that a sub-step does not
// allocate: after the first step every size has been seen and Eigen reuses the storage.
struct CableSolverWorkspace {
  // Islands: cables and the moving bodies they (and the joints) connect, solved one by one.
  std::vector<int> parent;                     // union-find over bodies
  std::vector<int> islandOfRoot;               // root body -> island, -1: none
  std::vector<std::vector<int>> islandRows;    // cables of each island, in cable order
  std::vector<std::vector<int>> islandJoints;  // joints of each island, in joint order
  int islands = 0;
  std::vector<int> jointIndex;  // the island's joints (indices into the input's joints)

  DofMap dofs;
  std::vector<StepMotion> motions;  // per dof body: how Box2D moves it (step_pose.h)
  std::vector<int> cablesWithRows;  // every cable that pulls on a moving body, in cable order
  std::vector<int> rowless;         // the other cables not skipped: no tension
  // What the islands and their rows and dofs were found from (layoutKey): while it stays the
  // same from one sub-step to the next, so do they, and buildRows restores its cable rows and dofs
  // from `layouts` (the floors and the step motions depend on the motion: built anew).
  std::vector<int> layoutKey, lastLayoutKey;
  // One LCP row per cable span (wheels that grip a cable split it, docs/wheels.md); a row over
  // several spans is a cable sliding on capstans between them: its constraint is their summed
  // length and span k pulls with weight k times the row's impulse (the e^(mu theta) ratios).
  // Floor rows (segment >= 0) follow the cables' rows.
  struct Row {
    int cable = 0;
    int first = 0, last = 0;     // spans
    size_t weights = 0;          // offset of span first's weight in rowWeights
    int segment = -1;            // -1: the spans' length; i: a floor on the cable's segment i
    Vec2 normal = Vec2::Zero();  // a floor's direction (floorNormal)
    bool rim = false;            // a floor on the point's tangent length to a circle (floors.h)
    double weight(const std::vector<double>& w, int k) const { return w[weights + k - first]; }
  };
  std::vector<Row> rows;  // this island's
  std::vector<double> rowWeights;
  struct IslandLayout {  // an island's cable rows (before floors and merges) and dof bodies
    std::vector<Row> rows;
    std::vector<double> rowWeights;
    std::vector<int> dofBodies;
    bool kept = false;  // of the present layoutKey
  };
  std::vector<IslandLayout> layouts;
  Eigen::VectorXd invM;          // M^-1 diagonal over the dofs
  Eigen::VectorXd vStar, vFree;  // predicted velocities (stage 2)
  Eigen::MatrixXd W;             // M'^-1 J^T, then projected onto the joints (n x m)

  // Geometric stiffness of the taut cables (geometric_stiffness.h).
  std::vector<TautCable> taut;
  std::vector<StiffnessBlock> blocks;
  bool stiff = false;
  bool stiffnessLeftOut = false;  // the midpoint rule's islands go without it (stage 5a)
  // M' = M + h^2 T G. G only couples the translations of bodies on stiff cables: those dofs
  // ("coupled") get a small dense LDLT, the others a division by their diagonal.
  std::vector<int> coupledIndex;  // dof -> row of coupledMass, -1: diagonal
  std::vector<int> coupledDofs;
  Eigen::VectorXd massDiagonal;
  Eigen::MatrixXd coupledMass;
  Eigen::LDLT<Eigen::MatrixXd> coupledLdlt;
  Eigen::VectorXd coupledRhs, coupledSolution;

  // The joint projection: in the joints' coordinates where they form trees (joint_tree.h),
  // else through the Schur complement of their rows (joint_projection.h).
  JointTree tree;
  std::vector<JointRow> joints;
  JointProjection projection;
  JointLimits limits;    // limited joints that the step would take past a bound
  Eigen::VectorXd vEnd;  // stage 6c's end-of-step velocities

  // Newton on the end-of-step lengths. pull: the midpoint rule's rows' right-hand side (stage 5).
  Eigen::VectorXd target, compliance, damped, pull, phi0, P, phi1, b, WP, v1, v0, dP;
  Eigen::VectorXd wpImpulses;  // the P that WP = W P was last taken for (timesImpulses)
  bool wpFresh = false;        // ... with the W of now (stages 2-4 clear it)
  Eigen::VectorXd haul, unhauledP, unhauledTarget;  // stage 6d: the kinematic bodies' haul (m)
  bool hauling = false;                             // a kinematic body moves this sub-step
  bool midpoint = false;  // the island takes the implicit midpoint rule (stage 5)
  Eigen::MatrixXd JW, K, JW0;
  Eigen::LDLT<Eigen::MatrixXd> redundancy;  // of J0 W: are there redundant cables?
  bool redundant = false;                   // ... and its answer
  std::vector<BodyState> predicted;
  std::vector<WrapPoint> path;
  CableKinematics kin;
  std::vector<BodyJacobian> floorJacobian;  // scratch: a floor row's J
  std::vector<double> restitution;          // per body: its shapes' largest (floorBounces)
  struct Bounce {                           // a floor row that may bounce (floorBounces)
    int row = 0;
    double opening = 0;  // (1 + e) v h
    double held = 0;     // its target if it does not reach the floor
    // A rigid rope's catch (ropeCatch): its restitution, start value and closing rate, for the
    // energy it gives back at the closing speed it reaches taut (bounceTargets).
    bool catchesRope = false;
    double restitution = 0, start = 0, closing = 0;
  };
  std::vector<Bounce> bounces;
  // The midpoint rule's island took its knock whole as impulses (knockAsImpulses), or its floor
  // pushed with no knock (judgeFloorOnMidpoint): it keeps the rule; the step is checked against
  // `knockAllowed` (J) once solved (midpointKnockGains).
  bool knockedOnMidpoint = false;
  double knockAllowed = 0;
  LcpWorkspace lcp;
  LcpSolution lcpSolution;
  // Per cable, the h and tension of the solve that last set its tension (Newton's warm start).
  struct WarmStart {
    double h = 0, tension = 0;
    int spans = 0;
  };
  std::vector<WarmStart> warm;
  // Per cable, the impulses (N s) of its floor rows in that solve, each by its segment's ends
  // (a wrap change renumbers segments): a body resting at its pulley is held by the same floors
  // step after step (docs/floors.md, "Resting at a pulley").
  struct FloorImpulse {
    int fromPulley = -1, fromVertex = -1, toPulley = -1, toVertex = -1;
    bool rim = false;
    double impulse = 0;
  };
  std::vector<std::vector<FloorImpulse>> floorWarm;
  // Rows the start-of-step J cannot pull on (blocked): they pull along J at the predicted pose
  // (stage 4b), one Jacobian each here.
  std::vector<char> ahead;
  std::vector<std::vector<BodyJacobian>> aheadJacobian;
  std::vector<BodyState> free;  // the island's bodies moved by v* over the step
  SparseIsland sparse;          // big islands (sparse_island.h)

  void factorStiffMass(double h);
  void applyInverseMass(Eigen::Ref<Eigen::MatrixXd> X);
};

namespace cable_stages {

using Workspace = CableSolverWorkspace;

// 1. Islands and rows (cable_solver_rows.cpp).
int findIslands(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables);
void buildRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int island);
double floorRow(Workspace& ws, std::span<const BodyState> bodies, const Cable& cable,
                const Workspace::Row& row);

// A floor row's impulse (N s) for the warm start of the next solve (cable_solver_newton.cpp).
Workspace::FloorImpulse floorImpulse(const Cable& c, const Workspace::Row& row, double impulse);

// 2-4. Predicted velocities, W, the joint projection (cable_solver_prepare.cpp).
void predictPrescribed(Workspace& ws, const CableSolveInput& in);
void prepareRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                 std::span<const Vec3> loads);
void addJacobianTimesW(const Workspace& ws, const std::vector<BodyJacobian>& jacobian,
                       Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> out);

// 4b. Rows with no say pull ahead (cable_solver_redirect.cpp).
bool redirectBlockedRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
double rowSay(Workspace& ws, std::span<const BodyState> bodies, std::span<const Cable> cables,
              int r);
void pathAhead(Workspace& ws, const Cable& cable, int span, std::span<const BodyState> bodies);

// 5, 6. Length targets and Newton on the end-of-step lengths (cable_solver_newton.cpp).
void lengthTargets(Workspace& ws, double h, double share, std::span<const Cable> cables);
// An elastic row's implicit spring-damper (stage 5): its spans' summed end-of-step stretch is
// h compliance P + damped, each span k pulling with its weight w_k times P (one span: w = 1; a
// row merged over a capstan: the spans at the ratio e^(mu theta), docs/polygon_friction.md).
struct ElasticRow {
  double compliance = 0;  // m / (N s^2): sum w_k / (h (k_k h + d_k))
  double damped = 0;      // m: sum d_k phi0_k / (k_k h + d_k)
};
ElasticRow elasticRow(const Workspace& ws, const Cable& c, const Workspace::Row& row, double h);
// Span k's end-of-step stretch (m) when it pulls with impulse `impulse` (N s, its weight times
// the row's): its spring-damper law k phi1 + d (phi1 - phi0) / h = impulse / h.
double springStretchAtEnd(const Cable& c, int k, double impulse, double h);
// 5b. Floors that may bounce, then the solve that bounces them (cable_solver_bounce.cpp).
bool floorBounces(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
// Floor row r's knock this step, (1 + e) v h, 0 if it does not bounce; phi: its value at the start.
double floorKnock(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r,
                  double& phi);
void solveBouncing(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                   StepStats& stats);
// Whether the midpoint rule's step, its knock taken whole as impulses (knockedOnMidpoint), ends
// above the energy the knock may end with (cable_solver_bounce.cpp).
bool midpointKnockGains(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
// A midpoint step whose floor pushes with no knock keeps the rule, to be judged as a knock is
// (midpointKnockGains) against its start energy (cable_solver_bounce.cpp).
void judgeFloorOnMidpoint(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
void timesImpulses(Workspace& ws, const Eigen::VectorXd& P);
void linearise(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
// Newton iterations from ws.P, each linearisation an LCP over all rows. True once the impulses
// have settled (the linearisation at a point the LCP keeps is exact there: it is the solution).
// Close: stopped, its last step small (newtonClose, newton_stop.h).
enum class Newton { Converged, Close, Stopped, Diverged };
Newton iterateNewton(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     bool redundant, StepStats& stats);
void solveLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                  StepStats& stats);

// 6. The start-of-step linearisation (cable_solver_start_of_step.cpp).
void solveStartOfStep(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                      bool redundant);
bool solveLinearised(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     bool redundant, StepStats& stats);
bool holdOverlongRows(Workspace& ws, std::span<const Cable> cables);

// 6. Checks on an answer (cable_solver_checks.cpp).
bool realisable(Workspace& ws, double h);
bool addsEnergy(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
double unmetLength(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
bool missesLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);

// 6, 6d. Newton, then hauled cables pay out (cable_solver_haul.cpp).
void newtonOnLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     StepStats& stats);

// 5a, 6a, 6e. The implicit midpoint rule (cable_solver_midpoint.cpp).
bool takesMidpointRule(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
void midpointSpringRows(Workspace& ws, std::span<const Cable> cables, double h);
void balanceMidpointWork(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
double midpointWorkLeft(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables);
bool pullAlongDiscreteGradient(Workspace& ws, const CableSolveInput& in,
                               std::span<const Cable> cables);

// 6b, 6c. Sliding capstans, crossed joint limits (cable_solver_rerun.cpp).
bool mergeSlidingSpans(Workspace& ws, std::span<const Cable> cables);
bool mergeLastSliding(Workspace& ws, std::span<const Cable> cables);
bool slidesAsMerged(Workspace& ws, std::span<const Cable> cables, double h);
bool lockCrossingLimits(Workspace& ws, const CableSolveInput& in);

// 7. Tensions and forces (cable_solver_forces.cpp).
void applyForces(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                 std::span<Vec3> loads);

// Calls f(J, weight) for each Jacobian that row r's J at the start of the step sums: its
// spans', or its floor's. The constraint is the plain sum; the weights are how hard each span
// pulls (W's columns).
template <class F>
void forStartJacobians(Workspace& ws, std::span<const BodyState> bodies,
                       std::span<const Cable> cables, int r, F&& f) {
  const Workspace::Row& row = ws.rows[r];
  const Cable& c = cables[row.cable];
  if (row.segment >= 0) {
    floorRow(ws, bodies, c, row);
    f(ws.floorJacobian, 1.0);
    return;
  }
  for (int k = row.first; k <= row.last; ++k)
    f(c.spanKinematics(k).jacobian, row.weight(ws.rowWeights, k));
}

// The Jacobians row r pulls along (W's columns): the start-of-step ones, or for a row the
// joints left no say at the start, J at the pose v* reaches (redirectBlockedRows).
template <class F>
void forForceJacobians(Workspace& ws, std::span<const BodyState> bodies,
                       std::span<const Cable> cables, int r, F&& f) {
  if (r < static_cast<int>(ws.ahead.size()) && ws.ahead[r])
    f(ws.aheadJacobian[r], 1.0);
  else
    forStartJacobians(ws, bodies, cables, r, f);
}

// The velocity Box2D moves dof k with when it ends the step at v1: v1, or (v0 + v1) / 2 under the
// midpoint rule (World adds the rest after Box2D's step).
inline Vec3 movedWith(const Workspace& ws, size_t k, const Vec3& v1) {
  return ws.midpoint ? Vec3(0.5 * (ws.v0.segment<3>(3 * k) + v1)) : v1;
}

}  // namespace cable_stages

}  // namespace cablelab
