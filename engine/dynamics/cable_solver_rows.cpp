// Stage 1 of the cable solve (cable_solver.cpp): the islands, each island's rows and dofs, and
// the floor rows (floors.h).
#include "engine/dynamics/cable_solver_stages.h"

#include "engine/dynamics/disjoint_sets.h"
#include "engine/dynamics/floors.h"
#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

namespace {

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

// Whether segment (p, q) could close to kFloorLength within the step, at the speed its ends have
// now plus a step of gravity (twice that, and a floor length, for margin): only then does it get
// a floor row. A hand's membranes have short end segments that never come close; rows cost.
bool mayReachFloor(const CableSolveInput& in, const WrapPoint& p, const WrapPoint& q) {
  auto speed = [&](const WrapPoint& w) {
    if (w.body < 0) return 0.0;
    const BodyState& b = in.bodies[w.body];
    const Vec2 v = pointVelocity(b, w.world);
    return v.norm() + (b.invMass > 0 ? in.h * in.gravity.norm() : 0.0);
  };
  const double gap = floorGap(p, q);
  return gap > 1e-9 && gap < 2 * kFloorLength + 2 * in.h * (speed(p) + speed(q));
}

}  // namespace

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
    auto moved = [&](int b) { return ws.dofs.ofBody[b] >= 0; };
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      const bool floor = needsFloor(cables[cable], i, in.bodies, in.h, in.gravity, moved) &&
                         mayReachFloor(in, path[i], path[i + 1]);
      // A slack cable's point at a circle: the rim row alone (needsDiscFloor).
      if (!floor && !needsDiscFloor(cables[cable], i, in.bodies, in.h, in.gravity, moved)) continue;
      const Vec2 n = floorNormal(path[i], path[i + 1], in.bodies, in.h, in.gravity);
      if (floor) {
        ws.rows.push_back({cable, 0, 0, ws.rowWeights.size(), static_cast<int>(i), n});
        ws.rowWeights.push_back(1.0);
      }
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
    const Vec2 offset = (e == 0 ? w.leaving() : w.arriving()) - w.world;
    along -= sign * n.dot(centre + offset);
    if (w.body < 0) continue;
    const Vec2 arm = centre - bodies[w.body].position;
    ws.floorJacobian.push_back({w.body, sign * Vec3(n.x(), n.y(), n.dot(perp(arm)))});
  }
  return kFloorLength - along;
}

}  // namespace cablelab::cable_stages
