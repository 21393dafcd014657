// The sparse solve of one big island: see sparse_island.h for the system, docs/model.md ("Big
// islands") for the threshold and the measured cost. Each stage mirrors the dense one of the
// same name in cable_solver.cpp, so that both give the same tensions (tests/engine/dynamics/
// sparse_island_test.cpp).
#include "engine/dynamics/sparse_island.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/floors.h"
#include "engine/dynamics/geometric_stiffness.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/newton_stop.h"
#include "engine/dynamics/step_pose.h"
#include "engine/dynamics/tension_solver.h"

namespace cablelab {

namespace {

constexpr int kDefaultSparseThreshold = 32;
int sparseThreshold = kDefaultSparseThreshold;

constexpr int kSparseNewtonIterations = 3;  // as the dense path's kNewtonIterations

// ldlt <- A, ordering A again only if its pattern is not the one `pattern` holds (stored).
void refactor(Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& ldlt,
              const Eigen::SparseMatrix<double>& A, std::vector<int>& pattern) {
  const int outer = static_cast<int>(A.outerSize()) + 1, nnz = static_cast<int>(A.nonZeros());
  bool same = static_cast<int>(pattern.size()) == outer + nnz;
  for (int i = 0; same && i < outer; ++i) same = pattern[i] == A.outerIndexPtr()[i];
  for (int i = 0; same && i < nnz; ++i) same = pattern[outer + i] == A.innerIndexPtr()[i];
  if (!same) {
    pattern.assign(A.outerIndexPtr(), A.outerIndexPtr() + outer);
    pattern.insert(pattern.end(), A.innerIndexPtr(), A.innerIndexPtr() + nnz);
    ldlt.analyzePattern(A);
  }
  ldlt.factorize(A);
}

}  // namespace

int sparseIslandThreshold() {
  return sparseThreshold;
}

void setSparseIslandThreshold(int rows) {
  sparseThreshold = rows < 0 ? kDefaultSparseThreshold : rows;
}

// Big enough, and none of the cases the dense path alone handles (sparse_island.h).
bool SparseIsland::qualifies(const CableSolveInput& in, std::span<const Cable> cables,
                             std::span<const int> islandCables, std::span<const int>) const {
  if (static_cast<int>(islandCables.size()) <= sparseThreshold) return false;
  auto moved = [&](int b) { return moves(in.bodies[b]); };
  for (int cable : islandCables) {
    const Cable& c = cables[cable];
    if (c.spanCount() != 1) return false;  // capstans and gripping wheels: dense only
    const auto path = c.path();
    for (size_t i = 0; i + 1 < path.size(); ++i)
      if (needsFloor(c, i, in.bodies, in.h, in.gravity, moved) ||
          needsDiscFloor(c, i, in.bodies, in.h, in.gravity, moved))
        return false;  // dense only
  }
  return true;
}

// Dense stage 2: the dofs (the cables' moving bodies, in cable order), M^-1, v* and J0.
void SparseIsland::buildDofs(const CableSolveInput& in, std::span<const Cable> cables,
                             std::span<const Vec3> loads) {
  if (dofOfBody_.size() != in.bodies.size()) dofOfBody_.assign(in.bodies.size(), -1);
  for (int b : bodyOfDof_) dofOfBody_[b] = -1;
  bodyOfDof_.clear();
  for (int cable : rows_)
    for (const auto& e : cables[cable].spanKinematics(0).jacobian)
      if (moves(in.bodies[e.body]) && dofOfBody_[e.body] < 0) {
        dofOfBody_[e.body] = 3 * static_cast<int>(bodyOfDof_.size());
        bodyOfDof_.push_back(e.body);
      }
  // Bodies jointed to them move with them (breadth first, as the dense path's dofs).
  for (size_t k = 0; k < bodyOfDof_.size(); ++k)
    for (int other : in.jointNeighbours[bodyOfDof_[k]])
      if (moves(in.bodies[other]) && dofOfBody_[other] < 0) {
        dofOfBody_[other] = 3 * static_cast<int>(bodyOfDof_.size());
        bodyOfDof_.push_back(other);
      }
  n_ = 3 * static_cast<int>(bodyOfDof_.size());
  invM_.resize(n_);
  vRaw_.resize(n_);
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const BodyState& s = in.bodies[bodyOfDof_[k]];
    invM_.segment<3>(3 * k) = Vec3(s.invMass, s.invMass, s.invInertia);
    Vec3 v(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    v += in.h * (invM_.segment<3>(3 * k).cwiseProduct(loads[bodyOfDof_[k]]));
    if (s.invMass > 0) v.head<2>() += in.h * in.gravity;
    vRaw_.segment<3>(3 * k) = v;
  }
  vFree_ = vRaw_;
  j0_.clear();
  j0Start_.assign(1, 0);
  j0Diagonal_.assign(m_, 0.0);
  for (int r = 0; r < m_; ++r) {
    for (const auto& e : cables[rows_[r]].spanKinematics(0).jacobian)
      if (const int d = dofOfBody_[e.body]; d >= 0)
        for (int c = 0; c < 3; ++c) {
          if (entered(e.body, c, e.d[c])) j0_.emplace_back(r, d + c, e.d[c]);
          j0Diagonal_[r] += e.d[c] * e.d[c] * invM_[d + c];
        }
    j0Start_.push_back(static_cast<int>(j0_.size()));
  }
}

// Whether component c of a Jacobian entry on `body` goes into the matrices. A cable tied to a
// body's centre does not turn it: those zeros are left out (a third fewer unknowns in a chain),
// but once a body has been turned by a cable its turn stays in, so the KKT pattern (and its
// ordering) does not change with the values.
bool SparseIsland::entered(int body, int c, double value) {
  if (c < 2) return true;
  if (turns_.size() <= static_cast<size_t>(body)) turns_.resize(body + 1, 0);
  if (value != 0) turns_[body] = 1;
  return turns_[body] != 0;
}

// Dense stage 3: M' = M + h^2 T G where the taut cables' geometric stiffness matters, built
// sparse (the dense path's coupled block, same entries), and M v* on the right-hand side.
void SparseIsland::buildStiffMass(double h, std::span<const Cable> cables) {
  blocks_.clear();
  stiffTriplets_.clear();
  stiff_ = false;
  taut_.clear();
  for (int cable : rows_) {
    const Warm& last = warm_[cable];
    const double tension = cables[cable].tension();
    const double pulling = pullingTension(tension, last.tension == tension ? last.h : 0, h);
    addGeometricStiffness(cables[cable], pulling, h, dofOfBody_, invM_, blocks_, taut_, stiff_);
  }
  momentum_.resize(n_);
  for (int d = 0; d < n_; ++d)  // an immovable dof keeps v* (dense: 0 once stiff)
    momentum_[d] = invM_[d] > 0 ? vRaw_[d] / invM_[d] : (stiff_ ? 0.0 : vRaw_[d]);
  if (!stiff_) return;
  for (const TautCable& t : taut_)
    for (size_t i = t.begin; i < t.end; ++i) {
      const int ia = dofOfBody_[blocks_[i].a], ib = dofOfBody_[blocks_[i].b];
      if (ia < 0 || ib < 0) continue;
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c)
          if (invM_[ia + r] > 0 && invM_[ib + c] > 0)
            stiffTriplets_.emplace_back(ia + r, ib + c, h * h * t.tension * blocks_[i].k(r, c));
    }
  for (int d = 0; d < n_; ++d) stiffTriplets_.emplace_back(d, d, invM_[d] > 0 ? 1 / invM_[d] : 1);
  mass_.resize(n_, n_);
  mass_.setFromTriplets(stiffTriplets_.begin(), stiffTriplets_.end());
  stiffTriplets_.resize(stiffTriplets_.size() - n_);  // keep the off-diagonal part only
  refactor(massLdlt_, mass_, massPattern_);
}

