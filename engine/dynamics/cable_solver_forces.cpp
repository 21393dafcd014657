// Stage 7 of the cable solve (cable_solver.cpp): the tensions, and the forces and poses that
// realise the solved end-of-step velocities.
#include "engine/dynamics/cable_solver_stages.h"

#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

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

}  // namespace cablelab::cable_stages
