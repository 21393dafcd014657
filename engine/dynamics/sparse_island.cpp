// The sparse solve of one big island: see sparse_island.h for the system, docs/model.md ("Big
// islands") for the threshold and the measured cost. Each stage mirrors the dense one of the
// same name in cable_solver.cpp, so that both give the same tensions (tests/engine/dynamics/
// sparse_island_test.cpp).
#include "engine/dynamics/sparse_island.h"

#include <algorithm>
#include <cmath>

#include "engine/dynamics/floors.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/tension_solver.h"

namespace cablelab {

namespace {

constexpr int kDefaultSparseThreshold = 48;
int sparseThreshold = kDefaultSparseThreshold;

constexpr int kSparseNewtonIterations = 3;  // as the dense path's kNewtonIterations

}  // namespace

int sparseIslandThreshold() { return sparseThreshold; }

void setSparseIslandThreshold(int rows) {
  sparseThreshold = rows < 0 ? kDefaultSparseThreshold : rows;
}

// Big enough, and none of the cases the dense path alone handles (sparse_island.h).
bool SparseIsland::qualifies(const CableSolveInput& in, std::span<const Cable> cables,
                             std::span<const int> islandCables,
                             std::span<const int> islandJoints) const {
  if (static_cast<int>(islandCables.size()) <= sparseThreshold) return false;
  if (!islandJoints.empty()) return false;  // the joint projection: dense only (yet)
  auto moved = [&](int b) { return moves(in.bodies[b]); };
  for (int cable : islandCables) {
    const Cable& c = cables[cable];
    if (c.spanCount() != 1) return false;  // capstans and gripping wheels: dense only
    const auto path = c.path();
    for (size_t i = 0; i + 1 < path.size(); ++i)
      if (needsFloor(path, i, moved)) return false;  // floor rows: dense only
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
          j0_.emplace_back(r, d + c, e.d[c]);
          j0Diagonal_[r] += e.d[c] * e.d[c] * invM_[d + c];
        }
    j0Start_.push_back(static_cast<int>(j0_.size()));
  }
}

// The dense path's mayBeStiff: whether a segment of the path could pass the stiffness test.
bool SparseIsland::stiffCable(double h2Tension, std::span<const WrapPoint> path) const {
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i].body, b = path[i + 1].body;
    if (a == b) continue;
    const Vec2 from = path[i].radius == 0 ? path[i].world : path[i].tangentOut;
    const Vec2 to = path[i + 1].radius == 0 ? path[i + 1].world : path[i + 1].tangentIn;
    double invMass = 0;
    for (int e : {a, b})
      if (e >= 0 && dofOfBody_[e] >= 0) invMass = std::max(invMass, invM_[dofOfBody_[e]]);
    if (h2Tension * invMass > 0.04 * (to - from).norm()) return true;
  }
  return false;
}

// Dense stage 3: M' = M + h^2 T G where the taut cables' geometric stiffness matters, built
// sparse (the dense path's coupled block, same entries), and M v* on the right-hand side.
void SparseIsland::buildStiffMass(double h, std::span<const Cable> cables) {
  blocks_.clear();
  stiffTriplets_.clear();
  stiff_ = false;
  struct Taut {
    double tension;
    size_t begin, end;
  };
  std::vector<Taut> taut;
  for (int cable : rows_) {
    const Cable& c = cables[cable];
    const double tension =
        std::max(c.tension(), c.elastic() ? c.stiffness() * std::max(0.0, c.stretch()) : 0.0);
    if (tension <= 0 || !stiffCable(h * h * tension, c.path())) continue;
    const size_t begin = blocks_.size();
    appendLengthHessianTranslation(c.path(), blocks_);
    for (size_t i = begin; i < blocks_.size(); ++i) {
      const StiffnessBlock& blk = blocks_[i];
      if (blk.a == blk.b && dofOfBody_[blk.a] >= 0)
        stiff_ |= h * h * tension * blk.k.trace() * invM_[dofOfBody_[blk.a]] > 0.05;
    }
    taut.push_back({tension, begin, blocks_.size()});
  }
  momentum_.resize(n_);
  for (int d = 0; d < n_; ++d)  // an immovable dof keeps v* (dense: 0 once stiff)
    momentum_[d] = invM_[d] > 0 ? vRaw_[d] / invM_[d] : (stiff_ ? 0.0 : vRaw_[d]);
  if (!stiff_) return;
  for (const Taut& t : taut)
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
  massLdlt_.compute(mass_);
}