// Redundant cables: J0 M^-1 J0^T singular (same rank as the dense path's J0 M'^-1 J0^T).
// Its LDLT pivots below kRankTolerance of the largest send the island to the dense path.
bool SparseIsland::redundant() {
  if (q_ == 0 && (m_ <= 1 || (compliance_.array() != 0).all())) return false;
  // With joints: [J0; C] (a cable the joints make redundant, or a closed loop of joints).
  std::vector<Triplet> rows = j0_;
  for (int j = 0; j < q_; ++j)
    for (int k = 0; k < 2; ++k)
      if (const int d = joints_[j].dof[k]; d >= 0)
        for (int c = 0; c < 3; ++c) rows.emplace_back(m_ + j, d + c, joints_[j].coeff[k][c]);
  Sparse J(m_ + q_, n_);
  J.setFromTriplets(rows.begin(), rows.end());
  const Sparse A = J * invM_.asDiagonal() * J.transpose();
  refactor(rankLdlt_, A, rankPattern_);
  if (rankLdlt_.info() != Eigen::Success) return true;
  const Eigen::VectorXd d = rankLdlt_.vectorD();
  return !(d.minCoeff() > kRankTolerance * d.cwiseAbs().maxCoeff());
}

// Dense stage 5, for one-span cables without floors.
void SparseIsland::lengthTargets(double h, double share, std::span<const Cable> cables) {
  const double beta = kBaumgarte * share;
  target_.resize(m_);
  compliance_.setZero(m_);
  damped_.setZero(m_);
  for (int r = 0; r < m_; ++r) {
    const Cable& c = cables[rows_[r]];
    const double phi = c.spanStretch(0);
    if (!c.elastic()) {
      target_[r] = phi < -kLengthSlop  ? 0.0
                   : phi > kLengthSlop ? phi - beta * (phi - kLengthSlop)
                                       : phi;
    } else {
      const double k = c.stiffness(), damp = c.damping();
      compliance_[r] = 1.0 / (h * (k * h + damp));
      damped_[r] = damp * phi / (k * h + damp);
    }
  }
}

