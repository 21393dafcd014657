// The cable solver's stages (see cable_solver.h for the table of contents, docs/model.md for the
// equations).
#include "engine/dynamics/cable_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "engine/cable/wrap.h"
#include "engine/dynamics/disjoint_sets.h"
#include "engine/dynamics/floors.h"
#include "engine/dynamics/geometric_stiffness.h"
#include "engine/dynamics/joint_limits.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/dynamics/joint_tree.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/newton_stop.h"
#include "engine/dynamics/sparse_island.h"
#include "engine/dynamics/step_pose.h"
#include "engine/dynamics/tension_solver.h"

namespace cablelab {

namespace {

// The most Box2D moves a body in a step (b2_maxTranslation, b2_maxRotation in b2_settings.h).
constexpr double kMaxStepTranslation = 2.0;              // m
constexpr double kMaxStepTurn = 0.5 * std::numbers::pi;  // rad
constexpr int kNewtonIterations = 3;  // on the end-of-step lengths; geometry is nearly linear
// With redundant rows Newton runs on J0 W (a chord method): it converges linearly, not
// quadratically, and a fast catch needs more steps (a puck at 50 m/s: 29 mm stretch after 3).
constexpr int kChordIterations = 12;

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

}  // namespace

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
  Eigen::VectorXd target, compliance, damped, pull, phi0, P, phi1, b, WP, v1, v0;
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
  LcpWorkspace lcp;
  LcpSolution lcpSolution;
  // Per cable, the h and tension of the solve that last set its tension (Newton's warm start).
  struct WarmStart {
    double h = 0, tension = 0;
    int spans = 0;
  };
  std::vector<WarmStart> warm;
  // Rows the start-of-step J cannot pull on (blocked): they pull along J at the predicted pose
  // (stage 4b), one Jacobian each here.
  std::vector<char> ahead;
  std::vector<std::vector<BodyJacobian>> aheadJacobian;
  std::vector<BodyState> free;  // the island's bodies moved by v* over the step
  SparseIsland sparse;          // big islands (sparse_island.h)

  void factorStiffMass(double h);
  void applyInverseMass(Eigen::Ref<Eigen::MatrixXd> X);
};

// Builds M' over the coupled dofs and factors it; immovable dofs (M^-1 = 0) stay put.
void CableSolverWorkspace::factorStiffMass(double h) {
  const int n = dofs.size();
  coupledIndex.assign(n, -1);
  coupledDofs.clear();
  auto couple = [&](int d) {
    if (invM[d] > 0 && coupledIndex[d] < 0) {
      coupledIndex[d] = static_cast<int>(coupledDofs.size());
      coupledDofs.push_back(d);
    }
  };
  for (const TautCable& t : taut)
    for (size_t i = t.begin; i < t.end; ++i) {
      const int ia = dofs.ofBody[blocks[i].a], ib = dofs.ofBody[blocks[i].b];
      if (ia < 0 || ib < 0) continue;
      for (int c = 0; c < 2; ++c) couple(ia + c), couple(ib + c);
    }
  const int nc = static_cast<int>(coupledDofs.size());
  coupledMass.setZero(nc, nc);
  for (const TautCable& t : taut) {
    const double scale = h * h * t.tension;
    for (size_t i = t.begin; i < t.end; ++i) {
      const int ia = dofs.ofBody[blocks[i].a], ib = dofs.ofBody[blocks[i].b];
      if (ia < 0 || ib < 0) continue;
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
          const int cr = coupledIndex[ia + r], cc = coupledIndex[ib + c];
          if (cr >= 0 && cc >= 0) coupledMass(cr, cc) += scale * blocks[i].k(r, c);
        }
    }
  }
  massDiagonal.resize(n);
  for (int d = 0; d < n; ++d) {
    const double m = invM[d] > 0 ? 1.0 / invM[d] : 1.0;
    if (coupledIndex[d] >= 0) coupledMass(coupledIndex[d], coupledIndex[d]) += m;
    massDiagonal[d] = m;
  }
  if (nc > 0) coupledLdlt.compute(coupledMass);
}

// X <- M'^-1 X: a scaling unless the geometric stiffness couples the dofs.
void CableSolverWorkspace::applyInverseMass(Eigen::Ref<Eigen::MatrixXd> X) {
  const int n = dofs.size();
  if (!stiff) {
    X.array().colwise() *= invM.array();  // column by column: X is column-major
    return;
  }
  for (int d = 0; d < n; ++d) {
    if (invM[d] == 0) X.row(d).setZero();  // immovable: no motion whatever the load
    if (coupledIndex[d] < 0) X.row(d) /= massDiagonal[d];
  }
  const int nc = static_cast<int>(coupledDofs.size());
  if (nc == 0) return;
  coupledRhs.resize(nc);
  coupledSolution.resize(nc);
  for (Eigen::Index col = 0; col < X.cols(); ++col) {
    for (int i = 0; i < nc; ++i) coupledRhs[i] = X(coupledDofs[i], col);
    coupledSolution = coupledLdlt.solve(coupledRhs);
    for (int i = 0; i < nc; ++i) X(coupledDofs[i], col) = coupledSolution[i];
  }
}

