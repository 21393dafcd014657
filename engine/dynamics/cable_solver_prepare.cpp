// Stages 2-4 of the cable solve (cable_solver.cpp): the predicted velocities, W = M'^-1 J^T with
// the taut cables' geometric stiffness, and their projection onto the joints.
#include "engine/dynamics/cable_solver_stages.h"

#include "engine/dynamics/geometric_stiffness.h"
#include "engine/dynamics/joint_projection.h"
#include "engine/dynamics/joint_tree.h"

namespace cablelab {

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

namespace cable_stages {

namespace {

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
    // Once per cable (not a floor, not a later span); none where stage 5a leaves it out.
    if (!ws.stiffnessLeftOut && row.segment < 0 && row.first == 0) {
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

}  // namespace

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

}  // namespace cable_stages

}  // namespace cablelab