// Newton's warm start, as the dense path's: the last impulses if this path set the tension.
void SparseIsland::warmStart(double h, std::span<const Cable> cables) {
  P_.setZero(m_);
  for (int r = 0; r < m_; ++r) {
    const Cable& c = cables[rows_[r]];
    const Warm& last = warm_[rows_[r]];
    if (last.h == h && last.tension == c.tension()) P_[r] = std::max(0.0, c.spanTension(0)) * h;
  }
}

// The island's joints, C v1 + bias = 0 (appendJointRows, the dense path's rows). In the KKT
// system they are equality rows with reactions C^T lambda: the same v1 as the dense path's
// projection through S = C M'^-1 C^T.
void SparseIsland::jointRows(const CableSolveInput& in, std::span<const int> islandJoints) {
  joints_.clear();
  for (int j : islandJoints)
    appendJointRows(in.joints[j], in.bodies, dofOfBody_, joints_, limits_.lock(j));
  motions_.resize(bodyOfDof_.size());
  stepMotions(in.joints, islandJoints, in.bodies, dofOfBody_, motions_);
  q_ = static_cast<int>(joints_.size());
}

// v1 = M'^-1 (M v* - J0^T P): the velocities the impulses P give (with joints: the KKT system
// with P fixed, so that v1 also keeps the joints).
void SparseIsland::velocitiesAt(const Eigen::VectorXd& P) {
  if (q_ > 0) {
    fixed_ = &P;
    factorAndSolve();
    fixed_ = nullptr;
    v1_ = sol_.head(n_);
    return;
  }
  rhs_ = momentum_;
  for (const Triplet& t : j0_)
    if (invM_[t.col()] > 0) rhs_[t.col()] -= t.value() * P[t.row()];
  if (stiff_) {
    v1_ = massLdlt_.solve(rhs_);
  } else {
    v1_.resize(n_);
    for (int d = 0; d < n_; ++d) v1_[d] = invM_[d] > 0 ? rhs_[d] * invM_[d] : rhs_[d];
  }
}