namespace {

using Workspace = CableSolverWorkspace;

// Calls f(body) for every body a span of the cable pulls on that moves, then, where a segment of
// no length is left out of the Jacobian (a point inside a drum), for the moving ends of its
// segments between two bodies (some twice over), which its floor rows push. Without them that
// point was no dof, and the rim floor that should push it out acted on the drum alone, which its
// axle holds (J W J^T 1e-10): a weight swung onto a winch drum went 15 cm into it and its rope
// 29 cm long.
template <class F>
void forMovingBodies(const Cable& cable, const CableSolveInput& in, F&& f) {
  bool leftOut = false;
  for (int k = 0; k < cable.spanCount(); ++k) {
    const CableKinematics& kin = cable.spanKinematics(k);
    leftOut |= kin.zeroLengthSegments > 0;
    for (const auto& e : kin.jacobian)
      if (moves(in.bodies[e.body])) f(e.body);
  }
  if (!leftOut) return;
  const auto& path = cable.path();
  for (size_t i = 0; i + 1 < path.size(); ++i)
    if (path[i].body != path[i + 1].body)
      for (const int body : {path[i].body, path[i + 1].body})
        if (body >= 0 && moves(in.bodies[body])) f(body);
}

// What findIslands and buildRows read (but for the floors and the step motions): per cable
// whether it is skipped, the moving bodies it pulls on and its spans, and which bodies move.
void layoutKey(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  std::vector<int>& key = ws.layoutKey;
  key.clear();
  for (size_t i = 0; i < cables.size(); ++i) {
    if (!in.skip.empty() && in.skip[i]) {
      key.push_back(-2);
      continue;
    }
    forMovingBodies(cables[i], in, [&](int body) { key.push_back(body); });
    key.push_back(-3 - cables[i].spanCount());
  }
  for (const BodyState& b : in.bodies) key.push_back(moves(b));
}

// 1a. Islands: a cable that pulls on something that moves gets a row; cables sharing a moving
// body, and moving bodies jointed together, are one island. Islands share no moving body, so
// each is solved on its own (a kinematic or static body in several islands moves as prescribed
// whatever the tensions). They are found anew only where the layout key changed. Returns the
// number of islands.
int findIslands(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables) {
  layoutKey(ws, in, cables);
  if (ws.layoutKey == ws.lastLayoutKey) {
    for (int i : ws.rowless) cables[i].setTension(0);
    return ws.islands;
  }
  std::swap(ws.layoutKey, ws.lastLayoutKey);
  for (Workspace::IslandLayout& layout : ws.layouts) layout.kept = false;
  const int bodies = static_cast<int>(in.bodies.size());
  ws.parent.resize(bodies);
  for (int b = 0; b < bodies; ++b) ws.parent[b] = b;
  ws.cablesWithRows.clear();
  ws.rowless.clear();
  for (size_t i = 0; i < cables.size(); ++i) {
    if (!in.skip.empty() && in.skip[i]) continue;
    int first = -1;
    forMovingBodies(cables[i], in, [&](int body) {
      if (first >= 0) unite(ws.parent, first, body);
      first = body;
    });
    (first >= 0 ? ws.cablesWithRows : ws.rowless).push_back(static_cast<int>(i));
  }
  for (int i : ws.rowless) cables[i].setTension(0);
  for (const JointFrame& j : in.joints)
    if (j.bodyA >= 0 && j.bodyB >= 0 && moves(in.bodies[j.bodyA]) && moves(in.bodies[j.bodyB]))
      unite(ws.parent, j.bodyA, j.bodyB);
  ws.islandOfRoot.assign(bodies, -1);
  for (auto& rows : ws.islandRows) rows.clear();
  for (auto& joints : ws.islandJoints) joints.clear();
  ws.islands = 0;
  for (int row : ws.cablesWithRows) {
    int body = -1;
    forMovingBodies(cables[row], in, [&](int b) { body = b; });
    int& island = ws.islandOfRoot[findRoot(ws.parent, body)];
    if (island < 0) island = ws.islands++;
    if (static_cast<int>(ws.islandRows.size()) < ws.islands) {
      ws.islandRows.resize(ws.islands);
      ws.islandJoints.resize(ws.islands);
    }
    ws.islandRows[island].push_back(row);
  }
  for (size_t j = 0; j < in.joints.size(); ++j) {
    const JointFrame& f = in.joints[j];
    const int body = f.bodyB >= 0 && moves(in.bodies[f.bodyB])   ? f.bodyB
                     : f.bodyA >= 0 && moves(in.bodies[f.bodyA]) ? f.bodyA
                                                                 : -1;
    if (body < 0) continue;
    const int island = ws.islandOfRoot[findRoot(ws.parent, body)];
    if (island >= 0) ws.islandJoints[island].push_back(static_cast<int>(j));
  }
  return ws.islands;
}

// Whether segment (p, q) could close to kFloorLength within the step, at the speed its ends have
// now plus a step of gravity (twice that, and a floor length, for margin): only then does it get
// a floor row. A hand's membranes have short end segments that never come close; rows cost.
bool mayReachFloor(const CableSolveInput& in, const WrapPoint& p, const WrapPoint& q) {
  auto speed = [&](const WrapPoint& w) {
    if (w.body < 0) return 0.0;
    const BodyState& b = in.bodies[w.body];
    const Vec2 v = b.velocity + b.angularVelocity * perp(Vec2(w.world - b.position));
    return v.norm() + (b.invMass > 0 ? in.h * in.gravity.norm() : 0.0);
  };
  const double gap = floorGap(p, q);
  return gap > 1e-9 && gap < 2 * kFloorLength + 2 * in.h * (speed(p) + speed(q));
}

// 1b. One island's rows (one per span of its cables), and the dofs of the bodies it moves: its
// cables' moving bodies in cable order, then those jointed to them (breadth first: they move with
// them). Then the floors.
void buildRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
               int island) {
  ws.dofs.clear();
  ws.jointIndex = ws.islandJoints[island];
  if (static_cast<int>(ws.layouts.size()) <= island) ws.layouts.resize(island + 1);
  Workspace::IslandLayout& layout = ws.layouts[island];
  if (layout.kept) {
    for (int body : layout.dofBodies) ws.dofs.add(body);
    ws.rows = layout.rows;
    ws.rowWeights = layout.rowWeights;
  } else {
    ws.rows.clear();
    ws.rowWeights.clear();
    for (int cable : ws.islandRows[island]) {
      forMovingBodies(cables[cable], in, [&](int body) { ws.dofs.add(body); });
      for (int k = 0; k < cables[cable].spanCount(); ++k) {
        ws.rows.push_back({cable, k, k, ws.rowWeights.size()});
        ws.rowWeights.push_back(1.0);
      }
    }
    for (size_t k = 0; k < ws.dofs.body.size(); ++k)
      for (int other : in.jointNeighbours[ws.dofs.body[k]])
        if (moves(in.bodies[other])) ws.dofs.add(other);
    layout = {ws.rows, ws.rowWeights, ws.dofs.body, true};
  }
  ws.motions.resize(ws.dofs.body.size());
  stepMotions(in.joints, ws.jointIndex, in.bodies, ws.dofs.ofBody, ws.motions);
  // Floors (floors.h): a short segment on a moving body gets a row of its own after the cables.
  for (int cable : ws.islandRows[island]) {
    const auto& path = cables[cable].path();
    for (size_t i = 0; i + 1 < path.size(); ++i)
      if (needsFloor(cables[cable], i, in.bodies, in.h, in.gravity,
                     [&](int b) { return ws.dofs.ofBody[b] >= 0; }) &&
          mayReachFloor(in, path[i], path[i + 1])) {
        const Vec2 n = floorNormal(path[i], path[i + 1], in.bodies, in.h, in.gravity);
        ws.rows.push_back({cable, 0, 0, ws.rowWeights.size(), static_cast<int>(i), n});
        ws.rowWeights.push_back(1.0);
        if (rimEnd(path[i], path[i + 1]) < 0) continue;
        ws.rows.push_back({cable, 0, 0, ws.rowWeights.size(), static_cast<int>(i), n, true});
        ws.rowWeights.push_back(1.0);
      }
  }
}

// A floor row's constraint kFloorLength - n . (q - p) of segment (p, q) on `bodies` (p, q: its
// contact points, a circle's tangent point moving with its centre; n: floorNormal, floors.h), and
// its J (into ws.floorJacobian).
double floorRow(Workspace& ws, std::span<const BodyState> bodies, const Cable& cable,
                const Workspace::Row& row) {
  const WrapPoint* ends[2] = {&cable.path()[row.segment], &cable.path()[row.segment + 1]};
  ws.floorJacobian.clear();
  // A point's gap to its floor at a circle (floors.h, rimGap).
  if (row.rim) {
    const int rim = rimEnd(*ends[0], *ends[1]);
    const WrapPoint &circle = *ends[rim], &point = *ends[1 - rim];
    const Vec2 c = worldPoint(bodies, circle.body, circle.local);
    const Vec2 x = worldPoint(bodies, point.body, point.local);
    Vec2 g;
    const double gap = rimGap(point.body, x, c, circle.radius, g);
    // d(kFloorLength - gap): -g at the point, g at the circle's centre.
    for (const auto& [body, at, d] :
         {std::tuple(point.body, x, Vec2(-g)), std::tuple(circle.body, c, g)})
      if (body >= 0)
        ws.floorJacobian.push_back(
            {body, Vec3(d.x(), d.y(), d.dot(perp(Vec2(at - bodies[body].position))))});
    return kFloorLength - gap;
  }
  const Vec2& n = row.normal;
  double along = 0;
  for (int e = 0; e < 2; ++e) {
    const double sign = e == 0 ? 1.0 : -1.0;  // d(kFloorLength - n . (q - p))
    const WrapPoint& w = *ends[e];
    const Vec2 centre = worldPoint(bodies, w.body, w.local);
    // A circle's contact is its tangent point at the start of the step, carried with its centre.
    const Vec2 offset = (e == 0 ? floorFrom(w) : floorTo(w)) - w.world;
    along -= sign * n.dot(centre + offset);
    if (w.body < 0) continue;
    const Vec2 arm = centre - bodies[w.body].position;
    ws.floorJacobian.push_back({w.body, sign * Vec3(n.x(), n.y(), n.dot(perp(arm)))});
  }
  return kFloorLength - along;
}

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

// Bodies that are not dofs (kinematic, static) at the end of the step: Box2D moves them with
// their prescribed velocity. Dofs are overwritten island by island in Newton.
void predictPrescribed(Workspace& ws, const CableSolveInput& in) {
  ws.predicted.assign(in.bodies.begin(), in.bodies.end());
  ws.hauling = false;
  for (BodyState& p : ws.predicted)
    if (!moves(p)) {
      ws.hauling |= driven(p);
      p.position += in.h * p.velocity;
      p.angle += in.h * p.angularVelocity;
    }
}

// 2. M^-1, the predicted velocity v* (gravity and loads, no cables) and J at the start of the
// step, stored transposed in W (it becomes M'^-1 J^T in stage 3).
void predictVelocities(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                       std::span<const Vec3> loads) {
  const DofMap& dofs = ws.dofs;
  const int n = dofs.size(), m = static_cast<int>(ws.rows.size());
  ws.invM.resize(n);
  for (size_t k = 0; k < dofs.body.size(); ++k) {
    const BodyState& s = in.bodies[dofs.body[k]];
    ws.invM.segment<3>(3 * k) = Vec3(s.invMass, s.invMass, s.invInertia);
  }
  ws.vStar.resize(n);
  ws.v0.resize(n);
  for (size_t k = 0; k < dofs.body.size(); ++k) {
    const BodyState& s = in.bodies[dofs.body[k]];
    Vec3 v(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    ws.v0.segment<3>(3 * k) = v;
    Vec3 load = loads[dofs.body[k]];
    if (!in.contacts.empty()) load += in.contacts[dofs.body[k]];
    v += in.h * (ws.invM.segment<3>(3 * k).cwiseProduct(load));
    if (s.invMass > 0) v.head<2>() += in.h * in.gravity;
    ws.vStar.segment<3>(3 * k) = v;
  }
  ws.W.setZero(n, m);
  ws.wpFresh = false;
  for (int r = 0; r < m; ++r)
    forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double weight) {
      for (const auto& e : jacobian)
        if (dofs.ofBody[e.body] >= 0) ws.W.block<3, 1>(dofs.ofBody[e.body], r) += weight * e.d;
    });
  ws.vFree = ws.vStar;  // what Box2D would reach without cables and joints (contacts as expected)
}