// Redundant cables: J0 M^-1 J0^T singular (same rank as the dense path's J0 M'^-1 J0^T).
// Its LDLT pivots below kRankTolerance of the largest send the island to the dense path.
bool SparseIsland::redundant() {
  if (m_ <= 1 || (compliance_.array() != 0).all()) return false;
  Sparse J(m_, n_);
  J.setFromTriplets(j0_.begin(), j0_.end());
  const Sparse A = J * invM_.asDiagonal() * J.transpose();
  rankLdlt_.compute(A);
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

// v1 = M'^-1 (M v* - J0^T P): the velocities the impulses P give.
void SparseIsland::velocitiesAt(const Eigen::VectorXd& P) {
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

// Dense linearise(): the end-of-step state for v1 (Box2D: q1 = q0 + h v1), each row's
// end-of-step length error and its J1, with the dense guard (a row whose J1 has turned against
// its J0 uses J0; measured here with M^-1, the dense path uses M'^-1).
void SparseIsland::linearise(const CableSolveInput& in, std::span<const Cable> cables,
                             std::span<BodyState> predicted, StepStats& stats) {
  const double h = in.h;
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const BodyState& s = in.bodies[bodyOfDof_[k]];
    BodyState& p = predicted[bodyOfDof_[k]];
    p.velocity = v1k_.segment<2>(3 * k);
    p.angularVelocity = v1k_[3 * k + 2];
    p.position = s.position + h * p.velocity;
    p.angle = s.angle + h * p.angularVelocity;
  }
  j1_.clear();
  j1Start_.assign(1, 0);
  phi1_.resize(m_);
  for (int r = 0; r < m_; ++r) {
    const Cable& c = cables[rows_[r]];
    const std::span<const WrapPoint> span = c.spanPath(0);
    path_.assign(span.begin(), span.end());
    cableKinematics(path_, predicted, kin_);
    phi1_[r] = c.spanStretch(0) + kin_.length - c.spanKinematics(0).length;
    const size_t begin = j1_.size();
    double jw = 0;
    for (const auto& e : kin_.jacobian)
      if (const int d = dofOfBody_[e.body]; d >= 0)
        for (int k = 0; k < 3; ++k) {
          j1_.emplace_back(r, d + k, e.d[k]);
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
// tail) and v1 (its head). The dense LCP's regularisation 1e-12 (1 + K_ii) is kept.
void SparseIsland::factorAndSolve(double) {
  kkt_.clear();
  if (stiff_) kkt_ = stiffTriplets_;
  for (int d = 0; d < n_; ++d) kkt_.emplace_back(d, d, invM_[d] > 0 ? 1 / invM_[d] : 1);
  rhs_.resize(n_ + m_);
  rhs_.head(n_) = momentum_;
  for (int r = 0; r < m_; ++r) {
    const int row = n_ + r;
    if (!active_[r]) {
      kkt_.emplace_back(row, row, 1.0);
      rhs_[row] = 0;
      continue;
    }
    for (int i = j0Start_[r]; i < j0Start_[r + 1]; ++i)
      if (invM_[j0_[i].col()] > 0) kkt_.emplace_back(j0_[i].col(), row, j0_[i].value());
    double j1v = 0;
    for (int i = j1Start_[r]; i < j1Start_[r + 1]; ++i) {
      kkt_.emplace_back(row, j1_[i].col(), j1_[i].value());
      j1v += j1_[i].value() * v1k_[j1_[i].col()];
    }
    const double kii = j0Diagonal_[r] + compliance_[r];
    kkt_.emplace_back(row, row, -(compliance_[r] + 1e-12 * (1 + kii)));
    rhs_[row] = j1v - e_[r];
  }
  kktMatrix_.resize(n_ + m_, n_ + m_);
  kktMatrix_.setFromTriplets(kkt_.begin(), kkt_.end());
  lu_.compute(kktMatrix_);
  if (lu_.info() != Eigen::Success) {
    failed_ = true;
    sol_.setZero(n_ + m_);
    return;
  }
  sol_ = lu_.solve(rhs_);
  for (int r = 0; r < m_; ++r)
    if (!active_[r]) sol_[n_ + r] = 0;
}

// The LCP K P = b of one linearisation by block principal pivoting on the KKT system, from
// the current active set: flip every infeasible row at once while that reduces their number,
// else the last one alone (Murty's rule, finite for K a P-matrix). Returns the pivots.
int SparseIsland::solveLcp(double h) {
  int best = m_ + 1, stalls = 0, pivots = 0;
  std::vector<int> wrong;
  for (const int maxPivots = 4 * m_ + 10; pivots < maxPivots; ++pivots) {
    factorAndSolve(h);
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
  for (int iteration = 0; iteration < kSparseNewtonIterations; ++iteration) {
    v1k_ = v1_;
    linearise(in, cables, predicted, stats);
    stats.solverIterations += solveLcp(in.h);
    if (failed_) return false;
    const Eigen::VectorXd next = sol_.tail(m_).cwiseMax(0.0);
    const double change = (next - P_).lpNorm<Eigen::Infinity>();
    P_ = next;
    if (sol_.tail(m_).minCoeff() < 0)
      velocitiesAt(P_);  // the LCP ran out of pivots: the clamped impulses' velocities
    else
      v1_ = sol_.head(n_);
    if (change <= 1e-9 * (1e-9 + P_.lpNorm<Eigen::Infinity>())) return true;
  }
  return false;
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
                         std::span<BodyState> predicted, std::span<Vec3> loads,
                         StepStats& stats) {
  if (!qualifies(in, cables, islandCables, islandJoints)) return false;
  rows_.assign(islandCables.begin(), islandCables.end());
  m_ = static_cast<int>(rows_.size());
  if (warm_.size() != cables.size()) warm_.assign(cables.size(), {});
  buildDofs(in, cables, loads);
  lengthTargets(in.h, in.share, cables);
  if (redundant()) return false;  // the dense path's minimum-norm solve
  buildStiffMass(in.h, cables);
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
  applyForces(in.h, cables, loads);
  ++stats.sparseIslands;
  return true;
}

}  // namespace cablelab