// Dense linearise(): the end-of-step state for v1 (stepPose), each row's
// end-of-step length error and its J1, with the dense guard (a row whose J1 has turned against
// its J0 uses J0; measured here with M^-1, the dense path uses M'^-1).
void SparseIsland::linearise(const CableSolveInput& in, std::span<const Cable> cables,
                             std::span<BodyState> predicted, StepStats& stats) {
  const double h = in.h;
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const BodyState& s = in.bodies[bodyOfDof_[k]];
    stepPose(s, v1k_.segment<3>(3 * k), h, motions_[k], predicted[bodyOfDof_[k]]);
  }
  j1_.clear();
  j1Start_.assign(1, 0);
  phi1_.resize(m_);
  for (int r = 0; r < m_; ++r) {
    const Cable& c = cables[rows_[r]];
    const std::span<const WrapPoint> span = c.spanPath(0);
    path_.assign(span.begin(), span.end());
    cableLengthJacobian(path_, predicted, kin_);
    phi1_[r] = c.spanStretch(0) + kin_.length - c.spanKinematics(0).length;
    const size_t begin = j1_.size();
    double jw = 0;
    for (const auto& e : kin_.jacobian)
      if (const int d = dofOfBody_[e.body]; d >= 0)
        for (int k = 0; k < 3; ++k) {
          if (entered(e.body, k, e.d[k])) j1_.emplace_back(r, d + k, e.d[k]);
          for (int i = j0Start_[r]; i < j0Start_[r + 1]; ++i)
            if (j0_[i].col() == d + k) jw += e.d[k] * invM_[d + k] * j0_[i].value();
        }
    if (!(jw > 1e-3 * j0Diagonal_[r])) {
      j1_.resize(begin);
      j1_.insert(j1_.end(), j0_.begin() + j0Start_[r], j0_.begin() + j0Start_[r + 1]);
      ++stats.linearisationFallbacks;
    }
    j1Start_.push_back(static_cast<int>(j1_.size()));
  }
  e_.resize(m_);
  for (int r = 0; r < m_; ++r)
    e_[r] = (cables[rows_[r]].elastic() ? phi1_[r] - damped_[r] : phi1_[r] - target_[r]) / h;
}

// The KKT system of the active set (sparse_island.h), factored and solved into P_new (sol_'s
// tail) and v1 (its head). The dense LCP's regularisation 1e-12 (1 + K_ii) is kept. A row off
// the active set keeps its entries, as zeros, and reads P = 0: the pattern stays the same, so
// it is analysed (ordered) once and each change costs a numeric factorisation only.
void SparseIsland::factorAndSolve() {
  kkt_.clear();
  if (stiff_) kkt_ = stiffTriplets_;
  for (int d = 0; d < n_; ++d) kkt_.emplace_back(d, d, invM_[d] > 0 ? 1 / invM_[d] : 1);
  rhs_.resize(n_ + m_ + q_);
  rhs_.head(n_) = momentum_;
  for (int r = 0; r < m_; ++r) {
    const int row = n_ + r;
    // fixed_: P given (the impulses act, the row reads P_r = given); else the LCP's rows.
    const bool on = fixed_ || active_[r], equation = !fixed_ && active_[r];
    for (int i = j0Start_[r]; i < j0Start_[r + 1]; ++i)
      if (invM_[j0_[i].col()] > 0) kkt_.emplace_back(j0_[i].col(), row, on ? j0_[i].value() : 0);
    double j1v = 0;
    for (int i = j1Start_[r]; i < j1Start_[r + 1]; ++i) {
      kkt_.emplace_back(row, j1_[i].col(), equation ? j1_[i].value() : 0);
      if (equation) j1v += j1_[i].value() * v1k_[j1_[i].col()];
    }
    const double kii = j0Diagonal_[r] + compliance_[r];
    kkt_.emplace_back(row, row, equation ? -(compliance_[r] + 1e-12 * (1 + kii)) : 1.0);
    rhs_[row] = equation ? j1v - e_[r] : fixed_ ? (*fixed_)[r] : 0.0;
  }
  for (int j = 0; j < q_; ++j) {
    const int row = n_ + m_ + j;
    for (int k = 0; k < 2; ++k)
      if (const int d = joints_[j].dof[k]; d >= 0)
        for (int c = 0; c < 3; ++c) {
          if (invM_[d + c] > 0) kkt_.emplace_back(d + c, row, joints_[j].coeff[k][c]);
          kkt_.emplace_back(row, d + c, joints_[j].coeff[k][c]);
        }
    rhs_[row] = -joints_[j].bias;
  }
  assembleKkt();
  lu_.factorize(kktMatrix_);
  if (lu_.info() != Eigen::Success) {
    failed_ = true;
    sol_.setZero(n_ + m_ + q_);
    return;
  }
  sol_ = lu_.solve(rhs_);
  for (int r = 0; r < m_; ++r)
    if (!fixed_ && !active_[r]) sol_[n_ + r] = 0;
}