// 3. W = M'^-1 J^T. M' adds the geometric stiffness h^2 T d^2(length)/dx^2 of taut cables where
// it matters (a light body on a tight band turns the force direction faster than one step
// resolves). Backward Euler on the turning force direction: (M + h^2 T G) v1 = M v* - J^T P, so
// the stiffness also resists the motion v* already carries into the band.
void inverseMass(Workspace& ws, double h, std::span<const Cable> cables) {
  ws.taut.clear();
  ws.blocks.clear();
  ws.stiff = false;
  for (const Workspace::Row& row : ws.rows)
    if (row.segment < 0 && row.first == 0) {  // once per cable: not a floor, not a later span
      const Cable& c = cables[row.cable];
      const Workspace::WarmStart& last = ws.warm[row.cable];
      const double pulling =
          pullingTension(c.tension(), last.tension == c.tension() ? last.h : 0, h);
      addGeometricStiffness(c, pulling, h, ws.dofs.ofBody, ws.invM, ws.blocks, ws.taut, ws.stiff);
    }
  if (ws.stiff) ws.factorStiffMass(h);
  ws.applyInverseMass(ws.W);
  if (ws.stiff) {
    const int n = ws.dofs.size();
    for (int d = 0; d < n; ++d) ws.vStar[d] = ws.invM[d] > 0 ? ws.vStar[d] / ws.invM[d] : 0.0;
    ws.applyInverseMass(ws.vStar);
  }
}

// Stage 4's rows: the island's joints among its dofs (joint_projection.h).
void jointRows(Workspace& ws, const CableSolveInput& in) {
  ws.joints.clear();
  for (int j : ws.jointIndex)
    appendJointRows(in.joints[j], in.bodies, ws.dofs.ofBody, ws.joints, ws.limits.lock(j));
}

// 4. W and v* projected onto what the joints allow: Box2D's joints act after our forces, so the
// cables must already see them (a pulley on a pivoted body turns, it does not translate).
void projectOntoJoints(Workspace& ws, const CableSolveInput& in) {
  if (ws.jointIndex.empty()) return;
  if (!ws.stiff && jointTreeProjection() &&
      ws.tree.build(in.joints, ws.jointIndex, in.bodies, ws.dofs.ofBody, ws.invM)) {
    ws.tree.project(ws.W, ws.vStar, ws.limits);
    return;
  }
  jointRows(ws, in);
  if (ws.joints.empty()) return;
  if (ws.stiff)
    ws.projection.projectDense(
        ws.joints, [&](Eigen::Ref<Eigen::MatrixXd> X) { ws.applyInverseMass(X); }, ws.W, ws.vStar);
  else
    ws.projection.projectDiagonal(ws.joints, ws.invM, ws.W, ws.vStar);
}

// A joining point that the free motion bends the cable round by more than this (sin of the turn)
// within a nominal sub-step (a step cut at the join is shorter: the turn over it is scaled) joins
// fast: pulling along J0, which has no share of it, the solve stops the
// cable with the other bodies while the point goes on (a puck at 5 m/s caught by a rope whose
// far end is on a pivoted arm: +8.5% energy; at 20 m/s: 13.5 kJ from 200 J). Slower joins keep
// J0: the share, a guess at the step's average, changes the energy at every wrap change of a
// hexagon swinging on its pivot (0.025 rad a step), for the worse as often as not. At 1 m/s
// (0.033 rad) the puck's catch gains 1.1%.
constexpr double kFastJoinTurn = 0.1;
constexpr double kJoinSay = 100;

// J0 W(:, r): how far a unit impulse of row r moves its own length (1/kg), W as stages 2-4 left
// it. 0 where the joints leave the row no say.
double rowSay(Workspace& ws, std::span<const BodyState> bodies, std::span<const Cable> cables,
              int r) {
  double say = 0;
  forStartJacobians(ws, bodies, cables, r, [&](const auto& jacobian, double) {
    for (const auto& e : jacobian)
      if (const int d = ws.dofs.ofBody[e.body]; d >= 0) say += e.d.dot(ws.W.block<3, 1>(d, r));
  });
  return say;
}

// Whether path point i (a point pulley or polygon vertex on a moving body, wrapped) bends the
// cable by almost nothing: it has just joined, or is about to leave.
bool nearlyStraight(const Cable& cable, std::span<const WrapPoint> path,
                    std::span<const Vec2> directions, size_t i) {
  const WrapPoint& w = path[i];
  if (w.pulley < 0 || w.body < 0 || w.kind == WrapPoint::Kind::Circle ||
      cable.wrapSide(w.pulley) == WrapSide::Threaded)
    return false;
  const Vec2 &in = directions[i - 1], &out = directions[i];
  return std::abs(cross(in, out)) < 1e-3 && in.dot(out) > 0;
}

// The span's path at `bodies` as the cable will take it (into ws.path, its length and J into
// ws.kin): a point pulley that the motion carried to its unwrapped side is left out, as the cable
// leaves it there. A path bent backwards round it would be longer, and Newton would pull to hold
// a length the cable never has (a rope straightening between fixed points: 9e9 N).
void pathAhead(Workspace& ws, const Cable& cable, int span, std::span<const BodyState> bodies) {
  const std::span<const WrapPoint> source = cable.spanPath(span);
  ws.path.assign(source.begin(), source.end());
  cableLengthJacobian(ws.path, bodies, ws.kin);
  for (size_t i = 1; i + 1 < ws.path.size(); ++i) {
    const WrapPoint& w = ws.path[i];
    if (w.kind != WrapPoint::Kind::Point || w.pulley < 0 ||
        cable.wrapSide(w.pulley) == WrapSide::Threaded)
      continue;
    // As the cable's own leave rule (Cable::leaveRound): a point that the cable doubled back
    // round past half a turn stays (with the sign alone, a point that hooked a ballast's cable
    // beyond its end pulley left the prediction, the solve saw a slack cable and let it go: the
    // rigid cable grew to 60 m).
    const Vec2 in = w.world - floorFrom(ws.path[i - 1]), out = floorTo(ws.path[i + 1]) - w.world;
    if (continuedPointTurn(in, out, cable.wrapSide(w.pulley), cable.pointTurn(w.pulley)) >= 0)
      continue;
    ws.path.erase(ws.path.begin() + static_cast<std::ptrdiff_t>(i));
    cableLengthJacobian(ws.path, bodies, ws.kin);
    i = 0;
  }
}

// 4b. Rows whose start-of-step J has lost its say: a point that just joined has no share of J0
// (theorem 1), and the joints may take the rest (a cable's end on an arm pivoted at its
// pulley). Pulling along J0 such a row needs unbounded impulses (1e24 N were seen), or throws
// the one body that can give cable (an arm spun to 236 rad/s by a puck it did not stop). A row
// with no say at all (J0 W = 0) pulls along J at the pose v* reaches instead; a row whose wrap
// point joins fast (v* bends the cable round it by more than kFastJoinTurn a sub-step) gives that
// point half the share of J it has there. Newton still solves the end-of-step length. True if
// any row was redirected (then stages 2-4 run again).
bool redirectBlockedRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  ws.ahead.assign(m, 0);
  bool any = false, moved = false;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0 || row.first != row.last) continue;
    const Cable& cable = cables[row.cable];
    const std::span<const WrapPoint> span = cable.spanPath(row.first);
    const std::span<const Vec2> directions = cable.spanKinematics(row.first).directions;
    int joining = -1;  // a nearly straight wrap point on a dof
    double reach = 0;  // the largest M^-1 on the row's bodies
    for (size_t i = 0; i < span.size(); ++i) {
      const int d = span[i].body >= 0 ? ws.dofs.ofBody[span[i].body] : -1;
      if (d < 0) continue;
      reach = std::max(reach, ws.invM[d]);
      if (i > 0 && i + 1 < span.size() && nearlyStraight(cable, span, directions, i))
        joining = static_cast<int>(i);
    }
    const double authority = ws.JW0(r, r);  // the row's say (rowSay: no row pulls ahead yet)
    const bool blocked = authority <= 1e-9 * reach;
    if (joining < 0 && !blocked) continue;
    if (!moved) {
      ws.free.assign(ws.predicted.begin(), ws.predicted.end());
      for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
        const BodyState& b = in.bodies[ws.dofs.body[k]];
        BodyState& f = ws.free[ws.dofs.body[k]];
        f.position = b.position + in.h * ws.vStar.segment<2>(3 * k);
        f.angle = b.angle + in.h * ws.vStar[3 * k + 2];
      }
      ws.aheadJacobian.resize(m);
      moved = true;
    }
    pathAhead(ws, cable, row.first, ws.free);
    if (joining < 0) {  // no say at all: the whole row pulls along J there
      ws.aheadJacobian[r] = ws.kin.jacobian;
      ws.ahead[r] = 1;
      any = true;
      continue;
    }
    // A joining point must still be on the path there, bent further onto its wrap side and by
    // more than kFastJoinTurn. It then gets half the share of J it has there, dL/dp = u_in -
    // u_out (the share grows from 0 over the step); the rest of the row keeps J0 (J there for
    // every body made a hexagon on its pivot lose 3 times the energy at wrap changes).
    const WrapPoint& w = span[joining];
    const auto kept = std::find_if(ws.path.begin(), ws.path.end(), [&](const WrapPoint& p) {
      return p.pulley == w.pulley && p.kind == w.kind && p.vertex == w.vertex;
    });
    if (kept == ws.path.end() || kept == ws.path.begin() || kept + 1 == ws.path.end()) continue;
    const size_t i = static_cast<size_t>(kept - ws.path.begin());
    const Vec2 pull = ws.kin.directions[i - 1] - ws.kin.directions[i];
    const Vec2 arm = kept->world - ws.free[w.body].position;
    const Vec3 share = 0.5 * Vec3(pull.x(), pull.y(), pull.dot(perp(arm)));
    // Slow joins keep J0, unless the rest of the row has less than kJoinSay times the say the
    // point would have (its share's M^-1 norm): a rope whose far end is on an arm pivoted 1 cm
    // beside its pulley (3e-4 against 3e-4) caught a puck at 1 m/s and gained 9 times the throw's
    // energy; a hexagon's vertex joining its rope holds 1e-4 against the weight's 1.
    const double turn = std::abs(cross(ws.kin.directions[i - 1], ws.kin.directions[i]));
    const Vec3 inverse = ws.invM.segment<3>(ws.dofs.ofBody[w.body]);
    if (turn <= std::abs(cross(directions[joining - 1], directions[joining])) ||
        (turn < kFastJoinTurn * in.share &&
         authority >= kJoinSay * share.dot(inverse.cwiseProduct(share))))
      continue;
    std::vector<BodyJacobian>& jacobian = ws.aheadJacobian[r];
    jacobian = cable.spanKinematics(row.first).jacobian;
    const auto entry = std::find_if(jacobian.begin(), jacobian.end(),
                                    [&](const BodyJacobian& e) { return e.body == w.body; });
    if (entry == jacobian.end())
      jacobian.push_back({w.body, share});
    else
      entry->d += share;
    ws.ahead[r] = 1;
    any = true;
  }
  return any;
}

