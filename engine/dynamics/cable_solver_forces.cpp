// Stage 7 of the cable solve (cable_solver.cpp): the tensions, and the forces and poses that
// realise the solved end-of-step velocities.
#include "engine/dynamics/cable_solver_stages.h"

#include <cmath>

#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

namespace {

// Under the midpoint rule gravity acts at the start pose: its work over the step is
// h m g . (v0 + v1) / 2, but a jointed body moves along the chord of its turn (stepPose), and
// gravity's potential changes by m g . (x1 - x0). For a link hanging below its pivot the two
// differ by m g L (h omega)^2 / 2 a step, always a gain: a square pendulum swinging into an
// elastic band gained 3.9 J of its 4.4 J largest kinetic energy in ten minutes at 60 Hz. That
// difference and what stage 6a left unbalanced (`cableGained`, midpointWorkLeft) are taken out
// of (or given back to) the island's end-of-step kinetic energy: the factor on v1 that does it
// (1 where it would take more than half of it: left as it is).
double midpointEnergyScale(const Workspace& ws, const CableSolveInput& in, double cableGained) {
  double gained = cableGained, kinetic = 0;
  BodyState end;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const int body = ws.dofs.body[k];
    const Vec3 v1 = ws.vStar.segment<3>(3 * k) - ws.WP.segment<3>(3 * k);
    for (int c = 0; c < 3; ++c) {
      const double invM = ws.invM[3 * static_cast<int>(k) + c];
      if (invM > 0) kinetic += 0.5 * v1[c] * v1[c] / invM;
    }
    const double invMass = ws.invM[3 * static_cast<int>(k)];
    if (ws.motions[k].kind == StepMotion::Kind::Free || !(invMass > 0)) continue;
    const Vec3 mean = movedWith(ws, k, v1);
    stepPose(in.bodies[body], mean, in.h, ws.motions[k], end);
    const Vec2 chord = end.position - in.bodies[body].position;
    gained += in.gravity.dot(in.h * mean.head<2>() - chord) / invMass;
  }
  if (!(kinetic > 0) || !(std::abs(gained) < 0.5 * kinetic)) return 1.0;
  return std::sqrt(1 - gained / kinetic);
}

}  // namespace

// 7. The tensions, and the force that gives the end-of-step velocity solved for (cable pull,
// geometric stiffness and joint reactions together): Box2D integrates v += h M^-1 F.
void applyForces(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                 std::span<Vec3> loads) {
  const double h = in.h;
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0) continue;  // a floor pushes; it is no cable's tension
    Cable& c = cables[row.cable];
    for (int k = row.first; k <= row.last; ++k) {
      const double impulse = row.weight(ws.rowWeights, k) * ws.P[r];
      // An elastic cable that slid: each span's stretch under its own spring law, by which the
      // end-of-step refresh shares the slid material (Cable::setSlidStretch).
      if (c.elastic() && row.first < row.last)
        c.setSlidStretch(k, springStretchAtEnd(c, k, impulse, h));
      c.setSpanTension(k, impulse / h);
    }
    for (int k = row.first; k < row.last; ++k) c.setSlipped(k, true);
    if (ws.haul[r] > 0) c.payOut(row.first, ws.haul[r]);
  }
  for (const Workspace::Row& row : ws.rows) {
    const Cable& c = cables[row.cable];
    ws.warm[row.cable] = {h, c.tension(), c.spanCount()};
    ws.floorWarm[row.cable].clear();
  }
  for (size_t r = 0; r < ws.rows.size(); ++r)
    if (const Workspace::Row& row = ws.rows[r]; row.segment >= 0 && ws.P[r] > 0)
      ws.floorWarm[row.cable].push_back(floorImpulse(cables[row.cable], row, ws.P[r]));
  timesImpulses(ws, ws.P);
  const double endScale =
      ws.midpoint ? midpointEnergyScale(ws, in, midpointWorkLeft(ws, in, cables)) : 1.0;
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
      if (ws.midpoint) in.kicks[body][c] += endScale * v1[c] - reached[c];
    }
    if (!in.placements.empty() && placedAfterStep(ws.motions[k], in.touching, body)) {
      BodyState& p = ws.predicted[body];
      stepPose(in.bodies[body], reached, h, ws.motions[k], p);
      in.placements[body] = {true, p.position, p.angle};
    }
  }
}

}  // namespace cablelab::cable_stages