// kktMatrix_ from kkt_: where the entries sit as last time, their values go into their slots;
// else the matrix is built anew and its pattern analysed.
void SparseIsland::assembleKkt() {
  const int size = n_ + m_ + q_;
  bool same = kktMatrix_.rows() == size && kktKeys_.size() == kkt_.size();
  for (size_t i = 0; same && i < kkt_.size(); ++i)
    same = kktKeys_[i].first == kkt_[i].row() && kktKeys_[i].second == kkt_[i].col();
  if (!same) {
    kktKeys_.resize(kkt_.size());
    for (size_t i = 0; i < kkt_.size(); ++i) kktKeys_[i] = {kkt_[i].row(), kkt_[i].col()};
    kktMatrix_.resize(size, size);
    kktMatrix_.setFromTriplets(kkt_.begin(), kkt_.end());  // keeps explicit zeros
    kktSlots_.resize(kkt_.size());
    const int* outer = kktMatrix_.outerIndexPtr();
    const int* inner = kktMatrix_.innerIndexPtr();
    for (size_t i = 0; i < kkt_.size(); ++i) {
      const int col = kkt_[i].col();
      kktSlots_[i] = static_cast<int>(
          std::lower_bound(inner + outer[col], inner + outer[col + 1], kkt_[i].row()) - inner);
    }
    lu_.analyzePattern(kktMatrix_);
  }
  double* values = kktMatrix_.valuePtr();
  std::fill(values, values + kktMatrix_.nonZeros(), 0.0);
  for (size_t i = 0; i < kkt_.size(); ++i) values[kktSlots_[i]] += kkt_[i].value();
}

// The LCP K P = b of one linearisation by block principal pivoting on the KKT system, from
// the current active set: flip every infeasible row at once while that reduces their number,
// else the last one alone (Murty's rule, finite for K a P-matrix). Returns the pivots.
int SparseIsland::solveLcp() {
  int best = m_ + 1, stalls = 0, pivots = 0;
  std::vector<int> wrong;
  for (const int maxPivots = 4 * m_ + 10; pivots < maxPivots; ++pivots) {
    factorAndSolve();
    if (failed_) return pivots;
    wrong.clear();
    for (int r = 0; r < m_; ++r) {
      const double P = sol_[n_ + r];
      if (active_[r]) {
        if (P < 0) wrong.push_back(r);
        continue;
      }
      double w = -e_[r];  // -J1 (v1_new - v1_k) - e: the row's end-of-step length rate
      for (int i = j1Start_[r]; i < j1Start_[r + 1]; ++i)
        w -= j1_[i].value() * (sol_[j1_[i].col()] - v1k_[j1_[i].col()]);
      if (w / (j0Diagonal_[r] + compliance_[r]) < -1e-15) wrong.push_back(r);
    }
    if (wrong.empty()) break;
    if (static_cast<int>(wrong.size()) < best) {
      best = static_cast<int>(wrong.size());
      stalls = 0;
    } else {
      ++stalls;
    }
    if (stalls < 3)
      for (int r : wrong) active_[r] = !active_[r];
    else
      active_[wrong.back()] = !active_[wrong.back()];
  }
  return pivots;
}