// J W for a row from a sparse Jacobian (a cable touches a few of the n dofs).
void addJacobianTimesW(const Workspace& ws, const std::vector<BodyJacobian>& jacobian,
                       Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>> out) {
  const Eigen::Index n = ws.W.rows(), m = ws.W.cols();
  for (const auto& e : jacobian)
    if (const int d = ws.dofs.ofBody[e.body]; d >= 0)
      for (Eigen::Index s = 0; s < m; ++s) {
        const double* w = ws.W.data() + s * n + d;
        out[s] += e.d[0] * w[0] + e.d[1] * w[1] + e.d[2] * w[2];
      }
}

// Stages 2-4, then J0 W from the Jacobians W pulls along (positive semidefinite): each row's say
// (stage 4b), the start-of-step linearisation (stage 6) and the guard on Newton's.
void prepareRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                 std::span<const Vec3> loads) {
  predictVelocities(ws, in, cables, loads);
  inverseMass(ws, in.h, cables);
  projectOntoJoints(ws, in);
  const int m = static_cast<int>(ws.rows.size());
  ws.JW0.setZero(m, m);
  for (int r = 0; r < m; ++r)
    forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
      addJacobianTimesW(ws, jacobian, ws.JW0.row(r));
    });
}

// 5. Position-level targets. Rigid: length at the end of the step = now (the error below the
// slop is float rounding: fixing it would amplify it by 1/h^2), a slack cable may come taut, an
// over-long one is shortened by a share of the excess per nominal sub-step (a step cut at an
// event fixes its share of that: fixing it all would ask for a velocity of error / h). Elastic: T =
// k phi1 + b (phi1 - phi0)/h.
void lengthTargets(Workspace& ws, double h, double share, std::span<const Cable> cables) {
  // Floors are rigid rows on kFloorLength - |segment|: they only ever push.
  const double beta = kBaumgarte * share;
  const int m = static_cast<int>(ws.rows.size());
  ws.target.resize(m);
  ws.compliance.setZero(m);
  ws.damped.setZero(m);
  ws.pull.setZero(m);
  ws.phi0.resize(m);
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    const int seg = row.segment;
    double phi = 0;
    if (seg >= 0)
      phi = kFloorLength - floorGap(c.path()[seg], c.path()[seg + 1], ws.rows[r].rim);
    else
      for (int k = row.first; k <= row.last; ++k) phi += c.spanStretch(k);
    ws.phi0[r] = phi;
    if (!c.elastic() || seg >= 0) {
      ws.target[r] = phi < -kLengthSlop  ? 0.0
                     : phi > kLengthSlop ? phi - beta * (phi - kLengthSlop)
                                         : phi;
    } else if (!ws.midpoint) {  // (midpointSpringRows pulls with the energy's discrete gradient)
      const double stiffK = c.stiffness(), damp = c.damping();
      ws.compliance[r] = 1.0 / (h * (stiffK * h + damp));
      ws.damped[r] = damp * phi / (stiffK * h + damp);
    }
  }
}

// A rigid row under the midpoint rule (stage 5a). Box2D's symplectic Euler swings the measured
// energy of a rope over a spinning pulley by about omega h / 2 (the built-in hexagon on its pivot:
// 3.2% of its largest kinetic energy at 1 sub-step, a square 11%); the midpoint rule holds it to
// 0.5% and 2.9%. Only where the rest of the step is exact under that rule too:
// - every joint is a revolute one without limits at the centre of mass of a body it hangs from
//   one that does not move (a pulley on its axle). Gravity's torque about an off-centre pivot is
//   taken at the start pose, and with q1 = q0 + h (v0 + v1) / 2 a start-pose force gains energy
//   every swing (a pendulum carrying an eyelet: +64% in a minute); without gravity a puck caught
//   by a rope on an arm pivoted off its centre kept 86% of the energy that Box2D's integration
//   kept to 1%, and a rope from a carriage on a rail stretched 3.5 mm (1e-6 m);
// - no circle, drum or kinematic body on the path, one span;
// - some pulley of the cable on a moving body (else Box2D's own integration, as the midpoint
//   solver leaves straight cables over fixed pulleys).
// The island's part of the conditions (its joints), then the cable's.
bool jointsAreAxles(const Workspace& ws, const CableSolveInput& in) {
  if (ws.jointIndex.empty()) return false;
  for (int j : ws.jointIndex) {
    const JointFrame& f = in.joints[j];
    const bool movesA = f.bodyA >= 0 && moves(in.bodies[f.bodyA]);
    const bool movesB = f.bodyB >= 0 && moves(in.bodies[f.bodyB]);
    if (f.limited || f.kind != JointDef::Kind::Revolute || (movesA && movesB)) return false;
    const Vec2 centre = in.bodies[movesA ? f.bodyA : f.bodyB].position;
    if ((f.anchor - centre).squaredNorm() > 1e-18) return false;
  }
  return true;
}
bool rigidRowTakesMidpointRule(const CableSolveInput& in, const Cable& c) {
  if (c.spanCount() != 1) return false;
  for (const WrapPoint& w : c.path())
    if (w.radius != 0 || (w.body >= 0 && driven(in.bodies[w.body]))) return false;
  for (int j = 0; j < c.pulleyCount(); ++j)
    if (c.pulleyBody(j) >= 0 && moves(in.bodies[c.pulleyBody(j)])) return true;
  return false;
}

// 5a. Undamped elastic cables on jointed (or touching-free) bodies: the backward-Euler spring of
// stage 5 damps them (an arm on a pivot pulled by a k = 200 N/m cable lost 90% of its energy in
// 1 s). Where every row of the island is such a cable, no body touches, and each row's axial
// mode is resolved (omega h <= 2, omega^2 = k J0 W), the island takes the implicit midpoint rule
// instead: q1 = q0 + h (v0 + v1) / 2, the spring pulling with its energy's discrete gradient
// (midpointSpringRows: k (phi0 + phi1) / 2 while taut), Box2D moving the bodies with
// (v0 + v1) / 2 and World adding the rest after its step (kicks). The joints allow v0 and v1
// alike, so they allow every velocity Box2D sees. The midpoint solver's rule (docs/cables.md,
// "Energy"), here with the joint projection of stages 2-4.
bool takesMidpointRule(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  if (in.kicks.empty() || ws.stiff || ws.rows.empty()) return false;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k)
    if (!in.touching.empty() && in.touching[ws.dofs.body[k]]) return false;
  int axles = -1;  // jointsAreAxles, asked once, where a rigid row needs it
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    if (row.segment >= 0 || row.first != row.last) return false;
    if (!c.elastic()) {
      // A row stage 4b redirected joins fast: a puck caught at 50 m/s by a rope on a pivoted
      // arm, under the midpoint rule, was thrown off before it wrapped.
      if (axles < 0) axles = jointsAreAxles(ws, in);
      if (!axles || (r < ws.ahead.size() && ws.ahead[r]) || !rigidRowTakesMidpointRule(in, c))
        return false;
      continue;
    }
    if (c.damping() != 0) return false;
    const double say = rowSay(ws, in.bodies, cables, static_cast<int>(r));
    if (!(c.stiffness() * say * in.h * in.h <= 4)) return false;
  }
  return true;
}

// The midpoint rule's rows at Newton's iterate (phi1 at q0 + h (v0 + v1) / 2): the cable pulls
// with the discrete gradient of its energy V = k/2 max(0, phi)^2, P = h g, g = (V(phi1) -
// V(phi0)) / (phi1 - phi0) (k (phi0 + phi1) / 2 while taut throughout; across a slack-taut
// switch the exact quotient, or the switch gains or loses energy). With s = dg/dphi1 and
// dphi1/dP = -(h/2) J1 W, Newton's row is (J1 W + 2 / (h^2 s)) P = J1 W P_k + 2 g / (h s).
void midpointSpringRows(Workspace& ws, std::span<const Cable> cables, double h) {
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    if (!cables[ws.rows[r].cable].elastic()) continue;
    const double k = cables[ws.rows[r].cable].stiffness();
    const double p0 = ws.phi0[r], p1 = ws.phi1[r], d = p1 - p0;
    double g, s;
    if ((p0 >= 0 && p1 >= 0) || (p0 <= 0 && p1 <= 0) || std::abs(d) < 1e-300) {
      g = 0.5 * k * (p0 + p1), s = 0.5 * k;  // slack throughout: g < 0, the LCP leaves it slack
    } else if (p1 > 0) {                     // comes taut
      g = 0.5 * k * p1 * p1 / d, s = 0.5 * k * p1 * (p1 - 2 * p0) / (d * d);
    } else {  // goes slack
      g = -0.5 * k * p0 * p0 / d, s = 0.5 * k * p0 * p0 / (d * d);
    }
    s = std::max(s, 1e-12 * k);
    ws.compliance[r] = 2 / (h * h * s);
    ws.pull[r] = 2 * g / s;
  }
}

// ws.WP = W P, column by column: W has a few columns (one per row), and Eigen's general product
// costs more than the arithmetic at these sizes. Kept while W and P stay as they are: the
// shortcut, the limit check and the forces all ask for the same product.
void timesImpulses(Workspace& ws, const Eigen::VectorXd& P) {
  if (ws.wpFresh && ws.wpImpulses.size() == P.size() && ws.wpImpulses == P) return;
  const Eigen::Index n = ws.W.rows(), m = ws.W.cols();
  ws.WP.setZero(n);
  for (Eigen::Index s = 0; s < m; ++s) {
    const double p = P[s];
    const double* w = ws.W.data() + s * n;
    for (Eigen::Index d = 0; d < n; ++d) ws.WP[d] += w[d] * p;
  }
  ws.wpImpulses = P;
  ws.wpFresh = true;
}

// The velocity Box2D moves dof k with when it ends the step at v1: v1, or (v0 + v1) / 2 under the
// midpoint rule (World adds the rest after Box2D's step).
Vec3 movedWith(const Workspace& ws, size_t k, const Vec3& v1) {
  return ws.midpoint ? Vec3(0.5 * (ws.v0.segment<3>(3 * k) + v1)) : v1;
}

// The end-of-step state for impulses P (Box2D integrates q1 = q0 + h v1), then each row's
// end-of-step length error phi1 and its linearisation J1 W.
void linearise(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  const double h = in.h;
  timesImpulses(ws, ws.P);
  ws.v1 = ws.vStar - ws.WP;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const BodyState& s = in.bodies[ws.dofs.body[k]];
    BodyState& p = ws.predicted[ws.dofs.body[k]];
    stepPose(s, movedWith(ws, k, ws.v1.segment<3>(3 * k)), h, ws.motions[k], p);
  }
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    ws.JW.row(r).setZero();
    if (row.segment >= 0) {
      ws.phi1[r] = floorRow(ws, ws.predicted, c, row);
      addJacobianTimesW(ws, ws.floorJacobian, ws.JW.row(r));
      continue;
    }
    ws.phi1[r] = 0;
    for (int k = row.first; k <= row.last; ++k) {
      pathAhead(ws, c, k, ws.predicted);
      ws.phi1[r] += c.spanStretch(k) + ws.kin.length - c.spanKinematics(k).length;
      addJacobianTimesW(ws, ws.kin.jacobian, ws.JW.row(r));
    }
  }
}

// Warm start: a cable's tension changes little from one sub-step to the next, so Newton starts
// from the impulses of the last solve when it had the same h and nothing has set the tension
// since (after a step cut at an event the impulse is not force times h: a length correction is
// m dv whatever h). Floors start at 0. True if any row starts away from 0.
bool warmStart(Workspace& ws, double h, std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  ws.P.setZero(m);
  bool warm = false;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    const Workspace::WarmStart& last = ws.warm[row.cable];
    if (row.segment >= 0 || last.h != h || last.tension != c.tension() ||
        last.spans != c.spanCount())
      continue;
    ws.P[r] = std::max(0.0, c.spanTension(row.first) / row.weight(ws.rowWeights, row.first)) * h;
    warm |= ws.P[r] > 0;
  }
  return warm;
}

// Newton iterations from ws.P, each linearisation an LCP over all rows. True once the impulses
// have settled (the linearisation at a point the LCP keeps is exact there: it is the solution).
enum class Newton { Converged, Stopped, Diverged };

// Newton's iterations from ws.P. Stopped: the iterations ran out while the steps still shrank
// (ws.P is the last iterate, as good as it got). Diverged: a step grew instead (ws.P is not an
// answer).
Newton iterateNewton(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     bool redundant, StepStats& stats) {
  const int m = static_cast<int>(ws.rows.size());
  const double h = in.h;
  double lastChange = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < (redundant ? kChordIterations : kNewtonIterations);
       ++iteration) {
    linearise(ws, in, cables);
    if (redundant) ws.JW = ws.JW0;
    // Guard (degenerate geometry): far from the start pose the end-of-step linearisation can lose
    // positive definiteness (a wrap point the predicted motion carries past its neighbour turns a
    // row's J1 against its J0: K_ii <= 0), and the LCP then answers with impulses of 1e6 N s.
    // Such a row falls back to the start-of-step Jacobian, whose J0 W is positive semidefinite.
    for (int r = 0; r < m; ++r)
      if (!(ws.JW(r, r) > 1e-3 * ws.JW0(r, r))) {
        ws.JW.row(r) = ws.JW0.row(r);
        ++stats.linearisationFallbacks;
      }
    if (ws.midpoint) midpointSpringRows(ws, cables, h);
    ws.K = ws.JW;
    ws.K.diagonal() += ws.compliance;
    ws.b.noalias() = ws.JW.lazyProduct(ws.P);  // a few rows: no GEMV kernel call
    for (int r = 0; r < m; ++r)
      ws.b[r] += (ws.midpoint && cables[ws.rows[r].cable].elastic() ? ws.pull[r]
                  : cables[ws.rows[r].cable].elastic() && ws.rows[r].segment < 0
                      ? ws.phi1[r] - ws.damped[r]
                      // under the midpoint rule dphi1/dP = -(h/2) J1 W
                      : (ws.midpoint ? 2 : 1) * (ws.phi1[r] - ws.target[r])) /
                 h;
    LcpSolution& sol = ws.lcpSolution;
    solveLcp(ws.K, ws.b, ws.lcp, sol, redundant);
    const double change = (sol.x - ws.P).lpNorm<Eigen::Infinity>();
    ws.P = sol.x;
    stats.solverIterations += sol.iterations;
    stats.residual = std::max(stats.residual, sol.residual);
    if (newtonSettled(change, lastChange, ws.P.lpNorm<Eigen::Infinity>())) return Newton::Converged;
    // Steps that grow, and not by rounding (a converged iterate's change of 1e-8 |P|).
    if (!(change < lastChange) && change > 1e-3 * ws.P.lpNorm<Eigen::Infinity>())
      return Newton::Diverged;
    lastChange = change;
  }
  return Newton::Stopped;
}

// Newton's shortcut. Where every row is a sum of distances between points fixed on bodies (no
// circle, no floor), phi1 = phi0 + h J0 v1 + R with a remainder R that the motion bounds
// (lengthRemainderBound). The start-of-step linearisation is then solved as one LCP, with no
// kinematics at a predicted pose, and kept when R is provably below kLinearTolerance: the end-of-
// step lengths are those Newton would converge to, to that tolerance. A body at rest, or slow
// against its segments' lengths, takes it (the hand holding its box); a fast one takes Newton.
constexpr double kLinearTolerance = 1e-12;  // m
bool linearShortcut = true;

bool pointRowsOnly(const Workspace& ws, std::span<const Cable> cables) {
  for (const Workspace::Row& row : ws.rows) {
    if (row.segment >= 0) return false;
    for (int k = row.first; k <= row.last; ++k)
      for (const WrapPoint& w : cables[row.cable].spanPath(k))
        if (w.radius != 0) return false;
  }
  return true;
}

// J v* for one row at the start of the step along the Jacobians it pulls along (W's): v* on the
// dofs, the prescribed motion elsewhere.
double startRate(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r) {
  double rate = 0;
  forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double weight) {
    for (const auto& e : jacobian) {
      if (const int d = ws.dofs.ofBody[e.body]; d >= 0) {
        rate += weight * e.d.dot(ws.vStar.segment<3>(d));
      } else {
        const BodyState& b = in.bodies[e.body];
        rate += weight * e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
      }
    }
  });
  return rate;
}