// Dense iterateNewton: from P_, each linearisation an LCP; true once the impulses settle.
bool SparseIsland::iterateNewton(const CableSolveInput& in, std::span<const Cable> cables,
                                 std::span<BodyState> predicted, StepStats& stats) {
  velocitiesAt(P_);
  double lastChange = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < kSparseNewtonIterations; ++iteration) {
    v1k_ = v1_;
    linearise(in, cables, predicted, stats);
    stats.solverIterations += solveLcp();
    if (failed_) return false;
    const Eigen::VectorXd next = sol_.segment(n_, m_).cwiseMax(0.0);
    const double change = (next - P_).lpNorm<Eigen::Infinity>();
    P_ = next;
    if (sol_.segment(n_, m_).minCoeff() < 0)
      velocitiesAt(P_);  // the LCP ran out of pivots: the clamped impulses' velocities
    else
      v1_ = sol_.head(n_);
    if (newtonSettled(change, lastChange, P_.lpNorm<Eigen::Infinity>())) return true;
    lastChange = change;
  }
  return newtonClose(lastChange, P_.lpNorm<Eigen::Infinity>());  // as the dense path's warm start
}

// Dense stage 7: the tensions, and the force that gives the solved end-of-step velocity.
void SparseIsland::applyForces(double h, std::span<Cable> cables, std::span<Vec3> loads) {
  for (int r = 0; r < m_; ++r) {
    Cable& c = cables[rows_[r]];
    c.setSpanTension(0, P_[r] / h);
    warm_[rows_[r]] = {h, c.tension(), P_[r] > 0};
  }
  for (size_t k = 0; k < bodyOfDof_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const int d = 3 * static_cast<int>(k) + c;
      if (invM_[d] > 0) loads[bodyOfDof_[k]][c] += (v1_[d] - vFree_[d]) / (h * invM_[d]);
    }
}

bool SparseIsland::solve(const CableSolveInput& in, std::span<Cable> cables,
                         std::span<const int> islandCables, std::span<const int> islandJoints,
                         std::span<BodyState> predicted, std::span<Vec3> loads, StepStats& stats) {
  if (!qualifies(in, cables, islandCables, islandJoints)) return false;
  rows_.assign(islandCables.begin(), islandCables.end());
  m_ = static_cast<int>(rows_.size());
  if (warm_.size() != cables.size()) warm_.assign(cables.size(), {});
  buildDofs(in, cables, loads);
  lengthTargets(in.h, in.share, cables);
  buildStiffMass(in.h, cables);
  limits_.free(islandJoints, static_cast<int>(in.joints.size()));
  // Solved again with each limited joint the step takes past its bound locked (dense 6c).
  do {
    jointRows(in, islandJoints);
    j1_ = j0_;  // J1's pattern until the first linearisation (velocitiesAt() with joints)
    j1Start_ = j0Start_;
    if (redundant()) return false;  // the dense path's minimum-norm solve
    active_.resize(m_);
    for (int r = 0; r < m_; ++r) active_[r] = warm_[rows_[r]].active;
    warmStart(in.h, cables);
    failed_ = false;
    StepStats warm;
    if (P_.lpNorm<Eigen::Infinity>() > 0 && iterateNewton(in, cables, predicted, warm)) {
      stats.solverIterations += warm.solverIterations;
      stats.linearisationFallbacks += warm.linearisationFallbacks;
    } else {
      P_.setZero(m_);
      iterateNewton(in, cables, predicted, stats);
    }
    if (failed_) return false;  // a singular KKT matrix: the dense path's guards take the island
  } while (limits_.lockCrossing(in.joints, islandJoints, in.bodies, dofOfBody_, v1_, in.h));
  applyForces(in.h, cables, loads);
  // As the dense path (cable_solver.cpp, stage 7): pivoted links end where the lengths were
  // solved for.
  if (!in.placements.empty())
    for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
      const int body = bodyOfDof_[k];
      if (!placedAfterStep(motions_[k], in.touching, body)) continue;
      BodyState& p = predicted[body];
      stepPose(in.bodies[body], v1_.segment<3>(3 * k), in.h, motions_[k], p);
      in.placements[body] = {true, p.position, p.angle};
    }
  ++stats.sparseIslands;
  return true;
}

}  // namespace cablelab