// The LCP on the start-of-step linearisation phi1 = phi0 + h J v1 (ws.lcpSolution): the
// shortcut's, and the answer where Newton on the end-of-step lengths diverges. Its J W is
// positive semidefinite, so its impulses are bounded by the motion they stop.
void solveStartOfStep(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                      bool redundant) {
  const int m = static_cast<int>(ws.rows.size());
  const double h = in.h;
  ws.K = ws.JW0;
  ws.b.resize(m);
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    double goal = ws.target[r];
    if (c.elastic() && row.segment < 0) {  // the implicit spring-damper (lengthTargets)
      const double k = c.stiffness(), damp = c.damping();
      ws.K(r, r) += 1.0 / (h * (k * h + damp));
      goal = damp * ws.phi0[r] / (k * h + damp);
    }
    ws.b[r] = (ws.phi0[r] - goal) / h + startRate(ws, in, cables, r);
  }
  solveLcp(ws.K, ws.b, ws.lcp, ws.lcpSolution, redundant);
}

// The shortcut's LCP on the start-of-step linearisation; true (ws.P set) if its remainder bound
// holds on every row.
bool solveLinearised(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     bool redundant, StepStats& stats) {
  if (!linearShortcut || ws.midpoint || !pointRowsOnly(ws, cables) ||
      std::find(ws.ahead.begin(), ws.ahead.end(), 1) != ws.ahead.end())
    return false;
  const double h = in.h;
  solveStartOfStep(ws, in, cables, redundant);
  const LcpSolution& sol = ws.lcpSolution;
  timesImpulses(ws, sol.x);
  ws.v1 = ws.vStar - ws.WP;
  // The remainder bound measures from the straight-line motion. A jointed body turns off it
  // (stepPose) by h |v| a / 2 or less (a = h omega): by far less than the tolerance too.
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const BodyState& s = in.bodies[ws.dofs.body[k]];
    BodyState& p = ws.predicted[ws.dofs.body[k]];
    p.position = s.position + h * ws.v1.segment<2>(3 * k);
    p.angle = s.angle + h * ws.v1[3 * k + 2];
    const double off =
        ws.motions[k].kind == StepMotion::Kind::Free ? 0
        : ws.motions[k].kind == StepMotion::Kind::Jointed
            ? 0.5 * h * h * ws.v1.segment<2>(3 * k).norm() * std::abs(ws.v1[3 * k + 2])
            : kLinearTolerance;  // pivoted: its anchor goes back on the pivot
    if (!(off <= 0.1 * kLinearTolerance)) return false;
  }
  for (const Workspace::Row& row : ws.rows)
    for (int k = row.first; k <= row.last; ++k)
      if (!(lengthRemainderBound(cables[row.cable].spanPath(k), in.bodies, ws.predicted) <=
            kLinearTolerance))
        return false;
  ws.P = sol.x;
  stats.solverIterations += sol.iterations;
  stats.residual = std::max(stats.residual, sol.residual);
  ++stats.linearSolves;
  return true;
}

// Whether Box2D can move the bodies as the impulses ws.P say: it moves no body further than
// b2_maxTranslation (2 m) or b2_maxRotation (pi / 2) a step, and an answer that needs more (a
// root of the end-of-step lengths a whole turn of a drum away) is none.
bool realisable(Workspace& ws, double h) {
  timesImpulses(ws, ws.P);
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const Vec3 v1 = ws.vStar.segment<3>(3 * k) - ws.WP.segment<3>(3 * k);
    if (!(h * v1.head<2>().norm() <= kMaxStepTranslation && h * std::abs(v1[2]) <= kMaxStepTurn))
      return false;
  }
  return true;
}

// Whether row r pulls on a kinematic body that moves (it hauls the row, stage 6d).
bool pullsOnDriven(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r) {
  if (!ws.hauling) return false;  // no kinematic body moves this sub-step (predictPrescribed)
  bool driving = false;
  forStartJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
    for (const auto& e : jacobian) driving |= driven(in.bodies[e.body]);
  });
  return driving;
}

// Whether the impulses ws.P leave an island of rigid rows (cables and floors) with more kinetic
// energy than such rows can give it. They only stop motion: the start-of-step LCP projects v*
// onto what they allow, which takes energy out, and the lengths they put right add what putting
// them right at their rates takes. A root of the end-of-step lengths that needs more is a pose
// the bodies cannot reach from here: a box whose rope is tied off its centre, turning as it
// reached its pulley at 9 m/s, had its tie point swung round to the pulley's far side, and the
// pair gained 190 J of their 470 in one step. Elastic rows store energy and driven bodies do
// work: their islands are not asked.
constexpr double kRigidEnergyAllowance = 0.1;  // of the kinetic energy at v*
bool addsEnergy(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  double correction = 0;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment < 0 && cables[row.cable].elastic()) return false;
    if (pullsOnDriven(ws, in, cables, r)) return false;
    const double rate = (ws.phi0[r] - ws.target[r]) / in.h;
    if (ws.JW0(r, r) > 0) correction += 0.5 * rate * rate / ws.JW0(r, r);
  }
  timesImpulses(ws, ws.P);
  double before = 0, after = 0;
  for (Eigen::Index d = 0; d < ws.vStar.size(); ++d)
    if (ws.invM[d] > 0) {
      const double v1 = ws.vStar[d] - ws.WP[d];
      before += 0.5 * ws.vStar[d] * ws.vStar[d] / ws.invM[d];
      after += 0.5 * v1 * v1 / ws.invM[d];
    }
  return after > (1 + kRigidEnergyAllowance) * before + correction;
}

// How far the rows miss their targets at the end of the step (m): rigid rows too long, floors
// closed past their length. Leaves phi1 at ws.P.
double unmetLength(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  linearise(ws, in, cables);
  double unmet = 0;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r)
    if (ws.rows[r].segment >= 0 || !cables[ws.rows[r].cable].elastic())
      unmet = std::max(unmet, ws.phi1[r] - ws.target[r]);
  return unmet;
}

// Whether the impulses ws.P leave a rigid row (a cable or a floor) more than kUnsettledLength
// past its target at the end of the step: the start-of-step answer, where Newton found none, is
// then too far off for the step to keep (World tries a shorter one). An island that a driven
// body hauls is solved again after this (stage 6d), and pays out what it cannot hold.
constexpr double kUnsettledLength = 1e-3;  // m
bool missesLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r)
    if (pullsOnDriven(ws, in, cables, r)) return false;
  return unmetLength(ws, in, cables) > kUnsettledLength;
}

// Rigid rows whose lengths no pose meets (redundant cables with rest lengths that disagree: a
// ring on 40 cables, some 1 or 2 cm short). The start-of-step LCP's targets, each row shortened
// by its Baumgarte share, then ask for a velocity no motion has, and its impulses grow without
// bound (4e12 N s threw the ring to 400 rad/s). Held at their lengths instead (target phi0), the
// rows ask for none: v1 = 0 meets them, so the impulses are bounded by the motion they stop.
// True if some row was let off its correction.
bool holdOverlongRows(Workspace& ws, std::span<const Cable> cables) {
  bool held = false;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0 || cables[row.cable].elastic() || !(ws.target[r] < ws.phi0[r])) continue;
    ws.target[r] = ws.phi0[r];
    held = true;
  }
  return held;
}

// 6. Newton on the end-of-step lengths phi1(P), each linearisation an LCP over all cables:
// tension >= 0, slack cables only shorten. A warm start that does not settle (a tiny mass the
// last impulses throw far) starts again from P = 0, so it only ever saves iterations.
void solveLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                  StepStats& stats) {
  const int m = static_cast<int>(ws.rows.size());
  ws.phi1.resize(m);
  ws.JW.resize(m, m);
  // Redundant cables (J0 W singular): J1 W is then singular too, but not symmetric, and its
  // symmetric part indefinite, so the minimum-norm solve (tension_solver.h) would be ill posed.
  // Such an island iterates on J0 W instead (a quasi-Newton step: it still converges to the
  // end-of-step lengths, only more slowly).
  bool& redundant = ws.redundant;
  redundant = false;
  if (m > 1 && (ws.compliance.array() == 0).any()) {  // elastic rows alone: K is definite
    ws.redundancy.compute(ws.JW0);
    redundant = rankDeficient(ws.redundancy);
  }
  if (solveLinearised(ws, in, cables, redundant, stats)) return;
  if (warmStart(ws, in.h, cables)) {
    StepStats warm;
    if (iterateNewton(ws, in, cables, redundant, warm) == Newton::Converged &&
        realisable(ws, in.h) && !addsEnergy(ws, in, cables)) {
      stats.solverIterations += warm.solverIterations;
      stats.residual = std::max(stats.residual, warm.residual);
      stats.linearisationFallbacks += warm.linearisationFallbacks;
      return;
    }
    ws.P.setZero(m);
  }
  if (iterateNewton(ws, in, cables, redundant, stats) != Newton::Diverged && realisable(ws, in.h) &&
      !addsEnergy(ws, in, cables))
    return;
  // Far from linear over the step: a segment the predicted motion folds past a wrap point, where
  // pulling harder makes the end-of-step length grow (Newton's impulses grew threefold an
  // iteration, to 8e4 N on a hand's band, and the soak's fingers were thrown), or a root a whole
  // turn of a drum away (the built-in winch, stalled with its weight at the drum, found one at
  // 1e5 N, then 1e7, 1e9, ... a step), or a root no rigid row can reach (addsEnergy). The
  // start-of-step linearisation answers instead; the next sub-step corrects what it leaves.
  solveStartOfStep(ws, in, cables, redundant);
  ws.P = ws.lcpSolution.x;
  stats.solverIterations += ws.lcpSolution.iterations;
  ++stats.newtonDivergences;
  if (addsEnergy(ws, in, cables) && holdOverlongRows(ws, cables)) {
    solveStartOfStep(ws, in, cables, redundant);
    ws.P = ws.lcpSolution.x;
    stats.solverIterations += ws.lcpSolution.iterations;
    ++stats.heldIslands;
    return;  // (the rows stay long: halving the step would not shorten them)
  }
  if (missesLengths(ws, in, cables)) ++stats.unsettledIslands;
}

// 6d. Hauled cables. A kinematic body cannot be stopped. Where it hauls a rigid cable out (its
// prescribed motion lengthens the row by haul_r in the sub-step) and the bodies along the cable
// cannot give way (a load already at its pulley, a boom that its stay holds), no tension holds
// the length: the rows are dependent and their targets inconsistent. Newton then leaves rows
// unmet (a load driven through its pulley and the cable metres long) or answers with impulses
// whose work against the kinematic body dwarfs every energy in the island (1e11 N s on a 10 kg
// load, and Box2D's float joints cannot cancel forces that size). Such rows pay out: solved
// again with the targets haulTargets gives them, kept unless that misses the rows by more, and
// applyForces lengthens each cable by its end-of-step stretch (Cable::payOut; World warns).
constexpr double kHaulUnmet = 1e-5;  // m: a row missed by more is not held
constexpr double kHaulWork = 1e3;    // work against the kinematic bodies, in island energies

// haul_r for the rigid cable rows (h J v over the kinematic bodies); true if any is hauled out.
bool hauledRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  bool any = false;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    if (ws.rows[r].segment >= 0 || cables[ws.rows[r].cable].elastic()) continue;
    double rate = 0;
    forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double weight) {
      for (const auto& e : jacobian)
        if (ws.dofs.ofBody[e.body] < 0) {
          const BodyState& b = in.bodies[e.body];
          rate += weight * e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
        }
    });
    ws.haul[r] = std::max(0.0, in.h * rate);
    any |= ws.haul[r] > 0;
  }
  return any;
}

// Whether the impulses do more work against the kinematic bodies (P_r haul_r / h) than
// kHaulWork times what the island's bodies would have moving at the haul speed on top of their
// own.
bool excessiveHaulWork(const Workspace& ws, double h) {
  const double most = ws.haul.maxCoeff();
  double energy = 0;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k)
    if (ws.invM[3 * k] > 0)
      energy += std::pow(most / h + ws.vStar.segment<2>(3 * k).norm(), 2) / ws.invM[3 * k];
  return ws.P.dot(ws.haul) / h > kHaulWork * energy;
}

// Paying out, a hauled row's target is its length error now plus what the kinematic bodies alone
// lengthen it by over the step, measured on the path (the dofs at their start pose, the kinematic
// bodies at their end pose), not h J v: it asks the rest to take back nothing, neither the
// length's curvature over the step nor a length error of before. The rows it depends on (a floor
// holding the load, a stay holding the boom) then agree with it, and no tension squeezes the load
// between the cable and its floor (at 4 sub-steps such a squeeze reached 1e7 N, the rows nearly
// dependent and their targets apart by the curvature).
void haulTargets(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int body : ws.dofs.body) ws.predicted[body] = in.bodies[body];
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    if (!(ws.haul[r] > 0)) continue;
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    double phi = 0;
    for (int k = row.first; k <= row.last; ++k) {
      pathAhead(ws, c, k, ws.predicted);
      phi += c.spanStretch(k) + ws.kin.length - c.spanKinematics(k).length;
    }
    ws.target[r] = std::max(phi, ws.phi0[r] + ws.haul[r]);
  }
}

void newtonOnLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     StepStats& stats) {
  ws.haul.setZero(static_cast<Eigen::Index>(ws.rows.size()));
  solveLengths(ws, in, cables, stats);
  if (!ws.hauling || !hauledRows(ws, in, cables)) {
    ws.haul.setZero();
    return;
  }
  double unmet = unmetLength(ws, in, cables);
  // A Newton that ran out of iterations misses by what it had left, not because nothing can give
  // way: a box whirled on a rope from a kinematic jib, jerked taut after going slack, missed by
  // 4e-5 m after 3 iterations, and the rope paid out 3.7 cm for good. Newton goes on from where it
  // stopped before the rows pay out.
  if (unmet > kHaulUnmet) {
    const Eigen::VectorXd stopped = ws.P;
    StepStats more;
    if (iterateNewton(ws, in, cables, ws.redundant, more) == Newton::Converged &&
        realisable(ws, in.h)) {
      stats.solverIterations += more.solverIterations;
      unmet = unmetLength(ws, in, cables);
    } else {
      ws.P = stopped;
    }
  }
  if (unmet <= kHaulUnmet && !excessiveHaulWork(ws, in.h)) {
    ws.haul.setZero();
    return;
  }
  // Paying out, the rows the kinematic bodies haul may come slack and the rest stop what they
  // must (a load arriving at its pulley: an inelastic stop). Where Newton's end-of-step geometry
  // is still near the dependent one (its impulses as large as before), the start-of-step LCP,
  // whose J0 W is positive semidefinite, answers.
  ws.unhauledP = ws.P;
  ws.unhauledTarget = ws.target;
  haulTargets(ws, in, cables);
  solveLengths(ws, in, cables, stats);
  if (excessiveHaulWork(ws, in.h)) {
    solveStartOfStep(ws, in, cables, ws.redundant);
    ws.P = ws.lcpSolution.x;
  }
  if (unmetLength(ws, in, cables) > std::max(unmet, kHaulUnmet)) {
    ws.target = ws.unhauledTarget;
    ws.P = ws.unhauledP;
    ws.haul.setZero();
    return;
  }
  // A cable pays out what it is too long at the end of this answer (phi1 is at it): the 1 cm of
  // an 8 cm haul that a load arriving at its pulley could not take up, then the haul itself
  // while the load stays there, and any length error that the dependent rows keep the motion from
  // taking back. Its length then agrees with the rows it depends on, and the next sub-step's
  // tensions are the least that hold the load, not a squeeze between the cable and a floor.
  for (Eigen::Index r = 0; r < ws.haul.size(); ++r) {
    if (!(ws.haul[r] > 0)) continue;
    ws.haul[r] = std::clamp(ws.phi1[r], 0.0, 2 * ws.haul[r] + std::max(0.0, ws.phi0[r]));
  }
}

constexpr int kBalancePasses = 4;

// 6a. The midpoint rule's energy balance. Row r's impulse does work P_r J_r (v0 + v1) / 2 on the
// bodies (J_r the Jacobian it pulls along; the joints' reactions do none), and the cable's energy
// changes by V(phi1) - V(phi0). Newton's discrete gradient makes the two equal where phi1 -
// phi0 = h J_r (v0 + v1) / 2; the length's curvature and a jointed body's turn (stepPose) leave
// a second-order difference, which over many swings adds up: an arm on a pivot with an undamped
// spring, its joint keeping its energy (joint_energy.h), gained 2.3 times its energy in 60 s at
// 60 Hz. Each pulling row's impulse is scaled until the two match, where the factor is within
// 0.5..2 (a few passes: the scaling moves the end pose a little).
void balanceMidpointWork(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int pass = 0; pass < kBalancePasses; ++pass) {
    linearise(ws, in, cables);  // phi1 and v1 at these impulses
    double worst = 0;
    for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
      if (!(ws.P[r] > 0)) continue;
      double rate = 0;  // J_r (v0 + v1) / 2
      forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
        for (const auto& e : jacobian)
          if (const int d = ws.dofs.ofBody[e.body]; d >= 0)
            rate += 0.5 * e.d.dot(ws.v0.segment<3>(d) + ws.v1.segment<3>(d));
      });
      const double k = cables[ws.rows[r].cable].stiffness();
      auto energy = [&](double phi) { return phi > 0 ? 0.5 * k * phi * phi : 0.0; };
      const double scale = (energy(ws.phi1[r]) - energy(ws.phi0[r])) / (ws.P[r] * rate);
      if (!(scale > 0.5 && scale < 2)) continue;
      ws.P[r] *= scale;
      worst = std::max(worst, std::abs(scale - 1));
    }
    if (worst < 1e-9) return;
  }
}

// 6c. Joint limits (joint_limits.h): true if the solved step takes a limited joint past its
// bound, which it then locks (stages 2-6 run again).
bool lockCrossingLimits(Workspace& ws, const CableSolveInput& in) {
  if (std::none_of(ws.jointIndex.begin(), ws.jointIndex.end(),
                   [&](int j) { return in.joints[j].limited; }))
    return false;
  timesImpulses(ws, ws.P);
  ws.vEnd = ws.vStar - ws.WP;
  return ws.limits.lockCrossing(in.joints, ws.jointIndex, in.bodies, ws.dofs.ofBody, ws.vEnd, in.h);
}

// 6e. Under the midpoint rule a rigid row pulls along J at the midpoint pose q0 + h (v0 + v1) / 4
// of the step just solved, as near the discrete gradient of its length as a turning path allows
// (G (q1 - q0) = length(q1) - length(q0): the row then does no work). Along the start-of-step J
// it did work a step on the turning path that added up: the hexagon on its pivot gained 47% of
// its largest kinetic energy in a minute. An elastic row pulls there too, whatever stage 4b gave
// it: along J0 (or 4b's half share for a joining vertex) its work missed its energy change by the
// first order in the turn (a polygon's lever arm changes across the step), often by more than
// stage 6a's factors 0.5..2 can balance; four undamped ropes over a hexagon spinning at 10 rad/s
// gained 25% of their largest kinetic energy in a minute, now 0.2%. True if any row was
// redirected (stages 2-5 run again).
bool pullAlongMidpointPose(Workspace& ws, const CableSolveInput& in,
                           std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  if (static_cast<int>(ws.ahead.size()) != m) ws.ahead.assign(m, 0);
  ws.aheadJacobian.resize(m);
  timesImpulses(ws, ws.P);
  ws.v1 = ws.vStar - ws.WP;
  ws.free.assign(ws.predicted.begin(), ws.predicted.end());
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const int b = ws.dofs.body[k];
    stepPose(in.bodies[b], movedWith(ws, k, ws.v1.segment<3>(3 * k)), 0.5 * in.h, ws.motions[k],
             ws.free[b]);
  }
  bool any = false;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    // A rigid row that stage 4b redirected keeps that Jacobian (takesMidpointRule refuses it).
    if ((ws.ahead[r] && !c.elastic()) || row.segment >= 0 || !(ws.P[r] > 0)) continue;
    pathAhead(ws, c, row.first, ws.free);
    ws.aheadJacobian[r] = ws.kin.jacobian;
    ws.ahead[r] = 1;
    any = true;
  }
  return any;
}

// 7. The tensions, and the force that gives the end-of-step velocity solved for (cable pull,
// geometric stiffness and joint reactions together): Box2D integrates v += h M^-1 F.
void applyForces(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                 std::span<Vec3> loads) {
  const double h = in.h;
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0) continue;  // a floor pushes; it is no cable's tension
    for (int k = row.first; k <= row.last; ++k)
      cables[row.cable].setSpanTension(k, row.weight(ws.rowWeights, k) * ws.P[r] / h);
    for (int k = row.first; k < row.last; ++k) cables[row.cable].setSlipped(k, true);
    if (ws.haul[r] > 0) cables[row.cable].payOut(row.first, ws.haul[r]);
  }
  for (const Workspace::Row& row : ws.rows) {
    const Cable& c = cables[row.cable];
    ws.warm[row.cable] = {h, c.tension(), c.spanCount()};
  }
  timesImpulses(ws, ws.P);
  // Under the midpoint rule Box2D reaches (v0 + v1) / 2 and the rest comes after its step. A link
  // pivoted on a body that does not move ends where the lengths were solved for, its anchor on
  // the pivot (stepPose), not where Box2D's joint correction puts it, (h omega)^3 or so away (at
  // a fast catch, as far as 1 cm of rope). Other jointed bodies keep Box2D's pose, whose
  // correction holds their joints together; so does a touching one, for its contacts.
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const int body = ws.dofs.body[k];
    const Vec3 v1 = ws.vStar.segment<3>(3 * k) - ws.WP.segment<3>(3 * k);
    const Vec3 reached = movedWith(ws, k, v1);
    for (int c = 0; c < 3; ++c) {
      const int d = 3 * static_cast<int>(k) + c;
      if (ws.invM[d] == 0) continue;
      loads[body][c] += (reached[c] - ws.vFree[d]) / (h * ws.invM[d]);
      if (ws.midpoint) in.kicks[body][c] += v1[c] - reached[c];
    }
    if (!in.placements.empty() && placedAfterStep(ws.motions[k], in.touching, body)) {
      BodyState& p = ws.predicted[body];
      stepPose(in.bodies[body], reached, h, ws.motions[k], p);
      in.placements[body] = {true, p.position, p.angle};
    }
  }
}

// 6b. Capstans: where the sticking tensions break T_high <= T_low e^(mu theta), the cable slides
// at that ratio instead (Euler-Eytelwein): the two rows beside the wheel become one, whose
// constraint is their summed length. True if any merged (then stages 2-6 run again).
bool mergeSlidingSpans(Workspace& ws, std::span<const Cable> cables) {
  bool merged = false;
  for (size_t r = 0; r + 1 < ws.rows.size(); ++r) {
    Workspace::Row& a = ws.rows[r];
    const Workspace::Row& b = ws.rows[r + 1];
    if (a.cable != b.cable || a.last + 1 != b.first || a.segment >= 0 || b.segment >= 0) continue;
    const SpanLink& link = cables[a.cable].link(a.last);
    if (link.grip != Grip::Capstan) continue;
    const double wa = a.weight(ws.rowWeights, a.last), wb = b.weight(ws.rowWeights, b.first);
    const double ta = ws.P[r] * wa, tb = ws.P[r + 1] * wb;
    const double ratio = std::exp(link.mu * std::max(0.0, link.wrapAngle));
    if (std::max(ta, tb) <= ratio * std::min(ta, tb) * (1 + 1e-9)) continue;
    // The merged row's impulse is b's: a's spans pull with ratio (or 1 / ratio) times it.
    const double scale = (ta > tb ? ratio : 1.0 / ratio) * wb / wa;
    const size_t offset = ws.rowWeights.size();
    for (int k = a.first; k <= a.last; ++k)
      ws.rowWeights.push_back(scale * a.weight(ws.rowWeights, k));
    for (int k = b.first; k <= b.last; ++k) ws.rowWeights.push_back(b.weight(ws.rowWeights, k));
    a.weights = offset;
    a.last = b.last;
    ws.rows.erase(ws.rows.begin() + static_cast<std::ptrdiff_t>(r) + 1);
    merged = true;
    --r;  // the merged row may slide on its next capstan too
  }
  return merged;
}

}  // namespace

void setLinearShortcut(bool on) {
  linearShortcut = on;
}

CableSolver::CableSolver() : ws_(std::make_unique<CableSolverWorkspace>()) {}
CableSolver::~CableSolver() = default;

void CableSolver::solve(const CableSolveInput& in, std::span<Cable> cables, std::span<Vec3> loads,
                        StepStats& stats) {
  CableSolverWorkspace& ws = *ws_;
  const int islands = findIslands(ws, in, cables);
  if (islands == 0) return;
  if (ws.dofs.ofBody.size() != in.bodies.size()) ws.dofs.reset(in.bodies.size());
  if (ws.warm.size() != cables.size()) ws.warm.assign(cables.size(), {});
  predictPrescribed(ws, in);
  for (int island = 0; island < islands; ++island) {
    // Big islands take the sparse path where it applies (sparse_island.h says which).
    if (ws.sparse.solve(in, cables, ws.islandRows[island], ws.islandJoints[island], ws.predicted,
                        loads, stats))
      continue;
    buildRows(ws, in, cables, island);
    ws.ahead.clear();
    ws.limits.free(ws.jointIndex, static_cast<int>(in.joints.size()));
    for (bool again = true; again;) {
      prepareRows(ws, in, cables, loads);
      if (ws.ahead.empty() && redirectBlockedRows(ws, in, cables))
        prepareRows(ws, in, cables, loads);
      ws.midpoint = takesMidpointRule(ws, in, cables);
      lengthTargets(ws, in.h, in.share, cables);
      newtonOnLengths(ws, in, cables, stats);
      if (ws.midpoint && pullAlongMidpointPose(ws, in, cables)) {
        prepareRows(ws, in, cables, loads);
        lengthTargets(ws, in.h, in.share, cables);
        newtonOnLengths(ws, in, cables, stats);
      }
      if (ws.midpoint) balanceMidpointWork(ws, in, cables);
      again = mergeSlidingSpans(ws, cables);
      if (again) {
        ws.ahead.clear();  // the rows changed: measure them again
      } else {
        again = lockCrossingLimits(ws, in);  // 6c
      }
    }
    applyForces(ws, in, cables, loads);
  }
  ws.dofs.clear();
}

}  // namespace cablelab
